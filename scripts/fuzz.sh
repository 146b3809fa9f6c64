#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz) with clang, ASan and UBSan in build-asan (the tree
# the sanitized suite ran in: scripts/instrumented_tree.sh), and runs each for SECONDS (default
# 60) on a seed corpus of circuits/, tests/bad_netlists/, tests/fuzz/seeds/ (circuits large
# enough for the sparse and descriptor step paths) and, when present, ../shared/realworld/.
# Fails on any crash, hang, sanitizer report or undocumented exception. A hang is 25 s on one
# input: this -O1 tree with Eigen's assertions on runs about a third as fast as the former -O2
# fuzz tree, against whose 10 s transient_fuzz.cpp's input filters were set.
# Long runs: bash scripts/fuzz.sh 36000
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
bash scripts/instrumented_tree.sh
cmake --build build-asan -j"$(nproc)" --target operating_point_fuzz transient_fuzz >/dev/null

seeds=build-fuzz/seeds
rm -rf "$seeds" && mkdir -p "$seeds/op" "$seeds/tran"
shopt -s nullglob
n=0
for f in circuits/*.cir circuits/*/*.cir tests/bad_netlists/*.cir tests/fuzz/seeds/*.cir $(find ../shared/realworld -name "*.cir" -o -name "*.sp" 2>/dev/null); do
  [ "$(stat -c %s "$f")" -le 4096 ] || continue
  n=$((n + 1))
  cp "$f" "$seeds/op/$n.cir"
  # transient_fuzz reads the method from the first byte.
  { printf "\\x$(printf %02x $((n % 6)))"; cat "$f"; } > "$seeds/tran/$n.cir"
done
# The large seeds with every method byte (the adaptive methods skip them: kMaxElementsAdaptive).
for f in tests/fuzz/seeds/*.cir; do
  for m in 0 1 2 3 4 5; do
    n=$((n + 1))
    { printf "\\x0$m"; cat "$f"; } > "$seeds/tran/$n.cir"
  done
done
# Inputs that once failed (first byte: the method), replayed by both targets.
for f in tests/fuzz/regressions/*; do
  n=$((n + 1))
  tail -c +2 "$f" > "$seeds/op/$n.cir"
  cp "$f" "$seeds/tran/$n.cir"
done
echo "fuzz: $n seed decks, $seconds s per target" >&2

export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
for target in operating_point_fuzz transient_fuzz; do
  corpus="build-fuzz/corpus/${target%_fuzz}"
  mkdir -p "$corpus"
  seed="$seeds/op"
  [ "$target" = transient_fuzz ] && seed="$seeds/tran"
  "build-asan/tests/fuzz/$target" "$corpus" "$seed" -dict=tests/fuzz/spice.dict \
    -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2048 -max_len=4096 \
    -artifact_prefix="build-fuzz/${target}-" -print_final_stats=1 2> "build-fuzz/${target}.log" || {
    tail -40 "build-fuzz/${target}.log" >&2
    echo "fuzz: $target found a failure; the input is build-fuzz/${target}-*" >&2
    exit 1
  }
  grep -E "stat::number_of_executed_units|cov:" "build-fuzz/${target}.log" | tail -2 >&2
done
