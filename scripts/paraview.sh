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
exec xvfb-run -a pvbatch "$@"
