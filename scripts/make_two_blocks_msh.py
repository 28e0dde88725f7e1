#!/usr/bin/env python3
"""Writes prm/two_blocks.msh: a Gmsh ASCII 2.2 mesh (in mm) of two separately
meshed hexahedral blocks for the two-block contact scene
(prm/two_blocks_cea.prm, prm/two_blocks_preload.prm).

- "base": 20 x 20 x 10 mm, x, y in [0, 20], z in [-10, 0], 4 x 4 x 2 cells;
- "block": 10 x 10 x 10 mm, x, y in [5, 15], z in [0, 10], 3 x 3 x 2 cells,
  so the contact faces do not match;
- surfaces: "base top" (z = 0), "base bottom" (z = -10), "block bottom"
  (z = 0), "block top" (z = 10).

Usage: scripts/make_two_blocks_msh.py [OUT.msh]   (default prm/two_blocks.msh)
No Gmsh needed: the format is written directly (Gmsh reference manual,
"MSH file format version 2").
"""
import os
import sys


def block(x0, x1, y0, y1, z0, z1, n, m):
    """Nodes (list of (x, y, z)) and hexahedra (8 node indices in Gmsh order:
    the bottom face counter-clockwise, then the top face) of an n x n x m
    box."""
    nodes, index = [], {}
    for k in range(m + 1):
        for j in range(n + 1):
            for i in range(n + 1):
                index[i, j, k] = len(nodes)
                nodes.append((x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * j / n,
                              z0 + (z1 - z0) * k / m))
    hexes = []
    for k in range(m):
        for j in range(n):
            for i in range(n):
                bottom = [index[i, j, k], index[i + 1, j, k],
                          index[i + 1, j + 1, k], index[i, j + 1, k]]
                top = [index[a, b, k + 1] for a, b in
                       ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1))]
                hexes.append(bottom + top)
    faces = {"bottom": [], "top": []}
    for j in range(n):
        for i in range(n):
            faces["bottom"].append([index[a, b, 0] for a, b in
                                    ((i, j), (i, j + 1), (i + 1, j + 1),
                                     (i + 1, j))])
            faces["top"].append([index[a, b, m] for a, b in
                                 ((i, j), (i + 1, j), (i + 1, j + 1),
                                  (i, j + 1))])
    return nodes, hexes, faces


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "prm",
        "two_blocks.msh")
    parts = [("base", block(0, 20, 0, 20, -10, 0, 4, 2)),
             ("block", block(5, 15, 5, 15, 0, 10, 3, 2))]
    # physical groups: (dimension, tag, name)
    groups = [(3, 1, "base"), (3, 2, "block"), (2, 3, "base top"),
              (2, 4, "base bottom"), (2, 5, "block bottom"),
              (2, 6, "block top")]
    tag = {name: t for _, t, name in groups}
    nodes, elements = [], []
    for name, (pts, hexes, faces) in parts:
        offset = len(nodes)
        nodes += pts
        for h in hexes:
            elements.append((5, tag[name], [offset + v for v in h]))
        for side, quads in faces.items():
            for q in quads:
                elements.append((3, tag[f"{name} {side}"],
                                 [offset + v for v in q]))
    with open(out, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write(f"$PhysicalNames\n{len(groups)}\n")
        for dim, t, name in groups:
            f.write(f'{dim} {t} "{name}"\n')
        f.write("$EndPhysicalNames\n")
        f.write(f"$Nodes\n{len(nodes)}\n")
        for i, (x, y, z) in enumerate(nodes):
            f.write(f"{i + 1} {x:.17g} {y:.17g} {z:.17g}\n")
        f.write("$EndNodes\n")
        f.write(f"$Elements\n{len(elements)}\n")
        for i, (kind, t, vs) in enumerate(elements):
            f.write(f"{i + 1} {kind} 2 {t} {t} " +
                    " ".join(str(v + 1) for v in vs) + "\n")
        f.write("$EndElements\n")
    print(f"wrote {out}: {len(nodes)} nodes, {len(elements)} elements")


if __name__ == "__main__":
    main()
