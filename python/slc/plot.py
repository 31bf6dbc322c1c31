"""Pictures with matplotlib: curves, a run's frames, a run's history (area and length against t)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._interface import Interface
from ._run import Problem, RunResult


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
    axes[0].plot(t, history["area"], marker=".", color="C0")
    axes[0].set_ylabel("area")
    if len(axes) > 1:
        axes[1].plot(t, history["length"], marker=".", color="C1")
        axes[1].set_ylabel("length")
    axes[-1].set_xlabel("t")
    for a in axes:
        a.grid(True, alpha=0.3)


def plot(obj, ax=None, *, cmap: str = "viridis", **style) -> Any:
    """Draws obj with matplotlib and returns the axes drawn on.

    - an Interface (or a Problem's initial curves): its closed curves, equal aspect; style goes
      to ``ax.plot`` (color, linewidth, label, ...);
    - a RunResult: its frames coloured by time (cmap), or its final curves when it kept none;
    - a list of (t, Interface) frames: the same;
    - a history dict (``RunResult.history``): area and length against t on two axes (ax may be
      a pair of axes; a single ax gets the area alone).
    ax: where to draw; a new figure when None.
    """
    import matplotlib.pyplot as plt

    if isinstance(obj, dict) and "t" in obj and "area" in obj:
        if ax is None:
            _, axes = plt.subplots(2, 1, sharex=True, figsize=(6, 5))
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
                        f"frames or a history dict, got {type(obj).__name__}")
    ax.set_aspect("equal", adjustable="datalim")
    return ax
