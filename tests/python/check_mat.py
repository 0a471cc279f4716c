"""Reads a unimo MAT v4 result with scipy.io.loadmat and DyMat and compares every
variable with the CSV of the same run. Usage: check_mat.py RESULT.mat RESULT.csv [TOL]

Prints the largest absolute difference and exits 1 when it exceeds TOL (1e-12) or a
CSV column is missing; exit code 77 when scipy or DyMat is not installed (skip)."""

import csv
import sys

try:
    import numpy as np
    import scipy.io
    import DyMat
except ImportError as e:  # the test suite skips on this code
    print(f"skip: {e}")
    sys.exit(77)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
    return {name: body[:, k] for k, name in enumerate(header)}


def scipy_trajectories(path):
    """Resolves dataInfo by hand from the raw matrices scipy reads."""
    m = scipy.io.loadmat(path, chars_as_strings=False)
    aclass = ["".join(row).rstrip("\0 ") for row in m["Aclass"]]
    assert aclass[0] == "Atrajectory" and aclass[3] == "binTrans", aclass
    names = ["".join(col).rstrip("\0 ") for col in m["name"].T]
    info, d1, d2 = m["dataInfo"], m["data_1"], m["data_2"]
    out = {}
    for k, name in enumerate(names):
        matrix, row = int(info[0, k]), int(info[1, k])
        sign, r = (-1.0 if row < 0 else 1.0), abs(row) - 1
        if matrix == 1:
            out[name] = np.full(d2.shape[1], sign * d1[r, 0])
        else:
            out[name] = sign * d2[r, :]
    return out


def main():
    mat_path, csv_path = sys.argv[1], sys.argv[2]
    tol = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-12
    reference = read_csv(csv_path)
    by_scipy = scipy_trajectories(mat_path)
    dymat = DyMat.DyMatFile(mat_path)
    worst = 0.0
    for name, values in reference.items():
        if name not in by_scipy:
            print(f"missing in the MAT file (scipy): {name}")
            return 1
        worst = max(worst, float(np.max(np.abs(by_scipy[name] - values))))
        if name != "time":
            from_dymat = np.asarray(dymat.data(name))
            if dymat.block(name) == 1:
                # Time-invariant (data_1): its values at the start and stop time.
                for v in from_dymat:
                    worst = max(worst, float(np.max(np.abs(values - v))))
                continue
            worst = max(worst, float(np.max(np.abs(from_dymat - values))))
            abscissa = np.asarray(dymat.abscissa(name, valuesOnly=True))
            worst = max(worst, float(np.max(np.abs(abscissa - reference["time"]))))
    print(f"{len(reference)} columns, {len(reference['time'])} rows, "
          f"{len(by_scipy)} variables in the MAT file; max |MAT - CSV| = {worst:.3e}")
    return 0 if worst <= tol else 1


if __name__ == "__main__":
    sys.exit(main())
