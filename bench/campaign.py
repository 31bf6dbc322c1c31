#!/usr/bin/env python3
"""Seeded randomized campaigns of `slc run` on curves: two sets, each a small size (the tests run
the defaults' one) and a large one for scripts/bench, each writing its table into docs/errors.md
(--doc).

Every run must end one of the honest ways: exit 0 with a result its law allows (status ok or
vanished), exit 2 (bad input, refused) or exit 3 (a numerical failure, `failed`, or an unstable
run, one line naming what to change). Counted as defects, each listed with its command:

  impossible  exit 0 with what the law cannot do: a documented budget broken (below), or an
              exact invariant (the number of curves, vanishing, growth);
  inaccurate  (set defaults) exit 0 within the budgets, but the curve off the exact one by more
              than 0.05 l (l the start's half-width): no budget is documented for the shape, so
              the campaign takes ten times docs/defaults.md's target of 5e-3 l (the
              table's "off the exact shape");
  crash       any other exit status, a timeout, "internal error" or "please report", or more
              than one line of error;
  mixed       (set options) an output folder that is not one run's whole results (summary,
              history and final interface disagreeing, a working folder or lock left behind, or
              a refused run that changed the folder) - every fourth run writes into the folder
              of the one before.

--set options (the default): random curves x laws x step sizes x options. Budgets of a whole
run (the guards check each step at 1%; these allow for drift over steps): area kept to 5% of A0
plus 20 eps L per step; curvature flow's area within 25% of 2 pi t plus 5% of A0; a curve
vanishes no earlier than 3/4 of the exact extinction time and no later than 1.5 times it (plus a
step).

--set defaults: one curve a run - a circle, an ellipse, a smooth star or a polygon (128 to 512
points, polygons of 3 to 8 sides and an L), its size log-uniform in 1e-3..1e3, its centre up to
10 sizes from the origin - under each built-in law in turn at the default settings (only
--initial, --velocity, --t-end and the law's --param, scaled with the curve: speeds in sizes per
unit time, centres of rotation within 2 sizes, final times a fraction of a turn, offsets of 0.05
to 0.3 sizes, a fraction of the extinction time). The exact laws and what a run may miss them by
(docs/errors.md, "What the guards catch"; A0, L0 the start's area and length, eps the run's, N
its steps; the number of curves is read at every step of history.csv):

  rotation, translation   the curve moved rigidly: area within 5% of A0 + 20 eps L0 (the run's
                          documented budget), one curve at every step; every final vertex within
                          0.05 l of the moved start, every moved vertex within 0.05 l of the
                          result;
  unit-normal (speed s)   every final vertex at signed distance s t from the start (the level
                          set of the start's signed distance) within 0.05 l; a growing region's
                          area does not fall by 1% (the guard); a convex curve growing by d = s t
                          has A0 + L0 d + pi d^2 (Steiner), within 1% of A0 (the campaign's: no
                          budget is documented for the rate);
  anisotropic             its speed lies in [R - |e|, R + |e|], so every final vertex lies at a
                          signed distance from the start between (R - |e|) t and (R + |e|) t,
                          within 0.05 l (comparison principle); the area cannot fall when
                          R > |e| (the guard); it vanishes only once the start eroded by
                          (|R| + |e|) t is empty;
  curvature               A(t) = A0 - 2 pi t until extinction at A0 / (2 pi): the area within 1%
                          of A0 (a user's run budget) + 0.5% of A0 (chords against the arcs the
                          guards measure) + 20 eps L0 N; one curve at every step; vanished only
                          with less left than a step's loss plus that budget; a circle stays one
                          of radius (R0^2 - 2t)^1/2 (within 0.05 l);
  volume-preserving-      area within 1% of A0 (+ 0.5% + 20 eps L0 N, as above), one curve at
  curvature               every step, the length not above L0 by more than 0.5% (the run's
                          budget); a circle stays itself (within 0.05 l);
  vortex                  LeVeque's flow on [0, 1]^2 (the curve inside it, sizes 1e-3 to 0.2;
                          a third of the runs to t = 8, the period): area within 5% of A0 (the
                          guards check 1% a step; the campaign holds the run to the rigid
                          motions' 5%), one curve at every step (a smooth flow neither tears nor
                          joins), and back at the start at t = 8 within 0.05 l.

  Runs ending ok but beyond docs/defaults.md's targets (5e-3 l for the shape of rigid motions
  and unit-normal, 1% of the change of area under curvature flow, 1e-3 of A0 kept under
  volume-preserving curvature) are counted apart ("beyond target"), not as defects.

  campaign.py --slc build/bin/slc --size small --check                  (30 runs)
  campaign.py --slc build/bin/slc --set defaults --size small --check   (the tests: 7 runs)
  campaign.py --slc build/bin/slc --size large --doc docs/errors.md --check   (scripts/bench: 400)
  campaign.py --slc build/bin/slc --set defaults --size large --doc docs/errors.md   (200)

--only I runs case I alone and --keep DIR keeps its files (caseI.json, outI/) to reproduce it.
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

SIZES = {"options": {"small": (30, 1), "large": (400, 2)},  # runs, seed
         "defaults": {"small": (7, 3), "large": (200, 4)}}
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


# ---------------------------------------------------------------------------------------------
# Shared by the sets of curves and by campaign3d.py: running one command and naming its end.

def run_outcome(cmd, folder, timeout):
    """Runs cmd; returns (outcome, detail, summary): outcome one of ok, vanished, unstable,
    failed (exit 3 with another status), refused (exit 2), crash; summary.json or None."""
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "crash", f"no end in {timeout:g} s", None
    # Notes (the domain grew, a step left |G| above eps, the curves were reoriented) and the
    # reversed orientation of a surface are not errors.
    err = "\n".join(l for l in r.stderr.strip().splitlines()
                    if not l.startswith("slc: note:") and "was oriented inward" not in l)
    if (r.returncode not in (0, 2, 3) or "internal error" in err or "please report" in err
            or len(err.splitlines()) > 1):
        return "crash", f"exit {r.returncode}: {err[:400]}", None
    if r.returncode == 2:
        return "refused", err, None
    path = os.path.join(folder, "summary.json")
    summary = json.load(open(path)) if os.path.exists(path) else None
    status = summary["status"] if summary else None
    if r.returncode == 3:
        return ("unstable" if status == "unstable" else "failed"), err, summary
    if status not in ("ok", "vanished"):
        return "crash", f"exit 0 with status {status}: {err[:300]}", summary
    return status, err, summary


OUTCOMES = ["ok", "vanished", "unstable", "failed", "refused", "impossible", "inaccurate", "crash"]
DEFECTS = ("impossible", "inaccurate", "crash")


class Tally:
    """Counts of outcomes a law (a row of the table), the defects and the runs beyond target."""

    def __init__(self, rows):
        self.rows = {r: {o: 0 for o in OUTCOMES + ["runs", "target"]} for r in rows}
        self.defects = []  # (kind, command, why)
        self.misses = []  # (command, what missed docs/defaults.md's target)

    def add(self, row, outcome, shown=None, why=None, target=None):
        c = self.rows[row]
        c["runs"] += 1
        c[outcome] += 1
        if outcome in DEFECTS:
            self.defects.append((outcome, shown, why))
        if target and outcome not in DEFECTS:
            c["target"] += 1
            self.misses.append((shown, target))

    def total(self):
        t = {o: 0 for o in OUTCOMES + ["runs", "target"]}
        for c in self.rows.values():
            for k, v in c.items():
                t[k] += v
        return t

    def table(self, title, target_column=True):
        head = ["law", "runs", "ok", "vanished", "unstable (exit 3)", "failed (exit 3)",
                "refused (exit 2)", "impossible", "off the exact shape", "crashes"]
        keys = ["runs", "ok", "vanished", "unstable", "failed", "refused", "impossible",
                "inaccurate", "crash"]
        if target_column:
            head.insert(3, "of them beyond target")
            keys.insert(2, "target")
        lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        rows = [(r, c) for r, c in self.rows.items() if c["runs"]]
        for row, c in rows + [(f"**{title}**", self.total())]:
            lines.append("| " + " | ".join([row] + [str(c[k]) for k in keys]) + " |")
        return lines


def write_region(path, name, lines):
    """Writes lines between the markers of region `name` in path (appended when absent)."""
    begin, end = f"<!-- {name}: written by bench/campaign", f"<!-- /{name} -->"
    text = open(path).read()
    if begin in text:
        head, rest = text.split(begin, 1)
        marker = begin + rest.split("-->", 1)[0] + "-->"
        text = head + "\n".join([marker] + lines + [end]) + rest.split(end, 1)[1]
    else:
        script = "campaign3d.py" if name.endswith("3d") else "campaign.py"
        marker = f"<!-- {name}: written by bench/{script} -->"
        text = text.rstrip("\n") + "\n\n" + "\n".join([marker] + lines + [end]) + "\n"
    open(path, "w").write(text)


def log_uniform(rng, lo, hi):
    return 10.0 ** rng.uniform(math.log10(lo), math.log10(hi))


# ---------------------------------------------------------------------------------------------
# Distances to polygons, for the exact laws of --set defaults.

def segment_distance(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    ll = dx * dx + dy * dy
    s = 0.0 if ll == 0.0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / ll))
    return math.hypot(p[0] - a[0] - s * dx, p[1] - a[1] - s * dy)


class Polygons:
    """Closed polygons' segments bucketed on a grid: the distance to them, and whether a point is
    inside (crossings of the segments in its row of the grid)."""

    def __init__(self, curves, cell):
        self.segs = [(c[i - 1], c[i]) for c in curves for i in range(len(c))]
        self.cell = cell
        self.grid, self.rows = {}, {}
        for n, (a, b) in enumerate(self.segs):
            i0, i1 = sorted((math.floor(a[0] / cell), math.floor(b[0] / cell)))
            j0, j1 = sorted((math.floor(a[1] / cell), math.floor(b[1] / cell)))
            for j in range(j0, j1 + 1):
                self.rows.setdefault(j, []).append(n)
                for i in range(i0, i1 + 1):
                    self.grid.setdefault((i, j), []).append(n)

    def distance(self, p):
        ci, cj = math.floor(p[0] / self.cell), math.floor(p[1] / self.cell)
        best = math.inf
        for r in range(0, 65):
            ring = [(ci + i, cj + j) for i in range(-r, r + 1) for j in (-r, r)]
            ring += [(ci + i, cj + j) for i in (-r, r) for j in range(-r + 1, r)]
            for key in set(ring):
                for n in self.grid.get(key, ()):
                    best = min(best, segment_distance(p, *self.segs[n]))
            if best <= r * self.cell:  # every segment not yet seen is at least r cells away
                return best
        return min(segment_distance(p, a, b) for a, b in self.segs)

    def inside(self, p):
        crossings = 0
        for n in self.rows.get(math.floor(p[1] / self.cell), ()):
            (ax, ay), (bx, by) = self.segs[n]
            if (ay > p[1]) != (by > p[1]) and p[0] < ax + (p[1] - ay) * (bx - ax) / (by - ay):
                crossings += 1
        return crossings % 2 == 1

    def signed_distance(self, p):
        d = self.distance(p)
        return -d if self.inside(p) else d


def one_sided(points, polygons):
    """The largest distance of the points from the polygons."""
    return max((polygons.distance(p) for p in points), default=0.0)


# ---------------------------------------------------------------------------------------------
# --set defaults: a user's curve under each built-in law at the default settings.

LAWS_2D = ["rotation", "translation", "unit-normal", "anisotropic", "curvature",
           "volume-preserving-curvature", "vortex"]
SHAPE_GROSS = 0.05  # of the half-width: ten times docs/defaults.md's target for the shape
SHAPE_TARGET = 5e-3  # docs/defaults.md: rigid motions and unit-normal
RIGID_RUN = 0.05  # the rigid motions' documented budget over a run
USER_AREA_DRIFT = 0.01  # a user's curves: the run's area lag under curvature flow
CHORDS = 0.005  # the final polygon's chords against the arcs the guards measure
LENGTH_RUN = 0.005  # the shortening laws' length over the run
EPS_LENGTHS = 20.0  # the guards' least tolerance, 20 eps L


def curve_shape(rng, centre, size):
    """One counterclockwise curve about centre: (points, description, convex, inradius)."""
    cx, cy = centre
    kind = rng.choices(["circle", "ellipse", "star", "polygon"], [3, 3, 3, 1])[0]
    turn = rng.uniform(0, 2 * math.pi)
    if kind == "circle":
        n = rng.choice([128, 256, 512])
        pts = [(cx + size * math.cos(2 * math.pi * i / n), cy + size * math.sin(2 * math.pi * i / n))
               for i in range(n)]
        return pts, f"circle R {size:.3g} ({n} points)", True, size
    if kind == "ellipse":
        b = size * rng.uniform(0.3, 1.0)
        n = 256
        pts = []
        for i in range(n):
            a = 2 * math.pi * i / n
            x, y = size * math.cos(a), b * math.sin(a)
            pts.append((cx + x * math.cos(turn) - y * math.sin(turn),
                        cy + x * math.sin(turn) + y * math.cos(turn)))
        return pts, f"ellipse {size:.3g} x {b:.3g}", True, b
    if kind == "star":
        n = rng.choice([256, 512])
        modes = [(k, rng.uniform(0.0, 0.3 / k), rng.uniform(0, 2 * math.pi)) for k in (2, 3, 5)]
        radii = [size * (1.0 + sum(am * math.cos(k * 2 * math.pi * i / n + ph) for k, am, ph in modes))
                 / (1.0 + sum(am for _, am, _ in modes)) for i in range(n)]
        pts = [(cx + r * math.cos(2 * math.pi * i / n), cy + r * math.sin(2 * math.pi * i / n))
               for i, r in enumerate(radii)]
        convex = all((pts[i][0] - pts[i - 1][0]) * (pts[(i + 1) % n][1] - pts[i][1])
                     - (pts[i][1] - pts[i - 1][1]) * (pts[(i + 1) % n][0] - pts[i][0]) >= 0
                     for i in range(n))
        shape = "convex" if convex else "non-convex"
        return pts, f"smooth {shape} star R {size:.3g}", convex, min(radii) * 0.9
    sides = rng.choice([3, 4, 5, 6, 8, 0])
    if sides == 0:  # an L: a non-convex polygon
        u = size / 2
        corners = [(-2, -2), (2, -2), (2, 0), (0, 0), (0, 2), (-2, 2)]
        pts = [(cx + u * (x * math.cos(turn) - y * math.sin(turn)),
                cy + u * (x * math.sin(turn) + y * math.cos(turn))) for x, y in corners]
        return pts, f"L polygon {size:.3g}", False, 0.5 * u
    pts = [(cx + size * math.cos(turn + 2 * math.pi * i / sides),
            cy + size * math.sin(turn + 2 * math.pi * i / sides)) for i in range(sides)]
    return pts, f"{sides}-gon R {size:.3g}", True, size * math.cos(math.pi / sides)


def defaults_case(rng, index):
    """One run of --set defaults: the curve, the law and its parameters, and what to check."""
    law = LAWS_2D[index % len(LAWS_2D)]
    if law == "vortex":  # the field lives on [0, 1]^2 (and repeats beyond)
        size = log_uniform(rng, 1e-3, 0.2)
        centre = (rng.uniform(1.5 * size, 1 - 1.5 * size), rng.uniform(1.5 * size, 1 - 1.5 * size))
    else:
        size = log_uniform(rng, 1e-3, 1e3)
        r, a = 10 * size * math.sqrt(rng.random()), rng.uniform(0, 2 * math.pi)
        centre = (r * math.cos(a), r * math.sin(a))
    pts, desc, convex, inradius = curve_shape(rng, centre, size)
    case = {"index": index, "law": law, "points": pts, "shape": desc, "convex": convex,
            "centre": centre, "size": size, "inradius": inradius}
    params = {}
    v0 = size * rng.uniform(0.3, 2.0)  # a speed: sizes per unit time
    if law == "rotation":
        omega = rng.choice([-1, 1]) * rng.uniform(0.5, 3.0)
        r, a = 2 * size * rng.random(), rng.uniform(0, 2 * math.pi)
        params = {"omega": omega, "cx": centre[0] + r * math.cos(a), "cy": centre[1] + r * math.sin(a)}
        t_end = rng.uniform(0.5, 6.3) / abs(omega)
    elif law == "translation":
        a = rng.uniform(0, 2 * math.pi)
        params = {"ux": v0 * math.cos(a), "uy": v0 * math.sin(a)}
        t_end = rng.uniform(0.5, 2.0)
    elif law == "unit-normal":
        grow = rng.random() < 0.7
        d = size * rng.uniform(0.05, 0.3) if grow else inradius * rng.uniform(0.1, 0.5)
        params = {"speed": v0 if grow else -v0}
        t_end = d / v0
    elif law == "anisotropic":
        if rng.random() < 0.5:  # the law's default shape of speed (R = -1, m = 4, eps = 1/3)
            params = {"R": -v0, "m": 4, "eps": v0 / 3}
        else:
            params = {"R": rng.choice([-1, 1]) * v0, "m": rng.choice([2, 3, 4, 5, 6]),
                      "eps": v0 * rng.uniform(-1.0, 1.0), "tilt": rng.uniform(0, math.pi)}
        fast = abs(params["R"]) + abs(params["eps"])
        grow = params["R"] - abs(params["eps"]) > 0
        d = size * rng.uniform(0.05, 0.3) if grow else inradius * rng.uniform(0.1, 0.5)
        t_end = d / fast
    elif law == "curvature":
        extinction = shoelace(pts) / (2 * math.pi)
        t_end = extinction * (rng.uniform(0.1, 0.9) if rng.random() < 0.85 else rng.uniform(1.05, 1.5))
    elif law == "volume-preserving-curvature":
        t_end = size * size * rng.uniform(0.02, 0.3)
    else:
        t_end = 8.0 if rng.random() < 1 / 3 else rng.uniform(0.5, 4.0)
    args = ["--velocity", law]
    for k, v in params.items():
        args += ["--param", f"{k}={v:.9g}"]
    case["params"] = {k: float(f"{v:.9g}") for k, v in params.items()}
    case["t_end"] = float(f"{t_end:.9g}")
    case["args"] = args + ["--t-end", f"{t_end:.9g}"]
    return case


def rigid_map_back(case, t):
    """The inverse of the rigid motion to t, as a function of a point."""
    p = case["params"]
    if case["law"] == "translation":
        return lambda q: (q[0] - p["ux"] * t, q[1] - p["uy"] * t)
    c, s = math.cos(-p["omega"] * t), math.sin(-p["omega"] * t)
    return lambda q: (p["cx"] + c * (q[0] - p["cx"]) - s * (q[1] - p["cy"]),
                      p["cy"] + s * (q[0] - p["cx"]) + c * (q[1] - p["cy"]))


def hausdorff(final_curves, start, points, cell):
    """The larger one-sided distance between the final curves and the start (the start's
    vertices against the final polygons, the final vertices against the start)."""
    return max(one_sided([q for c in final_curves for q in c], start),
               one_sided(points, Polygons(final_curves, cell)))


def judge_defaults(case, summary, final, history):
    """What the result breaks: (None, None) or ("impossible" or "inaccurate", why), and what
    missed docs/defaults.md's target (or None)."""
    law, pts, t_end = case["law"], case["points"], case["t_end"]
    a0, l0 = shoelace(pts), perimeter(pts)
    xs, ys = [q[0] for q in pts], [q[1] for q in pts]
    ell = 0.5 * max(max(xs) - min(xs), max(ys) - min(ys))
    cell = ell / 32
    eps, steps, status, t = summary["params"]["eps"], summary["steps"], summary["status"], summary["t"]
    area, length = summary["area"], summary.get("length", 0.0)
    curves = [[tuple(q) for q in c["points"]] for c in final.get("curves", [])]
    count = len(curves)
    most = max(history, key=lambda r: r["components"])  # the step with the most curves
    floor = EPS_LENGTHS * eps * l0 * max(steps, 1)
    start = Polygons([pts], cell)
    impossible = lambda why: ("impossible", why)  # noqa: E731
    inaccurate = lambda why: ("inaccurate", why)  # noqa: E731
    if status == "vanished" and law in ("rotation", "translation", "volume-preserving-curvature",
                                        "vortex"):
        return impossible("vanished under a law that keeps the area"), None
    if most["components"] > 1 and law in ("rotation", "translation", "curvature",
                                          "volume-preserving-curvature", "vortex"):
        split = [r for r in history if r["components"] > 1]
        return impossible(f"split under a law that cannot split a curve: {split[0]['components']:g} "
                          f"curves at t = {split[0]['t']:.4g}, {len(split)} of {len(history) - 1} "
                          f"steps split, up to {most['components']:g} curves; {count} at the "
                          f"end"), None
    if law in ("rotation", "translation", "vortex"):
        budget = RIGID_RUN * abs(a0) + EPS_LENGTHS * eps * l0
        if abs(area - a0) > budget:
            return impossible(f"area {area:.6g} from {a0:.6g} ({100 * (area / a0 - 1):+.3g}%), "
                              f"budget {budget:.3g}"), None
        if law == "vortex":
            if abs(t - 8.0 * round(t / 8.0)) < 1e-9 and t > 0:  # back at the start
                err = hausdorff(curves, start, pts, cell) / ell
                if err > SHAPE_GROSS:
                    return inaccurate(f"back at t = {t:g}, {err:.3g} l from the start"), None
            return None, None
        back = rigid_map_back(case, t)
        err = hausdorff([[back(q) for q in c] for c in curves], start, pts, cell) / ell
        if err > SHAPE_GROSS:
            return inaccurate(f"the curve is {err:.3g} l from the moved start"), None
        return None, (f"shape {err:.2e} l" if err > SHAPE_TARGET else None)
    if law in ("unit-normal", "anisotropic"):
        p = case["params"]
        if law == "unit-normal":
            lo = hi = p["speed"] * t
        else:
            lo, hi = (p["R"] - abs(p["eps"])) * t, (p["R"] + abs(p["eps"])) * t
        if status == "vanished":
            # The region holds the start eroded by |lo| t at least while that is not empty.
            if lo >= 0 or -lo < case["inradius"]:
                return impossible(f"vanished by t = {t:.4g}, where the start eroded by "
                                  f"{-lo:.3g} is not empty"), None
            return None, None
        if lo >= 0 and area < a0 * (1 - 0.01):
            return impossible(f"a growing region lost area: {area:.6g} from {a0:.6g}"), None
        if law == "unit-normal" and lo > 0 and case["convex"]:
            exact = a0 + l0 * lo + math.pi * lo * lo
            if abs(area - exact) > 0.01 * abs(a0):
                return impossible(f"area {area:.6g} where Steiner's formula gives {exact:.6g}"), None
        dist = [start.signed_distance(q) for c in curves for q in c]
        miss = max(max(lo - d for d in dist), max(d - hi for d in dist)) / ell
        if miss > SHAPE_GROSS:
            return inaccurate(f"vertices at signed distance {min(dist):.4g}..{max(dist):.4g} "
                              f"from the start, where the law gives {lo:.4g}..{hi:.4g}: "
                              f"{miss:.3g} l off"), None
        return None, (f"offset {miss:.2e} l" if law == "unit-normal" and miss > SHAPE_TARGET else None)
    # curvature, volume-preserving curvature
    budget = (USER_AREA_DRIFT + CHORDS) * abs(a0) + floor
    exact = max(a0 - 2 * math.pi * t, 0.0) if law == "curvature" else a0
    if status == "vanished":
        if exact > budget + 2 * math.pi * t_end / steps:
            return impossible(f"vanished at t = {t:.4g} with {exact:.4g} of area left by the law "
                              f"(extinction at {a0 / (2 * math.pi):.4g})"), None
        return None, None
    if abs(area - exact) > budget:
        return impossible(f"area {area:.6g} where the law gives {exact:.6g}, budget {budget:.3g}"), None
    if law == "volume-preserving-curvature" and length > l0 * (1 + LENGTH_RUN) + floor:
        return impossible(f"length {length:.6g} from {l0:.6g} under a law that shortens the curve"), None
    if case["shape"].startswith("circle"):
        r0 = case["size"]
        r_exact = math.sqrt(max(r0 * r0 - 2 * t, 0.0)) if law == "curvature" else r0
        cx, cy = case["centre"]
        err = max(abs(math.hypot(q[0] - cx, q[1] - cy) - r_exact) for c in curves for q in c) / r0
        if err > SHAPE_GROSS:
            return inaccurate(f"a vertex {err:.3g} R0 off the circle of radius {r_exact:.4g}"), None
    if law == "curvature" and abs(area - exact) > 0.01 * (a0 - exact):
        return None, f"area change off by {abs(area - exact) / (a0 - exact):.2e} of itself"
    if law == "volume-preserving-curvature" and abs(area - a0) > 1e-3 * abs(a0):
        return None, f"area kept to {abs(area - a0) / abs(a0):.2e}"
    return None, None


def defaults_campaign(a, slc, runs, seed):
    rng = random.Random(seed)
    work = os.path.abspath(a.keep) if a.keep else tempfile.mkdtemp(prefix="slc-campaign-")
    os.makedirs(work, exist_ok=True)
    tally = Tally(LAWS_2D)
    start = time.time()
    try:
        for i in range(runs):
            case = defaults_case(rng, i)
            if a.only is not None and i != a.only:
                continue
            initial = os.path.join(work, f"case{i}.json")
            with open(initial, "w") as f:
                json.dump({"curves": [{"points": case["points"]}]}, f)
            folder = os.path.join(work, f"out{i}")
            cmd = [slc, "run", "--initial", initial, *case["args"], "--out", folder, "--quiet",
                   "--threads", str(a.threads)]
            shown = " ".join(["slc", "run", "--initial", f"case{i}.json", *case["args"]])
            shown += f"  [{case['shape']} at ({case['centre'][0]:.4g}, {case['centre'][1]:.4g})]"
            outcome, detail, summary = run_outcome(cmd, folder, TIMEOUT_S)
            target = None
            if outcome in ("ok", "vanished"):
                final = json.load(open(os.path.join(folder, "final.json")))
                history = read_history(os.path.join(folder, "history.csv"))
                verdict, target = judge_defaults(case, summary, final, history)
                if verdict:
                    outcome, detail = verdict
            tally.add(case["law"], outcome, shown, detail, target)
            if a.verbose:
                print(f"{i} {case['law']} {case['shape']}: {outcome} {detail or ''} {target or ''}",
                      flush=True)
            if not a.keep:
                shutil.rmtree(folder, ignore_errors=True)
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)
    seconds = round(time.time() - start)
    report(tally, f"defaults, {a.size}", seed, seconds, a.doc, "campaign-defaults", True,
           a.threads)
    bad = sum(1 for d in tally.defects)
    return 1 if a.check and bad else 0


def report(tally, title, seed, seconds, doc, region, targets, threads):
    """Prints the defects, the runs beyond target and the table; writes the table to doc."""
    for kind, shown, why in tally.defects:
        print(f"{kind}: {shown}: {why}")
    for shown, what in tally.misses:
        print(f"beyond target: {shown}: {what}")
    lines = tally.table(f"{title}, seed {seed}", targets)
    print("\n".join(lines))
    print(json.dumps({"set": title, "seed": seed, **tally.total(), "seconds": seconds}))
    if doc:
        cores = "one thread" if threads == 1 else f"{threads} threads"
        out = lines + ["", f"{tally.total()['runs']} runs in {seconds} s, each on {cores}."]
        if tally.defects:
            out.append("")
        for kind, shown, why in tally.defects:
            out.append(f"- {kind}: `{shown}`: {why}")
        write_region(doc, region, out)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--slc", required=True)
    p.add_argument("--set", choices=SIZES, default="options", help="which campaign (see above)")
    p.add_argument("--size", choices=["small", "large"], default="small")
    p.add_argument("--seed", type=int)
    p.add_argument("--check", action="store_true", help="exit 1 when any defect is found")
    p.add_argument("--doc", help="write the counts into this file between campaign markers")
    p.add_argument("--only", type=int, help="run only the case of this index (to reproduce it)")
    p.add_argument("--keep", help="write the cases' files here and keep them")
    p.add_argument("--threads", type=int, default=1, help="--threads of each run (default 1)")
    p.add_argument("--verbose", action="store_true", help="print each run's outcome as it ends")
    a = p.parse_args()
    runs, seed = SIZES[a.set][a.size]
    seed = a.seed if a.seed is not None else seed
    slc = os.path.abspath(a.slc)
    if a.set == "defaults":
        return defaults_campaign(a, slc, runs, seed)
    return options_campaign(a, slc, runs, seed)


def options_campaign(a, slc, runs, seed):
    rng = random.Random(seed)
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
