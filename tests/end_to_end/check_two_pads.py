"""A disc between two pads (issue 23, section 5): two contact pairs, one on
each face of the disc, from a Gmsh mesh the check writes itself (disc 48 x 6
x 2 cells, r 50-120 mm, 10 mm thick, clamped at its hub; two 10 mm pads at
radius 100 mm, each held in-plane at its back and pressed by 100 N).
- preload (steady sliding, mu = 0.5): total normal force 2 x 100 N and
  friction 0.5 x that (1e-6); the two pads' contact pressures, tractions and
  gaps mirror each other about the disc's mid-plane (1e-6 of the peak);
- CEA (full solver, mu = 0.5): the same eigenvalues with the pairs listed
  in the other order (1e-10), disc modes named (n,m+-);
- 3 ms braking: both pads pressed (mean normal force 2 x 100 N after the
  ramp, 5 %); |F_T| <= mu F_N at every sample (1e-9) and F_T >= mu F_N
  cos(atan(5 / 95)) while every node slips after the ramp (the disc's
  velocity turns by that angle across a pad);
- its contact history names each node's pad face: squeal-tribology refuses
  it without Contact history/Face, naming both faces, and with an unknown
  face; each face alone gives its own damage.csv whose nodes mirror the
  other face's, with the same mean pressure per node (1e-6 of the peak).
Usage: check_two_pads.py SQUEAL WORK_DIR"""
import csv
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish, full_solver_point, run_squeal  # noqa: E402

squeal, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
os.chdir(work)


def write_mesh(path):
    """Gmsh 2.2: disc (sets 'disc', 'disc top', 'disc bottom', 'hub'), pads
    'top pad' / 'bottom pad' with faces 'top pad face' / 'top pad back',
    'bottom pad face' / 'bottom pad back'."""
    nodes, elements = [], []
    names = ["disc", "top pad", "bottom pad", "disc top", "disc bottom",
             "hub", "top pad face", "top pad back", "bottom pad face",
             "bottom pad back"]
    tag = {n: i + 1 for i, n in enumerate(names)}
    ns, nr, nz = 48, 6, 2
    idx = {}
    for k in range(nz + 1):
        for i in range(nr + 1):
            for j in range(ns):
                r = 0.05 + 0.07 * i / nr
                t = 2 * math.pi * j / ns
                idx[i, j, k] = len(nodes)
                nodes.append((r * math.cos(t), r * math.sin(t),
                              -0.01 + 0.01 * k / nz))
    for k in range(nz):
        for i in range(nr):
            for j in range(ns):
                jj = (j + 1) % ns
                b = [idx[i, j, k], idx[i + 1, j, k], idx[i + 1, jj, k],
                     idx[i, jj, k]]
                t = [idx[i, j, k + 1], idx[i + 1, j, k + 1],
                     idx[i + 1, jj, k + 1], idx[i, jj, k + 1]]
                elements.append((5, "disc", b + t))
                if k == nz - 1:
                    elements.append((3, "disc top", t))
                if k == 0:
                    elements.append((3, "disc bottom", b[::-1]))
                if i == 0:
                    elements.append((3, "hub", [b[0], b[3], t[3], t[0]]))
    for pad, z0, face, back in (("top pad", 0.0, "top pad face",
                                 "top pad back"),
                                ("bottom pad", -0.02, "bottom pad back",
                                 "bottom pad face")):
        n = 2
        pid = {}
        for k in range(n + 1):
            for j in range(n + 1):
                for i in range(n + 1):
                    pid[i, j, k] = len(nodes)
                    nodes.append((0.095 + 0.01 * i / n, -0.005 + 0.01 * j / n,
                                  z0 + 0.01 * k / n))
        for k in range(n):
            for j in range(n):
                for i in range(n):
                    b = [pid[i, j, k], pid[i + 1, j, k], pid[i + 1, j + 1, k],
                         pid[i, j + 1, k]]
                    t = [pid[i, j, k + 1], pid[i + 1, j, k + 1],
                         pid[i + 1, j + 1, k + 1], pid[i, j + 1, k + 1]]
                    elements.append((5, pad, b + t))
                    if k == 0:
                        elements.append((3, face, b[::-1]))
                    if k == n - 1:
                        elements.append((3, back, t))
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write(f"$PhysicalNames\n{len(names)}\n")
        for n in names:
            f.write(f'{3 if n in ("disc", "top pad", "bottom pad") else 2} '
                    f'{tag[n]} "{n}"\n')
        f.write(f"$EndPhysicalNames\n$Nodes\n{len(nodes)}\n")
        for i, x in enumerate(nodes):
            f.write(f"{i + 1} {x[0]:.17g} {x[1]:.17g} {x[2]:.17g}\n")
        f.write(f"$EndNodes\n$Elements\n{len(elements)}\n")
        for i, (kind, name, vs) in enumerate(elements):
            f.write(f"{i + 1} {kind} 2 {tag[name]} {tag[name]} " +
                    " ".join(str(v + 1) for v in vs) + "\n")
        f.write("$EndElements\n")


mesh = os.path.abspath("two_pads.msh")
write_mesh(mesh)
PAIRS = ["top: slave=top pad face, master=disc top",
         "bottom: slave=bottom pad face, master=disc bottom"]


def prm(analysis, pairs=PAIRS, extra=""):
    return f"""subsection Scene
  set Type = mesh file
  set Analysis = {analysis}
  subsection Mesh file
    set File = {mesh}
    set Bodies = disc: E=210e9, nu=0.3, rho=7800, type=disc, face=disc top, manifold=cylindrical; top pad: E=25e9, nu=0.3, rho=2500; bottom pad: E=25e9, nu=0.3, rho=2500
    set Contact pairs = {'; '.join(pairs)}
    set Holds = hub: set=hub; top back: set=top pad back, components=xy; bottom back: set=bottom pad back, components=xy
    set Loads = top: set=top pad back, direction=0 0 -1; bottom: set=bottom pad back, direction=0 0 1
  end
end
subsection Interface
  set Friction coefficient = 0.5
end
subsection Preload
  set Normal force = 100
end
{extra}"""


with open("base.prm", "w") as f:
    f.write("subsection Mesh\n  set Finite element degree = 1\nend\n")

# Preload.
out, log = run_squeal(squeal, "base.prm", "preload", prm("preload"))
line = [l for l in log.splitlines() if l.startswith("Preload converged")]
fn = float(line[0].split("normal force ")[1].split()[0]) if line else 0.
ft = float(line[0].split("friction force ")[1].split()[0]) if line else 0.
check("both pads pressed", abs(fn - 200.) < 2e-4 and abs(ft - 100.) < 1e-4,
      f"normal force {fn} N, friction force {ft} N", show=True)
with open(os.path.join(out, "contact.csv")) as f:
    rows = [r for r in csv.DictReader(f)]
top = {(round(float(r["x_m"]), 9), round(float(r["y_m"]), 9)): r
       for r in rows if float(r["z_m"]) > -0.005}
bottom = {(round(float(r["x_m"]), 9), round(float(r["y_m"]), 9)): r
          for r in rows if float(r["z_m"]) < -0.005}
peak = max(abs(float(r["p_N_Pa"])) for r in rows)
worst = 0.
for key, r in top.items():
    b = bottom.get(key)
    if b is None:
        worst = float("inf")
        break
    for c in ("p_N_Pa", "t_T1_Pa", "t_T2_Pa"):
        worst = max(worst, abs(float(r[c]) - float(b[c])) / peak)
check("the two pads mirror each other",
      len(top) == len(bottom) == 9 and peak > 0 and worst < 1e-6,
      f"{len(top)} + {len(bottom)} nodes, largest difference {worst:.1e} of "
      f"the peak pressure {peak:.3e} Pa", show=True)

# CEA, both pair orders.
cea = full_solver_point(0.5, 6000, names=("top pad.E", "top.mu"))
a, _ = run_squeal(squeal, "base.prm", "cea", prm("cea", extra=cea))
b, _ = run_squeal(squeal, "base.prm", "cea_swapped",
                  prm("cea", PAIRS[::-1], extra=cea))


def eigenvalues(d):
    with open(os.path.join(d, "eigenvalues.csv")) as f:
        return sorted((complex(float(r["re_per_s"]),
                               2 * math.pi * float(r["freq_Hz"]))
                       for r in csv.DictReader(f)), key=lambda z: z.imag)


la, lb = eigenvalues(a), eigenvalues(b)
worst = max((abs(x - y) / abs(x) for x, y in zip(la, lb)), default=1.)
check("pair order does not matter", len(la) == len(lb) and len(la) >= 5 and
      worst < 1e-10, f"{len(la)} eigenvalues, largest |dl|/|l| {worst:.1e}",
      show=True)
with open(os.path.join(a, "mode_participation.csv")) as f:
    names = [r["name"] for r in csv.DictReader(f)]
check("disc modes named", any(n.startswith("(0,") for n in names), names)

# Braking, 3 ms.
braking = """subsection Transient
  set End time = 3e-3
  set Ramp duration = 1e-3
  set Normal force = 100
  set Snapshot interval = 1e-3
  set Animation frames = 0
  set Checkpoint interval = 0
end
"""
out, _ = run_squeal(squeal, "base.prm", "braking", prm("braking",
                                                     extra=braking))
with open(os.path.join(out, "forces.csv")) as f:
    forces = [r for r in csv.DictReader(f)]
late = [float(r["normal_force_N"]) for r in forces
        if float(r["time_s"]) > 2e-3]
mean = sum(late) / max(len(late), 1)
check("braking: both pads pressed", late and abs(mean - 200.) < 10.,
      f"mean normal force after the ramp {mean:.2f} N", show=True)
excess = max(abs(float(r["tangential_force_N"])) -
             0.5 * float(r["normal_force_N"]) for r in forces)
check("braking: |F_T| <= mu F_N at every sample", excess <= 1e-9 * 200.,
      f"excess {excess:.1e} N", show=True)
slipping = [r for r in forces if int(r["n_stick"]) == 0 and
            float(r["time_s"]) > 1e-3]
# The disc's surface velocity turns by up to atan(5 / 95) across a pad, so
# the friction along the mean sliding direction is mu F_N times the
# pressure-weighted mean cosine: between cos(atan(5 / 95)) and 1.
low = math.cos(math.atan(5. / 95.))
err = max((max(0., low * 0.5 * float(r["normal_force_N"]) -
               float(r["tangential_force_N"])) for r in slipping),
          default=1e300)
check("braking: mu F_N cos(3 deg) <= F_T while every node slips",
      len(slipping) > 10 and err <= 1e-9 * 200.,
      f"{len(slipping)} samples, largest shortfall {err:.2e} N", show=True)

# Damage maps of each pad face from the contact history.
tribology = os.path.join(os.path.dirname(squeal), "squeal-tribology")
history = os.path.join(out, "contact_history.h5")


def run_tribology(face):
    name = "tribology_" + (face or "none")
    with open(name + ".prm", "w") as f:
        f.write(f"""subsection Contact history
  set File = {history}
  set Face = {face}
  set Start time = 1.5e-3
end
subsection Images
  set Files =
end
subsection Output
  set Directory = {name}
  set Overwrite = true
end
""")
    r = subprocess.run([tribology, name + ".prm"], capture_output=True,
                       text=True)
    return r, os.path.join(name, "damage.csv")


r, _ = run_tribology("")
check("tribology: a history of two faces needs Contact history/Face",
      r.returncode != 0 and "'top', 'bottom'" in r.stderr + r.stdout and
      "Contact history/Face" in r.stderr + r.stdout, r.stderr.strip(),
      show=True)
r, _ = run_tribology("left")
check("tribology: an unknown face is refused, naming the faces",
      r.returncode != 0 and "no pad face 'left'" in r.stderr + r.stdout,
      r.stderr.strip(), show=True)
faces = {}
for face in ("top", "bottom"):
    r, path = run_tribology(face)
    rows = []
    if r.returncode == 0:
        with open(path) as f:
            rows = list(csv.DictReader(f))
    faces[face] = rows
    check(f"tribology: face '{face}' alone", r.returncode == 0 and
          len(rows) == 9, f"{len(rows)} nodes; {r.stderr.strip()}", show=True)
top, bottom = faces["top"], faces["bottom"]
key = lambda r: (round(float(r["x_m"]), 7), round(float(r["y_m"]), 7))  # noqa
mirror = {key(r): float(r["mean_p_Pa"]) for r in bottom}
peak = max((float(r["mean_p_Pa"]) for r in top), default=0.)
worst = max((abs(float(r["mean_p_Pa"]) - mirror.get(key(r), math.inf))
             for r in top), default=math.inf)
zs = {round(float(r["z_m"]), 7) for r in top} & \
    {round(float(r["z_m"]), 7) for r in bottom}
check("tribology: the faces mirror each other (mean pressure per node)",
      len(top) == len(bottom) and peak > 0. and worst <= 1e-6 * peak and
      not zs, f"{len(top)} nodes each, peak {peak:.4g} Pa, largest "
      f"difference {worst:.2e} Pa", show=True)
finish()
