"""Output/Export matrices through the command line: a CEA of the two-block
scene (prm/two_blocks.msh, degree 1, 369 DoFs, Rayleigh damping, friction
on) writes the matrices of its second sweep point, and an independent dense
solve of them reproduces the run's eigenvalues. Checks:
- matrices/ holds point_1_M, _C, _K.mtx, every part, parts.csv, dofs.csv
  and point_1.csv, whose friction coefficient is the sweep's second value;
- M, C and K are the parts summed with parts.csv's coefficients of the
  point (to 1e-12 of each matrix's largest entry);
- numpy's dense eigensolve of the scaled companion form of
  (lambda^2 M + lambda C + K) phi = 0 on the unconstrained DoFs finds as many
  eigenvalues in the band (1-60 kHz, Im lambda > 0) as eigenvalues.csv has
  at the point, each within 1e-8 relative in frequency and 1e-6 |lambda| in
  the real part (the issue 25 tolerances of the dense comparison).
Usage: check_matrix_export.py SQUEAL WORK_DIR"""
import csv
import os
import sys

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from checks import check, finish, run_squeal  # noqa: E402

squeal, work = sys.argv[1], sys.argv[2]
root = os.path.abspath(os.path.join(here, "..", ".."))
os.makedirs(work, exist_ok=True)
os.chdir(work)
with open("base.prm", "w") as f:
    f.write(f"""include {root}/prm/two_blocks_cea.prm
subsection Scene
  subsection Mesh file
    set File = {root}/prm/two_blocks.msh
  end
end
subsection Mesh
  set Finite element degree = 1
end
subsection Eigensolver
  set Method = full
end
subsection Sweep
  set First values = 0.3, 0.6
end
""")
run, _ = run_squeal(squeal, "base.prm", "run",
                    "subsection Output\n  set Export matrices = 1\nend\n")
folder = os.path.join(run, "matrices")


def read_mtx(name):
    """The dense matrix of a MatrixMarket coordinate file in FOLDER."""
    with open(os.path.join(folder, name)) as f:
        header = f.readline().split()
        line = f.readline()
        while line.startswith("%"):
            line = f.readline()
        n, m, _ = (int(v) for v in line.split())
        A = np.zeros((n, m))
        for line in f:
            i, j, v = line.split()
            A[int(i) - 1, int(j) - 1] += float(v)
            if header[-1] == "symmetric" and i != j:
                A[int(j) - 1, int(i) - 1] += float(v)
    return A


expected = ["dofs.csv", "parts.csv", "point_1.csv", "point_1_M.mtx",
            "point_1_C.mtx", "point_1_K.mtx", "part_0.mtx"]
missing = [f for f in expected
           if not os.path.exists(os.path.join(folder, f))]
check("matrices/ holds the point's files", not missing, missing)
if missing:
    finish()

with open(os.path.join(folder, "point_1.csv")) as f:
    values = {r["parameter"]: float(r["value"]) for r in csv.DictReader(f)}
check("point_1.csv: the sweep's second friction coefficient",
      abs(values.get("block on base.mu", -1.) - 0.6) < 1e-12, values)

M, C, K = (read_mtx(f"point_1_{x}.mtx") for x in "MCK")
with open(os.path.join(folder, "parts.csv")) as f:
    parts = list(csv.DictReader(f))
check("parts.csv lists the parts", len(parts) >= 3, len(parts))
for name, A in (("mass", M), ("damping", C), ("stiffness", K)):
    total = sum(float(p[f"point_1_{name}"]) * read_mtx(f"part_{p['part']}.mtx")
                for p in parts)
    error = np.abs(total - A).max() / np.abs(A).max()
    check(f"{name}: the parts summed with the point's coefficients",
          error <= 1e-12, error, show=True)

with open(os.path.join(folder, "dofs.csv")) as f:
    free = [int(r["dof"]) for r in csv.DictReader(f)
            if r["constrained"] == "0"]
check("dofs.csv: free DoFs", 0 < len(free) < M.shape[0], len(free))
ix = np.ix_(free, free)
M, C, K = M[ix], C[ix], K[ix]
# mu = lambda / s: (s^2 mu^2 M + s mu C + K) phi = 0, companion form with
# M^-1 (M is symmetric positive definite on the free DoFs)
s = 2. * np.pi * 1e4
Minv = np.linalg.inv(M)
n = len(free)
A = np.block([[np.zeros((n, n)), np.eye(n)],
              [-Minv @ K / s**2, -Minv @ C / s]])
lam = s * np.linalg.eigvals(A)
f_min, f_max = 1000., 60000.
dense = sorted((l for l in lam
                if f_min <= l.imag / (2. * np.pi) <= f_max),
               key=lambda l: l.imag)

with open(os.path.join(run, "eigenvalues.csv")) as f:
    rows = [r for r in csv.DictReader(f) if r["point"] == "1"]
squeal_l = sorted((float(r["re_per_s"]) + 2j * np.pi * float(r["freq_Hz"])
                   for r in rows), key=lambda l: l.imag)
check("same number of eigenvalues in the band", len(dense) == len(squeal_l)
      and len(dense) > 0, f"dense {len(dense)}, squeal {len(squeal_l)}",
      show=True)
if len(dense) == len(squeal_l) and dense:
    df = max(abs(a.imag - b.imag) / abs(a.imag)
             for a, b in zip(dense, squeal_l))
    dr = max(abs(a.real - b.real) / abs(a) for a, b in zip(dense, squeal_l))
    check("frequencies within 1e-8 relative", df <= 1e-8, df, show=True)
    check("real parts within 1e-6 |lambda|", dr <= 1e-6, dr, show=True)
finish()
