#!/usr/bin/env bash
# Runs every MSL example that has reference results through `unimo simulate` (with
# ../shared/tools/msl-check, the criterion in its header) and rewrites
# docs/results/msl.md. Needs ../shared/msl and ../shared/msl-reference beside the
# project (test data, not part of it). Usage: bash bench/msl/run.sh [--filter REGEX]
set -euo pipefail
cd "$(dirname "$0")/../.."
shared="$(cd .. && pwd)/shared"
for d in "$shared/msl" "$shared/msl-reference" "$shared/tools/msl-check"; do
  [ -e "$d" ] || { echo "missing $d: the MSL test data must be beside the project" >&2; exit 2; }
done
cargo build --release --quiet
results="$(mktemp -d)/results.csv"
# msl-check's default command (the output grid, events, rows between where needed).
python3 "$shared/tools/msl-check" --unimo "${CARGO_TARGET_DIR:-target}/release/unimo" --msl "$shared/msl" \
  --ref "$shared/msl-reference" --results "$results" "$@" | tee "${results%.csv}.txt"
# The same with a row after every solver step (for comparison).
every='{unimo} simulate {msl}/Modelica/package.mo --model {model} --lib {msl} --vars {vars} --every-step --output {csv}'
python3 "$shared/tools/msl-check" --unimo "${CARGO_TARGET_DIR:-target}/release/unimo" --msl "$shared/msl" \
  --ref "$shared/msl-reference" --results "${results%.csv}.every.csv" --cmd "$every" "$@" > /dev/null
# References whose time column is named `Time` (msl-check reads `time`): a copy with
# the header renamed, compared the same way.
timefix="$(dirname "$results")/timefix"
python3 - "$shared/msl-reference" "$timefix" <<'PY'
import os, shutil, sys
ref, out = sys.argv[1], sys.argv[2]
for root, _, files in os.walk(ref):
    for f in files:
        if not f.endswith(".csv"):
            continue
        with open(os.path.join(root, f)) as fh:
            head = fh.readline()
        if head.split(",")[0].strip().strip('"') != "Time":
            continue
        dest = os.path.join(out, os.path.relpath(root, ref))
        os.makedirs(dest, exist_ok=True)
        shutil.copy(os.path.join(root, "comparisonSignals.txt"), dest)
        with open(os.path.join(root, f)) as src, open(os.path.join(dest, f), "w") as dst:
            src.readline()  # the header, written renamed
            dst.write(head.replace("Time", "time", 1))
            shutil.copyfileobj(src, dst)
PY
python3 "$shared/tools/msl-check" --unimo "${CARGO_TARGET_DIR:-target}/release/unimo" --msl "$shared/msl" \
  --ref "$timefix" --results "${results%.csv}.timefix.csv" > /dev/null
python3 bench/msl/report.py "$results" "$shared/msl-reference" "${results%.csv}.every.csv" \
  "${results%.csv}.timefix.csv" > docs/results/msl.md
echo "wrote docs/results/msl.md"
# Names: every file of the MSL through the name check (syntax errors must be 0).
"${CARGO_TARGET_DIR:-target}/release/unimo" check --no-balance --lib "$shared/msl" "$shared/msl" > "${results%.csv}.check" 2>&1 || true
python3 bench/msl/names.py "${results%.csv}.check" >> docs/results/msl.md
