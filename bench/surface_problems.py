#!/usr/bin/env python3
"""The named problems of moving surfaces at their own settings: runs `slc run --problem NAME`
for each, and writes their errors, volume changes, sizes and times into a Markdown table and
their final pictures into a figures folder (docs/tables/surface_problems.md, docs/figures/)."""
import argparse
import json
import shutil
import subprocess
import sys
from pathlib import Path

PROBLEMS = ["sphere-rotation", "sphere-curvature", "merging-spheres", "box-normal",
            "box-normal:speed=-1", "peanut-volume", "zalesak-sphere", "enright"]


def eps_text(eps):
    """1e-04, 2.5e-05: two digits where the second is not 0."""
    return f"{eps:.1e}".replace(".0e", "e")


def fmt(x, spec):
    return "" if x is None else format(x, spec)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--slc", required=True, help="the slc executable")
    parser.add_argument("--out", required=True, help="the table to write (.md)")
    parser.add_argument("--figures", required=True, help="folder of the final pictures")
    parser.add_argument("--work", default="out/surface_problems", help="run folders")
    parser.add_argument("--problems", nargs="*", default=PROBLEMS)
    args = parser.parse_args()
    rows = []
    for name in args.problems:
        # NAME or NAME:key=value,...: the problem with those parameters.
        problem, _, given = name.partition(":")
        params = [a for kv in given.split(",") if kv for a in ("--param", kv)]
        out = Path(args.work) / name.replace(":", "_").replace("=", "").replace(",", "_")
        run = subprocess.run([args.slc, "run", "--problem", problem, *params, "--out", str(out),
                              "--quiet"], capture_output=True, text=True)
        if run.returncode not in (0, 3):
            sys.exit(f"slc run --problem {name} failed: {run.stderr.strip()}")
        s = json.loads((out / "summary.json").read_text())
        s["row"] = f"{problem} ({given})" if given else problem
        rows.append(s)
        Path(args.figures).mkdir(parents=True, exist_ok=True)
        shutil.copy(out / "final.png", Path(args.figures) / f"surface_{out.name}.png")
        print(f"{name}: {s['status']}, e_inf {s['e_inf']}, {s['wall_s']:.1f} s", flush=True)
    lines = [
        "<!-- written by bench/surface_problems.py (scripts/bench); do not edit -->",
        "",
        "| problem | N | K | ε | status | triangles | components | genus | e_inf | volume change "
        "| steps beyond ε | largest \\|G\\| left | G evaluations | wall s | CPU s |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for s in rows:
        p = s["params"]
        lines.append(
            f"| {s['row']} | {p['N']} | {p['K']} | {eps_text(p['eps'])} | {s['status']} "
            f"| {s['triangles']:,} | {s['components']} | {s['genus']} | {fmt(s['e_inf'], '.2e')} "
            f"| {100 * s['volume_change']:+.3f}% | {s.get('unconverged_steps', 0)} "
            f"| {fmt(s.get('largest_residual'), '.2e')} | {s['g_evals']:,} | {s['wall_s']:.1f} "
            f"| {s['cpu_s']:.1f} |")
    threads = rows[0]["params"]["threads"] if rows else 0
    lines += ["", f"{threads} threads; e_inf is the largest |exact| over the final vertices and "
              "triangle centroids, where the exact surface is known at the end. Steps beyond ε: "
              "the steps whose contour refinement left an edge midpoint or centroid with |G| > ε "
              "(splits refused along sharp edges), and the largest |G| they left "
              "(summary.json: unconverged_steps, largest_residual)."]
    Path(args.out).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
