#!/usr/bin/env bash
# Billiards scaling: cost per simulated second against the number of balls, sweep and
# prune against all pairs, in one run. Usage: bash bench/paper-b/scaling.sh [N...]
# Needs target/release/unimo. Prints a markdown table (medians of 3 runs).
set -euo pipefail
cd "$(dirname "$0")/../.."
BIN=${UNIMO:-target/release/unimo}
TMP=${TMPDIR:-/tmp}/unimo-scaling
mkdir -p "$TMP"
NS=${*:-10 100 1000}
LAW=${LAW:---impulses}
echo "| N balls | broadphase | steps | events | world evaluations | simulate ms (median of 3) | ms per simulated s | real-time factor | us per world evaluation | box tests per evaluation | narrowphase pairs per evaluation |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for n in $NS; do
  for bp in sap all-pairs; do
    flag=""; [ "$bp" = all-pairs ] && flag=--all-pairs
    python3 bench/paper-b/billiards.py "$n" $LAW $flag --name B > "$TMP/B$n$bp.mo"
    runs=()
    for k in 1 2 3; do
      "$BIN" simulate "$TMP/B$n$bp.mo" --method dopri5 --vars Px --stats -o "$TMP/out.csv" 2> "$TMP/stats$k.json"
      runs+=("$(tail -1 "$TMP/stats$k.json")")
    done
    python3 - "$n" "$bp" "${runs[@]}" <<'PY'
import json, sys, statistics
n, bp = sys.argv[1], sys.argv[2]
runs = [json.loads(r) for r in sys.argv[3:]]
ms = statistics.median(r["simulate_ms"] for r in runs)
r = runs[0]; c = r["collision"]; T = 1.0
print("| %s | %s | %d | %d | %d | %.1f | %.1f | %.2f | %.1f | %.0f | %.1f |" % (n, bp, r["steps"], r["events"], c["evaluations"], ms, ms / T,
      1000 * T / ms, 1000 * ms / c["evaluations"], c["broadphase_tests"] / c["evaluations"], c["narrowphase_pairs"] / c["evaluations"]))
PY
  done
done
