#!/usr/bin/env python3
"""Writes the scaling chain model (issue #23 point 5): N coupled states, ~2.2N equations.

    gen_chain.py N [explicit|newton] > chain.mo

explicit: every algebraic variable is an explicit assignment (symbolic Jacobian).
newton:   y[i] + 0.1*sin(y[i]) = x[i] is a scalar nonlinear block per i (Newton blocks).
"""
import sys


def chain(n: int, kind: str) -> str:
    m = max(n // 5, 1)
    if kind == "explicit":
        y_eq = "    y[i] = 0.5*sin(x[i]) + 0.1*x[i];"
    elif kind == "newton":
        y_eq = "    y[i] + 0.1*sin(y[i]) = x[i];"
    else:
        raise SystemExit(f"unknown kind {kind!r}: explicit or newton")
    return f"""model Chain
  parameter Integer n = {n};
  parameter Integer m = {m};
  Real x[n](each start = 1, each fixed = true);
  Real y[n];
  Real w[m];
equation
  der(x[1]) = -x[1];
  for i in 1:n loop
{y_eq}
  end for;
  for i in 2:n loop
    der(x[i]) = y[i-1] - 2*x[i] + 0.5*y[i];
  end for;
  for k in 1:m loop
    w[k] = x[5*k - 4] + y[5*k - 4];
  end for;
  annotation(experiment(StartTime = 0, StopTime = 1, Interval = 0.01));
end Chain;
"""


if __name__ == "__main__":
    n = int(sys.argv[1])
    kind = sys.argv[2] if len(sys.argv) > 2 else "explicit"
    sys.stdout.write(chain(n, kind))
