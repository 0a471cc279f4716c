#!/usr/bin/env python3
"""Figures of docs/results/paper-a.md from a result CSV of one of paper A's scenes
(unimo simulate ... --vars t,ConstraintSurfaces.State,Energy,...): impacts, switches,
first contact and first rolling times, time in each constraint state, energy behaviour
per state, and the drift of the integrated closest points and of the contact gap."""
import csv
import sys


def load(path):
    rows = list(csv.reader(open(path)))
    names = rows[0]
    data = [[float(x) for x in r] for r in rows[1:]]
    return names, data


def main(path):
    names, data = load(path)
    c = {n: k for k, n in enumerate(names)}
    t = [r[c["t"]] for r in data]
    st = [r[c["ConstraintSurfaces.State"]] for r in data]
    out = {}
    last = data[-1]
    for n in ("Impacts", "Switches", "tFirstContact", "tFirstRolling"):
        if n in c:
            out[n] = last[c[n]]
    out["physical time"] = t[-1]
    out["final state"] = int(st[-1])
    # time per state (between consecutive rows, in physical time)
    per = {0: 0.0, 1: 0.0, 2: 0.0}
    for a, b in zip(data, data[1:]):
        per[int(a[c["ConstraintSurfaces.State"]])] += b[c["t"]] - a[c["t"]]
    out["time in Flight/Sliding/Rolling"] = "%.4g / %.4g / %.4g" % (per[0], per[1], per[2])
    if "Energy" in c:
        e = [r[c["Energy"]] for r in data]
        low, rise = e[0], 0.0
        for x in e:
            rise = max(rise, x - low)
            low = min(low, x)
        out["energy start/end"] = "%.10g / %.10g" % (e[0], e[-1])
        out["largest energy rise above its running minimum (relative)"] = "%.2e" % (rise / abs(e[0]))
        # intervals of one state: energy change per interval
        worst = {0: 0.0, 1: 0.0, 2: 0.0}
        longest_roll = (0.0, 0.0)
        k = 0
        while k < len(data) - 1:
            s = st[k]
            j = k
            while j + 1 < len(data) and st[j + 1] == s:
                j += 1
            if j > k:
                d = (e[j] - e[k]) / abs(e[0])
                if int(s) == 2 and t[j] - t[k] > longest_roll[0]:
                    longest_roll = (t[j] - t[k], d)
                if int(s) != 2:
                    worst[int(s)] = max(worst[int(s)], d)
            k = j + 1
        out["largest energy gain within one Flight interval (relative)"] = "%.2e" % worst[0]
        out["largest energy gain within one Sliding interval (relative)"] = "%.2e" % worst[1]
        out["longest Rolling interval: length, relative energy change"] = "%.4g s, %.2e" % longest_roll
    if "ConstraintSurfaces.rPBDrift" in c:
        out["max drift ‖rPB − closed form‖"] = "%.2e" % max(r[c["ConstraintSurfaces.rPBDrift"]] for r in data)
    if "ConstraintSurfaces.Gap" in c:
        g = [abs(r[c["ConstraintSurfaces.Gap"]]) for r, s in zip(data, st) if s > 0]
        if g:
            out["max abs(gap) in contact"] = "%.2e" % max(g)
            out["abs(gap) at the end"] = "%.2e" % abs(last[c["ConstraintSurfaces.Gap"]])
    for k, v in out.items():
        print("| %s | %s |" % (k, v))


if __name__ == "__main__":
    main(sys.argv[1])
