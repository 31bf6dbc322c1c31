#!/usr/bin/env python3
"""This slc beside an earlier revision of itself, on runs whose results neither should change:
cells of the paper's Tables 5-7 in the plane, moving surfaces, contouring and distance queries.
Each command runs on one thread, the two builds alternated, `--repeat` times each; the least CPU
time of each and the median of the pairs' ratios are kept (summary.json's cpu_s, the computation
without the pictures and files it writes, which the two revisions need not write alike; for a
distance query the whole process's), and the outputs are compared byte for byte (final.json,
final.obj, the distances printed). Writes the table into the region `versus` of
docs/notes/performance.md (between <!-- begin versus --> and <!-- end versus -->).

With --instructions, each command runs once a build under valgrind's callgrind instead, and the
table gives the instructions of the library call that computes the result (slc::run,
slc::contour, slc::contour_surface: their inclusive count, without reading, drawing and writing,
as cpu_s times them) or, for a distance query, of the whole process: a count that does not move
with the machine's load, where the times of this machine move by 15-30% between runs. It writes
the region `versus-instructions`.

The earlier revision is built from a git worktree in --work (only the tool, release flags as the
release preset's), or given as a binary by --old."""
import argparse
import hashlib
import json
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from campaign3d import icosphere, write_obj  # noqa: E402
from thin_cost import write_region  # noqa: E402


def cases(folder):
    sphere = folder / "sphere.obj"
    v, f = icosphere(4)
    write_obj(sphere, [[0.5 * c for c in p] for p in v], f)
    points = folder / "points.csv"
    n = 60
    points.write_text("".join(f"{-0.9 + 1.8 * i / n},{-0.9 + 1.8 * j / n},{-0.9 + 1.8 * k / n}\n"
                              for i in range(n + 1) for j in range(n + 1) for k in range(n + 1)))
    plane = folder / "plane.csv"
    m = 400
    plane.write_text("".join(f"{-1 + 2 * i / m},{-1 + 2 * j / m}\n"
                             for i in range(m + 1) for j in range(m + 1)))
    circles = folder / "circles.json"
    curves = [{"points": [[cx + r * math.cos(2 * math.pi * i / 4096),
                           r * math.sin(2 * math.pi * i / 4096)] for i in range(4096)]}
              for cx, r in ((-0.4, 0.3), (0.4, 0.35))]
    circles.write_text(json.dumps({"curves": curves}))
    run = ["run", "--quiet"]
    return [
        ("Table 5, 160/0/5/1e-5, P = 2 (propeller-rotation)",
         run + ["--problem", "propeller-rotation", "-N", "160", "-K", "5", "--eps", "1e-5", "-P", "2"],
         "final.json"),
        ("Table 6, 160/0/5/1e-5, P = 2 (merging-circles)",
         run + ["--problem", "merging-circles", "-N", "160", "-K", "5", "--eps", "1e-5", "-P", "2"],
         "final.json"),
        ("Table 7, 160/2/6/1e-6, P = 2 (circle-curvature)",
         run + ["--problem", "circle-curvature", "-N", "160", "-S", "2", "-K", "6", "--eps", "1e-6",
                "-P", "2"],
         "final.json"),
        ("sphere-rotation, N = 8, K = 5", run + ["--problem", "sphere-rotation", "-N", "8", "-K", "5"],
         "final.obj"),
        ("contour of the torus, K = 5, eps 1e-4", ["contour", "--function", "torus", "-K", "5",
                                                   "--eps", "1e-4"], "final.obj"),
        ("contour of two circles (8,192 points), K = 10, P = 4, uniform tree",
         ["contour", "--initial", str(circles), "-K", "10", "--refine", "4", "--eps", "1e-10",
          "--eta", "1e-11", "--thin-depth", "0"],
         "final.json"),
        ("distance, 401² points to two circles",
         ["distance", "--initial", str(circles), "--points", str(plane)], None),
        ("distance, 61³ points to a sphere (5,120 triangles)",
         ["distance", "--initial", str(sphere), "--points", str(points)], None),
    ]


def timed(slc, args, out, instructions=False):
    """Runs slc with args into folder out; returns its CPU seconds: summary.json's cpu_s where it
    writes one (the computation alone, not the pictures and files), else the whole process's; or
    with instructions, the instructions the process executes, counted by callgrind."""
    out.mkdir(parents=True, exist_ok=True)
    command = [slc, *args, "--threads", "1"]
    if args[0] != "distance":
        command += ["--out", str(out)]
    profile = out.with_suffix(".callgrind")
    if instructions:
        command = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={profile}", *command]
    with open(out.with_suffix(".stdout"), "wb") as stdout:
        p = subprocess.Popen(command, stdout=stdout, stderr=subprocess.PIPE)
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        err = p.stderr.read().decode()
    if p.returncode != 0:
        sys.exit(f"{' '.join(command)}: exit status {p.returncode}: {err.strip()}")
    if instructions:
        entry = computation(args)
        if entry is None:
            counted = re.search(r"Collected : (\d+)", err)
            if not counted:
                sys.exit(f"{' '.join(command)}: callgrind printed no count")
            return int(counted.group(1))
        table = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100",
                                str(profile)], capture_output=True, text=True, check=True).stdout
        counts = [int(m.group(1).replace(",", "")) for m in
                  re.finditer(r"^\s*([\d,]+) \(\s*[\d.]+%\)\s+\S*:" + entry, table, re.M)]
        if not counts:
            sys.exit(f"{' '.join(command)}: no {entry} in its profile")
        return max(counts)
    summary = out / "summary.json"
    if summary.exists():
        return json.loads(summary.read_text())["cpu_s"]
    return usage.ru_utime + usage.ru_stime


def computation(args):
    """The library call whose inclusive instructions stand for a command's computation, as a
    pattern of callgrind's function names; None for the whole process."""
    if args[0] == "run":
        surface = any(a.startswith("sphere") for a in args)
        return r"slc::run\(slc::Surface const&" if surface else r"slc::run\(slc::Interface const&"
    if args[0] == "contour":
        return r"slc::contour_surface\(" if "--function" in args else r"slc::contour\("
    return None


def digest(out, name):
    path = out / name if name else out.with_suffix(".stdout")
    return hashlib.sha256(path.read_bytes()).hexdigest()


def build_old(revision, work):
    work = Path(work)
    if not (work / ".git").exists():
        subprocess.run(["git", "worktree", "add", "-f", str(work), revision], check=True)
    else:
        subprocess.run(["git", "-C", str(work), "checkout", "-q", revision], check=True)
    build = work / "build"
    subprocess.run(["cmake", "-S", str(work), "-B", str(build), "-G", "Ninja",
                    "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_FLAGS=-DSLC_ENABLE_ASSERTS",
                    "-DSLC_BUILD_TESTS=OFF", "-DSLC_BUILD_BENCH=OFF", "-DSLC_BUILD_PYTHON=OFF",
                    "-DSLC_BUILD_EXAMPLES=OFF"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["ninja", "-C", str(build), "slc"], check=True, stdout=subprocess.DEVNULL)
    return str(build / "bin" / "slc")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--slc", default="build/bin/slc", help="this build's tool")
    parser.add_argument("--revision", help="the earlier revision, built in --work")
    parser.add_argument("--work", default="out/versus-worktree")
    parser.add_argument("--old", help="the earlier build's tool, instead of --revision")
    parser.add_argument("--out", default="docs/notes/performance.md")
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--instructions", action="store_true",
                        help="count instructions under callgrind, once a build, instead of timing")
    a = parser.parse_args()
    if not a.old and not a.revision:
        sys.exit("give --revision REV or --old BINARY")
    old = a.old or build_old(a.revision, a.work)
    label = a.revision or a.old
    counting = a.instructions
    repeats = 1 if counting else a.repeat  # a count does not vary from run to run
    lines = ([f"| command (one thread) | instructions, {label} | instructions, this | "
              "this ÷ before | same output |"] if counting else
             [f"| command (one thread) | least CPU s, {label} | least CPU s, this | this ÷ before, "
              "median of the pairs (range) | same output |"]) + ["|---|---|---|---|---|"]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for number, (name, args, output) in enumerate(cases(folder)):
            best = {"old": float("inf"), "new": float("inf")}
            digests = {}
            ratios = []
            for repeat in range(repeats):
                pair = {}
                for key, slc in (("old", old), ("new", a.slc)):
                    out = folder / f"{number}-{key}-{repeat}"
                    pair[key] = timed(slc, args, out, instructions=counting)
                    best[key] = min(best[key], pair[key])
                    digests[key] = digest(out, output)
                ratios.append(pair["new"] / pair["old"])
            ratio = statistics.median(ratios)
            same = "yes" if digests["old"] == digests["new"] else "no"
            if counting:
                print(f"{name}: {best['old']:,} before, {best['new']:,} now, ratio {ratio:.4f}, "
                      f"same output: {same}", flush=True)
                lines.append(f"| {name} | {best['old']:,} | {best['new']:,} | {ratio:.4f} "
                             f"| {same} |")
                continue
            print(f"{name}: {best['old']:.3f} s before, {best['new']:.3f} s now, median ratio "
                  f"{ratio:.3f} ({min(ratios):.3f}-{max(ratios):.3f}), same output: {same}",
                  flush=True)
            lines.append(f"| {name} | {best['old']:.3f} | {best['new']:.3f} | {ratio:.3f} "
                         f"({min(ratios):.2f}–{max(ratios):.2f}) | {same} |")
    write_region(a.out, "versus-instructions" if counting else "versus", lines)

if __name__ == "__main__":
    main()
