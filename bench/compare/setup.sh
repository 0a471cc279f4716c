#!/usr/bin/env bash
# Installs what the comparison needs that the machine may lack (run as root once):
# SUNDIALS (Debian's libsundials-dev, for IDA) and SciPy (PyPI). diffsol comes from
# crates.io through cargo when run.sh builds bench/compare/diffsol.
set -euo pipefail
if ! dpkg -s libsundials-dev >/dev/null 2>&1; then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y libsundials-dev
fi
python3 -c 'import scipy' 2>/dev/null || python3 -m pip install scipy
