"""scripts/make_brake.py --disc-layers N: the solid disc's friction ring and
hat wall get N cells through the disc's 25 mm (the z planes of its nodes in
[0, 25] mm are k 25 / N), everything else of the mesh stays as it was (the
other bodies' cells and every node outside the disc's thickness), and a
layer count out of range or with --ventilated is one clear error.
--min-cells N: every stretch between two break points gets at least N
cells (the 5 mm backplates' z planes k 5 / N mm, the hat wall's 6 mm
radial planes k 6 / N mm), N = 1 is the default mesh node for node, and N
out of range is one clear error.
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



def planes(mesh, body, axis, lo, hi, radial=False):
    """The distinct coordinates [mm] (z, or the radius with RADIAL) of
    BODY's nodes in [LO, HI], sorted."""
    nodes = {n for c in mesh.cells[body] for n in c}
    out = set()
    for n in nodes:
        x = mesh.coords[n]
        v = (x[0] ** 2 + x[1] ** 2) ** 0.5 if radial else x[axis]
        if lo - 1e-9 <= v <= hi + 1e-9:
            out.add(round(v, 6))
    return sorted(out)


same, _ = make_brake.build(h, min_cells=1)
check("--min-cells 1 is the default mesh node for node",
      same.coords == default.coords and same.cells == default.cells, "")
bp_lo = -make_brake.PAD_THICKNESS - make_brake.BACKPLATE_THICKNESS
bp_hi = -make_brake.PAD_THICKNESS
check("default: one cell through the inner backplate",
      planes(default, "backplates", 2, bp_lo, bp_hi) == [bp_lo, bp_hi],
      planes(default, "backplates", 2, bp_lo, bp_hi))
for n in (2, 3):
    mesh, _ = make_brake.build(h, min_cells=n)
    got = planes(mesh, "backplates", 2, bp_lo, bp_hi)
    want = [round(bp_lo + k * (bp_hi - bp_lo) / n, 6) for k in range(n + 1)]
    check(f"--min-cells {n}: the inner backplate's z planes k 5 / {n} mm",
          got == want, f"{got}, wanted {want}")
    # the hat wall, r 80-86 mm (the disc's nodes at mid height of the hat)
    r_in, r_out = make_brake.HAT_R_IN, make_brake.HAT_R_OUT
    got = planes(mesh, "disc", None, r_in, r_out, radial=True)
    want = [round(r_in + k * (r_out - r_in) / n, 6) for k in range(n + 1)]
    check(f"--min-cells {n}: the hat wall's radii k 6 / {n} mm",
          len(got) == n + 1 and all(abs(a - b) < 1e-3
                                    for a, b in zip(got, want)),
          f"{got}, wanted {want}")
    check(f"--min-cells {n}: more cells in every body",
          all(len(mesh.cells[b]) > len(default.cells[b])
              for b in ("disc", "friction material", "backplates",
                        "caliper", "bracket")),
          {b: len(c) for b, c in mesh.cells.items()})

script = os.path.join(root, "scripts", "make_brake.py")
for args, words in ((["--disc-layers", "0"], "--disc-layers must be 1 to 32"),
                    (["--min-cells", "0"], "--min-cells must be 1 to 8"),
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
