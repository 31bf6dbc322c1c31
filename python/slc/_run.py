"""Moving curves: velocity laws from Python, runs, the paper's named problems and convergence
studies, on top of the module _slc (the library's run loop, with the GIL released)."""

from __future__ import annotations

import inspect
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from . import _slc
from ._interface import Interface, _integer, _interface, _points, _refine, _threads
from ._problem import _NamedProblem
from ._tables import ConvergenceTable, cell_arrays, nan_array as _array
from ._surface import (Step, Surface, SurfaceProblem, SurfaceRunResult, SurfaceStudy,
                       _check_frames, _run_end, _RunEnd, run_surface, study_surface)


class FlowField:
    """A velocity field f(t, points (m, 2)) -> (m, 2) known everywhere, so that the step samples
    it along each characteristic (fourth-order Runge–Kutta to ε/10, one contour per step) instead of
    extending vertex velocities. f is called once per batch and stage. A callable of two
    arguments given as a velocity is taken as one (FlowField(f, name) gives it a name)."""

    def __init__(self, f: Callable[[float, np.ndarray], Any], name: str | None = None):
        if not callable(f):
            raise TypeError(f"FlowField needs a callable f(t, points), got {type(f).__name__}")
        self.f = f
        self.name = name or getattr(f, "__name__", "flow-field")


class NormalSpeed:
    """A normal speed f(t, points (m, 2), normals (m, 2)) -> (m,) known off the curve (u = v N,
    v > 0 outward), such as a speed that depends on position, time and direction but not on
    curvature. The step evaluates it where it needs it, with the normal of the distance field
    (the direct extension), so offsets and corners move exactly; f is called once per batch."""

    def __init__(self, f: Callable[[float, np.ndarray, np.ndarray], Any], name: str | None = None):
        if not callable(f):
            raise TypeError(
                f"NormalSpeed needs a callable f(t, points, normals), got {type(f).__name__}")
        self.f = f
        self.name = name or getattr(f, "__name__", "normal-speed")


class _Expression:
    """Text for muparser with named constants; the subclass says which law it is."""

    kind = ""

    def __init__(self, text: str, **constants: float):
        if not isinstance(text, str):
            raise TypeError(f"{type(self).__name__} needs a string, got {type(text).__name__}")
        self.text = text
        self.constants = {k: float(v) for k, v in constants.items()}


class SpeedExpression(_Expression):
    """A normal speed typed as text, as ``slc run --speed``: v(x, y, t, C, nx, ny) with
    muparser's operators and functions and the named constants given
    (``SpeedExpression("a + C", a=0.5)``); v > 0 moves outward, C = -1/R on a circle. Without C
    it is evaluated off the curve as a NormalSpeed is; with C it takes curvature defaults.
    Moving a surface it reads z and nz too, and C is the mean curvature (-2/R on a sphere)."""

    kind = "speed"


class FieldExpression(_Expression):
    """A flow field typed as text, as ``slc run --field``: "U, V" in x, y, t and the named
    constants (``FieldExpression("-y, x")``), sampled along the characteristics; moving a
    surface, "U, V, W" in x, y, z, t (``FieldExpression("-y, x, 0")``)."""

    kind = "field"


class FieldFile:
    """A steady flow field sampled on a uniform grid, as ``slc run --field-file``: for curves CSV
    lines x,y,u,v or legacy VTK STRUCTURED_POINTS, interpolated bilinearly; for a surface an
    OpenVDB vector grid (.vdb), interpolated trilinearly. outside="error" (the default): a run
    that leaves the grid (the box of a VDB grid's active voxels) ends with status "error";
    outside="zero": the field is zero there, and what leaves the grid stops (``slc run
    --field-outside zero``)."""

    def __init__(self, path, outside: str = "error"):
        if outside not in ("error", "zero"):
            raise ValueError(f"FieldFile: outside must be 'error' or 'zero', got {outside!r}")
        self.path = str(path)
        self.outside = outside


@dataclass(kw_only=True)
class RunResult(_RunEnd):
    """How a run of curves ended: status, t, history, summary, message and e_inf as every run
    has them, the final curves and the frames kept."""

    interface: Interface
    frames: list[tuple[float, Interface]] = field(default_factory=list)


class Problem(_NamedProblem):
    """One of the paper's experiments or a standard benchmark (``slc.problem(name)``): initial
    curves, law, final time and the paper's settings, and the exact solution where one is known.
    ``slc.run(problem)`` runs it as ``slc run --problem NAME`` does."""

    __slots__ = ()
    _make = staticmethod(_slc.make_problem)
    _kind = "Problem"

    params = property(lambda self: dict(self._p.velocity_params), doc="the law's parameters")
    parameters = property(lambda self: dict(self._p.parameters),
                          doc="the problem's own parameters (R0, tilt, ...), in use")

    @property
    def settings(self) -> dict[str, Any]:
        """The paper's settings: steps N, depth K, refine P, eps, eta, smoothing S."""
        p = self._p
        refine = p.refine if p.refine == "converged" else int(p.refine)
        return {"steps": p.steps, "depth": p.depth, "refine": refine, "eps": p.eps,
                "eta": p.eta, "smoothing": p.smoothing}

    @property
    def interface(self) -> Interface:
        """The initial curves, at the problem's initial time."""
        return Interface._trusted(self._p.initial, self._p.t_start)

    def exact(self, points, t: float) -> np.ndarray | None:
        """The exact signed distance to the curves at time t at each of the (m, 2) points, or
        None where the exact solution is not known; points are checked as distance() checks
        them."""
        return self._p.exact(_points(points, "points"), float(t))

    def error(self, interface) -> float | None:
        """The paper's Eq. (11) error of curves at their time: the largest |exact distance| over
        their vertices and segment midpoints; None where the exact solution is not known."""
        curves = _interface(interface)
        return self._p.error(curves._curves, curves.time)


def problem(name: str, **params: float) -> Problem | SurfaceProblem:
    """The named problem with its own or its law's parameters set (``tilt=10``, ``omega=2``), as
    ``slc run --problem NAME --param k=v``: a Problem of curves, or a SurfaceProblem for a
    problem of surfaces (``sphere-rotation``, ``enright``, ...); ValueError for an unknown name
    or parameter."""
    if name in dict(_slc.surface_problems()):
        return SurfaceProblem(name, params)
    return Problem(name, params)


def problems() -> dict[str, str]:
    """The named problems, of curves and of surfaces, each with one line saying what it is."""
    return dict(_slc.problems()) | dict(_slc.surface_problems())


def velocities(dimension: int = 2) -> list[str]:
    """The built-in velocity laws' names: of curves (dimension 2) or of surfaces (3)."""
    if dimension == 3:
        return list(_slc.surface_velocity_names())
    if dimension != 2:
        raise ValueError(f"dimension must be 2 or 3, got {dimension}")
    return list(_slc.velocity_names())


def _positional_parameters(f) -> tuple[int, int | None] | None:
    """(required, most): how many positional arguments f needs and takes at most (None: any
    number), or None when its signature cannot be read."""
    try:
        signature = inspect.signature(f)
    except (TypeError, ValueError):
        return None
    required, most = 0, 0
    for p in signature.parameters.values():
        if p.kind == p.VAR_POSITIONAL:
            most = None
        elif p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD):
            required += p.default is p.empty
            if most is not None:
                most += 1
    return required, most


def _callable_kind(f) -> str:
    """The kind of law a callable velocity is, by the arguments it takes: f(t, points) a flow
    field, f(t, points, normals) a law of vertices without the curvature, otherwise (four, or a
    signature that cannot be read) f(t, points, normals, curvature)."""
    arguments = _positional_parameters(f)
    if arguments is None:
        return "curve"
    required, most = arguments
    if required > 4 or (most is not None and most < 2):
        raise TypeError(
            f"a velocity callable takes (t, points), (t, points, normals) or (t, points, normals, "
            f"curvature), got {getattr(f, '__name__', type(f).__name__)}{inspect.signature(f)}")
    if most == 2:
        return "flow-field"  # it cannot take normals: a field known everywhere
    if required == 3 or most == 3:
        return "vertex-no-curvature"
    return "curve"


def _law(velocity, params, geometry):
    """The _slc.LawSpec of a velocity argument."""
    params = {k: float(v) for k, v in (params or {}).items()}
    if isinstance(velocity, FlowField):
        return _slc.LawSpec(velocity.f, "flow-field", velocity.name, params, geometry)
    if isinstance(velocity, _Expression):
        if params:
            raise ValueError("an expression's constants go to the expression itself: "
                             "SpeedExpression(text, a=0.5)")
        return _slc.LawSpec(velocity.text, velocity.kind, velocity.text, velocity.constants,
                            geometry)
    if isinstance(velocity, FieldFile):
        return _slc.LawSpec(velocity.path, "field-file", velocity.path, params, geometry,
                            zero_outside=velocity.outside == "zero")
    if isinstance(velocity, NormalSpeed):
        return _slc.LawSpec(velocity.f, "normal", velocity.name, params, geometry)
    if isinstance(velocity, str):
        return _slc.LawSpec(velocity, "builtin", velocity, params, geometry)
    if callable(velocity):
        # f(t, points) is sampled as a FlowField is; f(t, points, normals) takes no curvature,
        # which is then not computed for a surface (a Gaussian mean over the vertices within a
        # few sqrt(k)).
        return _slc.LawSpec(velocity, _callable_kind(velocity),
                            getattr(velocity, "__name__", "python"), params, geometry)
    raise TypeError("velocity must be a law's name, a FlowField, a NormalSpeed or a callable "
                    "f(t, points), f(t, points, normals) or f(t, points, normals, curvature), got "
                    f"{type(velocity).__name__}")


def _overrides(steps=None, depth=None, refine=None, eps=None, eta=None, smoothing=None,
               extension=None, arcs=None, area_correction=None, thin_depth=None,
               volume_drift=None, guards=None, until_components=None):
    """The settings given, as the library's RunOverrides: it checks their ranges and refuses those
    of the other dimension (ValueError naming them)."""
    o = _slc.RunOverrides()
    o.steps = _integer("steps", steps)
    o.depth = _integer("depth", depth)
    o.refine = None if refine is None else _refine(refine)
    o.eps = None if eps is None else float(eps)
    o.eta = None if eta is None else float(eta)
    o.smoothing = _integer("smoothing", smoothing)
    o.extension = extension
    o.arcs = None if arcs is None else bool(arcs)
    o.area_correction = None if area_correction is None else bool(area_correction)
    o.thin_depth = _integer("thin_depth", thin_depth)
    if isinstance(volume_drift, bool):
        raise TypeError(f"volume_drift must be a number, got {volume_drift!r}")
    o.volume_drift = None if volume_drift is None else float(volume_drift)
    if guards is not None and not isinstance(guards, bool):
        raise TypeError(f"guards must be True or False, got {guards!r}")
    o.guards = guards
    left = _integer("until_components", until_components)
    if left is not None and left < 1:
        raise ValueError(f"until_components must be 1 or more, got {until_components}")
    o.until_components = left
    return o


def _law_params(velocity, params, keywords, caller: str = "run") -> dict | None:
    """params with a built-in law's parameters given as keywords to run() (``omega=2``), as one
    dict for the library to check against the law's parameters (ValueError naming the one it
    lacks, and those it has). A keyword for any other velocity, or one also in params, is
    ValueError naming it."""
    if not keywords:
        return params
    k = sorted(keywords)[0]
    if velocity is not None and not isinstance(velocity, str):
        raise ValueError(f"{caller}() has no option '{k}': its other keywords are a built-in law's "
                         f"parameters, and the velocity {type(velocity).__name__} is not one")
    twice = sorted(set(keywords) & set(params or {}))
    if twice:
        raise ValueError(f"parameter '{twice[0]}' is given twice, in params and as a keyword")
    return {**(params or {}), **keywords}


def _subject(subject, velocity, t_end, params, geometry):
    """(_slc.Problem, LawSpec or None) for a Problem or for curves under a velocity."""
    if isinstance(subject, Problem):
        if velocity is not None or params or geometry is not None:
            raise ValueError("a named problem runs its own law: set its parameters with "
                             "slc.problem(name, **params)")
        return subject._fresh(t_end), None
    curves = _interface(subject)
    if velocity is None:
        raise TypeError("run needs a velocity: a law's name, a FlowField, a NormalSpeed or a "
                        "callable")
    if t_end is None:
        raise TypeError("run needs t_end, the final time")
    law = _law(velocity, params, geometry)
    return _slc.curve_problem(curves._curves, curves.time, float(t_end), law), law


def _surface_subject(subject, velocity, t_end, params):
    """The _slc.SurfaceProblem of a SurfaceProblem or of a Surface under a velocity."""
    if isinstance(subject, SurfaceProblem):
        if velocity is not None or params:
            raise ValueError("a named problem runs its own law: set its parameters with "
                             "slc.problem(name, **params)")
        return subject._fresh(t_end)
    if velocity is None:
        raise TypeError("run needs a velocity: a law's name, a FlowField, a NormalSpeed or a "
                        "callable")
    if t_end is None:
        raise TypeError("run needs t_end, the final time")
    return _slc.user_surface_problem(subject.vertices, subject.triangles, subject.time,
                                     float(t_end), _law(velocity, params, None))


# The settings of a run that run() and study() take by name: the rest of study's keywords are a
# law's parameters.
_SETTINGS = set(inspect.signature(_overrides).parameters)


def run(interface, velocity=None, t_end: float | None = None, *, steps: int | None = None,
        depth: int | None = None, refine=None, eps: float | None = None,
        eta: float | None = None, smoothing: int | None = None,
        params: dict[str, float] | None = None, geometry: str | None = None,
        extension: str | None = None, arcs: bool | None = None,
        area_correction: bool | None = None, thin_depth: int | None = None,
        volume_drift: float | None = None, guards: bool | None = None,
        until_components: int | None = None, frames: int = 0,
        observer: Callable[[Step], Any] | None = None, threads: int | None = None,
        estimate: bool = False, **law_params: float) -> RunResult:
    """Moves curves from interface.time to t_end, as ``slc run --initial`` does, or runs a named
    problem (``run(slc.problem("zalesak"))``, t_end optional) as ``slc run --problem`` does. A
    Surface (or a SurfaceProblem) moves the same way and gives a SurfaceRunResult; its velocity
    takes (m, 3) arrays, the options of curves alone (smoothing, geometry, extension, arcs) are
    refused, area_correction turns the volume correction on or off, and thin_depth (as
    ``--thin-depth``; a named problem's own, for a user's shape 6 for curves (2 under a speed that
    depends on the normal) and 2 for a surface)
    splits cells up to that many levels beyond K where a part thinner than a
    cell lies; volume_drift (surfaces only, as ``--volume-drift``) is the fraction of its volume a
    surface under a law that keeps it may drift before the run ends "unstable" (0.01 unless set);
    guards=False (as ``--no-guards``, curves and surfaces) takes every step whole and goes on to the
    end even when one breaks what the law keeps, to see what a coarse run gives: the result's
    status is then "broken", its message names the first break, and a UserWarning says so.
    until_components (as ``--until-components``) ends the run, status "ok", once at most that many
    components are left (particles: outer curves; a surface's connected components), t_end then
    the latest time.

    velocity: a built-in law's name (``velocities()``; its parameters as keywords,
    ``run(I, "rotation", 1.0, omega=2)``, or in params), a FlowField, a
    NormalSpeed, or a callable. A callable f(t, points (m, 2)) -> (m, 2) is a flow field, sampled
    everywhere as a FlowField is; f(t, points (N, 2), normals (N, 2), curvature (N,)) (or
    f(t, points, normals), without the curvature) returns (N, 2) vertex velocities or (N,) normal
    speeds v (u = v N, v > 0 outward), called once per stage with all vertices and extended off
    the curve from the nearest point, as a curvature law is. Vertex velocities that do not depend
    on the normals belong in f(t, points): a rotation so written comes back to 1.2e-4 after a
    full turn of an ellipse 1 x 0.6, written with normals to 2.3e-2.

    Unset options take the tool's defaults (docs/defaults.md), or the problem's: steps N, depth K
    (eps follows as 10^-K times the curves' half-width unless given), refine P (passes or
    "converged"), eps, eta, smoothing S; geometry "intrinsic", "embedded" or "arclength";
    extension "nearest", "whitney" or "direct"; arcs; area_correction. frames: keep this many
    frames besides the initial one, at evenly spaced times (a run of your own without steps
    takes a multiple of them; a named problem keeps its steps). observer(step) after each step returns True or None to go
    on, False to stop the run (status "interrupted"), as Ctrl-C does in the tool; anything else
    is a TypeError. threads: worker threads (None or 0: OMP_NUM_THREADS when set, else every
    available core; never more than the cores), as the tool's --threads; results do not depend
    on it, and ``summary`` reports it.
    estimate: as ``slc run --estimate``, run again at half resolution (N/2 steps, K − 1, 4 eps)
    and put the distance between the two final interfaces in ``summary["error_estimate"]`` (an
    estimate of this run's error when it converges at first order or faster; a note says why
    there is none).
    """
    options = _overrides(steps, depth, refine, eps, eta, smoothing, extension, arcs,
                         area_correction, thin_depth, volume_drift, guards, until_components)
    params = _law_params(velocity, params, law_params)
    threads = _threads(threads)
    if isinstance(interface, (Surface, SurfaceProblem)):
        if geometry is not None:
            raise ValueError("geometry is for curves, not surfaces")
        p = _surface_subject(interface, velocity, t_end, params)
        return run_surface(p, options, frames, observer, threads, estimate)
    p, law = _subject(interface, velocity, t_end, params, geometry)
    _check_frames(frames)

    on_step = None
    if observer is not None:
        def on_step(step, n, t, arrays, cpu_s):
            return observer(Step(step, n, t, Interface._trusted(arrays, t), cpu_s))

    out = _slc.run(p, law, options, int(frames), threads, on_step, bool(estimate))
    return RunResult(
        interface=Interface._trusted(out["curves"], out["t"]),
        frames=[(t, Interface._trusted(a, t)) for t, a in out["frames"]],
        **_run_end(out, stacklevel=3),
    )


@dataclass
class Study(ConvergenceTable):
    """The paper's convergence table (§4.2, Tables 5–7) of a problem with an exact solution: row
    r runs N·2^r steps at depth K + r with eps/10^r, columns P = 0..4.

    ``cells``: one dict per run (row, P, run, N, K, eps, S, status, e_inf, cpu_s_per_step,
    g_evals_per_vertex, segments), row-major. ``errors`` and ``cpu_s_per_step``: rows x columns
    arrays (NaN where a run has no error). ``row_orders`` (rows x columns-1): log2 of the error
    ratio of neighbouring columns, about 1 while refinement controls the error;
    ``column_orders`` (rows-1 x columns): of neighbouring rows, about 2 at P = 4 (second order
    in time)."""

    def table(self) -> str:
        """The errors as a Markdown table, a row per N/S/K/eps and a column per P."""
        return self._markdown(lambda c: f"{c['N']}/{c['S']}/{c['K']}/{c['eps']:.0e}")


@dataclass
class SelfConvergence:
    """Runs of the same curves or surface and law at successive resolutions (N doubled, K + 1,
    eps/4 each), for motions without an exact solution: ``runs`` (curves: level, run, status, t,
    area, components, segments, cpu_s, interface; a surface: level, run, N, K, eps, status,
    message, t, volume, area, components, genus, unconverged_steps, largest_residual, cpu_s,
    surface), ``distances`` between the final interfaces of neighbours (vertices and segment
    midpoints, or triangle centroids), ``orders`` observed from them (log2 of successive
    distance ratios) and ``estimate`` of the finest run's error (a dict: error, order, observed)
    or None."""

    runs: list[dict[str, Any]]
    distances: np.ndarray
    orders: np.ndarray
    estimate: dict[str, Any] | None


def study(subject, velocity=None, t_end: float | None = None, *, rows: int | None = None,
          observer: Callable[[dict], Any] | None = None, threads: int | None = None,
          params: dict[str, float] | None = None, geometry: str | None = None,
          **options) -> Study | SelfConvergence | SurfaceStudy:
    """A convergence study, as ``slc study`` does.

    For a Problem with an exact solution: the paper's table (``Study``) of ``rows`` rows (1..5,
    default 5) by P = 0..4. For a SurfaceProblem with a study (sphere-rotation,
    sphere-curvature, merging-spheres): ``SurfaceStudy`` of ``rows`` (default 3) by ``columns``
    (default 4) runs, as ``slc study --problem`` on a surface. For curves or a Surface under a
    velocity to t_end: a self-convergence study (``SelfConvergence``) at ``rows`` resolutions
    (3..5, default 3), as ``slc study --initial``. options are run()'s (steps, depth, refine,
    eps, eta, smoothing, extension, arcs, area_correction; for a surface steps, depth, refine,
    eps, eta, thin_depth, area_correction, volume_drift, guards) and set the coarsest run; other
    keywords are a built-in law's parameters, as for run(). observer(dict) after each run.
    """
    threads = _threads(threads)
    if isinstance(subject, SurfaceProblem):
        if velocity is not None or t_end is not None or params or geometry is not None or (
                set(options) - {"columns"}):
            raise ValueError("the study of a surface problem sets every run: give rows, "
                             "columns, observer and threads only")
        return study_surface(subject, 3 if rows is None else _integer("rows", rows),
                             _integer("columns", options.get("columns", 4)), observer, threads)
    params = _law_params(velocity, params,
                         {k: v for k, v in options.items() if k not in _SETTINGS}, "study")
    options = {k: v for k, v in options.items() if k in _SETTINGS}
    if isinstance(subject, Surface):
        if geometry is not None:
            raise ValueError("geometry is for curves, not surfaces")
        p = _surface_subject(subject, velocity, t_end, params)
        on_surface_run = None
        if observer is not None:
            def on_surface_run(r):
                return observer(_surface_run_dict(r))
        s = _slc.self_convergence_surface(p, 3 if rows is None else _integer("rows", rows),
                                          _overrides(**options), threads,
                                          on_surface_run)
        return SelfConvergence(
            runs=[_surface_run_dict(r) for r in s["runs"]],
            distances=np.array(s["distances"], dtype=float),
            orders=_array(s["orders"]),
            estimate=s["estimate"],
        )
    p, law = _subject(subject, velocity, t_end, params, geometry)
    o = _overrides(**options)
    if isinstance(subject, Problem):
        s = _slc.study(p, 5 if rows is None else _integer("rows", rows), o, threads,
                       observer)
        return Study(
            **cell_arrays(s),
            row_orders=np.array([_array(r) for r in s["row_orders"]]),
            column_orders=np.array([_array(r) for r in s["column_orders"][:-1]]).reshape(
                s["rows"] - 1, s["columns"]),
        )
    on_run = None
    if observer is not None:
        def on_run(r):
            return observer(_run_dict(r))
    s = _slc.self_convergence(p, law, 3 if rows is None else _integer("rows", rows), o,
                              threads, on_run)
    return SelfConvergence(
        runs=[_run_dict(r) for r in s["runs"]],
        distances=np.array(s["distances"], dtype=float),
        orders=_array(s["orders"]),
        estimate=s["estimate"],
    )


def _surface_run_dict(r: dict) -> dict:
    r = dict(r)
    r["surface"] = Surface._trusted(r.pop("vertices"), r.pop("triangles"), r["t"])
    return r


def _run_dict(r: dict) -> dict:
    r = dict(r)
    r["interface"] = Interface._trusted(r.pop("curves"), r["t"])
    return r
