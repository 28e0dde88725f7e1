"""The scene from a mesh file against the built-in scene it was exported
from (issue 23): squeal --export-mesh writes the coarse TriboBrake with its
sets as an Abaqus .inp; a Scene/Type = mesh file run on it names the same
bodies, pair, holds, load and springs from those sets. Compared with the
built-in scene:
- CEA (full solver, degree 2): every eigenvalue |dl| / |l| <= 1e-10, the
  same mode names and kinetic-energy shares (1e-8); the built-in run's
  memory estimate within 2x of its measured peak;
- preload (degree 1): contact.csv pressures, tractions and gaps equal to
  2e-10 of each quantity's largest value (the file's 10 digits);
- 3 ms braking (degree 1): forces.csv equal to 1e-10 of each column's
  largest value;
and the scene-level checks of a mesh-file scene (--validate): a missing set
(the error lists the file's sets), cells in no body, a free-floating body
(named), a master set out of reach, a slave set that is not plane, an
unknown key, an analysis the scene cannot run, overlapping bodies;
--export-mesh refuses to overwrite.
Usage: check_scene_mesh_file.py SQUEAL BASE_PRM WORK_DIR"""
import csv
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish, memory_estimate_holds, run_squeal  # noqa: E402

squeal, base, work = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
os.makedirs(work, exist_ok=True)
os.chdir(work)
inp = os.path.abspath("tribobrake.inp")
if os.path.exists(inp):
    os.remove(inp)

r = subprocess.run([squeal, "--export-mesh", inp, base], capture_output=True,
                   text=True)
check("export", r.returncode == 0 and os.path.exists(inp), r.stdout + r.stderr)
r = subprocess.run([squeal, "--export-mesh", inp, base], capture_output=True,
                   text=True)
check("export refuses to overwrite", r.returncode != 0 and "exists" in r.stderr,
      r.stderr)

SCENE = {
    "Bodies": "disc: set=DISC, E=210e9, nu=0.3, rho=7800, type=disc, "
              "face=DISC_FACE, manifold=cylindrical; "
              "pad: set=PAD, E=25e9, nu=0.3, rho=2500; "
              "support: set=SUPPORT, E=210e9, nu=0.3, rho=76500",
    "Contact pairs": "pad on disc: slave=PAD_FACE, master=DISC_FACE",
    "Holds": "disc hub: set=DISC_HUB",
    "Point holds": "loading arm: point=0.1 0 0.11, component=x",
    "Loads": "support top: set=SUPPORT_TOP, direction=0 0 -1",
    "Springs": "support springs: body=support, direction=0 1 0, "
               "nodes=SUPPORT_SPRINGS",
}


def scene_text(analysis, **changes):
    entries = dict(SCENE, **changes)
    lines = "".join(f"    set {k} = {v}\n" for k, v in entries.items())
    return (f"subsection Scene\n  set Type = mesh file\n"
            f"  set Analysis = {analysis}\n  subsection Mesh file\n"
            f"    set File = {inp}\n{lines}  end\nend\n")


def rows(path):
    with open(path) as f:
        return [r for r in csv.reader(f) if r and not r[0].startswith("#")]


def columns_equal(name, a_path, b_path, relative, skip=(), groups=()):
    """Every numeric column of two CSVs equal to RELATIVE of its largest
    value (of the largest value in its group: columns of one quantity,
    such as the traction components)."""
    a, b = rows(a_path), rows(b_path)
    ok = len(a) == len(b) and len(a) > 2 and a[0] == b[0]
    worst = 0.
    if ok:
        for c, col in enumerate(a[0]):
            if col in skip:
                continue
            try:
                va = [float(r[c]) for r in a[1:]]
                vb = [float(r[c]) for r in b[1:]]
            except ValueError:
                ok = ok and [r[c] for r in a] == [r[c] for r in b]
                continue
            group = next((g for g in groups if col in g), (col,))
            scale = max(max(abs(float(r[a[0].index(g)])) for r in a[1:])
                        for g in group)
            scale = max(scale, 1e-300)
            d = max(abs(x - y) for x, y in zip(va, vb)) / scale
            worst = max(worst, d)
    check(name, ok and worst <= relative,
          f"{len(a)} rows, largest difference {worst:.2e} of the column's "
          f"largest value (allowed {relative:g})", show=True)


# CEA, full solver.
builtin, log = run_squeal(squeal, base, "cea_builtin")
ok, said = memory_estimate_holds(log)
check("CEA: the memory estimate within 2x of the peak", ok, said, show=True)
meshed, _ = run_squeal(squeal, base, "cea_mesh_file", scene_text("cea"))
ea, eb = rows(f"{builtin}/eigenvalues.csv"), rows(f"{meshed}/eigenvalues.csv")
h = ea[0]
lam = lambda r: complex(float(r[h.index("re_per_s")]),  # noqa: E731
                        2 * 3.141592653589793 * float(r[h.index("freq_Hz")]))
la = sorted((lam(r) for r in ea[1:]), key=lambda z: z.imag)
lb = sorted((lam(r) for r in eb[1:]), key=lambda z: z.imag)
worst = max((abs(x - y) / abs(x) for x, y in zip(la, lb)), default=1.)
check("CEA eigenvalues equal", len(la) == len(lb) and len(la) >= 10 and
      worst <= 1e-10, f"{len(la)} eigenvalues, largest |dl|/|l| {worst:.2e}",
      show=True)
pa = rows(f"{builtin}/mode_participation.csv")
pb = rows(f"{meshed}/mode_participation.csv")
check("mode names equal", len(pa) == len(pb) and len(pa) > 2 and
      [r[-1] for r in pa] == [r[-1] for r in pb] and pa[0] == pb[0],
      f"{[r[-1] for r in pa[1:6]]} / {[r[-1] for r in pb[1:6]]}")
columns_equal("kinetic-energy shares equal", f"{builtin}/mode_participation.csv",
              f"{meshed}/mode_participation.csv", 1e-8,
              skip=("point", "mode", "freq_Hz", "re_per_s"))

# Preload, degree 1.
degree1 = "subsection Mesh\n  set Finite element degree = 1\nend\n"
builtin, _ = run_squeal(squeal, base, "preload_builtin",
                        "subsection Scene\n  set Analysis = preload\nend\n" +
                        degree1)
meshed, _ = run_squeal(squeal, base, "preload_mesh_file",
                       scene_text("preload") + degree1)
columns_equal("preload contact equal", f"{builtin}/contact.csv",
              f"{meshed}/contact.csv", 2e-10,
              groups=(("p_N_Pa", "t_T1_Pa", "t_T2_Pa"),))

# Braking, degree 1, 3 ms.
builtin, _ = run_squeal(squeal, base, "braking_builtin",
                        "subsection Scene\n  set Analysis = braking\nend\n" +
                        degree1)
meshed, _ = run_squeal(squeal, base, "braking_mesh_file",
                       scene_text("braking") + degree1)
columns_equal("braking forces equal", f"{builtin}/forces.csv",
              f"{meshed}/forces.csv", 1e-10)


# Bad scenes: one clear error each, from --validate.
def refused(name, expected, analysis="cea", **changes):
    with open(name + ".prm", "w") as f:
        f.write(f"include {base}\n" + scene_text(analysis, **changes))
    r = subprocess.run([squeal, "--validate", name + ".prm"],
                       capture_output=True, text=True)
    message = r.stderr.strip()
    check(name, r.returncode != 0 and all(e in message for e in expected) and
          message.count("\n") == 0, message or r.stdout)


refused("missing set", ["Bodies, item 'disc'", "no cell set 'DISCS'",
                        "'DISC'", "'PAD'"],
        Bodies=SCENE["Bodies"].replace("set=DISC,", "set=DISCS,"))
refused("cells in no body", ["cells of mesh file", "belong to no body"],
        Bodies=SCENE["Bodies"].rsplit(";", 1)[0])
refused("free-floating body", ["nothing holds body 'pad', 'support'",
                               "free-floating"],
        **{"Contact pairs": "", "Springs": "", "Point holds": ""})
refused("master out of reach", ["Contact pairs, item 'pad on disc'",
                                "SUPPORT_TOP", "out of reach"],
        **{"Contact pairs": "pad on disc: slave=PAD_FACE, master=SUPPORT_TOP"})
refused("slave not plane", ["'DISC_HUB' is not plane"],
        **{"Contact pairs": "pad on disc: slave=DISC_HUB, master=PAD_FACE"})
refused("unknown key", ["item 'disc'", "young=1", "set, E, nu, rho"],
        Bodies=SCENE["Bodies"].replace("E=210e9, nu", "young=1, E=210e9, nu", 1))
refused("analysis needs a load", ["Scene/Analysis = preload", "a load"],
        analysis="preload", Loads="")

# Overlapping bodies: two unit cubes, the second shifted by half its edge.
with open("overlap.inp", "w") as f:
    f.write("*NODE\n")
    n = 0
    for shift in (0., 0.5):
        for z in (0., 1.):
            for y in (0., 1.):
                for x in (0., 1.):
                    n += 1
                    f.write(f"{n}, {x + shift}, {y}, {z}\n")
    f.write("*ELEMENT, TYPE=C3D8, ELSET=A\n1, 1, 2, 4, 3, 5, 6, 8, 7\n")
    f.write("*ELEMENT, TYPE=C3D8, ELSET=B\n2, 9, 10, 12, 11, 13, 14, 16, 15\n")
with open("overlap.prm", "w") as f:
    f.write(f"""subsection Scene
  set Type = mesh file
  subsection Mesh file
    set File = {os.path.abspath("overlap.inp")}
    set Bodies = a: set=A, E=1e9, nu=0.3, rho=1000; b: set=B, E=1e9, nu=0.3, rho=1000
  end
end
""")
r = subprocess.run([squeal, "--validate", "overlap.prm"], capture_output=True,
                   text=True)
check("overlapping bodies", r.returncode != 0 and
      ("bodies 'b' and 'a' overlap" in r.stderr or
       "bodies 'a' and 'b' overlap" in r.stderr), r.stderr or r.stdout)
finish()
