#!/usr/bin/env python3
"""Parameter folding, scene by scene: plan operations, zero crossings, states, events and
run time with every parameter folded (the default) and with every parameter kept
tunable (--tunable-all), and the largest difference between the two results.

  python3 bench/fold/report.py [--unimo target/release/unimo] [--runs 3]

Prints a Markdown table (docs/results/folding.md). Run time: the median of --runs runs
of `simulate_ms` from --stats. The difference: over the output times both results
have (an event adds rows at its instant; the last row of a time is used), for every
column both have, relative to the column's largest magnitude (at least 1).
"""
import argparse, csv, json, os, statistics, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXT = "tests/paper_a/Extremes.mo"
BALLS = ["tests/fold/ThreeBalls.mo", "models/ThreeBallsOnTable.mo"]
SCENES = [
    # (label, files, model, extra args)
    ("ellipsoid, f = 0.08 (Extremes.Base)", [EXT], "Extremes.Base", ["--stop-time", "3"]),
    ("ellipsoid, f = 0 (Extremes.Frictionless)", [EXT], "Extremes.Frictionless", ["--stop-time", "3"]),
    ("ellipsoid, k = 0 (Extremes.PlasticImpacts)", [EXT], "Extremes.PlasticImpacts", ["--stop-time", "3"]),
    ("three balls, table friction 0.1", BALLS, "ThreeBalls.WithFriction", ["--stop-time", "0.26"]),
    ("three balls, no friction", BALLS, "ThreeBalls.Frictionless", ["--stop-time", "0.26"]),
    ("bouncing ball (models/BouncingBall.mo)", ["models/BouncingBall.mo"], None, []),
    ("four-bar linkage (models/FourBar.mo)", ["models/FourBar.mo"], None, []),
    ("billiards (models/Billiards.mo)", ["models/Billiards.mo"], None, []),
]


def run(unimo, files, model, extra, tunable_all, out):
    cmd = [unimo, "simulate", *files, "--stats", "-o", out, *extra]
    if model:
        cmd += ["--model", model]
    if tunable_all:
        cmd.append("--tunable-all")
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)}\n{p.stderr}")
    return json.loads(next(l for l in p.stderr.splitlines() if l.startswith("{")))


def read(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    head = rows[0]
    data = {}
    for r in rows[1:]:
        data[float(r[0])] = [float(x) for x in r]
    return head, data


def difference(a, b, states_only=False):
    (ha, da), (hb, db) = read(a), read(b)
    times = [t for t in da if t in db]
    worst = (0.0, "")
    for j, name in enumerate(ha[1:], 1):
        if name not in hb or (states_only and f"der({name})" not in ha):
            continue
        k = hb.index(name)
        scale = max([1.0] + [abs(db[t][k]) for t in times])
        d = max(abs(da[t][j] - db[t][k]) for t in times) / scale
        if d > worst[0]:
            worst = (d, name)
    return worst


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--unimo", default=os.path.join(ROOT, "target/release/unimo"))
    ap.add_argument("--runs", type=int, default=3)
    a = ap.parse_args()
    tmp = tempfile.mkdtemp()
    print("| scene | folded parameters | plan ops (tunable → folded) | zero crossings | states | events | simulate ms, median of %d (tunable → folded) | largest difference, states | largest difference, all columns |" % a.runs)
    print("|---|---|---|---|---|---|---|---|---|")
    for label, files, model, extra in SCENES:
        stats = {}
        for mode in (True, False):
            out = os.path.join(tmp, f"{mode}.csv")
            runs = [run(a.unimo, files, model, extra, mode, out) for _ in range(a.runs)]
            s = runs[0]
            s["ms"] = statistics.median(r["simulate_ms"] for r in runs)
            stats[mode] = s
        files = (os.path.join(tmp, "False.csv"), os.path.join(tmp, "True.csv"))
        ds, cs = difference(*files, states_only=True)
        d, col = difference(*files)
        t, f = stats[True], stats[False]
        print(f"| {label} | {f['parameters_folded']} | {t['plan_ops']} → {f['plan_ops']} "
              f"| {t['zero_crossings']} → {f['zero_crossings']} | {t['states']} → {f['states']} "
              f"| {t['events']} → {f['events']} | {t['ms']:.1f} → {f['ms']:.1f} "
              f"| {ds:.1e} | {d:.1e}{f' (`{col}`)' if col else ''} |")


if __name__ == "__main__":
    main()
