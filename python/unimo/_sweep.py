"""Sweeps: points from a grid or samples, run on local threads (the native sweep, GIL
released) or as Dask tasks, gathered into one pandas table."""

from __future__ import annotations

import itertools
import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence

from . import _unimo


def samples(grid_or_samples: Any) -> List[Dict[str, Any]]:
    """A dict of lists -> every combination (first key slowest); a list of dicts or a
    DataFrame -> its rows."""
    if hasattr(grid_or_samples, "to_dict") and hasattr(grid_or_samples, "columns"):
        return [dict(r) for r in grid_or_samples.to_dict("records")]
    if isinstance(grid_or_samples, Mapping):
        names = list(grid_or_samples)
        values = [list(grid_or_samples[n]) for n in names]
        return [dict(zip(names, combo)) for combo in itertools.product(*values)]
    return [dict(s) for s in grid_or_samples]


def _rows(
    spec: tuple,
    fixed: Dict[str, Any],
    points: Sequence[Dict[str, Any]],
    outputs: List[str],
    options: Dict[str, Any],
    jobs: int,
    summary: Optional[Callable[[Any], Dict[str, Any]]],
) -> List[Dict[str, Any]]:
    """Runs `points` here on `jobs` threads; one row dict per point."""
    from . import Result, _param_pairs

    native_points = [_param_pairs({**fixed, **p}) for p in points]
    outcomes = _unimo.sweep(
        spec, native_points, outputs, jobs, summary is not None, options
    )
    rows = []
    for point, outcome in zip(points, outcomes):
        row: Dict[str, Any] = dict(point)
        error = outcome["error"]
        row["status"] = "ok" if error is None else "failed"
        row["error_code"] = None if error is None else error[1]
        row["error_message"] = None if error is None else error[2]
        row["error_location"] = None if error is None else error[3]
        row.update(dict(outcome["values"]))
        if summary is not None and error is None and "result" in outcome:
            result = Result(outcome["result"])
            result.stats = dict(outcome["stats"])
            try:
                row.update(summary(result))
            except Exception as e:  # a summary that fails marks its point
                row["status"] = "failed"
                row["error_code"] = "summary"
                row["error_message"] = f"{type(e).__name__}: {e}"
        rows.append(row)
    return rows


def run_chunk(spec, fixed, points, outputs, options, summary, jobs=1):
    """One Dask task: compiles the model from its shipped source and runs `points`."""
    return _rows(spec, fixed, points, outputs, options, jobs, summary)


def run(
    spec: tuple,
    fixed: Dict[str, Any],
    points: List[Dict[str, Any]],
    outputs: List[str],
    options: Dict[str, Any],
    jobs: Optional[int] = None,
    client: Any = None,
    summary: Optional[Callable[[Any], Dict[str, Any]]] = None,
    chunks: Optional[int] = None,
):
    import pandas as pd

    if client is None:
        jobs = jobs or os.cpu_count() or 1
        # Bounded batches: with a summary, whole results are kept per batch only.
        batch = 256 if summary is not None else max(len(points), 1)
        rows: List[Dict[str, Any]] = []
        for start in range(0, len(points), batch):
            part = points[start : start + batch]
            rows.extend(_rows(spec, fixed, part, outputs, options, jobs, summary))
    else:
        workers = len(client.scheduler_info().get("workers", {})) or 1
        n = max(1, min(len(points), chunks or 4 * workers))
        bounds = [round(k * len(points) / n) for k in range(n + 1)]
        parts = [points[bounds[k] : bounds[k + 1]] for k in range(n)]
        futures = [
            client.submit(
                run_chunk, spec, fixed, part, outputs, options, summary,
                jobs or 1, pure=False,
            )
            for part in parts
        ]
        rows = [row for part in client.gather(futures) for row in part]
    return pd.DataFrame(rows)

