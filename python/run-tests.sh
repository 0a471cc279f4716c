#!/usr/bin/env bash
# Builds the Python package into a virtual environment and runs its tests (pytest,
# with a Dask LocalCluster of two worker processes). Needs network for pip the first
# time; not part of .ci/run. Usage: python/run-tests.sh [VENV] (default .venv-python).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
venv="${1:-$here/../.venv-python}"
python3 -m venv "$venv"
"$venv/bin/pip" install -q --upgrade pip
"$venv/bin/pip" install -q "$here[test]"
"$venv/bin/python" -m pytest -q "$here/tests"
