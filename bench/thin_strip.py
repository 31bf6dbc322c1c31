#!/usr/bin/env python3
"""A strip 1 long and 0.06 wide (two cells of the default tree) under Mullins-Sekerka and
Hele-Shaw at the tool's defaults to t = 0.001: its frames drawn by the tool into
docs/figures/potential_strip_LAW.png, and what each run kept (the area's drift, the length at the
end, whether the length fell at every step) into the region `thin-strip` of
docs/algorithms/potential.md."""
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


def stadium(width):
    """The strip [-0.5, 0.5] x [-w/2, w/2] with half-discs on its ends, counterclockwise."""
    r = 0.5 * width
    points = [[-0.5 + i / 200, -r] for i in range(200)]
    points += [[0.5 + r * math.cos(a), r * math.sin(a)]
               for a in (-0.5 * math.pi + math.pi * i / 30 for i in range(30))]
    points += [[0.5 - i / 200, r] for i in range(200)]
    points += [[-0.5 + r * math.cos(a), r * math.sin(a)]
               for a in (0.5 * math.pi + math.pi * i / 30 for i in range(30))]
    return {"curves": [{"points": points}]}


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--slc", required=True)
    ap.add_argument("--doc", required=True, help="the page holding the region `thin-strip`")
    ap.add_argument("--figures", required=True, help="folder for potential_strip_*.png")
    ap.add_argument("--work", default="out/thin_strip")
    a = ap.parse_args()
    work = Path(a.work)
    work.mkdir(parents=True, exist_ok=True)
    start = work / "strip.json"
    start.write_text(json.dumps(stadium(0.06)))
    lines = ["| law | steps | status | area drift | length, start → end | length fell every step | "
             "CPU s |", "|---|---|---|---|---|---|---|"]
    for law in ("mullins-sekerka", "hele-shaw"):
        out = work / law
        subprocess.run([a.slc, "run", "--initial", str(start), "--velocity", law, "--t-end",
                        "0.001", "--frames", "8", "--out", str(out), "--quiet"], check=True)
        summary = json.loads((out / "summary.json").read_text())
        rows = list(csv.DictReader(open(out / "history.csv")))
        areas = [float(r["area"]) for r in rows]
        lengths = [float(r["length"]) for r in rows]
        drift = max(abs(x / areas[0] - 1) for x in areas)
        fell = all(b <= a0 for a0, b in zip(lengths, lengths[1:]))
        lines.append(f"| {law} | {summary['steps']} | {summary['status']} | {drift:.1e} | "
                     f"{lengths[0]:.3f} → {lengths[-1]:.3f} | {'yes' if fell else 'no'} | "
                     f"{summary['cpu_s']:.2g} |")
        shutil.copy(out / "frames.png", Path(a.figures) / f"potential_strip_{law}.png")
    write_region(a.doc, "thin-strip", lines)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
