"""The generated passenger-car brake (scripts/make_brake.py, issue 24) at its
coarse size and degree 1:
- the script writes the mesh and scene; squeal validates them (six bodies,
  two contact pairs, every body held);
- preload (steady sliding, mu = 0.3): the hydraulic force pair F on the
  piston and the caliper bore presses both pads, the outer one through the
  fist caliper, so the total normal force is 2 F (the axial springs of the
  ears and guide pins, 1e5 N/m, carry less than 1e-3 of it) and the
  friction force mu times it (1e-6: every node slips);
- CEA (full solver, 500-6000 Hz): the linked parameter contact.mu sweeps
  both pairs' friction coefficients together: its eigenvalues at 0.5 equal
  those of a run with both pairs set to 0.5 by Interface/Friction
  coefficient (1e-10); at contact.mu = 0 every eigenvalue decays, at the
  rate of Rayleigh damping within its bounds alpha / 2 <= -Re lambda <=
  (alpha + beta omega^2) / 2 (1 %: the interface and springs are not
  damped); disc modes are named (n,m+-);
- braking (0.15 ms, contact.mu = 0.5): the matrix-free stiffness product,
  with the transversely isotropic friction material and the springs that
  join two bodies, equals the assembled matrix on a vector (1e-12, checked
  at set-up) and over the run: its contact forces equal the sparse run's
  (1e-9 of the peak), and under mpirun -np 2 (1e-8), where the two pads'
  contact problems are solved on different ranks.
Usage: check_brake.py SQUEAL WORK_DIR"""
import csv
import math
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from checks import (check, check_brake_force_loop,  # noqa: E402
                    finish, make_brake, run_squeal)

squeal, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
os.chdir(work)

make_brake()
force = 2e6 * math.pi * 0.054 ** 2 / 4   # the script's piston force [N]

with open("base.prm", "w") as f:
    f.write("""INCLUDE brake/brake_scene.prm
subsection Mesh
  set Finite element degree = 1
end
subsection Interface
  set Normal stiffness = 1e13
end
subsection Damping
  set Alpha = 0.02
  set Beta = 1e-7
end
""")

# --validate: the scene against its mesh
with open("validate.prm", "w") as f:
    f.write("include base.prm\nsubsection Scene\n  set Analysis = preload\n"
            "end\n")
r = subprocess.run([squeal, "--validate", "validate.prm"],
                   capture_output=True, text=True)
bodies = ["disc", "friction material", "backplates", "piston", "caliper",
          "bracket"]
check("the scene validates", r.returncode == 0 and
      all(f"{b}.E" in r.stdout for b in bodies) and "contact.mu" in
      r.stdout, (r.stdout + r.stderr)[-2000:])

# Preload: the force loop through the caliper.
out, log = run_squeal(squeal, "base.prm", "preload", """subsection Scene
  set Analysis = preload
end
subsection Interface
  set Friction coefficient = 0.3
end
subsection Preload
  set Friction = steady sliding
end
""")
check_brake_force_loop(out, force, 0.3,
                       "both pads pressed by the caliper's force loop")


def cea(name, first, values, mu=None, shapes="none"):
    interface = (f"subsection Interface\n  set Friction coefficient = {mu}\n"
                 "end\n") if mu is not None else ""
    folder, _ = run_squeal(squeal, "base.prm", name, f"""subsection Scene
  set Analysis = cea
end
{interface}subsection Eigensolver
  set Method = full
  set Minimum frequency = 500
  set Maximum frequency = 6000
end
subsection Sweep
  set First parameter = {first}
  set First values = {values}
  set Second parameter = friction material.E
  set Second values = 8e9
end
subsection Output
  set Mode shapes = {shapes}
end
""")
    with open(os.path.join(folder, "eigenvalues.csv")) as f:
        rows = list(csv.DictReader(f))
    by_point = {}
    for row in rows:
        by_point.setdefault(int(row["point"]), []).append(
            complex(float(row["re_per_s"]),
                    2 * math.pi * float(row["freq_Hz"])))
    return folder, {p: sorted(v, key=lambda z: z.imag)
                    for p, v in by_point.items()}


linked_dir, linked = cea("cea_linked", "contact.mu", "0, 0.5", shapes="all")
_, single = cea("cea_pairs", "damping.alpha", "0.02", mu=0.5)
a, b = linked.get(1, []), single.get(0, [])
worst = max((abs(x - y) / abs(x) for x, y in zip(a, b)), default=1.)
check("contact.mu moves both pairs", len(a) == len(b) >= 10 and
      worst < 1e-10, f"{len(a)} and {len(b)} eigenvalues at mu = 0.5, "
      f"largest |dl|/|l| {worst:.1e}", show=True)
alpha, beta = 0.02, 1e-7   # base.prm's Damping
free = linked.get(0, [])
bad = [z for z in free if not (0.99 * alpha / 2 <= -z.real <=
                               1.01 * (alpha + beta * z.imag ** 2) / 2)]
check("at contact.mu = 0 every mode decays within the Rayleigh bounds",
      len(free) >= 10 and not bad, f"{len(free)} modes, outside: {bad[:3]}",
      show=True)
with open(os.path.join(linked_dir, "mode_participation.csv")) as f:
    names = {row["name"] for row in csv.DictReader(f)}
check("disc modes named (0,m) and (1,m)",
      all(any(n.startswith(p) for n in names) for p in ("(0,2", "(0,3",
                                                        "(1,")),
      sorted(names)[:12])

# Braking: matrix-free (anisotropic body, springs between bodies) against
# the assembled matrix, serial and on two ranks.
def braking(name, product, mpi=0):
    out, log = run_squeal(squeal, "base.prm", name, f"""subsection Scene
  set Analysis = braking
end
subsection Interface
  set Friction coefficient = 0.5
end
subsection Transient
  set Ramp duration = 5e-5
  set End time = 1.5e-4
  set Sampling rate = 1e6
  set Snapshot interval = 0
  set Animation frames = 0
  set Checkpoint interval = 0
  set Stiffness product = {product}
end
""", mpi=mpi)
    with open(os.path.join(out, "forces.csv")) as f:
        rows = list(csv.DictReader(f))
    return log, [(float(r["normal_force_N"]), float(r["tangential_force_N"]))
                 for r in rows]


log_free, free_forces = braking("braking_matrix_free", "matrix-free")
line = [l for l in log_free.splitlines() if "relative difference" in l]
diff = float(line[0].split("relative difference ")[1].split(")")[0]) \
    if line else 1.
check("braking: matrix-free product = assembled matrix (anisotropic, "
      "springs between bodies)", diff < 1e-12, line, show=True)
_, sparse_forces = braking("braking_sparse", "sparse")
log_np2, mpi_forces = braking("braking_np2", "matrix-free", mpi=2)
check("braking on two ranks: the two pads' contact groups split among them",
      "in 2 independent groups, split among the ranks" in log_np2,
      [l for l in log_np2.splitlines() if l.startswith("Braking:")])
peak = max((abs(n) for n, _ in sparse_forces), default=0.)
for label, forces, tol in (("matrix-free", free_forces, 1e-9),
                           ("np = 2", mpi_forces, 1e-8)):
    worst = max((max(abs(a[0] - b[0]), abs(a[1] - b[1]))
                 for a, b in zip(forces, sparse_forces)), default=1e300)
    check(f"braking: {label} forces = sparse run's",
          len(forces) == len(sparse_forces) > 100 and peak > 0.1 * force and
          worst <= tol * peak, f"{len(forces)} samples, peak {peak:.1f} N, "
          f"largest difference {worst:.2e} N", show=True)
finish()
