#!/usr/bin/env bash
# Set up and reproduce the report's Example 1 (m = 0.2, omega = pi/3) into results/example1.
# Mesh h_contact = 0.01 m (2x Table 2's C1) so that the run reaches its steady state in about
# 8 minutes on 2 cores; pass e.g. `--mesh C2` for the report's mesh (about an hour and more).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/hotroll example 1 --mesh 0.01 --out results/example1 "$@"
