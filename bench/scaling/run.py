#!/usr/bin/env python3
"""Scaling benchmark (issue #23 point 5): wall time per phase of `unimo simulate --stats`
on the chain model at growing N, and the growth exponents (log-log slopes).

    bench/scaling/run.py [--bin target/release/unimo] [--sizes 1000,3000,...]
                         [--kinds explicit,newton] [--methods bdf,radau5] [--repeat 3]
                         [--engine tape|native]

Prints one Markdown table per (kind, method): the median of each phase over the
repeats per N (wall times; `cpu` is the process's user and system CPU time), then the
slope between successive N and the least-squares slope over all N for the total, the
CPU time, `simulate`, `integrate`, `output` and the compile-time phases. The load
average at the start and the end is printed too (a shared machine's wall times grow
with it).
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from gen_chain import chain  # noqa: E402

PHASES = ["parse", "flatten", "lower", "structure", "compile", "native", "initialize",
          "integrate", "evaluation", "linear_algebra", "events", "output", "simulate",
          "write"]


def run_once(binary, path, method, engine):
    started = time.perf_counter()
    before = os.times()
    args = [binary, "simulate", path, "--method", method, "--stats", "-o", os.devnull]
    if engine:
        args += ["--engine", engine]
    done = subprocess.run(args, capture_output=True, text=True)
    wall = (time.perf_counter() - started) * 1e3
    after = os.times()
    # User and system CPU time of the process (all its threads): on a shared machine
    # the wall times also hold the time the process waited for a core.
    cpu = ((after.children_user - before.children_user)
           + (after.children_system - before.children_system)) * 1e3
    if done.returncode != 0:
        raise SystemExit(f"{path} ({method}) failed:\n{done.stderr}")
    stats = json.loads(done.stderr.strip().splitlines()[-1])
    row = dict(stats["phases_ms"])
    row["total"] = wall
    row["cpu"] = cpu
    row["steps"] = stats["steps"]
    row["rhs"] = stats["rhs"]
    row["sparse_lu"] = stats["sparse_lu"]
    return row


def slope(xs, ys):
    lx = [math.log(x) for x in xs]
    ly = [math.log(max(y, 1e-9)) for y in ys]
    mx, my = statistics.fmean(lx), statistics.fmean(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def table(kind, method, sizes, rows):
    print(f"\n### {kind} chain, {method}\n")
    cols = ["total", "cpu"] + PHASES
    print("| N | steps | rhs | sparse LU | " + " | ".join(cols) + " |")
    print("|---" * (len(cols) + 4) + "|")
    for n in sizes:
        r = rows[n]
        cells = [f"{r[c]:.0f}" for c in cols]
        print(f"| {n} | {r['steps']} | {r['rhs']} | {r['sparse_lu']} | " + " | ".join(cells) + " |")
    for c in ["total", "cpu", "simulate", "integrate", "output", "structure", "compile", "write"]:
        ys = [rows[n][c] for n in sizes]
        steps = [math.log(ys[k + 1] / max(ys[k], 1e-9)) / math.log(sizes[k + 1] / sizes[k])
                 for k in range(len(sizes) - 1)]
        print(f"\n- `{c}`: exponent between successive N "
              + ", ".join(f"{s:.2f}" for s in steps)
              + f"; least squares over all N {slope(sizes, ys):.2f}", end="")
    print()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bin", default=os.path.join(HERE, "..", "..", "target", "release", "unimo"))
    p.add_argument("--sizes", default="1000,3000,10000,30000,50000")
    p.add_argument("--kinds", default="explicit,newton")
    p.add_argument("--methods", default="bdf,radau5")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--engine", default="", help="passed to --engine (default: unimo's choice)")
    a = p.parse_args()
    sizes = [int(s) for s in a.sizes.split(",")]
    print("load average at start: " + " ".join(f"{x:.2f}" for x in os.getloadavg()))
    with tempfile.TemporaryDirectory() as tmp:
        for kind in a.kinds.split(","):
            for method in a.methods.split(","):
                rows = {}
                for n in sizes:
                    path = os.path.join(tmp, f"chain_{kind}_{n}.mo")
                    with open(path, "w") as f:
                        f.write(chain(n, kind))
                    runs = [run_once(a.bin, path, method, a.engine) for _ in range(a.repeat)]
                    rows[n] = {k: (statistics.median(r[k] for r in runs)
                                   if isinstance(runs[0][k], float) else runs[0][k])
                               for k in runs[0]}
                    print(f"{kind} {method} N={n}: {rows[n]['total']:.0f} ms",
                          file=sys.stderr, flush=True)
                table(kind, method, sizes, rows)
    print("\nload average at end: " + " ".join(f"{x:.2f}" for x in os.getloadavg()))


if __name__ == "__main__":
    main()
