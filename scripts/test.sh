#!/usr/bin/env bash
# Quick start 2: set up, then build and run the whole test suite with ctest
# (labels: fast = unit tests, slow = whole replays, engines = --emit-jobs lists
# run by GNU parallel and a Slurm array; all run here).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
