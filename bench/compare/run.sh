#!/usr/bin/env bash
# Runs the whole comparison and writes results.md. The four small problems run in ROUNDS
# rounds, each round every tool (unimo, IDA, diffsol) one after the other, so that a slow
# or fast stretch of the shared machine falls on all of them; a cell's time is the median
# of its rounds' medians. BRUSS2D and SciPy run once, one tool after the other.
#   bash bench/compare/run.sh              (from anywhere; RUNS=5 SCIPY_RUNS=5 ROUNDS=5 by default)
# Environment: ROUNDS, RUNS (runs per configuration and round for unimo, IDA and diffsol), SCIPY_RUNS,
# UNIMO_TOLERANCES (comma-separated; default the 1-2-5 series from 5e-3 to 1e-10),
# BRUSS_RUNS (runs per configuration of the 2,048-equation BRUSS2D, default 3; SciPy runs
# it once), CARGO_TARGET_DIR for the diffsol project (default /work/tgt-compare).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
RUNS="${RUNS:-5}"
ROUNDS="${ROUNDS:-5}"
SCIPY_RUNS="${SCIPY_RUNS:-5}"
BRUSS_RUNS="${BRUSS_RUNS:-3}"
# unimo's tolerances: the 1-2-5 series from 5e-3 to 1e-10 (the other tools run at 1e-4,
# 1e-6, 1e-8, 1e-10; the table at equal digits reads unimo's whole work-precision curve).
UNIMO_TOLERANCES="${UNIMO_TOLERANCES:-5e-3,2e-3,1e-3,5e-4,2e-4,1e-4,5e-5,2e-5,1e-5,5e-6,2e-6,1e-6,5e-7,2e-7,1e-7,5e-8,2e-8,1e-8,5e-9,2e-9,1e-9,1e-10}"
export BRUSS2D_REF="$HERE/refs/bruss2d.csv"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-/work/tgt-compare}"
OUT="$HERE/out"
mkdir -p "$OUT"
: > "$OUT/results.tsv"
: > "$OUT/load.txt"
: > "$OUT/solutions.txt"

# Load average, the machine's CPU use over a 1 s sample, and the busiest process in it
# (other work on the shared machine shows up here).
load() {
  local sample
  sample="$(top -b -n 2 -d 1 -o %CPU | awk '/^top -/ { n++ }
      n == 2 && /^%Cpu/ { for (i = 1; i <= NF; i++) if ($i ~ /^id,?$/) idle = $(i - 1) }
      n == 2 && $1 ~ /^[0-9]+$/ && !p { p = $12 " at " $9 "%" }
      END { printf "CPU %.0f%% busy (average over the 2 cores), busiest process %s", 100 - idle, p }')"
  echo "$1: load average $(cut -d' ' -f1-3 /proc/loadavg); 1 s sample: $sample" | tee -a "$OUT/load.txt"
}

# ---- prerequisites and builds (not timed) ------------------------------------------
dpkg -s libsundials-dev >/dev/null 2>&1 || { echo "libsundials-dev missing: run setup.sh" >&2; exit 1; }
python3 -c 'import scipy' 2>/dev/null || { echo "scipy missing: run setup.sh" >&2; exit 1; }
# UNIMO_BIN: the unimo binary to measure (default target/release/unimo of the repository).
UNIMO_BIN="${UNIMO_BIN:-$REPO/target/release/unimo}"
if [ ! -x "$UNIMO_BIN" ]; then (cd "$REPO" && CARGO_TARGET_DIR="$REPO/target" cargo build --release --bin unimo); fi
# A private copy, so that a concurrent rebuild of target/ cannot swap the binary mid-run.
cp "$UNIMO_BIN" "$OUT/unimo"
UNIMO="$OUT/unimo"
make -C "$HERE/ida" >/dev/null
(cd "$HERE/diffsol" && cargo build --release --quiet)
DIFFSOL="$CARGO_TARGET_DIR/release/compare-diffsol"
# The peers' POLLU reaction table and analytic Jacobians, checked (complex-step derivatives).
python3 "$HERE/scipy_compare.py" check

# ---- versions ------------------------------------------------------------------------
{
  echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "- machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(uname -sr)"
  DIRTY=""
  if (cd "$REPO" && GIT_OPTIONAL_LOCKS=0 git status --porcelain --untracked-files=no 2>/dev/null | grep -q .); then
    DIRTY=" (the work tree had uncommitted changes, which the binary may include)"
  fi
  echo "- unimo: $("$UNIMO" --version), HEAD $(cd "$REPO" && git rev-parse --short HEAD 2>/dev/null || echo '?')$DIRTY, binary built $(date -u -r "$UNIMO_BIN" '+%Y-%m-%d %H:%M UTC'), sha256 $(sha256sum "$UNIMO" | cut -c1-12)"
  echo "- IDA: $("$HERE/ida/ida_compare" version), Debian libsundials-dev $(dpkg-query -W -f='${Version}' libsundials-dev), $(cc --version | head -1)"
  echo "- diffsol: $(grep -A1 '^name = "diffsol"$' "$HERE/diffsol/Cargo.lock" | sed -n 's/version = "\(.*\)"/\1/p') ($(rustc --version))"
  echo "- SciPy: $(python3 -c 'import scipy, numpy, sys; print(f"scipy {scipy.__version__}, numpy {numpy.__version__}, Python {sys.version.split()[0]}")')"
} > "$OUT/versions.md"
cat "$OUT/versions.md"

# ---- 1.-3. unimo, IDA, diffsol ------------------------------------------------------------
# unimo: one model file per problem; appends its rows to results.tsv.
unimo_bench() { # problem model ref atol-factor runs
  # The other tools' tolerances and the ones between them (the table at equal digits).
  "$UNIMO" bench "$REPO/models/$2.mo" --reference "$HERE/refs/$3.csv" \
    --tolerances "$UNIMO_TOLERANCES" \
    --atol-factor "$4" --runs "$5" --points 1 --color never > "$OUT/unimo-$3.txt" || true
  cat "$OUT/unimo-$3.txt"
  # model method rtol atol median_ms steps scd_end scd_grid [FAILED: msg]
  awk -v P="$1" 'NR > 1 {
      status = "ok"; scd = $7
      if (NF > 8) { status = $9; for (i = 10; i <= NF; i++) status = status " " $i; scd = "-" }
      printf "%s\tunimo\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n", P, $2, $3, $4, scd, $6, $5, status
    }' "$OUT/unimo-$3.txt" >> "$OUT/results.tsv"
}
SMALL="ROBER:Robertson:rober:1e-6 HIRES:Hires:hires:1e-2 VDPOL:VanDerPol:vdpol:1e-2 POLLU:Pollu:pollu:1"
for round in $(seq 1 "$ROUNDS"); do
  load "round $round of $ROUNDS, before unimo"
  for spec in $SMALL; do
    IFS=: read -r P M R A <<< "$spec"
    unimo_bench "$P" "$M" "$R" "$A" "$RUNS"
  done
  load "round $round of $ROUNDS, before IDA"
  for p in rober hires vdpol pollu; do
    "$HERE/ida/ida_compare" "$RUNS" $p analytic 2>> "$OUT/solutions.txt" | tee -a "$OUT/results.tsv"
    "$HERE/ida/ida_compare" "$RUNS" $p dq 2>/dev/null | tee -a "$OUT/results.tsv"
  done
  load "round $round of $ROUNDS, before diffsol"
  "$DIFFSOL" "$RUNS" rober hires vdpol pollu 2>> "$OUT/solutions.txt" | tee -a "$OUT/results.tsv"
done
load "BRUSS2D, before unimo"
unimo_bench BRUSS2D Brusselator2D bruss2d 1e-2 "$BRUSS_RUNS"
load "BRUSS2D, before IDA"
"$HERE/ida/ida_compare" "$BRUSS_RUNS" bruss2d analytic 2>> "$OUT/solutions.txt" | tee -a "$OUT/results.tsv"
load "BRUSS2D, before diffsol"
# BRUSS2D: BDF only by default (point 4 compares with diffsol's BDF; its SDIRK methods take
# many times longer on this problem); BRUSS_DIFFSOL_METHODS=bdf,tr_bdf2,esdirk34 for all.
METHODS="${BRUSS_DIFFSOL_METHODS:-bdf}" "$DIFFSOL" "$BRUSS_RUNS" bruss2d 2>> "$OUT/solutions.txt" | tee -a "$OUT/results.tsv"

# ---- 4. SciPy --------------------------------------------------------------------------
load "before SciPy"
python3 "$HERE/scipy_compare.py" "$SCIPY_RUNS" 2>> "$OUT/solutions.txt" | tee -a "$OUT/results.tsv"
load "after SciPy"

python3 "$HERE/make_table.py" "$OUT" "$RUNS" "$SCIPY_RUNS" "$BRUSS_RUNS" "$ROUNDS" > "$HERE/results.md"
echo "wrote $HERE/results.md"
