#!/usr/bin/env python3
"""A head with two ears thinner than its cells (python/tests/shapes3d.py: ears 0.1 thick, 1.1% of
its size 9.1, a quarter of a cell at the default K) at the defaults, against exact answers: grown
and shrunk at unit speed to t = 0.01 against the exact offsets (each vertex's distance to the
given surface, by `slc distance`, against t), and under mean curvature flow to t = 0.001 at the
defaults and at twice their resolution (-K 6). Writes the region `thin-ears` of
docs/performance.md. About 3 minutes on two cores; run with the package's Python
(scripts/python-env)."""

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

import slc

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python" / "tests"))
from campaign3d import read_obj, write_obj  # noqa: E402
from shapes3d import head_with_ears  # noqa: E402
from thin_cost import write_region  # noqa: E402


def run(binary, given, folder, name, args):
    out = folder / name
    subprocess.run([binary, "run", "--initial", str(given), *args, "--threads", "2", "--out",
                    str(out), "--quiet"], check=True)
    return out, json.loads((out / "summary.json").read_text())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--slc", default="build/bin/slc")
    parser.add_argument("--out", default="docs/performance.md")
    a = parser.parse_args()
    head = head_with_ears()
    size = float(np.ptp(head.vertices, axis=0).max())
    lines = ["| the head with ears 0.1 thick, at unit speed to t = 0.01 | status | components, "
             "genus | farthest vertex from the exact offset, / size | wall s, 2 threads |",
             "|---|---|---|---:|---:|"]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        given = folder / "head.obj"
        write_obj(given, head.vertices.tolist(), head.triangles.tolist())
        for name, speed in (("grown (the ears 0.12 thick)", 1), ("shrunk (the ears 0.08 thick)", -1)):
            out, s = run(a.slc, given, folder, f"speed{speed}",
                         ["--velocity", "unit-normal", "--param", f"speed={speed}",
                          "--t-end", "0.01"])
            d, _ = slc.distance(head, np.array(read_obj(out / "final.obj")[0]))
            error = float(np.abs(d - 0.01 * speed).max()) / size
            lines.append(f"| {name} | {s['status']} | {s['components']}, {s['genus']} | "
                         f"{100 * error:.2g}% | {s['wall_s']:.0f} |")
            print(lines[-1], flush=True)
        lines += ["", "| the head under mean curvature flow to t = 0.001 | status | components, "
                  "genus | volume change | wall s, 2 threads |", "|---|---|---|---:|---:|"]
        volumes = []
        for name, extra in (("at the defaults (K 5)", []), ("twice the resolution (-K 6)", ["-K", "6"])):
            _, s = run(a.slc, given, folder, f"curvature{len(volumes)}",
                       ["--velocity", "curvature", "--t-end", "0.001", *extra])
            volumes.append(s["volume"])
            lines.append(f"| {name} | {s['status']} | {s['components']}, {s['genus']} | "
                         f"{100 * (s['volume'] / s['volume_initial'] - 1):+.3g}% | "
                         f"{s['wall_s']:.0f} |")
            print(lines[-1], flush=True)
    lines += ["", f"Size {size:.3g}. The final volumes at the defaults and at twice their "
              f"resolution differ by {100 * abs(volumes[0] / volumes[1] - 1):.2g}% (goal: within "
              f"0.5%); the offsets' goal is 1% of the size."]
    write_region(a.out, "thin-ears", lines)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
