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


def deck(h, f_max, modes):
    """The text of the deck at element size h [mm]; (text, DoFs)."""
    mesh, _ = make_brake.build(h)
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
    for face in [f for pair in TIES for f in pair]:
        lines.append(f"*SURFACE, NAME={name(face)}, TYPE=ELEMENT")
        for quad in mesh.faces[face]:
            e, number = face_of[frozenset(quad)]
            lines.append(f"{e}, S{number}")
    fixed = set()
    for hold in HOLDS:
        nodes = set()
        for quad in mesh.faces[hold]:
            nodes.update(quad)
            nodes.update(midside(quad[i], quad[(i + 1) % 4])
                         for i in range(4))
        fixed |= nodes
        lines.append(f"*NSET, NSET={name(hold)}")
        ordered = sorted(n + 1 for n in nodes)
        for i in range(0, len(ordered), 16):
            lines.append(", ".join(str(n) for n in ordered[i:i + 16]))
    for body, text in materials().items():
        lines += [f"*MATERIAL, NAME=M_{name(body)}"] + text
        lines.append(f"*SOLID SECTION, ELSET={name(body)}, "
                     f"MATERIAL=M_{name(body)}")
    for k, (slave, master) in enumerate(TIES):
        lines += [f"*TIE, NAME=TIE{k + 1}, POSITION TOLERANCE=0.5",
                  f"{name(slave)}, {name(master)}"]
    lines += ["*BOUNDARY"] + [f"{name(hold)}, 1, 3" for hold in HOLDS]
    lines += ["*STEP", "*FREQUENCY, SOLVER=SPOOLES",
              f"{modes}, 0., {f_max:g}", "*END STEP", ""]
    return "\n".join(lines), 3 * (len(coords) - len(fixed))


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
