#!/usr/bin/python3
"""End-to-end check of the contact refinement (Mesh/Contact refinements).

usage: check_contact_refinement.py SQUEAL PRM WORKDIR

PRM is the coarse preloaded TriboBrake (tests/preload/coarse.prm: degree 1,
pad 4 x 4 cells, 100 N with steady sliding at mu = 0.5), here with the
hard-contact limit of the interface stiffness (k_n = 1e14 N/m^3 in the
preload's penalty law and in the CEA), whose pressure peaks at the pad's
leading edge and whose trailing part separates. The
CEA about it at one point (E_pad = 25 GPa, mu = 0.5, full solver) runs
with 0 and 2 contact refinement cycles (fraction 0.25). Checks:
- the indicator, recomputed here from the preload's contact.csv: for every
  pad cell of the first cycle (the unrefined 4 x 4 grid, its face nodes at
  its corners) the pressure variation max - min over its face nodes equals
  contact_refinement.csv's to 1e-5 of the largest (the code interpolates
  the nodal field at the cells' vertices, which lie within about 1e-9 m of
  the pad nodes where the pressure gradient is about 2e9 Pa/m: a few Pa);
- the marking: per cycle ceil(0.25 x contact cells) or more (ties) are
  refined, each with a variation at least that of every cell left;
- where: the first cycle refines the pad cells at the leading edge (the
  pad nodes of largest pressure are corners of refined cells) and no pad
  cell at the separated trailing edge; every refined cell's centre lies on
  the contact plane's side cells (|z| below a cell's thickness) and the
  disc cells overlap the pad footprint;
- the mesh grows only there: at least 7 new cells per refined cell and at
  most 3x that (the one-irregular rule refines a few neighbours), far
  below one global refinement (7 x 768 new cells);
- the CEA on the refined mesh: as many modes in the band, the same number
  of unstable modes (classification unchanged under the refinement), no
  frequency moved by more than 1 %;
- mpirun -np 2 gives the serial eigenvalues (1e-8 of |lambda|);
- refused: Contact refinements without Scene/Analysis = preloaded cea.
"""
import csv
import math
import os
import sys

from checks import check, finish, run_table_point

squeal, prm, work = sys.argv[1:4]
prm = os.path.abspath(prm)
os.makedirs(work, exist_ok=True)
os.chdir(work)
FRACTION = 0.25


def run(name, cycles, mpi=0, analysis="preloaded cea"):
    return run_table_point(squeal, prm, name, f"""subsection Scene
  set Analysis = {analysis}
end
subsection Mesh
  set Contact refinements = {cycles}
  set Contact refinement fraction = {FRACTION}
end
subsection Interface
  set Normal stiffness = 1e14
end
""", mpi)


def eigenvalues(out):
    with open(os.path.join(out, "eigenvalues.csv"), newline="") as f:
        return [complex(float(r["re_per_s"]), 2 * math.pi * float(r["freq_Hz"]))
                for r in csv.DictReader(f)]


def cells_in(log):
    """Cell counts of the 'Mesh: N cells' lines, in order."""
    return [int(line.split()[1]) for line in log.splitlines()
            if line.startswith("Mesh: ")]


out0, r0 = run("unrefined", 0)
out2, r2 = run("refined", 2)
for name, r in (("unrefined", r0), ("refined", r2)):
    if r.returncode != 0:
        check(f"{name} runs", False, r.stdout[-2000:] + r.stderr[-2000:])
        finish()
print(r2.stdout[r2.stdout.find("Contact refinement cycle 0"):][:600])

with open(os.path.join(out2, "preload", "contact.csv"), newline="") as f:
    nodes = [(float(r["x_m"]), float(r["y_m"]), float(r["p_N_Pa"]), int(r["status"]))
             for r in csv.DictReader(f)]
with open(os.path.join(out2, "contact_refinement.csv"), newline="") as f:
    table = list(csv.DictReader(f))
xs = sorted({round(x, 9) for x, _, _, _ in nodes})
ys = sorted({round(y, 9) for _, y, _, _ in nodes})
pressure = {(round(x, 9), round(y, 9)): p for x, y, p, _ in nodes}
status = {(round(x, 9), round(y, 9)): s for x, y, _, s in nodes}
largest = max(float(r["pressure_variation_Pa"]) for r in table)

# the indicator of the first cycle's pad cells, recomputed
first_pad = [r for r in table if r["cycle"] == "0" and r["body"] == "pad"]
worst = 0.
for r in first_pad:
    x, y = float(r["x"]), float(r["y"])
    corners = [(a, b) for a in xs for b in ys
               if abs(a - x) < 0.51 * (xs[1] - xs[0]) and abs(b - y) < 0.51 * (ys[1] - ys[0])]
    ps = [pressure[c] for c in corners]
    worst = max(worst, abs(max(ps) - min(ps) - float(r["pressure_variation_Pa"])))
check("the pad cells' indicator is the pressure variation over their face nodes",
      len(first_pad) == (len(xs) - 1) * (len(ys) - 1) and worst <= 1e-5 * largest,
      f"{len(first_pad)} pad cells, largest difference {worst:.3g} Pa of {largest:.3g}")

# the marking
cycles = sorted({r["cycle"] for r in table})
check("two cycles in contact_refinement.csv", cycles == ["0", "1"], str(cycles))
for c in cycles:
    rows = [r for r in table if r["cycle"] == c]
    refined = [float(r["pressure_variation_Pa"]) for r in rows if r["refined"] == "1"]
    kept = [float(r["pressure_variation_Pa"]) for r in rows if r["refined"] == "0"]
    check(f"cycle {c}: the {FRACTION:g} of the contact cells with the largest "
          "variation refined",
          len(refined) >= math.ceil(FRACTION * len(rows)) and
          min(refined) >= max(kept, default=0.),
          f"{len(refined)} of {len(rows)} refined, smallest refined "
          f"{min(refined):.4g} Pa, largest kept {max(kept, default=0.):.4g} Pa")

# where: the leading edge, not the separated trailing edge
peak = max(pressure, key=pressure.get)
refined_pad = [(float(r["x"]), float(r["y"])) for r in first_pad if r["refined"] == "1"]


def corner_of(node, cell):
    return (abs(node[0] - cell[0]) < 0.51 * (xs[1] - xs[0]) and
            abs(node[1] - cell[1]) < 0.51 * (ys[1] - ys[0]))


separated_cells = [cell for cell in ((float(r["x"]), float(r["y"])) for r in first_pad)
                   if all(status[n] == 0 for n in pressure if corner_of(n, cell))]
check("the first cycle refines the pad cells at the peak pressure (leading edge)",
      any(corner_of(peak, cell) for cell in refined_pad),
      f"peak {pressure[peak] / 1e6:.3g} MPa at {peak}, refined pad cells {refined_pad}")
check("no separated pad cell is refined",
      separated_cells and not any(c in refined_pad for c in separated_cells),
      f"{len(separated_cells)} separated pad cells")
x_lo, x_hi, y_lo, y_hi = xs[0], xs[-1], ys[0], ys[-1]
check("every refined cell touches the contact plane",
      all(abs(float(r["z"])) < 0.0051 for r in table if r["refined"] == "1"),
      str([r["z"] for r in table if r["refined"] == "1"]))
# a disc cell overlapping the footprint has its centre within one disc cell
# (2 pi 0.105 m / 48 = 13.7 mm at the pad's outer radius) of it
off = [math.hypot(max(x_lo - float(r["x"]), 0., float(r["x"]) - x_hi),
                  max(y_lo - float(r["y"]), 0., float(r["y"]) - y_hi))
       for r in table if r["body"] == "disc" and r["refined"] == "1"]
check("the refined disc cells are under the pad", off and max(off) < 0.014,
      f"{len(off)} refined disc cells, farthest centre {1e3 * max(off, default=0):.2f} mm "
      "off the footprint", True)

# the mesh grows only there
counts = cells_in(r2.stdout)
n_refined = sum(r["refined"] == "1" for r in table)
grown = counts[-1] - counts[0]
check("the mesh grows by the refined cells (and few one-irregular neighbours)",
      7 * n_refined <= grown <= 21 * n_refined and grown < 0.2 * 7 * counts[0],
      f"{counts[0]} -> {counts[-1]} cells for {n_refined} refined")

# the CEA on the refined mesh
lam0, lam2 = eigenvalues(out0), eigenvalues(out2)
check("as many modes in the band", len(lam0) == len(lam2), f"{len(lam0)} vs {len(lam2)}")
unstable = [sum(1 for l in lam if l.real > 1e-3) for lam in (lam0, lam2)]
check("the classification is unchanged under the contact refinement",
      unstable[0] == unstable[1] and unstable[0] > 0, f"unstable modes {unstable}")
moved = max(abs(a.imag - b.imag) / abs(b.imag) for a, b in zip(lam2, lam0))
check("no frequency moves by more than 1 %", moved < 0.01, f"largest {100 * moved:.3f} %")

# mpirun -np 2
outp, rp = run("refined_np2", 2, mpi=2)
if rp.returncode != 0:
    check("refined under mpirun -np 2 runs", False, rp.stdout[-2000:] + rp.stderr[-2000:])
    finish()
lamp = eigenvalues(outp)
gap = max(abs(a - b) / abs(b) for a, b in zip(lamp, lam2)) if len(lamp) == len(lam2) else 1.
check("mpirun -np 2 gives the serial eigenvalues", gap < 1e-8, f"{gap:.3g}")

# refused without a preload
_, rr = run("refused", 1, analysis="cea")
msg = rr.stdout + rr.stderr
check("refused: Contact refinements without a preload",
      rr.returncode != 0 and "Contact refinements" in msg and "preloaded cea" in msg,
      msg[-400:])
finish()
