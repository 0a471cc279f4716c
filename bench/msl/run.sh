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
# A row after every solver step besides the experiment's grid (see the results page).
cmd='{unimo} simulate {msl}/Modelica/package.mo --model {model} --lib {msl} --vars {vars} --every-step --output {csv}'
python3 "$shared/tools/msl-check" --unimo target/release/unimo --msl "$shared/msl" \
  --ref "$shared/msl-reference" --results "$results" --cmd "$cmd" "$@" | tee "${results%.csv}.txt"
# The same with msl-check's default command (the experiment's output grid alone).
python3 "$shared/tools/msl-check" --unimo target/release/unimo --msl "$shared/msl" \
  --ref "$shared/msl-reference" --results "${results%.csv}.grid.csv" "$@" > /dev/null
python3 bench/msl/report.py "$results" "$shared/msl-reference" "${results%.csv}.grid.csv" > docs/results/msl.md
echo "wrote docs/results/msl.md"
# Names: every file of the MSL through the name check (syntax errors must be 0).
target/release/unimo check --no-balance --lib "$shared/msl" "$shared/msl" > "${results%.csv}.check" 2>&1 || true
python3 bench/msl/names.py "${results%.csv}.check" >> docs/results/msl.md
