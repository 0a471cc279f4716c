"""Sweeps: points from a grid or samples, run on local threads (the native sweep, GIL
released) or as Dask tasks, gathered into one pandas table."""

from __future__ import annotations

import itertools
import os
from dataclasses import dataclass
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


@dataclass
class Sweep:
    """What every point of a sweep shares: the model (its source text and options,
    compiled where the point runs), the parameter values of every point, the outputs,
    the run options and the summary function."""

    spec: tuple
    fixed: Dict[str, Any]
    outputs: List[str]
    options: Dict[str, Any]
    summary: Optional[Callable[[Any], Dict[str, Any]]] = None

    def rows(self, points: Sequence[Dict[str, Any]], jobs: int = 1) -> List[Dict[str, Any]]:
        """Runs `points` here on `jobs` threads (the work of one Dask task, which
        compiles the model from its shipped source); one row dict per point."""
        from . import Result, _param_pairs

        summary = self.summary
        native_points = [_param_pairs({**self.fixed, **p}) for p in points]
        outcomes = _unimo.sweep(
            self.spec, native_points, self.outputs, jobs, summary is not None, self.options
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


def run(
    sweep: Sweep,
    points: List[Dict[str, Any]],
    jobs: Optional[int] = None,
    client: Any = None,
    chunks: Optional[int] = None,
):
    import pandas as pd

    if client is None:
        jobs = jobs or os.cpu_count() or 1
        # Bounded batches: with a summary, whole results are kept per batch only.
        batch = 256 if sweep.summary is not None else max(len(points), 1)
        rows: List[Dict[str, Any]] = []
        for start in range(0, len(points), batch):
            rows.extend(sweep.rows(points[start : start + batch], jobs))
    else:
        workers = len(client.scheduler_info().get("workers", {})) or 1
        n = max(1, min(len(points), chunks or 4 * workers))
        bounds = [round(k * len(points) / n) for k in range(n + 1)]
        parts = [points[bounds[k] : bounds[k + 1]] for k in range(n)]
        futures = [client.submit(sweep.rows, part, jobs or 1, pure=False) for part in parts]
        rows = [row for part in client.gather(futures) for row in part]
    return pd.DataFrame(rows)
