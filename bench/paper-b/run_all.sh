#!/usr/bin/env bash
# Every number of docs/results/paper-b.md: tunnelling table, billiards momentum and
# energy, cylinder at rest, spring, scaling, and the work-precision benches.
# Usage: bash bench/paper-b/run_all.sh   (needs target/release/unimo; writes to $OUT)
set -euo pipefail
cd "$(dirname "$0")/../.."
BIN=${UNIMO:-target/release/unimo}
OUT=${OUT:-${TMPDIR:-/tmp}/unimo-paper-b}
mkdir -p "$OUT" docs/results/paper-b

echo "## tunnelling: 5 cm ball, 100 m/s, 1 cm plate"
echo "| method | rtol | steps | events | lowest centre z (plate top 0.005) | final v |"
echo "|---|---|---|---|---|---|"
for m in dopri5 radau5 bdf; do
  for t in 1e-3 1e-4 1e-5 1e-6 1e-7 1e-8 1e-9; do
    "$BIN" simulate tests/collision/Tunnel.mo --method $m --tolerance $t --every-step \
      --vars ball.r[3],ball.v[3] -o "$OUT/tunnel.csv" --stats 2> "$OUT/s.json"
    python3 - "$m" "$t" "$OUT" <<'PY'
import csv, json, sys
m, t, out = sys.argv[1:4]
s = json.loads(open(out + "/s.json").read().strip().splitlines()[-1])
rows = list(csv.reader(open(out + "/tunnel.csv"))); h = rows[0]; d = [[float(x) for x in r] for r in rows[1:]]
z, v = h.index("ball.r[3]"), h.index("ball.v[3]")
print("| %s | %s | %d | %d | %.5f | %.3f |" % (m, t, s["steps"], s["events"], min(r[z] for r in d), d[-1][v]))
PY
  done
done
"$BIN" simulate tests/collision/TunnelNoSweep.mo --method dopri5 --tolerance 1e-3 --vars ball.r[3] -o "$OUT/ghost.csv"
echo "without the sweep (dopri5, 1e-3): final z = $(tail -1 "$OUT/ghost.csv" | cut -d, -f2)"

echo; echo "## billiards: momentum and energy (dopri5, rtol 1e-6)"
for f in BilliardsBreakImpulses BilliardsBreakPenalty Billiards; do
  "$BIN" simulate models/$f.mo --method dopri5 --tolerance 1e-6 --every-step --vars Px,Py,E,world.gaps[2],world.contactChanges -o "$OUT/$f.csv" --stats 2> "$OUT/$f.json"
  python3 - "$f" "$OUT" <<'PY'
import csv, json, sys, math
f, out = sys.argv[1:3]
s = json.loads(open(out + "/" + f + ".json").read().strip().splitlines()[-1])
rows = list(csv.reader(open(out + "/" + f + ".csv"))); h = rows[0]; d = [[float(x) for x in r] for r in rows[1:]]
px, py, e, c = h.index("Px"), h.index("Py"), h.index("E"), h.index("world.contactChanges")
p0 = math.hypot(d[0][px], d[0][py])
dp = max(math.hypot(r[px] - d[0][px], r[py] - d[0][py]) for r in d) / p0
print("%s: steps %d, events %d, contact changes %d, max |P - P0|/|P0| = %.1e, E(1)/E(0) = %.6f, simulate %.1f ms" % (
    f, s["steps"], s["events"], d[-1][c], dp, d[-1][e] / d[0][e], s["simulate_ms"]))
PY
done
for t in 0 0.25 1; do
  "$BIN" simulate models/Billiards.mo --method dopri5 --tolerance 1e-6 --stop-time 1 --points 4 -o "$OUT/snap.csv" >/dev/null 2>&1 || true
done

echo; echo "## cylinder on a box, 10 s"
"$BIN" simulate models/CylinderOnBox.mo --vars cylinder.r[1],cylinder.r[2],cylinder.r[3],cylinder.w[1],cylinder.w[2],cylinder.w[3] -o "$OUT/cyl.csv" --stats 2> "$OUT/cyl.json"
python3 - "$OUT" <<'PY'
import csv, json, sys
out = sys.argv[1]
s = json.loads(open(out + "/cyl.json").read().strip().splitlines()[-1])
rows = list(csv.reader(open(out + "/cyl.csv"))); h = rows[0]; d = [[float(x) for x in r] for r in rows[1:]]
w = max(abs(r[h.index("cylinder.w[%d]" % k)]) for r in d for k in (1, 2, 3))
dr = max(abs(r[h.index("cylinder.r[%d]" % k)] - d[0][h.index("cylinder.r[%d]" % k)]) for r in d for k in (1, 2, 3))
print("steps %d, max |w| = %.1e rad/s, max displacement %.1e m, simulate %.1f ms" % (s["steps"], w, dr, s["simulate_ms"]))
PY

echo; echo "## compression spring: every method, error of the cap height against radau5 at 1e-9"
runs="radau5:1e-9"
for m in bdf radau5; do for t in 1e-3 1e-4 1e-5 1e-6 1e-7 1e-8; do runs="$runs $m:$t"; done; done
for t in 1e-3 1e-4 1e-5 1e-6; do runs="$runs dopri5:$t"; done
echo "| method | rtol | steps | events | shortest (m) | at t (s) | passes its start at t (s) | contact changes | max cap height error (m) | simulate ms |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for run in $runs; do
  m=${run%%:*}; t=${run#*:}
  "$BIN" simulate models/CompressionSpring.mo --method $m --tolerance $t --vars length,gapMin,world.contactChanges \
    --output-tolerance 0 -o "$OUT/spring-$m-$t.csv" --stats 2> "$OUT/spring.json"
  python3 - "$OUT" "$m" "$t" <<'PY'
import csv, json, sys
out, m, t = sys.argv[1:4]
s = json.loads(open(out + "/spring.json").read().strip().splitlines()[-1])
def rows(f):
    r = list(csv.reader(open(f))); h = r[0]
    return h, [[float(x) for x in row] for row in r[1:]]
h, d = rows(out + "/spring-%s-%s.csv" % (m, t))
L, C = h.index("length"), h.index("world.contactChanges")
lo = min(d, key=lambda r: r[L])
past = next((r[0] for r in d if r[0] > lo[0] and r[L] > 0.08), float("nan"))
# The error on the output grid (rows at event instants left out: both runs have them
# at slightly different times).
grid = lambda d: {round(r[0] * 1e4): r[L] for r in d if abs(r[0] * 1e4 - round(r[0] * 1e4)) < 1e-6}
ref, own = grid(rows(out + "/spring-radau5-1e-9.csv")[1]), grid(d)
err = max(abs(own[k] - ref[k]) for k in ref if k in own)
print("| %s | %s | %d | %d | %.5f | %.4f | %.4f | %d | %.1e | %.0f |" % (
    m, t, s["steps"], s["events"], lo[L], lo[0], past, d[-1][C], err, s["simulate_ms"]))
PY
done
