#!/usr/bin/python3
"""End-to-end check of the CEA about the preload (Scene/Analysis = preloaded cea).

usage: check_preloaded_cea.py SQUEAL PRM WORKDIR

On the coarse TriboBrake at one point (E_pad = 25 GPa, mu = 0.5, full
solver):
- with a frictionless preload every pad node stays in contact, so the
  interface is the whole pad face and the eigenvalues equal those of the
  plain CEA (an independent run) to 1e-8 relative;
- with the steady-sliding preload the trailing part of the pad lifts off:
  the preload's contact.csv has separated nodes, the run says how many
  interface points remain, and the eigenvalues change (the interface
  stiffness has gone where the pad separated);
- under `mpirun -np 2` the sliding case gives the serial eigenvalues
  (1e-8 of |lambda|);
- out of core (Linear solver/Out-of-core factorisation), the sliding case
  gives the in-core eigenvalues (1e-10 of |lambda|), MUMPS's factor files
  appear in the Out-of-core directory while it runs (listed every 2 ms)
  and none is left, and the memory estimate says the factors are out of
  core.
"""
import csv
import os
import shutil
import sys

from checks import run_table_point

squeal, prm, work = sys.argv[1:4]
prm = os.path.abspath(prm)
os.makedirs(work, exist_ok=True)
os.chdir(work)


def fail(msg):
    print("FAILED:", msg)
    sys.exit(1)


def run(name, analysis, friction, mpi=0):
    out, r = run_table_point(squeal, prm, name, f"""subsection Scene
  set Analysis = {analysis}
end
subsection Preload
  set Friction = {friction}
end
""", mpi)
    if r.returncode != 0:
        fail(f"{name}: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
    return out, r.stdout, eigenvalues(out)


def eigenvalues(out):
    """(Re lambda [1/s], f [Hz]) of every row of OUT/eigenvalues.csv."""
    with open(os.path.join(out, "eigenvalues.csv"), newline="") as f:
        return [(float(r["re_per_s"]), float(r["freq_Hz"]))
                for r in csv.DictReader(f)]


def largest_distance(lam, ref):
    """Largest |lambda - lambda_ref| / |lambda_ref| over paired rows."""
    return max(max(abs(a[0] - b[0]), abs(a[1] - b[1]) * 6.283185307) /
               abs(complex(b[0], 6.283185307 * b[1])) for a, b in zip(lam, ref))


def same_eigenvalues(what, lam, ref, tolerance):
    """Fails unless LAM has REF's rows, each within TOLERANCE of |lambda|;
    returns the largest distance."""
    if len(lam) != len(ref):
        fail(f"{what}: {len(lam)} eigenvalues against {len(ref)}")
    worst = largest_distance(lam, ref)
    if worst > tolerance:
        fail(f"{what} changes the eigenvalues by {worst:.2e}")
    return worst


_, _, plain = run("plain", "cea", "frictionless")
out0, log0, full = run("frictionless", "preloaded cea", "frictionless")
with open(os.path.join(out0, "preload", "contact.csv"), newline="") as f:
    if any(int(r["status"]) == 0 for r in csv.DictReader(f)):
        fail("the frictionless preload separated a pad node")
worst = same_eigenvalues("full-contact preload", full, plain, 1e-8)
print(f"frictionless preload, full contact: eigenvalues as the plain CEA "
      f"({worst:.1e}): ok")

out1, log1, lifted = run("sliding", "preloaded cea", "steady sliding")
with open(os.path.join(out1, "preload", "contact.csv"), newline="") as f:
    separated = sum(int(r["status"]) == 0 for r in csv.DictReader(f))
if separated == 0:
    fail("the sliding preload kept every pad node in contact")
if "quadrature points with contact" not in log1:
    fail("the run does not report the interface left after the preload")
change = max(abs(a[1] - b[1]) / b[1] for a, b in zip(lifted, plain)) \
    if len(lifted) == len(plain) else 1.
if change < 1e-4:
    fail("separation did not change the eigenvalues")
print(f"sliding preload: {separated} pad nodes separated, eigenvalues moved "
      f"(largest frequency change {100 * change:.2f} %): ok")
_, _, lifted2 = run("sliding_np2", "preloaded cea", "steady sliding", mpi=2)
worst = same_eigenvalues("mpirun -np 2", lifted2, lifted, 1e-8)
print(f"mpirun -np 2: the serial eigenvalues ({worst:.1e}): ok")

# Out of core: MUMPS's factors (the preload's LU, the full solver's LDL^T
# and block Lanczos's Cholesky) written to files in Linear solver/Out-of-core
# directory, which the run lists while it runs, and the in-core eigenvalues.
ooc = os.path.abspath("factors")
shutil.rmtree(ooc, ignore_errors=True)
os.makedirs(ooc)
out3, r3, seen = run_table_point(squeal, prm, "sliding_ooc", f"""subsection Scene
  set Analysis = preloaded cea
end
subsection Preload
  set Friction = steady sliding
end
subsection Linear solver
  set Out-of-core factorisation = out of core
  set Out-of-core directory = {ooc}
end
""", watch=ooc)
if r3.returncode != 0:
    fail(f"out of core: exit {r3.returncode}\n{r3.stdout}\n{r3.stderr}")
if "MUMPS's factors out of core" not in r3.stdout:
    fail("out of core: the memory estimate does not say so")
# Symmetric eigensolver = auto: block Lanczos (one pass through the factor
# files per block of vectors)
if "; block for the symmetric modes" not in r3.stdout:
    fail("out of core: the full solver did not take block Lanczos for the "
         "symmetric modes (Symmetric eigensolver = auto)")
factor_files = sorted(f for f in seen if f.startswith("mumps_"))
if not factor_files:
    fail(f"out of core: no MUMPS factor file appeared in {ooc} ({sorted(seen)})")
if os.listdir(ooc):
    fail(f"out of core: files left in {ooc}: {os.listdir(ooc)}")
worst = same_eigenvalues("out of core", eigenvalues(out3), lifted, 1e-10)
print(f"out of core: {len(factor_files)} MUMPS factor files seen while it ran, "
      f"none left; the in-core eigenvalues ({worst:.1e}): ok")
print("all checks passed")
