"""Closed triangle surfaces as numpy arrays, and what moves them: runs, the named problems of
surfaces and their convergence studies, on top of the module _slc (the library's run loop of
surfaces, with the GIL released). ``slc.run`` and ``slc.study`` dispatch here for a Surface or a
SurfaceProblem."""

from __future__ import annotations

import numbers
import warnings
from dataclasses import dataclass, field
from typing import Any, Callable, NamedTuple

import numpy as np

from . import _slc
from ._interface import _AtTime, _points
from ._problem import _NamedProblem
from ._tables import ConvergenceTable, cell_arrays, nan_array as _array


def _vertices(a) -> np.ndarray:
    """a as a C-contiguous float64 (n, 3) array; TypeError or ValueError naming the vertices."""
    return _points(a, "vertices", 3)


def _triangles(a) -> np.ndarray:
    arr = np.asarray(a)
    if arr.dtype.kind not in "iu":
        raise TypeError(f"triangles must hold integer vertex indices, got dtype {arr.dtype}")
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"triangles must be an (m, 3) array, got shape {arr.shape}")
    return np.ascontiguousarray(arr, dtype=np.int64)


def _frozen(a, dtype) -> np.ndarray:
    a = np.asarray(a, dtype=dtype)
    a.flags.writeable = False
    return a


class Surface(_AtTime):
    """A closed triangle surface in space: ``vertices`` (n, 3) and ``triangles`` (m, 3) vertex
    indices, each triangle counterclockwise seen from outside.

    ``Surface(vertices, triangles)`` validates as the tool does its files (closed, manifold, no
    crossings, finite coordinates): a fault raises ValueError with one line naming the triangle,
    edge or vertex; unused vertices are dropped, and a component facing inward is reversed, with
    a warning. Vertices no triangle uses are kept and ignored. ``Surface(slc.contour_surface(...))`` takes the contour's result.
    """

    __slots__ = ("_vertices", "_triangles", "_time")

    def __init__(self, vertices, triangles=None, time: float | None = None):
        if isinstance(vertices, Surface):
            self._vertices, self._triangles = vertices._vertices, vertices._triangles
            self.time = vertices.time if time is None else time
            return
        if triangles is None and isinstance(vertices, tuple) and len(vertices) >= 2:
            vertices, triangles = vertices[0], vertices[1]  # contour_surface's result
        if triangles is None:
            raise TypeError("Surface needs vertices and triangles")
        self.time = 0.0 if time is None else time
        v, t, notes = _slc.prepare_surface(_vertices(vertices), _triangles(triangles))
        for note in notes:
            warnings.warn(note, stacklevel=2)
        self._vertices = _frozen(v, np.float64)
        self._triangles = _frozen(t, np.int64)

    @classmethod
    def _trusted(cls, vertices, triangles, time: float = 0.0) -> "Surface":
        """A surface the library produced, valid already (or empty: a run whose surface
        vanished)."""
        out = cls.__new__(cls)
        out._vertices = _frozen(vertices, np.float64)
        out._triangles = _frozen(triangles, np.int64)
        out.time = time
        return out

    def __reduce__(self):
        return (Surface._trusted, (np.array(self._vertices), np.array(self._triangles),
                                   self.time))

    vertices = property(lambda self: self._vertices, doc="read-only (n, 3) float64 array")
    triangles = property(lambda self: self._triangles,
                         doc="read-only (m, 3) int64 array of vertex indices")

    def _measures(self) -> dict[str, Any]:
        return _slc.surface_measures(self._vertices, self._triangles)

    volume = property(lambda self: self._measures()["volume"],
                      doc="Enclosed volume (inner components subtract).")
    area = property(lambda self: self._measures()["area"], doc="Total area.")
    components = property(lambda self: self._measures()["components"],
                          doc="Connected components.")
    genus = property(lambda self: self._measures()["genus"],
                     doc="Total genus: the handles of all components (0 for spheres, 1 for a "
                         "torus).")

    def __len__(self) -> int:
        """Number of triangles."""
        return len(self._triangles)

    def __repr__(self) -> str:
        return (f"<slc.Surface: {len(self._triangles)} triangles, {len(self._vertices)} "
                f"vertices, t = {self.time:g}>")

    @classmethod
    def load(cls, path, time: float = 0.0) -> "Surface":
        """Reads a surface file (.obj, .stl ASCII or binary, .ply, or .vdb: see
        :meth:`from_vdb`), validated as ``slc run --initial`` does."""
        v, t, notes = _slc.load_surface(str(path))
        for note in notes:
            warnings.warn(f"{path}: {note}", stacklevel=2)
        return cls._trusted(v, t, time)

    def save(self, path) -> None:
        """Writes the surface as .obj (17 significant digits) or .vtp (for ParaView, with
        ``.time``), by the extension."""
        _slc.save_surface(str(path), self._vertices, self._triangles, self.time)

    @classmethod
    def from_vdb(cls, path, grid: str | None = None, depth: int | None = None,
                 time: float = 0.0) -> "Surface":
        """Reads the zero set of a level-set grid (class level set, float or double) of an
        OpenVDB file: the first such grid, or the one named ``grid``. slc contours the grid's
        trilinear interpolant at the depth whose cells are about a voxel wide (or ``depth``) and
        validates the result as :meth:`load` does. A file that is not OpenVDB, truncated, or
        without such a grid or zero crossing is a ValueError naming it."""
        v, t, notes = _slc.load_vdb(str(path), grid or "", depth)
        for note in notes:
            warnings.warn(f"{path}: {note}", stacklevel=2)
        return cls._trusted(v, t, time)

    def to_vdb(self, path, voxel: float, half_width: float = 3.0, name: str = "surface") -> None:
        """Writes the surface as an OpenVDB narrow-band level set: one FloatGrid ``name`` of
        class level set with voxels of size ``voxel``, holding the exact signed distance
        (negative inside) at the voxel centres within ``half_width`` voxels of the surface."""
        _slc.save_vdb(str(path), self._vertices, self._triangles, float(voxel),
                      float(half_width), name)


def _surface(x) -> Surface:
    return x if isinstance(x, Surface) else Surface(x)


class SurfaceProblem(_NamedProblem):
    """A named problem of surfaces (``slc.problem("sphere-rotation")``): initial surface, law,
    final time, settings and the exact solution where it is known; ``slc.run(problem)`` runs it
    as ``slc run --problem NAME`` does."""

    __slots__ = ()
    _make = staticmethod(_slc.make_surface_problem)
    _kind = "SurfaceProblem"

    settings = property(lambda self: dict(self._p.settings),
                        doc="its steps N, depth K, refine P and eps")

    @property
    def surface(self) -> Surface:
        """The initial surface."""
        v, t = self._p.initial
        return Surface._trusted(v, t, 0.0)

    def exact(self, points, t: float) -> np.ndarray | None:
        """A signed function of the (m, 3) points whose zero set is the exact surface at time t
        (the exact signed distance where it is simple), or None where it is not known; a point
        not finite or beyond the coordinate limit (±1e100) raises ValueError naming it."""
        return self._p.exact(_vertices(points), float(t))

    def error(self, surface) -> float | None:
        """The largest |exact| over the surface's vertices and triangle centroids at its time;
        None where the exact surface is not known."""
        s = _surface(surface)
        return self._p.error(s._vertices, s._triangles, s.time)


class Step(NamedTuple):
    """What an observer of run() sees after each step, for curves and surfaces alike."""

    step: int  #: 1..steps
    steps: int  #: N
    t: float  #: the time reached
    interface: Any  #: the curves (Interface) or the surface (Surface) at t
    cpu_s: float  #: CPU seconds of this step

    @property
    def surface(self):
        """The interface, by the name a run of a surface gives it."""
        return self.interface


SurfaceStep = Step  # the name surfaces' observers had; one type for both dimensions


@dataclass(kw_only=True)
class _RunEnd:
    """How a run ended, for curves and surfaces alike: ``status`` is "ok", "vanished",
    "interrupted" (Ctrl-C, or an observer returned False), "error", "unstable" (a step broke what
    the law keeps — area or volume, parts, shape, rate — even in sub-steps of 1/256 of a step,
    1/16 for a surface) or, with
    guards=False, "broken" (the run reached its end, but a step broke what the law keeps);
    ``message`` says why, naming the time. ``history``: per-step arrays; ``summary``: the keys
    of summary.json."""

    status: str
    t: float
    history: dict[str, np.ndarray]
    summary: dict[str, Any] = field(default_factory=dict)
    message: str = ""

    @property
    def e_inf(self) -> float | None:
        """The error at the end where the exact solution is known: Eq. (11) for curves (the
        largest |exact distance| over vertices and segment midpoints), the largest |exact| over
        vertices and centroids for a surface; None otherwise."""
        return self.summary.get("e_inf")


@dataclass(kw_only=True)
class SurfaceRunResult(_RunEnd):
    """How a run of a surface ended (see RunResult); a law that keeps the volume also ends
    "unstable" when the volume drifted by more than volume_drift, 1% unless set."""

    surface: Surface
    frames: list[tuple[float, Surface]] = field(default_factory=list)


def _check_frames(frames) -> None:
    """TypeError unless frames (the frames a run keeps) is an integer."""
    if isinstance(frames, bool) or not isinstance(frames, numbers.Integral):
        raise TypeError(f"frames must be an integer, got {frames!r}")


def _run_end(out: dict, stacklevel: int) -> dict[str, Any]:
    """How a run ended, from the module's answer: status, t, history, summary and message, as a
    RunResult and a SurfaceRunResult take them. Warns (UserWarning) what the command line notes
    on stderr: the summary's note (contours left beyond eps, a part split off thinner than the
    cells without thin cells), a step taken again with deeper thin cells (thin_deeper) or kept
    at shallower ones where parts met (thin_shallower), and with guards=False the first break;
    stacklevel: as warnings.warn's, the caller's frame being 2."""
    summary = out["summary"]
    if "note" in summary:
        warnings.warn(summary["note"], stacklevel=stacklevel)
    if "thin_deeper" in summary:
        d = summary["thin_deeper"]
        warnings.warn(f"{d['why']}: a part thinner than the contours resolved, kept by deeper "
                      f"thin cells, up to {d['depth']} levels deep, in {d['steps']} of the "
                      "run's steps", stacklevel=stacklevel)
    if "thin_shallower" in summary:
        d = summary["thin_shallower"]
        warnings.warn(f"{d['why']}: deeper thin cells made holes or handles that neither the "
                      f"step's start nor shallower cells had (as where parts meet), and "
                      f"{d['substeps']} sub-step{'' if d['substeps'] == 1 else 's'} kept the "
                      f"shallower cells that made none, down to {d['depth']} "
                      f"level{'' if d['depth'] == 1 else 's'}", stacklevel=stacklevel)
    if out["status"] == "broken":
        warnings.warn(f"guards=False: {out['message']}", stacklevel=stacklevel)
    return {k: out[k] for k in ("status", "t", "history", "summary", "message")}


def run_surface(p, options, frames: int, observer: Callable[[Step], Any] | None,
                threads: int, estimate: bool = False) -> SurfaceRunResult:
    """Runs the _slc.SurfaceProblem p with the settings `options` (a _slc.RunOverrides: steps,
    depth, refine, eps, eta, thin_depth, area_correction: the volume correction, volume_drift:
    the fraction of the volume a law that keeps it may drift before the run ends "unstable",
    guards: False to go on to the end through steps that break what the law keeps, status
    "broken"); estimate: run it again at half resolution and add summary["error_estimate"]."""
    _check_frames(frames)
    on_step = None
    if observer is not None:
        def on_step(step, n, t, v, tri, cpu_s):
            return observer(Step(step, n, t, Surface._trusted(v, tri, t), cpu_s))
    out = _slc.run_surface(p, options, int(frames), threads, on_step,
                           bool(estimate))
    return SurfaceRunResult(
        surface=Surface._trusted(out["vertices"], out["triangles"], out["t"]),
        frames=[(t, Surface._trusted(v, tri, t)) for t, v, tri in out["frames"]],
        **_run_end(out, stacklevel=4),
    )


@dataclass
class SurfaceStudy(ConvergenceTable):
    """The convergence table of a problem of surfaces: row r runs N·2^r steps at depth K + r
    with eps/4^r, columns P = 0, 1, ... passes of refinement.

    ``cells``: one dict per run (row, P, N, K, eps, status, e_inf, cpu_s_per_step, wall_s,
    triangles), row-major. ``errors`` and ``cpu_s_per_step``: rows x columns arrays (NaN where a
    run has no error). ``row_orders`` (rows x columns-1) and ``column_orders`` (rows-1 x
    columns): log2 of the error ratios of neighbours."""

    def table(self) -> str:
        """The errors as a Markdown table, a row per N/K/eps and a column per P."""
        return self._markdown(lambda c: f"{c['N']}/{c['K']}/{c['eps']:.2g}")


def study_surface(problem: SurfaceProblem, rows: int, columns: int,
                  observer: Callable[[dict], Any] | None, threads: int) -> SurfaceStudy:
    s = _slc.study_surface(problem._p, rows, columns, threads, observer)
    rows, columns = s["rows"], s["columns"]
    return SurfaceStudy(
        **cell_arrays(s),
        row_orders=np.array([_array(r) for r in s["row_orders"]]).reshape(rows, columns - 1),
        column_orders=np.array([_array(r) for r in s["column_orders"]]).reshape(rows - 1, columns),
    )
