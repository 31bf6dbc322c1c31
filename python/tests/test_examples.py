"""The examples of examples/python run as a user runs them, and say what they should."""

import csv
import math
import os
import subprocess
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "python"


def run_example(name, *args, cwd):
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)], cwd=cwd,
                          env=env, capture_output=True, text=True, timeout=600, check=True)


def test_run_and_plot_draws_a_figure_and_keeps_the_area_law(tmp_path):
    out = run_example("run_and_plot.py", tmp_path / "figure.png", cwd=tmp_path)
    assert (tmp_path / "figure.png").stat().st_size > 10_000
    words = out.stdout.split()
    lost, exact = float(words[words.index("lost") + 1].rstrip(",")), 2 * math.pi * 0.2
    assert words[1] == "ok:" and abs(lost - exact) < 1e-3 * exact


def test_the_sweep_example_writes_one_row_per_case(tmp_path):
    run_example("sweep.py", tmp_path / "table.csv", cwd=tmp_path)
    with open(tmp_path / "table.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 8 and {r["status"] for r in rows} == {"ok"}
    assert max(abs(float(r["area_error"])) for r in rows) < 1e-3
