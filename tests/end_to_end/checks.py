"""Shared by the end-to-end checks: named pass/fail lines, the exit code,
and running squeal on a parameter file that includes a base one."""
import os
import shutil
import subprocess
import sys
import threading
import time

_failures = []


def check(name, ok, detail="", show=False):
    """Prints `name: ok` (with the detail if show) or `name: FAILED detail`
    and records a failure."""
    shown = f" ({detail})" if show and detail else ""
    print(f"{name}: {'ok' + shown if ok else 'FAILED ' + str(detail)}")
    if not ok:
        _failures.append(name)


def finish():
    """Prints the verdict and exits 1 if any check failed."""
    print("all checks passed" if not _failures else
          f"CHECKS FAILED: {', '.join(_failures)}")
    sys.exit(1 if _failures else 0)


def pvd_loads(squeal, pvd, fields=()):
    """Opens PVD (a ParaView collection) through VTK's XML readers with
    squeal-check-pvd, built beside SQUEAL: every entry exists, loads, holds
    points and every point field of FIELDS. Returns (ok, what it said)."""
    tool = os.path.join(os.path.dirname(squeal), "squeal-check-pvd")
    r = subprocess.run([tool, pvd, *fields], capture_output=True, text=True)
    return r.returncode == 0, (r.stdout + r.stderr).strip()


def every_pvd_loads(squeal, out):
    """Stops the check unless every .pvd below the folder OUT (a finished
    run's) loads through VTK's XML readers (a .pvd without entries is
    allowed: Output/Mode shapes = none)."""
    for folder, _, files in os.walk(out):
        for f in sorted(files):
            if f.endswith(".pvd"):
                ok, said = pvd_loads(squeal, os.path.join(folder, f),
                                     ("--allow-empty",))
                if not ok:
                    print(f"FAILED: {said}")
                    sys.exit(1)


def run_squeal(squeal, base_prm, name, extra="", mpi=0):
    """Writes NAME.prm (include BASE_PRM, then EXTRA, then Output/Directory =
    NAME), runs squeal on it into a fresh folder NAME, under `mpirun -np MPI`
    if MPI; stops the check with the output on a non-zero exit. Returns
    (folder, standard output)."""
    out = os.path.abspath(name)
    shutil.rmtree(out, ignore_errors=True)
    with open(name + ".prm", "w") as f:
        f.write(f"include {base_prm}\n{extra}subsection Output\n"
                f"  set Directory = {out}\nend\n")
    launcher = ["mpirun", "-np", str(mpi)] if mpi else []
    r = subprocess.run(launcher + [squeal, name + ".prm"], capture_output=True,
                       text=True)
    if r.returncode != 0:
        print(f"FAILED: {name}: exit {r.returncode}\n{r.stdout[-3000:]}\n{r.stderr}")
        sys.exit(1)
    every_pvd_loads(squeal, out)
    return out, r.stdout


def full_solver_point(mu=0.5, f_max=None, e_pad=25e9, f_min=None,
                      names=("pad.E", "pad on disc.mu")):
    """Parameter-file text: the full solver at the single sweep point
    NAMES[0] = E_PAD and NAMES[1] = MU (default: the TriboBrake's pad
    modulus and friction coefficient at thesis Table 3.1's 25 GPa and 0.5),
    in the band F_MIN-F_MAX Hz where given."""
    band = (f"  set Minimum frequency = {f_min}\n" if f_min else "") + \
        (f"  set Maximum frequency = {f_max}\n" if f_max else "")
    return f"""subsection Eigensolver
  set Method = full
{band}end
subsection Sweep
  set First parameter = {names[0]}
  set First values = {e_pad:g}
  set Second parameter = {names[1]}
  set Second values = {mu}
end
"""


def run_watching(command, folder, every=0.002):
    """Runs COMMAND (a list) to its end while listing FOLDER every EVERY
    seconds. Returns (subprocess.CompletedProcess, the set of file names
    seen in FOLDER at any time)."""
    seen = set()
    with subprocess.Popen(command, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True) as p:
        out, err = [], []
        readers = [threading.Thread(target=lambda s=s, b=b: b.append(s.read()))
                   for s, b in ((p.stdout, out), (p.stderr, err))]
        for t in readers:
            t.start()
        while p.poll() is None:
            seen.update(os.listdir(folder))
            time.sleep(every)
        for t in readers:
            t.join()
    return subprocess.CompletedProcess(command, p.returncode, "".join(out),
                                       "".join(err)), seen


def run_table_point(squeal, base_prm, name, extra, mpi=0, watch=None):
    """Writes NAME.prm (include BASE_PRM, then EXTRA, then the full solver
    at the single point E_pad = 25 GPa, mu = 0.5 of thesis Table 3.1 and
    Output/Directory = NAME without mode shapes), runs squeal on it into a
    fresh folder NAME, under `mpirun -np MPI` if MPI. Returns (folder,
    subprocess.CompletedProcess); the caller judges the exit code. With
    WATCH (a folder), returns (folder, process, the file names seen in WATCH
    while it ran; run_watching())."""
    out = os.path.abspath(name)
    shutil.rmtree(out, ignore_errors=True)
    with open(name + ".prm", "w") as f:
        f.write(f"""include {base_prm}
{extra}{full_solver_point()}subsection Output
  set Directory = {out}
  set Mode shapes = none
end
""")
    launcher = ["mpirun", "-np", str(mpi)] if mpi else []
    if watch:
        r, seen = run_watching(launcher + [squeal, name + ".prm"], watch)
    else:
        r = subprocess.run(launcher + [squeal, name + ".prm"],
                           capture_output=True, text=True)
    if r.returncode == 0:
        every_pvd_loads(squeal, out)
    return (out, r, seen) if watch else (out, r)



def memory_estimate_holds(stdout, factor=2.):
    """Whether a run's estimate of its peak memory (the largest of its
    `Memory: U MB in use ...; estimated peak E MB` lines, printed after the
    set-up and by the first full solve after its count) lies within FACTOR
    of the peak it measured at its end (`Peak memory: P MB`), and is at
    least what was in use when it was printed. Returns (ok, detail)."""
    use = estimate = peak = None
    for line in stdout.splitlines():
        line = line.strip()
        if line.startswith("Memory: "):
            e = float(line.split("estimated peak ")[1].split()[0])
            if estimate is None or e > estimate:
                use, estimate = float(line.split()[1]), e
        elif line.startswith("Peak memory: "):
            peak = float(line.split()[2])
    if estimate is None or peak is None:
        return False, "no 'Memory: ... estimated peak' or 'Peak memory' line"
    ok = use <= estimate and peak / factor <= estimate <= peak * factor
    return ok, f"in use {use} MB, estimated peak {estimate} MB, peak {peak} MB"


def preload_summary(folder):
    """The key value lines of FOLDER/preload_summary.txt as a dict (numbers
    as floats, words as strings)."""
    summary = {}
    with open(os.path.join(folder, "preload_summary.txt")) as f:
        for row in f:
            key, _, value = row.partition(" ")
            try:
                summary[key] = float(value)
            except ValueError:  # a word: normal_contact_law
                summary[key] = value.strip()
    return summary


def check_brake_force_loop(folder, force, mu, what):
    """The preload of make_brake.py's brake in FOLDER: the force pair FORCE
    [N] on the piston and the caliper's bore presses both pads, so the
    normal force is 2 FORCE (1e-3: the soft axial springs carry the rest),
    and every node slides: friction MU times it (1e-6)."""
    summary = preload_summary(folder)
    fn = summary.get("normal_force_N", 0.)
    ft = summary.get("friction_force_N", 0.)
    check(f"{what}: normal force 2 F",
          abs(fn - 2 * force) < 1e-3 * 2 * force,
          f"normal force {fn:.6g} N, 2 F = {2 * force:.6g} N", show=True)
    check(f"{what}: every node slides, friction = mu x normal",
          fn > 0 and abs(ft - mu * fn) < 1e-6 * fn,
          f"friction {ft:.10g} N, {mu} x normal {mu * fn:.10g} N", show=True)


def make_brake(*options):
    """Runs scripts/make_brake.py --size coarse OPTIONS --out brake (in the
    current folder); stops the check unless it writes brake/brake.msh and
    brake/brake_scene.prm."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                          "..", "scripts", "make_brake.py")
    r = subprocess.run([sys.executable, script, "--size", "coarse",
                        *options, "--out", "brake"], capture_output=True,
                       text=True)
    ok = r.returncode == 0 and os.path.isfile("brake/brake.msh") and \
        os.path.isfile("brake/brake_scene.prm")
    check(" ".join(("make_brake.py",) + options) + " writes the brake", ok,
          r.stdout + r.stderr, show=True)
    if not ok:
        finish()
