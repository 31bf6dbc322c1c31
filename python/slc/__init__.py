"""slc: semi-Lagrangian contouring for moving curves in the plane and surfaces in space.

The C++ library on numpy arrays (docs/python.md), with the defaults of ``slc run --initial``:

- ``Interface(curves)``: closed curves, each an (n, 2) array, validated like the tool's files;
- ``distance(shape, points)``: signed distances (negative inside) and nearest points of curves
  or of a Surface;
- ``contour(f, box, depth)``: the zero set of a vectorised function f((m, 2)) -> (m,);
- ``contour_surface(f, box, depth)``: the same in space, f((m, 3)) -> (m,): a closed triangle
  surface as (vertices, triangles, stats);
- ``Surface(vertices, triangles)``: a closed triangle surface, validated like the tool's files;
- ``run(interface, velocity, t_end)``: the curves moved by a built-in law or a Python one;
  ``run(surface, velocity, t_end)`` the same for a surface;
- ``problem(name)``, ``run(problem)``, ``study(...)``: the paper's experiments and convergence;
- ``plot(obj)``: an interface, a run's frames or its history, with matplotlib;
- ``sweep(cases)``: many runs on a dask cluster, gathered into one table.

Bad input raises ValueError (TypeError for an argument of the wrong kind) with the tool's one-line
message; a numerical failure RuntimeError. A Python callback is called with whole arrays (all the
vertices of a stage, or a batch of points), never per point; what it raises reaches the caller.
"""

from ._interface import Interface, contour, contour_surface, distance
from ._surface import Step, Surface, SurfaceProblem, SurfaceRunResult, SurfaceStep, SurfaceStudy
from ._run import (FieldExpression, FieldFile, FlowField, NormalSpeed, Problem, RunResult,
                   SelfConvergence, SpeedExpression, Study, problem, problems, run, study,
                   velocities)
from .plot import plot
from .sweep import grid, sweep

__all__ = [
    "Interface",
    "FieldExpression",
    "FieldFile",
    "FlowField",
    "NormalSpeed",
    "Problem",
    "RunResult",
    "SelfConvergence",
    "SpeedExpression",
    "Step",
    "Surface",
    "SurfaceProblem",
    "SurfaceRunResult",
    "SurfaceStep",
    "SurfaceStudy",
    "Study",
    "contour",
    "contour_surface",
    "distance",
    "grid",
    "plot",
    "problem",
    "problems",
    "run",
    "study",
    "sweep",
    "velocities",
]
