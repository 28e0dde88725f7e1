#!/usr/bin/python3
"""End-to-end check of Mesh/Adaptive cycles (tests/end_to_end/adaptive.prm).

usage: check_adaptive.py SQUEAL PRM WORKDIR

- without cycles the run writes mesh_error.csv (cells and indicator share
  per body) and no adaptive_cycles.csv; with Output/Error indicator = false
  neither mesh_error file, and the same eigenvalues;
- cycles 0 and 1 solve without refinement rounds (they only drive the
  indicator), the last cycle's solve (the sweep's first point) is refined
  to the residual tolerance;
- with 2 cycles, adaptive_cycles.csv has the cycles 0, 1, 2 with cells and
  DoFs growing, the frequency changes from cycle 1 on, and the final mesh
  (mesh_error.csv) has more cells than the first;
- the refinement went where the indicator pointed: the body with the
  largest share of the first mesh's indicator gained the largest fraction of
  new cells (ties allowed), the one with the smallest share fewer;
- the modes' frequencies on the final mesh are below those of the first
  mesh on the whole (refinement relaxes a conforming displacement model: the
  median of the matched changes is a decrease);
- Mesh/Marking = error (Doerfler's bulk criterion) with Refinement fraction
  0.5 refines fewer cells than Marking = cells with the same fraction (half
  of the cells): the indicator is concentrated in the support, so half of
  the squared indicator sits in far fewer than half of the cells.
"""
import csv
import os
import re
import sys

from checks import check, finish, run_squeal

squeal, prm, work = sys.argv[1:4]
prm = os.path.abspath(prm)
os.makedirs(work, exist_ok=True)
os.chdir(work)


def run(name, cycles, extra="", mpi=0):
    return run_squeal(squeal, prm, name,
                      f"subsection Mesh\n  set Adaptive cycles = {cycles}\n{extra}end\n",
                      mpi)


def table(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def bodies(out):
    return {r["body"]: (int(r["cells"]), float(r["share_of_squared_indicator"]))
            for r in table(os.path.join(out, "mesh_error.csv"))}


def eigenvalues(out):
    """(frequency [Hz], growth rate [1/s]) of every mode in OUT, sorted."""
    return sorted((float(r["freq_Hz"]), float(r["re_per_s"]))
                  for r in table(os.path.join(out, "eigenvalues.csv")))


plain, _ = run("plain", 0)
b0 = bodies(plain)
check("no cycles: mesh_error.csv, no adaptive_cycles.csv",
      set(b0) == {"disc", "pad", "support"}
      and not os.path.exists(os.path.join(plain, "adaptive_cycles.csv")), str(b0))
quiet, _ = run_squeal(squeal, prm, "no_indicator",
                      "subsection Output\n  set Error indicator = false\nend\n")
check("Output/Error indicator = false: no mesh_error files, the same "
      "eigenvalues",
      not any(os.path.exists(os.path.join(quiet, "mesh_error." + e))
              for e in ("csv", "vtu"))
      and eigenvalues(quiet) == eigenvalues(plain)
      and len(eigenvalues(plain)) > 10, str(len(eigenvalues(quiet))))
adaptive, log = run("adaptive", 2)
cycles = table(os.path.join(adaptive, "adaptive_cycles.csv"))
check("adaptive_cycles.csv: cycles 0, 1, 2 with cells and DoFs growing",
      [int(r["cycle"]) for r in cycles] == [0, 1, 2]
      and all(int(a["cells"]) < int(b["cells"]) and int(a["dofs"]) < int(b["dofs"])
              for a, b in zip(cycles, cycles[1:])), str(cycles))
check("frequency changes reported from cycle 1 on",
      float(cycles[0]["max_relative_change"]) < 0
      and all(float(r["max_relative_change"]) >= 0 for r in cycles[1:])
      and "change from the previous mesh" in log, log[-1500:])
# the cycles before the last only drive the indicator (the projection, no
# refinement rounds); the last is the sweep's first point, refined to
# Eigensolver/Residual tolerance (1e-10)
solves = [(int(c), int(n), float(r)) for c, n, r in re.findall(
    r"Adaptive cycle (\d+): .*\((\d+) refinement rounds, largest relative "
    r"residual ([0-9.eE+-]+)\)", log)]
check("cycles 0 and 1 without refinement rounds, cycle 2 refined to 1e-10",
      [c for c, _, _ in solves] == [0, 1, 2]
      and solves[0][1] == 0 and solves[1][1] == 0
      and solves[2][1] >= 1 and solves[2][2] <= 1e-10, str(solves))
b2 = bodies(adaptive)
gain = {b: b2[b][0] / b0[b][0] for b in b0}
worst = max(b0, key=lambda b: b0[b][1])
least = min(b0, key=lambda b: b0[b][1])
check("the body with the largest indicator share gained the most cells, the "
      "one with the smallest share fewer",
      gain[worst] == max(gain.values()) and gain[least] < gain[worst],
      f"shares {b0}, gains {gain}", True)
f0 = [f for f, _ in eigenvalues(plain)]
f2 = [f for f, _ in eigenvalues(adaptive)]
changes = sorted(min(f2, key=lambda g: abs(g - f)) - f for f in f0 if 1000 < f < 9500)
check("frequencies move down with refinement (median change < 0)",
      changes and changes[len(changes) // 2] < 0,
      f"median change {changes[len(changes) // 2] if changes else None} Hz", True)


# the same refinement on a mesh distributed over two ranks (the shared
# triangulation is repartitioned after each refinement): the same cells and
# DoFs in every cycle and the same eigenvalues (full solver to residual 1e-8:
# 1e-7 relative in frequency, 1e-5 of |Re| + 1 1/s in growth rate)
adaptive_np2, _ = run("adaptive_np2", 2, mpi=2)
cycles_np2 = table(os.path.join(adaptive_np2, "adaptive_cycles.csv"))
check("mpirun -np 2: the same cells and DoFs in every cycle",
      [(r["cells"], r["dofs"]) for r in cycles_np2]
      == [(r["cells"], r["dofs"]) for r in cycles], f"{cycles_np2} vs {cycles}")


e1, e2 = eigenvalues(adaptive), eigenvalues(adaptive_np2)
df = max((abs(a[0] - b[0]) / a[0] for a, b in zip(e1, e2)), default=1.)
dre = max((abs(a[1] - b[1]) / (abs(a[1]) + 1) for a, b in zip(e1, e2)), default=1.)
check("mpirun -np 2: the same eigenvalues on the refined mesh",
      len(e1) == len(e2) and df < 1e-7 and dre < 1e-5,
      f"{len(e1)} / {len(e2)} modes, frequency {df:.2e}, growth rate {dre:.2e}", True)


def refined(marking):
    out, _ = run("marking_" + marking, 1,
                 f"  set Marking = {marking}\n  set Refinement fraction = 0.5\n")
    c = table(os.path.join(out, "adaptive_cycles.csv"))
    return (int(c[1]["cells"]) - int(c[0]["cells"])) / 7, int(c[0]["cells"])


by_error, n0 = refined("error")
by_cells, _ = refined("cells")
check("Marking = error refines fewer cells than Marking = cells at fraction 0.5",
      1 <= by_error < 0.6 * by_cells and by_cells >= 0.5 * n0 - 1,
      f"{n0} cells; refined: {by_error:g} (error), {by_cells:g} (cells)", True)
finish()
