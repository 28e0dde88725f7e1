"""scripts/make_brake.py --disc-layers N: the solid disc's friction ring and
hat wall get N cells through the disc's 25 mm (the z planes of its nodes in
[0, 25] mm are k 25 / N), everything else of the mesh stays as it was (the
other bodies' cells and every node outside the disc's thickness), and a
layer count out of range or with --ventilated is one clear error.
Usage: check_disc_layers.py WORK_DIR"""
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.normpath(os.path.join(here, "..", ".."))
sys.path.insert(0, os.path.join(root, "scripts"))
sys.path.insert(0, here)
import make_brake  # noqa: E402
from checks import check, finish  # noqa: E402

work = sys.argv[1]
os.makedirs(work, exist_ok=True)
T = make_brake.DISC_THICKNESS


def disc_planes(mesh):
    """The z [mm] of the disc's nodes within its thickness, sorted."""
    nodes = {n for c in mesh.cells["disc"] for n in c}
    return sorted({round(mesh.coords[n][2], 9) for n in nodes
                   if -1e-9 <= mesh.coords[n][2] <= T + 1e-9})


h = 10.0
default, _ = make_brake.build(h)
check(f"default at {h} mm: two cells through the disc",
      disc_planes(default) == [0.0, T / 2, T], disc_planes(default))
for layers in (1, 3, 5):
    mesh, _ = make_brake.build(h, disc_layers=layers)
    planes = disc_planes(mesh)
    want = [round(T * k / layers, 9) for k in range(layers + 1)]
    check(f"--disc-layers {layers}: the disc's z planes k 25 / {layers} mm",
          planes == want, f"planes {planes}, wanted {want}")
    for body in ("friction material", "backplates", "piston", "caliper",
                 "bracket"):
        check(f"--disc-layers {layers}: {body} keeps its cells",
              len(mesh.cells[body]) == len(default.cells[body]),
              f"{len(mesh.cells[body])} against "
              f"{len(default.cells[body])}")
    # the disc's cells change only below z = T (the ring and the hat
    # wall), whose columns of two cells become columns of LAYERS
    below = sum(1 for c in default.cells["disc"]
                if max(default.coords[n][2] for n in c) <= T + 1e-9)
    above = len(default.cells["disc"]) - below
    want = above + below // 2 * layers
    check(f"--disc-layers {layers}: {want} disc cells",
          len(mesh.cells["disc"]) == want, len(mesh.cells["disc"]))

script = os.path.join(root, "scripts", "make_brake.py")
for args, words in ((["--disc-layers", "0"], "--disc-layers must be 1 to 32"),
                    (["--disc-layers", "3", "--ventilated"],
                     "--disc-layers is for the solid disc")):
    r = subprocess.run([sys.executable, script, "--size", "coarse", "--out",
                        os.path.join(work, "bad")] + args,
                       capture_output=True, text=True)
    check(f"make_brake.py {' '.join(args)}: one clear error, no mesh",
          r.returncode != 0 and words in r.stderr and
          not os.path.exists(os.path.join(work, "bad", "brake.msh")),
          f"exit {r.returncode}, stderr {r.stderr.strip()!r}")
finish()
