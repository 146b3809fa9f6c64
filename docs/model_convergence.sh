#!/usr/bin/env bash
# Model convergence study (issue 3): ngspice's Shockley diodes approach lcspice's ideal ones as
# the emission coefficient N goes to 0. For each circuit and N, `lcspice validate --report` gives
# max|lcspice - ngspice|/range per probe; the largest over the probes is tabulated against N.
# A second sweep keeps N = 0.01 and lets ngspice take coarse steps (TMAX = k * TSTEP): sharp
# diodes with a coarse maximum step give wrong answers without any error message.
# Usage: bash docs/model_convergence.sh [build/cli/lcspice]   -> docs/model_convergence.tsv, .png
set -uo pipefail
cd "$(dirname "$0")/.."
lcspice=${1:-build/cli/lcspice}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=docs/model_convergence.tsv
echo -e "circuit\tsweep\tN\tngspice_tmax_over_tstep\tworst_probe\tmax_err_over_range\tngspice_cpu_s\toutcome" > "$out"

worst() {  # the report table's largest max_error_over_range and its probe (names may be quoted)
  awk -F, 'NR > 1 { v = $(NF-3) + 0; name = $0; sub(/,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*$/, "", name)
                    gsub(/"/, "", name); if (v > best) { best = v; worst = name } }
           END { printf "%s\t%.4e", worst, best }' "$1"
}

run_case() {  # circuit sweep N k
  local circuit=$1 sweep=$2 n=$3 k=$4 tstep tmax log
  tstep=$(awk 'tolower($1) == ".tran" {print $2}' circuits/$circuit.cir)
  tmax=$(awk -v s="$tstep" -v k="$k" 'BEGIN {
    v = s; m = 1; u = tolower(v); sub(/[a-z]+$/, "", v)
    if (u ~ /m$/) m = 1e-3; else if (u ~ /u$/) m = 1e-6; else if (u ~ /n$/) m = 1e-9
    printf "%.6g", v * m * k }')
  log=$tmp/$circuit-$n-$k.log
  # the probes the validation suite compares (circuits/validation.tsv)
  probes=$(awk -F'\t' -v c="$circuit" '$1 == c { if (match($3, /--probe [^ ]+/)) print substr($3, RSTART + 8, RLENGTH - 8) }' circuits/validation.tsv)
  "$lcspice" validate circuits/$circuit.cir --emission "$n" --max-step "$tmax" --tol 1e9 \
      --timeout 60 --report "$tmp/r.csv" ${probes:+--probe "$probes"} > "$log" 2>&1
  local code=$?
  if [ $code -eq 0 ]; then
    cpu=$(grep -oE '[0-9.]+ s CPU' "$log" | awk '{print $1}')
    echo -e "$circuit\t$sweep\t$n\t$k\t$(worst "$tmp/r.csv")\t$cpu\tok" >> "$out"
  else
    why=$(grep -m1 'ngspice failed' "$log" | sed 's/.*ngspice failed: //' | cut -c1-70)
    echo -e "$circuit\t$sweep\t$n\t$k\t-\t-\t-\tngspice failed: $why" >> "$out"
  fi
}

for circuit in half_wave_rectifier lc_tank_bridge; do
  for n in 1 0.3 0.1 0.03 0.01 0.003 0.001 0.0003; do run_case $circuit emission $n 1; done
  for k in 1 5 25 125; do run_case $circuit max-step 0.01 $k; done
done
column -t -s $'\t' "$out"

for c in half_wave_rectifier lc_tank_bridge; do
  awk -F'\t' -v c=$c '$1 == c && $2 == "emission" && $8 == "ok" { print $3, $6 }' "$out" > "$tmp/$c.dat"
done
gnuplot <<GP
set terminal pngcairo size 900,550 noenhanced font ',10'
set output 'docs/model_convergence.png'
set logscale xy
set grid
set key top left
set xlabel 'emission coefficient N of the Shockley diodes in ngspice'
set ylabel 'max |lcspice - ngspice| / range (worst probe)'
set title 'ngspice (Shockley diodes) against lcspice (ideal diodes) as N -> 0'
plot '$tmp/half_wave_rectifier.dat' using 1:2 with linespoints lw 2 title 'half-wave LC rectifier', \
     '$tmp/lc_tank_bridge.dat' using 1:2 with linespoints lw 2 title 'LC tank + bridge', \
     0.1 * x with lines dt 2 title 'proportional to N'
GP
echo "wrote $out and docs/model_convergence.png"
