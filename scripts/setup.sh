#!/usr/bin/env bash
# Installs what squeal needs from Debian 12 (when missing), configures and builds
# it in Release into build/. Safe to run again: it only does what is missing.
#   bash scripts/setup.sh [--packages] [--paraview]
#     --packages: install, do not build
#     --paraview: also ParaView for scripts/paraview.sh (Debian's paraview and
#       xvfb; python3-paraview conflicts with libvtk9-dev's python3-vtk9, so
#       its modules are unpacked into build/paraview instead of installed)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# libopenblas0-pthread: Debian's optimised BLAS/LAPACK replaces the reference
# ones behind libblas.so.3 (MUMPS factorisations, SLEPc orthogonalisation and
# the dense eigenproblems of the reduced sweep run several times faster).
# calculix-ccx: CalculiX 2.20, the peer code of end_to_end/calculix_two_blocks
# and of the side-by-side benchmarks. python3-h5py: end_to_end/cea_contact_history
# writes its contact histories (contact_history.h5) with it.
packages=(libdeal.ii-dev libeigen3-dev numdiff python3-matplotlib python3-numpy
          python3-h5py
          openmpi-bin libopenmpi-dev cmake make g++ libopenblas0-pthread
          libopencv-dev libopencv-contrib-dev libfftw3-dev libgmsh-dev
          libvtk9-dev zlib1g-dev clang-format python3-gmsh calculix-ccx)
build_it=1
with_paraview=0
for arg in "$@"; do
  case "$arg" in
    --packages) build_it=0 ;;
    --paraview) with_paraview=1 ;;
    *) echo "setup.sh: unknown option '$arg' (allowed: --packages, --paraview)" >&2; exit 2 ;;
  esac
done
[ "$with_paraview" -eq 1 ] && packages+=(paraview xvfb xauth)
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
mkdir -p "$here/build"
if [ "$with_paraview" -eq 1 ] && [ ! -d "$here/build/paraview/usr/lib/python3/dist-packages/paraview" ]; then
  version=$(dpkg-query -W -f='${Version}' paraview)
  tmp=$(mktemp -d)
  (cd "$tmp" && apt-get download -q "python3-paraview=$version" > /dev/null 2>&1) ||
    (cd "$tmp" && apt-get update -q > /dev/null && apt-get download -q "python3-paraview=$version")
  dpkg-deb -x "$tmp"/python3-paraview_*.deb "$here/build/paraview"
  rm -rf "$tmp"
fi
[ "$build_it" -eq 0 ] && exit 0
cd "$here/build"
if [ ! -f CMakeCache.txt ]; then
  cmake -DCMAKE_BUILD_TYPE=Release "$here" > cmake.log || { cat cmake.log; exit 1; }
fi
make -j"$(nproc)" 2>&1 | grep -E "error|warning|Error|Built target" || true
test "${PIPESTATUS[0]}" -eq 0
