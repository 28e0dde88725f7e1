#!/usr/bin/python3
"""Speed against error of squeal on the clamped disc (verification A3).

usage: /usr/bin/python3 benchmarks/speed_vs_error/run_disc.py [SQUEAL] [WORKDIR]

Runs build/squeal (full solver, friction and damping off) on a sequence of
uniform disc meshes of degree 1, 2 and 3, and for each records the DoFs, the
wall time of the whole run (set-up, eigensolve, output) and the largest and
median relative frequency error of the 41 listed modes below 20 kHz against
the converged reference of verification.md A3 (the k-th computed frequency
against the k-th of the table expanded by multiplicity, as in the
cea_disc_modes test; the band is solved to 40 kHz so that a coarse mesh whose
modes come out too stiff still has 41 to compare, and a mesh with fewer
counts the missing ones as 100 % error). The meshes of NP2 run again under
mpirun -np 2 (their time and largest error in the last column). Writes WORKDIR/results.csv and, next to this script,
disc_pareto.png (error against wall time) and prints a Markdown table.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from common import finish_pareto, run_disc  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..", "..")
squeal = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "squeal")
work = sys.argv[2] if len(sys.argv) > 2 else "/tmp/squeal_speed_vs_error"


# (degree, cells around, radial, through the thickness)
MESHES = [(1, 48, 6, 2), (1, 64, 10, 2), (1, 96, 16, 3), (1, 128, 20, 4),
          (2, 32, 4, 1), (2, 48, 6, 2), (2, 64, 10, 2), (2, 96, 16, 2),
          (3, 32, 4, 1), (3, 48, 6, 2)]
NP2 = [(2, 64, 10, 2), (2, 96, 16, 2), (3, 32, 4, 1), (3, 48, 6, 2)]


def run(degree, around, radial, thick, ranks=1):
    return run_disc(squeal, work, degree, around, radial, thick, 40000, ranks)


def main():
    os.makedirs(work, exist_ok=True)
    rows = []
    for mesh in MESHES:
        row = run(*mesh)
        print(f"{row['mesh']}: {row['dofs']} DoFs, {row['seconds']} s, "
              f"max {100 * row['max_error']:.3f} %, median "
              f"{100 * row['median_error']:.3f} %", flush=True)
        rows.append(row)
    np2 = {}
    for mesh in NP2:
        row = run(*mesh, ranks=2)
        np2[row["mesh"]] = row
        print(f"{row['mesh']} (np 2): {row['seconds']} s, max "
              f"{100 * row['max_error']:.3f} %", flush=True)
    with open(os.path.join(work, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for degree, marker in ((1, "o"), (2, "s"), (3, "^")):
        sel = [r for r in rows if r["degree"] == degree]
        ax.loglog([r["seconds"] for r in sel],
                  [100 * r["max_error"] for r in sel], marker + "-",
                  label=f"degree {degree} (largest error)")
        for r in sel:
            ax.annotate(f"{r['dofs'] // 1000}k", (r["seconds"], 100 * r["max_error"]),
                        fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.axhline(0.5, color="k", lw=0.8, ls="--")
    png = os.path.join(here, "disc_pareto.png")
    finish_pareto(fig, ax, png,
                  "Clamped disc (A3): error against time, uniform meshes",
                  "largest frequency error below 20 kHz [%]",
                  legend_size=10)
    print("\n| mesh | degree | DoFs | wall time [s] | largest error | median error "
          "| mpirun -np 2: wall time [s], largest error |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        q = np2.get(r["mesh"])
        p2 = f"{q['seconds']}, {100 * q['max_error']:.3f} %" if q else ""
        print(f"| {r['mesh']} | {r['degree']} | {r['dofs']} | {r['seconds']} | "
              f"{100 * r['max_error']:.3f} % | {100 * r['median_error']:.3f} % | {p2} |")


if __name__ == "__main__":
    main()
