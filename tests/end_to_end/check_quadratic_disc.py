"""The clamped disc of verification A3 read from an Abaqus .inp of 20-node
C3D20R elements the check writes itself (24 sectors x 4 rings x 1 layer,
mid-side nodes on the true circles): squeal takes the corners as the cells
and the mid-side nodes as the geometry (a manifold per curved element), so
at degree 3 the first 14 frequencies in 900-8000 Hz ((0,0)-(0,6) with their
doublets and the torsion mode) are within 0.5 % of the A3 values. The same
mesh written as C3D8 (corners only: a 24-gon) is further from them: the
mid-side nodes are what carries the curvature. The same quadratic mesh as
a VTK unstructured grid (.vtu, type 25, sets as cell data) gives the C3D20R
frequencies (1e-9).
Usage: check_quadratic_disc.py SQUEAL WORK_DIR"""
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish, full_solver_point, run_squeal  # noqa: E402

squeal, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
os.chdir(work)

# verification.md A3 (Hz) in 900-8000 Hz, doublets twice, torsion 6303.3
A3 = sorted([1629.8] + 2 * [1638.5] + 2 * [1839.8] + 2 * [2557.6] +
            2 * [3853.5] + 2 * [5611.7] + [6303.3] + 2 * [7731.5])


def position(i2, j2, k2, ns, nr, nl):
    r = 0.05 + 0.07 * i2 / (2 * nr)
    t = 2 * math.pi * j2 / (2 * ns)
    return r * math.cos(t), r * math.sin(t), -0.01 + 0.01 * k2 / (2 * nl)


def write_vtu(path, ids, elements, ns, nr, nl):
    """The same disc as an ASCII VTK grid of quadratic hexahedra (type 25,
    VTK's node order is Abaqus'), quadrilaterals for HUB and TOP, cell data
    arrays DISC, HUB and TOP (0/1)."""
    cells = [(25, nodes, (1, 0, 0)) for _, nodes in elements]
    cells += [(9, [nodes[0], nodes[3], nodes[7], nodes[4]], (0, 1, 0))
              for ring, nodes in elements if ring == 0]
    cells += [(9, nodes[4:8], (0, 0, 1)) for _, nodes in elements]
    points = sorted(ids.items(), key=lambda t: t[1])
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" '
                'version="0.1" byte_order="LittleEndian">\n<UnstructuredGrid>'
                f'\n<Piece NumberOfPoints="{len(points)}" '
                f'NumberOfCells="{len(cells)}">\n<Points>\n<DataArray '
                'type="Float64" NumberOfComponents="3" format="ascii">\n')
        for key, _ in points:
            f.write("%.17g %.17g %.17g\n" % position(*key, ns, nr, nl))
        f.write('</DataArray>\n</Points>\n<Cells>\n<DataArray type="Int64" '
                'Name="connectivity" format="ascii">\n')
        for _, nodes, _ in cells:
            f.write(" ".join(str(n - 1) for n in nodes) + "\n")
        offsets, o = [], 0
        for _, nodes, _ in cells:
            o += len(nodes)
            offsets.append(str(o))
        f.write('</DataArray>\n<DataArray type="Int64" Name="offsets" '
                'format="ascii">\n' + " ".join(offsets) + '\n</DataArray>\n'
                '<DataArray type="UInt8" Name="types" format="ascii">\n' +
                " ".join(str(t) for t, _, _ in cells) +
                '\n</DataArray>\n</Cells>\n<CellData>\n')
        for k, name in enumerate(("DISC", "HUB", "TOP")):
            f.write(f'<DataArray type="Int32" Name="{name}" format="ascii">\n'
                    + " ".join(str(m[k]) for _, _, m in cells) +
                    "\n</DataArray>\n")
        f.write("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")


def write_disc(path, quadratic, ns=24, nr=4, nl=1):
    """C3D20R (or C3D8 with the corners only) annulus r = 50-120 mm,
    z = -10-0 mm; *ELSET DISC, *SURFACE HUB (S6 of the inner ring) and TOP
    (S2)."""
    ids = {}

    def node(i2, j2, k2):
        key = (i2, j2 % (2 * ns), k2)
        if key not in ids:
            ids[key] = len(ids) + 1
        return ids[key]

    elements = []
    for k in range(nl):
        for i in range(nr):
            for j in range(ns):
                a, b, c = 2 * i, 2 * j, 2 * k
                corners = [(a, b, c), (a + 2, b, c), (a + 2, b + 2, c),
                           (a, b + 2, c), (a, b, c + 2), (a + 2, b, c + 2),
                           (a + 2, b + 2, c + 2), (a, b + 2, c + 2)]
                edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6),
                         (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
                nodes = [node(*p) for p in corners]
                if quadratic:
                    for e0, e1 in edges:
                        p, q = corners[e0], corners[e1]
                        nodes.append(node(*[(x + y) // 2 for x, y in zip(p, q)]))
                elements.append((i, nodes))
    if path.endswith(".vtu"):
        write_vtu(path, ids, elements, ns, nr, nl)
        return
    with open(path, "w") as f:
        f.write("*NODE\n")
        for key, n in sorted(ids.items(), key=lambda t: t[1]):
            f.write(f"{n}, %.17g, %.17g, %.17g\n"
                    % position(*key, ns, nr, nl))
        f.write(f"*ELEMENT, TYPE={'C3D20R' if quadratic else 'C3D8'}, "
                "ELSET=DISC\n")
        for e, (_, nodes) in enumerate(elements):
            line = [str(e + 1)] + [str(n) for n in nodes]
            # at most 16 entries a line, continued on the next
            f.write(", ".join(line[:16]) +
                    (",\n" + ", ".join(line[16:]) if len(line) > 16 else "")
                    + "\n")
        f.write("*SURFACE, NAME=HUB, TYPE=ELEMENT\n")
        for e, (ring, _) in enumerate(elements):
            if ring == 0:
                f.write(f"{e + 1}, S6\n")
        f.write("*SURFACE, NAME=TOP, TYPE=ELEMENT\n")
        for e in range(len(elements)):
            f.write(f"{e + 1}, S2\n")


with open("base.prm", "w") as f:
    f.write("subsection Mesh\n  set Finite element degree = 3\nend\n"
            "subsection Damping\n  set Alpha = 0\n  set Beta = 0\nend\n" +
            full_solver_point(0, 8000, 0, names=("damping.alpha", "damping.beta")))

errors, spectra = {}, {}
for kind, quadratic, ext in (("C3D20R", True, "inp"), ("C3D8", False, "inp"),
                             ("vtu", True, "vtu")):
    mesh = os.path.abspath(f"disc_{kind}.{ext}")
    write_disc(mesh, quadratic)
    out, _ = run_squeal(squeal, "base.prm", kind, f"""subsection Scene
  set Type = mesh file
  subsection Mesh file
    set File = {mesh}
    set Bodies = disc: set=DISC, E=210e9, nu=0.3, rho=7800, type=disc, face=TOP
    set Holds = hub: set=HUB
  end
end
""")
    with open(os.path.join(out, "eigenvalues.csv")) as f:
        freqs = sorted(float(r["freq_Hz"]) for r in csv.DictReader(f))
    err = max((abs(x - y) / y for x, y in zip(freqs, A3)), default=1.)
    errors[kind] = (len(freqs), err)
    spectra[kind] = freqs
    print(f"{kind}: {len(freqs)} frequencies, largest error against A3 "
          f"{100 * err:.3f} %")

n, err = errors["C3D20R"]
check("C3D20R disc within 0.5 % of A3", n == len(A3) and err < 5e-3,
      f"{n} frequencies (expected {len(A3)}), largest error {100 * err:.3f} %",
      show=True)
check("the mid-side nodes carry the curvature",
      errors["C3D8"][1] > 2 * err,
      f"corners only: {100 * errors['C3D8'][1]:.3f} %", show=True)
a, b = spectra["C3D20R"], spectra["vtu"]
diff = max((abs(x - y) / x for x, y in zip(a, b)), default=1.)
check("the same disc as a .vtu of quadratic hexahedra (VTK type 25): the "
      "C3D20R frequencies to 1e-9", len(a) == len(b) and diff < 1e-9,
      f"{len(b)} frequencies, largest relative difference {diff:.1e}",
      show=True)
finish()
