#!/usr/bin/env bash
# Installs what squeal needs from Debian 12 (when missing), configures and builds
# it in Release into build/. Safe to run again: it only does what is missing.
#   bash scripts/setup.sh [--packages]   (--packages: install, do not build)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# libopenblas0-pthread: Debian's optimised BLAS/LAPACK replaces the reference
# ones behind libblas.so.3 (MUMPS factorisations, SLEPc orthogonalisation and
# the dense eigenproblems of the reduced sweep run several times faster).
packages=(libdeal.ii-dev libeigen3-dev numdiff python3-matplotlib python3-numpy
          openmpi-bin libopenmpi-dev cmake make g++ libopenblas0-pthread
          libopencv-dev libopencv-contrib-dev libfftw3-dev libgmsh-dev
          libvtk9-dev zlib1g-dev clang-format)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "squeal setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
[ "${1:-}" = "--packages" ] && exit 0
mkdir -p "$here/build"
cd "$here/build"
if [ ! -f CMakeCache.txt ]; then
  cmake -DCMAKE_BUILD_TYPE=Release "$here" > cmake.log || { cat cmake.log; exit 1; }
fi
make -j"$(nproc)" 2>&1 | grep -E "error|warning|Error|Built target" || true
test "${PIPESTATUS[0]}" -eq 0
