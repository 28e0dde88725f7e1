#!/usr/bin/python3
"""squeal against CalculiX 2.20 on the clamped disc (verification A3).

usage: /usr/bin/python3 benchmarks/speed_vs_error/run_calculix.py [SQUEAL] [WORKDIR]

Needs Debian's calculix-ccx (`apt-get install calculix-ccx`; the script stops
with that advice when `ccx` is missing). Both codes on the same machine, one
after the other:
- CalculiX: the decks of calculix/make_decks.py (C3D20R and C3D8I at several
  densities), regenerated into WORKDIR and checked byte for byte against the
  committed calculix/decks/*.inp.xz, each run by `ccx -i` with
  OMP_NUM_THREADS=2 and OPENBLAS_NUM_THREADS=1 (OpenBLAS' own threads made
  CalculiX 20x slower here), 50 eigenfrequencies (SPOOLES + ARPACK,
  shift-invert at 0);
- squeal: full solver, uniform disc meshes of degree 2, 3 and 4, solved to
  24 kHz (above the 41 listed modes below 20 kHz, as CalculiX's 50 modes are),
  1 MPI rank.
Error = largest and median relative frequency error of the 41 modes below
20 kHz against the A3 table (common.disc_errors). Wall time = the whole run
of each program (reading, assembly, eigensolve, output).

Prints both tables and the time each code needs to reach 1 %, 0.5 % and
0.1 % (the fastest run of its sequence below that error), writes
WORKDIR/calculix.csv, WORKDIR/squeal.csv and, next to this script,
calculix_pareto.png.
"""
import csv
import lzma
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "calculix"))
from common import disc_errors, finish_pareto, run_disc  # noqa: E402
from make_decks import DECKS, deck_name, write_all  # noqa: E402

root = os.path.join(here, "..", "..")
squeal = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "squeal")
work = sys.argv[2] if len(sys.argv) > 2 else "/tmp/squeal_calculix"

# squeal's sequence: (degree, cells around, radial, through the thickness)
SQUEAL_MESHES = [(2, 48, 6, 2), (2, 64, 10, 2), (3, 32, 4, 1), (3, 48, 6, 1),
                 (4, 32, 4, 1), (4, 48, 6, 1)]
TARGETS = (0.01, 0.005, 0.001)


def ccx_frequencies(dat):
    """The frequencies [Hz] (CYCLES/TIME column) of a CalculiX .dat file."""
    freqs = []
    with open(dat) as f:
        text = f.read()
    table = text.split("E I G E N V A L U E   O U T P U T", 1)[1]
    table = table.split("P A R T I C I P A T I O N", 1)[0]
    for line in table.splitlines():
        cols = line.split()
        if len(cols) == 5 and re.fullmatch(r"\d+", cols[0]):
            freqs.append(float(cols[3]))
    if not freqs:
        sys.exit(f"{dat}: no eigenvalue table")
    return freqs


def run_ccx(inp):
    """Runs CalculiX on INP; returns (DoFs, wall seconds, frequencies)."""
    job = inp[:-4]
    env = dict(os.environ, OMP_NUM_THREADS="2", OPENBLAS_NUM_THREADS="1")
    start = time.monotonic()
    r = subprocess.run(["ccx", "-i", os.path.basename(job)], cwd=os.path.dirname(job),
                       capture_output=True, text=True, env=env)
    seconds = time.monotonic() - start
    if r.returncode != 0 or "Job finished" not in r.stdout:
        sys.exit(f"{inp}: ccx failed\n{r.stdout[-3000:]}\n{r.stderr}")
    with open(inp) as f:
        text = f.read()
    nodes = len(text.split("*NODE", 1)[1].split("*ELEMENT", 1)[0].splitlines()) - 1
    fixed = len(",".join(text.split("*NSET, NSET=NINNER", 1)[1]
                         .split("*BOUNDARY", 1)[0].split()).strip(",").split(","))
    return 3 * (nodes - fixed), seconds, ccx_frequencies(job + ".dat")


def check_committed(paths):
    """Stops unless every regenerated deck equals its committed .inp.xz."""
    for p in paths:
        committed = os.path.join(here, "calculix", "decks", os.path.basename(p) + ".xz")
        with lzma.open(committed, "rt") as f, open(p) as g:
            if f.read() != g.read():
                sys.exit(f"{p} differs from {committed}: regenerate the decks "
                         "(calculix/make_decks.py) and commit them")


def time_to(rows, target):
    """The fastest run of ROWS whose largest error is below TARGET, or None."""
    ok = [r for r in rows if r["max_error"] < target]
    return min(ok, key=lambda r: r["seconds"]) if ok else None


def write_csv(path, rows):
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    os.replace(path + ".tmp", path)


def main():
    if shutil.which("ccx") is None:
        sys.exit("ccx not found: apt-get install calculix-ccx (CalculiX 2.20)")
    os.makedirs(work, exist_ok=True)
    paths = write_all(os.path.join(work, "decks"))
    check_committed(paths)
    ccx_rows = []
    for d, inp in zip(DECKS, paths):
        dofs, seconds, freqs = run_ccx(inp)
        errors = disc_errors(freqs)
        row = dict(mesh=deck_name(*d), element=d[0], dofs=dofs,
                   seconds=round(seconds, 1), max_error=max(errors),
                   median_error=statistics.median(errors))
        print(f"CalculiX {row['mesh']}: {dofs} DoFs, {row['seconds']} s, max "
              f"{100 * row['max_error']:.3f} %, median {100 * row['median_error']:.3f} %",
              flush=True)
        ccx_rows.append(row)
    write_csv(os.path.join(work, "calculix.csv"), ccx_rows)
    squeal_rows = []
    for mesh in SQUEAL_MESHES:
        row = run_disc(squeal, work, *mesh, 24000)
        print(f"squeal {row['mesh']}: {row['dofs']} DoFs, {row['seconds']} s, max "
              f"{100 * row['max_error']:.3f} %, median {100 * row['median_error']:.3f} %",
              flush=True)
        squeal_rows.append(row)
    write_csv(os.path.join(work, "squeal.csv"), squeal_rows)

    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    series = [("squeal degree %d" % p, [r for r in squeal_rows if r["degree"] == p], m)
              for p, m in ((2, "s-"), (3, "^-"), (4, "D-"))]
    series += [("CalculiX " + e, [r for r in ccx_rows if r["element"] == e], m)
               for e, m in (("C3D20R", "o--"), ("C3D8I", "v--"))]
    for label, sel, marker in series:
        ax.loglog([r["seconds"] for r in sel], [100 * r["max_error"] for r in sel],
                  marker, label=label)
    for t in TARGETS:
        ax.axhline(100 * t, color="k", lw=0.6, ls=":")
    png = os.path.join(here, "calculix_pareto.png")
    finish_pareto(fig, ax, png,
                  "Clamped disc (A3): squeal against CalculiX 2.20",
                  "largest frequency error below 20 kHz [%]",
                  xlabel="wall time of the run [s] (2 cores)")

    print("\n| code | mesh | DoFs | wall time [s] | largest error | median error |")
    print("|---|---|---|---|---|---|")
    for code, rows in (("CalculiX", ccx_rows), ("squeal", squeal_rows)):
        for r in rows:
            print(f"| {code} | {r['mesh']} | {r['dofs']} | {r['seconds']} | "
                  f"{100 * r['max_error']:.3f} % | {100 * r['median_error']:.3f} % |")
    print("\n| target | squeal | CalculiX C3D20R | CalculiX C3D8I |")
    print("|---|---|---|---|")
    for t in TARGETS:
        cells = []
        for rows in (squeal_rows, [r for r in ccx_rows if r["element"] == "C3D20R"],
                     [r for r in ccx_rows if r["element"] == "C3D8I"]):
            best = time_to(rows, t)
            cells.append(f"{best['seconds']} s ({best['mesh']}, {best['dofs']} DoFs)"
                         if best else "not reached")
        print(f"| {100 * t:g} % | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
