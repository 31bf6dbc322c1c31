#!/usr/bin/env python3
"""What thin cells cost a shape that has no thin part: users' shapes at the default settings
(thin cells, the start check and the confirmation of a step's topology by deeper thin cells) beside
the same runs with --thin-depth 0 (the paper's uniform trees, none of these), in the same session,
the runs of either alternated, the least CPU time of each kept, and the G evaluations of each
(the same in every repetition: results do not depend on the clock). Writes the table into the region
`thin-cost` of docs/performance.md (between <!-- begin thin-cost --> and <!-- end thin-cost -->).

The shapes: a unit circle (256 points) under curve shortening to t = 0.1 and grown at unit speed
to t = 0.5; a sphere of radius 0.5 (an icosphere of 1,280 triangles) grown at unit speed to
t = 0.05 and under mean curvature flow to t = 0.02."""
import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from campaign3d import icosphere, write_obj  # noqa: E402


def cases(folder):
    circle = folder / "circle.json"
    points = [[math.cos(2 * math.pi * i / 256), math.sin(2 * math.pi * i / 256)] for i in range(256)]
    circle.write_text(json.dumps({"curves": [{"points": points}]}))
    sphere = folder / "sphere.obj"
    v, f = icosphere(3)
    write_obj(sphere, [[0.5 * c for c in p] for p in v], f)
    return [
        ("circle, curve shortening to t = 0.1", [
            "--initial", str(circle), "--velocity", "curvature", "--t-end", "0.1"]),
        ("circle, grown at unit speed to t = 0.5", [
            "--initial", str(circle), "--velocity", "unit-normal", "--t-end", "0.5"]),
        ("sphere (1,280 triangles), grown at unit speed to t = 0.05", [
            "--initial", str(sphere), "--velocity", "unit-normal", "--t-end", "0.05"]),
        ("sphere (1,280 triangles), mean curvature flow to t = 0.02", [
            "--initial", str(sphere), "--velocity", "curvature", "--t-end", "0.02"]),
    ]


def run(slc, args, out):
    subprocess.run([slc, "run", *args, "--threads", "1", "--out", str(out), "--quiet"],
                   check=True, capture_output=True)
    s = json.loads((out / "summary.json").read_text())
    return s["cpu_s"], s["g_evals"], s["status"]


def write_region(path, name, lines):
    begin, end = f"<!-- begin {name} -->", f"<!-- end {name} -->"
    text = Path(path).read_text()
    if begin not in text or end not in text:
        sys.exit(f"{path} has no region '{name}' ({begin} ... {end})")
    head, rest = text.split(begin, 1)
    Path(path).write_text(head + "\n".join([begin] + lines + [end]) + rest.split(end, 1)[1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--slc", default="build/bin/slc")
    parser.add_argument("--out", default="docs/performance.md")
    parser.add_argument("--repeat", type=int, default=3)
    a = parser.parse_args()
    lines = ["| shape and law | G evaluations, default | --thin-depth 0 | CPU s, default | "
             "--thin-depth 0 | ratio |", "|---|---|---|---|---|---|"]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for name, args in cases(folder):
            best = {"default": math.inf, "none": math.inf}
            evals = {}
            for _ in range(a.repeat):
                for key, extra in (("default", []), ("none", ["--thin-depth", "0"])):
                    cpu, g, status = run(a.slc, args + extra, folder / key)
                    if status != "ok":
                        sys.exit(f"{name}, {key}: status {status}")
                    best[key] = min(best[key], cpu)
                    evals[key] = g
            ratio = best["default"] / best["none"]
            print(f"{name}: {evals['default']:,} against {evals['none']:,} G evaluations, "
                  f"{best['default']:.3g} s against {best['none']:.3g} s ({ratio:.2f})")
            lines.append(f"| {name} | {evals['default']:,} | {evals['none']:,} | "
                         f"{best['default']:.3g} | {best['none']:.3g} | {ratio:.2f} |")
    write_region(a.out, "thin-cost", lines)


if __name__ == "__main__":
    main()
