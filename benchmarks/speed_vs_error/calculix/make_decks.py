#!/usr/bin/python3
"""CalculiX decks of the clamped disc of verification.md A3.

usage: /usr/bin/python3 make_decks.py [DIR]

With DIR: writes the decks there as plain .inp files (what run_calculix.py
runs). Without: writes them xz-compressed into decks/ next to this script,
the committed copies (1.2 MB instead of 26 MB).

Writes one input deck per (element, mesh) of DECKS below, named
ELEMENT_AROUNDxRADIALxTHICK.inp: a steel annulus (inner radius 50 mm, outer
120 mm, thickness 10 mm, E = 210 GPa, nu = 0.3, rho = 7800 kg/m^3, SI units),
structured in cylindrical coordinates (cells around x radial x through the
thickness, every node placed on its circle (13 digits: CalculiX reads at most
20 characters a field), so the 20-node elements
follow the curved edges), every node of the inner face fixed in x, y and z,
and a *FREQUENCY step asking for MODES eigenfrequencies (the 41 listed modes
below 20 kHz and a margin; squeal's comparison runs solve to 24 kHz).

Element types: C3D20R (20-node serendipity brick, reduced 2x2x2 integration)
and C3D8I (8-node brick with incompatible modes). Node order as in the
CalculiX manual (corners 1-4 on the bottom face counter-clockwise, 5-8 above
them, mid-side nodes 9-12 on the bottom edges 1-2, 2-3, 3-4, 4-1, 13-16 on
the top edges, 17-20 on the vertical edges), with the local axes along
(r, theta, z) so every Jacobian is positive.
"""
import lzma
import math
import os
import sys

INNER, OUTER, THICKNESS = 0.050, 0.120, 0.010
MODES = 50

# (element, cells around, radial, through the thickness)
DECKS = [("C3D20R", 32, 4, 1), ("C3D20R", 48, 6, 2), ("C3D20R", 64, 8, 2),
         ("C3D20R", 96, 10, 3), ("C3D20R", 128, 14, 3),
         ("C3D8I", 48, 6, 2), ("C3D8I", 96, 12, 3), ("C3D8I", 128, 16, 4),
         ("C3D8I", 192, 24, 5)]

# Corners and mid-edge nodes of a cell in half-cell steps (r, theta, z).
CORNERS = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0),
           (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2)]
MIDSIDE = [(1, 0, 0), (2, 1, 0), (1, 2, 0), (0, 1, 0),
           (1, 0, 2), (2, 1, 2), (1, 2, 2), (0, 1, 2),
           (0, 0, 1), (2, 0, 1), (2, 2, 1), (0, 2, 1)]


def deck(element, around, radial, thick):
    """The text of one deck."""
    quadratic = element == "C3D20R"
    nr, nt, nz = 2 * radial, 2 * around, 2 * thick  # half-cell grid

    def used(i, j, k):
        odd = (i % 2) + (j % 2) + (k % 2)
        return odd == 0 or (quadratic and odd == 1)

    # CalculiX sizes its arrays by the node count: number the used nodes 1..N
    numbers = {}
    for k in range(nz + 1):
        for j in range(nt):
            for i in range(nr + 1):
                if used(i, j, k):
                    numbers[(i, j, k)] = len(numbers) + 1

    def node_id(i, j, k):
        return numbers[(i, j % nt, k)]

    lines = [f"*HEADING\nsqueal benchmark: clamped disc (verification A3), "
             f"{element} {around} x {radial} x {thick}",
             "*NODE, NSET=NALL"]
    inner = []
    for k in range(nz + 1):
        for j in range(nt):
            for i in range(nr + 1):
                if not used(i, j, k):
                    continue
                r = INNER + (OUTER - INNER) * i / nr
                t = 2 * math.pi * j / nt
                lines.append(f"{node_id(i, j, k)}, {r * math.cos(t):.12e}, "
                             f"{r * math.sin(t):.12e}, {THICKNESS * k / nz:.12e}")
                if i == 0:
                    inner.append(node_id(i, j, k))
    lines.append(f"*ELEMENT, TYPE={element}, ELSET=EALL")
    number = 0
    for c in range(thick):
        for b in range(around):
            for a in range(radial):
                number += 1
                pattern = CORNERS + (MIDSIDE if quadratic else [])
                ids = [node_id(2 * a + di, 2 * b + dj, 2 * c + dk)
                       for di, dj, dk in pattern]
                # at most 16 entries on a line; a trailing comma continues it
                head, tail = ids[:15], ids[15:]
                lines.append(", ".join(str(x) for x in [number] + head)
                             + ("," if tail else ""))
                if tail:
                    lines.append(", ".join(str(x) for x in tail))
    lines.append("*NSET, NSET=NINNER")
    for s in range(0, len(inner), 12):
        lines.append(", ".join(str(x) for x in inner[s:s + 12]))
    lines += ["*BOUNDARY", "NINNER, 1, 3",
              "*MATERIAL, NAME=STEEL", "*ELASTIC", "210e9, 0.3",
              "*DENSITY", "7800.",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
              "*STEP", "*FREQUENCY", f"{MODES}", "*END STEP", ""]
    return "\n".join(lines)


def deck_name(element, around, radial, thick):
    return f"{element}_{around}x{radial}x{thick}"


def write_all(folder, compressed=False):
    """Writes every deck of DECKS into FOLDER (tmp + rename), xz-compressed
    (NAME.inp.xz) if COMPRESSED; returns the paths."""
    os.makedirs(folder, exist_ok=True)
    paths = []
    for d in DECKS:
        path = os.path.join(folder, deck_name(*d) + ".inp" + (".xz" if compressed else ""))
        opener = (lambda p: lzma.open(p, "wt", preset=9)) if compressed else \
            (lambda p: open(p, "w"))
        with opener(path + ".tmp") as f:
            f.write(deck(*d))
        os.replace(path + ".tmp", path)
        paths.append(path)
    return paths


if __name__ == "__main__":
    if len(sys.argv) > 1:
        written = write_all(sys.argv[1])
    else:
        written = write_all(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                         "decks"), compressed=True)
    for p in written:
        print("wrote", p)
