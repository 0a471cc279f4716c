#!/usr/bin/env python3
"""SciPy side of the unimo comparison: solve_ivp with Radau and BDF, analytic Jacobians.

ROBER: solve_ivp has no DAE support, so the DAE's algebraic equation y1 + y2 + y3 = 1 is
eliminated exactly (y3 = 1 - y1 - y2) and the remaining two ODEs are integrated; y3 is
recovered at the end. The error control therefore acts on y1 and y2 only.
HIRES, VDPOL: plain ODEs.

All solve_ivp options are defaults apart from rtol, a scalar atol and `jac`. One call per
run over the whole interval; solve_ivp stores every step (t_eval=None), which is how the
step count is read (len(sol.t) - 1).

Usage: scipy_compare.py [RUNS] [PROBLEM...]     (RUNS default 3)
Prints one tab-separated line per configuration:
problem tool method rtol atol scd steps median_ms status
"""
import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

ROBER_REF = [2.083340149701255e-8, 8.333360770334713e-14, 0.9999999791665050]
HIRES_REF = [7.371312573325668e-4, 1.442485726316185e-4, 5.888729740967575e-5,
             1.175651343283149e-3, 2.386356198831331e-3, 6.238968252742796e-3,
             2.849998395185769e-3, 2.850001604814231e-3]
VDPOL_REF = [1.706167732170483, -0.8928097010247975]
EPS = 1e-6


def rober_f(t, y):
    y1, y2 = y
    y3 = 1.0 - y1 - y2
    return np.array([-0.04 * y1 + 1e4 * y2 * y3,
                     0.04 * y1 - 1e4 * y2 * y3 - 3e7 * y2 * y2])


def rober_jac(t, y):
    y1, y2 = y
    a = 1e4 * (1.0 - y1 - 2.0 * y2)
    return np.array([[-0.04 - 1e4 * y2, a],
                     [0.04 + 1e4 * y2, -a - 6e7 * y2]])


def rober_full(y):
    return [y[0], y[1], 1.0 - y[0] - y[1]]


def hires_f(t, x):
    return np.array([
        -1.71 * x[0] + 0.43 * x[1] + 8.32 * x[2] + 0.0007,
        1.71 * x[0] - 8.75 * x[1],
        -10.03 * x[2] + 0.43 * x[3] + 0.035 * x[4],
        8.32 * x[1] + 1.71 * x[2] - 1.12 * x[3],
        -1.745 * x[4] + 0.43 * x[5] + 0.43 * x[6],
        -280.0 * x[5] * x[7] + 0.69 * x[3] + 1.71 * x[4] - 0.43 * x[5] + 0.69 * x[6],
        280.0 * x[5] * x[7] - 1.81 * x[6],
        -280.0 * x[5] * x[7] + 1.81 * x[6],
    ])


HIRES_J0 = np.zeros((8, 8))
for (i, j), v in {(0, 0): -1.71, (0, 1): 0.43, (0, 2): 8.32, (1, 0): 1.71, (1, 1): -8.75,
                  (2, 2): -10.03, (2, 3): 0.43, (2, 4): 0.035, (3, 1): 8.32, (3, 2): 1.71,
                  (3, 3): -1.12, (4, 4): -1.745, (4, 5): 0.43, (4, 6): 0.43, (5, 3): 0.69,
                  (5, 4): 1.71, (5, 5): -0.43, (5, 6): 0.69, (6, 6): -1.81,
                  (7, 6): 1.81}.items():
    HIRES_J0[i, j] = v


def hires_jac(t, x):
    J = HIRES_J0.copy()
    a, b = 280.0 * x[7], 280.0 * x[5]
    J[5, 5] -= a
    J[5, 7] = -b
    J[6, 5] = a
    J[6, 7] = b
    J[7, 5] = -a
    J[7, 7] = -b
    return J


def vdpol_f(t, y):
    return np.array([y[1], ((1.0 - y[0] * y[0]) * y[1] - y[0]) / EPS])


def vdpol_jac(t, y):
    return np.array([[0.0, 1.0],
                     [(-2.0 * y[0] * y[1] - 1.0) / EPS, (1.0 - y[0] * y[0]) / EPS]])


PROBLEMS = {
    "rober": ("ROBER", rober_f, rober_jac, [1.0, 0.0], 1e11, 1e-6, ROBER_REF, rober_full),
    "hires": ("HIRES", hires_f, hires_jac, [1, 0, 0, 0, 0, 0, 0, 0.0057], 321.8122, 1e-2,
              HIRES_REF, list),
    "vdpol": ("VDPOL", vdpol_f, vdpol_jac, [2.0, 0.0], 2.0, 1e-2, VDPOL_REF, list),
}


def scd(y, ref):
    worst = 0.0
    for a, b in zip(y, ref):
        e = abs((a - b) / b)
        worst = max(worst, math.inf if math.isnan(e) else e)
    return -math.log10(worst) if worst > 0 else 16.0


def main():
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    keys = sys.argv[2:] or ["rober", "hires", "vdpol"]
    for key in keys:
        name, f, jac, y0, t_end, factor, ref, full = PROBLEMS[key]
        for method in ["Radau", "BDF"]:
            for rtol in [1e-4, 1e-6, 1e-8, 1e-10]:
                atol = rtol * factor
                times = []
                sol = None
                for _ in range(max(runs, 1)):
                    t0 = time.perf_counter()
                    sol = solve_ivp(f, (0.0, t_end), np.array(y0, dtype=float),
                                    method=method, rtol=rtol, atol=atol, jac=jac)
                    times.append((time.perf_counter() - t0) * 1e3)
                times.sort()
                median = times[len(times) // 2]
                steps = len(sol.t) - 1
                if sol.status != 0 or sol.t[-1] != t_end:
                    msg = f"{sol.message} (t = {sol.t[-1]:g})".replace("\t", " ")
                    print(f"{name}\tSciPy\t{method}\t{rtol:.0e}\t{atol:.0e}\t-\t{steps}\t"
                          f"{median:.3f}\tFAILED: {msg}", flush=True)
                    continue
                y = [float(v) for v in full(sol.y[:, -1])]
                print(f"{name} SciPy {method} {rtol:.0e}: y = {y}", file=sys.stderr)
                print(f"{name}\tSciPy\t{method}\t{rtol:.0e}\t{atol:.0e}\t{scd(y, ref):.2f}\t"
                      f"{steps}\t{median:.3f}\tok", flush=True)


if __name__ == "__main__":
    main()
