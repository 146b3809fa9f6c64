#!/usr/bin/env bash
# The whole test suite again under AddressSanitizer + UndefinedBehaviorSanitizer, in the clang
# tree scripts/instrumented_tree.sh configures (Eigen's assertions on; scripts/fuzz.sh runs its
# fuzz targets next). Called by scripts/test.sh after the Release suite; needs what
# scripts/setup.sh installs.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/instrumented_tree.sh
cmake --build build-asan -j"$(nproc)" >/dev/null
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The random-circuit differential test's first 30 seeds (of the Release run's 120): under the
# sanitizers each group of 10 costs about 20 s of CPU at -O1. The other groups are still listed
# by ctest and pass with no test run.
export LCSPICE_RANDOM_SEEDS="${LCSPICE_RANDOM_SEEDS:-1:30}"
cd build-asan
ctest --output-on-failure -j"$(nproc)" --timeout 600
