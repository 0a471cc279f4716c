#!/usr/bin/env python3
"""Every MSL example of tests/msl.rs's quick set exported as an FMU and checked with FMPy
against `unimo simulate` (tests/python/check_fmu.py), on the example's comparison
signals: Model Exchange (FMI 2, FMPy's CVode at rtol 1e-9 against `unimo simulate
--tolerance 1e-10`) and Co-Simulation (FMI 3, both at the model's tolerance).

Usage: bench/fmi/quick_set.py --bin target/release/unimo [--msl ../shared/msl]
       [--refs ../shared/msl-reference] [--filter REGEX] [--kinds me,cs]

The FMU library libunimo_fmi.so must be next to the binary. Prints one line per example
and kind (the worst relative error or the failure) and a summary; exit 1 when any fails.
Not a CI test: about ten minutes for the set.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def examples():
    text = open(os.path.join(ROOT, "tests", "msl.rs")).read()
    block = text[text.index("const EXAMPLES"):]
    block = block[: block.index("];")]
    return re.findall(r'"(Modelica\.[A-Za-z0-9_.]+)"', block)


def signals(refs, name):
    path = os.path.join(refs, *name.split("."), "comparisonSignals.txt")
    with open(path) as f:
        rows = [r.strip() for r in f.read().splitlines()[1:] if r.strip()]
    return ",".join(rows)


def run(cmd, timeout):
    try:
        o = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        return o.returncode, o.stdout + o.stderr
    except subprocess.TimeoutExpired:
        return -1, f"timeout after {timeout} s"


def check(args, name, kind, tmp):
    vars_ = signals(args.refs, name)
    stem = name.split(".")[-1]
    fmi = "2" if kind == "me" else "3"
    fmu = os.path.join(tmp, f"{stem}-{kind}.fmu")
    csv = os.path.join(tmp, f"{stem}-{kind}.csv")
    src = ["--lib", args.msl, "--model", name]
    code, out = run([args.bin, "fmu", *src, "--fmi", fmi, "--kind", kind, "-o", fmu], 300)
    if code != 0:
        return f"export failed: {out.strip().splitlines()[-1] if out.strip() else code}"
    sim = [args.bin, "simulate", *src, "--vars", vars_, "--output", csv, "--output-tolerance", "0"]
    extra = []
    if kind == "me":
        sim += ["--tolerance", "1e-10"]
        extra = ["rtol=1e-9"]
    code, out = run(sim, 300)
    if code != 0:
        return f"simulate failed: {out.strip().splitlines()[-1]}"
    script = os.path.join(ROOT, "tests", "python", "check_fmu.py")
    code, out = run([sys.executable, script, fmu, csv, vars_, "1e300", *extra], 600)
    for f in (fmu, csv):
        if os.path.exists(f):
            os.remove(f)
    worst = [l for l in out.splitlines() if l.startswith("worst")]
    if code != 0 or not worst:
        lines = [l for l in out.strip().splitlines() if l.strip()]
        return "FMPy failed: " + (lines[-1] if lines else str(code))
    return float(worst[0].split()[1])


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--bin", required=True)
    p.add_argument("--msl", default=os.path.join(ROOT, "..", "shared", "msl"))
    p.add_argument("--refs", default=os.path.join(ROOT, "..", "shared", "msl-reference"))
    p.add_argument("--filter", default="")
    p.add_argument("--kinds", default="me,cs")
    args = p.parse_args()
    args.bin = os.path.abspath(args.bin)
    failed = 0
    results = []
    with tempfile.TemporaryDirectory(prefix="unimo-fmi-quick-") as tmp:
        for name in examples():
            if not re.search(args.filter, name):
                continue
            for kind in args.kinds.split(","):
                r = check(args, name, kind, tmp)
                results.append((name, kind, r))
                text = f"{r:.2e}" if isinstance(r, float) else r
                print(f"{name} {kind}: {text}", flush=True)
                failed += not isinstance(r, float)
    for kind in args.kinds.split(","):
        errs = sorted(r for _, k, r in results if k == kind and isinstance(r, float))
        n = sum(1 for _, k, _ in results if k == kind)
        if errs:
            print(f"{kind}: {len(errs)} of {n} ran; errors median {errs[len(errs) // 2]:.1e}, "
                  f"worst {errs[-1]:.1e}; above 1e-4: "
                  + ", ".join(f"{nm.split('.')[-1]} {r:.1e}" for nm, k, r in results
                              if k == kind and isinstance(r, float) and r > 1e-4))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
