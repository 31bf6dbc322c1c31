#!/usr/bin/env python3
"""A seeded randomized campaign of `slc run` on surfaces: spheres (icospheres and UV spheres),
ellipsoids, tori and pairs of separate spheres, of 290 to 1280 triangles (a pair 640 or 1600),
sizes log-uniform in 1e-3..1e3, centres up to 10 sizes from the origin (inside the unit cube for
Enright's field, sizes 1e-3 to 0.2), under each built-in law of surfaces in turn, every other run
at the default settings (only --initial, --velocity, --t-end and the law's --param, scaled with
the surface) and the others coarse (-K 3 or 4, -N 5 to 10).

Every run must exit 0 with a result its law allows (status ok or vanished), 2 (refused) or 3
(failed or unstable, one line). Counted as defects, each listed with its command (the surface
files are written with --keep DIR, and --only I runs case I alone):

  impossible  exit 0 with what the law cannot do: a documented budget broken (below), or an
              exact invariant (the components and the genus, vanishing, growth);
  inaccurate  exit 0 within the budgets, but a vertex off the exact surface by more than 0.05 l
              (l the input's half-width; no budget is documented for a shape: the campaign's,
              as for curves), the table's "off the exact shape";
  crash       any other exit status, a timeout, "internal error" or "please report", or more
              than one line of error.

The exact laws and what a run may miss them by (docs/errors.md, "What the guards catch", and
docs/surfaces.md; V0 and A0 the volume and area of the run's start, eps the run's):

  every law               a user's surface is read as curved patches through its vertex normals,
                          so the run's start holds a volume between the input triangles' and the
                          smooth shape's they sample, up to eps A0;
  rotation, translation   the surface moved rigidly: the volume within 1% of V0
                          (SurfaceRunOptions::volume_drift, the documented budget of a run); the
                          components (at every step of history.csv) and the genus kept; every
                          final vertex within 0.05 l of the moved smooth shape;
  enright                 a smooth divergence-free flow: the volume as above, the components (at
                          every step) and the genus kept: no tear, no hole;
  unit-normal (speed s)   every final vertex at signed distance s t from the smooth start (its
                          exact offset) within 0.05 l; a growing region's volume does not fall by
                          1%; a sphere's or an ellipsoid's growth by d = s t is Steiner's
                          A0 d + M d^2 + 4/3 pi d^3 (M the triangles' integral of mean curvature)
                          within 10% (the guards' budget of a step) plus eps A; two spheres stay
                          two unless their offsets can meet; vanished only once the start eroded
                          by |s| t is empty;
  anisotropic             its speed lies in [R - 4/15 e, R + 2/5 e] (e > 0), so every final
                          vertex lies between the offsets by those speeds times t, within 0.05 l
                          (comparison principle); a growing region's volume does not fall;
  curvature               a sphere: R(t)^2 = R0^2 - 4t (R0 that of V0), vertices within 0.05 l
                          of that sphere and the volume within 2% of V0 plus a quarter of the
                          law's change (no budget is documented for surfaces: the campaign's);
                          two spheres the same each, the smaller vanishing at its R0^2/4;
                          ellipsoids and tori by comparison: the surface keeps out of the shrunk
                          spheres inscribed in the start (radius (r^2 - 4t)^1/2) and inside the
                          shrunk sphere about it (within 0.05 l), vanishes no earlier than its
                          inscribed spheres (a step's slack), and a convex start never splits;
                          the area not above the start's by 0.5% (SurfaceRunOptions::area_growth);
  volume-preserving-      the volume as under a rigid motion, the area not above the start's by
  curvature               0.5%; a sphere stays itself (within 0.05 l); it cannot vanish.

  campaign3d.py --slc build/bin/slc --size small --check                 (the tests: 4 coarse runs)
  campaign3d.py --slc build/bin/slc --size large --doc docs/errors.md    (scripts/bench: 60)
"""
import argparse
import json
import math
import os
import random
import shutil
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree for the import below
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from campaign import Tally, log_uniform, read_history, report, run_outcome  # noqa: E402

SIZES = {"small": (4, 5), "large": (60, 6)}  # runs, seed
TIMEOUT_S = float(os.environ.get("SLC_CAMPAIGN_TIMEOUT", "600"))
LAWS_3D = ["rotation", "translation", "enright", "unit-normal", "anisotropic", "curvature",
           "volume-preserving-curvature"]
SHAPE_GROSS = 0.05  # of the half-width
VOLUME_DRIFT = 0.01  # SurfaceRunOptions::volume_drift
KEEPS_VOLUME = ("rotation", "translation", "enright", "volume-preserving-curvature")
AREA_GROWTH = 0.005  # SurfaceRunOptions::area_growth
CURVATURE_VOLUME = 0.02  # the campaign's own: of V0, beside a quarter of the law's change
STEINER_STEP = 0.1  # a constant normal speed's swept volume, a step
CUBIC_RANGE = (-4.0 / 15.0, 0.4)  # n_x^4 + n_y^4 + n_z^4 - 3/5 over the unit sphere


# ---------------------------------------------------------------------------------------------
# Vectors, rotations and triangle meshes.

def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def unit_vector(rng):
    z, a = rng.uniform(-1, 1), rng.uniform(0, 2 * math.pi)
    s = math.sqrt(1 - z * z)
    return (s * math.cos(a), s * math.sin(a), z)


def random_rotation(rng):
    """A uniformly random rotation matrix (rows), from a random unit quaternion."""
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(x * x for x in q))
    w, x, y, z = (v / n for v in q)
    return ((1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)),
            (2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)),
            (2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)))


def apply(m, v):
    return (dot(m[0], v), dot(m[1], v), dot(m[2], v))


def apply_t(m, v):  # the transpose: the inverse of a rotation
    return tuple(m[0][i] * v[0] + m[1][i] * v[1] + m[2][i] * v[2] for i in range(3))


def rotate_about(axis, angle, v):
    """v turned by angle about the unit axis (Rodrigues)."""
    c, s = math.cos(angle), math.sin(angle)
    k = cross(axis, v)
    d = dot(axis, v) * (1 - c)
    return tuple(v[i] * c + k[i] * s + axis[i] * d for i in range(3))


def icosphere(level):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / norm(p) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
         (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        middle, finer = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p = tuple((v[a][i] + v[b][i]) / 2 for i in range(3))
                v.append(tuple(c / norm(p) for c in p))
                middle[key] = len(v) - 1
            return middle[key]

        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = finer
    return v, f


def uv_sphere(rows, columns):
    """The unit sphere: rows - 1 rings of columns vertices between the poles."""
    v = [(0.0, 0.0, 1.0)]
    for i in range(1, rows):
        th = math.pi * i / rows
        v += [(math.sin(th) * math.cos(2 * math.pi * j / columns),
               math.sin(th) * math.sin(2 * math.pi * j / columns), math.cos(th)) for j in range(columns)]
    v.append((0.0, 0.0, -1.0))
    f = []
    ring = lambda i, j: 1 + (i - 1) * columns + j % columns  # noqa: E731
    for j in range(columns):
        f.append((0, ring(1, j), ring(1, j + 1)))
        for i in range(1, rows - 1):
            f += [(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)),
                  (ring(i, j), ring(i + 1, j + 1), ring(i, j + 1))]
        f.append((len(v) - 1, ring(rows - 1, j + 1), ring(rows - 1, j)))
    return v, f


def torus_mesh(big, small, around, tube):
    v = []
    for i in range(around):
        a = 2 * math.pi * i / around
        for j in range(tube):
            b = 2 * math.pi * j / tube
            v.append(((big + small * math.cos(b)) * math.cos(a),
                      (big + small * math.cos(b)) * math.sin(a), small * math.sin(b)))
    f = []
    for i in range(around):
        for j in range(tube):
            p, q = i * tube + j, (i + 1) % around * tube + j
            p2, q2 = i * tube + (j + 1) % tube, (i + 1) % around * tube + (j + 1) % tube
            f += [(p, q, q2), (p, q2, p2)]
    return v, f


def volume_area(v, f):
    vol = area = 0.0
    for a, b, c in f:
        vol += dot(v[a], cross(v[b], v[c])) / 6
        area += norm(cross(sub(v[b], v[a]), sub(v[c], v[a]))) / 2
    return vol, area


def outward(v, f):
    return f if volume_area(v, f)[0] > 0 else [(a, c, b) for a, b, c in f]


def steiner(v, f, d):
    """The volume of the outer offset by d of a convex polyhedron: V + A d + M d^2 + 4/3 pi d^3,
    M half the sum over the edges of length times exterior dihedral angle."""
    vol, area = volume_area(v, f)
    normals = [cross(sub(v[b], v[a]), sub(v[c], v[a])) for a, b, c in f]
    edges = {}
    for n, (a, b, c) in enumerate(f):
        for p, q in ((a, b), (b, c), (c, a)):
            edges.setdefault((min(p, q), max(p, q)), []).append(n)
    m = 0.0
    for (p, q), (n1, n2) in edges.items():
        c = dot(normals[n1], normals[n2]) / (norm(normals[n1]) * norm(normals[n2]))
        m += 0.5 * norm(sub(v[p], v[q])) * math.acos(max(-1.0, min(1.0, c)))
    return vol + area * d + m * d * d + 4 * math.pi / 3 * d ** 3


def write_obj(path, v, f):
    with open(path, "w") as out:
        out.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in v)
        out.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f)


def read_obj(path):
    v, f = [], []
    with open(path) as src:
        for line in src:
            w = line.split()
            if w and w[0] == "v":
                v.append(tuple(float(x) for x in w[1:4]))
            elif w and w[0] == "f":
                f.append(tuple(int(x.split("/")[0]) - 1 for x in w[1:4]))
    return v, f


# ---------------------------------------------------------------------------------------------
# The shapes: meshes with their exact signed distances.

def ellipsoid_distance(axes, y):
    """Signed distance from y to the ellipsoid of semi-axes `axes` about the origin (Eberly,
    "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid": bisection on
    the one root of F(t) = sum (e_i y_i / (t + e_i^2))^2 - 1 above -e_min^2)."""
    order = sorted(range(3), key=lambda i: -axes[i])
    e = [axes[i] for i in order]
    z = [max(abs(y[i]), 1e-12 * e[0]) for i in order]
    inside = sum((z[i] / e[i]) ** 2 for i in range(3)) < 1
    g = lambda t: sum((e[i] * z[i] / (t + e[i] ** 2)) ** 2 for i in range(3)) - 1  # noqa: E731
    lo = -e[2] ** 2 + e[2] * z[2]
    hi = -e[2] ** 2 + math.sqrt(sum((e[i] * z[i]) ** 2 for i in range(3)))
    for _ in range(200):
        t = 0.5 * (lo + hi)
        if t in (lo, hi):
            break
        if g(t) > 0:
            lo = t
        else:
            hi = t
    t = 0.5 * (lo + hi)
    x = [e[i] ** 2 * z[i] / (t + e[i] ** 2) for i in range(3)]
    d = math.sqrt(sum((x[i] - z[i]) ** 2 for i in range(3)))
    return -d if inside else d


def make_shape(rng, kind, centre, size):
    """A surface about centre: its mesh, its exact signed distance, and what the checks need."""
    s = {"kind": kind, "centre": centre}
    if kind in ("sphere", "ellipsoid"):
        if rng.random() < 0.5:
            level = rng.choice([2, 3])
            unit, faces = icosphere(level)
            s["mesh"] = f"icosphere of {len(faces)} triangles"
        else:
            rows, columns = rng.randint(10, 20), rng.randint(16, 32)
            unit, faces = uv_sphere(rows, columns)
            s["mesh"] = f"UV sphere of {len(faces)} triangles"
        if kind == "sphere":
            s["radii"], s["centres"] = [size], [centre]
            v = [tuple(centre[i] + size * p[i] for i in range(3)) for p in unit]
            s["distance"] = lambda x: norm(sub(x, centre)) - size
            s["inner"], s["outer"], s["desc"] = size, size, f"sphere R {size:.3g}"
            s["smooth_volume"] = 4 / 3 * math.pi * size ** 3
        else:
            axes = (size, size * rng.uniform(0.5, 1.0), size * rng.uniform(0.4, 1.0))
            q = random_rotation(rng)
            v = [tuple(c + w for c, w in zip(centre, apply(q, tuple(axes[i] * p[i] for i in range(3)))))
                 for p in unit]
            s["distance"] = lambda x: ellipsoid_distance(axes, apply_t(q, sub(x, centre)))
            s["inner"], s["outer"] = min(axes), max(axes)
            s["smooth_volume"] = 4 / 3 * math.pi * axes[0] * axes[1] * axes[2]
            s["desc"] = "ellipsoid " + " x ".join(f"{a:.3g}" for a in axes)
        s["genus"], s["components"], s["convex"] = 0, 1, True
    elif kind == "torus":
        small = size * rng.uniform(0.35, 0.5)
        around, tube = rng.choice([24, 32, 40]), rng.choice([12, 16])
        unit, faces = torus_mesh(size, small, around, tube)
        q = random_rotation(rng)
        v = [tuple(c + w for c, w in zip(centre, apply(q, p))) for p in unit]

        def distance(x):
            y = apply_t(q, sub(x, centre))
            return math.hypot(math.hypot(y[0], y[1]) - size, y[2]) - small

        def from_core(x):
            y = apply_t(q, sub(x, centre))
            return math.hypot(math.hypot(y[0], y[1]) - size, y[2])

        s.update(distance=distance, from_core=from_core, inner=small, outer=size + small,
                 smooth_volume=2 * math.pi ** 2 * size * small ** 2,
                 genus=1, components=1, convex=False, small=small,
                 desc=f"torus {size:.3g}, {small:.3g}", mesh=f"{len(faces)} triangles")
    else:  # two spheres
        r2 = size * rng.uniform(0.5, 1.0)
        gap = size * rng.uniform(0.3, 1.0)
        axis = unit_vector(rng)
        c1 = tuple(centre[i] - axis[i] * (size + gap / 2) for i in range(3))
        c2 = tuple(centre[i] + axis[i] * (r2 + gap / 2) for i in range(3))
        level = rng.choice([2, 2, 3]) if r2 > 0.7 * size else 2
        unit, uf = icosphere(level)
        unit2, uf2 = icosphere(2)
        v = [tuple(c1[i] + size * p[i] for i in range(3)) for p in unit]
        v += [tuple(c2[i] + r2 * p[i] for i in range(3)) for p in unit2]
        faces = uf + [(a + len(unit), b + len(unit), c + len(unit)) for a, b, c in uf2]
        s["radii"], s["centres"] = [size, r2], [c1, c2]
        s["distance"] = lambda x: min(norm(sub(x, c1)) - size, norm(sub(x, c2)) - r2)
        s.update(inner=r2, outer=size, genus=0, components=2, convex=False, gap=gap,
                 smooth_volume=4 / 3 * math.pi * (size ** 3 + r2 ** 3),
                 desc=f"two spheres R {size:.3g}, {r2:.3g}, {gap:.3g} apart",
                 mesh=f"{len(faces)} triangles")
    faces = outward(v, faces)
    s["v"], s["f"] = v, faces
    s["volume"], s["area"] = volume_area(v, faces)
    xs = [[p[i] for p in v] for i in range(3)]
    s["half_width"] = 0.5 * max(max(x) - min(x) for x in xs)
    s["extent"] = max(norm(sub(p, centre)) for p in v)
    return s


def surface_case(rng, index, coarse_only):
    """One run: the surface, the law and its parameters, and the settings."""
    law = LAWS_3D[index % len(LAWS_3D)]
    coarse = coarse_only or index % 2 == 1
    kind = rng.choices(["sphere", "ellipsoid", "torus", "two spheres"], [3, 2, 2, 2])[0]
    if law == "enright":  # the field lives on the unit cube
        size = log_uniform(rng, 1e-3, 0.2)
        span = 2.4 * size
        centre = tuple(rng.uniform(span, 1 - span) for _ in range(3))
    else:
        size = log_uniform(rng, 1e-3, 1e3)
        centre = tuple(10 * size * rng.random() ** (1 / 3) * c for c in unit_vector(rng))
    s = make_shape(rng, kind, centre, size)
    v0 = size * rng.uniform(0.3, 2.0)
    params = {}
    if law == "rotation":
        omega = rng.choice([-1, 1]) * rng.uniform(0.5, 2.0)
        axis = unit_vector(rng)
        c = tuple(centre[i] + size * rng.random() * w for i, w in enumerate(unit_vector(rng)))
        params = {"omega": omega, "ax": axis[0], "ay": axis[1], "az": axis[2],
                  "cx": c[0], "cy": c[1], "cz": c[2]}
        t_end = rng.uniform(0.3, 3.0) / abs(omega)
    elif law == "translation":
        u = unit_vector(rng)
        params = {"ux": v0 * u[0], "uy": v0 * u[1], "uz": v0 * u[2]}
        t_end = rng.uniform(0.3, 1.5)
    elif law == "enright":
        t_end = rng.uniform(0.2, 1.0)
    elif law == "unit-normal":
        grow = rng.random() < 0.7
        d = size * rng.uniform(0.05, 0.3) if grow else s["inner"] * rng.uniform(0.1, 0.5)
        params = {"speed": v0 if grow else -v0}
        t_end = d / v0
    elif law == "anisotropic":
        if rng.random() < 0.5:  # the law's default shape of speed (R = 1, eps = 0.5)
            params = {"R": v0, "eps": v0 / 2}
        else:
            params = {"R": rng.choice([-1, 1]) * v0, "eps": v0 * rng.uniform(-1.5, 1.5)}
        lo, hi = speed_range(params)
        if lo > 0:
            t_end = size * rng.uniform(0.05, 0.3) / hi
        else:
            t_end = s["inner"] * rng.uniform(0.1, 0.5) / max(abs(lo), abs(hi))
    elif law == "curvature":
        life = s["inner"] ** 2 / 4  # the inscribed sphere's: the surface lives at least this
        past = kind in ("sphere", "two spheres") and rng.random() < 0.2
        t_end = life * (rng.uniform(1.05, 1.4) if past else rng.uniform(0.1, 0.8))
    else:
        t_end = size * size * rng.uniform(0.01, 0.1)
    args = ["--velocity", law]
    for k, v in params.items():
        args += ["--param", f"{k}={v:.9g}"]
    params = {k: float(f"{v:.9g}") for k, v in params.items()}
    args += ["--t-end", f"{t_end:.9g}"]
    if coarse:
        args += ["-K", str(rng.choice([3, 4])), "-N", str(rng.randint(5, 10))]
    return {"index": index, "law": law, "shape": s, "params": params,
            "t_end": float(f"{t_end:.9g}"), "args": args, "coarse": coarse}


def speed_range(p):
    """The anisotropic law's least and greatest normal speed."""
    a, b = p["R"] + p["eps"] * CUBIC_RANGE[0], p["R"] + p["eps"] * CUBIC_RANGE[1]
    return min(a, b), max(a, b)


# ---------------------------------------------------------------------------------------------
# The judge.

def rigid_back(case, t):
    """The inverse of the rigid motion to t."""
    p = case["params"]
    if case["law"] == "translation":
        return lambda x: (x[0] - p["ux"] * t, x[1] - p["uy"] * t, x[2] - p["uz"] * t)
    axis = (p["ax"], p["ay"], p["az"])
    n = norm(axis)
    axis = tuple(a / n for a in axis)
    c = (p["cx"], p["cy"], p["cz"])
    return lambda x: tuple(ci + wi for ci, wi in zip(c, rotate_about(axis, -p["omega"] * t, sub(x, c))))


def reads_input(s, summary):
    """Why the run's start is not the input's surface, or None: a user's surface is read as
    curved patches through its vertex normals (docs/surfaces.md), so the start's volume lies
    between the triangles' and the smooth shape's they sample, up to eps A."""
    start, slack = summary["volume_initial"], summary["params"]["eps"] * summary["area_initial"]
    lo, hi = sorted((s["volume"], s["smooth_volume"]))
    if not lo - slack <= start <= hi + slack:
        return (f"the run starts with volume {start:.6g}, where the triangles hold "
                f"{s['volume']:.6g} and the smooth shape {s['smooth_volume']:.6g}")
    return None


def keeps_volume(s, summary):
    """Why the volume broke a law that keeps it, or None."""
    vol, start = summary["volume"], summary["volume_initial"]
    if abs(vol - start) > VOLUME_DRIFT * abs(start) * (1 + 1e-9):
        return f"volume {vol:.6g} from the run's start {start:.6g} ({100 * (vol / start - 1):+.3g}%)"
    return None


def area_not_grown(summary):
    a, a0 = summary["area"], summary["area_initial"]
    if a > a0 * (1 + AREA_GROWTH):
        return f"area {a:.6g} from {a0:.6g} (+{100 * (a / a0 - 1):.3g}%) under a law that shrinks it"
    return None


def judge(case, summary, final_vertices, history):
    """What the result breaks: None, a string (impossible: a budget or an exact invariant), or
    ("inaccurate", why): a vertex off the exact surface by more than SHAPE_GROSS."""
    law, s, p = case["law"], case["shape"], case["params"]
    why = reads_input(s, summary)
    if why:
        return why
    most = max(history, key=lambda r: r["components"])
    if (law in ("rotation", "translation", "enright") or s["convex"] and law == "curvature") \
            and most["components"] > s["components"]:
        return (f"{most['components']:g} components from {s['components']} at t = "
                f"{most['t']:.4g}, under a law that cannot split the surface")
    status, t = summary["status"], summary["t"]
    tol = SHAPE_GROSS * s["half_width"]
    comps, genus = summary.get("components"), summary.get("genus")
    k = case["t_end"] / summary["steps"]
    if law in ("rotation", "translation", "enright"):
        if status == "vanished":
            return "vanished under a law that keeps the volume"
        why = keeps_volume(s, summary)
        if why:
            return why
        if comps != s["components"] or genus != s["genus"]:
            return (f"{comps} components of genus {genus} from {s['components']} of genus "
                    f"{s['genus']} under a motion that cannot tear or join the surface")
        if law != "enright":
            back = rigid_back(case, t)
            err = max(abs(s["distance"](back(x))) for x in final_vertices)
            if err > tol:
                return "inaccurate", f"a vertex {err / s['half_width']:.3g} l from the moved surface"
        return None
    if law in ("unit-normal", "anisotropic"):
        lo, hi = (p["speed"], p["speed"]) if law == "unit-normal" else speed_range(p)
        lo, hi = lo * t, hi * t
        if status == "vanished":
            if lo >= 0 or -lo < max(s.get("radii", [s["inner"]])):
                return f"vanished by t = {t:.4g}, where the start eroded by {-lo:.3g} is not empty"
            return None
        if lo >= 0 and summary["volume"] < s["volume"] * (1 - VOLUME_DRIFT):
            return f"a growing region lost volume: {summary['volume']:.6g} from {s['volume']:.6g}"
        dist = [s["distance"](x) for x in final_vertices]
        miss = max(max(lo - d for d in dist), max(d - hi for d in dist))
        if miss > tol:
            return "inaccurate", (f"vertices at signed distance {min(dist):.4g}..{max(dist):.4g} "
                                  f"from the start, where the law gives {lo:.4g}..{hi:.4g}: "
                                  f"{miss / s['half_width']:.3g} l off")
        if law == "unit-normal" and lo > 0 and s["convex"]:
            # Steiner: the offset by d of the start sweeps A d + M d^2 + 4/3 pi d^3, M the
            # integral of the mean curvature (the triangles'); the guards allow 10% a step.
            m = steiner(s["v"], s["f"], 1.0) - s["volume"] - s["area"] - 4 * math.pi / 3
            swept = summary["area_initial"] * lo + m * lo * lo + 4 * math.pi / 3 * lo ** 3
            grown = summary["volume"] - summary["volume_initial"]
            slack = STEINER_STEP * swept + summary["params"]["eps"] * summary["area"]
            if abs(grown - swept) > slack:
                return f"the volume grew by {grown:.6g} where Steiner's formula gives {swept:.6g}"
        if s["kind"] == "two spheres" and lo >= 0 and comps == 1 and 2 * hi < s["gap"] - 2 * tol:
            return f"two spheres {s['gap']:.3g} apart joined, offset by {hi:.3g} at most"
        return None
    if law == "curvature":
        return judge_curvature(case, summary, final_vertices, t, k, tol)
    # volume-preserving curvature
    if status == "vanished":
        return "vanished under a law that keeps the volume"
    why = keeps_volume(s, summary) or area_not_grown(summary)
    if why:
        return why
    if s["kind"] == "sphere":
        err = max(abs(s["distance"](x)) for x in final_vertices)
        if err > tol:
            return "inaccurate", f"a vertex {err / s['half_width']:.3g} l off the sphere the law keeps"
    return None


def judge_curvature(case, summary, final_vertices, t, k, tol):
    s = case["shape"]
    status = summary["status"]
    if s["kind"] in ("sphere", "two spheres"):
        # Each sphere of the run's start: R(t)^2 = R0^2 - 4t.
        scale = (summary["volume_initial"] / sum(4 / 3 * math.pi * r ** 3 for r in s["radii"])) ** (1 / 3)
        r0 = [r * scale for r in s["radii"]]
        left = [math.sqrt(r * r - 4 * t) if r * r > 4 * t else 0.0 for r in r0]
        v_exact = sum(4 / 3 * math.pi * r ** 3 for r in left)
        if status == "vanished":
            # t is the end of the step in which it vanished: a sphere the law keeps to the next
            # step's end (the components' rule below) may not vanish; one that dies within the
            # step it vanished in has.
            if any(r * r > 4 * (t + k) for r in r0):
                return f"vanished at t = {t:.4g}, the exact extinction {max(r0) ** 2 / 4:.4g}"
            return None
        v0 = summary["volume_initial"]
        budget = CURVATURE_VOLUME * v0 + 0.25 * (v0 - v_exact)
        if abs(summary["volume"] - v_exact) > budget:
            return f"volume {summary['volume']:.6g} where the law gives {v_exact:.6g}, budget {budget:.3g}"
        alive = sum(1 for r in r0 if r * r > 4 * (t + k))
        if not (alive <= summary["components"] <= sum(1 for r in r0 if r * r > 4 * (t - k))):
            return f"{summary['components']} components where the law leaves {alive}"
        for x in final_vertices:
            d = min(abs(norm(sub(x, c)) - r) for c, r in zip(s["centres"], left))
            if d > tol:
                return "inaccurate", f"a vertex {d / s['half_width']:.3g} l off the shrinking spheres"
        return area_not_grown(summary)
    # Comparison: the inscribed spheres of the start shrink inside the surface, the sphere about
    # it shrinks outside it.
    inner, outer = s["inner"], s["extent"]
    if status == "vanished":
        if inner * inner > 4 * (t - k):
            return f"vanished at t = {t:.4g}, before its inscribed spheres ({inner ** 2 / 4:.4g})"
        return None
    if outer * outer < 4 * (t - k):
        return f"still there at t = {t:.4g}, after the sphere about it vanished ({outer ** 2 / 4:.4g})"
    r_out = math.sqrt(max(outer * outer - 4 * t, 0.0))
    r_in = math.sqrt(max(inner * inner - 4 * t, 0.0))
    far = max(norm(sub(x, s["centre"])) for x in final_vertices)
    if far > r_out + tol:
        return "inaccurate", (f"a vertex {far:.4g} from the centre, outside the shrunk sphere "
                              f"about the start ({r_out:.4g})")
    if s["kind"] == "torus":
        near = min(s["from_core"](x) for x in final_vertices)
    else:
        near = min(norm(sub(x, s["centre"])) for x in final_vertices)
    if near < r_in - tol:
        return "inaccurate", (f"a vertex {near:.4g} from the core, inside the shrunk inscribed "
                              f"spheres ({r_in:.4g})")
    return area_not_grown(summary)


# ---------------------------------------------------------------------------------------------

def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--slc", required=True)
    p.add_argument("--size", choices=SIZES, default="small")
    p.add_argument("--seed", type=int)
    p.add_argument("--check", action="store_true", help="exit 1 when any defect is found")
    p.add_argument("--doc", help="write the counts into this file between campaign markers")
    p.add_argument("--only", type=int, help="run only the case of this index (to reproduce it)")
    p.add_argument("--keep", help="write the cases' files here and keep them")
    p.add_argument("--threads", type=int, default=1, help="--threads of each run (default 1)")
    p.add_argument("--verbose", action="store_true", help="print each run's outcome as it ends")
    p.add_argument("--runs", type=int, help="this many runs instead of the size's")
    p.add_argument("--coarse-only", action="store_true", help="every run coarse")
    p.add_argument("--coarse-args", default="",
                   help="more settings of the coarse runs, e.g. '-P 0' (no refinement)")
    a = p.parse_args()
    runs, seed = SIZES[a.size]
    runs = a.runs or runs
    seed = a.seed if a.seed is not None else seed
    rng = random.Random(seed)
    slc = os.path.abspath(a.slc)
    work = os.path.abspath(a.keep) if a.keep else tempfile.mkdtemp(prefix="slc-campaign3d-")
    os.makedirs(work, exist_ok=True)
    tally = Tally([f"{law}, {how}" for law in LAWS_3D for how in ("defaults", "coarse")])
    start = time.time()
    try:
        for i in range(runs):
            case = surface_case(rng, i, a.size == "small" or a.coarse_only)
            if case["coarse"]:
                case["args"] += a.coarse_args.split()
            if a.only is not None and i != a.only:
                continue
            s = case["shape"]
            initial = os.path.join(work, f"case{i}.obj")
            write_obj(initial, s["v"], s["f"])
            folder = os.path.join(work, f"out{i}")
            cmd = [slc, "run", "--initial", initial, *case["args"], "--out", folder, "--quiet",
                   "--threads", str(a.threads)]
            shown = " ".join(["slc", "run", "--initial", f"case{i}.obj", *case["args"]])
            c = s["centre"]
            shown += f"  [{s['desc']} ({s['mesh']}) at ({c[0]:.4g}, {c[1]:.4g}, {c[2]:.4g})]"
            began = time.time()
            outcome, detail, summary = run_outcome(cmd, folder, TIMEOUT_S)
            if outcome in ("ok", "vanished"):
                final = os.path.join(folder, "final.obj")
                vertices = read_obj(final)[0] if os.path.exists(final) else []
                history = read_history(os.path.join(folder, "history.csv"))
                why = judge(case, summary, vertices, history)
                if why:
                    outcome, detail = why if isinstance(why, tuple) else ("impossible", why)
            row = f"{case['law']}, {'coarse' if case['coarse'] else 'defaults'}"
            tally.add(row, outcome, shown, detail)
            if a.verbose:
                drift = ""
                if summary and summary.get("volume_initial"):
                    # The start's volume, and a law that keeps it the end's, from the smooth shape's.
                    drift = f" start {summary['volume_initial'] / s['smooth_volume'] - 1:+.2%}"
                    if case["law"] in KEEPS_VOLUME and summary.get("volume") is not None:
                        drift += f", end {summary['volume'] / s['smooth_volume'] - 1:+.2%}"
                print(f"{i} {row} {s['desc']}: {outcome} in {time.time() - began:.1f} s"
                      f"{drift} {detail or ''}", flush=True)
            if not a.keep:
                shutil.rmtree(folder, ignore_errors=True)
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)
    seconds = round(time.time() - start)
    report(tally, f"surfaces, {a.size}", seed, seconds, a.doc, "campaign-3d", False, a.threads)
    return 1 if a.check and tally.defects else 0


if __name__ == "__main__":
    sys.exit(main())
