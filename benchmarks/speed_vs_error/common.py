"""Shared by the speed-against-error scripts: run squeal on a parameter text."""
import os
import subprocess
import sys
import time


def save_png(fig, path):
    """Writes FIG to PATH through a temporary name (an earlier plot is
    replaced only by a complete one)."""
    fig.savefig(path + ".tmp.png", dpi=130)
    os.replace(path + ".tmp.png", path)
    print("wrote", path)


def finish_pareto(fig, ax, path, title, ylabel,
                  xlabel="wall time of the run [s] (1 MPI rank)",
                  legend_size=8):
    """Labels, grids and lays out the error-against-time axes AX of FIG
    (log-log, errors in per cent) and saves the figure to PATH (save_png)."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(fontsize=legend_size)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    save_png(fig, path)


def run_squeal(squeal, body, out, ranks=1):
    """Writes BODY plus an Output subsection (directory OUT, overwrite, no
    mode shapes) to OUT.prm, runs SQUEAL on it (under mpirun -np RANKS when
    RANKS > 1) and returns (stdout, wall seconds); exits with squeal's
    output if it fails. A finished run is recorded in OUT.run.json (its
    parameter text, rank count, stdout and time); a later call with the same
    text and ranks whose output is still there returns that record instead
    of running again, so an interrupted benchmark resumes where it stopped."""
    import json
    prm = out + ".prm"
    text = body + f"""subsection Output
  set Directory = {out}
  set Overwrite = true
  set Mode shapes = none
end
"""
    record = out + ".run.json"
    if os.path.exists(record) and os.path.isdir(out):
        with open(record) as f:
            r = json.load(f)
        if r["prm"] == text and r["ranks"] == ranks:
            print(f"{out}: reusing the finished run ({r['seconds']:.0f} s)",
                  file=sys.stderr)
            return r["stdout"], r["seconds"]
    with open(prm, "w") as f:
        f.write(text)
    start = time.monotonic()
    command = [squeal, prm]
    if ranks > 1:
        command = ["mpirun", "-np", str(ranks)] + command
    r = subprocess.run(command, capture_output=True, text=True)
    seconds = time.monotonic() - start
    if r.returncode != 0:
        sys.exit(f"{out}: squeal failed\n{r.stdout}\n{r.stderr}")
    with open(record + ".tmp", "w") as f:
        json.dump(dict(prm=text, ranks=ranks, stdout=r.stdout, seconds=seconds), f)
    os.replace(record + ".tmp", record)
    return r.stdout, seconds


def single_point_sweep(first, first_value, second, second_value):
    """The Sweep subsection of a run at one point."""
    return f"""subsection Sweep
  set First parameter = {first}
  set First values = {first_value}
  set Second parameter = {second}
  set Second values = {second_value}
end
"""


def read_run(stdout, out):
    """(DoFs, [(freq_Hz, re_per_s)] sorted by frequency) of a finished run."""
    import csv
    import os
    import re
    dofs = int(re.search(r"(\d+) DoFs", stdout).group(1))
    with open(os.path.join(out, "eigenvalues.csv")) as f:
        modes = sorted((float(r["freq_Hz"]), float(r["re_per_s"]))
                       for r in csv.DictReader(f))
    return dofs, modes


def disc_mesh(degree, around, radial, thick):
    """The Mesh subsection: FE degree and the disc's cell counts."""
    return f"""subsection Mesh
  set Finite element degree = {degree}
  set Disc cells circumference = {around}
  set Disc cells radial = {radial}
  set Disc cells thickness = {thick}
end
"""


# verification.md A3: (name, Hz, multiplicity)
A3 = [("(0,0)", 1629.8, 1), ("(0,1)", 1638.5, 2), ("(0,2)", 1839.8, 2),
      ("(0,3)", 2557.6, 2), ("(0,4)", 3853.5, 2), ("(0,5)", 5611.7, 2),
      ("(0,6)", 7731.5, 2), ("(0,7)", 10146.9, 2), ("(0,8)", 12813.0, 2),
      ("(0,9)", 15696.4, 2), ("(0,10)", 18770.4, 2), ("(1,0)", 9669.8, 1),
      ("(1,1)", 9924.2, 2), ("(1,2)", 10703.9, 2), ("(1,3)", 12041.6, 2),
      ("(1,4)", 13954.6, 2), ("(1,5)", 16421.6, 2), ("(1,6)", 19380.9, 2),
      ("in-plane n=0", 6303.3, 1), ("in-plane n=1", 9515.5, 2),
      ("in-plane n=2", 14503.4, 2), ("in-plane n=3", 17988.6, 2)]
REFERENCE = sorted(f for _, f, m in A3 for _ in range(m))


def disc_errors(freqs):
    """Relative errors of the computed disc frequencies FREQS [Hz] against
    REFERENCE: the k-th lowest against the k-th of the A3 table expanded by
    multiplicity, over the 41 listed modes below 20 kHz; a run with fewer
    modes gets one more entry of 1.0 (a missed mode counts as 100 %)."""
    freqs = sorted(freqs)
    n = min(len(freqs), len(REFERENCE))
    errors = [abs(freqs[k] - REFERENCE[k]) / REFERENCE[k] for k in range(n)]
    if len(freqs) < len(REFERENCE):
        errors.append(1.0)
    return errors


def run_disc(squeal, work, degree, around, radial, thick, max_frequency, ranks=1):
    """One squeal run of the disc alone (full solver, friction and damping
    off) on a uniform mesh, solved to MAX_FREQUENCY [Hz] on RANKS MPI ranks;
    returns a dict with
    the mesh name, degree, DoFs, wall seconds, largest and median error
    (disc_errors) and the number of modes found."""
    import os
    import statistics
    name = f"d{degree}_{around}x{radial}x{thick}"
    out = os.path.join(work, name + (f"_np{ranks}" if ranks > 1 else ""))
    stdout, seconds = run_squeal(squeal, """subsection Scene
  set Type = disc
end
""" + disc_mesh(degree, around, radial, thick) + f"""subsection Eigensolver
  set Method = full
  set Minimum frequency = 900
  set Maximum frequency = {max_frequency}
end
subsection Damping
  set Alpha = 0
  set Beta = 0
end
""" + single_point_sweep("damping.alpha", 0, "damping.beta", 0), out,
                                 ranks)
    dofs, modes = read_run(stdout, out)
    errors = disc_errors([f for f, _ in modes])
    return dict(mesh=name, degree=degree, dofs=dofs, seconds=round(seconds, 1),
                max_error=max(errors), median_error=statistics.median(errors),
                modes=len(modes))
