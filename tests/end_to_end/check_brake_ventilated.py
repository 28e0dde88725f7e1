"""The ventilated disc of scripts/make_brake.py --ventilated (coarse size,
degree 1):
- the disc's volume, summed over the hexahedra of its physical group as
  Gmsh reads the file, equals the drawing's: two 9 mm cheeks and 36 vanes
  of 4 degrees (10 mm high) on the ring r = 86-150, the hat wall r = 80-86
  from the outboard cheek (z = 19) to the flange top (z = 45) and the flange
  r = 33-80, 6 thick (2e-3: the cells' straight chords of the circles);
  a solid ring would be 30 % more;
- the preload (steady sliding, mu = 0.3): the force pair F on the piston
  and the caliper's bore presses both pads on the cheeks, so the normal
  force is 2 F (1e-3: the soft axial springs) and friction mu times it;
- the preloaded CEA at one point (full solver, 500-6000 Hz; the solver
  itself fails unless it finds every symmetric mode that inertia counts):
  at least 20 modes in the band, every residual below 1e-10.
Usage: check_brake_ventilated.py SQUEAL WORK_DIR"""
import csv
import math
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from checks import (check, check_brake_force_loop,  # noqa: E402
                    finish, make_brake, run_squeal)

squeal, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
os.chdir(work)

make_brake("--ventilated")


def tetrahedron(a, b, c, d):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [d[i] - a[i] for i in range(3)]
    return abs(u[0] * (v[1] * w[2] - v[2] * w[1]) -
               u[1] * (v[0] * w[2] - v[2] * w[0]) +
               u[2] * (v[0] * w[1] - v[1] * w[0])) / 6


def hexahedron(p):
    """Volume of a hexahedron with planar faces (Gmsh's node order: bottom
    face 0-3, top face 4-7) as six tetrahedra about the diagonal 0-6."""
    return sum(tetrahedron(p[0], p[6], p[a], p[b]) for a, b in
               ((1, 2), (2, 3), (3, 7), (7, 4), (4, 5), (5, 1)))


import gmsh  # noqa: E402  (Debian's python3-gmsh, as make_brake.py)
gmsh.initialize([], False)
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open("brake/brake.msh")
volume = 0.
n_cells = 0
for dim, tag in gmsh.model.getPhysicalGroups(3):
    if gmsh.model.getPhysicalName(dim, tag) != "disc":
        continue
    for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
        _, _, nodes = gmsh.model.mesh.getElements(dim, entity)
        for cell in range(len(nodes[0]) // 8):
            corners = [gmsh.model.mesh.getNode(n)[0]
                       for n in nodes[0][8 * cell:8 * cell + 8]]
            volume += hexahedron(corners)
            n_cells += 1
gmsh.finalize()
ring = math.pi * (150.0 ** 2 - 86.0 ** 2)
vanes = 36 * math.radians(4.0) / (2 * math.pi)
drawing = (ring * (2 * 9.0 + vanes * 10.0) +
           math.pi * (86.0 ** 2 - 80.0 ** 2) * (45.0 - 19.0) +
           math.pi * (80.0 ** 2 - 33.0 ** 2) * 6.0)
check("disc volume = the drawing's (two cheeks, 36 vanes, hat, flange)",
      n_cells > 0 and abs(volume - drawing) < 2e-3 * drawing,
      f"{n_cells} hexahedra, {volume:.6g} mm^3 against {drawing:.6g} mm^3 "
      f"(solid ring: {drawing + ring * (1 - vanes) * 10.0:.6g})", show=True)

force = 2e6 * math.pi * 0.054 ** 2 / 4   # the script's piston force [N]
with open("base.prm", "w") as f:
    f.write("""INCLUDE brake/brake_scene.prm
subsection Mesh
  set Finite element degree = 1
end
subsection Interface
  set Normal stiffness = 1e13
  set Friction coefficient = 0.3
end
subsection Preload
  set Friction = steady sliding
end
subsection Damping
  set Alpha = 0.02
  set Beta = 1e-7
end
""")
out, _ = run_squeal(squeal, "base.prm", "preload",
                    "subsection Scene\n  set Analysis = preload\nend\n")
check_brake_force_loop(out, force, 0.3, "both pads pressed on the cheeks")

out, _ = run_squeal(squeal, "base.prm", "cea", """subsection Scene
  set Analysis = preloaded cea
end
subsection Eigensolver
  set Method = full
  set Minimum frequency = 500
  set Maximum frequency = 6000
end
subsection Sweep
  set First parameter = contact.mu
  set First values = 0.5
  set Second parameter = friction material.E
  set Second values = 8e9
end
subsection Output
  set Mode shapes = none
end
""")
with open(os.path.join(out, "full_solver.csv")) as f:
    row = next(csv.DictReader(f))
with open(os.path.join(out, "eigenvalues.csv")) as f:
    n_eigen = len(list(csv.DictReader(f)))
modes, counted = int(row["modes"]), int(row["symmetric_in_band"])
residual = float(row["largest_residual"])
check("CEA: the band's modes found, residuals below 1e-10",
      modes == n_eigen and modes >= 20 and residual <= 1e-10,
      f"{modes} modes, {counted} counted by inertia without friction, "
      f"largest residual {residual:.3g}", show=True)
finish()
