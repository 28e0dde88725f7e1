#!/usr/bin/env bash
# The default ctest suite under AddressSanitizer and UndefinedBehaviorSanitizer:
# squeal, squeal-tribology and every test built with -DSQUEAL_SANITIZE=ON in
# build-sanitize/ (deal.II, PETSc and the other libraries are not
# instrumented), then ctest -LE long there. Any report aborts the program
# that made it, so its test fails, except what scripts/ubsan.supp lists (UB
# inside deal.II's own headers, which squeal cannot change). Leak checking is off: Open MPI and PETSc
# keep allocations until exit by design.
#   bash scripts/sanitize.sh [ctest arguments]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/setup.sh" --packages
mkdir -p "$here/build-sanitize"
cd "$here/build-sanitize"
if [ ! -f CMakeCache.txt ]; then
  cmake -DCMAKE_BUILD_TYPE=Release -DSQUEAL_SANITIZE=ON "$here" > cmake.log ||
    { cat cmake.log; exit 1; }
fi
make -j"$(nproc)" 2>&1 | grep -E "error|Error" || true
test "${PIPESTATUS[0]}" -eq 0
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:detect_odr_violation=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:suppressions=$here/scripts/ubsan.supp
ctest -LE long --output-on-failure -j2 "$@"
