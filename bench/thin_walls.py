#!/usr/bin/env python3
"""A closed surface with a wall thinner than the cells, turned a full turn at the default settings
(`slc run --initial box.obj --velocity rotation --t-end 2π`, two threads): a unit cube with a
cavity 0.87 × 0.8 × 0.8 whose one wall is 0.03 thick, against the exact law (a rigid motion keeps
the shape); and the same box grown and shrunk at unit speed by 0.01 (the wall 0.05 and 0.01
thick), against the exact offsets. Writes the tables into the region `thin-walls` of
docs/performance.md.

Columns: the status, components and genus at the end; the volume change relative to the start's
contour; the Hausdorff distance between the given surface and the returned one (each side's
vertices and 20,000 points on its triangles, measured by `slc distance` to the other); the
deepest thin cells a step took and how many steps took deeper ones than the run's own; the time
loop's wall and CPU seconds from summary.json. Goal (issue: thin parts at the defaults): ok,
volume within 0.5%, Hausdorff within 1% of the size, under 300 s wall on this machine. For the
offsets: the components and genus, the volume against the exact offset's, and the largest
| |d(x)| − t | over the returned vertices, d the exact distance to the given box (`slc
distance`): each vertex's distance to the exact offset, at least, within 1% of the size. Last,
mean curvature flow to t = 0.001 at the defaults and at twice their resolution (-K 6): the same
components, and final volumes within 0.5% of each other."""
import math
import argparse
import json
import random
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from campaign3d import read_obj, write_obj  # noqa: E402
from thin_cost import write_region  # noqa: E402


def box(lo, hi, n, inward, v, f):
    """The six faces of the box [lo, hi], each an n × n grid of squares cut in two, outward
    facing (inward: the cavity's, facing into it), appended to v and f."""
    index = {}

    def vertex(p):
        key = tuple(round(c, 12) for c in p)
        if key not in index:
            index[key] = len(v)
            v.append(key)
        return index[key]

    for axis in range(3):
        u, w = (axis + 1) % 3, (axis + 2) % 3
        for side in (0, 1):
            def at(i, j):
                p = [0.0, 0.0, 0.0]
                p[axis] = hi[axis] if side else lo[axis]
                p[u] = lo[u] + (hi[u] - lo[u]) * i / n
                p[w] = lo[w] + (hi[w] - lo[w]) * j / n
                return vertex(p)
            for i in range(n):
                for j in range(n):
                    q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]
                    if (side == 0) != inward:
                        q.reverse()
                    f.append((q[0], q[1], q[2]))
                    f.append((q[0], q[2], q[3]))


def samples(v, f, n, rng):
    """The vertices and n points spread over the triangles at random (fixed seed)."""
    out = list(v)
    for _ in range(n):
        a, b, c = (v[i] for i in rng.choice(f))
        r, s = rng.random(), rng.random()
        if r + s > 1.0:
            r, s = 1.0 - r, 1.0 - s
        out.append(tuple(a[k] + r * (b[k] - a[k]) + s * (c[k] - a[k]) for k in range(3)))
    return out


def distances(slc, surface, points, folder):
    """The signed distances from the points to the surface, by `slc distance`."""
    csv = folder / "points.csv"
    csv.write_text("\n".join(f"{x!r},{y!r},{z!r}" for x, y, z in points) + "\n")
    out = subprocess.run([slc, "distance", "--initial", str(surface), "--points", str(csv)],
                         check=True, capture_output=True, text=True).stdout
    rows = out.splitlines()[1:]  # after the header
    return [float(line.split(",")[3]) for line in rows if line.strip()]


def farthest(slc, surface, points, folder):
    """The largest |distance| from the points to the surface."""
    return max(abs(d) for d in distances(slc, surface, points, folder))


def offset_volume(t):
    """The exact volume of the box offset by t (t > 0 grows it): the outer cube grows with
    rounded edges and corners and the cavity shrinks with sharp ones; shrunk, the other way
    round."""
    cavity = (0.87, 0.8, 0.8)
    def rounded(sides, r):  # a box grown by r, its edges and corners rounded
        a, b, c = sides
        return (a * b * c + 2 * r * (a * b + b * c + c * a) + math.pi * r * r * (a + b + c)
                + 4 / 3 * math.pi * r ** 3)
    if t >= 0:
        return rounded((1, 1, 1), t) - math.prod(s - 2 * t for s in cavity)
    return (1 + 2 * t) ** 3 - rounded(cavity, -t)


def offset_error(slc, given, final, t, folder):
    """The largest |d(x) − t| over the vertices x of `final`, d the given box's distance."""
    v, _ = read_obj(final)
    return max(abs(d - t) for d in distances(slc, given, v, folder))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--slc", default="build/bin/slc")
    parser.add_argument("--out", default="docs/performance.md")
    a = parser.parse_args()
    lines = ["| shape, full turn at the defaults | status | components, genus | volume change | "
             "Hausdorff / size | deepest thin cells | steps deeper | wall s, 2 threads | CPU s |",
             "|---|---|---|---:|---:|---:|---:|---:|---:|"]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        v, f = [], []
        box([-0.5] * 3, [0.5] * 3, 10, False, v, f)
        box([-0.47, -0.4, -0.4], [0.4, 0.4, 0.4], 10, True, v, f)
        given = folder / "wallbox.obj"
        write_obj(given, v, f)
        out = folder / "turn"
        subprocess.run([a.slc, "run", "--initial", str(given), "--velocity", "rotation",
                        "--t-end", "6.283185307179586", "--threads", "2", "--out", str(out),
                        "--quiet"], check=True)
        s = json.loads((out / "summary.json").read_text())
        rng = random.Random(1)
        back_v, back_f = read_obj(out / "final.obj")
        hausdorff = max(farthest(a.slc, out / "final.obj", samples(v, f, 20000, rng), folder),
                        farthest(a.slc, given, samples(back_v, back_f, 20000, rng), folder))
        deeper = s.get("thin_deeper", {})
        change = s["volume"] / s["volume_initial"] - 1.0
        lines.append(
            f"| a unit box, one wall 0.03 thick | {s['status']} | {s['components']}, {s['genus']} | "
            f"{100 * change:+.2g}% | {hausdorff:.2g} | {deeper.get('depth', s['params']['thin_depth'])} | "
            f"{deeper.get('steps', 0)} of {s['steps']} | {s['wall_s']:.0f} | {s['cpu_s']:.0f} |")
        print(lines[-1], flush=True)
        lines += ["", "| the same box at unit speed to t = 0.01 | status | components, genus | "
                  "volume against the exact | farthest vertex from the exact offset | "
                  "wall s, 2 threads |", "|---|---|---|---:|---:|---:|"]
        for name, speed in (("grown (the wall 0.05 thick)", 1), ("shrunk (the wall 0.01 thick)", -1)):
            out = folder / f"speed{speed}"
            subprocess.run([a.slc, "run", "--initial", str(given), "--velocity", "unit-normal",
                            "--param", f"speed={speed}", "--t-end", "0.01", "--threads", "2",
                            "--out", str(out), "--quiet"], check=True)
            s = json.loads((out / "summary.json").read_text())
            exact = offset_volume(0.01 * speed)
            error = offset_error(a.slc, given, out / "final.obj", 0.01 * speed, folder)
            lines.append(f"| {name} | {s['status']} | {s['components']}, {s['genus']} | "
                         f"{100 * (s['volume'] / exact - 1):+.2g}% | {error:.2g} | {s['wall_s']:.0f} |")
            print(lines[-1], flush=True)
        # Mean curvature flow, at the defaults and at twice their resolution.
        lines += ["", "| the same box under mean curvature flow to t = 0.001 | status | "
                  "components, genus | volume change | deepest thin cells | wall s, 2 threads | "
                  "CPU s |", "|---|---|---|---:|---:|---:|---:|"]
        volumes = []
        for name, extra in (("at the defaults (K 5)", []), ("twice the resolution (-K 6)", ["-K", "6"])):
            out = folder / f"curvature{len(volumes)}"
            subprocess.run([a.slc, "run", "--initial", str(given), "--velocity", "curvature",
                            "--t-end", "0.001", *extra, "--threads", "2", "--out", str(out),
                            "--quiet"], check=True)
            s = json.loads((out / "summary.json").read_text())
            volumes.append(s["volume"])
            deeper = s.get("thin_deeper", {})
            lines.append(f"| {name} | {s['status']} | {s['components']}, {s['genus']} | "
                         f"{100 * (s['volume'] / s['volume_initial'] - 1):+.3g}% | "
                         f"{deeper.get('depth', s['params']['thin_depth'])} | {s['wall_s']:.0f} | "
                         f"{s['cpu_s']:.0f} |")
            print(lines[-1], flush=True)
        lines += ["", f"The final volumes at the defaults and at twice their resolution differ by "
                  f"{100 * abs(volumes[0] / volumes[1] - 1):.2g}% (goal: within 0.5%)."]
    write_region(a.out, "thin-walls", lines)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
