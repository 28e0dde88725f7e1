#!/usr/bin/env bash
# Quick start, command 1: set up, build, run the TriboBrake complex eigenvalue
# sweep (prm/tribobrake_cea.prm) and make its plots. Extra arguments go to squeal
# (for example --overwrite).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/setup.sh"
cd "$here"
build/squeal "$@" prm/tribobrake_cea.prm
/usr/bin/python3 scripts/plot_cea.py output/tribobrake_cea
