#!/usr/bin/python3
"""The default mesh of prm/tribobrake_cea.prm against the uniform ones.

usage: /usr/bin/python3 benchmarks/speed_vs_error/run_default_mesh.py [SQUEAL] [WORKDIR]

At the default sweep's first point (E_pad = 1 GPa, mu = 0.01, where the
tolerance-driven mesh is chosen), full solver, band 900-20 000 Hz:
  uniform_d2      degree 2, disc 64 x 10 x 2, pad 4 x 4 x 2, support 4 x 4 x 10
                  (the CEA issue's default mesh)
  uniform_d2_ps   degree 2, the same disc, pad 8 x 8 x 4, support 8 x 8 x 20
  tolerance_d3    the Mesh subsection of prm/tribobrake_cea.prm: degree 3,
                  disc 32 x 4 x 1, refined until every estimate < 0.5 %
  reference_d4    degree 4, disc 48 x 6 x 1, pad and support as the default
                  (114 483 DoFs, about 22 min and 16 GB)
  fine_pad_support  degree 3 from the tolerance start, band 1.5-9.1 kHz,
                  tolerance 0.05 %, one refinement cycle (fraction 0.1): its
                  degree-4 partners on the refined mesh are the reference of
                  the pad and support modes, which reference_d4 leaves on the
                  default pad and support cells
uniform_d2_ps and tolerance_d3 run a second time under mpirun -np 2
(NAME_np2): their wall times in the table's last column, their largest
error beside it.
Each run's k-th mode is compared with the reference's k-th (both sorted by
frequency; the runs find the same number of modes in the band), error
|lambda - lambda_ref| / |lambda_ref| on the complex eigenvalue. For the
tolerance run each mode is also paired through its own degree-4 partner
(adaptive_modes.csv, matched by shape) with the nearest reference
eigenvalue, and its true error is set beside its estimate. Prints Markdown
tables and writes default_mesh_pareto.png beside this script. A run whose
WORKDIR/NAME/eigenvalues.csv, NAME.stdout and NAME.seconds exist is read,
not rerun.
"""
import csv
import math
import os
import statistics
import sys

from common import finish_pareto, run_squeal, single_point_sweep

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..", "..")
squeal = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "squeal")
work = sys.argv[2] if len(sys.argv) > 2 else "/tmp/squeal_default_mesh"


def mesh(degree, disc, pad=(4, 2), support=10, extra=""):
    return f"""subsection Mesh
  set Finite element degree = {degree}
  set Disc cells circumference = {disc[0]}
  set Disc cells radial = {disc[1]}
  set Disc cells thickness = {disc[2]}
  set Pad cells side = {pad[0]}
  set Pad cells thickness = {pad[1]}
  set Support cells length = {support}
{extra}end
"""


def eigensolver(low, high):
    return f"""subsection Eigensolver
  set Method = full
  set Minimum frequency = {low}
  set Maximum frequency = {high}
end
"""


TOLERANCE = """  set Frequency tolerance = {}
  set Adaptive cycles = {}
  set Refinement fraction = {}
"""
RUNS = {
    "uniform_d2": mesh(2, (64, 10, 2)) + eigensolver(900, 20000),
    "uniform_d2_ps": mesh(2, (64, 10, 2), (8, 4), 20) + eigensolver(900, 20000),
    "tolerance_d3": mesh(3, (32, 4, 1), extra=TOLERANCE.format(0.005, 3, 0.05))
    + eigensolver(900, 20000),
    "reference_d4": mesh(4, (48, 6, 1)) + eigensolver(900, 20000),
    "fine_pad_support": mesh(3, (32, 4, 1), extra=TOLERANCE.format(5e-4, 1, 0.1))
    + eigensolver(1500, 9100),
}


def lam(freq, re):
    return complex(float(re), 2 * math.pi * float(freq))


def run(name, ranks=1):
    """(DoFs of the final mesh, wall seconds, sorted eigenvalues, output
    dir, the adaptive cycles' full-solve seconds)."""
    out = os.path.join(work, name + ("_np2" if ranks == 2 else ""))
    if not all(os.path.exists(p) for p in (os.path.join(out, "eigenvalues.csv"),
                                           out + ".stdout", out + ".seconds")):
        print(f"running {name} ...", flush=True)
        stdout, seconds = run_squeal(
            squeal, "subsection Scene\n  set Type = tribobrake\nend\n"
            + RUNS[name] + single_point_sweep("pad.E", 1e9,
                                              "pad on disc.mu", 0.01),
            out, ranks)
        with open(out + ".stdout", "w") as f:
            f.write(stdout)
        with open(out + ".seconds", "w") as f:
            f.write(f"{seconds:.1f}\n")
    with open(out + ".stdout") as f:
        stdout = f.read()
    with open(out + ".seconds") as f:
        seconds = float(f.read())
    dofs = [int(line.split(" DoFs")[0].split()[-1]) for line in stdout.splitlines()
            if " DoFs" in line and ("Mesh:" in line or "Adaptive cycle" in line)]
    with open(os.path.join(out, "eigenvalues.csv")) as f:
        modes = sorted((lam(r["freq_Hz"], r["re_per_s"]) for r in csv.DictReader(f)),
                       key=lambda z: z.imag)
    solves = [float(line.split("full solve ")[1].split(" s")[0])
              for line in stdout.splitlines()
              if line.startswith("Adaptive cycle") and "full solve " in line]
    return dofs[-1], seconds, modes, out, solves


def partners(out):
    """The last cycle's rows of adaptive_modes.csv: (lambda, estimate,
    degree + 1 partner)."""
    with open(os.path.join(out, "adaptive_modes.csv")) as f:
        rows = list(csv.DictReader(f))
    last = max(int(r["cycle"]) for r in rows)
    return [(lam(r["freq_Hz"], r["re_per_s"]),
             float(r["estimated_relative_error"]),
             lam(r["estimate_partner_freq_Hz"], r["estimate_partner_re_per_s"]))
            for r in rows if int(r["cycle"]) == last]


def errors_by_rank(modes, ref):
    if len(modes) != len(ref):
        sys.exit(f"{len(modes)} modes against {len(ref)} in the reference: "
                 "the band edges differ, pair them by hand")
    return [abs(m - r) / abs(r) for m, r in zip(modes, ref)]


def main():
    os.makedirs(work, exist_ok=True)
    runs = {name: run(name) for name in RUNS}
    np2 = {name: run(name, 2) for name in ("uniform_d2_ps", "tolerance_d3")}
    ref = runs["reference_d4"][2]
    print("| mesh | DoFs | wall time [s] | modes | largest error | median error "
          "| at | np = 2: wall time [s], largest error |")
    print("|---|---|---|---|---|---|---|---|")
    points = []
    solve_point = None
    for name in ("uniform_d2", "uniform_d2_ps", "tolerance_d3", "reference_d4"):
        dofs, seconds, modes, _, solves = runs[name]
        if name == "reference_d4":
            print(f"| {name} | {dofs} | {seconds:.0f} | {len(modes)} | reference "
                  "| | | |")
            continue
        e = errors_by_rank(modes, ref)
        k = max(range(len(e)), key=e.__getitem__)
        parallel = ""
        if name in np2:
            _, seconds2, modes2, _, _ = np2[name]
            parallel = (f"{seconds2:.0f}, "
                        f"{100 * max(errors_by_rank(modes2, ref)):.3f} %")
        print(f"| {name} | {dofs} | {seconds:.0f} | {len(modes)} | "
              f"{100 * max(e):.3f} % | {100 * statistics.median(e):.3f} % | "
              f"{modes[k].imag / 2 / math.pi:.0f} Hz | {parallel} |")
        points.append((name, dofs, seconds, max(e), statistics.median(e)))
        if solves:
            print(f"| {name}: its final solve alone, without the estimate | {dofs} | "
                  f"{solves[-1]:.0f} | | | | | |")
            solve_point = (solves[-1], max(e))

    # the tolerance run's estimates against its true errors
    fine = partners(runs["fine_pad_support"][3])
    print("\n| mode [Hz] | estimate | true (reference_d4) | true / estimate "
          "| true (fine_pad_support) | true / estimate |")
    print("|---|---|---|---|---|---|")
    worst = {"ref": 0., "fine": 0.}
    for z, estimate, partner in partners(runs["tolerance_d3"][3]):
        r = min(ref, key=lambda y: abs(y - partner))
        true_ref = abs(z - r) / abs(r)
        cells = [f"{z.imag / 2 / math.pi:.1f}", f"{100 * estimate:.3f} %",
                 f"{100 * true_ref:.3f} %",
                 f"{true_ref / estimate:.2f}" if estimate > 1e-5 else "-"]
        if estimate > 1e-5:
            worst["ref"] = max(worst["ref"], true_ref / estimate)
        # paired through the degree-4 partners (the default cells' and the
        # refined mesh's), which differ far less than neighbouring modes
        if 1500 < z.imag / 2 / math.pi < 9100:
            _, _, fine_partner = min(fine, key=lambda row: abs(row[2] - partner))
            true_fine = abs(z - fine_partner) / abs(fine_partner)
            cells += [f"{100 * true_fine:.3f} %",
                      f"{true_fine / estimate:.2f}" if estimate > 1e-5 else "-"]
            if estimate > 1e-5:
                worst["fine"] = max(worst["fine"], true_fine / estimate)
        else:
            cells += ["", ""]
        print("| " + " | ".join(cells) + " |")
    print(f"\nlargest true / estimate: {worst['ref']:.2f} (reference_d4), "
          f"{worst['fine']:.2f} (fine_pad_support, 1.5-9.1 kHz)")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for name, dofs, seconds, largest, median in points:
        ax.loglog(seconds, 100 * largest, "o", color="C0")
        ax.loglog(seconds, 100 * median, "s", color="C1")
        ax.annotate(f"{name}\n{dofs} DoFs", (seconds, 100 * largest),
                    textcoords="offset points", xytext=(6, 4), fontsize=8)
    if solve_point:
        ax.loglog(solve_point[0], 100 * solve_point[1], "o", mfc="none",
                  color="C0", label="tolerance_d3: its solve alone, without "
                  "the estimate")
    ax.set_xlim(100, 2000)
    ax.set_ylim(0.05, 4)
    ax.axhline(0.5, color="grey", ls="--", lw=1)
    ax.plot([], [], "o", color="C0", label="largest error in the band")
    ax.plot([], [], "s", color="C1", label="median error")
    finish_pareto(fig, ax, os.path.join(here, "default_mesh_pareto.png"),
                  "TriboBrake, E_pad = 1 GPa, mu = 0.01, 0.9-20 kHz",
                  "eigenvalue error against degree 4 [%]")


if __name__ == "__main__":
    main()
