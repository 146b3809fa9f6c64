#!/usr/bin/env bash
# Installs what lcspice needs from Debian's packages (only what is missing), then configures
# and builds it in build/. Safe to run again; it does nothing that is already done.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(cmake g++ make pkg-config libeigen3-dev libboost-graph-dev libsundials-dev
          libngspice0-dev libgtest-dev libcli11-dev gnuplot-nox
          libsuitesparse-dev
          clang libclang-rt-14-dev)  # clang: the ASan+UBSan suite and libFuzzer (scripts/fuzz.sh)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" >/dev/null
echo "setup: built build/cli/lcspice" >&2
