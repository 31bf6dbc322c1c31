"""Curves as numpy arrays: the Interface, exact distances, and the contour of a function."""

from __future__ import annotations

import math
import numbers
import warnings
from typing import Any, Callable

import numpy as np

from . import _slc

def _points(a, what: str, dim: int = 2) -> np.ndarray:
    """a as a C-contiguous float64 (n, dim) array; TypeError or ValueError naming `what`."""
    arr = np.asarray(a)
    if arr.dtype.kind not in "iuf":
        raise TypeError(f"{what} must hold real numbers, got dtype {arr.dtype}")
    if arr.ndim != 2 or arr.shape[1] != dim:
        raise ValueError(f"{what} must be an (n, {dim}) array, got shape {arr.shape}")
    return np.ascontiguousarray(arr, dtype=np.float64)


def _time(value) -> float:
    """value as the time of an Interface or a Surface: ValueError unless a finite number (the
    tool's files refuse any other)."""
    t = float(value)
    if not math.isfinite(t):
        raise ValueError(f"time must be finite, got {t}")
    return t


def _frozen(arrays) -> list[np.ndarray]:
    out = []
    for a in arrays:
        a = np.asarray(a, dtype=np.float64)
        a.flags.writeable = False
        out.append(a)
    return out


def _is_one_curve(curves) -> bool:
    """Whether curves is one curve rather than a list of them: a 2D array-like of numbers whose
    last dimension is 2 (an (n, 2) array, or a list of [x, y] points). A list of curves makes a
    3D array, or none at all when their lengths differ."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # numpy's warning of a ragged list of curves
            arr = np.asarray(curves)
    except (ValueError, TypeError):
        return False
    return arr.ndim == 2 and arr.shape[1] == 2 and arr.dtype.kind in "iuf"


class _AtTime:
    """A shape at a time: the time property both Interface and Surface have."""

    @property
    def time(self) -> float:
        """The time the shape is at, where a run starts; setting it (or giving it to the
        constructor) to NaN or ±inf raises ValueError."""
        return self._time

    @time.setter
    def time(self, value) -> None:
        self._time = _time(value)


class Interface(_AtTime):
    """Closed curves in the plane, each an (n, 2) array of its vertices (the closing segment
    implicit), counterclockwise around their inside, holes clockwise.

    ``Interface(curves)`` validates as the tool does its files: an open or self-crossing curve,
    curves that cross, fewer than 3 distinct points, a non-finite coordinate raise ValueError with
    one line naming the curve and vertex; consecutive duplicate points are dropped; a curve the
    other way round is reversed, with a warning. One (n, 2) array, or one list of [x, y] points
    (``Interface([[0, 0], [1, 0], [0, 1]])``), is one curve; a list of them is many.
    """

    __slots__ = ("_curves", "_time")

    def __init__(self, curves, time: float | None = None):
        if isinstance(curves, Interface):
            self._curves = curves._curves
            self.time = curves.time if time is None else time
            return
        if isinstance(curves, (str, bytes)) or not hasattr(curves, "__iter__"):
            raise TypeError(f"curves must be a list of (n, 2) arrays, got {type(curves).__name__}")
        if _is_one_curve(curves):
            curves = [curves]
        self.time = 0.0 if time is None else time
        arrays = [_points(c, f"curve {i}") for i, c in enumerate(curves)]
        prepared, notes = _slc.prepare(arrays)
        for note in notes:
            warnings.warn(note, stacklevel=2)
        self._curves = _frozen(prepared)

    def __reduce__(self):
        """Pickled (for dask workers, multiprocessing) as the trusted arrays and the time."""
        return (Interface._trusted, ([np.array(c) for c in self._curves], self.time))

    @classmethod
    def _trusted(cls, arrays, time: float = 0.0) -> "Interface":
        """Curves the library produced, valid already (or none: a run whose curves vanished)."""
        out = cls.__new__(cls)
        out._curves = _frozen(arrays)
        out.time = time
        return out

    @property
    def curves(self) -> list[np.ndarray]:
        """The curves, each a read-only (n, 2) float64 array."""
        return list(self._curves)

    @property
    def area(self) -> float:
        """Enclosed area: holes subtract."""
        return _slc.area(self._curves)

    @property
    def length(self) -> float:
        """Total length of all curves."""
        return _slc.length(self._curves)

    @property
    def points(self) -> np.ndarray:
        """All vertices, curve after curve, as one (N, 2) array."""
        if not self._curves:
            return np.empty((0, 2))
        return np.concatenate(self._curves)

    def __len__(self) -> int:
        """Number of curves."""
        return len(self._curves)

    def __repr__(self) -> str:
        n = sum(len(c) for c in self._curves)
        return f"<slc.Interface: {len(self._curves)} curves, {n} vertices, t = {self.time:g}>"

    @classmethod
    def load(cls, path) -> "Interface":
        """Reads an interface file ({"time": t, "curves": [{"points": [[x, y], ...]}, ...]}),
        validated as ``slc run --initial`` does; its time becomes ``.time``."""
        arrays, time, notes = _slc.load(str(path))
        for note in notes:
            warnings.warn(f"{path}: {note}", stacklevel=2)
        return cls._trusted(arrays, time)

    def save(self, path) -> None:
        """Writes the interface file the tool reads, with ``.time`` and 17 significant digits."""
        _slc.save(str(path), self._curves, self.time)


def _interface(x) -> Interface:
    return x if isinstance(x, Interface) else Interface(x)


def _query_points(points, dim: int) -> tuple[np.ndarray, tuple[int, ...]]:
    """points, one point (dim,) or any array (..., dim) of them, as a float64 (m, dim) array and
    the shape the answers take (points.shape without its last dimension); ValueError naming the
    shape otherwise."""
    arr = np.asarray(points)
    if arr.dtype.kind not in "iuf":
        raise TypeError(f"points must hold real numbers, got dtype {arr.dtype}")
    if arr.ndim == 0 or arr.shape[-1] != dim:
        raise ValueError(f"points must be one point ({dim},) or an array (..., {dim}) of points, "
                         f"got shape {arr.shape}")
    flat = np.ascontiguousarray(arr.reshape(-1, dim), dtype=np.float64)
    return flat, arr.shape[:-1]


def _threads(threads) -> int:
    """threads as the library takes it: None and 0 ask for OMP_NUM_THREADS when it is set, else
    the available cores (set_thread_count, as the tool's --threads)."""
    if threads is None:
        return 0
    if isinstance(threads, bool) or not isinstance(threads, numbers.Integral):
        raise TypeError(f"threads must be an integer or None, got {threads!r}")
    return int(threads)


def distance(shape, points, *, threads: int | None = None):
    """Signed distance (negative inside) and a nearest point of curves (an Interface, or what
    Interface() takes) or of a Surface, exact to rounding, as ``slc distance`` for a file of each.

    points: (m, d) points give ``(distance (m,), nearest (m, d))``; a grid (..., d) gives
    distances (...) and nearest points (..., d); one point (d,) a float and a (d,) point; d is 2
    for curves and 3 for a surface. A point not finite or beyond the coordinate limit (±1e100)
    raises ValueError naming it (by its index in the points taken row after row), as the tool
    refuses it. threads: as run()'s."""
    from ._surface import Surface  # (the module of surfaces builds on this one)

    if isinstance(shape, Surface):
        xs, answer_shape = _query_points(points, 3)
        d, nearest = _slc.surface_distance(shape.vertices, shape.triangles, xs, _threads(threads))
    else:
        curves = _interface(shape)
        xs, answer_shape = _query_points(points, 2)
        d, nearest = _slc.distance(curves._curves, xs, _threads(threads))
    if answer_shape == ():
        return d[0], nearest[0]
    return d.reshape(answer_shape), nearest.reshape(answer_shape + (xs.shape[1],))


def _refine(refine) -> int:
    if isinstance(refine, str):
        if refine != "converged":
            raise ValueError(f"refine must be a number of passes or 'converged', got '{refine}'")
        return _slc.until_converged
    if isinstance(refine, bool) or not isinstance(refine, numbers.Integral):
        raise TypeError(f"refine must be an integer or 'converged', got {refine!r}")
    if refine < 0:
        raise ValueError(f"refine must be 0 or more, or 'converged', got {refine}")
    return int(refine)


def _warn_no_zero(domain: str, depth: int) -> None:
    """The UserWarning of a contour that found nothing, for contour's caller."""
    warnings.warn(f"G = f has no zero in the domain {domain} (none found at depth {depth}): "
                  "the contour is empty", UserWarning, stacklevel=3)


def _integer(name: str, value) -> int | None:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    return int(value)


def contour(f: Callable[[np.ndarray], Any], box, depth: int, eps: float | None = None,
            refine=None, thin_depth: int = 0, stats: bool = False):
    """The zero set of f, a vectorised function f((m, 2) array) -> (m,) array, in box, by the
    adaptive contouring (paper §2): curves with f > 0 on their right (counterclockwise around
    regions where f < 0).

    box: (x0, y0, x1, y1), a rectangle taken as the square around it, or b for [-b, b]².
    depth: K, the deepest level of the topology tree. eps: ε, the midpoint tolerance of
    refinement (default 10^-K). refine: P passes, or "converged"; by default converged when eps
    is given, none otherwise. thin_depth: levels beyond K, 0 to 8, that cells split where f bends
    as a distance does beside a part thinner than a cell, a near contact or a corner (as ``slc
    contour --thin-depth``; 0 by default, since f need not be a distance). f is called once per
    batch of points, on the calling thread. stats=True returns ``(curves, stats)``, stats a dict
    of the contour's statistics under the keys of ``slc contour``'s summary.json (cells, leaves,
    segments, vertices, g_evals, passes, …) with eps and domain, as contour_surface's.

    Where f has no zero in the box (none the tree of depth K finds: f keeps one sign at every
    point sampled), the result is an empty Interface, with a UserWarning saying so.
    """
    if isinstance(box, numbers.Real):
        box = (-box, -box, box, box)
    box = [float(v) for v in box]
    if refine is None:
        refine = "converged" if eps is not None else 0
    if isinstance(depth, bool) or not isinstance(depth, numbers.Integral):
        raise TypeError(f"depth must be an integer, got {depth!r}")
    arrays, figures = _slc.contour(f, box, int(depth), None if eps is None else float(eps),
                                   _refine(refine), _integer("thin_depth", thin_depth))
    if not arrays:
        x0, y0, x1, y1 = figures["domain"]
        _warn_no_zero(f"[{x0:g}, {x1:g}]x[{y0:g}, {y1:g}]", depth)
    curves = Interface._trusted(arrays)
    return (curves, figures) if stats else curves


def contour_surface(f, box, depth: int, eps: float | None = None,
                    refine=None, slack: float | None = None, eta: float | None = None,
                    thin_depth: int | None = None, creases: bool | None = None,
                    threads: int | None = None):
    """The zero set of f, a vectorised function f((m, 3) array) -> (m,) array, in box, by the
    contouring of space (paper §2 with d = 3): a closed, oriented triangle surface facing f > 0.

    box: (x0, y0, z0, x1, y1, z1), a box taken as the cube around it, or b for [-b, b]³.
    depth: K, the deepest level of the octree. eps: ε, the tolerance of refinement at edge
    midpoints and centroids (default 10^-K). refine: P passes, or "converged"; by default
    converged when eps is given, none otherwise. slack: δ >= 0 when
    |f(x) - f(y)| <= |x - y| + δ everywhere (0 for a signed distance): points far from the
    surface are then not evaluated, and the surface is the same. eta: η, |f| <= η at every
    vertex (default 1e-10, or eps/100 when refining). thin_depth: as for contour() (default 0;
    for a Surface, 2, and where that loses its components or handles the thin depth that keeps
    them, as ``slc contour`` takes it: stats["thin_depth"], and a warning says so). creases:
    refinement follows the creases where the flat facets of a mesh meet, when f is a mesh's
    distance. f may be a Surface itself: its exact signed distance, computed on ``threads``
    threads without calls into Python, as ``slc contour --initial mesh.obj`` contours it
    (creases followed unless creases=False; slack is 0). Returns
    (vertices (n, 3) float array,
    triangles (m, 3) int array of vertex indices, stats dict). Where f has no zero in the box
    (none the octree of depth K finds), both arrays are empty, with a UserWarning saying so.
    """
    if isinstance(box, numbers.Real):
        box = (-box, -box, -box, box, box, box)
    box = [float(v) for v in box]
    if refine is None:
        refine = "converged" if eps is not None else 0
    if isinstance(depth, bool) or not isinstance(depth, numbers.Integral):
        raise TypeError(f"depth must be an integer, got {depth!r}")
    from ._surface import Surface  # (the module of surfaces builds on this one)

    eps = None if eps is None else float(eps)
    eta = None if eta is None else float(eta)
    if isinstance(f, Surface):
        vertices, triangles, stats = _slc.contour_surface_mesh(
            f.vertices, f.triangles, box, int(depth), eps, _refine(refine), eta,
            None if thin_depth is None else _integer("thin_depth", thin_depth),
            True if creases is None else bool(creases), _threads(threads))
    else:
        vertices, triangles, stats = _slc.contour_surface(
            f, box, int(depth), eps, _refine(refine), None if slack is None else float(slack),
            eta, 0 if thin_depth is None else _integer("thin_depth", thin_depth), bool(creases))
    if "note" in stats:
        warnings.warn(stats["note"], UserWarning, stacklevel=2)
    if len(triangles) == 0:
        x0, y0, z0, x1, y1, z1 = stats["domain"]
        _warn_no_zero(f"[{x0:g}, {x1:g}]x[{y0:g}, {y1:g}]x[{z0:g}, {z1:g}]", depth)
    return vertices, triangles, stats
