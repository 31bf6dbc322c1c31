"""Tests of the Python package slc: exact laws (area under curvature flow, Huygens' offset, a full
rotation), the contour of an analytic function, bad input, callbacks and their errors."""

import math
import random
import os
import re
import subprocess
import sys
import signal
import threading

import numpy as np
import pytest

import slc


def circle(r=1.0, n=128, cx=0.0, cy=0.0):
    th = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    return np.c_[cx + r * np.cos(th), cy + r * np.sin(th)]


def ellipse(a=1.0, b=0.6, n=128):
    th = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    return np.c_[a * np.cos(th), b * np.sin(th)]


# ---- Interface ---------------------------------------------------------------------------------


def test_interface_holds_oriented_read_only_curves_with_area_and_length():
    square = np.array([[0, 0], [0, 1], [1, 1], [1, 0]])  # clockwise, integers
    with pytest.warns(UserWarning, match="reoriented"):
        curves = slc.Interface([square])
    (c,) = curves.curves
    assert c.dtype == np.float64 and c.shape == (4, 2)
    assert not c.flags.writeable
    assert curves.area == pytest.approx(1.0)
    assert curves.length == pytest.approx(4.0)


def test_interface_round_trips_through_a_file(tmp_path):
    curves = slc.Interface([circle(1.0, 64), circle(0.3, 32)[::-1]], time=0.5)  # a hole
    path = tmp_path / "shape.json"
    curves.save(path)
    back = slc.Interface.load(path)
    assert back.time == 0.5
    for a, b in zip(curves.curves, back.curves):
        np.testing.assert_array_equal(a, b)
    assert back.area == pytest.approx(curves.area)


BAD_CURVES = {
    "non-finite": ([np.array([[0, 0], [1, 0], [np.nan, 1]])], "finite"),
    "self-crossing": ([np.array([[0, 0], [1, 1], [1, 0], [0, 1]])], "cross"),
    "open (two points)": ([np.array([[0, 0], [1, 0]])], "3"),
    "no curves": ([], "no curves"),
    "curves crossing": ([circle(1.0, 32), circle(1.0, 32, cx=0.5)], "cross"),
}


@pytest.mark.parametrize("name", BAD_CURVES)
def test_every_bad_interface_is_a_value_error_of_one_line(name):
    curves, words = BAD_CURVES[name]
    with pytest.raises(ValueError) as e:
        slc.Interface(curves)
    message = str(e.value)
    assert "\n" not in message and words in message, message


def test_a_bad_file_is_a_value_error_naming_it(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"curves": [{"points": [[0, 0], [1, 1], [1, 0], [0, 1]]}]}')
    with pytest.raises(ValueError, match="bad.json") as e:
        slc.Interface.load(path)
    assert "\n" not in str(e.value)
    with pytest.raises(ValueError, match="missing.json"):
        slc.Interface.load(tmp_path / "missing.json")


def test_shapes_and_dtypes_are_checked():
    with pytest.raises(ValueError, match=r"curve 0 must be an \(n, 2\) array, got shape \(4, 3\)"):
        slc.Interface([np.zeros((4, 3))])
    with pytest.raises(TypeError, match="real numbers"):
        slc.Interface([np.array([["a", "b"], ["c", "d"], ["e", "f"]])])
    with pytest.raises(TypeError, match="real numbers"):
        slc.Interface([circle(1.0, 8).astype(complex)])
    with pytest.raises(TypeError):
        slc.Interface(3.0)
    curves = slc.Interface(circle())
    for shape in [(3,), (4, 3), (2, 2, 1), ()]:
        words = f"points must be one point (2,) or an array (..., 2) of points, got shape {shape}"
        with pytest.raises(ValueError, match=re.escape(words)):
            slc.distance(curves, np.zeros(shape))


def test_one_list_of_points_is_one_curve_and_a_list_of_them_many():
    # A 2D array-like of numbers with last dimension 2 is one curve; it used to be read as three
    # curves of one point each, and refused.
    triangle = [[0, 0], [1, 0], [0, 1]]
    for one in (triangle, np.array(triangle), [np.array(p) for p in triangle]):
        curves = slc.Interface(one)
        assert len(curves) == 1 and curves.area == pytest.approx(0.5)
    square = [[2, 2], [3, 2], [3, 3], [2, 3]]
    for many, area in [([triangle, square], 1.5), ([np.array(triangle), np.array(square)], 1.5),
                       ([triangle, [[2, 2], [3, 2], [2, 3]]], 1.0)]:  # of equal lengths
        curves = slc.Interface(many)
        assert len(curves) == 2 and curves.area == pytest.approx(area)
    d, _ = slc.distance(triangle, [0.25, 0.25])
    assert d == pytest.approx(-0.25)


# ---- distance ----------------------------------------------------------------------------------


def test_distance_is_signed_with_nearest_points():
    square = slc.Interface([np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]])])
    d, nearest = slc.distance(square, [[0, 0], [3, 0], [2, 2], [0.5, -0.5]])
    np.testing.assert_allclose(d, [-1, 2, math.sqrt(2), -0.5], atol=1e-15)
    np.testing.assert_allclose(nearest, [[nearest[0][0], nearest[0][1]], [1, 0], [1, 1], [0.5, -1]])
    assert d.shape == (4,) and nearest.shape == (4, 2)


def test_distance_of_one_point_is_a_number_and_of_a_grid_keeps_its_shape():
    # As scikit-fmm and scipy answer: one point (2,) gives a float and a (2,) point, a grid
    # (..., 2) distances (...) and nearest points (..., 2), each the same as the rows alone.
    square = slc.Interface([[-1, -1], [1, -1], [1, 1], [-1, 1]])
    d, nearest = slc.distance(square, [3, 0])
    assert np.ndim(d) == 0 and d == pytest.approx(2.0) and nearest.shape == (2,)
    np.testing.assert_allclose(nearest, [1, 0])
    x, y = np.meshgrid(np.linspace(-2, 2, 5), np.linspace(-2, 2, 3))
    grid = np.stack([x, y], axis=-1)
    d, nearest = slc.distance(square, grid)
    assert d.shape == (3, 5) and nearest.shape == (3, 5, 2)
    rows_d, rows_nearest = slc.distance(square, grid.reshape(-1, 2))
    np.testing.assert_array_equal(d, rows_d.reshape(3, 5))
    np.testing.assert_array_equal(nearest, rows_nearest.reshape(3, 5, 2))
    assert d[1, 2] == pytest.approx(-1.0) and d[0, 0] == pytest.approx(math.sqrt(2))
    with pytest.raises(ValueError, match=r"point 0: \(nan, 0\) is not finite"):
        slc.distance(square, [np.nan, 0.0])
    with pytest.raises(ValueError, match=r"point 3: \(inf, 0\) is not finite"):
        slc.distance(square, [[[0, 0], [1, 0]], [[0, 1], [np.inf, 0]]])


@pytest.mark.parametrize("point, words", [
    ([np.nan, 0.0], r"point 1: \(nan, 0\) is not finite"),
    ([-np.inf, np.nan], r"point 1: \(-inf, nan\) is not finite"),
    ([np.inf, 0.0], r"point 1: \(inf, 0\) is not finite"),
    ([1e200, 0.0], r"point 1: \(1e\+200, 0\) is beyond the coordinate limit ±1e\+100"),
])
def test_query_points_not_finite_or_beyond_the_coordinate_limit_are_refused(point, words):
    # As `slc distance --points` refuses them; a NaN point used to crash the interpreter, and an
    # infinite one to give distance inf. The exact solution of a problem takes the same points.
    curves = slc.Interface(circle())
    points = np.array([[0.5, 0.0], point])
    for call in (lambda: slc.distance(curves, points),
                 lambda: slc.problem("zalesak").exact(points, 0.0)):
        with pytest.raises(ValueError, match=words) as e:
            call()
        assert "\n" not in str(e.value)
    d, _ = slc.distance(curves, [[1e100, 0.0]])  # the limit itself is a point
    assert d[0] == pytest.approx(1e100)


def test_a_time_that_is_not_finite_is_refused(tmp_path):
    # The tool refuses a file whose time is not finite: such a time is refused where it is set,
    # before save() could write it.
    for t in (np.inf, -np.inf, np.nan):
        with pytest.raises(ValueError, match="time must be finite"):
            slc.Interface(circle(), time=t)
    curves = slc.Interface(circle(), time=0.5)
    with pytest.raises(ValueError, match="time must be finite, got inf"):
        slc.Interface(curves, time=np.inf)
    with pytest.raises(ValueError, match="time must be finite, got nan"):
        curves.time = float("nan")
    assert curves.time == 0.5
    curves.time = np.float64(2)
    assert type(curves.time) is float and curves.time == 2.0
    curves.save(tmp_path / "c.json")
    assert slc.Interface.load(tmp_path / "c.json").time == 2.0


# ---- contour -----------------------------------------------------------------------------------


def test_contour_of_a_circle_is_within_eps():
    r, eps = 0.6, 1e-6
    calls = []

    def g(p):  # G > 0 outside
        calls.append(p.shape)
        return np.hypot(p[:, 0], p[:, 1]) - r

    curves = slc.contour(g, (-1, -1, 1, 1), 5, eps=eps)
    assert len(curves) == 1
    c = curves.curves[0]
    mid = 0.5 * (c + np.roll(c, -1, axis=0))
    assert np.abs(np.hypot(c[:, 0], c[:, 1]) - r).max() < 1e-9  # vertices: root tolerance
    assert np.abs(np.hypot(mid[:, 0], mid[:, 1]) - r).max() <= eps
    assert curves.area > 0.0  # counterclockwise around G < 0
    assert all(len(s) == 2 and s[1] == 2 for s in calls)
    assert max(s[0] for s in calls) > 100  # batches, not points
    # With its statistics, under the keys of `slc contour`'s summary.json, as for surfaces.
    again, stats = slc.contour(g, (-1, -1, 1, 1), 5, eps=eps, stats=True)
    assert np.array_equal(again.curves[0], c)
    assert stats["segments"] == len(c) and stats["curves"] == 1 and stats["eps"] == eps
    assert stats["passes"] > 0 and stats["g_evals"] > len(c)
    assert stats["domain"] == [-1.0, -1.0, 1.0, 1.0]


def test_contour_splits_thin_cells_where_asked_in_both_dimensions():
    # Rings whose walls are 0.005 to 0.04 wide, a twelfth to two thirds of a cell at K = 5 in
    # [-1, 1]^2: torn at K, their two curves with four levels of thin cells (60 of 60 such rings;
    # 42 before thin cells followed the wall into the neighbours of the cells where G bends).
    rng = np.random.default_rng(7)
    for _ in range(20):
        cx, cy = rng.uniform(-0.05, 0.05, 2)
        radius, width = rng.uniform(0.3, 0.7), rng.uniform(0.005, 0.04)

        def ring(p):
            return np.abs(np.hypot(p[:, 0] - cx, p[:, 1] - cy) - radius) - width / 2

        assert len(slc.contour(ring, 1, 5)) != 2
        curves = slc.contour(ring, 1, 5, thin_depth=4)
        assert len(curves) == 2
        exact = np.pi * ((radius + width / 2) ** 2 - (radius - width / 2) ** 2)
        assert abs(curves.area - exact) < 0.05 * exact
    # A shell as thin, in space, with two levels.
    def shell(p):
        return np.abs(np.linalg.norm(p - [0.013, -0.021, 0.007], axis=1) - 0.61) - 0.01

    _, triangles, stats = slc.contour_surface(shell, 1, 5, slack=0.0, thin_depth=2)
    assert stats["thin_cells"] > 0 and stats["finest_cell"] == 2.0 / 2 ** 7
    with pytest.raises(ValueError, match="thin_depth: must be an integer from 0 to 8, got 9"):
        slc.contour(ring, 1, 5, thin_depth=9)
    with pytest.raises(TypeError, match="thin_depth must be an integer"):
        slc.contour_surface(shell, 1, 5, thin_depth=1.5)


def test_contour_parts_two_discs_the_triangles_join_across_a_gap():
    # Two discs 0.05 apart, the gap under half a cell at K = 4 in [-1, 1]^2: the linear contour
    # joins them, refinement parts them where f in the gap is positive (the library's
    # Contour.TwoDiscsTheInterpolantJoinsArePartedWhereGSaysTheyAreTwo, through the package).
    c1, r1, c2, r2 = (-0.1827, -0.1866), 0.3666, (-0.3569, 0.4529), 0.2169

    def discs(p):
        return np.minimum(np.hypot(p[:, 0] - c1[0], p[:, 1] - c1[1]) - r1,
                          np.hypot(p[:, 0] - c2[0], p[:, 1] - c2[1]) - r2)

    assert len(slc.contour(discs, 1, 4)) == 1
    curves, stats = slc.contour(discs, 1, 4, refine=2, stats=True)
    assert len(curves) == 2 and stats["parted"] >= 1
    areas = sorted(abs(slc.Interface([c]).area) for c in curves.curves)
    assert areas[0] == pytest.approx(math.pi * r2 ** 2, rel=1e-2)
    assert areas[1] == pytest.approx(math.pi * r1 ** 2, rel=1e-2)


def test_a_step_that_tears_a_wall_is_taken_again_deeper():
    # A ring whose wall shrinks to 0.01 in one step at K = 4 with one level of thin cells: torn
    # into pieces there, the ring again at five levels, and the run says so, as the command
    # line's note.
    ring = slc.Interface([circle(0.5, 256), circle(0.44, 256)[::-1]])
    with pytest.warns(UserWarning, match="kept by deeper thin cells, up to 5 levels deep, in 1 of"):
        r = slc.run(ring, "unit-normal", 0.025, speed=-1, steps=1, depth=4, thin_depth=1)
    assert r.status == "ok" and len(r.interface) == 2
    assert r.summary["thin_deeper"]["depth"] == 5 and r.summary["thin_deeper"]["steps"] == 1
    exact = math.pi * (0.475 ** 2 - 0.465 ** 2)
    assert abs(r.interface.area - exact) < 2e-3 * exact


def test_circles_that_meet_keep_shallower_thin_cells_and_merge():
    # Two circles of one's own (radii 0.303 and 0.290, 0.099 apart) grown at unit speed at the
    # defaults: where they meet, thin cells 8 levels deep make holes of the gap narrowing between
    # them that neither the start nor 6 levels have; the step keeps shallower cells, and the run
    # says so. One curve, within 1e-5 of the union of the grown circles (1.1e-6 measured).
    r1, r2, gap, angle = 0.30275433263752743, 0.29049347765365385, 0.09933537693614436, 2.8848
    bx, by = (r1 + r2 + gap) * math.cos(angle), (r1 + r2 + gap) * math.sin(angle)

    def polygon(r, n, phase, cx=0.0, cy=0.0):
        th = phase + np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
        return np.c_[cx + r * np.cos(th), cy + r * np.sin(th)]

    pair = slc.Interface([polygon(r1, 181, 0.2693), polygon(r2, 174, 0.5480, bx, by)])
    with pytest.warns(UserWarning, match="kept the shallower cells that made none, down to"):
        r = slc.run(pair, "unit-normal", 0.1)
    assert r.status == "ok" and len(r.interface) == 1
    assert "8 levels deep made" in r.summary["thin_shallower"]["why"]
    assert r.summary["thin_shallower"]["depth"] <= 6 and r.summary["thin_shallower"]["substeps"] >= 1
    x = np.concatenate(r.interface.curves)
    off = np.minimum(np.hypot(x[:, 0], x[:, 1]) - r1 - 0.1,
                     np.hypot(x[:, 0] - bx, x[:, 1] - by) - r2 - 0.1)
    assert np.abs(off).max() < 1e-5


def test_contour_checks_what_f_returns_and_passes_its_errors_on():
    with pytest.raises(ValueError, match=r"f must return an \(m,\) array"):
        slc.contour(lambda p: np.zeros((len(p), 2)), 1.0, 4)
    with pytest.raises(RuntimeError, match="not finite"):
        slc.contour(lambda p: np.full(len(p), np.nan), 1.0, 4)

    class Mine(Exception):
        pass

    def boom(p):
        raise Mine("from f")

    with pytest.raises(Mine, match="from f"):
        slc.contour(boom, 1.0, 4)
    with pytest.raises(ValueError, match="depth"):
        slc.contour(lambda p: p[:, 0], 1.0, 99)


def test_contour_of_a_function_without_a_zero_warns_and_is_empty():
    with pytest.warns(UserWarning, match=r"G = f has no zero in the domain \[-1, 1\]x\[-1, 1\] "
                      r"\(none found at depth 4\): the contour is empty"):
        curves = slc.contour(lambda p: 1.0 + p[:, 0] ** 2, 1.0, 4)
    assert len(curves) == 0 and curves.area == 0.0
    with pytest.warns(UserWarning, match=r"no zero in the domain \[-1, 1\]x\[-1, 1\]x\[-1, 1\]"):
        vertices, triangles, stats = slc.contour_surface(lambda p: -1.0 - p[:, 0] ** 2, 1.0, 3)
    assert vertices.shape == (0, 3) and triangles.shape == (0, 3) and stats["triangles"] == 0


def test_contour_surface_follows_the_creases_of_a_mesh():
    # A torus of 24 x 12 flat quads: its distance folds along the mesh's edges. Refinement that
    # follows the creases meets eps (19,156 triangles at the default thin depth 2); plain
    # refinement stops at 1.36 eps with 24,910.
    n, m = 24, 12
    u, v = np.meshgrid(2 * np.pi * np.arange(n) / n, 2 * np.pi * np.arange(m) / m, indexing="ij")
    r = 0.55 + 0.2 * np.cos(v)
    vertices = np.stack([r * np.cos(u), r * np.sin(u), 0.2 * np.sin(v)], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(n), np.arange(m), indexing="ij")
    at = lambda a, b: (a % n) * m + (b % m)  # noqa: E731
    quads = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]
    triangles = np.concatenate([np.stack([quads[0], quads[1], quads[2]], axis=-1).reshape(-1, 3),
                                np.stack([quads[0], quads[2], quads[3]], axis=-1).reshape(-1, 3)])
    mesh = slc.Surface(vertices, triangles)

    def g(p):
        return slc.distance(mesh, p)[0]

    eps = 1e-3
    # The Surface itself: its exact distance in C++, creases followed by default.
    vertices, triangles, stats = slc.contour_surface(mesh, 1.0, 3, eps=eps)
    assert stats["converged"] and stats["residual"] <= eps and stats["creases"]
    assert slc.Surface(vertices, triangles).genus == 1
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    for p in (0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a), (a + b + c) / 3):
        assert np.abs(g(p)).max() <= eps
    # Its distance as a Python function, creases and the Surface's thin depth asked for: the
    # same contour.
    v2, t2, s2 = slc.contour_surface(g, 1.0, 3, eps=eps, slack=0.0, creases=True,
                                     thin_depth=stats["thin_depth"])
    assert s2["converged"] and len(t2) == len(triangles)
    # Plain refinement, halving edges across the creases, stops beyond eps with more triangles.
    _, plain, plain_stats = slc.contour_surface(mesh, 1.0, 3, eps=eps, creases=False)
    assert not plain_stats["converged"] and len(triangles) < len(plain)
    # A box turned off the axes: its edges and corners cut to eps = 1e-5, its volume exact.
    corners = np.array([[x, y, z] for x in (-.4, .4) for y in (-.4, .4) for z in (-.4, .4)])
    cz, sz, cx, sx = np.cos(0.3), np.sin(0.3), np.cos(0.2), np.sin(0.2)
    turn = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]]) @ np.array(
        [[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7),
             (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    box = slc.Surface(corners @ turn.T, np.array(faces))
    vb, tb, sb = slc.contour_surface(box, 1.0, 4, eps=1e-5)
    assert sb["converged"] and sb["residual"] <= 1e-5
    assert abs(slc.Surface(vb, tb).volume / 0.512 - 1) < 1e-6


def test_contour_surface_of_a_surface_says_when_it_tears_a_thin_wall():
    # A box with a wall 0.03 thick (a cavity 0.87 x 0.8 x 0.8 in a unit cube) at K = 5: without
    # thin cells the wall is pierced, which the stats and a warning say, as slc contour's note;
    # at the default thin depth (2) it is kept.
    corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    faces = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                      [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    outer = -0.5 + corners
    inner = np.array([-0.47, -0.4, -0.4]) + corners * [0.87, 0.8, 0.8]
    box = slc.Surface(np.vstack([outer, inner]), np.vstack([faces, 8 + faces[:, [0, 2, 1]]]))
    with pytest.warns(UserWarning, match=r"the contour has 1 component with 288 handles where "
                      r"the input has 2 components with 0 handles: .*raise thin_depth \(now 0\)"):
        _, _, torn = slc.contour_surface(box, 0.75, 5, thin_depth=0)
    assert torn["kept_topology"] is False
    vertices, triangles, kept = slc.contour_surface(box, 0.75, 5)
    assert kept["kept_topology"] is True and "note" not in kept and kept["thin_depth"] == 2
    s = slc.Surface(vertices, triangles)
    assert s.genus == 0 and abs(s.volume - (1 - 0.87 * 0.64)) < 1e-4


def test_contour_surface_of_a_surface_keeps_the_thin_depth_that_keeps_it():
    # A hexagonal pyramid in a general turn at K = 4: the default thin cells (2 levels) follow
    # its 60 degree base edges and catch them unevenly, a handle beside one; left at its default,
    # the thin depth that has none (1) is kept, as slc contour keeps it, and refinement meets eps
    # with the volume exact. Given, a thin depth is kept as given.
    rng = random.Random(1)
    angles = [rng.uniform(0, 2 * math.pi) for _ in range(3)]
    corners = [(0.5 * math.cos(k * math.pi / 3), 0.5 * math.sin(k * math.pi / 3), -0.3)
               for k in range(6)] + [(0.0, 0.0, 0.5)]
    turned = []
    for x, y, z in corners:
        for angle, axis in zip(angles, "zxz"):
            c, s = math.cos(angle), math.sin(angle)
            if axis == "z":
                x, y = c * x - s * y, s * x + c * y
            else:
                y, z = c * y - s * z, s * y + c * z
        turned.append((x, y, z))
    faces = [(k, (k + 1) % 6, 6) for k in range(6)] + [(0, k + 1, k) for k in range(1, 5)]
    pyramid = slc.Surface(np.array(turned), np.array(faces))
    # The domain slc contour takes: the cube around the bounding box, 1.5 times its half-side.
    lo, hi = pyramid.vertices.min(axis=0), pyramid.vertices.max(axis=0)
    centre, half = 0.5 * (lo + hi), 0.75 * (hi - lo).max()
    box = (*(centre - half), *(centre + half))
    with pytest.warns(UserWarning, match=r"at thin_depth 2 has parts, holes or handles .* kept "
                      r"thin_depth 1"):
        vertices, triangles, stats = slc.contour_surface(pyramid, box, 4, eps=1e-3)
    assert stats["thin_depth"] == 1 and stats["kept_topology"] and stats["converged"]
    s = slc.Surface(vertices, triangles)
    exact = 0.5 * 6 * 0.25 * math.sin(math.pi / 3) * 0.8 / 3
    assert s.genus == 0 and abs(s.volume / exact - 1) < 1e-5
    with pytest.warns(UserWarning, match=r"1 handle.*raise thin_depth \(now 2\)"):
        _, _, given = slc.contour_surface(pyramid, box, 4, thin_depth=2)
    assert given["thin_depth"] == 2 and given["kept_topology"] is False


def test_contour_surface_of_a_torus_is_closed_and_within_eps():
    eps = 1e-3

    def g(p):  # a torus about the z axis, G > 0 outside
        return np.hypot(np.hypot(p[:, 0], p[:, 1]) - 0.55, p[:, 2]) - 0.2

    vertices, triangles, stats = slc.contour_surface(g, 1.0, 4, eps=eps)
    assert vertices.shape[1] == 3 and triangles.shape[1] == 3
    assert stats["converged"] and stats["triangles"] == len(triangles)
    # The statistics under the keys of `slc contour`'s summary.json.
    assert stats["vertices"] == len(vertices) and len(stats["finest_at"]) == 3
    assert stats["unconverged_roots"] == 0 and 0 < stats["residual"] <= eps
    assert stats["g_evals_tree"] + stats["g_evals_roots"] + stats["g_evals_refine"] == stats["g_evals"]
    # Vertices: roots to eta, by default eps/100 when refining; an eta given is kept.
    assert stats["eta"] == pytest.approx(eps / 100)
    assert np.abs(g(vertices)).max() <= stats["eta"]
    v1, _, s1 = slc.contour_surface(g, 1.0, 4, eps=eps, eta=1e-10)
    assert s1["eta"] == 1e-10 and np.abs(g(v1)).max() <= 1e-10
    assert s1["g_evals"] > stats["g_evals"]
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    for p in (0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a), (a + b + c) / 3):
        assert np.abs(g(p)).max() <= eps
    # Closed and oriented: every directed edge once, and its reverse present.
    edges = {(int(t[k]), int(t[(k + 1) % 3])) for t in triangles for k in range(3)}
    assert len(edges) == 3 * len(triangles)
    assert all((j, i) in edges for (i, j) in edges)
    # Euler characteristic V - E + F = 0 for a torus; the volume is positive (faces outward).
    assert len(vertices) - len(edges) // 2 + len(triangles) == 0
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
    assert abs(volume / (2 * np.pi**2 * 0.55 * 0.2**2) - 1) < 0.01
    # g is a signed distance: with slack 0 far points are settled, and the surface is the same.
    v2, t2, s2 = slc.contour_surface(g, 1.0, 4, eps=eps, slack=0)
    assert np.array_equal(v2, vertices) and np.array_equal(t2, triangles)
    assert s2["settled"] > 0 and s2["g_evals"] < stats["g_evals"]
    with pytest.raises(ValueError, match="eta must be positive"):
        slc.contour_surface(g, 1.0, 3, eta=-1)
    with pytest.raises(ValueError, match="distance slack must be >= 0"):
        slc.contour_surface(g, 1.0, 3, slack=-1)
    with pytest.raises(ValueError, match="box must be six numbers"):
        slc.contour_surface(g, (0, 0, 1, 1), 4)
    with pytest.raises(ValueError, match=r"f must return an \(m,\) array"):
        slc.contour_surface(lambda p: p, 1.0, 3)


# ---- run ---------------------------------------------------------------------------------------


def test_curvature_flow_loses_area_at_two_pi():
    # dA/dt = −2π for any closed curve under curvature flow. The run reads the polygon as arcs
    # through its vertices, so the area it starts from is the circle's, π: to 1e−3 of ΔA.
    t = 0.1
    r = slc.run(slc.Interface(circle(1.0, 256)), "curvature", t)
    assert r.status == "ok" and r.t == pytest.approx(t)
    loss = math.pi - r.interface.area
    assert loss == pytest.approx(2 * math.pi * t, rel=1e-3)
    h = r.history
    assert set(h) >= {"t", "area", "length", "components", "segments"}
    assert len(h["t"]) == 41 and h["t"][0] == 0.0 and h["t"][-1] == pytest.approx(t)
    assert h["components"].dtype == np.int64 and (h["components"] == 1).all()
    s = r.summary
    assert s["status"] == "ok" and s["params"]["N"] == 40 and s["params"]["K"] == 5
    assert s["params"]["P"] == 2 and s["params"]["eps"] == pytest.approx(1e-5)


def test_a_star_polygon_under_curvature_flow_vanishes_when_its_area_says():
    # Ten corners (points 0.5, notches 0.2): its first step keeps dA/dt = -2 pi only in sub-steps
    # of 1/32, then whole steps; it vanishes at A / 2 pi = 0.0468 to within a step (measured
    # 0.0475 of 0.05 in 40 steps), its area A - 2 pi t to 0.5% of A on the way.
    pts = [[(0.5 if i % 2 == 0 else 0.2) * math.cos(math.pi / 2 + i * math.pi / 5),
            (0.5 if i % 2 == 0 else 0.2) * math.sin(math.pi / 2 + i * math.pi / 5)]
           for i in range(10)]
    star = slc.Interface(np.array(pts))
    r = slc.run(star, "curvature", 0.05)
    assert r.status == "vanished"
    assert r.t == pytest.approx(star.area / (2 * math.pi), abs=0.05 / 40)
    h = r.history
    alive = h["components"] > 0
    assert np.abs(h["area"][alive] - (star.area - 2 * math.pi * h["t"][alive])).max() < 5e-3 * star.area
    assert r.summary["substeps"]["most"] >= 32


def test_mullins_sekerka_keeps_the_area_and_the_small_of_two_circles_vanishes():
    # Coarsening: the circle of radius 0.3 vanishes into the one of 0.5 (at t = 0.056 by the
    # accuracy tests), the total area kept to rounding through it, the length falling.
    assert "mullins-sekerka" in slc.velocities()
    two = [circle(0.3, 128) + np.array([-1.0, 0.0]), circle(0.5, 128) + np.array([1.0, 0.0])]
    r = slc.run(slc.Interface(two), "mullins-sekerka", 0.08, steps=64)
    assert r.status == "ok" and len(r.interface.curves) == 1
    h = r.history
    assert h["components"][0] == 2 and h["components"][-1] == 1
    assert np.abs(h["area"] / h["area"][0] - 1).max() < 1e-12
    assert (np.diff(h["length"]) <= 1e-12).all()
    # Asked to stop when one is left: the same steps up to the vanishing, then the end.
    until = slc.run(slc.Interface(two), "mullins-sekerka", 0.08, steps=64, until_components=1)
    vanished = int(np.argmax(h["components"] == 1))
    assert until.status == "ok" and "1 components left" in until.summary["message"]
    assert len(until.history["t"]) == vanished + 1 and until.history["t"][-1] < 0.08
    with pytest.raises(ValueError, match="until_components must be 1 or more"):
        slc.run(slc.Interface(two), "mullins-sekerka", 0.08, until_components=0)
    with pytest.raises(ValueError, match="sigma must be positive"):
        slc.run(slc.Interface(two), "mullins-sekerka", 0.08, params={"sigma": -1})


def test_the_coarsening_problem_runs_until_as_many_particles_as_asked_are_left():
    p = slc.problem("coarsening", count=20, left=10)
    r = slc.run(p)
    h = r.history
    assert r.status == "ok" and len(r.interface.curves) == 10 and h["t"][-1] < 0.005
    assert h["components"][0] == 20 and (np.diff(h["components"]) <= 0).all()
    assert np.abs(h["area"] / h["area"][0] - 1).max() < 1e-12
    import matplotlib
    matplotlib.use("Agg")
    axes = slc.plot(h)  # the particles' count on a third axis, as history.png
    assert len(axes) == 3 and axes[2].get_ylabel() == "curves"
    assert len(slc.plot(slc.run(slc.Interface([circle(0.5, 64)]), "curvature", 0.01).history)) == 2
    with pytest.raises(ValueError, match="left must be a whole number"):
        slc.problem("coarsening", count=20, left=20)


def test_hele_shaw_with_a_source_grows_at_the_injection_rate():
    # A drop of radius 0.5 fed at q = 1 off its centre: A(t) = A(0) + q t.
    r = slc.run(slc.Interface(circle(0.5, 256)), "hele-shaw", 0.2, steps=16,
                params={"q": 1.0, "sx": 0.1, "sy": 0.05})
    assert r.status == "ok"
    h = r.history
    assert np.abs(h["area"] - h["area"][0] - h["t"]).max() < 1e-12
    with pytest.raises(ValueError, match="inside no region"):
        slc.run(slc.Interface(circle(0.5, 64)), "hele-shaw", 0.1, params={"q": 1.0, "sx": 2.0})


def test_an_estimate_runs_again_at_half_resolution():
    # As slc run --estimate: the distance to the run at N/2, K - 1, 4 eps, which bounds this
    # run's error when it converges at first order (measured: 8.0e-5 against 7.4e-7).
    r = slc.run(slc.Interface(circle(1.0, 256)), "curvature", 0.1, estimate=True)
    e = r.summary["error_estimate"]
    assert e["coarse"] == "20/0/4/2/4e-05" and e["coarse_status"] == "ok"
    p = r.interface.points
    error = np.abs(np.hypot(p[:, 0], p[:, 1]) - math.sqrt(1 - 0.2)).max()
    assert error <= e["estimate"] == e["distance"] < 1e-3
    assert "error_estimate" not in slc.run(slc.Interface(circle(1.0, 256)), "curvature", 0.1).summary
    with pytest.raises(ValueError, match="estimate compares with the run at half resolution"):
        slc.run(slc.Interface(circle(1.0, 256)), "curvature", 0.1, steps=1, estimate=True)


def test_python_normal_speed_gives_huygens_offset():
    # Unit outward speed: Γ(t) is the offset of Γ(0) at distance t (Huygens), the distance to
    # Γ(0) of every vertex equals t. The law is called once per stage with all vertices.
    initial = slc.Interface(ellipse())
    calls = []

    def speed(t, points, normals, curvature):
        calls.append(len(points))
        assert points.shape == normals.shape == (len(points), 2)
        assert curvature.shape == (len(points),)
        return np.ones(len(points))

    r = slc.run(initial, speed, 0.3, steps=20)
    assert r.status == "ok"
    d, _ = slc.distance(initial, r.interface.points)
    assert np.abs(d - 0.3).max() < 3e-3
    # Predictor and corrector of each step, each with the curvature and at C +- h (the check that
    # the speed does not fall as C grows).
    assert len(calls) == 3 * 2 * 20
    assert min(calls) >= len(initial.curves[0])


def test_a_python_law_backward_in_curvature_is_refused():
    # v = 1 - C moves the most convex parts out the fastest: ill-posed, as the speed expression
    # 'a - C' is, and refused the same way (test_surfaces.py: on surfaces); v = 1 + C is curvature flow
    # with a drift, and runs.
    message = r"velocity 'backward' falls as the curvature C grows \(dv/dC = -1 at \("

    def backward(t, p, n, c):
        return 1.0 - c

    backward.__name__ = "backward"
    with pytest.raises(ValueError, match=message):
        slc.run(slc.Interface(ellipse()), backward, 0.01, steps=2)
    assert slc.run(slc.Interface(ellipse()), lambda t, p, n, c: 1.0 + c, 0.01, steps=2).status == "ok"
    # Vertex velocities: the normal part's slope is the one checked.
    with pytest.raises(ValueError, match="falls as the curvature C grows"):
        slc.run(slc.Interface(ellipse()), lambda t, p, n, c: -c[:, None] * n, 0.01, steps=2)


def test_python_vertex_velocity_and_flow_field_turn_a_full_circle():
    # A rotation about the origin: after t = 2π the curve is back where it started. The field
    # sampled along the characteristics (fourth order in time) comes back to 2e−4 of the ellipse's
    # half-width 0.8, measured; vertex velocities extended from the nearest point take a callable's
    # defaults, those of a curvature law (P = 2, arcs: measured 3.5e−2, as the star's rotation in
    # docs/defaults.md). Tolerances: about twice the measured errors.
    initial = slc.Interface(ellipse(0.8, 0.4, 128) + [0.2, 0.1])

    def field(t, p):
        return np.c_[-p[:, 1], p[:, 0]]

    for velocity, tolerance in ((slc.FlowField(field), 5e-4), (lambda t, p, n, k: field(t, p), 7e-2)):
        r = slc.run(initial, velocity, 2 * math.pi, frames=4)
        assert r.status == "ok"
        d, _ = slc.distance(initial, r.interface.points)
        assert np.abs(d).max() < tolerance
        assert [t for t, _ in r.frames] == pytest.approx(np.linspace(0, 2 * math.pi, 5))
        assert r.interface.area == pytest.approx(initial.area, rel=1e-2)
    assert r.summary["params"]["extension"] == "nearest"


def test_a_built_in_laws_parameters_are_keywords_of_run():
    # run(I, "rotation", t, omega=2) is run(I, "rotation", t, params={"omega": 2}); a keyword that
    # is neither an option nor the law's parameter is refused naming it and the law's
    # parameters (it used to be a TypeError of Python's, and params= the only way).
    initial = slc.Interface(ellipse())
    a = slc.run(initial, "rotation", 0.1, steps=2, omega=2)
    b = slc.run(initial, "rotation", 0.1, steps=2, params={"omega": 2})
    assert a.summary["params"]["velocity_params"]["omega"] == 2.0
    for x, y in zip(a.interface.curves, b.interface.curves):
        np.testing.assert_array_equal(x, y)
    c = slc.run(initial, "rotation", 0.1, steps=2, omega=2, params={"cx": 0.0})
    np.testing.assert_array_equal(c.interface.points, a.interface.points)
    with pytest.raises(ValueError, match="velocity 'rotation' has no parameter 'omga'; its "
                                         "parameters: omega, cx, cy"):
        slc.run(initial, "rotation", 0.1, omga=2)
    with pytest.raises(ValueError, match="'omega' is given twice, in params and as a keyword"):
        slc.run(initial, "rotation", 0.1, params={"omega": 1}, omega=2)
    with pytest.raises(ValueError, match="run\\(\\) has no option 'omega'"):
        slc.run(initial, lambda t, p: p, 0.1, omega=2)
    with pytest.raises(ValueError, match="study\\(\\) has no option 'omega'"):
        slc.study(initial, slc.FieldExpression("-y, x"), 0.1, omega=2)
    with pytest.raises(ValueError, match="a named problem runs its own law"):
        slc.run(slc.problem("zalesak"), omega=2)


def _expected_threads(cores: int) -> int:
    """The tool's --threads 0: OMP_NUM_THREADS when set to a positive count, else the cores,
    never more than the cores."""
    n = os.environ.get("OMP_NUM_THREADS", "")
    return min(int(n), cores) if n.isdigit() and int(n) > 0 else cores


def test_threads_are_the_tools_threads_and_the_summary_reports_them():
    # It used to report the process's default, set again when the run was over.
    cores = len(os.sched_getaffinity(0))
    initial = slc.Interface(ellipse())
    for threads, expected in [(1, 1), (None, _expected_threads(cores)),
                              (0, _expected_threads(cores)), (10**6, cores)]:
        r = slc.run(initial, "rotation", 0.1, steps=2, threads=threads)
        assert r.summary["threads"] == expected, threads
    with pytest.raises(ValueError, match="threads must be 0 or more, got -1"):
        slc.run(initial, "rotation", 0.1, steps=2, threads=-1)
    with pytest.raises(TypeError, match="threads must be an integer or None"):
        slc.run(initial, "rotation", 0.1, steps=2, threads=True)


def test_omp_num_threads_sets_the_threads_as_for_the_tool():
    script = (
        "import numpy as np, slc\n"
        "th = np.linspace(0, 2 * np.pi, 64, endpoint=False)\n"
        "r = slc.run(slc.Interface(np.c_[np.cos(th), 0.6 * np.sin(th)]), 'rotation', 0.1,\n"
        "            steps=2)\n"
        "s = slc.Surface(slc.contour_surface(lambda p: np.linalg.norm(p, axis=1) - 0.5, 1.0, 3))\n"
        "q = slc.run(s, 'rotation', 0.1, steps=1, depth=3)\n"
        "print(r.summary['threads'], q.summary['params']['threads'])\n")
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         env=dict(os.environ, OMP_NUM_THREADS="1"), timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["1", "1"]


def test_a_callable_of_two_arguments_is_a_flow_field():
    # f(t, points) -> (m, 2) is known everywhere: sampled along the characteristics as a
    # FlowField is, to the last bit, and back to 2.4e-4 of the start after a full turn
    # (measured). It used to be called with four arguments (TypeError); written with normals it
    # takes the nearest-point extension instead: 3.5e-2, as test above.
    initial = slc.Interface(ellipse(0.8, 0.4, 128) + [0.2, 0.1])
    calls = []

    def field(t, p):
        calls.append(p.shape)
        return np.c_[-p[:, 1], p[:, 0]]

    r = slc.run(initial, field, 2 * math.pi, threads=1)
    flow = slc.run(initial, slc.FlowField(field), 2 * math.pi, threads=1)
    assert r.status == flow.status == "ok" and r.summary["params"]["extension"] == "direct"
    for a, b in zip(r.interface.curves, flow.interface.curves):
        np.testing.assert_array_equal(a, b)
    d, _ = slc.distance(initial, r.interface.points)
    assert np.abs(d).max() < 1e-3
    assert calls and all(shape[1] == 2 for shape in calls)
    with pytest.raises(TypeError, match=r"a velocity callable takes \(t, points\)"):
        slc.run(initial, lambda t: 0.0, 1.0)


def test_a_callable_of_three_arguments_moves_curves_as_one_of_four():
    # f(t, points, normals) is called without the curvature, and otherwise is the callable of
    # four arguments: the same defaults (P = 2, arcs) and the same curves. Refined to
    # convergence, this rotation used to blow up to 20,000 segments, 1.3 off its shape.
    initial = slc.Interface(ellipse(0.8, 0.4, 128) + [0.2, 0.1])

    def three(t, p, n):
        return np.c_[-p[:, 1], p[:, 0]]

    a = slc.run(initial, three, 2 * math.pi, threads=1)
    b = slc.run(initial, lambda t, p, n, k: three(t, p, n), 2 * math.pi, threads=1)
    assert a.status == b.status == "ok"
    assert a.summary["params"] | {"velocity": ""} == b.summary["params"] | {"velocity": ""}
    for x, y in zip(a.interface.curves, b.interface.curves):
        np.testing.assert_array_equal(x, y)
    d, _ = slc.distance(initial, a.interface.points)
    assert np.abs(d).max() < 7e-2  # measured 3.5e-2, as the test above


def test_built_in_law_with_params_matches_the_defaults():
    r = slc.run(slc.Interface(circle(0.5, 64)), "rotation", math.pi, params={"omega": 2},
                steps=10)
    assert r.status == "ok" and r.summary["params"]["velocity_params"] == {"omega": 2.0}
    assert r.summary["params"]["extension"] == "direct"
    with pytest.raises(ValueError, match="unknown velocity"):
        slc.run(slc.Interface(circle()), "nope", 1.0)
    with pytest.raises(ValueError, match="omeg"):
        slc.run(slc.Interface(circle()), "rotation", 1.0, params={"omeg": 1})
    with pytest.raises(ValueError, match="t-end"):
        slc.run(slc.Interface(circle()), "rotation", -1.0)
    with pytest.raises(ValueError, match="extension must be one of"):
        slc.run(slc.Interface(circle()), "rotation", 1.0, extension="far")


def test_an_exception_in_a_callback_reaches_the_caller_unchanged():
    class Mine(Exception):
        pass

    def law(t, p, n, k):
        if t > 0.05:
            raise Mine("from the law")
        return np.zeros(len(p))

    with pytest.raises(Mine, match="from the law"):
        slc.run(slc.Interface(circle()), law, 0.2, steps=4)

    def stop(step):
        raise KeyError("from the observer")

    with pytest.raises(KeyError, match="from the observer"):
        slc.run(slc.Interface(circle()), "curvature", 0.01, steps=4, observer=stop)
    with pytest.raises(ValueError, match="must return"):
        slc.run(slc.Interface(circle()), lambda t, p, n, k: np.zeros(3), 0.1, steps=2)


def test_an_observer_sees_every_step_and_may_stop_the_run():
    seen = []

    def observer(step):
        seen.append((step.step, step.t, len(step.interface)))
        return step.step < 3

    r = slc.run(slc.Interface(circle()), "curvature", 0.01, steps=10, observer=observer)
    assert r.status == "interrupted" and r.summary["steps_done"] == 3
    assert [s[0] for s in seen] == [1, 2, 3] and len(r.history["t"]) == 4


def test_an_observer_returns_true_false_or_none():
    # Anything else is a TypeError saying so, not pybind11's "Unable to cast".
    with pytest.raises(TypeError, match="the observer must return True, False .* or None, got "
                                        "str 'yes'"):
        slc.run(slc.Interface(circle()), "curvature", 0.01, steps=2, threads=1,
                observer=lambda s: "yes")
    r = slc.run(slc.Interface(circle()), "curvature", 0.01, steps=4, threads=1,
                observer=lambda s: np.bool_(s.step < 2))
    assert r.status == "interrupted" and r.summary["steps_done"] == 2
    r = slc.run(slc.Interface(circle()), "curvature", 0.01, steps=2, threads=1,
                observer=lambda s: None)
    assert r.status == "ok"


def test_ctrl_c_stops_a_run_between_steps():
    # SIGINT from another thread while the run is in C++: the run stops after the step. Python's
    # own handler is put in place first: a test run started in the background by a shell
    # without job control inherits SIGINT ignored, and the run would go on for all its steps.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        r = slc.run(slc.Interface(circle()), "unit-normal", 0.5, steps=100000)
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert r.status == "interrupted" and 0 < r.summary["steps_done"] < 100000


def test_a_vanishing_curve_ends_the_run():
    r = slc.run(slc.Interface(circle(0.2, 64)), "curvature", 0.05, steps=20)
    assert r.status == "vanished" and len(r.interface) == 0 and r.interface.area == 0.0


def test_the_gil_is_released_while_the_library_works():
    # A Python thread counts while the run is in C++: between the first and the last step it
    # runs only if the run released the GIL (the observer's few lines hold it for microseconds).
    count, done = [0], threading.Event()

    def spin():
        while not done.is_set():
            count[0] += 1

    seen = {}

    def observer(step):
        seen[step.step] = count[0]

    worker = threading.Thread(target=spin)
    worker.start()
    try:
        slc.run(slc.Interface(circle()), "curvature", 0.05, steps=20, threads=1, observer=observer)
    finally:
        done.set()
        worker.join()
    assert seen[20] - seen[1] > 10000
