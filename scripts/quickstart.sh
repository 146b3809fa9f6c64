#!/usr/bin/env bash
# Quick start: set up, then simulate the default circuit to a CSV and say where it is.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mkdir -p out
circuit=circuits/lc_tank_bridge.cir
build/cli/lcspice run "$circuit" -o out/lc_tank_bridge.csv --stats
echo "quickstart: simulated $circuit; waveforms in $(pwd)/out/lc_tank_bridge.csv"
