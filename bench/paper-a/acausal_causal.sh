#!/usr/bin/env bash
# The acausal constraint object against the causal hybrid automaton of the paper
# (docs/results/paper-a.md, "Acausal against causal"): FlySlideRoll and SlideRollSwitch,
# both formulations with BDF and Radau5 at rtol 1e-8 and 1e-10, each acausal run compared
# with the causal run of the same settings by bench/paper-a/crosscheck.py (event kinds
# and times, first rolling time). FlySlideRoll's runs are also compared with the
# event-driven reference when OUTDIR/reference-1e-12.csv exists (bench/paper-a/crosscheck.sh).
# usage: bash bench/paper-a/acausal_causal.sh [OUTDIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-target/paper-a-causal}
mkdir -p "$out"
bin=${UNIMO:-${CARGO_TARGET_DIR:-target}/release/unimo}
vars=t,ConstraintSurfaces.State,Impacts,Energy,tFirstRolling
for scene in FlySlideRoll SlideRollSwitch; do
  for run in bdf:1e-8 bdf:1e-10 radau5:1e-8 radau5:1e-10; do
    method=${run%%:*}
    rtol=${run##*:}
    for form in "" Causal; do
      "$bin" simulate "models/$scene$form.mo" --method "$method" --tolerance "$rtol" \
        --vars "$vars" -o "$out/$scene$form-$method-$rtol.csv" 2>/dev/null
    done
    echo "== $scene $method rtol $rtol: acausal (model) against causal (reference)"
    python3 bench/paper-a/crosscheck.py "$out/$scene-$method-$rtol.csv" \
      "$out/${scene}Causal-$method-$rtol.csv"
  done
done
