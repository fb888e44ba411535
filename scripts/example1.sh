#!/usr/bin/env bash
# Set up and reproduce the report's Example 1 (m = 0.2, omega = pi/3) into results/example1:
# the direct steady solver on the report's mesh C2 (about 10 s on 2 cores with the figures).
# The report's own scheme, explicit time stepping to the steady state, is one option away:
#   bash scripts/example1.sh --method transient --out results/example1_transient
# (about 5 minutes on C2 with 2 threads).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/hotroll example 1 --mesh C2 --out results/example1 "$@"
