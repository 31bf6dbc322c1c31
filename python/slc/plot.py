"""Pictures with matplotlib: curves, a run's frames, a run's history (area, length and, when it
changed, the number of curves against t); surfaces shaded in 3D axes, and their history (volume
and area against t)."""

from __future__ import annotations

from typing import Any

import numpy as np

from . import _slc
from ._interface import Interface
from ._run import Problem, RunResult
from ._surface import Surface, SurfaceProblem, SurfaceRunResult


def _draw_curves(ax, interface: Interface, **style) -> None:
    label = style.pop("label", None)
    for i, c in enumerate(interface.curves):
        closed = np.vstack([c, c[:1]])
        ax.plot(closed[:, 0], closed[:, 1], label=label if i == 0 else None, **style)


def _draw_frames(ax, frames, cmap) -> None:
    import matplotlib as mpl

    colors = mpl.colormaps[cmap]
    times = [t for t, _ in frames]
    t0, t1 = min(times), max(times)
    for t, interface in frames:
        s = 0.0 if t1 == t0 else (t - t0) / (t1 - t0)
        _draw_curves(ax, interface, color=colors(s), linewidth=1.2, label=f"t = {t:.3g}")
    if len(frames) <= 8:
        ax.legend(fontsize="small", loc="best")
    else:
        norm = mpl.colors.Normalize(t0, t1)
        ax.figure.colorbar(mpl.cm.ScalarMappable(norm=norm, cmap=colors), ax=ax, label="t")


def _draw_history(axes, history: dict[str, np.ndarray]) -> None:
    t = history["t"]
    # Curves: area and length; surfaces: volume and area.
    first, second = ("volume", "area") if "volume" in history else ("area", "length")
    axes[0].plot(t, history[first], marker=".", color="C0")
    axes[0].set_ylabel(first)
    if len(axes) > 1:
        axes[1].plot(t, history[second], marker=".", color="C1")
        axes[1].set_ylabel(second)
    if len(axes) > 2:
        axes[2].step(t, history["components"], where="post", color="C2")
        axes[2].set_ylabel("curves" if "length" in history else "components")
    axes[-1].set_xlabel("t")
    axes[-1].ticklabel_format(axis="x", style="sci", scilimits=(-2, 3))  # no 0.000125 crowding
    for a in axes:
        a.grid(True, alpha=0.3)


def _new_surface_axes(surface: Surface):
    """3D axes looking at surface as slc's pictures do (``slc run``'s final.png): from azimuth 35°
    and elevation 25° about the up axis its extents suggest (z for CAD files and slc's shapes, y
    for a scan standing in y; ``_slc.up_axis``)."""
    import matplotlib.pyplot as plt

    ax = plt.figure(figsize=(5, 5)).add_subplot(projection="3d")
    if len(surface) > 0:
        v = surface.vertices
        up = _slc.up_axis(v.min(axis=0).tolist(), v.max(axis=0).tolist())
        ax.view_init(elev=25, azim=35, vertical_axis=up)
    return ax


def _draw_surface(ax, surface: Surface, color) -> None:
    """The triangles shaded by the angle of their normals to a light above the viewer's left
    shoulder (the axes' view: azim, elev about its vertical axis), on equal axes."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    v, t = surface.vertices, surface.triangles
    corners = v[t]
    n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    azim, elev = np.radians(ax.azim), np.radians(ax.elev)
    toward = np.array([np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim), np.sin(elev)])
    right = np.array([-np.sin(azim), np.cos(azim), 0.0])  # the viewer's right
    up = np.cross(toward, right)
    light = toward - 0.5 * right + 0.6 * up
    # Those are in the frame whose third axis is the vertical one; matplotlib rolls its axes so.
    light = np.roll(light, getattr(ax, "_vertical_axis", 2) - 2)
    shade = 0.25 + 0.75 * np.clip(n @ (light / np.linalg.norm(light)), 0.0, 1.0)
    import matplotlib.colors as mcolors

    rgb = np.array(mcolors.to_rgb(color))
    colors = shade[:, None] * rgb
    # Edges in the faces' own colours: no seams between neighbours.
    ax.add_collection3d(Poly3DCollection(corners, facecolors=colors, edgecolors=colors,
                                         linewidths=0.3))
    lo, hi = v.min(axis=0), v.max(axis=0)
    centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo).max()
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")


def plot(obj, ax=None, *, cmap: str = "viridis", **style) -> Any:
    """Draws obj with matplotlib and returns the axes drawn on.

    - an Interface (or a Problem's initial curves): its closed curves, equal aspect; style goes
      to ``ax.plot`` (color, linewidth, label, ...);
    - a RunResult: its frames coloured by time (cmap), or its final curves when it kept none;
    - a list of (t, Interface) frames: the same;
    - a history dict (``RunResult.history``): area and length against t on two axes, and the
      number of curves on a third when it changed (ax may be two or three axes; a single ax gets
      the area alone); a surface's history: volume and area (and its components);
    - a Surface, a SurfaceProblem's initial surface or a SurfaceRunResult's final one: shaded
      triangles on 3D axes (ax must be 3D: ``projection="3d"``); ``color`` sets the colour. New
      axes look from azimuth 35°, elevation 25° about the up axis the surface's extents suggest,
      as the tool's pictures do (a scan standing in y stands up).
    ax: where to draw; a new figure when None.
    """
    import matplotlib.pyplot as plt

    if isinstance(obj, SurfaceProblem):
        obj = obj.surface
    if isinstance(obj, SurfaceRunResult):
        obj = obj.surface
    if isinstance(obj, Surface):
        if ax is None:
            ax = _new_surface_axes(obj)
        if len(obj) > 0:
            _draw_surface(ax, obj, style.get("color", "C0"))
        return ax
    if isinstance(obj, dict) and "t" in obj and "area" in obj:
        if ax is None:
            # The number of curves (or components) too when it changed, as history.png does.
            counts = obj.get("components")
            changed = counts is not None and len(np.unique(counts)) > 1
            rows = 3 if changed else 2
            _, axes = plt.subplots(rows, 1, sharex=True, figsize=(6, 2.5 * rows))
        else:
            axes = list(ax) if np.iterable(ax) else [ax]
        _draw_history(list(axes), obj)
        return axes
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 5))
    if isinstance(obj, Problem):
        obj = obj.interface
    if isinstance(obj, RunResult):
        if obj.frames:
            _draw_frames(ax, obj.frames, cmap)
        else:
            _draw_curves(ax, obj.interface, **({"color": "C0"} | style))
    elif isinstance(obj, Interface):
        _draw_curves(ax, obj, **({"color": "C0"} | style))
    elif isinstance(obj, (list, tuple)) and all(
            isinstance(f, tuple) and len(f) == 2 and isinstance(f[1], Interface) for f in obj):
        _draw_frames(ax, list(obj), cmap)
    else:
        raise TypeError("plot draws an Interface, a Problem, a RunResult, a list of (t, Interface) "
                        "frames, a history dict, a Surface, a SurfaceProblem or a "
                        f"SurfaceRunResult, got {type(obj).__name__}")
    ax.set_aspect("equal", adjustable="datalim")
    return ax
