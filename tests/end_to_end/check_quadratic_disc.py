"""The clamped disc of verification A3 read from an Abaqus .inp of 20-node
C3D20R elements the check writes itself (24 sectors x 4 rings x 1 layer,
mid-side nodes on the true circles): squeal takes the corners as the cells
and the mid-side nodes as the geometry (a manifold per curved element), so
at degree 3 the first 14 frequencies in 900-8000 Hz ((0,0)-(0,6) with their
doublets and the torsion mode) are within 0.5 % of the A3 values. The same
mesh written as C3D8 (corners only: a 24-gon) is further from them: the
mid-side nodes are what carries the curvature.
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
    with open(path, "w") as f:
        f.write("*NODE\n")
        for (i2, j2, k2), n in sorted(ids.items(), key=lambda t: t[1]):
            r = 0.05 + 0.07 * i2 / (2 * nr)
            t = 2 * math.pi * j2 / (2 * ns)
            z = -0.01 + 0.01 * k2 / (2 * nl)
            f.write(f"{n}, {r * math.cos(t):.17g}, {r * math.sin(t):.17g}, "
                    f"{z:.17g}\n")
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

errors = {}
for kind, quadratic in (("C3D20R", True), ("C3D8", False)):
    mesh = os.path.abspath(f"disc_{kind}.inp")
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
    print(f"{kind}: {len(freqs)} frequencies, largest error against A3 "
          f"{100 * err:.3f} %")

n, err = errors["C3D20R"]
check("C3D20R disc within 0.5 % of A3", n == len(A3) and err < 5e-3,
      f"{n} frequencies (expected {len(A3)}), largest error {100 * err:.3f} %",
      show=True)
check("the mid-side nodes carry the curvature",
      errors["C3D8"][1] > 2 * err,
      f"corners only: {100 * errors['C3D8'][1]:.3f} %", show=True)
finish()
