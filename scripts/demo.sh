#!/usr/bin/env bash
# Quick start 1: set up, then run every plugin config in configs/ side by side
# on the bundled default rawlog (grid196, book Sec. 4.6.1) and print the
# comparison table. Outputs: out/demo/<config>/ (maps, figures, stats.json),
# out/demo/comparison.csv and comparison.md.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh esif esif_all_plugins  # the host and the plugins only: the tests are test.sh's
configs=$(ls configs/*.ini | paste -sd, -)
./build/bin/esif compare --configs "$configs" --rawlog rawlogs/grid196.rawlog --out out/demo
