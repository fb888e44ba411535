#!/usr/bin/env bash
# Set up and run the test suite on both cores (pytest-xdist, one worker per core; a file's
# tests stay on one worker so its module fixtures are computed once). The slow-marked runs
# (a transient Coulomb run to steady state) are outside: add -m slow to run them.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/python -m pytest -q -n 2 --dist loadfile "$@"
