"""What a named problem of curves (slc.Problem) and of surfaces (slc.SurfaceProblem) share: the
problem made by name from the library, a fresh copy for each run, and what describes it."""

from __future__ import annotations

from typing import Callable


class _NamedProblem:
    """A named problem held as the library's object: ``_make(name, params)`` makes it anew for
    each run (a run may change its final time), so that one Problem can run many times."""

    __slots__ = ("_p", "_params")
    _make: Callable = None  # the library's maker, set by each subclass
    _kind = "problem"       # for repr

    def __init__(self, name: str, params: dict[str, float] | None = None):
        self._params = {k: float(v) for k, v in (params or {}).items()}
        self._p = type(self)._make(name, self._params)

    def _fresh(self, t_end: float | None):
        p = type(self)._make(self._p.name, self._params)
        if t_end is not None:
            p.t_end = float(t_end)
        return p

    name = property(lambda self: self._p.name, doc="as in ``slc run --problem NAME``")
    description = property(lambda self: self._p.description, doc="what it is")
    t_end = property(lambda self: self._p.t_end, doc="the final time")
    velocity = property(lambda self: self._p.velocity, doc="the built-in law's name")
    domain = property(lambda self: self._p.domain,
                      doc="the box it runs in: (x0, y0, x1, y1), or (x0, y0, z0, x1, y1, z1)")
    has_exact = property(lambda self: self._p.has_exact, doc="whether the exact solution is known")

    def __repr__(self) -> str:
        return f"<slc.{self._kind} {self.name}: {self.description}>"
