#!/usr/bin/env python3
"""SciPy side of the unimo comparison: solve_ivp with Radau and BDF, analytic Jacobians.

ROBER: solve_ivp has no DAE support, so the DAE's algebraic equation y1 + y2 + y3 = 1 is
eliminated exactly (y3 = 1 - y1 - y2) and the remaining two ODEs are integrated; y3 is
recovered at the end. The error control therefore acts on y1 and y2 only.
HIRES, VDPOL, POLLU: plain ODEs with dense analytic Jacobians.
BRUSS2D: 2 N^2 = 2,048 ODEs with an analytic Jacobian given as a scipy.sparse CSC matrix, so
that solve_ivp factors it with SuperLU (splu). Its reference values are read from
refs/bruss2d.csv. SciPy's Radau takes minutes per run on it (over 2 minutes at rtol 1e-4
on the shared machine: a complex sparse LU per step through Python), so BRUSS2D is run once
per configuration, and Radau only at the tolerances listed in BRUSS_RADAU_RTOLS (none by
default); the others are reported as not run.

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

from pathlib import Path

import numpy as np
from scipy import sparse
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


# ---- POLLU (test set pollu.f): 25 reactions, r_k = k_k y_a (y_b) ----------------------
POLLU_K = [0.35, 26.6, 1.23e4, 8.6e-4, 8.2e-4, 1.5e4, 1.3e-4, 2.4e4, 1.65e4, 9.0e3, 2.2e-2,
           1.2e4, 1.88, 1.63e4, 4.8e6, 3.5e-4, 1.75e-2, 1.0e8, 4.44e11, 1.24e3, 2.1, 5.78,
           4.74e-2, 1.78e3, 3.12]
# Reactants of each reaction (0-based species), None: first order.
POLLU_REACTANTS = [(0, None), (1, 3), (4, 1), (6, None), (6, None), (6, 5), (8, None), (8, 5),
                   (10, 1), (10, 0), (12, None), (9, 1), (13, None), (0, 5), (2, None),
                   (3, None), (3, None), (15, None), (15, None), (16, 5), (18, None),
                   (18, None), (0, 3), (18, 0), (19, None)]
# Net production of each reaction: (species, coefficient).
POLLU_STOICH = [
    [(0, -1), (1, 1), (2, 1)], [(0, 1), (1, -1), (3, -1)], [(0, 1), (1, -1), (4, -1), (5, 1)],
    [(4, 2), (6, -1), (7, 1)], [(6, -1), (7, 1)], [(4, 1), (5, -1), (6, -1), (7, 1)],
    [(4, 1), (7, 1), (8, -1), (9, 1)], [(5, -1), (8, -1), (10, 1)],
    [(0, 1), (1, -1), (9, 1), (10, -1), (11, 1)], [(0, -1), (10, -1), (12, 1)],
    [(0, 1), (10, 1), (12, -1)], [(0, 1), (1, -1), (9, -1), (13, 1)],
    [(4, 1), (6, 1), (13, -1)], [(0, -1), (5, -1), (14, 1)], [(2, -1), (3, 1)],
    [(3, -1), (15, 1)], [(2, 1), (3, -1)], [(5, 2), (15, -1)], [(2, 1), (15, -1)],
    [(4, 1), (5, -1), (16, -1), (17, 1)], [(1, 1), (18, -1)], [(0, 1), (2, 1), (18, -1)],
    [(0, -1), (3, -1), (18, 1)], [(0, -1), (18, -1), (19, 1)], [(0, 1), (18, 1), (19, -1)]]
POLLU_Y0 = [0, 0.2, 0, 0.04, 0, 0, 0.1, 0.3, 0.01, 0, 0, 0, 0, 0, 0, 0, 0.007, 0, 0, 0]
# pollu.f's solut at t = 60 (RADAU5 in quadruple-like precision on a Cray C90).
POLLU_REF = [0.5646255480022769e-1, 0.1342484130422339, 0.4139734331099427e-8,
             0.5523140207484359e-2, 0.2018977262302196e-6, 0.1464541863493966e-6,
             0.7784249118997964e-1, 0.3245075353396018, 0.7494013383880406e-2,
             0.1622293157301561e-7, 0.1135863833257075e-7, 0.2230505975721359e-2,
             0.2087162882798630e-3, 0.1396921016840158e-4, 0.8964884856898295e-2,
             0.4352846369330103e-17, 0.6899219696263405e-2, 0.1007803037365946e-3,
             0.1772146513969984e-5, 0.5682943292316392e-4]


def pollu_f_written_out(y):
    """pollu.f's feval, written out: checks the reaction table above (`check`)."""
    r = [POLLU_K[k] * y[a] * (1.0 if b is None else y[b])
         for k, (a, b) in enumerate(POLLU_REACTANTS)]
    r = [0.0] + r  # 1-based like the test set
    return np.array([
        -r[1] - r[10] - r[14] - r[23] - r[24] + r[2] + r[3] + r[9] + r[11] + r[12] + r[22] + r[25],
        -r[2] - r[3] - r[9] - r[12] + r[1] + r[21],
        -r[15] + r[1] + r[17] + r[19] + r[22],
        -r[2] - r[16] - r[17] - r[23] + r[15],
        -r[3] + r[4] + r[4] + r[6] + r[7] + r[13] + r[20],
        -r[6] - r[8] - r[14] - r[20] + r[3] + r[18] + r[18],
        -r[4] - r[5] - r[6] + r[13],
        r[4] + r[5] + r[6] + r[7],
        -r[7] - r[8],
        -r[12] + r[7] + r[9],
        -r[9] - r[10] + r[8] + r[11],
        r[9],
        -r[11] + r[10],
        -r[13] + r[12],
        r[14],
        -r[18] - r[19] + r[16],
        -r[20],
        r[20],
        -r[21] - r[22] - r[24] + r[23] + r[25],
        -r[25] + r[24]])


# f = S r(y), J = S dr/dy, r_k = k_k * y_a (* y_b); J = S dr/dy --------------------------
POLLU_S = np.zeros((20, 25))
for _k, _terms in enumerate(POLLU_STOICH):
    for _i, _coef in _terms:
        POLLU_S[_i, _k] = _coef
POLLU_KV = np.array(POLLU_K)
POLLU_A = np.array([a for a, _ in POLLU_REACTANTS])
POLLU_B = np.array([-1 if b is None else b for _, b in POLLU_REACTANTS])
POLLU_TWO = POLLU_B >= 0


def pollu_rates(y):
    r = POLLU_KV * y[POLLU_A]
    r[POLLU_TWO] *= y[POLLU_B[POLLU_TWO]]
    return r


def pollu_f(t, y):
    return POLLU_S @ pollu_rates(y)


def pollu_jac(t, y):
    dr = np.zeros((25, 20))
    for k in range(25):
        a, b = POLLU_A[k], POLLU_B[k]
        if b < 0:
            dr[k, a] += POLLU_KV[k]
        else:
            dr[k, a] += POLLU_KV[k] * y[b]
            dr[k, b] += POLLU_KV[k] * y[a]
    return POLLU_S @ dr


# ---- BRUSS2D: u, v on an N x N periodic grid, state (u, v) of cell (i, j) at 2 (i N + j) --
BRUSS_N, BRUSS_ALPHA, BRUSS_T_END = 32, 1.0, 11.5
BRUSS_C = BRUSS_ALPHA * BRUSS_N * BRUSS_N
BRUSS_RADAU_RTOLS = []


def bruss_init():
    g = np.arange(BRUSS_N) / BRUSS_N
    shape = 22.0 * g * (1.0 - g) ** 1.5, 27.0 * g * (1.0 - g) ** 1.5
    x = np.empty(2 * BRUSS_N * BRUSS_N)
    x[0::2] = np.tile(shape[0][None, :], (BRUSS_N, 1)).ravel()  # u(x_i, y_j) = 22 y (1 - y)^1.5
    x[1::2] = np.tile(shape[1][:, None], (1, BRUSS_N)).ravel()  # v(x_i, y_j) = 27 x (1 - x)^1.5
    return x


def bruss_lap(a):
    return np.roll(a, 1, 0) + np.roll(a, -1, 0) + np.roll(a, 1, 1) + np.roll(a, -1, 1) - 4.0 * a


def bruss_f(t, x):
    u = x[0::2].reshape(BRUSS_N, BRUSS_N)
    v = x[1::2].reshape(BRUSS_N, BRUSS_N)
    uuv = u * u * v
    d = np.empty_like(x)
    d[0::2] = (1.0 + uuv - 4.4 * u + BRUSS_C * bruss_lap(u)).ravel()
    d[1::2] = (3.4 * u - uuv + BRUSS_C * bruss_lap(v)).ravel()
    return d


def _bruss_diffusion():
    n = BRUSS_N
    ring = sparse.diags([np.ones(n - 1), np.ones(n - 1)], [1, -1], shape=(n, n)).tolil()
    ring[0, n - 1] = ring[n - 1, 0] = 1.0
    lap1 = ring.tocsr() - 2.0 * sparse.identity(n)
    lap2 = sparse.kron(lap1, sparse.identity(n)) + sparse.kron(sparse.identity(n), lap1)
    return (BRUSS_C * sparse.kron(lap2, sparse.identity(2))).tocsc()


BRUSS_D = _bruss_diffusion()


def bruss_jac(t, x):
    u, v = x[0::2], x[1::2]
    n = x.size
    main = np.empty(n)
    main[0::2] = 2.0 * u * v - 4.4
    main[1::2] = -u * u
    upper = np.zeros(n - 1)
    upper[0::2] = u * u
    lower = np.zeros(n - 1)
    lower[0::2] = 3.4 - 2.0 * u * v
    return (BRUSS_D + sparse.diags([lower, main, upper], [-1, 0, 1])).tocsc()


def read_reference(name):
    lines = (Path(__file__).resolve().parent / "refs" / name).read_text().splitlines()
    return [float(v) for v in lines[1].split(",")[1:]]


PROBLEMS = {
    "rober": ("ROBER", rober_f, rober_jac, [1.0, 0.0], 1e11, 1e-6, ROBER_REF, rober_full),
    "hires": ("HIRES", hires_f, hires_jac, [1, 0, 0, 0, 0, 0, 0, 0.0057], 321.8122, 1e-2,
              HIRES_REF, list),
    "vdpol": ("VDPOL", vdpol_f, vdpol_jac, [2.0, 0.0], 2.0, 1e-2, VDPOL_REF, list),
    "pollu": ("POLLU", pollu_f, pollu_jac, POLLU_Y0, 60.0, 1.0, POLLU_REF, list),
    "bruss2d": ("BRUSS2D", bruss_f, bruss_jac, None, BRUSS_T_END, 1e-2, None, list),
}


def scd(y, ref):
    worst = 0.0
    for a, b in zip(y, ref):
        e = abs((a - b) / b)
        worst = max(worst, math.inf if math.isnan(e) else e)
    return -math.log10(worst) if worst > 0 else 16.0


def check():
    """The reaction table against pollu.f's equations, and every analytic Jacobian against
    complex-step derivatives (exact to rounding: no cancellation), at random points."""
    rng = np.random.default_rng(1)
    y = rng.uniform(0.1, 1.0, 20)
    assert np.allclose(pollu_f(0, y), pollu_f_written_out(y), rtol=1e-13, atol=0)
    for key in PROBLEMS:
        _, f, jac, y0, *_ = PROBLEMS[key]
        y = bruss_init() if key == "bruss2d" else np.array(y0, dtype=float)
        y = y * rng.uniform(0.5, 1.5, y.size) + rng.uniform(0.01, 0.1, y.size)
        J = jac(0.0, y)
        J = J.toarray() if sparse.issparse(J) else np.asarray(J)
        for j in rng.choice(y.size, min(y.size, 40), replace=False):
            e = np.zeros(y.size, dtype=complex)
            e[j] = 1e-30j
            col = f(0.0, y + e).imag / 1e-30
            assert np.allclose(J[:, j], col, rtol=1e-12, atol=1e-14 * np.abs(col).max()), (key, j)
    print("check: POLLU's reaction table and every Jacobian agree")


def main():
    if sys.argv[1:2] == ["check"]:
        check()
        return
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    keys = sys.argv[2:] or ["rober", "hires", "vdpol", "pollu", "bruss2d"]
    for key in keys:
        name, f, jac, y0, t_end, factor, ref, full = PROBLEMS[key]
        if key == "bruss2d":
            y0, ref = bruss_init(), read_reference("bruss2d.csv")
        for method in ["Radau", "BDF"]:
            for rtol in [1e-4, 1e-6, 1e-8, 1e-10]:
                atol = rtol * factor
                if key == "bruss2d" and method == "Radau" and rtol not in BRUSS_RADAU_RTOLS:
                    print(f"{name}\tSciPy\t{method}\t{rtol:.0e}\t{atol:.0e}\t-\t-\t0\t"
                          "NOT RUN: SciPy's Radau takes minutes per run here", flush=True)
                    continue
                times = []
                sol = None
                for _ in range(1 if key == "bruss2d" else max(runs, 1)):
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
                shown = y if len(y) <= 20 else f"{y[:4]} ... ({len(y)} values)"
                print(f"{name} SciPy {method} {rtol:.0e}: y = {shown}", file=sys.stderr)
                print(f"{name}\tSciPy\t{method}\t{rtol:.0e}\t{atol:.0e}\t{scd(y, ref):.2f}\t"
                      f"{steps}\t{median:.3f}\tok", flush=True)


if __name__ == "__main__":
    main()
