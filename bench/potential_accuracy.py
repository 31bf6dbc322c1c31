#!/usr/bin/env python3
"""Time to an accuracy under a potential law: the unit circle perturbed by mode m (r = 1 + δ cos mθ,
δ = 1e-3) under two-phase Mullins-Sekerka (σ = 1) over 1.5 e-folding times of its exact linear
rate λ_m = -2m(m² - 1), at the default depth and growing numbers of steps N. The error is that of
the mode's amplitude at the end against δ e^{λT}, relative; the CPU time is the run's. Writes the
table and the first N at or below 1e-4 into the region `potential-accuracy` of
docs/performance.md."""
import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from thin_cost import write_region  # noqa: E402

DELTA = 1e-3
TARGET = 1e-4


def solve(a, b):
    """Gaussian elimination with partial pivoting."""
    n = len(b)
    m = [row[:] + [b[i]] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        for r in range(c + 1, n):
            f = m[r][c] / m[c][c]
            for k in range(c, n + 1):
                m[r][k] -= f * m[c][k]
    x = [0.0] * n
    for r in range(n - 1, -1, -1):
        x[r] = (m[r][n] - sum(m[r][k] * x[k] for k in range(r + 1, n))) / m[r][r]
    return x


def amplitude(points, m, modes=12):
    """The amplitude of mode m of r(θ), from a least-squares Fourier series of r(θ) through the
    vertices up to `modes` (no quadrature: exact for a band-limited r, whatever the spacing)."""
    rows, rhs = [], []
    for x, y in points:
        t = math.atan2(y, x)
        rows.append([1.0] + [f(j * t) for j in range(1, modes + 1) for f in (math.cos, math.sin)])
        rhs.append(math.hypot(x, y))
    n = len(rows[0])
    ata = [[sum(r[i] * r[j] for r in rows) for j in range(n)] for i in range(n)]
    atb = [sum(r[i] * v for r, v in zip(rows, rhs)) for i in range(n)]
    c = solve(ata, atb)
    return math.hypot(c[2 * m - 1], c[2 * m])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--slc", default="build/bin/slc")
    ap.add_argument("--out", default="docs/performance.md")
    ap.add_argument("--mode", type=int, default=3)
    ap.add_argument("--steps", default="20,40,80,160,320,640")
    a = ap.parse_args()
    m = a.mode
    rate = -2.0 * m * (m * m - 1)
    t_end = 1.5 / abs(rate)
    exact = DELTA * math.exp(rate * t_end)
    lines = [f"`mullins-sekerka` on r = 1 + 10⁻³ cos {m}θ (400 vertices) to t = {t_end:.4g} "
             f"(1.5 e-folds of λ = {rate:.0f}), default depth, written by "
             "`bench/potential_accuracy.py`: the amplitude's error against δe^{λt}, relative.", "",
             "| steps N | K | segments | amplitude error | CPU s |", "|---|---|---|---|---|"]
    first = None
    with tempfile.TemporaryDirectory() as tmp:
        start = Path(tmp) / "start.json"
        pts = [[(1 + DELTA * math.cos(m * t)) * math.cos(t), (1 + DELTA * math.cos(m * t)) * math.sin(t)]
               for t in (2 * math.pi * i / 400 for i in range(400))]
        start.write_text(json.dumps({"time": 0, "curves": [{"points": pts}]}))
        for n in (int(s) for s in a.steps.split(",")):
            out = Path(tmp) / f"n{n}"
            subprocess.run([a.slc, "run", "--initial", str(start), "--velocity", "mullins-sekerka",
                            "--t-end", repr(t_end), "-N", str(n), "--threads", "1", "--quiet",
                            "--out", str(out)], check=True)
            summary = json.loads((out / "summary.json").read_text())
            final = json.loads((out / "final.json").read_text())["curves"][0]["points"]
            error = abs(amplitude(final, m) / exact - 1)
            lines.append(f"| {n} | {summary['params']['K']} | {summary['segments']} | {error:.2e} | "
                         f"{summary['cpu_s']:.3g} |")
            if first is None and error <= TARGET:
                first = (n, summary["cpu_s"])
    lines.append("")
    lines.append(f"First at or below {TARGET:g}: " +
                 (f"N = {first[0]}, {first[1]:.3g} s CPU." if first else "none of these runs."))
    write_region(a.out, "potential-accuracy", lines)


if __name__ == "__main__":
    main()
