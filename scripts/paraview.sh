#!/usr/bin/env bash
# Runs a ParaView Python script off-screen: Debian's pvbatch (package paraview)
# with the python3-paraview modules that `scripts/setup.sh --paraview`
# unpacks into build/paraview (Debian 12's python3-paraview conflicts with
# python3-vtk9, which squeal's libvtk9-dev needs, so it is not installed),
# on a virtual X display (xvfb-run; ParaView 5.11 aborts off-screen without
# one).
#   scripts/paraview.sh SCRIPT.py [ARGS...]
# Exit status 77 when ParaView is not set up.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
modules="$here/build/paraview/usr/lib/python3/dist-packages"
if ! command -v pvbatch > /dev/null || ! command -v xvfb-run > /dev/null ||
   [ ! -d "$modules/paraview" ]; then
  echo "paraview.sh: ParaView is not set up; run: bash scripts/setup.sh --paraview" >&2
  exit 77
fi
export PYTHONPATH="$modules${PYTHONPATH:+:$PYTHONPATH}"
# Debian's pvbatch 5.11 now and then aborts while creating its window under
# Xvfb (vtkXOpenGLRenderWindow::CreateAWindow); that start is tried again,
# at most three times, and only the last attempt's messages are shown.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for attempt in 1 2 3; do
  status=0
  xvfb-run -a pvbatch "$@" 2> "$log" || status=$?
  if [ "$status" -ne 0 ] && [ "$attempt" -lt 3 ] &&
     grep -q "CreateAWindow" "$log"; then
    echo "paraview.sh: pvbatch could not open its window under Xvfb; starting it again" >&2
    continue
  fi
  cat "$log" >&2
  exit "$status"
done
