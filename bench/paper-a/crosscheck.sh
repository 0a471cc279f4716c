#!/usr/bin/env bash
# Paper A's example 1 against the event-driven reference (issue #21, points 3 and 4):
# the reference at rtol 1e-9 and 1e-12, the acausal model with BDF and Radau5 at rtol
# 1e-8 and 1e-10, Radau5 at 1e-11 and Dopri5 at 1e-12 (one run at a time), and per run
# the comparison of bench/paper-a/crosscheck.py. Release builds; about a minute on a quiet machine.
# usage: bash bench/paper-a/crosscheck.sh [OUTDIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-target/paper-a-crosscheck}
mkdir -p "$out"
cargo build --release -q --bin unimo -p unimo -p unimo-reference
bin=${CARGO_TARGET_DIR:-target}/release
for rtol in 1e-9 1e-12; do
  "$bin/ellipsoid-reference" --rtol "$rtol" --events "$out/reference-$rtol.csv" > "$out/reference-$rtol.txt"
done
energy=$(awk '/^energy:/ {print $2}' "$out/reference-1e-12.txt")
cat "$out/reference-1e-12.txt"
vars=t,ConstraintSurfaces.State,Impacts,Energy,ConstraintSurfaces.Gap,CentreHeight,tFirstRolling
for run in bdf:1e-8 bdf:1e-10 radau5:1e-8 radau5:1e-10 radau5:1e-11 dopri5:1e-12; do
  method=${run%%:*}
  rtol=${run##*:}
  {
    echo "== $method rtol $rtol"
    start=$(date +%s.%N)
    "$bin/unimo" simulate models/FlySlideRoll.mo --method "$method" --tolerance "$rtol" \
      --vars "$vars" --stats -o "$out/model-$method-$rtol.csv" 2>&1 | grep -v '^note' || true
    echo "wall $(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.2f", b - a}') s"
    python3 bench/paper-a/crosscheck.py "$out/model-$method-$rtol.csv" "$out/reference-1e-12.csv" "$energy"
  }
done
echo "== divergence of two reference runs 1e-12 apart (height, then omega_y)"
"$bin/ellipsoid-reference" --rtol 1e-12 --perturb 1:1e-12 | sed -n '/perturbed/,$p'
"$bin/ellipsoid-reference" --rtol 1e-12 --perturb 11:1e-12 | sed -n '/perturbed/,$p'
