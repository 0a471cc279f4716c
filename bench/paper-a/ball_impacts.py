#!/usr/bin/env python3
"""Impact times of models/LibraryBouncingBall.mo against the closed form
t_n = sqrt(2 h/g) (1 + 2 k (1 - k^(n-1)) / (1 - k)), from a CSV with columns t and
impacts (unimo simulate ... --vars t,impacts,Contact.State,Contact.Gap)."""
import csv
import math
import sys

h, g, k = 1.0, 9.81, 0.8
rows = list(csv.reader(open(sys.argv[1])))
c = {n: i for i, n in enumerate(rows[0])}
data = [[float(x) for x in r] for r in rows[1:]]
times = []
for a, b in zip(data, data[1:]):
    if b[c["impacts"]] > a[c["impacts"]]:
        times.append(b[c["t"]])
n_check = int(sys.argv[2]) if len(sys.argv) > 2 else 20
worst = 0.0
for n, t in enumerate(times[:n_check], start=1):
    exact = math.sqrt(2 * h / g) * (1 + 2 * k * (1 - k ** (n - 1)) / (1 - k))
    worst = max(worst, abs(t - exact) / exact)
zeno = math.sqrt(2 * h / g) * (1 + k) / (1 - k)
last = data[-1]
print(f"impacts: {len(times)}; worst relative error of impacts 1..{min(n_check, len(times))}: {worst:.1e}")
print(f"last impact at t = {times[-1]:.10f}; Zeno time {zeno:.10f}")
if "Contact.State" in c:
    print(f"final state {int(last[c['Contact.State']])} at t = {last[c['t']]:.6g}")
if "Contact.Gap" in c:
    print(f"final gap {last[c['Contact.Gap']]:.2e}")
