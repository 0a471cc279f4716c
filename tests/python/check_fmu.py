"""Checks a unimo FMU with FMPy: `fmpy validate`, then a simulation compared with the
CSV of `unimo simulate` for the same model and output grid.

Usage: check_fmu.py FMU RESULT.csv VARS TOL [stop=T] [rtol=R] [parameter=value ...]

stop and rtol override the FMU's default experiment (rtol: the relative tolerance of
FMPy's CVode in Model Exchange, or of our solver in Co-Simulation).

VARS: comma-separated variables to compare. The comparison is on the output grid
points (rows whose time appears once in both results: event instants, where the left
and right limits are both written, are left out). Per variable the error is
max |fmpy - unimo| / max(1, max |unimo|); the script prints it and exits 1 when any
exceeds TOL. The FMU kind (ME or CS) is read from the FMU. Exit code 77 when FMPy is
not installed (the test suite skips).
"""

import csv
import sys

try:
    import numpy as np
    import fmpy
    from fmpy.validation import validate_fmu
except ImportError as e:
    print(f"skip: {e}")
    sys.exit(77)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    body = np.array([[float(x) for x in r] for r in rows[1:]])
    return {name: body[:, k] for k, name in enumerate(header)}


def single_times(t):
    """Indices of the rows whose time occurs once (not an event's two limits)."""
    keep = np.ones(len(t), dtype=bool)
    same = np.isclose(t[1:], t[:-1], rtol=0, atol=1e-12 * max(1.0, abs(t[-1])))
    keep[1:][same] = False
    keep[:-1][same] = False
    return np.nonzero(keep)[0]


def main():
    fmu, csv_path, names, tol = sys.argv[1], sys.argv[2], sys.argv[3].split(","), float(sys.argv[4])
    starts = dict(a.split("=", 1) for a in sys.argv[5:])
    starts = {k: float(v) for k, v in starts.items()}
    stop = starts.pop("stop", None)
    rtol = starts.pop("rtol", None)
    problems = validate_fmu(fmu)
    if problems:
        print("fmpy validate:", *problems, sep="\n  ")
        return 1
    md = fmpy.read_model_description(fmu)
    kind = "ModelExchange" if md.modelExchange is not None else "CoSimulation"
    reference = read_csv(csv_path)
    t_ref = reference["time"]
    ex = md.defaultExperiment
    # The reference's output grid (`unimo simulate --stop-time` changes it): its most
    # frequent step (rows at events split a grid interval in two).
    steps = np.diff(t_ref)
    steps = steps[steps > 1e-9 * max(1.0, abs(float(t_ref[-1])))]
    values, counts = np.unique(np.round(steps, 12), return_counts=True)
    interval = float(values[np.argmax(counts)])
    result = fmpy.simulate_fmu(
        fmu,
        fmi_type=kind,
        start_time=float(ex.startTime),
        stop_time=float(ex.stopTime) if stop is None else stop,
        relative_tolerance=float(ex.tolerance) if rtol is None else rtol,
        output_interval=interval,
        output=names,
        start_values=starts,
    )
    t = result["time"]
    ours, theirs = single_times(t_ref), single_times(t)
    # Grid points present in both.
    pairs = []
    for i in ours:
        j = np.searchsorted(t[theirs], t_ref[i] - 1e-9 * interval)
        if j < len(theirs) and abs(t[theirs[j]] - t_ref[i]) <= 1e-9 * interval:
            pairs.append((i, theirs[j]))
    if len(pairs) < 0.5 * len(ours):
        print(f"only {len(pairs)} of {len(ours)} grid points are in FMPy's result")
        return 1
    i_ref = np.array([p[0] for p in pairs])
    i_fmu = np.array([p[1] for p in pairs])
    worst = 0.0
    for name in names:
        a, b = reference[name][i_ref], result[name][i_fmu]
        scale = max(1.0, float(np.max(np.abs(reference[name]))))
        err = float(np.max(np.abs(a - b))) / scale
        print(f"{kind} {name}: max error {err:.3e} (scale {scale:.3g}) over {len(pairs)} points")
        worst = max(worst, err)
    print(f"worst {worst:.3e} tolerance {tol:.1e}")
    return 0 if worst <= tol else 1


if __name__ == "__main__":
    sys.exit(main())
