#!/usr/bin/env python3
"""The table of bench/paper-a/sweep.sh from its output folder: python3 sweep_table.py OUTDIR MODELNAME."""
import csv, json, math, re, sys
out, name = sys.argv[1], sys.argv[2]
def last(path):
    r = list(csv.reader(open(path)))
    return dict(zip(r[0], map(float, r[-1])))
def stats(path):
    text = open(path).read()
    m = re.search(r"\{.*\}", text)
    err = re.search(r"error\[(E\d+)\]", text)
    return (json.loads(m.group(0)) if m else {}), (err.group(1) if err else None)
ref = last(f"{out}/{name}-ref.csv")
rs, _ = stats(f"{out}/{name}-ref.stats")
keys = [k for k in ref if k not in ("time",)]
print(f"reference: radau5 rtol 1e-11, {rs.get('simulate_ms', float('nan')):.0f} ms, " +
      ", ".join(f"{k} = {ref[k]:.12g}" for k in keys))
print("| method | rtol | simulate ms | steps | events | " + " | ".join(f"rel. error {k}" for k in keys) + " |")
print("|---|---|---|---|---|" + "---|" * len(keys))
for m in ("bdf", "radau5"):
    for tol in ("1e-4", "1e-6", "1e-8", "1e-10"):
        s, err = stats(f"{out}/{name}-{m}-{tol}.stats")
        if err:
            print(f"| {m} | {tol} | failed {err} | | | " + " | ".join("" for _ in keys) + " |")
            continue
        v = last(f"{out}/{name}-{m}-{tol}.csv")
        errs = []
        for k in keys:
            d = abs(v[k] - ref[k]) / abs(ref[k]) if ref[k] != 0 else abs(v[k])
            errs.append(f"{d:.1e}")
        print(f"| {m} | {tol} | {s['simulate_ms']:.0f} | {s['steps']} | {s['events']} | " + " | ".join(errs) + " |")
