#!/usr/bin/env bash
# Quick start, command 2: set up, build, check the C++ formatting and run the
# ctest verification suite.
# Tests labelled "long" are left out; run them with: cd build && ctest -L long
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# --paraview: the ParaView test (end_to_end/paraview) runs too
"$here/scripts/setup.sh" --paraview
# every C++ file follows .clang-format (deal.II's style)
"$here/scripts/check_format.sh"
cd "$here/build"
# OpenMPI refuses to start as root unless told; CI runs as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Two tests run at once (and some on 2 MPI ranks): one BLAS thread each, so
# the 2 cores are not oversubscribed.
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
ctest -LE long --output-on-failure -j2 "$@"
