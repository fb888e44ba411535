#!/usr/bin/env bash
# Set up (the venv; Debian's chromium for the report test, when root on Debian) and run the
# test suite on both cores (pytest-xdist, one worker per core; a file's tests stay on one
# worker so its module fixtures are computed once). The slow-marked runs (a transient
# Coulomb run to steady state) are outside: add -m slow to run them.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# the report test renders the pages in Debian's headless chromium (tests/results/test_report.py)
if ! command -v chromium >/dev/null && [ -z "${HOTROLL_SKIP_BROWSER:-}" ]; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium
  else
    echo "tests/results/test_report.py needs Debian's chromium: sudo apt-get install chromium" \
         "(or HOTROLL_SKIP_BROWSER=1 to skip the browser part)" >&2
  fi
fi
# the layers import one way and no package has an import cycle (docs/architecture.md)
.venv/bin/lint-imports --no-cache
.venv/bin/ruff check hotroll tests scripts benchmarks
# --no-loadscope-reorder: the files in collection order, the longest first (tests/conftest.py),
# not by their number of tests (xdist's default, which left the mesh-table study for last)
.venv/bin/python -m pytest -q -n 2 --dist loadfile --no-loadscope-reorder "$@"
