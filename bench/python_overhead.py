"""What a velocity law written in Python costs beside the same law built in: CPU seconds of the
same run (one thread, the defaults of slc.run) with each, at curves of 2000 vertices and more.
Writes its table into docs/python.md between the markers of the section "Overhead"."""

import argparse
import math
import re
import time

import numpy as np

import slc

BEGIN, END = "<!-- overhead: begin -->", "<!-- overhead: end -->"


def ellipse(n=400):
    th = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    return slc.Interface(np.c_[np.cos(th), 0.6 * np.sin(th)])


def ones(t, points, normals):
    return np.ones(len(points))


def curvature_flow(t, points, normals, curvature):
    return curvature  # V = C, C = -1/R on a circle: inward


CASES = [
    # (what, built-in, Python, t_end, run options)
    ("unit normal speed", "unit-normal", slc.NormalSpeed(ones), 0.3, {"eps": 1e-6}),
    ("unit normal speed", "unit-normal", slc.NormalSpeed(ones), 0.3, {"eps": 1e-7}),
    ("curvature flow", "curvature", curvature_flow, 0.05, {"depth": 7}),
    ("curvature flow", "curvature", curvature_flow, 0.05, {"depth": 8}),
]


def cpu(velocity, t_end, options, repeats):
    best, result = math.inf, None
    for _ in range(repeats):
        start = time.process_time()
        result = slc.run(ellipse(), velocity, t_end, threads=1, **options)
        best = min(best, time.process_time() - start)
    return best, result


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="docs/python.md")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    rows = ["| law | setting | vertices | built in (s) | Python (s) | ratio | same curves |",
            "|---|---|---|---|---|---|---|"]
    for what, built_in, python, t_end, options in CASES:
        t0, r0 = cpu(built_in, t_end, options, args.repeats)
        t1, r1 = cpu(python, t_end, options, args.repeats)
        same = all(np.array_equal(a, b) for a, b in zip(r0.interface.curves, r1.interface.curves))
        setting = ", ".join(f"{k} = {v:g}" for k, v in options.items())
        rows.append(f"| {what} | {setting} | {r0.summary['segments']} | {t0:.3f} | "
                    f"{t1:.3f} | {t1 / t0:.2f} | {'yes' if same else 'no'} |")
        print(rows[-1], flush=True)
    table = "\n".join(rows)
    text = open(args.out).read()
    section = (f"{BEGIN}\n{table}\n\nWritten by `bench/python_overhead.py` (`scripts/bench`): the "
               "least CPU seconds of "
               f"{args.repeats} runs each, one thread, an ellipse 1 × 0.6 to the final time.\n{END}")
    text = re.sub(re.escape(BEGIN) + ".*?" + re.escape(END), lambda _: section, text, flags=re.S)
    open(args.out, "w").write(text)


if __name__ == "__main__":
    main()
