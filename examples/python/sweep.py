"""A parameter sweep on dask.distributed: circles of several radii under unit normal speed and
under curvature flow, two worker processes here (a LocalCluster; pass a Client of your cluster to
slc.sweep to run elsewhere), the results in one table. Usage: sweep.py [table.csv]"""

import math
import sys

import numpy as np

import slc


def circle(radius, n=200):
    th = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    return slc.Interface(radius * np.c_[np.cos(th), np.sin(th)])


cases = [dict(name=f"{law} R={radius}", interface=circle(radius), velocity=law, t_end=0.1,
              steps=steps)
         for law in ("unit-normal", "curvature")
         for radius in (0.5, 1.0)
         for steps in (10, 20)]

if __name__ == "__main__":  # worker processes import this file: run the sweep only here
    table = slc.sweep(cases, workers=2)
    # Exact: unit speed adds 2 pi R t + pi t^2 of area; curvature flow takes 2 pi t.
    radius = np.array([float(n.split("R=")[1]) for n in table["name"]])
    exact = np.where(table["velocity"] == "unit-normal",
                     math.pi * ((radius + 0.1) ** 2 - radius**2), -2 * math.pi * 0.1)
    table["area_error"] = (table["area"] - math.pi * radius**2 - exact) / (math.pi * radius**2)
    print(table[["name", "steps", "status", "area", "area_error", "cpu_s"]].to_string(index=False))
    table.to_csv(sys.argv[1] if len(sys.argv) > 1 else "sweep.csv", index=False)
