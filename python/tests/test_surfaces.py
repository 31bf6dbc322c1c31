"""Tests of moving surfaces from Python: the Surface, runs under built-in laws and laws written in
Python or as expressions (against the built-in law they must equal, or an exact solution), named
problems, studies, observers and errors."""

import math
import pathlib

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import slc  # noqa: E402
from shapes3d import head_with_ears  # noqa: E402


DATA = pathlib.Path(__file__).resolve().parents[2] / "tests" / "cli" / "data"


def sphere(r=0.5, depth=4, eps=1e-3):
    return slc.Surface(slc.contour_surface(lambda p: np.linalg.norm(p, axis=1) - r, 1.0, depth,
                                           eps=eps))


def mean_radius(s):
    return np.linalg.norm(s.vertices, axis=1).mean()


# ---- the Surface -------------------------------------------------------------------------------


def test_a_surface_goes_to_openvdb_and_back(tmp_path):
    s = sphere()
    voxel = 0.02
    s.to_vdb(tmp_path / "s.vdb", voxel=voxel)
    back = slc.Surface.from_vdb(tmp_path / "s.vdb")
    assert back.components == 1 and back.genus == 0
    # The level set holds exact distances of s, whose vertices lie within 1e-3 of the sphere;
    # the zero set of its trilinear interpolant lies within a small part of a voxel of s.
    assert np.abs(np.linalg.norm(back.vertices, axis=1) - 0.5).max() <= voxel
    assert back.volume == pytest.approx(s.volume, rel=1e-2)
    assert len(slc.Surface.load(tmp_path / "s.vdb")) == len(back)
    assert len(slc.Surface.from_vdb(tmp_path / "s.vdb", grid="surface", depth=5)) > 0


def test_an_openvdb_vector_grid_moves_a_surface(tmp_path):
    # tests/cli/data/velocity.vdb: (-y, x, 0) on the voxels of [0, 2]^3, written by OpenVDB.
    field = slc.FieldFile(DATA / "velocity.vdb")
    ball = slc.Surface(slc.contour_surface(
        lambda p: np.linalg.norm(p - [1.0, 1.0, 1.0], axis=1) - 0.3, (0.5, 0.5, 0.5, 1.5, 1.5, 1.5),
        4))
    r = slc.run(ball, field, 0.2, steps=2, depth=4)
    assert r.status == "ok"
    want = [math.cos(0.2) - math.sin(0.2), math.sin(0.2) + math.cos(0.2), 1.0]
    assert np.abs(r.surface.vertices.mean(axis=0) - want).max() < 0.02
    r = slc.run(ball, field, 0.8, steps=2, depth=3)
    assert r.status == "error" and "left the region" in r.message
    # Zero outside the voxels when asked: what leaves them stops on the box's faces, where the
    # surface folds into an edge that refinement at K 3 does not resolve, and says so.
    with pytest.warns(UserWarning, match="refinement left"):
        r = slc.run(ball, slc.FieldFile(DATA / "velocity.vdb", outside="zero"), 0.8, steps=2,
                    depth=3)
    assert r.status == "ok", r.message
    assert r.surface.vertices.min() > -0.01 and r.surface.vertices.max() < 2.01
    with pytest.raises(ValueError, match="outside must be 'error' or 'zero', got 'none'"):
        slc.FieldFile("f.vdb", outside="none")
    with pytest.raises(ValueError, match=r"takes an OpenVDB vector grid \(.vdb\), got 'f.csv'"):
        slc.run(ball, slc.FieldFile("f.csv"), 0.1)
    with pytest.raises(ValueError, match=r"an OpenVDB field \(.vdb\) moves surfaces, not curves"):
        slc.run(slc.Interface([[0, 0], [1, 0], [0, 1]]), field, 0.1)


def test_openvdb_errors_are_value_errors(tmp_path):
    s = sphere()
    with pytest.raises(ValueError, match="voxel size must be positive and finite, got 0"):
        s.to_vdb(tmp_path / "s.vdb", voxel=0)
    with pytest.raises(ValueError, match="cannot read .*missing.vdb"):
        slc.Surface.from_vdb(tmp_path / "missing.vdb")
    (tmp_path / "text.vdb").write_text("v 0 0 0\n")
    with pytest.raises(ValueError, match="text.vdb: not a readable OpenVDB file"):
        slc.Surface.from_vdb(tmp_path / "text.vdb")
    s.to_vdb(tmp_path / "s.vdb", voxel=0.05, name="ball")
    cut = (tmp_path / "s.vdb").read_bytes()[:2000]
    (tmp_path / "cut.vdb").write_bytes(cut)
    with pytest.raises(ValueError, match="cut.vdb: not a readable OpenVDB file: its 2000 bytes"):
        slc.Surface.from_vdb(tmp_path / "cut.vdb")
    with pytest.raises(ValueError, match=r"no grid named 'surface' \(grids: 'ball' \(class level"):
        slc.Surface.from_vdb(tmp_path / "s.vdb", grid="surface")


def test_a_surface_is_validated_measured_and_saved(tmp_path):
    s = sphere()
    assert s.components == 1 and s.genus == 0 and len(s) == len(s.triangles)
    assert s.volume == pytest.approx(4 / 3 * math.pi * 0.125, rel=3e-3)
    assert s.area == pytest.approx(math.pi, rel=3e-3)
    assert not s.vertices.flags.writeable
    for name in ("s.obj", "s.vtp"):
        s.save(tmp_path / name)
    back = slc.Surface.load(tmp_path / "s.obj")
    assert np.array_equal(back.vertices, s.vertices)
    assert np.array_equal(back.triangles, s.triangles)
    # Turned inside out: reversed, with a warning.
    with pytest.warns(UserWarning, match="reversed"):
        inward = slc.Surface(s.vertices, s.triangles[:, ::-1])
    assert inward.volume == pytest.approx(s.volume)
    with pytest.raises(ValueError, match="edge"):
        slc.Surface(s.vertices, s.triangles[1:])  # a hole
    with pytest.raises(ValueError, match="names vertex"):
        slc.Surface(s.vertices, s.triangles + len(s.vertices))
    with pytest.raises(TypeError, match="integer vertex indices"):
        slc.Surface(s.vertices, s.triangles.astype(float))
    with pytest.raises(ValueError, match=r"\(n, 3\)"):
        slc.Surface(s.vertices[:, :2], s.triangles)


def test_a_surface_time_that_is_not_finite_is_refused(tmp_path):
    s = sphere(depth=3, eps=3e-3)
    for t in (np.inf, np.nan):
        with pytest.raises(ValueError, match="time must be finite"):
            slc.Surface(s.vertices, s.triangles, time=t)
        with pytest.raises(ValueError, match="time must be finite"):
            slc.Surface(s, time=t)
    with pytest.raises(ValueError, match="time must be finite, got -inf"):
        s.time = -np.inf
    assert s.time == 0.0
    s.time = 1.5
    s.save(tmp_path / "s.vtp")


def test_a_surface_problems_exact_solution_refuses_points_not_finite():
    p = slc.problem("sphere-rotation")
    with pytest.raises(ValueError, match=r"point 1: \(nan, 0, 0\) is not finite"):
        p.exact(np.array([[0.0, 0.0, 0.0], [np.nan, 0.0, 0.0]]), 0.0)
    with pytest.raises(ValueError, match=r"point 0: \(0, 0, -1e\+200\) is beyond the coordinate "
                                         r"limit ±1e\+100"):
        p.exact(np.array([[0.0, 0.0, -1e200]]), 0.0)
    assert p.exact(np.array([[0.0, 0.0, 0.0]]), 0.0).shape == (1,)


def cube():
    """The cube [-1, 1]³, each face two triangles counterclockwise seen from outside."""
    v = [[x, y, z] for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)]
    v = [v[0], v[1], v[3], v[2], v[4], v[5], v[7], v[6]]  # counterclockwise around each z face
    t = [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [2, 3, 7], [2, 7, 6],
         [0, 4, 7], [0, 7, 3], [1, 2, 6], [1, 6, 5]]
    return slc.Surface(v, t)


def test_distance_to_a_surface_is_exact_signed_and_keeps_the_shape_of_the_points():
    # As `slc distance --initial cube.obj`: it used to be a TypeError naming the Surface. One
    # point gives a float and a (3,) point, a grid (..., 3) distances (...) and nearest (..., 3).
    s = cube()
    d, nearest = slc.distance(s, [[0, 0, 0], [3, 0, 0], [2, 2, 2], [0.5, -0.2, 0.1]])
    np.testing.assert_allclose(d, [-1, 2, math.sqrt(3), -0.5], atol=1e-15)
    np.testing.assert_allclose(nearest[1:], [[1, 0, 0], [1, 1, 1], [1, -0.2, 0.1]], atol=1e-15)
    assert abs(np.abs(nearest[0]).max() - 1) < 1e-15  # on a face: every one is as near
    d, nearest = slc.distance(s, [0, 0, 3])
    assert np.ndim(d) == 0 and d == pytest.approx(2.0) and nearest.shape == (3,)
    grid = np.stack(np.meshgrid(*3 * [np.linspace(-2, 2, 3)], indexing="ij"), axis=-1)
    d, nearest = slc.distance(s, grid)
    assert d.shape == (3, 3, 3) and nearest.shape == (3, 3, 3, 3)
    assert d[1, 1, 1] == pytest.approx(-1.0) and d[0, 1, 1] == pytest.approx(1.0)
    with pytest.raises(ValueError, match=r"points must be one point \(3,\) or an array "
                                         r"\(\.\.\., 3\) of points, got shape \(4, 2\)"):
        slc.distance(s, np.zeros((4, 2)))
    with pytest.raises(ValueError, match=r"point 1: \(0, nan, 0\) is not finite"):
        slc.distance(s, [[0, 0, 0], [0, np.nan, 0]])


# ---- runs --------------------------------------------------------------------------------------


def test_python_laws_equal_the_built_in_ones_bit_for_bit():
    s = sphere(depth=3, eps=3e-3)
    options = dict(steps=2, depth=4, eps=3e-3)
    built_in = slc.run(s, "rotation", 0.5, **options)
    field = slc.run(s, slc.FlowField(lambda t, p: np.c_[-p[:, 1], p[:, 0], 0 * p[:, 2]]), 0.5,
                    **options)
    assert built_in.status == field.status == "ok"
    assert np.array_equal(built_in.surface.vertices, field.surface.vertices)
    assert np.array_equal(built_in.surface.triangles, field.surface.triangles)
    grow = slc.run(s, "unit-normal", 0.05, **options)
    speed = slc.run(s, slc.NormalSpeed(lambda t, p, n: np.ones(len(p))), 0.05, **options)
    assert np.array_equal(grow.surface.vertices, speed.surface.vertices)
    # Expressions too.
    typed = slc.run(s, slc.FieldExpression("-y, x, 0"), 0.5, **options)
    assert np.array_equal(built_in.surface.vertices, typed.surface.vertices)
    typed = slc.run(s, slc.SpeedExpression("v", v=1), 0.05, **options)
    assert np.array_equal(grow.surface.vertices, typed.surface.vertices)
    # Unit speed: the sphere of radius 0.55, to the contour's tolerance (measured 1.4e-4).
    assert np.abs(np.linalg.norm(grow.surface.vertices, axis=1) - 0.55).max() < 3e-3


def test_a_built_in_laws_parameters_are_keywords_of_run_for_surfaces_too():
    # The same path as for curves: omega=2 is params={"omega": 2}, to the last bit, and differs
    # from the default omega = 1; an unknown keyword names itself and the law's parameters.
    s = sphere(depth=3, eps=3e-3)
    s = slc.Surface(s.vertices + [0.2, 0, 0], s.triangles)  # off the axis: a rotation moves it
    a = slc.run(s, "rotation", 0.1, steps=1, depth=3, threads=1, omega=2)
    b = slc.run(s, "rotation", 0.1, steps=1, depth=3, threads=1, params={"omega": 2})
    c = slc.run(s, "rotation", 0.1, steps=1, depth=3, threads=1)
    np.testing.assert_array_equal(a.surface.vertices, b.surface.vertices)
    # The centre (0.2, 0, 0) turns about z by omega t: the area centroid's y is 0.2 sin(omega t)
    # to 2.6e-4 (measured) on this coarse sphere; the two omegas are 2e-2 apart.
    for r, omega in [(a, 2), (c, 1)]:
        v, t = r.surface.vertices, r.surface.triangles
        centroids = v[t].mean(axis=1)
        areas = np.linalg.norm(np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]), axis=1)
        y = (centroids[:, 1] * areas).sum() / areas.sum()
        assert y == pytest.approx(0.2 * math.sin(0.1 * omega), abs=1e-3), omega
    with pytest.raises(ValueError, match="velocity 'rotation' has no parameter 'omga'; its "
                                         "parameters: omega, ax, ay, az, cx, cy, cz"):
        slc.run(s, "rotation", 0.1, omga=2)
    with pytest.raises(ValueError, match="run\\(\\) has no option 'omega'"):
        slc.run(s, slc.FieldExpression("-y, x, 0"), 0.1, omega=2)


def test_a_python_curvature_law_shrinks_a_sphere_as_R2_falls_at_4():
    # Mean curvature flow, u = C N with C = -2/R: R^2 = R0^2 - 4t.
    s = sphere(depth=3, eps=3e-3)
    r = slc.run(s, lambda t, p, n, c: c, 0.01, steps=2, depth=4, eps=1e-3)
    assert r.status == "ok" and r.t == pytest.approx(0.01)
    # Measured: 3.0e-4 below, within eps = 1e-3.
    assert mean_radius(r.surface) == pytest.approx(math.sqrt(0.25 - 0.04), abs=1e-3)
    assert r.summary["velocity"] == "<lambda>" and r.summary["dimension"] == 3
    assert list(r.history) == ["t", "volume", "area", "triangles", "components", "cpu_s"]
    assert len(r.history["t"]) == 3 and r.history["volume"][-1] < r.history["volume"][0]


def test_a_python_law_backward_in_curvature_is_refused_on_surfaces():
    # As on curves (test_slc.py): v = -C moves the most convex parts out the fastest.
    with pytest.raises(ValueError, match=r"velocity '<lambda>' falls as the curvature C grows"):
        slc.run(sphere(depth=3, eps=3e-3), lambda t, p, n, c: -c, 0.01, steps=1, depth=4, eps=1e-3)


def test_an_estimate_of_a_surface_runs_again_at_half_resolution():
    # A sphere growing at unit speed, as tests/cli/surface_run_test.sh runs it with --estimate;
    # depth 4 sets eps to 1e-3 4^(5-4) = 4e-3 times the half-width 0.5.
    r = slc.run(sphere(), "unit-normal", 0.05, steps=4, depth=4, estimate=True)
    e = r.summary["error_estimate"]
    assert e["coarse"] == "N 2, K 3, eps 0.008" and e["coarse_status"] == "ok"
    error = np.abs(np.linalg.norm(r.surface.vertices, axis=1) - 0.55).max()
    assert error <= e["estimate"] < 1e-2  # measured 5.7e-5 and 4.9e-3


def test_a_named_problem_of_surfaces_runs_and_reports_its_error():
    p = slc.problem("sphere-rotation")
    assert isinstance(p, slc.SurfaceProblem) and p.has_exact and p.t_end == pytest.approx(2 * math.pi)
    assert "sphere-rotation" in slc.problems() and "enright" in slc.velocities(3)
    assert p.settings["thin_depth"] == 0 and slc.problem("enright").settings["thin_depth"] == 2
    r = slc.run(p, t_end=math.pi / 2, steps=4, depth=4, eps=1e-3, frames=2)
    assert r.status == "ok" and len(r.frames) == 3
    assert r.e_inf is not None and r.e_inf < 3e-3  # measured 1.0e-3 at eps = 1e-3
    assert r.e_inf == pytest.approx(p.error(r.surface))


def test_a_surface_and_its_history_are_drawn(tmp_path):
    import matplotlib.pyplot as plt

    s = sphere(depth=3, eps=3e-3)
    r = slc.run(s, "unit-normal", 0.05, steps=2, depth=3, eps=3e-3)
    ax = slc.plot(r)
    assert ax.name == "3d" and len(ax.collections) == 1
    assert len(ax.collections[0].get_facecolor()) == len(r.surface)
    axes = slc.plot(r.history)
    assert axes[0].get_ylabel() == "volume" and axes[1].get_ylabel() == "area"
    ax.figure.savefig(tmp_path / "s.png")
    # A figure standing in y (a scan's axes) stands up, as in the tool's pictures: the light
    # follows the vertical axis, so its top faces are lit.
    figure = slc.Surface(slc.contour_surface(
        lambda p: np.linalg.norm(p / [0.3, 0.8, 0.2], axis=1) - 1.0, 1.0, 4))
    assert slc._slc.up_axis([-0.3, -0.8, -0.2], [0.3, 0.8, 0.2]) == "y"
    assert slc._slc.up_axis([-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]) == "z"
    ax = slc.plot(figure)
    assert (ax.elev, ax.azim) == (25, 35) and ax._vertical_axis == 1
    shade = np.asarray(ax.collections[0].get_facecolor())[:, 0] / matplotlib.colors.to_rgb("C0")[0]
    v, t = figure.vertices, figure.triangles
    heights = v[t].mean(axis=1)[:, 1]
    assert shade[heights > 0.7].mean() > shade[heights < -0.7].mean()
    ax.figure.savefig(tmp_path / "standing.png")
    plt.close("all")


def test_a_head_with_ears_thinner_than_a_cell_turns_a_full_turn_at_the_defaults():
    # Ears 0.1 thick, 1.1% of the model's size and a quarter of a cell at the default K: the
    # turn keeps them, one surface of genus 0, its volume and its shape.
    given = head_with_ears()
    size = np.ptp(given.vertices, axis=0).max()
    r = slc.run(given, "rotation", 2 * math.pi)
    assert r.status == "ok", r.message
    assert r.summary["components"] == 1 and r.summary["genus"] == 0
    assert abs(r.surface.volume / given.volume - 1) < 5e-3
    d_back, _ = slc.distance(given, r.surface.vertices)
    d_there, _ = slc.distance(r.surface, given.vertices)
    assert max(np.abs(d_back).max(), np.abs(d_there).max()) < 0.01 * size


def test_the_volume_correction_is_reported_and_can_be_turned_off():
    s = sphere(depth=3, eps=3e-3)
    kept = slc.run(s, "volume-preserving-curvature", 0.004, steps=2, depth=3)
    assert kept.status == "ok" and "volume_corrected" in kept.summary
    assert abs(kept.summary["volume_change"]) < 1e-12
    off = slc.run(s, "volume-preserving-curvature", 0.004, steps=2, depth=3,
                  area_correction=False)
    assert off.status == "ok" and "volume_corrected" not in off.summary


def test_contours_left_beyond_eps_at_sharp_edges_are_reported():
    corners = [(x, y, z) for z in (-0.35, 0.35) for y in (-0.3, 0.3) for x in (-0.4, 0.4)]
    faces = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4), (2, 6, 7),
             (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]
    box = slc.Surface(np.array(corners), np.array(faces))
    with pytest.warns(UserWarning, match="in 2 of 2 steps refinement left"):
        r = slc.run(box, "rotation", 0.5, steps=2, depth=4, eps=1e-3)
    assert r.status == "ok"
    assert r.summary["unconverged_steps"] == 2 and r.summary["largest_residual"] > 2e-3


def test_thin_depth_splits_cells_beyond_the_depth_in_both_dimensions():
    corners = [(x, y, z) for z in (-0.35, 0.35) for y in (-0.3, 0.3) for x in (-0.4, 0.4)]
    faces = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4), (2, 6, 7),
             (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]
    box = slc.Surface(np.array(corners), np.array(faces))
    with pytest.warns(UserWarning):
        plain = slc.run(box, "rotation", 0.5, steps=1, depth=4, eps=1e-3, thin_depth=0)
        thin = slc.run(box, "rotation", 0.5, steps=1, depth=4, eps=1e-3)
    assert plain.summary["params"]["thin_depth"] == 0
    assert thin.summary["params"]["thin_depth"] == 2  # a user's surface's default
    assert len(thin.surface) > len(plain.surface)  # finer along the sharp edges
    # A square annulus whose wall is a fifth of a cell at the default K: kept at the default
    # thin depth; without thin cells the contours lose it, and the run is refused at the start.
    outer = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
    inner = [(-0.99, -0.99), (-0.99, 0.99), (0.99, 0.99), (0.99, -0.99)]
    annulus = slc.Interface([np.array(outer), np.array(inner)])
    kept = slc.run(annulus, "translation", 0.1, params={"ux": 0.3, "uy": 0.1})
    assert kept.summary["params"]["thin_depth"] == 6 and len(kept.interface) == 2
    assert abs(kept.interface.area - annulus.area) < 0.02 * annulus.area
    with pytest.raises(RuntimeError, match="do not keep the curves as given: 2 components with "
                       "1 hole became"):
        slc.run(annulus, "translation", 0.1, params={"ux": 0.3, "uy": 0.1}, thin_depth=0)
    with pytest.raises(ValueError, match="thin_depth: must be an integer from 0 to 8, got 9"):
        slc.run(box, "rotation", 0.5, steps=1, depth=4, eps=1e-3, thin_depth=9)


def test_volume_drift_and_guards_set_what_ends_a_run_of_a_surface_only():
    # Linear contours at K = 3 lose 1% of a turning sphere's volume by t = 3.9 of 6: the run
    # ends unstable at the default drift of 1% and finishes with 5% allowed.
    c = np.array([0.03, -0.02, 0.01])
    s = slc.Surface(slc.contour_surface(lambda p: np.linalg.norm(p - c, axis=1) - 0.6, 1.0, 4,
                                        eps=1e-3))
    tight = slc.run(s, "rotation", 6.0, steps=40, depth=3, refine=0)
    assert tight.status == "unstable" and "volume drifted" in tight.message
    assert 3.0 < tight.t < 6.0
    loose = slc.run(s, "rotation", 6.0, steps=40, depth=3, refine=0, volume_drift=0.05)
    assert loose.status == "ok" and loose.summary["params"]["volume_drift"] == 0.05
    assert -0.05 < loose.surface.volume / s.volume - 1 < -0.01
    with pytest.raises(ValueError, match="volume_drift is for surfaces, not curves"):
        slc.run(slc.problem("vortex"), volume_drift=0.1)
    with pytest.raises(ValueError, match="volume_drift: must be a positive finite number, got 0"):
        slc.run(s, "rotation", 1.0, volume_drift=0)
    # guards=False goes on to the end, warns and ends "broken" where the drift passed 1%; no
    # step was split, so the surface is the loose run's.
    assert loose.summary["split_steps"] == 0
    with pytest.warns(UserWarning, match="guards=False: at t = 3.9: the volume drifted"):
        unguarded = slc.run(s, "rotation", 6.0, steps=40, depth=3, refine=0, guards=False)
    assert unguarded.status == "broken" and unguarded.t == 6.0
    assert unguarded.message.startswith("at t = 3.9: the volume drifted")
    assert unguarded.summary["params"]["guards"] is False
    assert np.array_equal(unguarded.surface.vertices, loose.surface.vertices)
    # Curves too: Table 5's propeller at 40/0/3/0 drifts past 5% of its area at t = 2.2, and
    # unguarded goes on to t = 4 pi.
    with pytest.warns(UserWarning, match="guards=False: at t = 2.199.*the area has drifted by"):
        curves = slc.run(slc.problem("propeller-rotation"), steps=40, depth=3, refine=0,
                         guards=False)
    assert curves.status == "broken" and curves.t == pytest.approx(4 * math.pi)
    with pytest.raises(TypeError, match="guards must be True or False"):
        slc.run(s, "rotation", 1.0, guards=1)


def test_the_domain_of_a_users_surface_grows_as_it_moves_away():
    s = sphere(r=0.3, depth=4, eps=1e-3)
    r = slc.run(s, slc.FieldExpression("1, 0, 0"), 1.0, steps=4)
    assert r.status == "ok" and r.summary["domain_grown"]["doublings"] >= 1
    centre = 0.5 * (r.surface.vertices.min(axis=0) + r.surface.vertices.max(axis=0))
    assert np.allclose(centre, [1.0, 0.0, 0.0], atol=2e-3)


def test_an_observer_stops_a_run_of_a_surface():
    seen = []

    def observer(step):
        # one Step type for curves and surfaces: .interface, also named .surface for a surface
        assert isinstance(step, slc.Step) and isinstance(step.interface, slc.Surface)
        assert step.surface is step.interface
        seen.append((step.step, step.t, len(step.surface)))
        return step.step < 2

    r = slc.run(sphere(depth=3, eps=3e-3), "rotation", 1.0, steps=4, depth=4, eps=3e-3,
                observer=observer)
    assert r.status == "interrupted" and r.t == pytest.approx(0.5) and len(seen) == 2


def test_an_observer_of_a_surface_returns_true_false_or_none():
    with pytest.raises(TypeError, match=r"the observer must return True, False .* or None, got "
                                        r"list \[1\]"):
        slc.run(sphere(depth=3, eps=3e-3), "rotation", 1.0, steps=2, depth=3, threads=1,
                observer=lambda s: [1])


def test_a_study_of_surfaces_gives_its_table():
    st = slc.study(slc.problem("sphere-rotation"), rows=1, columns=1)
    assert st.errors.shape == (1, 1) and st.cells[0]["N"] == 16 and st.cells[0]["K"] == 5
    assert 0 < st.errors[0, 0] < 5e-3
    assert "| 16/5/0.0004 |" in st.table()


def test_self_convergence_of_a_surface_of_ones_own():
    # A sphere of radius 0.5 grown at unit speed to 0.6, with no exact solution given: three
    # resolutions from N 1, K 2, eps 1.6e-2. Measured: order 2.24, the finest run's estimate
    # 1.0e-3 against its error 9.0e-4 at vertices and centroids.
    s = sphere(depth=3, eps=1e-3)
    seen = []
    st = slc.study(s, "unit-normal", 0.1, steps=1, depth=2, eps=1.6e-2,
                   observer=lambda r: seen.append((r["level"], r["N"], r["K"])))
    assert seen == [(0, 1, 2), (1, 2, 3), (2, 4, 4)]
    assert [r["status"] for r in st.runs] == ["ok"] * 3
    assert st.distances.shape == (2,) and st.orders.shape == (1,)
    assert 1.5 < st.orders[0] < 2.5
    final = st.runs[-1]["surface"]
    assert isinstance(final, slc.Surface) and final.time == pytest.approx(0.1)
    v, t = final.vertices, final.triangles
    points = np.vstack([v, v[t].mean(axis=1)])
    error = np.abs(np.linalg.norm(points, axis=1) - 0.6).max()
    assert 0.5 * error < st.estimate["error"] < 3 * error
    with pytest.raises(ValueError, match="3 to 5 resolutions"):
        slc.study(s, "unit-normal", 0.1, rows=2)
    with pytest.raises(ValueError, match="geometry is for curves"):
        slc.study(s, "unit-normal", 0.1, geometry="embedded")


def test_bad_input_to_a_run_of_a_surface_is_refused():
    s = sphere(depth=3, eps=3e-3)
    with pytest.raises(ValueError, match="arcs is for curves"):
        slc.run(s, "rotation", 1.0, arcs=True)
    with pytest.raises(ValueError, match="unknown velocity 'spin'"):
        slc.run(s, "spin", 1.0)
    with pytest.raises(ValueError, match=r"takes an OpenVDB vector grid \(.vdb\), got .f.csv."):
        slc.run(s, slc.FieldFile("f.csv"), 1.0)
    with pytest.raises(ValueError, match="a flow field needs three"):
        slc.run(s, slc.FieldExpression("-y, x"), 1.0)
    with pytest.raises(ValueError, match=r"must return \(m, 3\) velocities"):
        slc.run(s, slc.FlowField(lambda t, p: p[:, :2]), 1.0, steps=1, depth=3)
    with pytest.raises(ValueError, match="must come after"):
        slc.run(slc.Surface(s, time=2.0), "rotation", 1.0)
    with pytest.raises(ValueError, match="sets every run"):
        slc.study(slc.problem("sphere-rotation"), steps=4)
    with pytest.raises(ValueError, match="no convergence study"):
        slc.study(slc.problem("enright"))


def test_a_callable_of_three_arguments_is_called_without_the_curvature():
    # The same rotation as a callable of (t, points, normals) and of (t, points, normals, C):
    # the curvature is not passed, and the surfaces agree to the last bit.
    s = sphere(r=0.3, depth=3, eps=1e-3)
    seen = []

    def three(t, x, n):
        seen.append(n.shape)
        return np.stack([-x[:, 1], x[:, 0], 0 * x[:, 2]], axis=1)

    def four(t, x, n, c):
        return np.stack([-x[:, 1], x[:, 0], 0 * x[:, 2]], axis=1)

    a = slc.run(s, three, 0.2, steps=2, depth=3)
    b = slc.run(s, four, 0.2, steps=2, depth=3)
    assert a.status == b.status == "ok" and seen and all(shape[1] == 3 for shape in seen)
    assert np.array_equal(a.surface.vertices, b.surface.vertices)
    assert np.array_equal(a.surface.triangles, b.surface.triangles)


def test_a_callable_of_two_arguments_moves_a_surface_as_a_flow_field():
    # f(t, points) -> (m, 3) is a FlowField, sampled everywhere: the same surface to the last bit
    # (it used to be called with four arguments, a TypeError).
    s = sphere(r=0.3, depth=3, eps=1e-3)

    def spin(t, x):
        return np.stack([-x[:, 1], x[:, 0], 0 * x[:, 2]], axis=1)

    a = slc.run(s, spin, 0.2, steps=2, depth=3, threads=1)
    b = slc.run(s, slc.FlowField(spin), 0.2, steps=2, depth=3, threads=1)
    assert a.status == b.status == "ok"
    assert np.array_equal(a.surface.vertices, b.surface.vertices)
    assert np.array_equal(a.surface.triangles, b.surface.triangles)
