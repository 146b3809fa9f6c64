#!/usr/bin/env bash
# Regenerates the golden reference waveforms in tests/golden/ and checks them by refinement.
# For each circuit of manifest.tsv: implicit Euler at TSTEP/64 (the reference, kept at the
# multiples of TSTEP) and at TSTEP/32; prints, per probe, the largest difference between the two
# relative to the probe's range. Implicit Euler being first order, the reference's own error is
# about that difference, and the test at TSTEP (error about 64 times larger) is checked against
# tolerances far above it. Usage: bash tests/golden/generate.sh [build/cli/lcspice]
set -euo pipefail
cd "$(dirname "$0")/../.."
lcspice=${1:-build/cli/lcspice}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

keep_every() {  # keep the header and every N-th data row starting at t = 0
  awk -v n="$1" 'NR == 1 || (NR - 2) % n == 0'
}

grep -v '^#' tests/golden/manifest.tsv | while read -r circuit tol; do
  [ -n "$circuit" ] || continue
  net=circuits/$circuit.cir
  tstep=$(awk 'tolower($1) == ".tran" {print $2}' "$net")
  step64=$(awk -v s="$tstep" 'BEGIN {
    v = s; m = 1; u = tolower(v); sub(/[a-z]+$/, "", v)
    if (u ~ /meg/) m = 1e6; else if (u ~ /m$/) m = 1e-3; else if (u ~ /u$/) m = 1e-6;
    else if (u ~ /n$/) m = 1e-9; else if (u ~ /p$/) m = 1e-12; else if (u ~ /k$/) m = 1e3;
    printf "%.17g", v * m / 64 }')
  step32=$(awk -v s="$step64" 'BEGIN { printf "%.17g", 2 * s }')
  "$lcspice" run "$net" --method euler --step "$step64" | keep_every 64 > tests/golden/$circuit.csv
  "$lcspice" run "$net" --method euler --step "$step32" | keep_every 32 > "$tmp/$circuit.32.csv"
  echo "$circuit: reference at TSTEP/64 = $step64 s; refinement check against TSTEP/32:"
  paste -d, tests/golden/$circuit.csv "$tmp/$circuit.32.csv" | awk '
    function split_csv(line, out,    n, i, c, field, quoted) {  # RFC 4180 fields of one line
      n = 0; field = ""; quoted = 0
      for (i = 1; i <= length(line); i++) {
        c = substr(line, i, 1)
        if (c == "\"") quoted = !quoted
        else if (c == "," && !quoted) { out[++n] = field; field = "" }
        else field = field c
      }
      out[++n] = field
      return n
    }
    { nf = split_csv($0, f) }
    NR == 1 { n = nf / 2; for (i = 2; i <= n; i++) name[i] = f[i]; next }
    { for (i = 2; i <= n; i++) {
        a = f[i]; b = f[i + n]; d = a - b; if (d < 0) d = -d
        if (d > diff[i]) diff[i] = d
        if (!(i in lo) || a + 0 < lo[i]) lo[i] = a + 0
        if (!(i in hi) || a + 0 > hi[i]) hi[i] = a + 0 } }
    END { for (i = 2; i <= n; i++) {
        r = hi[i] - lo[i]; if (r == 0) r = 1
        printf "  %-12s max|ref64 - ref32|/range = %.2e\n", name[i], diff[i] / r } }'
done
