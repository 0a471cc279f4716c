"""Sweep throughput: 1,000 runs of the bouncing ball and 100 of FlySlideRoll (stop
time 5), on 1 and 2 local threads and on a Dask LocalCluster of 2 worker processes.
Also the cost of one compilation and one run alone (each point compiles the model).

Usage: python bench/sweep.py [--ball N] [--fsr N]   (needs the unimo package, dask)
Prints one Markdown table."""

import argparse
import statistics
import time
from pathlib import Path

import numpy as np

import unimo

ROOT = Path(__file__).resolve().parents[1]
MODELS = {
    "BouncingBall": (ROOT / "models" / "BouncingBall.mo", "e", (0.7, 0.9)),
    "FlySlideRoll": (ROOT / "models" / "FlySlideRoll.mo", "k", (0.3, 0.9)),
}
STOP = 5.0


def median_time(f, repeat=5):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ball", type=int, default=1000)
    ap.add_argument("--fsr", type=int, default=100)
    args = ap.parse_args()
    from dask.distributed import Client, LocalCluster

    cluster = LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    client = Client(cluster)
    client.run(lambda: __import__("unimo"))  # workers import the package before timing
    rows = []
    for name, n in (("BouncingBall", args.ball), ("FlySlideRoll", args.fsr)):
        path, param, (lo, hi) = MODELS[name]
        model = unimo.compile(path)
        compile_s = median_time(lambda: unimo.compile(path))
        run_s = median_time(lambda: model.simulate(stop_time=STOP))
        samples = [{param: float(v)} for v in np.linspace(lo, hi, n)]
        figures = {}
        for label, kw in (
            ("1 thread", {"jobs": 1}),
            ("2 threads", {"jobs": 2}),
            ("LocalCluster 2x1", {"client": client}),
        ):
            t = time.perf_counter()
            table = model.sweep(samples, stop_time=STOP, **kw)
            seconds = time.perf_counter() - t
            failed = int((table.status != "ok").sum())
            figures[label] = (n / seconds, seconds, failed)
        rows.append((name, n, compile_s, run_s, figures))
    client.close()
    cluster.close()
    print(f"| model | runs | compile (ms) | run to t={STOP:g} (ms) | "
          "1 thread (runs/s) | 2 threads (runs/s) | LocalCluster 2x1 (runs/s) | failed |")
    print("|---|---|---|---|---|---|---|---|")
    for name, n, c, r, f in rows:
        cells = [f"{f[k][0]:.1f} ({f[k][1]:.2f} s)" for k in f]
        failed = "/".join(str(f[k][2]) for k in f)
        print(f"| {name} | {n} | {c * 1e3:.2f} | {r * 1e3:.2f} | " + " | ".join(cells) + f" | {failed} |")


if __name__ == "__main__":
    main()
