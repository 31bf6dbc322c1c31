"""Ensembles and parameter sweeps on dask.distributed: the same code on a LocalCluster here and
on a cluster scheduler elsewhere, the results gathered into one table (a pandas DataFrame)."""

from __future__ import annotations

import ast
import inspect
import itertools
import numbers
import sys
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


def _is_main_test(test: ast.expr) -> bool:
    """Whether test is ``__name__ == "__main__"`` (either way round)."""
    if not (isinstance(test, ast.Compare) and len(test.ops) == 1 and
            isinstance(test.ops[0], ast.Eq)):
        return False
    sides = [test.left, test.comparators[0]]
    return (any(isinstance(x, ast.Name) and x.id == "__name__" for x in sides) and
            any(isinstance(x, ast.Constant) and x.value == "__main__" for x in sides))


def _unguarded_call() -> str | None:
    """Where the script being run (__main__) calls into sweep outside an ``if __name__ ==
    "__main__":`` block, as "file, line n", or None when it does so inside one (or there is no
    script file: an interactive session, ``python -c``). The worker processes of a LocalCluster
    import the script again, and an unguarded call would start clusters in each of them."""
    main = sys.modules.get("__main__")
    if getattr(main, "__file__", None) is None:
        return None
    frame = sys._getframe(1)
    while frame is not None and not (frame.f_code.co_name == "<module>" and
                                     frame.f_globals is vars(main)):
        frame = frame.f_back
    if frame is None:
        return None
    path, line = frame.f_code.co_filename, frame.f_lineno
    try:
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
    except (OSError, SyntaxError, ValueError):
        return None
    for node in ast.walk(tree):
        if (isinstance(node, ast.If) and _is_main_test(node.test) and
                node.body[0].lineno <= line <= node.body[-1].end_lineno):
            return None
    return f"{path}, line {line}"


def sweep(cases: Iterable[dict[str, Any]], *, client=None, workers: int = 2):
    """Runs every case (a dict of slc.run arguments: interface, velocity, t_end, steps, params,
    ...; 'name' labels its row) on a dask.distributed cluster and returns one pandas DataFrame, a
    row per case in the order given (run_case's columns).

    client: a ``distributed.Client`` of any cluster whose workers can ``import slc``; None starts
    a LocalCluster of ``workers`` single-threaded processes here and closes it after. A case that
    fails with bad input raises its ValueError here; a run's own failure is a row with status
    "error".

    The worker processes a LocalCluster starts import the calling script again: a script must call
    sweep under ``if __name__ == "__main__":``, and RuntimeError says so before any starts.
    """
    cases = list(cases)
    for i, case in enumerate(cases):
        _check(case, i)
    where = None if client is not None else _unguarded_call()
    if where is not None:
        raise RuntimeError(f"slc.sweep starts worker processes that import the script again: put "
                           f"the script's work under 'if __name__ == \"__main__\":' ({where} "
                           "calls it outside one)")
    import pandas as pd

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
