#!/usr/bin/python3
"""The tolerance-driven cycles do not depend on the BLAS kernels' rounding.

usage: check_adaptive_determinism.py SQUEAL PRM WORKDIR

PRM: the clamped disc from degree 1 with h or p
(end_to_end/adaptive_tolerance_degree.prm), run here for three cycles:
an h step, then a degree step. The disc's 20-fold symmetric mesh has doublets
whose two eigenvectors are any pair of their space, different with every
rounding; the marking and the estimate must not depend on which pair. The
same input is run under three OpenBLAS core types (OPENBLAS_CORETYPE
Nehalem, Core2, Prescott: SSE kernels that every x86-64 host runs, whose
roundings differ), and the checks are:
- adaptive_cycles.csv: the same cells, DoFs, degree, estimate DoFs and
  number of modes above the tolerance in every cycle;
- adaptive_modes.csv: the same number of modes, frequencies and estimated
  errors within 1e-5 relative of each other (the file's six significant
  digits), and no mode of the band without a partner (an estimate of
  100 %) on the last mesh.
"""
import csv
import os
import sys

from checks import check, finish, run_squeal

squeal, prm, work = sys.argv[1:4]
prm = os.path.abspath(prm)
os.makedirs(work, exist_ok=True)
os.chdir(work)

extra = "subsection Mesh\n  set Adaptive cycles = 2\nend\n"
runs = {}
for core in ("Nehalem", "Core2", "Prescott"):
    os.environ["OPENBLAS_CORETYPE"] = core
    out, log = run_squeal(squeal, prm, core, extra)
    with open(os.path.join(out, "adaptive_cycles.csv")) as f:
        cycles = list(csv.DictReader(f))
    with open(os.path.join(out, "adaptive_modes.csv")) as f:
        modes = list(csv.DictReader(f))
    runs[core] = (cycles, modes)
    print(core, [(r["cycle"], r["cells"], r["dofs"], r["degree"],
                  r["max_estimated_error"]) for r in cycles])

keys = ("cycle", "cells", "dofs", "degree", "estimate_dofs", "modes_above_tolerance")
first_cycles, first_modes = runs["Nehalem"]
check("three cycles, one of them a degree step",
      len(first_cycles) == 3 and first_cycles[-1]["degree"] != first_cycles[0]["degree"],
      str([(r["cells"], r["degree"]) for r in first_cycles]))
for core in ("Core2", "Prescott"):
    cycles, modes = runs[core]
    check(f"{core}: the same cycles as Nehalem (cells, DoFs, degree, estimate)",
          [[r[k] for k in keys] for r in cycles]
          == [[r[k] for k in keys] for r in first_cycles],
          f"{[[r[k] for k in keys] for r in cycles]} against "
          f"{[[r[k] for k in keys] for r in first_cycles]}", True)
    df = max((abs(float(a["freq_Hz"]) - float(b["freq_Hz"])) / float(b["freq_Hz"])
              for a, b in zip(modes, first_modes)), default=1.)
    de = max((abs(float(a["estimated_relative_error"]) -
                  float(b["estimated_relative_error"])) /
              float(b["estimated_relative_error"])
              for a, b in zip(modes, first_modes)), default=1.)
    check(f"{core}: the same modes and estimates as Nehalem",
          len(modes) == len(first_modes) > 0 and df < 1e-5 and de < 1e-5,
          f"{len(modes)} / {len(first_modes)} modes, frequencies {df:.2e}, "
          f"estimates {de:.2e} apart", True)
# the band of the prm (0.9-8 kHz) less the 2 % margins of the tolerance checks
band = [r for r in first_modes if 1.02 * 900. < float(r["freq_Hz"]) < 0.98 * 8000.]
check("every mode of the band on the last mesh has a partner (no estimate of "
      "100 %)",
      len(band) >= 12 and all(float(r["estimated_relative_error"]) < 1. and
                              r["estimate_partner_freq_Hz"] != "" for r in band),
      str([(r["freq_Hz"], r["estimated_relative_error"]) for r in band]))
finish()
