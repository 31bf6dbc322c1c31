"""A user's curve under a velocity law written in Python: a figure of its frames and its area
history. Usage: run_and_plot.py [figure.png]"""

import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import slc  # noqa: E402

# A three-lobed curve.
th = np.linspace(0.0, 2.0 * math.pi, 300, endpoint=False)
r = 1.0 + 0.3 * np.cos(3 * th)
curve = slc.Interface(np.c_[r * np.cos(th), r * np.sin(th)])


def shrink(t, points, normals, curvature):
    """Curvature flow, V = C (C = -1/R on a circle: inward), with all vertices at once."""
    return curvature


t_end = 0.2
result = slc.run(curve, shrink, t_end, frames=4)
loss = curve.area - result.interface.area
print(f"status {result.status}: area lost {loss:.5f}, exactly 2 pi t = {2 * math.pi * t_end:.5f}")

fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.5))
slc.plot(result, ax=left)
left.set_title("curvature flow of a three-lobed curve")
slc.plot(result.history, ax=right)
right.plot(result.history["t"], curve.area - 2 * math.pi * result.history["t"], "k--",
           label="exact: A0 - 2 pi t")
right.legend()
fig.tight_layout()
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "run_and_plot.png", dpi=110)
