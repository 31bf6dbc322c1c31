"""Surfaces of users' kinds that the tests and the benchmarks share."""

import math

import numpy as np

import slc


def head_with_ears(half_thickness=0.05):
    """A head (an ellipsoid of semi-axes 2.5, 2.5, 3.4) with two ears, flat ellipses 1.8 by 3.4
    thickened to 2 half_thickness with rounded rims, leaning out by 0.35 rad, joined smoothly."""
    def ear(p, centre, lean):
        c, s = math.cos(lean), math.sin(lean)
        q = p - centre
        u, v, w = c * q[:, 0] - s * q[:, 2], q[:, 1], s * q[:, 0] + c * q[:, 2]
        # (u, w) in the ear's plane, v across it
        out = np.maximum(np.hypot(u / 0.9, w / 1.7) - 1.0, 0.0) * 0.9
        return np.hypot(out, v) - half_thickness

    def smooth_min(a, b, k=0.15):
        h = np.clip(0.5 + 0.5 * (b - a) / k, 0.0, 1.0)
        return b * (1 - h) + a * h - k * h * (1 - h)

    def f(p):
        head = (np.linalg.norm(p / [2.5, 2.5, 3.4], axis=1) - 1.0) * 2.5
        ears = np.minimum(ear(p, [-1.0, 0.0, 4.0], -0.35), ear(p, [1.0, 0.0, 4.0], 0.35))
        return smooth_min(head, ears)

    return slc.Surface(slc.contour_surface(f, (-5, -5, -4, 5, 5, 6), 5, eps=1e-3, thin_depth=3))
