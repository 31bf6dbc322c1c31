"""Convergence tables as numpy arrays and Markdown, shared by the studies of curves and surfaces."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

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


def cell_arrays(s: dict) -> dict:
    """The cells of a convergence table as _slc gives them, with their errors and CPU seconds a
    step as rows x columns arrays: the fields every ConvergenceTable has but the orders."""
    shape = (s["rows"], s["columns"])
    cells = s["cells"]
    return {"cells": cells,
            "errors": nan_array(c["e_inf"] for c in cells).reshape(shape),
            "cpu_s_per_step": nan_array(c["cpu_s_per_step"] for c in cells).reshape(shape)}


@dataclass
class ConvergenceTable:
    """What a convergence table of curves (Study) and of surfaces (SurfaceStudy) holds: ``cells``
    (one dict per run, row-major), ``errors`` and ``cpu_s_per_step`` (rows x columns, NaN where a
    run has no error), ``row_orders`` and ``column_orders`` (log2 of the error ratios of
    neighbours)."""

    cells: list[dict[str, Any]]
    errors: np.ndarray
    cpu_s_per_step: np.ndarray
    row_orders: np.ndarray
    column_orders: np.ndarray

    def _markdown(self, row_name: Callable[[dict[str, Any]], str]) -> str:
        """The errors as a Markdown table, each row named by row_name of its first cell."""
        columns = self.errors.shape[1]
        return errors_markdown([row_name(c) for c in self.cells[::columns]], self.errors)
