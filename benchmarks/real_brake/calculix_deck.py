"""CalculiX decks of the brake of scripts/make_brake.py, for the side-by-side
of run_modes.py: the mesh the script builds (the same nodes and hexahedra as
its brake.msh), as 20-node bricks C3D20R (mid-side nodes on the circle about
the hub axis for the disc's circumferential edges, as squeal's cylindrical
manifold places them; straight elsewhere, as squeal's mapping of the other
bodies), in mm, N, t, s (so moduli in MPa and densities in t/mm^3).

The model is the brake's frictionless assembly with its pads tied to the disc
(the comparison model of run_modes.py, the same in both codes): every body
of brake_scene.prm with its material (the friction material transversely
isotropic about z as *ELASTIC, TYPE=ENGINEERING CONSTANTS), the disc held at
its hub face and the bracket at its mounts (*BOUNDARY), each pad face tied to
its disc face (*TIE), no springs, no load, and a *FREQUENCY step for the
eigenfrequencies up to F_MAX.
"""
import math
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "scripts"))
import make_brake  # noqa: E402

# Abaqus/CalculiX C3D20: mid-side nodes 9-20 on these corner pairs
EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
         (0, 4), (1, 5), (2, 6), (3, 7)]
# the brick's faces S1-S6 by their corners
FACES = {1: (0, 1, 2, 3), 2: (4, 7, 6, 5), 3: (0, 4, 5, 1), 4: (1, 5, 6, 2),
         5: (2, 6, 7, 3), 6: (3, 7, 4, 0)}
TIES = [("inner pad face", "disc inboard face"),
        ("outer pad face", "disc outboard face")]
HOLDS = ["disc hub", "bracket mounts"]


def materials():
    """(body, *MATERIAL lines) in mm-N-t-s."""
    def iso(m):
        return ["*ELASTIC", f"{m['E'] * 1e-6:.9g}, {m['nu']:.9g}",
                "*DENSITY", f"{m['rho'] * 1e-12:.9g}"]
    pad = make_brake.PAD
    g12 = pad["E"] / (2 * (1 + pad["nu"]))
    friction = ["*ELASTIC, TYPE=ENGINEERING CONSTANTS",
                ", ".join(f"{v:.9g}" for v in (
                    pad["E"] * 1e-6, pad["E"] * 1e-6, pad["Et"] * 1e-6,
                    pad["nu"], pad["nut"], pad["nut"], g12 * 1e-6,
                    pad["Gt"] * 1e-6)),
                f"{pad['Gt'] * 1e-6:.9g}",
                "*DENSITY", f"{pad['rho'] * 1e-12:.9g}"]
    steel = iso(make_brake.STEEL)
    return {"disc": iso(make_brake.DISC), "friction material": friction,
            "backplates": steel, "piston": steel, "caliper": steel,
            "bracket": steel}


def name(s):
    return s.upper().replace(" ", "_")


def deck(h, f_max, modes, friction=None, min_cells=1):
    """The text of the deck at element size h [mm] (MIN_CELLS: the
    generator's fewest cells between two break points); (text, DoFs). With
    FRICTION (a dict: k_n [N/m^3], mu, stick_slope [N/mm^3], theta [rad],
    force [N], f_min [Hz], and increment, the static step's fixed increment,
    if not CalculiX's automatic ones from 0.1 of the step) the pads are in frictional contact with the disc
    instead of tied, the piston's back and the caliper's bore are held in x
    and y (the model has no springs), and the deck is
    CalculiX's brake-squeal practice: a *STATIC step that presses the pads
    (FORCE on the piston's back and on the caliper's bore, as squeal's force
    pair) and turns the disc by THETA at its hub so that the pads slip, then
    a perturbed, unsymmetric *FREQUENCY step of MODES eigenvalues from
    F_MIN up."""
    mesh, _ = make_brake.build(h, min_cells=min_cells)
    coords = [list(c) for c in mesh.coords]
    mid = {}
    disc_nodes = {n for c in mesh.cells["disc"] for n in c}

    def midside(a, b):
        key = (min(a, b), max(a, b))
        if key not in mid:
            pa, pb = coords[a], coords[b]
            ra, rb = math.hypot(pa[0], pa[1]), math.hypot(pb[0], pb[1])
            p = [(x + y) / 2 for x, y in zip(pa, pb)]
            if (a in disc_nodes and b in disc_nodes and abs(ra - rb) < 1e-9
                    and abs(pa[2] - pb[2]) < 1e-9 and ra > 0):
                t = math.atan2(pa[1] + pb[1], pa[0] + pb[0])
                p = [ra * math.cos(t), ra * math.sin(t), pa[2]]
            mid[key] = len(coords)
            coords.append(p)
        return mid[key]

    elements = {}   # body -> [(id, 20 nodes)]
    face_of = {}    # frozenset of 4 corners -> (element id, face number)
    eid = 0
    for body, cells in mesh.cells.items():
        for c in cells:
            eid += 1
            nodes = list(c) + [midside(c[a], c[b]) for a, b in EDGES]
            elements.setdefault(body, []).append((eid, nodes))
            for number, corners in FACES.items():
                face_of[frozenset(c[i] for i in corners)] = (eid, number)
    lines = ["** The brake of scripts/make_brake.py, element size "
             f"{h:g} mm, pads tied to the disc, frictionless "
             "(benchmarks/real_brake/calculix_deck.py)", "*NODE"]
    lines += [f"{i + 1}, {p[0]:.12g}, {p[1]:.12g}, {p[2]:.12g}"
              for i, p in enumerate(coords)]
    for body, els in elements.items():
        lines.append(f"*ELEMENT, TYPE=C3D20R, ELSET={name(body)}")
        for e, nodes in els:
            ids = [str(n + 1) for n in nodes]
            lines.append(f"{e}, " + ", ".join(ids[:15]) + ",")
            lines.append(", ".join(ids[15:]))
    loads = ["piston back", "caliper bore"]
    faces = [f for pair in TIES for f in pair]
    if friction:
        faces += loads
    for face in faces:
        lines.append(f"*SURFACE, NAME={name(face)}, TYPE=ELEMENT")
        for quad in mesh.faces[face]:
            e, number = face_of[frozenset(quad)]
            lines.append(f"{e}, S{number}")

    def face_nodes(face):
        nodes = set()
        for quad in mesh.faces[face]:
            nodes.update(quad)
            nodes.update(midside(quad[i], quad[(i + 1) % 4])
                         for i in range(4))
        return nodes

    fixed = set()
    for hold in HOLDS + (loads if friction else []):
        nodes = face_nodes(hold)
        if hold in HOLDS:
            fixed |= nodes
        lines.append(f"*NSET, NSET={name(hold)}")
        ordered = sorted(n + 1 for n in nodes)
        for i in range(0, len(ordered), 16):
            lines.append(", ".join(str(n) for n in ordered[i:i + 16]))
    for body, text in materials().items():
        lines += [f"*MATERIAL, NAME=M_{name(body)}"] + text
        lines.append(f"*SOLID SECTION, ELSET={name(body)}, "
                     f"MATERIAL=M_{name(body)}")
    dofs = 3 * (len(coords) - len(fixed))
    if not friction:
        for k, (slave, master) in enumerate(TIES):
            lines += [f"*TIE, NAME=TIE{k + 1}, POSITION TOLERANCE=0.5",
                      f"{name(slave)}, {name(master)}"]
        lines += ["*BOUNDARY"] + [f"{name(hold)}, 1, 3" for hold in HOLDS]
        lines += ["*STEP", "*FREQUENCY, SOLVER=SPOOLES",
                  f"{modes}, 0., {f_max:g}", "*END STEP", ""]
        return "\n".join(lines), dofs
    # the pads in frictional contact with the disc: penalty k_n [N/m^3] as
    # N/mm^3, Coulomb mu with its stick slope [N/mm^3]
    lines += ["*SURFACE INTERACTION, NAME=PAD",
              "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
              f"{friction['k_n'] * 1e-9:g}", "*FRICTION",
              f"{friction['mu']:g}, {friction['stick_slope']:g}"]
    for slave, master in TIES:
        lines += ["*CONTACT PAIR, INTERACTION=PAD, TYPE=SURFACE TO SURFACE",
                  f"{name(slave)}, {name(master)}"]
    lines += ["*BOUNDARY", "BRACKET_MOUNTS, 1, 3", "PISTON_BACK, 1, 2",
              "CALIPER_BORE, 1, 2",
              "*STEP, NLGEOM=NO, INC=1000", "*STATIC",
              "{0:g}, 1., {0:g}, {0:g}".format(friction["increment"])
              if friction.get("increment") else "0.1, 1.",
              "*BOUNDARY"]
    # the disc turned by theta about z at its hub, counterclockwise (squeal's
    # Interface/Rotation sense): the linearised rotation theta e_z x x, which
    # strains nothing in small-strain elasticity
    theta = friction["theta"]
    for n in sorted(face_nodes("disc hub")):
        x, y, _ = coords[n]
        lines += [f"{n + 1}, 1, 1, {-theta * y:.12g}",
                  f"{n + 1}, 2, 2, {theta * x:.12g}", f"{n + 1}, 3, 3, 0."]
    lines.append("*DLOAD")
    for face in loads:
        area = sum(quad_area([coords[v] for v in quad])
                   for quad in mesh.faces[face])
        pressure = friction["force"] / area    # N/mm^2, into the face
        for quad in mesh.faces[face]:
            e, number = face_of[frozenset(quad)]
            lines.append(f"{e}, P{number}, {pressure:.12g}")
    lines += ["*END STEP", "*STEP, PERTURBATION", "*FREQUENCY",
              f"{modes}, {friction['f_min']:g}, {f_max:g}",
              "*END STEP", ""]
    return "\n".join(lines), dofs


def quad_area(p):
    """Area of the planar quadrilateral with the corners P, in order."""
    a = [x - y for x, y in zip(p[2], p[0])]
    b = [x - y for x, y in zip(p[3], p[1])]
    c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
         a[0] * b[1] - a[1] * b[0]]
    return 0.5 * math.sqrt(sum(x * x for x in c))

if __name__ == "__main__":
    import argparse
    p = argparse.ArgumentParser(description="writes a CalculiX deck of the "
                                "tied, frictionless brake")
    p.add_argument("out")
    p.add_argument("--element-size", type=float, default=10.0)
    p.add_argument("--max-frequency", type=float, default=16000.)
    p.add_argument("--modes", type=int, default=150)
    a = p.parse_args()
    text, dofs = deck(a.element_size, a.max_frequency, a.modes)
    with open(a.out, "w") as f:
        f.write(text)
    print(f"{a.out}: {dofs} DoFs")
