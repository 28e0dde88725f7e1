"""The friction-coupled CEA of a block sliding on a base, stated in squeal and
in CalculiX 2.20 on the same hexahedral mesh (run_two_blocks.py and the test
end_to_end/calculix_two_blocks use it).

The scene (mm, N, t, s in CalculiX; SI in squeal):
- a steel base 70 x 20 x 10 mm (E 210 GPa, nu 0.3, 7800 kg/m^3) held at its
  bottom face, and a friction block 10 x 10 x 10 mm (E 10 GPa, nu 0.25,
  2500 kg/m^3) on it, held in x and y at its top face and pressed down by a
  uniform traction there; the meshes do not match on the contact face;
- penalty contact of the block's bottom (slave) on the base's top (master),
  k_n = 1e13 N/m^3 (1e4 N/mm^3), Coulomb friction mu, the base sliding along
  +x under the block.

squeal: `Scene/Analysis = preloaded cea` at degree 1 (trilinear hexahedra),
steady sliding (the friction force mu p along +x, thesis eq. 3-1), no
damping, the full solver.

CalculiX: C3D8 (the same trilinear space, 2 x 2 x 2 Gauss points: the same
element matrices), `*CONTACT PAIR, TYPE=SURFACE TO SURFACE` with
`PRESSURE-OVERCLOSURE=LINEAR` at the same k_n and `*FRICTION` mu with the
stick slope LAMBDA; a `*STATIC` step that applies the traction and moves the
base's bottom by SLIDE along x (the pads then slip: SLIDE >> mu p / LAMBDA),
then `*STEP, PERTURBATION` with `*FREQUENCY`, whose stiffness is the
contact's unsymmetric tangent at the end of the static step (complex
frequencies where friction couples modes). CalculiX moves the base; squeal
linearises about the base already moved by SLIDE (its mesh is written
shifted), so both see the same geometry under the block.
"""
import os
import subprocess

# the brick's faces S1-S6 by their corners (Abaqus/CalculiX numbering)
FACES = {1: (0, 1, 2, 3), 2: (4, 7, 6, 5), 3: (0, 4, 5, 1), 4: (1, 5, 6, 2),
         5: (2, 6, 7, 3), 6: (3, 7, 4, 0)}
BASE = dict(E=210e9, nu=0.3, rho=7800)
BLOCK = dict(E=10e9, nu=0.25, rho=2500)
K_N = 1e13          # N/m^3
BLOCK_AREA = 1e-4   # m^2, the block's top and bottom


def box(x0, x1, y0, y1, z0, z1, nx, ny, nz):
    """Nodes (x, y, z), hexahedra (8 node indices: bottom counter-clockwise,
    then top) and the bottom and top quadrilaterals of an nx x ny x nz box
    (outward normals)."""
    nodes, index = [], {}
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                index[i, j, k] = len(nodes)
                nodes.append((x0 + (x1 - x0) * i / nx,
                              y0 + (y1 - y0) * j / ny,
                              z0 + (z1 - z0) * k / nz))
    square = ((0, 0), (1, 0), (1, 1), (0, 1))
    hexes = [[index[i + a, j + b, k + c] for c in (0, 1) for a, b in square]
             for k in range(nz) for j in range(ny) for i in range(nx)]
    faces = {
        "bottom": [[index[i + a, j + b, 0] for b, a in square]
                   for j in range(ny) for i in range(nx)],
        "top": [[index[i + a, j + b, nz] for a, b in square]
                for j in range(ny) for i in range(nx)]}
    return nodes, hexes, faces


def parts(shift=0.0, base_cells=(28, 8, 4), block_cells=(5, 5, 4)):
    """[(name, box)]: the base moved by SHIFT [mm] along x, and the block."""
    return [("base", box(-30 + shift, 40 + shift, 0, 20, -10, 0,
                         *base_cells)),
            ("block", box(5, 15, 5, 15, 0, 10, *block_cells))]


GROUPS = [(3, 1, "base"), (3, 2, "block"), (2, 3, "base top"),
          (2, 4, "base bottom"), (2, 5, "block bottom"), (2, 6, "block top")]


def write_msh(path, bodies):
    """Writes BODIES (parts()) as a Gmsh 2.2 ASCII mesh in mm."""
    tag = {name: t for _, t, name in GROUPS}
    nodes, elements = [], []
    for name, (points, hexes, faces) in bodies:
        offset = len(nodes)
        nodes += points
        elements += [(5, tag[name], [offset + v for v in h]) for h in hexes]
        for side, quads in faces.items():
            elements += [(3, tag[f"{name} {side}"], [offset + v for v in q])
                         for q in quads]
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write(f"$PhysicalNames\n{len(GROUPS)}\n")
        for dim, t, name in GROUPS:
            f.write(f'{dim} {t} "{name}"\n')
        f.write(f"$EndPhysicalNames\n$Nodes\n{len(nodes)}\n")
        for i, (x, y, z) in enumerate(nodes):
            f.write(f"{i + 1} {x:.17g} {y:.17g} {z:.17g}\n")
        f.write(f"$EndNodes\n$Elements\n{len(elements)}\n")
        for i, (kind, t, vs) in enumerate(elements):
            f.write(f"{i + 1} {kind} 2 {t} {t} " +
                    " ".join(str(v + 1) for v in vs) + "\n")
        f.write("$EndElements\n")


def squeal_prm(msh, out, mu, force, f_max=120e3):
    """squeal's parameter file: preloaded CEA of the mesh MSH (base already
    moved) at friction coefficient MU under FORCE [N], results into OUT."""
    def body(name, m):
        return f"{name}: E={m['E']:g}, nu={m['nu']:g}, rho={m['rho']:g}"
    return f"""subsection Scene
  set Type = mesh file
  set Analysis = preloaded cea
  subsection Mesh file
    set File = {msh}
    set Length unit = 1e-3
    set Bodies = {body('base', BASE)}; {body('block', BLOCK)}
    set Contact pairs = block on base: slave=block bottom, master=base top, \\
                                       sliding=1 0 0
    set Holds = base bottom: set=base bottom; \\
                block top: set=block top, components=xy
    set Loads = press: set=block top, direction=0 0 -1
  end
end
subsection Mesh
  set Finite element degree = 1
end
subsection Interface
  set Normal stiffness = {K_N:g}
  set Friction coefficient = {mu:g}
end
subsection Preload
  set Normal force = {force:g}
  set Friction = steady sliding
end
subsection Damping
  set Alpha = 0
  set Beta = 0
end
subsection Eigensolver
  set Method = full
  set Minimum frequency = 1000
  set Maximum frequency = {f_max:g}
end
subsection Sweep
  set First parameter  = block on base.mu
  set First values     = {mu:g}
  set Second parameter = block.E
  set Second values    = {BLOCK['E']:g}
end
subsection Output
  set Directory = {out}
  set Overwrite = true
  set Mode shapes = none
end
"""


def calculix_deck(mu, force, slide, stick_slope, modes=40, bodies=None,
                  increment=None):
    """CalculiX's deck: static preload with friction (the base moved by SLIDE
    [mm], the traction FORCE [N] on the block's top), then the perturbed,
    unsymmetric *FREQUENCY (MODES eigenvalues). STICK_SLOPE in N/mm^3. The
    static step's increments: CalculiX's automatic ones from 0.1 of the step,
    or fixed ones of INCREMENT."""
    bodies = bodies or parts()
    lines, nodes, elements, surfaces = ["*NODE"], [], {}, {}
    element = 0
    for name, (points, hexes, faces) in bodies:
        offset = len(nodes)
        nodes += points
        face_of = {}
        for h in hexes:
            element += 1
            elements.setdefault(name, []).append(
                (element, [offset + v for v in h]))
            for number, corners in FACES.items():
                face_of[frozenset(offset + h[i] for i in corners)] = \
                    (element, number)
        for side, quads in faces.items():
            surfaces[f"{name} {side}"] = [
                face_of[frozenset(offset + v for v in q)] for q in quads]
            surfaces[f"{name} {side} nodes"] = sorted(
                {offset + v for q in quads for v in q})
    lines += [f"{i + 1}, {x:.12g}, {y:.12g}, {z:.12g}"
              for i, (x, y, z) in enumerate(nodes)]
    for name, els in elements.items():
        lines.append(f"*ELEMENT, TYPE=C3D8, ELSET={name.upper()}")
        lines += [f"{e}, " + ", ".join(str(n + 1) for n in ns)
                  for e, ns in els]
    for s in ("base top", "block bottom"):
        lines.append(f"*SURFACE, NAME={s.upper().replace(' ', '_')}, "
                     "TYPE=ELEMENT")
        lines += [f"{e}, S{n}" for e, n in surfaces[s]]
    for s in ("base bottom", "block top"):
        lines.append(f"*NSET, NSET={s.upper().replace(' ', '_')}")
        lines += [f"{n + 1}," for n in surfaces[s + " nodes"]]
    for name, m in (("BASE", BASE), ("BLOCK", BLOCK)):
        lines += [f"*MATERIAL, NAME=M_{name}", "*ELASTIC",
                  f"{m['E'] * 1e-6:.9g}, {m['nu']:g}", "*DENSITY",
                  f"{m['rho'] * 1e-12:.9g}",
                  f"*SOLID SECTION, ELSET={name}, MATERIAL=M_{name}"]
    # CalculiX refuses mu = 0: a friction force of 1e-9 p stands for none
    lines += ["*SURFACE INTERACTION, NAME=PAD",
              "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
              f"{K_N * 1e-9:g}", "*FRICTION",
              f"{max(mu, 1e-9):g}, {stick_slope:g}",
              "*CONTACT PAIR, INTERACTION=PAD, TYPE=SURFACE TO SURFACE",
              "BLOCK_BOTTOM, BASE_TOP",
              "*BOUNDARY", "BASE_BOTTOM, 2, 3", "BLOCK_TOP, 1, 2",
              "*STEP, NLGEOM=NO, INC=1000", "*STATIC",
              f"{increment:g}, 1., {increment:g}, {increment:g}"
              if increment else "0.1, 1.",
              "*BOUNDARY", f"BASE_BOTTOM, 1, 1, {slide:g}", "*DLOAD"]
    traction = force / (BLOCK_AREA * 1e6)   # N/mm^2
    lines += [f"{e}, P{n}, {traction:.12g}" for e, n in surfaces["block top"]]
    lines += ["*END STEP", "*STEP, PERTURBATION", "*FREQUENCY", f"{modes}",
              "*END STEP", ""]
    return "\n".join(lines)


def calculix_eigenvalues(dat):
    """The eigenvalues in CalculiX's .dat file DAT as a sorted list of
    (frequency [Hz], growth rate Re lambda [1/s]). CalculiX prints each
    eigenvalue as omega = a + i b [rad/s] of exp(i omega t), so
    lambda = i omega and Re lambda = -b; a conjugate pair carries +-b."""
    with open(dat) as f:
        text = f.read()
    table = text.split("E I G E N V A L U E   O U T P U T")[1]
    table = table.split("P A R T I C I P A T I O N")[0]
    values = []
    for line in table.splitlines():
        cols = line.split()
        if len(cols) == 4 and cols[0].isdigit():
            # mode, Re omega [rad/s], Re omega / 2 pi [Hz], Im omega [rad/s]
            values.append((float(cols[2]), -float(cols[3])))
    return sorted(values)


def run_calculix(deck, name, work, command=None):
    """Runs `ccx` (through COMMAND, a function of the argument list and the
    folder, if given) on DECK as WORK/NAME.inp with one thread; its
    eigenvalues (calculix_eigenvalues)."""
    with open(os.path.join(work, name + ".inp"), "w") as f:
        f.write(deck)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    run = command or (lambda args, cwd: subprocess.run(
        args, cwd=cwd, capture_output=True, text=True, env=env))
    r = run(["ccx", "-i", name], work)
    if r.returncode != 0 or "Job finished" not in r.stdout:
        raise RuntimeError(f"{name}: ccx failed\n{r.stdout[-2000:]}")
    return calculix_eigenvalues(os.path.join(work, name + ".dat"))


def run_squeal(squeal, mu, force, slide, name, work):
    """squeal's preloaded CEA of the scene with the base moved by SLIDE;
    sorted [(frequency [Hz], Re lambda [1/s])]."""
    import csv
    msh = os.path.join(work, name + ".msh")
    write_msh(msh, parts(slide))
    out = os.path.join(work, name)
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as f:
        f.write(squeal_prm(msh, out, mu, force))
    r = subprocess.run([squeal, prm], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{name}: squeal failed\n{r.stdout[-3000:]}\n"
                           f"{r.stderr}")
    with open(os.path.join(out, "eigenvalues.csv")) as f:
        return sorted((float(row["freq_Hz"]), float(row["re_per_s"]))
                      for row in csv.DictReader(f))
