#!/usr/bin/env bash
# Create .venv (Python >= 3.11) and install hotroll with its dependencies from PyPI.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$PY" -c 'import sys; assert sys.version_info >= (3, 11), "hotroll needs Python >= 3.11"'
  "$PY" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -e ".[test,pyroll,mpi]"
# byte-compile hotroll once: where PYTHONDONTWRITEBYTECODE is set (this machine, the CI's)
# every command would otherwise compile its ~100 modules again (about 0.13 s a command)
.venv/bin/python -m compileall -q hotroll
