#!/usr/bin/env python3
"""Builds refs/bruss2d.csv, BRUSS2D's reference values at t = 11.5, from tight runs of two
independent solvers, and says how far they agree (refs/bruss2d.md records the result).

  python3 bench/compare/bruss2d_reference.py UNIMO_BINARY

Runs (not timed): unimo's Radau5 (models/Brusselator2D.mo, sparse LU) and SUNDIALS IDA
(ida/ida_compare, BDF with KLU), each at rtol 1e-12 and 1e-13 (atol = rtol * 1e-2). The
reference written is unimo's Radau5 at 1e-13 (order 5, and its two tolerances agree best);
IDA's run at 1e-13 is the independent check.
Column order: the peers' layout, (u, v) of cell (i, j) at 2 ((i - 1) N + (j - 1)), named
"u[i,j]", "v[i,j]" (quoted, as unimo writes them) as in unimo's results.
"""
import csv
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
N, T_END = 32, 11.5
NAMES = [f"{s}[{i},{j}]" for i in range(1, N + 1) for j in range(1, N + 1) for s in "uv"]


def unimo(binary, rtol):
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "bruss.csv"
        subprocess.run([binary, "simulate", str(REPO / "models/Brusselator2D.mo"),
                        "--method", "radau5", "--tolerance", repr(rtol),
                        "--atol", repr(rtol * 1e-2), "--points", "1", "-o", str(out)],
                       check=True)
        rows = list(csv.reader(out.open()))
    header, last = rows[0], rows[-1]
    assert float(last[0]) == T_END
    column = {name: k for k, name in enumerate(header)}
    return [float(last[column[name]]) for name in NAMES]


def ida(rtol):
    line = subprocess.run([str(HERE / "ida/ida_compare"), "solve", "bruss2d", repr(rtol),
                           repr(rtol * 1e-2)], check=True, capture_output=True,
                          text=True).stdout.strip()
    values = [float(v) for v in line.split(",")]
    assert values[0] == T_END
    return values[1:]


def agree(a, b):
    return max(abs(x - y) / abs(y) for x, y in zip(a, b))


def main():
    binary = sys.argv[1]
    runs = {("unimo radau5", t): unimo(binary, t) for t in (1e-12, 1e-13)}
    runs.update({("IDA", t): ida(t) for t in (1e-12, 1e-13)})
    reference = runs[("unimo radau5", 1e-13)]
    for (tool, rtol), y in runs.items():
        print(f"{tool} rtol {rtol:.0e}: max relative difference to the reference "
              f"{agree(y, reference):.2e}")
    (HERE / "refs/bruss2d.csv").write_text(
        "time," + ",".join(f'"{name}"' for name in NAMES) + "\n"
        + ",".join([repr(T_END)] + [repr(v) for v in reference]) + "\n")
    print("wrote refs/bruss2d.csv")


if __name__ == "__main__":
    main()
