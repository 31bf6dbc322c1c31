"""Convergence tables as numpy arrays and Markdown, shared by the studies of curves and surfaces."""

from __future__ import annotations

import math

import numpy as np


def errors_markdown(names: list[str], errors: np.ndarray) -> str:
    """A row per run name and a column per P, "—" where a run has no error."""
    rows, columns = errors.shape
    lines = ["| run | " + " | ".join(f"P = {c}" for c in range(columns)) + " |",
             "|---|" + "---|" * columns]
    for r in range(rows):
        lines.append(f"| {names[r]} | " + " | ".join(
            "—" if math.isnan(e) else f"{e:.2e}" for e in errors[r]) + " |")
    return "\n".join(lines)


def nan_array(values) -> np.ndarray:
    """values as a float array, None as NaN."""
    return np.array([math.nan if v is None else v for v in values], dtype=float)
