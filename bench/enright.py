#!/usr/bin/env python3
"""Enright's test, slc beside OpenVDB in the same run: `slc run --problem enright` at the given
settings (K, N, eps) and OpenVDB's level-set advection (bench/enright_openvdb.cpp: HJWENO5 +
TVD-RK3, its own EnrightField) at the given resolutions, each on the same threads; writes the
volume at t = 1.5 (slc: the history) and t = 3, the volume change, the distance of the returned
surface from the sphere, the status and the wall time into a Markdown table
(docs/tables/enright.md), and slc's surfaces at t = 1.5 and 3 into --figures.

A slc setting's run folder already holding a finished run of the same options (its summary.json)
is read instead of run again with --reuse: a run at K = 7 takes some seven minutes. The pictures
are the last setting's of each K."""
import argparse
import json
import shutil
import subprocess
import sys
from pathlib import Path


def slc_row(slc, work, setting, threads, reuse, figures):
    depth, steps, eps, *rest = setting.split(":")
    drift = rest[0] if rest and rest[0] else None
    thin = rest[1] if len(rest) > 1 and rest[1] else None
    out = Path(work) / (f"slc-K{depth}-N{steps}-eps{eps}" + (f"-drift{drift}" if drift else "")
                        + (f"-thin{thin}" if thin else ""))
    summary = out / "summary.json"
    if not (reuse and summary.exists()):
        run = subprocess.run([slc, "run", "--problem", "enright", "-K", depth, "-N", steps,
                              "--eps", eps, "--threads", str(threads), "--frames", "2",
                              "--out", str(out), "--quiet"]
                             + (["--volume-drift", drift] if drift else [])
                             + (["--thin-depth", thin] if thin else []),
                             capture_output=True, text=True)
        if run.returncode not in (0, 3):
            sys.exit(f"slc run --problem enright failed: {run.stderr.strip()}")
    s = json.loads(summary.read_text())
    p = s["params"]
    if figures and s["status"] == "ok":  # the sheet at t = 1.5 and the sphere back at t = 3
        Path(figures).mkdir(parents=True, exist_ok=True)
        for frame, name in ((1, "t1.5"), (2, "t3")):
            picture = out / "frames" / f"frame_{frame:04d}.png"
            if picture.exists():
                shutil.copy(picture, Path(figures) / f"enright_K{depth}_{name}.png")
    if (p["K"], p["N"], p["eps"]) != (int(depth), int(steps), float(eps)) or (
            drift and p.get("volume_drift") != float(drift)) or (
            thin and p.get("thin_depth") != int(thin)):
        sys.exit(f"{summary}: not the run K {depth} N {steps} eps {eps}")
    half = None
    for line in (out / "history.csv").read_text().splitlines()[1:]:
        f = line.split(",")
        if abs(float(f[1]) - 1.5) < 1e-9:
            half = float(f[2])
    v0 = s["volume_initial"]
    return {
        "method": f"slc K = {depth}, N = {steps}, ε = {eps}"
                  + (f", thin depth {p['thin_depth']}" if p.get("thin_depth") else "")
                  + (f", volume drift allowed {100 * float(drift):g}%" if drift else ""),
        "status": s["status"] + (f" at t = {s['t']:.3g}" if s["status"] != "ok" else ""),
        "half": None if half is None else half / v0 - 1,
        "change": s["volume_change"] if s["status"] == "ok" else None,
        "message": s.get("message") if s["status"] != "ok" else None,
        "distance": s["e_inf"],
        "size": f"{s['triangles']:,} triangles",
        "wall": s["wall_s"],
        "threads": p["threads"],
    }


def openvdb_row(program, resolution, threads):
    run = subprocess.run([program, str(resolution), str(threads)], capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{program} {resolution} failed: {run.stderr.strip()}")
    r = json.loads(run.stdout)
    v0 = r["volume_initial"]
    return {
        "method": f"OpenVDB {resolution}³ (HJWENO5, TVD-RK3)",
        "status": "ok" if r["volume_final"] > 0 else "vanished",
        "half": r["volume_half"] / v0 - 1,
        "change": r["volume_change"],
        "distance": r["distance"] if r["distance"] >= 0 else None,
        "size": f"voxel 1/{resolution}",
        "wall": r["wall_s"],
        "threads": r["threads"],
    }


def percent(x):
    return "—" if x is None else f"{100 * x:+.4g}%"


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--slc", required=True, help="the slc executable")
    parser.add_argument("--openvdb", help="bench/enright_openvdb's executable (none: no peer)")
    parser.add_argument("--out", required=True, help="the table to write (.md)")
    parser.add_argument("--work", default="out/enright", help="run folders")
    parser.add_argument("--settings", nargs="*",
                        default=["4:30:1e-3:1", "5:30:5e-4:1", "6:60:1e-4", "6:30:1e-4",
                                 "6:30:1e-4::3", "7:15:5e-4", "7:60:1e-4", "7:30:5e-5",
                                 "7:30:1e-4"],
                        help="slc settings K:N:eps, K:N:eps:DRIFT with --volume-drift DRIFT, "
                             "K:N:eps:DRIFT:THIN (DRIFT may be empty) with --thin-depth THIN")
    parser.add_argument("--resolutions", nargs="*", type=int, default=[64, 128, 256])
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--figures", help="folder for the pictures of slc's runs that end ok")
    parser.add_argument("--reuse", action="store_true",
                        help="read finished slc runs in --work instead of running them again")
    args = parser.parse_args()
    rows = []
    if args.openvdb:
        for r in args.resolutions:
            rows.append(openvdb_row(args.openvdb, r, args.threads))
            print(rows[-1], flush=True)
    for setting in args.settings:
        rows.append(slc_row(args.slc, args.work, setting, args.threads, args.reuse,
                            args.figures))
        print(rows[-1], flush=True)
    lines = [
        "<!-- written by bench/enright.py (scripts/bench); do not edit -->",
        "",
        "| method | status | volume at t = 1.5 | volume at t = 3 | distance from the sphere at "
        "t = 3 | size | wall s | threads |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        distance = "—" if r["distance"] is None else f"{r['distance']:.3g}"
        lines.append(f"| {r['method']} | {r['status']} | {percent(r['half'])} "
                     f"| {percent(r['change'])} | {distance} | {r['size']} "
                     f"| {r['wall']:.4g} | {r['threads']} |")
    lines += ["", "Volumes relative to the initial one, each measured by its own method (slc: "
              "the exact volume of its triangles; OpenVDB: tools::levelSetVolume). Distance: the "
              "largest | |x − c| − 0.15 | over the returned surface's vertices (slc: and triangle "
              "centroids; OpenVDB: the vertices of tools::volumeToMesh). slc's runs end "
              "`unstable` when the sheet tears or a hole opens in it (a smooth flow keeps the "
              "number of components and the genus) or the volume drifts by more than 1% (or "
              "the drift allowed, `--volume-drift`, in the coarse rows)."]
    stopped = [f"- {r['method']}: {r['message']}" for r in rows if r.get("message")]
    if stopped:
        lines += ["", "Where slc's runs stopped:", ""] + stopped
    Path(args.out).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
