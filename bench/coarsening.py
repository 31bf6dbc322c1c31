#!/usr/bin/env python3
"""The coarsening problem (100 particles under two-phase Mullins-Sekerka until 10 are left) by the
tool, and what it measures: the number of particles against time, the total area's drift, and the
mean radius cubed against time in the late stage (from half the particles on), whose slope the
LSW law says is constant (each particle's radius that of a circle of its area, from the frames). Writes the table into the region `coarsening` of
docs/algorithms/potential.md and the run's frames and history into docs/figures/."""
import argparse
import csv
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from thin_cost import write_region  # noqa: E402


def fit(xs, ys):
    """Least squares y = a + b x: b and the correlation r."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    syy = sum((y - my) ** 2 for y in ys)
    sxy = sum((x - mx) * (y - my) for x, y in zip(xs, ys))
    return sxy / sxx, sxy / math.sqrt(sxx * syy)


def shoelace(points):
    """The signed area of a closed polygon."""
    return 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1]))


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--slc", required=True)
    ap.add_argument("--doc", required=True, help="the page holding the region `coarsening`")
    ap.add_argument("--figures", required=True, help="folder for coarsening_*.png")
    ap.add_argument("--work", default="out/coarsening")
    a = ap.parse_args()
    write_region(a.doc, "coarsening", ["(measuring)"])  # the region exists before the hour's run
    # A run that ends unstable (exit status 3) is measured as far as it went, and says so.
    subprocess.run([a.slc, "run", "--problem", "coarsening", "--frames", "100", "--quiet",
                    "--out", a.work], check=False)
    summary = json.loads((Path(a.work) / "summary.json").read_text())
    with open(Path(a.work) / "history.csv") as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    t = [r["t"] for r in rows]
    n = [int(r["components"]) for r in rows]
    area = [r["area"] for r in rows]
    cpu = sum(r["cpu_s"] for r in rows)
    drift = max(abs(x / area[0] - 1) for x in area)
    # The mean radius from the frames (and the final curves): each particle's radius is that of
    # a circle of its area.
    states = sorted(Path(a.work, "frames").glob("frame_*.json")) + [Path(a.work) / "final.json"]
    ft, fn, fcubed = [], [], []
    for path in states:
        state = json.loads(path.read_text())
        radii = [math.sqrt(abs(shoelace(c["points"])) / math.pi) for c in state["curves"]]
        if ft and state["time"] <= ft[-1]:
            continue
        ft.append(state["time"])
        fn.append(len(radii))
        fcubed.append((sum(radii) / len(radii)) ** 3)
    late = [i for i in range(len(ft)) if fn[i] <= fn[0] // 2]
    if len(late) < 4:
        sys.exit(f"the run ended with {n[-1]} particles, before its late stage")
    slope, r = fit([ft[i] for i in late], [fcubed[i] for i in late])
    halves = [len(late) // 2, len(late) - len(late) // 2]
    first = fit([ft[i] for i in late[:halves[0]]], [fcubed[i] for i in late[:halves[0]]])[0]
    second = fit([ft[i] for i in late[halves[0]:]], [fcubed[i] for i in late[halves[0]:]])[0]
    marks = []
    for target in (100, 75, 50, 35, 25, 20, 15, 10):  # the first time level at or below each
        hit = next((i for i in range(len(ft)) if fn[i] <= target), None)
        if hit is not None:
            marks.append(f"| {fn[hit]} | {ft[hit]:.3g} | {fcubed[hit]:.3g} |")
    ended = "" if summary["status"] == "ok" else (
        f" It ended **{summary['status']}** at t = {summary['t']:.3g}: {summary['message']}")
    lines = [
        f"`slc run --problem coarsening` ({n[0]} particles, {len(rows) - 1} steps of "
        f"{t[1] - t[0]:.3g}, {cpu:.0f} s CPU), written by `bench/coarsening.py`.{ended}",
        "",
        "| particles | t | mean radius³ |",
        "|---|---|---|",
        *marks,
        "",
        f"- The total area drifted by at most {drift:.1e} of its start.",
        f"- Late stage ({fn[late[0]]} particles down to {fn[-1]}, {len(late)} frames): mean "
        f"radius cubed against t has slope {slope:.3g} (correlation {r:.4f}); {first:.3g} over its "
        f"first half and {second:.3g} over its second (the LSW law: one constant slope).",
    ]
    write_region(a.doc, "coarsening", lines)
    figures = Path(a.figures)
    # Four panels: the start, when half and a quarter of the particles are left, and the end.
    panel_times = [t[0]] + [t[next(i for i in range(len(rows)) if n[i] <= n[0] // d)] for d in (2, 4)]
    panel_times.append(t[-1])
    subprocess.run([a.slc, "render", "--frames", str(Path(a.work) / "frames"), "--columns", "4",
                    "--times", ",".join(f"{x:.17g}" for x in panel_times), "--domain", "1",
                    "--title", f"coarsening: {n[0]} particles to {n[-1]}",
                    "--out", str(figures / "coarsening_frames.png")], check=True)
    shutil.copy(Path(a.work) / "history.png", figures / "coarsening_history.png")


if __name__ == "__main__":
    main()
