#!/bin/bash
# The linear-solver comparison of benchmarks/scale/README.md: the coarse
# passenger-car brake's stiffness (scripts/make_brake.py --size coarse,
# 91 374 DoFs at degree 2, no friction) exported by a one-point CEA
# (Output/Export matrices), then K + (2 pi 1 kHz)^2 M solved for 4
# right-hand sides by each solver of squeal-bench-linear-solvers, on 1 rank
# and (MUMPS) on 2. hypre's BoomerAMG gets 600 s.
# usage: bash benchmarks/scale/run_linear_solvers.sh [BUILD_DIR [WORK_DIR]]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
work=${2:-$root/output/linear_solvers}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OPENBLAS_NUM_THREADS=1
cd "$root"
[ -f prm/brake_coarse/brake.msh ] ||
  /usr/bin/python3 scripts/make_brake.py --size coarse
mkdir -p "$work"
cat > "$work/export.prm" << EOF
INCLUDE prm/brake_coarse/brake_scene.prm
subsection Scene
  set Analysis = cea
end
subsection Mesh
  set Finite element degree = 2
end
subsection Interface
  set Normal stiffness = 1e13
  set Friction coefficient = 0
end
subsection Eigensolver
  set Method = full
  set Minimum frequency = 500
  set Maximum frequency = 1000
end
subsection Sweep
  set First parameter  = contact.mu
  set First values     = 0
  set Second parameter = disc.E
  set Second values    = 1.1e11
end
subsection Output
  set Directory = $work/export
  set Overwrite = true
  set Export matrices = 0
  set Mode shapes = none
end
EOF
"$build/squeal" "$work/export.prm" > "$work/export.log"
matrices=$work/export/matrices
bench=$build/squeal-bench-linear-solvers
echo "solver,ranks,n,nonzeros,setup_s,solve_s_per_rhs,iterations_per_rhs,largest_relative_error,memory_before_MB,peak_MB,factor_MB"
for solver in mumps-lu mumps-ldlt umfpack amg-ml amg-gamg; do
  "$bench" "$matrices" 0 "$solver" 1000 4
done
for drop in 1e-8 1e-6; do
  "$bench" "$matrices" 0 mumps-lu-blr 1000 4 "$drop"
  PETSC_OPTIONS="-ksp_type gmres -ksp_rtol 1e-10" \
    "$bench" "$matrices" 0 mumps-lu-blr 1000 4 "$drop"
done
for solver in mumps-lu mumps-ldlt; do
  mpirun -np 2 "$bench" "$matrices" 0 "$solver" 1000 4
done
timeout 600 "$bench" "$matrices" 0 amg-hypre 1000 1 ||
  echo "amg-hypre: no answer within 600 s"
