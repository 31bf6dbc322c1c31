"""Ensembles and parameter sweeps on dask.distributed: the same code on a LocalCluster here and
on a cluster scheduler elsewhere, the results gathered into one table (a pandas DataFrame)."""

from __future__ import annotations

import inspect
import itertools
import numbers
from typing import Any, Iterable

from ._interface import Interface
from ._run import Problem, run

# The columns every row of a sweep has, after its case's own scalar entries.
RESULT_COLUMNS = ["status", "t", "area", "area_change", "length", "components", "segments",
                  "e_inf", "cpu_s", "wall_s", "message"]

_RUN_PARAMETERS = {name for name, p in inspect.signature(run).parameters.items()
                   if p.kind != p.VAR_KEYWORD} - {"observer", "frames"}


def grid(**axes: Iterable[Any]) -> list[dict[str, Any]]:
    """Every combination of the values given per key, as a list of cases for sweep():
    ``grid(velocity=["curvature"], t_end=[0.1], steps=[20, 40])`` is two cases."""
    keys = list(axes)
    return [dict(zip(keys, values)) for values in itertools.product(*(axes[k] for k in keys))]


def _check(case: dict[str, Any], index: int) -> None:
    if not isinstance(case, dict):
        raise TypeError(f"case {index} must be a dict of run() arguments, got "
                        f"{type(case).__name__}")
    unknown = sorted(set(case) - _RUN_PARAMETERS - {"name"})
    if unknown:
        raise ValueError(f"case {index} has {', '.join(map(repr, unknown))}, not an argument of "
                         "slc.run (nor 'name', a label; a law's parameters go in 'params')")
    if "interface" not in case:
        raise ValueError(f"case {index} has no 'interface' (curves, or an slc.Problem)")


def _scalar(value) -> bool:
    return isinstance(value, (str, bool, numbers.Number))


def run_case(case: dict[str, Any]) -> dict[str, Any]:
    """One row of a sweep: the case's scalar entries (its name, the law's name, t_end, steps,
    params as params.k) and what the run gave (RESULT_COLUMNS). Runs on one thread unless the
    case sets threads, so that workers do not compete for cores."""
    args = {k: v for k, v in case.items() if k != "name"}
    args.setdefault("threads", 1)
    subject = args.pop("interface")
    row: dict[str, Any] = {}
    if "name" in case:
        row["name"] = case["name"]
    if isinstance(subject, Problem):
        row["problem"] = subject.name
    for k, v in case.items():
        if k == "params":
            row.update({f"params.{p}": x for p, x in v.items()})
        elif k not in ("name", "interface") and _scalar(v):
            row[k] = v
    start = subject.interface.area if isinstance(subject, Problem) else \
        (subject if isinstance(subject, Interface) else Interface(subject)).area
    r = run(subject, **args)
    s = r.summary
    row.update(status=r.status, t=r.t, area=r.interface.area,
               area_change=(r.interface.area - start) / start if start else float("nan"),
               length=r.interface.length, components=len(r.interface),
               segments=s.get("segments"), e_inf=s.get("e_inf"), cpu_s=s.get("cpu_s"),
               wall_s=s.get("wall_s"), message=r.message)
    return row


def sweep(cases: Iterable[dict[str, Any]], *, client=None, workers: int = 2):
    """Runs every case (a dict of slc.run arguments: interface, velocity, t_end, steps, params,
    ...; 'name' labels its row) on a dask.distributed cluster and returns one pandas DataFrame, a
    row per case in the order given (run_case's columns).

    client: a ``distributed.Client`` of any cluster whose workers can ``import slc``; None starts
    a LocalCluster of ``workers`` single-threaded processes here and closes it after. A case that
    fails with bad input raises its ValueError here; a run's own failure is a row with status
    "error".
    """
    import pandas as pd

    cases = list(cases)
    for i, case in enumerate(cases):
        _check(case, i)
    if client is None:
        from distributed import Client, LocalCluster

        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as c:
            rows = c.gather(c.map(run_case, cases, pure=False))
    else:
        rows = client.gather(client.map(run_case, cases, pure=False))
    frame = pd.DataFrame(rows)
    first = [c for c in frame.columns if c not in RESULT_COLUMNS]
    return frame[first + RESULT_COLUMNS]
