#!/usr/bin/env bash
# Set up, then run the whole test suite (unit, golden-waveform, command-line tests) in the
# Release build, then again under AddressSanitizer + UndefinedBehaviorSanitizer (clang, -O1),
# then each libFuzzer target for 60 s in the same instrumented tree (scripts/fuzz.sh; longer runs:
# bash scripts/fuzz.sh 36000).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
(cd build && ctest --output-on-failure -j"$(nproc)")
bash scripts/test_sanitized.sh
bash scripts/fuzz.sh 60
