#!/usr/bin/env python3
"""The paper's figures at the paper's own parameters (docs/figures.md).

Runs each figure's problem with `slc run` at the N/S/K/P/eps the paper gives, measures what the
paper claims (area kept, errors against exact solutions, distances between runs it overlays,
runs tilted and turned back), copies the pictures into docs/figures/ and writes docs/figures.md.
Standard library only; called by `scripts/figures paper`.
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile


def run(slc, out, args):
    """slc run ARGS --out OUT; returns summary.json (the run may end unstable: exit 3)."""
    done = subprocess.run([slc, "run", "--quiet", *args, "--out", out],
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode not in (0, 3):
        sys.exit(f"slc run {' '.join(args)}: exit {done.returncode}: {done.stderr.strip()}")
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def history(out):
    with open(os.path.join(out, "history.csv")) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def area_drift(out):
    """Largest |A(t) − A(0)| / A(0) over the run, and the last one."""
    rows = history(out)
    a0 = rows[0]["area"]
    drifts = [(r["area"] - a0) / a0 for r in rows]
    return max(drifts, key=abs), drifts[-1]


def from_its_circle(out):
    """The largest distance of a vertex of the final curve (the first, when there are several)
    from the circle of its area about its centroid."""
    with open(os.path.join(out, "final.json")) as f:
        points = json.load(f)["curves"][0]["points"]
    a = cx = cy = 0.0
    for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1]):
        w = x0 * y1 - x1 * y0
        a, cx, cy = a + 0.5 * w, cx + (x0 + x1) * w, cy + (y0 + y1) * w
    cx, cy, radius = cx / (6 * a), cy / (6 * a), math.sqrt(abs(a) / math.pi)
    return max(abs(math.hypot(x - cx, y - cy) - radius) for x, y in points)


def largest_zigzag(out, t0, t1):
    """Over the frames from t0 to t1: the largest distance of a vertex from the chord of its two
    neighbours, among the vertices where the curve turns by more than 30°."""
    worst = 0.0
    folder = os.path.join(out, "frames")
    for name in sorted(os.listdir(folder)):
        with open(os.path.join(folder, name)) as f:
            frame = json.load(f)
        if not t0 <= frame["time"] <= t1:
            continue
        for c in frame["curves"]:
            p = c["points"]
            for a, b, d in zip(p[-1:] + p[:-1], p, p[1:] + p[:1]):
                u, v = (b[0] - a[0], b[1] - a[1]), (d[0] - b[0], d[1] - b[1])
                turn = abs(math.atan2(u[0] * v[1] - u[1] * v[0], u[0] * v[0] + u[1] * v[1]))
                chord = math.hypot(d[0] - a[0], d[1] - a[1])
                if turn > math.radians(30) and chord > 0:
                    off = abs((d[0] - a[0]) * (b[1] - a[1]) - (d[1] - a[1]) * (b[0] - a[0]))
                    worst = max(worst, off / chord)
    return worst


def components_range(out):
    counts = [int(r["components"]) for r in history(out)]
    return min(counts), max(counts)


def load_curves(path):
    with open(path) as f:
        return [c["points"] for c in json.load(f)["curves"]]


def turned(curves, degrees):
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    return [[[c * x - s * y, s * x + c * y] for x, y in curve] for curve in curves]


def samples(curves):
    """Vertices and segment midpoints: where Eq. 11 measures errors."""
    out = []
    for curve in curves:
        n = len(curve)
        for i in range(n):
            a, b = curve[i], curve[(i + 1) % n]
            out.append(a)
            out.append([0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])])
    return out


def one_way(slc, work, curves, points, box):
    ref = os.path.join(work, "ref.json")
    pts = os.path.join(work, "pts.csv")
    with open(ref, "w") as f:
        json.dump({"curves": [{"points": c} for c in curves]}, f)
    with open(pts, "w") as f:
        f.writelines(f"{x!r},{y!r}\n" for x, y in points)
    done = subprocess.run([slc, "distance", "--initial", ref, "--points", pts, "--box",
                           ",".join(repr(v) for v in box)],
                          capture_output=True, text=True, check=True)
    lines = done.stdout.strip().splitlines()[1:]
    return max(abs(float(line.split(",")[2])) for line in lines)


def largest_corner_cut(slc, work, out, box, tilt=0.0):
    """Fig. 13 shrinking: the largest distance from a corner of the exact triangle (circumradius
    1 − 2t, its apex at 90° + tilt) to the curves, over every frame of the run."""
    worst = 0.0
    folder = os.path.join(out, "frames")
    for name in sorted(os.listdir(folder)):
        with open(os.path.join(folder, name)) as f:
            frame = json.load(f)
        radius = 1.0 - 2.0 * frame["time"]
        corners = [(radius * math.cos(math.radians(90.0 + 120.0 * j + tilt)),
                    radius * math.sin(math.radians(90.0 + 120.0 * j + tilt))) for j in range(3)]
        curves = [c["points"] for c in frame["curves"]]
        worst = max(worst, one_way(slc, work, curves, corners, box))
    return worst


def hausdorff(slc, work, a, b, box):
    """Hausdorff distance between two sets of curves, at vertices and midpoints; inf if either
    is empty."""
    if not a or not b:
        return math.inf
    return max(one_way(slc, work, a, samples(b), box), one_way(slc, work, b, samples(a), box))


def frame_path(out, j):
    return os.path.join(out, "frames", f"frame_{j:04d}.json")


def fmt(x, digits=2):
    if x is None:
        return "—"
    if isinstance(x, float) and math.isinf(x):
        return "∞"
    return f"{x:.{digits}g}".replace("e-0", "e−").replace("e-", "e−").replace("e+0", "e")


class Figures:
    def __init__(self, slc, work, figures):
        self.slc, self.work, self.figures = slc, work, figures
        self.md = []

    def out(self, name):
        return os.path.join(self.work, name)

    def run(self, name, args):
        return run(self.slc, self.out(name), args)

    def picture(self, name, target):
        shutil.copy(os.path.join(self.out(name), "frames.png"), os.path.join(self.figures, target))
        return f"![{name}](figures/{target})"

    def panels(self, runs, times, columns, target, view=None, by_run=False):
        """The frames nearest `times` of runs, a list of (legend label, run name), a panel a time
        with the runs overlaid (`slc render --columns`), or with by_run a panel a run (all its
        frames, or those nearest `times`), written to docs/figures/target."""
        folder = self.out(f"panels-{target}")
        os.makedirs(folder, exist_ok=True)
        for label, name in runs:  # the legend names a run by its folder's name
            os.symlink(self.out(name), os.path.join(folder, label))
        args = [self.slc, "render", "--frames", *[os.path.join(folder, l) for l, _ in runs],
                "--columns", str(columns), "--out", os.path.join(self.figures, target)]
        if times:
            args += ["--times", ",".join(f"{t:g}" for t in times)]
        if by_run:
            args.append("--by-run")
        if view:
            args += ["--box", ",".join(f"{v:g}" for v in view)]
        subprocess.run(args, check=True)
        return f"![{target}](figures/{target})"

    def distance(self, a_name, b_name, box, j=None, turn_b=0.0):
        """Distance between the final curves (or frame j) of two runs, b turned by turn_b°; None
        when a run ended before frame j."""
        if j is not None and not all(os.path.exists(frame_path(self.out(n), j))
                                     for n in (a_name, b_name)):
            return None

        def curves(name):
            path = (os.path.join(self.out(name), "final.json") if j is None
                    else frame_path(self.out(name), j))
            return load_curves(path)
        return hausdorff(self.slc, self.work, curves(a_name), turned(curves(b_name), turn_b), box)

    def write(self, text):
        self.md.append(text)

    # Fig. 13 -----------------------------------------------------------------------------
    def triangles(self):
        self.write("""## Fig. 13: triangles growing and shrinking with unit normal speed

> Inward motion should keep corners sharp, while outward motion should produce rounded corners.
> […] Fig. 13 superimposes 40/0/4/2/10⁻⁴ over 80/0/5/2/10⁻⁴ runs to show convergence to
> graphical accuracy. Runs at resolution 80/0/5/2/10⁻⁵ and tilted 0° vs 10° show that grid
> orientation effects are negligible.

`slc run --problem triangle-normal --param speed=±1 [--param tilt=10] -N … -K … -P 2 --eps …`:
an equilateral triangle of circumradius 1 to t = 0.4 in [−2.5, 2.5]² (the paper gives neither
size nor domain). The exact solution is the offset of the triangle by t: sharp when shrinking,
with corner arcs of radius t when growing. E∞ is Eq. 11's error against it; the distances are
between the final curves (vertices and midpoints), the tilted run turned back by 10°.
The paper extends the vertex velocities to the nearest point (the problem's default); with
`--extension direct` the speed is evaluated off the curve with the distance field's normal, so
G is the exact offset of the polygon (docs/algorithms/evolve.md).

| motion | extension | E∞ 40/0/4/2/1e−4 | E∞ 80/0/5/2/1e−4 | their distance | E∞ 80/0/5/2/1e−5, 0° | 10° | 0° vs 10° turned back | largest corner cut, every step of 40/0/4/2/1e−4, 80/0/5/2/1e−4 | curves during the runs |
|---|---|---|---|---|---|---|---|---|---|
""")
        box = [-2.5, -2.5, 2.5, 2.5]
        for speed, motion in ((-1, "shrinking"), (1, "growing")):
            for extension in ("nearest", "direct"):
                tag = f"tri{speed:+d}{extension}"
                base = ["--problem", "triangle-normal", "--param", f"speed={speed}",
                        "--extension", extension]
                runs = {
                    "coarse": ["-N", "40", "-K", "4", "-P", "2", "--eps", "1e-4", "--frames", "40"],
                    "fine": ["-N", "80", "-K", "5", "-P", "2", "--eps", "1e-4", "--frames", "80"],
                    "flat": ["-N", "80", "-K", "5", "-P", "2", "--eps", "1e-5"],
                    "tilted": ["-N", "80", "-K", "5", "-P", "2", "--eps", "1e-5", "--param",
                               "tilt=10", "--frames", "4"],
                }
                s = {k: self.run(f"{tag}-{k}", base + v) for k, v in runs.items()}
                counts = [components_range(self.out(f"{tag}-{k}")) for k in runs]
                lo, hi = min(c[0] for c in counts), max(c[1] for c in counts)
                cuts = "—" if speed > 0 else ", ".join(
                    fmt(largest_corner_cut(self.slc, self.work, self.out(f"{tag}-{k}"), box))
                    for k in ("coarse", "fine"))
                self.write(
                    f"| {motion} | {extension} | {fmt(s['coarse']['e_inf'])} | "
                    f"{fmt(s['fine']['e_inf'])} | "
                    f"{fmt(self.distance(f'{tag}-coarse', f'{tag}-fine', box))} | "
                    f"{fmt(s['flat']['e_inf'])} | {fmt(s['tilted']['e_inf'])} | "
                    f"{fmt(self.distance(f'{tag}-flat', f'{tag}-tilted', box, turn_b=-10))} | "
                    f"{cuts} | {lo}–{hi} |\n".replace("1–1", "1"))
        self.write("\nThe paper's method (the nearest-point extension) at t = 0, 0.1, …, 0.4: "
                   "40/0/4/2/1e−4 (`coarse`) over 80/0/5/2/1e−4 (`fine`), and the 80/0/5/2/1e−5 "
                   "run tilted 10° and turned back (`tilted`):\n\n")
        for speed, target in ((-1, "figure13_shrinking.png"), (1, "figure13_growing.png")):
            tag = f"tri{speed:+d}nearest"
            back = self.out(f"{tag}-tilted-back")
            os.makedirs(os.path.join(back, "frames"), exist_ok=True)
            for j in range(5):
                with open(frame_path(self.out(f"{tag}-tilted"), j)) as f:
                    frame = json.load(f)
                for curve in frame["curves"]:
                    curve["points"] = turned([curve["points"]], -10)[0]
                with open(frame_path(back, j), "w") as f:
                    json.dump(frame, f)
            self.write(self.panels([("coarse", f"{tag}-coarse"), ("fine", f"{tag}-fine"),
                                    ("tilted", f"{tag}-tilted-back")],
                                   [0, 0.1, 0.2, 0.3, 0.4], 5, target,
                                   view=[-1.6, -1.6, 1.6, 1.6]) + "\n\n")
        self.write(
            "Shrinking, the corners stay sharp with both extensions: refinement places a vertex "
            "where the sides' lines meet, and a tip that the tree's interpolant parts from its "
            "body at a neck narrower than a cell (K = 5, t ≈ 0.2) is joined back "
            "(docs/algorithms/contour.md). The paper's nearest-point extension moves each corner "
            "vertex along its averaged normal; at a shrinking corner (a shock) each side keeps "
            "its own normal's velocity up to the corner, and the corrector takes both of its "
            "velocities from the side its characteristic comes from (docs/algorithms/evolve.md). "
            "Before that, a point on the bisector could take one side's velocity from Γ(t) and "
            "the other's from the predicted curve, G jumped there, and refinement could not "
            "place the corner: the largest cut over the steps was 0.13 and 0.012 "
            "(docs/notes/corners.md). "
            "Growing, the corner arcs start smaller than a cell and the paper's triangle "
            "safeguard keeps refinement from reaching them (a user's run, which has it off, ends "
            "2.3e−4 from the exact offset: docs/defaults.md).\n\n")

    # Fig. 4 ------------------------------------------------------------------------------
    def island(self):
        self.write("""## Fig. 4: an island forming at the cusps where circles merge

The paper's Fig. 4 shows an island (a hole) pinched off where merging circles meet and then
closing, without giving its circles. `merging-circles` at Fig. 14's 80/0/4/1/1e−4, with a frame
every step, near the place where its three circles meet:

""")
        self.run("island", ["--problem", "merging-circles", "-N", "80", "-K", "4", "-P", "1",
                            "--eps", "1e-4", "--frames", "80"])
        changes, prev = [], None
        for row in history(self.out("island")):
            if row["components"] != prev:
                changes.append(f"{int(row['components'])} at t = {row['t']:g}")
                prev = row["components"]
        self.write("The number of curves: " + ", ".join(changes) + ".\n\n" + self.panels(
            [("island", "island")], [0.1625, 0.175, 0.2, 0.2125, 0.225, 0.2375, 0.25, 0.2625],
            4, "figure4_island.png", view=[-0.5, -0.2, 0.5, 0.8]) + "\n\n")

    # Figs. 12, 14, 16 ----------------------------------------------------------------------
    def side_by_side(self):
        self.write("""## Figs. 12, 14 and 16: the captions' runs side by side

The paper draws each of these as four runs, coarse to fine, each with its frames overlaid. Here
the same N/S/K/P/ε (the caption's), each run's frames in time's colours (dark first), and its E∞
(Eq. 11) at the end.

""")
        figures = [
            ("Fig. 12: a propeller under rigid rotation, two periods", "propeller-rotation",
             "figure12_propeller.png", 8,
             [("40", "0", "3", "1", "1e-3"), ("80", "0", "4", "2", "1e-4"),
              ("160", "0", "5", "3", "1e-5"), ("320", "0", "6", "4", "1e-6")]),
            ("Fig. 14: circles merging with unit normal velocity", "merging-circles",
             "figure14_merging.png", 5,
             [("40", "0", "3", "0", "1e-3"), ("80", "0", "4", "1", "1e-4"),
              ("160", "0", "5", "2", "1e-5"), ("320", "0", "6", "3", "1e-6")]),
            ("Fig. 16: circles shrinking under curvature flow, 0 ≤ t ≤ 2", "circle-curvature",
             "figure16_curvature.png", 8,
             [("20", "1", "3", "0", "1e-3"), ("40", "1", "4", "1", "1e-4"),
              ("80", "1", "5", "2", "1e-5"), ("160", "2", "6", "3", "1e-6")]),
        ]
        for title, problem, target, frames, runs in figures:
            names, cells = [], []
            for n, smoothing, k, p, eps in runs:
                name = f"{problem}-{n}"
                s = self.run(name, ["--problem", problem, "-N", n, "-S", smoothing, "-K", k,
                                    "-P", p, "--eps", eps, "--frames", str(frames)])
                names.append((name, name))
                cells.append(f"{n}/{smoothing}/{k}/{p}/{eps.replace('-', '−')}: "
                             f"{s['status']}, E∞ {fmt(s['e_inf'])}")
            self.write(f"**{title}.** " + "; ".join(cells) + ".\n\n"
                       + self.panels(names, [], 4, target, by_run=True) + "\n\n")

    # Fig. 15 -----------------------------------------------------------------------------
    def wulff(self):
        self.write("""## Fig. 15: circles growing and shrinking into Wulff shapes

> We evolve an initially circular interface under Eq. (12) with R = −1 and |R| + ε(1 − m²) = −4.
> Fig. 15 shows the development of the faceted interface, superimposing computations tilted at
> 0°, 10° and 180°/m for anisotropies m = 3, 4, 5 and 6. Grid effects are negligible.

`slc run --problem wulff --param m=M [--param tilt=A]` at the problem's 80/0/5/2/1e−5 in
[−3.5, 3.5]² from a circle of radius 1.5 to t = 1 (the paper gives no radius, domain or time).
`tilt` turns the anisotropy's axes, v = R + ε cos(m(θ − A)); the tilted runs are turned back by
A and compared with the untilted one (vertices and midpoints) at t = 0.5, before m = 3, whose
speed is −1 − (5/8) cos 3θ, shrinks away (its radius falls at 0.375 to 1.625). The cells are 0.22.

| m | 0° vs 10° turned back | 0° vs 180°/m turned back | 0° vs 10° not turned back | curves during the runs |
|---|---|---|---|---|
""")
        box = [-3.5, -3.5, 3.5, 3.5]
        for m in (3, 4, 5, 6):
            names = []
            for tilt in (0, 10, 180 / m):
                name = f"wulff{m}-{tilt:g}"
                self.run(name, ["--problem", "wulff", "--param", f"m={m}", "--param",
                                f"tilt={tilt:.17g}", "--frames", "4"])
                names.append((name, tilt))
            lo = min(components_range(self.out(n))[0] for n, _ in names)
            hi = max(components_range(self.out(n))[1] for n, _ in names)
            # t = 0.5: frame 2 of 4.
            def half(name, turn):
                return turned(load_curves(frame_path(self.out(name), 2)), -turn)
            flat = half(names[0][0], 0)
            distances = [hausdorff(self.slc, self.work, flat, half(n, t), box)
                         for n, t in names[1:]]
            unturned = hausdorff(self.slc, self.work, flat, turned(half(names[1][0], 10), 10), box)
            self.write(f"| {m} | {fmt(distances[0])} | {fmt(distances[1])} | {fmt(unturned)} | "
                       f"{lo}–{hi} |\n".replace("1–1", "1"))
            self.superimposed(f"wulff-m{m}", names)
            grown = []
            for tilt in (0, 10, 180 / m):
                name = f"wulff{m}-grow-{tilt:g}"
                self.run(name, ["--problem", "wulff", "--param", f"m={m}", "--param", "R=1",
                                "--param", f"tilt={tilt:.17g}", "--frames", "4"])
                grown.append((name, tilt))
            self.superimposed(f"wulff-grow-m{m}", grown)
        self.write("\nAs the paper draws them: for each m, the frames at t = 0, 0.25, …, 1 of the "
                   "runs tilted 0°, 10° and 180°/m, turned back and superimposed (up to the "
                   "last frame before m = 3 vanishes); shrinking (R = −1, the paper's) and "
                   "growing (R = +1):\n\n")
        for kind, prefix in (("shrinking", "wulff-m"), ("growing", "wulff-grow-m")):
            target = f"figure15_{kind}.png"
            self.write(self.panels([(f"m = {m}", f"{prefix}{m}") for m in (3, 4, 5, 6)], [], 4,
                                   target, by_run=True) + "\n\n")
        self.write(
            "The tilted runs agree with the untilted one to a fraction of a cell, where "
            "the unturned ones differ by the turn itself. m = 3 stays jagged on its non-convex "
            "side (v + v'' < 0 there): a normal speed that depends on the normal is first order "
            "in time in this method (docs/algorithms/evolve.md).\n\n")

    def superimposed(self, name, runs):
        """A run folder `name` whose frames are those of runs, a list of (run, tilt in degrees),
        each turned back by its tilt, frame by frame: for `--by-run` panels in which runs tilted
        differently are superimposed."""
        frames = os.path.join(self.out(name), "frames")
        os.makedirs(frames, exist_ok=True)
        j = 0
        for i in range(5):
            for run_name, tilt in runs:
                if not os.path.exists(frame_path(self.out(run_name), i)):
                    continue  # the run vanished before this frame's time
                with open(frame_path(self.out(run_name), i)) as f:
                    frame = json.load(f)
                for curve in frame["curves"]:
                    curve["points"] = turned([curve["points"]], -tilt)[0]
                with open(frame_path(self.out(name), j), "w") as f:
                    json.dump(frame, f)
                j += 1

    # Fig. 17 -----------------------------------------------------------------------------
    def polygon(self):
        self.write("""## Fig. 17: a tilted polygon shrinking under curvature flow

> The curvature velocity displays fast-moving infinite transients at initial sharp corners, an
> intermediate regime of smooth motion, and infinite velocity again as the interface vanishes.
> […] runs a through d have parameters 320/1/5/4/10⁻³ through 2560/4/8/4/10⁻⁶.

`slc run --problem polygon-curvature` (a comb-shaped 12-gon of area 72 tilted 10°, in
[−8, 8]², docs/problems.md; the paper gives neither) with the paper's runs a–d, frames at
t = 0.1, 0.2, …; the distance between successive runs (vertices and midpoints) where the paper
overlays them. The exact area falls at 2π, so the polygon vanishes at 72/2π = 11.46.
*Zigzag*: over the frames from t = 1.6 to 3.3, the largest distance of a vertex from the chord of
its two neighbours where the curve turns by more than 30° there (a smooth curve at these
vertex spacings turns by a few degrees).

Run a with the paper's embedded mesh, M = 2^(K+1) = 64 (h = 0.25), keeps zigzags of a few
hundredths from the corners' transients: bumps narrower than the mesh, whose curvature the
module does not see, so no step damps them. With M = 128 (h = 0.125; k/h² = 2.6, stable at
S = 1) they are gone and the run lies nearer b; the picture draws run a so.

| run | M | status | vanished at t | zigzag, t = 1.6–3.3 | seconds |
|---|---|---|---|---|---|
""")
        runs = {"a": ["-N", "320", "-S", "1", "-K", "5", "-P", "4", "--eps", "1e-3"],
                "b": ["-N", "640", "-S", "2", "-K", "6", "-P", "4", "--eps", "1e-4"],
                "c": ["-N", "1280", "-S", "3", "-K", "7", "-P", "4", "--eps", "1e-5"],
                "d": ["-N", "2560", "-S", "4", "-K", "8", "-P", "4", "--eps", "1e-6"]}
        meshes = {"a64": ("a", 64), "a": ("a", 128), "b": ("b", 128), "c": ("c", 256),
                  "d": ("d", 512)}
        per_unit = 10  # frames a unit of time: 130 over the problem's t = 0 to 13
        for name, (paper_run, mesh) in meshes.items():
            args = runs[paper_run]
            s = self.run(f"polygon-{name}", ["--problem", "polygon-curvature", *args,
                                             "--mesh", str(mesh), "--frames", str(13 * per_unit)])
            zigzag = largest_zigzag(self.out(f"polygon-{name}"), 1.6, 3.3)
            self.write(f"| {paper_run}: {'/'.join(args[1::2])} | {mesh} | {s['status']} | "
                       f"{fmt(s['t'], 4)} | {fmt(zigzag)} | {fmt(s['wall_s'], 3)} |\n")
        box = [-8.0, -8.0, 8.0, 8.0]
        times = (1, 2, 4, 8)
        self.write("\n| t ≈ | " + " | ".join(str(t) for t in times) + " |\n|---|"
                   + "---|" * len(times) + "\n")
        for a, b, label in (("a64", "b", "a (M 64) vs b"), ("a", "b", "a (M 128) vs b"),
                            ("b", "c", "b vs c"), ("c", "d", "c vs d")):
            self.write(f"| {label} | " + " | ".join(
                fmt(self.distance(f"polygon-{a}", f"polygon-{b}", box, j=per_unit * t))
                for t in times) + " |\n")
        self.write("\nThe four runs overlaid at t ≈ 0, 1, 2, 4 and 8 (the frame nearest each; run a "
                   "with M = 128):\n\n" + self.panels([(n, f"polygon-{n}") for n in runs],
                                                     [0, 1, 2, 4, 8], 5, "figure17_polygon.png",
                                                     view=[-7, -6, 7, 6]) + "\n\n")

    # Fig. 18 -----------------------------------------------------------------------------
    def spiral(self):
        self.write("""## Fig. 18: a spiral unwinding under area-preserving curvature flow (Eq. 13)

> V = (C − ∫C ds / ∫1 ds) N smooths the moving interface by curvature while preserving the area
> inside the interface. […] 512/2/7/3/10⁻³ and 1024/3/8/3/10⁻⁴ runs converge to graphical
> accuracy. The interface is shown at geometrically increasing times t = 0, 0.01, 0.02, …, 2.56.

`slc run --problem spiral-nonlocal` with the paper's N/S/K/P/ε: a tilted square spiral (a strip
of half-width 0.1, arms 0.5, 0.5, 1, 1, …) in [−5, 5]², to t = 2.56 (the paper gives no size or
domain). The area drift is (A(t) − A(0))/A(0), largest over the run and at the end, without and
with `--area-correction` (shifts along the normals by the area lost over the length after each
step). The distance between the two runs is taken at the paper's drawn times.
""")
        box = [-5.0, -5.0, 5.0, 5.0]
        runs = {"spiral512": ["-N", "512", "-S", "2", "-K", "7", "-P", "3", "--eps", "1e-3"],
                "spiral1024": ["-N", "1024", "-S", "3", "-K", "8", "-P", "3", "--eps", "1e-4"]}
        self.write("\n| run | status | area drift, largest | at t = 2.56 | with the correction: largest"
                   " | at t = 2.56 | curves | seconds |\n|---|---|---|---|---|---|---|---|\n")
        s_of = {}
        for name, args in runs.items():
            s = s_of[name] = self.run(name, ["--problem", "spiral-nonlocal", *args, "--frames",
                                             "256"])
            c = self.run(name + "c", ["--problem", "spiral-nonlocal", *args, "--area-correction"])
            worst, last = area_drift(self.out(name))
            cworst, clast = area_drift(self.out(name + "c"))
            lo, hi = components_range(self.out(name))
            self.write(f"| {'/'.join(args[1::2])} | {s['status']} | {fmt(worst)} | {fmt(last)} | "
                       f"{fmt(cworst)} | {fmt(clast)} | {lo}–{hi} | {fmt(s['wall_s'], 3)} |\n"
                       .replace("| 1–1 |", "| 1 |"))
        self.write("\n| t | " + " | ".join(f"{0.01 * j:g}" for j in (1, 2, 4, 8, 16, 32, 64, 128, 256))
                   + " |\n|---|" + "---|" * 9 + "\n| distance between the runs | " + " | ".join(
                       fmt(self.distance("spiral512", "spiral1024", box, j=j))
                       for j in (1, 2, 4, 8, 16, 32, 64, 128, 256)) + " |\n\n")
        drawn = [0.0] + [0.01 * 2 ** j for j in range(9)]
        self.write("The paper's times, both runs in each panel (a run that ended early shows its "
                   "last frame):\n\n"
                   + self.panels([("512 steps", "spiral512"), ("1024 steps", "spiral1024")],
                                 drawn, 5, "figure18_spiral.png",
                                 view=[-1.7, -1.7, 2.2, 2.2]) + "\n\n")
        self.write(
            "**Stability and the domain.** The step is explicit, so curvature flow is stable only "
            "while k/h² stays below a bound that S raises (the embedded mesh has h = 2b/M, "
            "M = 2^(K+1), in the domain [−b, b]²). Wiggles show as length in excess of the circle "
            "the spiral ends as, L/(2√(πA)) − 1 where the run ends (t = 2.56 unless the guard "
            "ended it, below):\n\n"
            "| run | b | k/h² | status | ends at t | excess length there | from its circle there "
            "| area drift there |\n"
            "|---|---|---|---|---|---|---|---|\n")
        for name, args in runs.items():
            n, k_depth = int(args[1]), int(args[5])
            for b in (3, 4, 5):
                out = f"{name}_b{b}"
                if b == 5:
                    out = name
                    summary = s_of[name]
                else:
                    summary = self.run(out, ["--problem", "spiral-nonlocal", *args, "--domain",
                                             str(b)])
                h = 2.0 * b / 2 ** (k_depth + 1)
                rows = history(self.out(out))
                a, length = rows[-1]["area"], rows[-1]["length"]
                excess = length / (2.0 * math.sqrt(math.pi * a)) - 1.0
                self.write(f"| {'/'.join(args[1::2])} | {b} | {2.56 / n / h ** 2:.3g} | "
                           f"{summary['status']} | {fmt(rows[-1]['t'], 4)} | {fmt(excess)} | "
                           f"{fmt(from_its_circle(self.out(out)))} | "
                           f"{fmt(area_drift(self.out(out))[1])} |\n")
        self.write(
            "\nIn [−3, 3]² the 1024-step run is not stable; the 512-step run reaches t = 2.56 but "
            "ends four times farther from its circle than in [−5, 5]². In [−5, 5]² both run "
            "stably with the widest margin (k/h² at most 6.6), which is why the problem takes it "
            "(in [−4, 4]² they end nearer their circle, at k/h² up to 10.2). A 1–2 in the first table's curves is "
            "a speck torn off for a step where a corner is thinner than the cells (summary.json's "
            "note names the place). The embedded module's curvature, interpolated to the "
            "vertices, varies from vertex to vertex at a scale its mesh does not resolve (the "
            "polygon's distance field is kinked at every vertex); used as it is, that roughened "
            "the curve below the mesh, where the curvature cannot see the roughness to damp it, "
            "the length grew, which Eq. 13 forbids, and the guard ended the 512-step run at "
            "t = 2.545 (docs/errors.md). The module now averages its vertex curvature along "
            "the curve over one mesh spacing, and both runs reach t = 2.56. They then ended "
            "in a four-fold shape in step with the mesh (2.7e−3 from its circle at 512 "
            "steps): F, the distance to the polygon, is kinked inside it along each vertex's "
            "bisector, and the plain ENO rule steps round those small kinks or not as they "
            "fall between the mesh points, so where the contour runs along the tree's lines, "
            "with few vertices far apart, the module saw the circle flatter than it is and "
            "the flow pushed it out there. The problem's ENO differences of F are biased "
            "(a side keeps the stencil unless the other side's difference is less than half "
            "of its own; the mean of a rule leaning left and one leaning right), which takes "
            "that error out (the distances from a circle in the table above; "
            "docs/algorithms/geometry.md; lab notes in docs/notes/area-preserving.md).\n\n"
            "Without the correction the area stays within the first table's figures: the law's "
            "mean, the Lagrange multiplier of the area, is fixed each step on the curve the step "
            "produces, by secant steps until the step keeps the area (docs/algorithms/evolve.md; "
            "moved once a step it let the area jump by 1e−4 to 4e−4 where the corners round "
            "off). Taken over the curve the step starts from, as "
            "Eq. 13 reads, it let the area drift by 1.7% (512 steps) and 0.68% (1024), nearly "
            "all of it by t = 0.16, while the spiral's corners and arms of width 0.2 are far "
            "from resolved by steps of k = 0.005 (the arms' own time scale is 0.1² = 0.01). The "
            "correction keeps the area to rounding.\n\n")

    # Fig. 19 -----------------------------------------------------------------------------
    def bubbles(self):
        self.write("""## Fig. 19: bubbles merging under area-preserving curvature flow (Eq. 13)

> Fig. 19 shows complex dynamic merging of initially circular bubbles under (13), with parameters
> 2048/3/7/4/10⁻⁴.

`slc run --problem bubbles-nonlocal`: twelve circles of radii 0.25–0.75 placed in [−2.7, 2.7]² by
a fixed pseudo-random sequence, in [−5, 5]² (k/h² = 3.3; in [−3, 3]², 9.1, the merged bubble
wiggles), to t = 10.24 (the paper gives neither its bubbles nor its domain or time).

| run | status | area drift, largest | at the end | with the correction: largest | at the end | curves at the end | seconds |
|---|---|---|---|---|---|---|---|
""")
        args = ["-N", "2048", "-S", "3", "-K", "7", "-P", "4", "--eps", "1e-4"]
        s = self.run("bubbles", ["--problem", "bubbles-nonlocal", *args, "--frames", "1024"])
        self.run("bubblesc", ["--problem", "bubbles-nonlocal", *args, "--area-correction"])
        worst, last = area_drift(self.out("bubbles"))
        cworst, clast = area_drift(self.out("bubblesc"))
        self.write(f"| 2048/3/7/4/1e−4 | {s['status']} | {fmt(worst)} | {fmt(last)} | "
                   f"{fmt(cworst)} | {fmt(clast)} | {s['components']} | {fmt(s['wall_s'], 3)} |\n\n")
        drawn = [0.0] + [0.01 * 2 ** j for j in range(11)]
        changes, prev = [], None
        for row in history(self.out("bubbles")):
            if row["components"] != prev:
                changes.append(row["components"])
                prev = row["components"]
        self.write("At geometrically growing times: the bubbles that touch merge within the first "
                   "tenths, the small ones shrink and vanish, the rest round off into one (a panel "
                   "after the run's end shows its last frame). The number of curves, each time it "
                   f"changed: {', '.join(str(int(c)) for c in changes)}; where two bubbles first "
                   "touch, the neck can leave a speck for a step or two.\n\n"
                   + self.panels([("2048 steps", "bubbles")], drawn, 4, "figure19_bubbles.png",
                                 view=[-3.2, -3.2, 3.2, 3.2]) + "\n\n")
        rows = history(self.out("bubbles"))
        a, length = rows[-1]["area"], rows[-1]["length"]
        self.write(
            "Without the correction the area stays within the table's figures through the "
            "merges (with the mean over the curve each step starts from, 1.2% was lost). "
            + (f"The guard ended the run at t = {fmt(s['t'], 4)}: {s['message']}. "
               if s["status"] != "ok" else "")
            + f"At t = {fmt(rows[-1]['t'], 4)} the merged bubble is "
            f"{fmt(length / (2.0 * math.sqrt(math.pi * a)) - 1.0)} longer than the circle of "
            f"its area and lies within {fmt(from_its_circle(self.out('bubbles')))} of it (1.9e−3 "
            "with the plain ENO rule for ∇F, see Fig. 18; with the embedded curvature used as "
            "interpolated, the vertex-scale roughness of the spiral's section grew the length "
            "until the guard ended the run at t = 7.735). With the mean moved once a step, the "
            "merges, where a neck or gap thinner than a cell is filled or cut in a step, moved "
            "the area by 1e−4 to 3e−4 (with the domain widened or narrowed by 1–2%); moved by "
            "secant steps until the step keeps the area (docs/algorithms/evolve.md), by the "
            "table's. With the correction every step keeps the area to rounding.\n\n")


HEADER = """# The paper's figures at its own parameters

Written by `bench/figures.py` (`scripts/figures paper`); do not edit by hand. Each section quotes
the paper, says what it leaves open and what slc chose, and gives what was measured here. The
problems' own pictures are in [problems.md](problems.md); the tables in [tables/](tables/).

## Where each figure and table is

"drawn": as the paper draws it; "partly": some of its panels or runs; "differs": drawn, and the
result is not the paper's (the section below says how).

| paper | what it shows | here | status |
|---|---|---|---|
| Fig. 1 | complexity, facetting, merging, time scales | the problems below and in [problems.md](problems.md) | an illustration |
| Fig. 2 | a distance tree and its triangulation | [algorithms/distance.md](algorithms/distance.md) (`slc tree`) | drawn |
| Fig. 3 | V_x and its nearest-point extension W_x, K = 5 and 6 | [algorithms/distance.md](algorithms/distance.md) (`slc tree`, panels.png) | drawn: the tree, V_x on Γ and W_x at depths 5 and 6 |
| Fig. 4 | an island forming at a cusp as circles merge | below | drawn, with `merging-circles` (the paper's circles are not given) |
| Fig. 5 | linear contouring and bisection | [algorithms/contour.md](algorithms/contour.md) (`examples/implicit_contour`) | drawn, on a Cassini oval: the interpolant's zero set and its vertices moved along their edges to roots |
| Fig. 6 | a propeller contoured on K-level trees | [algorithms/contour.md](algorithms/contour.md) | drawn |
| Fig. 7 | adaptive refinement of a zero set | [algorithms/contour.md](algorithms/contour.md) | drawn |
| Fig. 8 | refinement's safeguards | [algorithms/contour.md](algorithms/contour.md) (`examples/refinement_safeguards`) | drawn, on two zero sets the linear contour gets wrong: a bridge between two ovals kept as one simple curve, and a thin ellipse's tips held by the triangle safeguard (cut by 0.41, against 1.6e−5 without it) |
| Fig. 9 | the local embedded mesh, x- and y-intervals | [algorithms/geometry.md](algorithms/geometry.md) | drawn |
| Fig. 10 | errors against CPU time | [tables/](tables/) `*_error_vs_time.png` | drawn |
| Fig. 11 | semi-Lagrangian evaluation | [algorithms/evolve.md](algorithms/evolve.md) (`examples/semi_lagrangian`) | drawn, from a step written out by hand that gives `slc::advance`'s curve to the bit |
| Fig. 12 | a propeller turned twice, four runs | below | drawn |
| Fig. 13 | triangles growing and shrinking | below | drawn: the paper's extension keeps the shrinking corners sharp at every step (the section's largest corner cut) |
| Fig. 14 | circles merging, four runs | below | drawn |
| Fig. 15 | Wulff shapes, tilts superimposed | below | drawn; m = 3 jagged on its non-convex side |
| Fig. 16 | circles under curvature flow, four runs | below | drawn |
| Fig. 17 | a polygon under curvature flow, runs a–d | below | drawn, run a with the embedded mesh M = 128: at the paper's M = 2^(K+1) = 64 it keeps zigzags of 0.05 at t = 1.6–3.3, narrower than the mesh |
| Fig. 18 | a spiral under Eq. 13 | below | drawn; both runs reach t = 2.56, their final curves 2.6e−4 and 7.5e−4 from a circle, the area within 6.7e−6 |
| Fig. 19 | bubbles merging under Eq. 13 | below | drawn; reaches t = 10.24, the final bubble 4.0e−4 from a circle, the area within 6.9e−6 |
| Table 1 | distance tree cost | [tables/table1.md](tables/table1.md) | reproduced (cells 10–20% fewer) |
| Tables 2, 3 | linear and adaptive contouring | [table2.md](tables/table2.md), [table3.md](tables/table3.md) | reproduced |
| Table 5 | a propeller turned twice | [tables/table5.md](tables/table5.md) | 16 of 25 errors at or below the paper's; the 9 above (coarse rows, P ≥ 1) are mostly the step lagging the turn (5.8° at 80/0/4/4; +2.7°, the trapezoidal rule's own lead, with the exact field at the corrector's first foot x − kW(x), whose W Eq. 5 reads at x from the nearest point of Γ(t)) |
| Table 6 | circles merging | [tables/table6.md](tables/table6.md) | 24 of 25 at or below, by Eq. 11's exact distance |
| Table 7 | a circle under curvature flow | [tables/table7.md](tables/table7.md) | 25 of 25 at or below |

"""


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--slc", required=True)
    parser.add_argument("--out", required=True, help="the Markdown file to write")
    parser.add_argument("--figures", required=True, help="folder of the pictures")
    parser.add_argument("--only", nargs="*",
                        default=["island", "side_by_side", "triangles", "wulff", "polygon",
                                 "spiral", "bubbles"])
    args = parser.parse_args()
    os.makedirs(args.figures, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        figures = Figures(os.path.abspath(args.slc), work, args.figures)
        for part in args.only:
            print(f"figures: {part}", file=sys.stderr)
            getattr(figures, part)()
        with open(args.out, "w") as f:
            f.write(HEADER + "".join(figures.md))


if __name__ == "__main__":
    main()
