#!/usr/bin/env python3
"""Compares the event sequence of an acausal run of paper A's example 1 (a CSV of
`unimo simulate models/FlySlideRoll.mo --vars t,ConstraintSurfaces.State,Impacts,Energy,
ConstraintSurfaces.Gap,...`) with the event-driven reference (`ellipsoid-reference
--events ref.csv`): counts per kind, first rolling time, the event where the two
sequences part (first different kind, or a time off by more than 1e-3 relative), the
largest relative time difference before it and over the first 100 events, the energy
at t = 150 and the largest |gap| in contact. The reference may also be another run's CSV
(the causal model's, for instance), whose events are read in the same way.

usage: crosscheck.py MODEL.csv REFERENCE_EVENTS.csv [REFERENCE_ENERGY]"""
import csv
import sys

KINDS = ("impact", "landing-sliding", "landing-rolling", "lift-off", "slide-roll", "roll-slide")
SWITCH = {(0, 1): "landing-sliding", (0, 2): "landing-rolling", (1, 0): "lift-off",
          (2, 0): "lift-off", (1, 2): "slide-roll", (2, 1): "roll-slide"}


def load(path):
    rows = list(csv.reader(open(path)))
    names = rows[0]
    return {n: k for k, n in enumerate(names)}, [[float(x) for x in r] for r in rows[1:]]


def model_events(c, data):
    s, i, t = c["ConstraintSurfaces.State"], c["Impacts"], c["t"]
    events = []
    for a, b in zip(data, data[1:]):
        if b[i] > a[i]:
            events.append((b[t], "impact"))
        if b[s] != a[s]:
            events.append((b[t], SWITCH[(int(a[s]), int(b[s]))]))
    return events


def at_time(c, data, name, when):
    t, k = c["t"], c[name]
    for a, b in zip(data, data[1:]):
        if a[t] <= when <= b[t] and b[t] > a[t]:
            return a[k] + (b[k] - a[k]) * (when - a[t]) / (b[t] - a[t])
    # the run ends where `t >= tStop` was located, which may be a rounding short of it
    if abs(data[-1][t] - when) < 1e-9 * max(1.0, abs(when)):
        return data[-1][k]
    return float("nan")


def reference_events(path):
    """The reference's events: an event list (`t,kind`) or another run's CSV (for
    example the causal model's), whose events are read as the model's are."""
    header = next(csv.reader(open(path)))
    if "kind" in header:
        return [(float(r["t"]), r["kind"]) for r in csv.DictReader(open(path))]
    return model_events(*load(path))


def main(model_csv, reference_csv, reference_energy=None):
    c, data = load(model_csv)
    model = model_events(c, data)
    reference = reference_events(reference_csv)
    n = min(len(model), len(reference))
    part = next((k for k in range(n) if model[k][1] != reference[k][1]
                 or abs(model[k][0] - reference[k][0]) > 1e-3 * reference[k][0]), None)
    agree = n if part is None else part
    diffs = [abs(model[k][0] - reference[k][0]) / reference[k][0] for k in range(agree)]
    print("| | model | reference |")
    print("|---|---|---|")
    print("| events | %d | %d |" % (len(model), len(reference)))
    for kind in KINDS:
        print("| %s | %d | %d |" % (kind, sum(e[1] == kind for e in model),
                                    sum(e[1] == kind for e in reference)))
    first = lambda ev: next((e[0] for e in ev if e[1] in ("slide-roll", "landing-rolling")), None)
    print("| first rolling | %s | %s |" % (first(model), first(reference)))
    print("events agreeing in kind (times within 1e-3): %d" % agree)
    if diffs:
        print("largest relative time difference: first 100 events %.2e, all agreeing %.2e"
              % (max(diffs[:100]), max(diffs)))
    if part is not None:
        print("the sequences part at event %d:" % part)
        for k in range(max(0, part - 3), min(n, part + 3)):
            print("  %d model %.9f %s | reference %.9f %s" % (k, model[k][0], model[k][1],
                                                             reference[k][0], reference[k][1]))
    if "Energy" in c:
        e150 = at_time(c, data, "Energy", 150.0)
        line = "energy at t = 150: %.12g" % e150
        if reference_energy is not None:
            line += " (reference %.12g, rel. diff %.1e)" % (
                reference_energy, abs(e150 - reference_energy) / reference_energy)
        print(line)
    if "ConstraintSurfaces.Gap" in c:
        s, g = c["ConstraintSurfaces.State"], c["ConstraintSurfaces.Gap"]
        gaps = [abs(r[g]) for r in data if r[s] > 0]
        if gaps:
            print("largest |gap| in contact (output rows): %.2e" % max(gaps))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]) if len(sys.argv) > 3 else None)
