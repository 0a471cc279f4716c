#!/usr/bin/env bash
# Error against run time for paper A's scenes, per quantity (docs/results/paper-a.md).
# Usage: bash bench/paper-a/sweep.sh MODEL "VAR1,VAR2,..." OUTDIR
# Runs the reference (radau5, rtol 1e-11) and bdf/radau5 at rtol 1e-4 ... 1e-10, then
# prints per quantity the relative error at the end against the reference, with the
# simulate time from --stats.
set -euo pipefail
model=$1; vars=$2; out=$3
bin=${UNIMO:-target/release/unimo}
mkdir -p "$out"
name=$(basename "$model" .mo)
"$bin" simulate "$model" --method radau5 --tolerance 1e-11 --vars "$vars" \
  --output "$out/$name-ref.csv" --stats 2> "$out/$name-ref.stats" || true
for m in bdf radau5; do
  for tol in 1e-4 1e-6 1e-8 1e-10; do
    "$bin" simulate "$model" --method $m --tolerance $tol --vars "$vars" \
      --output "$out/$name-$m-$tol.csv" --stats 2> "$out/$name-$m-$tol.stats" || true
  done
done
python3 "$(dirname "$0")/sweep_table.py" "$out" "$name"
