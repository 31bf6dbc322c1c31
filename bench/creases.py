#!/usr/bin/env python3
"""Polyhedra contoured to eps by following their creases (`slc contour --initial poly.obj -K 5
--eps E`): a box, a regular tetrahedron, an octahedron, an L-shaped prism, a wedge of 10° and
pyramids of 5, 6, 8 and 12 faces, each turned 0.3 rad about z and 0.2 about x (off the octree's
axes), at eps 1e-3 and 1e-5; then pyramids of 5 to 16 faces turned at random (three turns each)
at K 3 and 4, eps 1e-3 and 1e-5, counted. Writes the tables into the region `creases` of
docs/surfaces.md.

Columns: the largest |G| at the contour's vertices, edge midpoints and centroids (summary.json's
`error`, G the exact distance to the polyhedron), the triangles, and the volume against the
exact polyhedron's."""
import argparse
import json
import math
import random
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from thin_cost import write_region  # noqa: E402


def turned(p, about_z=0.3, about_x=0.2):
    x, y, z = p
    c, s = math.cos(about_z), math.sin(about_z)
    x, y = c * x - s * y, s * x + c * y
    c, s = math.cos(about_x), math.sin(about_x)
    return x, c * y - s * z, s * y + c * z


def pyramid(n):
    """n faces about an apex 0.8 above a regular n-gon of radius 0.5, and the exact volume."""
    base = [(0.5 * math.cos(2 * math.pi * k / n), 0.5 * math.sin(2 * math.pi * k / n), -0.3)
            for k in range(n)]
    faces = [tuple(range(n - 1, -1, -1))] + [(k, (k + 1) % n, n) for k in range(n)]
    return base + [(0, 0, 0.5)], faces, 0.5 * n * 0.25 * math.sin(2 * math.pi / n) * 0.8 / 3


def shapes():
    a, t, o = 0.4, 0.5, 0.6
    h = 0.8 * math.tan(math.radians(5))
    yield "box 0.8", [(-a, -a, -a), (a, -a, -a), (a, a, -a), (-a, a, -a), (-a, -a, a),
                      (a, -a, a), (a, a, a), (-a, a, a)], \
        [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)], \
        (2 * a) ** 3
    yield "regular tetrahedron", [(t, t, t), (t, -t, -t), (-t, t, -t), (-t, -t, t)], \
        [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)], 8 * t ** 3 / 3
    yield "octahedron (four faces at a corner)", \
        [(o, 0, 0), (-o, 0, 0), (0, o, 0), (0, -o, 0), (0, 0, o), (0, 0, -o)], \
        [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)], \
        4 * o ** 3 / 3
    yield "L-shaped prism (a concave edge)", \
        [(-a, -a, -0.3), (a, -a, -0.3), (a, 0, -0.3), (0, 0, -0.3), (0, a, -0.3), (-a, a, -0.3),
         (-a, -a, 0.3), (a, -a, 0.3), (a, 0, 0.3), (0, 0, 0.3), (0, a, 0.3), (-a, a, 0.3)], \
        [(0, 3, 2, 1), (0, 5, 4, 3), (6, 7, 8, 9), (6, 9, 10, 11), (0, 1, 7, 6), (1, 2, 8, 7),
         (2, 3, 9, 8), (3, 4, 10, 9), (4, 5, 11, 10), (5, 0, 6, 11)], 0.6 * 3 * a * a
    yield "wedge of 10°", [(-0.4, 0, -0.3), (0.4, -h, -0.3), (0.4, h, -0.3), (-0.4, 0, 0.3),
                           (0.4, -h, 0.3), (0.4, h, 0.3)], \
        [(0, 2, 1), (3, 4, 5), (0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)], 0.5 * 0.8 * 2 * h * 0.6
    for n in (5, 6, 8, 12):
        yield (f"pyramid of {n} faces", *pyramid(n))


def sci(x):
    """x to two digits, with the docs' minus sign in the exponent: 9.8e−8."""
    mantissa, exponent = f"{x:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}".replace("-", "−")


def write_obj(path, corners, faces, turn):
    with open(path, "w") as f:
        for p in corners:
            f.write("v %.17g %.17g %.17g\n" % turn(p))
        for face in faces:
            for k in range(1, len(face) - 1):
                f.write(f"f {face[0] + 1} {face[k] + 1} {face[k + 1] + 1}\n")


def contour(slc, obj, depth, eps, out):
    r = subprocess.run([slc, "contour", "--initial", str(obj), "-K", str(depth), "--eps",
                        str(eps), "--out", str(out)], capture_output=True, text=True)
    if r.returncode not in (0, 3):
        sys.exit(f"{obj} K {depth} eps {eps}: exit {r.returncode}: {r.stderr}")
    return json.loads((out / "summary.json").read_text())


def random_turn(seed):
    rng = random.Random(seed)
    angles = [rng.uniform(0, 2 * math.pi) for _ in range(3)]

    def turn(p):
        x, y, z = p
        for angle, axis in zip(angles, "zxz"):
            c, s = math.cos(angle), math.sin(angle)
            if axis == "z":
                x, y = c * x - s * y, s * x + c * y
            else:
                y, z = c * y - s * z, s * y + c * z
        return x, y, z
    return turn


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--slc", default="build/bin/slc")
    parser.add_argument("--out", default="docs/surfaces.md")
    a = parser.parse_args()
    lines = ["| surface | ε 1e−3: error, triangles | ε 1e−5: error, triangles | "
             "volume at ε 1e−5 (exact) |", "|---|---|---|---|"]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for name, corners, faces, exact in shapes():
            obj = folder / "shape.obj"
            write_obj(obj, corners, faces, turned)
            cells = []
            for eps in (1e-3, 1e-5):
                s = contour(a.slc, obj, 5, eps, folder / "out")
                mark = "" if s["converged"] else " (stopped)"
                cells.append(f"{sci(s['error'])}{mark}, {s['triangles']:,}")
            print(f"{name}: {cells}, volume {s['volume']:.9f} ({exact:.9f})", flush=True)
            lines.append(f"| {name} | {cells[0]} | {cells[1]} | {s['volume']:.9f} "
                         f"({exact:.9f}) |")
        lines += ["", "| pyramid, turned at random | K 3, ε 1e−3 | K 3, ε 1e−5 | K 4, ε 1e−3 | "
                  "K 4, ε 1e−5 |", "|---|---|---|---|---|"]
        stopped = []
        for n in (5, 6, 7, 8, 10, 12, 16):
            corners, faces, exact = pyramid(n)
            row = []
            for depth in (3, 4):
                for eps in (1e-3, 1e-5):
                    met = 0
                    for seed in (1, 2, 3):
                        obj = folder / "pyramid.obj"
                        write_obj(obj, corners, faces, random_turn(seed))
                        s = contour(a.slc, obj, depth, eps, folder / "out")
                        if s["converged"] and abs(s["volume"] - exact) <= 10 * eps * eps + \
                                1e-6 * exact:
                            met += 1
                        else:
                            stopped.append(f"{n} faces, turn {seed}, K {depth}, ε {sci(eps)}: "
                                           f"{sci(s['error'])}, genus {s['genus']}")
                    row.append(f"{met} of 3")
            print(f"pyramid {n}: {row}", flush=True)
            lines.append(f"| {n} faces | " + " | ".join(row) + " |")
        lines += ["", "Stopped short of ε (exit 3): " + ("; ".join(stopped) or "none") + "."]
    write_region(a.out, "creases", lines)


if __name__ == "__main__":
    main()
