#!/usr/bin/env python3
"""A seeded randomized campaign of `slc run`: random curves x laws x step sizes x options.

Every run must end one of three honest ways: exit 0 with a result its law allows, exit 2 (bad
input, refused) or exit 3 (a numerical failure or an unstable run, one line naming what to
change). Counted as defects, each listed with its command:

  impossible  exit 0 with what the law cannot do: a rigid motion or an area-keeping law that
              changed the area by more than the budget below, or the number of curves; a
              growing curve that vanished or lost area; curvature flow whose area missed
              A0 - 2 pi t, that split a curve, or that vanished early or stayed long after the
              exact extinction;
  crash       any other exit status, a timeout, or "internal error";
  mixed       an output folder that is not one run's whole results (summary, history and final
              interface disagreeing, a working folder or lock left behind, or a refused run that
              changed the folder) - every fourth run writes into the folder of the one before.

Budgets of a whole run (the guards check each step at 1%; these allow for drift over steps):
area kept to 5% of A0 plus 20 eps L per step; curvature flow's area within 25% of 2 pi t plus
5% of A0; a curve vanishes no earlier than 3/4 of the exact extinction time and no later than
1.5 times it (plus a step).

  campaign.py --slc build/bin/slc --size small --check      (the tests: a few dozen runs)
  campaign.py --slc build/bin/slc --size large --doc docs/errors.md   (scripts/bench)
"""
import argparse
import hashlib
import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

SIZES = {"small": (30, 1), "large": (400, 2)}  # runs, seed
TIMEOUT_S = float(os.environ.get("SLC_CAMPAIGN_TIMEOUT", "300"))


def star(rng, centre, radius, spiky):
    """A star-shaped (so simple) counterclockwise polygon about centre."""
    if spiky:  # sharp points: 5 to 9 tips, two vertices a point
        tips = rng.randint(5, 9)
        depth = rng.uniform(0.3, 0.7)
        pts = []
        for k in range(2 * tips):
            a = math.pi * k / tips
            r = radius * (1.0 if k % 2 == 0 else depth)
            pts.append((centre[0] + r * math.cos(a), centre[1] + r * math.sin(a)))
        return pts
    n = rng.choice([24, 48, 96])
    modes = [(k, rng.uniform(0.0, 0.25 / k), rng.uniform(0, 2 * math.pi)) for k in (2, 3, 4)]
    pts = []
    for i in range(n):
        a = 2 * math.pi * i / n
        r = radius * (1.0 + sum(amp * math.cos(k * a + ph) for k, amp, ph in modes))
        pts.append((centre[0] + r * math.cos(a), centre[1] + r * math.sin(a)))
    return pts


def shoelace(pts):
    return 0.5 * sum(pts[i - 1][0] * pts[i][1] - pts[i][0] * pts[i - 1][1] for i in range(len(pts)))


def perimeter(pts):
    return sum(math.dist(pts[i - 1], pts[i]) for i in range(len(pts)))


def random_case(rng, index):
    """One run: curves, law, steps and options, and what the law allows."""
    scale = 10.0 ** rng.uniform(-2, 2)
    offset = (rng.uniform(-3, 3) * scale, rng.uniform(-3, 3) * scale)
    kind = rng.choice(["rigid", "rigid", "still", "growing", "curvature", "keeps-area"])
    # Several separated curves only where every curve's fate is fixed by the law.
    count = rng.choice([1, 1, 2, 3]) if kind in ("rigid", "still") else 1
    curves = []
    for c in range(count):
        centre = (offset[0] + 3.0 * scale * c, offset[1])
        curves.append(star(rng, centre, scale, spiky=rng.random() < 0.3))
    args = []
    if kind == "rigid":
        if rng.random() < 0.5:
            omega = rng.uniform(-3, 3)
            args += ["--velocity", "rotation", "--param", f"omega={omega:.6g}",
                     "--param", f"cx={offset[0]:.6g}", "--param", f"cy={offset[1]:.6g}"]
            t_end = rng.uniform(0.5, 6.3) / max(abs(omega), 0.1)
        else:
            ux, uy = rng.uniform(-1, 1) * scale, rng.uniform(-1, 1) * scale
            args += ["--velocity", "translation", "--param", f"ux={ux:.6g}", "--param", f"uy={uy:.6g}"]
            t_end = rng.uniform(0.1, 3.0)
    elif kind == "still":
        args += ["--velocity", "unit-normal", "--param", "speed=0"]
        t_end = rng.uniform(0.1, 2.0)
    elif kind == "growing":
        speed = rng.uniform(0.1, 5.0) * scale
        args += ["--velocity", "unit-normal", "--param", f"speed={speed:.6g}"]
        t_end = rng.uniform(0.1, 2.0)
    elif kind == "curvature":
        args += ["--velocity", "curvature"]
        extinction = abs(shoelace(curves[0])) / (2 * math.pi)
        t_end = extinction * rng.uniform(0.2, 1.3)
    else:
        args += ["--velocity", "volume-preserving-curvature"]
        t_end = rng.uniform(0.05, 0.5) * scale * scale
    args += ["--t-end", f"{t_end:.6g}"]
    options = []
    if rng.random() < 0.7:
        options += ["-N", str(rng.choice([1, 2, 4, 10, 20, 40]))]
    if rng.random() < 0.5:
        options += ["-K", str(rng.choice([4, 5, 6, 7]))]
    if rng.random() < 0.4:
        options += ["-P", str(rng.choice(["0", "1", "2", "converged"]))]
    if rng.random() < 0.3:
        options += [rng.choice(["--arcs", "--no-arcs"])]
    if rng.random() < 0.2 and kind in ("rigid", "still", "growing"):
        options += ["--extension", rng.choice(["direct", "nearest"])]
    return {"index": index, "kind": kind, "curves": curves, "args": args + options, "t_end": t_end}


def read_history(path):
    rows = []
    with open(path) as f:
        header = f.readline().strip().split(",")
        for line in f:
            rows.append(dict(zip(header, (float(v) for v in line.strip().split(",")))))
    return rows


def folder_digest(folder):
    if not os.path.isdir(folder):
        return None
    h = hashlib.sha256()
    for root, _, files in sorted(os.walk(folder)):
        for name in sorted(files):
            path = os.path.join(root, name)
            h.update(path.encode())
            with open(path, "rb") as f:
                h.update(f.read())
    return h.hexdigest()


def whole_folder(folder):
    """Why the folder is not one run's whole results, or None."""
    parent, name = os.path.split(os.path.abspath(folder))
    left = [e for e in os.listdir(parent) if e.startswith(name + ".slc-") or e == name + ".lock"]
    if left:
        return f"left behind: {left}"
    try:
        summary = json.load(open(os.path.join(folder, "summary.json")))
        history = read_history(os.path.join(folder, "history.csv"))
        final = json.load(open(os.path.join(folder, "final.json")))
    except (OSError, ValueError) as e:
        return f"unreadable results: {e}"
    area = sum(shoelace(c["points"]) for c in final.get("curves", []))
    if summary.get("area") is None or abs(area - summary["area"]) > 1e-9 * max(1.0, abs(area)):
        return f"final.json's area {area} is not summary.json's {summary.get('area')}"
    if abs(history[-1]["area"] - summary["area"]) > 1e-9 * max(1.0, abs(area)):
        return f"history.csv ends at area {history[-1]['area']}, summary.json says {summary['area']}"
    if abs(history[-1]["t"] - summary["t"]) > 1e-12 * max(1.0, abs(summary["t"])):
        return "history.csv and summary.json end at different times"
    return None


def judge(case, summary, history):
    """Why an exit-0 result is physically impossible, or None."""
    kind, t_end = case["kind"], case["t_end"]
    a0 = sum(shoelace(c) for c in case["curves"])
    l0 = sum(perimeter(c) for c in case["curves"])
    eps = summary["params"]["eps"]
    steps = summary["steps"]
    status = summary["status"]
    area = summary["area"]
    curves = history[-1]["components"]
    n0 = len(case["curves"])
    if kind in ("rigid", "still", "keeps-area"):
        budget = 0.05 * abs(a0) + 20 * eps * l0 * steps
        if status == "vanished":
            return "vanished under a law that keeps area"
        if abs(area - a0) > budget:
            return f"area {area:.6g} from {a0:.6g}, budget {budget:.3g}"
        if kind != "keeps-area" and curves != n0:
            return f"{curves:g} curves from {n0} under a rigid motion"
    elif kind == "growing":
        if status == "vanished":
            return "a growing curve vanished"
        if area < a0 * (1 - 0.01):
            return f"a growing curve lost area: {area:.6g} from {a0:.6g}"
    elif kind == "curvature":
        extinction = a0 / (2 * math.pi)
        k = t_end / steps
        if max(r["components"] for r in history) > 1:
            return "curvature flow split a curve"
        if status == "vanished":
            if summary["t"] < 0.75 * extinction:
                return f"vanished at {summary['t']:.4g}, exact extinction {extinction:.4g}"
        else:
            if t_end > 1.5 * extinction + k:
                return f"still there at {t_end:.4g}, exact extinction {extinction:.4g}"
            if t_end < extinction:
                exact = a0 - 2 * math.pi * t_end
                budget = 0.25 * 2 * math.pi * t_end + 0.05 * a0
                if abs(area - exact) > budget:
                    return f"area {area:.6g} where the law gives {exact:.6g}, budget {budget:.3g}"
    return None


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--slc", required=True)
    p.add_argument("--size", choices=SIZES, default="small")
    p.add_argument("--seed", type=int)
    p.add_argument("--check", action="store_true", help="exit 1 when any defect is found")
    p.add_argument("--doc", help="write the counts into this file between campaign markers")
    p.add_argument("--only", type=int, help="run only the case of this index (to reproduce it)")
    p.add_argument("--keep", help="write the cases' files here and keep them")
    a = p.parse_args()
    runs, seed = SIZES[a.size]
    seed = a.seed if a.seed is not None else seed
    rng = random.Random(seed)
    slc = os.path.abspath(a.slc)
    work = os.path.abspath(a.keep) if a.keep else tempfile.mkdtemp(prefix="slc-campaign-")
    os.makedirs(work, exist_ok=True)
    counts = {"runs": 0, "ok": 0, "vanished": 0, "unstable": 0, "failed": 0, "refused": 0,
              "impossible": 0, "crash": 0, "mixed": 0, "split": 0}
    defects = []
    refusals = {}
    folder = None
    start = time.time()
    try:
        for i in range(runs):
            case = random_case(rng, i)
            if a.only is not None and i != a.only:
                continue
            initial = os.path.join(work, f"case{i}.json")
            with open(initial, "w") as f:
                json.dump({"curves": [{"points": c} for c in case["curves"]]}, f)
            if folder is None or i % 4 != 3:
                folder = os.path.join(work, f"out{i}")
            before = folder_digest(folder)
            cmd = [slc, "run", "--initial", initial, *case["args"], "--out", folder, "--quiet",
                   "--threads", "1"]
            shown = " ".join(["slc", "run", "--initial", f"case{i}.json", *case["args"]])
            counts["runs"] += 1
            try:
                r = subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT_S)
            except subprocess.TimeoutExpired:
                counts["crash"] += 1
                defects.append(("crash", shown, f"no end in {TIMEOUT_S:g} s"))
                continue
            # Notes (the domain grew, the curves were reoriented) are not errors.
            err = "\n".join(l for l in r.stderr.strip().splitlines() if not l.startswith("slc: note:"))
            if r.returncode not in (0, 2, 3) or "internal error" in err or len(err.splitlines()) > 1:
                counts["crash"] += 1
                defects.append(("crash", shown, f"exit {r.returncode}: {err[:300]}"))
                continue
            if r.returncode == 2:
                counts["refused"] += 1
                refusals[err.split(":", 2)[-1].strip()[:90]] = refusals.get(err.split(":", 2)[-1].strip()[:90], 0) + 1
                if folder_digest(folder) != before:
                    counts["mixed"] += 1
                    defects.append(("mixed", shown, "a refused run changed the folder"))
                continue
            if r.returncode == 3 and not os.path.exists(os.path.join(folder, "summary.json")):
                counts["failed"] += 1
                continue
            why = whole_folder(folder)
            if why:
                counts["mixed"] += 1
                defects.append(("mixed", shown, why))
                continue
            summary = json.load(open(os.path.join(folder, "summary.json")))
            history = read_history(os.path.join(folder, "history.csv"))
            status = summary["status"]
            if summary.get("substeps", {}).get("split_steps", 0) > 0:
                counts["split"] += 1
            if r.returncode == 3:
                counts["unstable" if status == "unstable" else "failed"] += 1
                continue
            counts[status if status in ("ok", "vanished") else "failed"] += 1
            why = judge(case, summary, history)
            if why:
                counts["impossible"] += 1
                defects.append(("impossible", shown, why))
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)
    counts["seconds"] = round(time.time() - start)
    for kind, shown, why in defects:
        print(f"{kind}: {shown}: {why}")
    print(json.dumps({"size": a.size, "seed": seed, **counts}))
    for why, n in sorted(refusals.items(), key=lambda x: -x[1]):
        print(f"refused {n}: {why}")
    if a.doc:
        write_doc(a.doc, a.size, seed, counts, defects)
    bad = counts["impossible"] + counts["crash"] + counts["mixed"]
    return 1 if a.check and bad else 0


def write_doc(path, size, seed, c, defects):
    begin, end = "<!-- campaign: written by bench/campaign.py -->", "<!-- /campaign -->"
    lines = [begin,
             f"| campaign | runs | ok | vanished | unstable (exit 3) | failed (exit 3) | refused (exit 2) "
             f"| split into sub-steps | impossible | crashes | mixed folders |",
             "|---|---|---|---|---|---|---|---|---|---|---|",
             f"| {size}, seed {seed} | {c['runs']} | {c['ok']} | {c['vanished']} | {c['unstable']} "
             f"| {c['failed']} | {c['refused']} | {c['split']} | {c['impossible']} | {c['crash']} "
             f"| {c['mixed']} |"]
    if defects:
        lines.append("")
    for kind, shown, why in defects:
        lines.append(f"- {kind}: `{shown}`: {why}")
    lines.append(end)
    text = open(path).read()
    if begin in text:
        head, rest = text.split(begin, 1)
        text = head + "\n".join(lines) + rest.split(end, 1)[1]
    else:
        text = text.rstrip("\n") + "\n\n" + "\n".join(lines) + "\n"
    open(path, "w").write(text)


if __name__ == "__main__":
    sys.exit(main())
