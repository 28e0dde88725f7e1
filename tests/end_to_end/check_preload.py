#!/usr/bin/python3
"""End-to-end check of the TriboBrake preload (Scene/Analysis = preload).

usage: check_preload.py SQUEAL PRM WORKDIR

Runs build/squeal on the coarse preload and checks:
- the memory estimate printed after the set-up (in use plus MUMPS's LU)
  within a factor 2 of the peak the run measures at its end;
- the output files (contact.csv, preload_summary.txt, contact.pvd,
  contact_surface.vtu, displacement.vtu, parameters.prm), contact.pvd's
  entries loading through VTK's reader, and the pressure map of
  scripts/plot_contact.py;
- equilibrium: the normal contact force equals the 100 N load (1e-8), the
  friction force is mu N (1e-10), and the support's springs, evaluated from
  the spring matrix alone, hold back the friction force (1e-6);
- the contact.csv rows: the pressures integrate to N within 10 % with the
  trapezoid rule on the nodal grid (an independent quadrature of the
  nodal pressure field), the friction traction field is mu p_N (steady
  sliding), and the pressure is highest at the leading edge (smallest y, where
  the disc enters) and falls row by row towards the trailing edge (thesis
  sec. 3.4);
- the normal contact law: the default is penalty (pressure = k_n x
  penetration, k_n = Interface/Normal stiffness): every node in contact
  penetrates, no separated node does, k_n times the nodal penetrations
  integrates (trapezoid rule) to N within 10 %, and the summary's largest
  penetration is contact.csv's; with `hard` no node in contact has a gap
  (1e-9 of the penalty's largest penetration), the whole trailing edge
  lifts, and at least as many nodes separate as with the compliant law
  (which spreads the contact);
- frictionless: no friction force, springs unloaded;
- 4 load steps: a contact table and a pad-face file per step, listed in
  contact.pvd, and the same final state as one step (steady sliding is
  path-independent);
- Coulomb stick/slip, disc at rest, 2 load steps: the semi-smooth Newton
  iteration converges (at most 15 iterations per step), its slip residual
  falls super-linearly once the sets stop changing (each step's ratio
  smaller than the one before, last residual below 1e-10), the normal force
  is 100 N and both stick and slip nodes exist;
- Coulomb with the disc turning 0.1 m per load step (a slip 10^4-10^5 x the
  elastic one): every node in contact slips, and the state is the steady
  sliding one (pressures and tractions within 0.5 % of the peak pressure,
  friction mu N within 1e-3, the springs hold it back within 1e-3);
- MPI: `mpirun -np 2` (MUMPS on the distributed structure) gives the serial
  run's pressures and tractions (1e-8 of the peak pressure), statuses and
  forces, for steady sliding and for Coulomb with the disc at rest;
- a second run into the same directory is refused.
"""
import csv
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import memory_estimate_holds, pvd_loads  # noqa: E402

squeal, prm, work = sys.argv[1:4]
prm = os.path.abspath(prm)
here = os.path.dirname(os.path.abspath(__file__))
plot = os.path.join(here, "..", "..", "scripts", "plot_contact.py")
os.makedirs(work, exist_ok=True)
os.chdir(work)


def fail(msg):
    print("FAILED:", msg)
    sys.exit(1)


def run(name, extra="", mpi=0):
    out = os.path.abspath(name)
    shutil.rmtree(out, ignore_errors=True)
    with open(name + ".prm", "w") as f:
        f.write(f"include {prm}\n{extra}subsection Output\n  set Directory = {out}\nend\n")
    launcher = ["mpirun", "-np", str(mpi)] if mpi else []
    r = subprocess.run(launcher + [squeal, name + ".prm"], capture_output=True,
                       text=True)
    if r.returncode != 0:
        fail(f"{name}: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
    run.stdout = r.stdout
    summary = {}
    for line in open(os.path.join(out, "preload_summary.txt")):
        k, v = line.split()
        try:
            summary[k] = float(v)
        except ValueError:  # a word: normal_contact_law
            summary[k] = v
    with open(os.path.join(out, "contact.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    return out, summary, rows


out, s, rows = run("sliding")
ok, said = memory_estimate_holds(run.stdout)
if not ok:
    fail(f"start-of-run memory estimate: {said}")
print(f"start-of-run memory estimate within 2x of the peak: ok ({said})")
for f in ["contact.csv", "preload_summary.txt", "contact.pvd",
          "contact_surface.vtu", "displacement.vtu", "parameters.prm"]:
    if not os.path.isfile(os.path.join(out, f)):
        fail(f"missing {f}")
ok, said = pvd_loads(squeal, os.path.join(out, "contact.pvd"))
if not ok:
    fail(f"contact.pvd does not load through VTK: {said}")
r = subprocess.run(["/usr/bin/python3", plot, out], capture_output=True, text=True)
if r.returncode != 0 or not os.path.isfile(os.path.join(out, "contact_pressure.png")):
    fail(f"plot_contact.py failed: {r.stderr}")
print("output files and pressure map: ok")

mu, N = 0.5, 100.
if abs(s["normal_force_N"] / N - 1) > 1e-8:
    fail(f"normal force {s['normal_force_N']}")
if abs(s["friction_force_N"] / (mu * N) - 1) > 1e-10:
    fail(f"friction force {s['friction_force_N']}")
if abs(s["spring_force_N"] / (mu * N) - 1) > 1e-6:
    fail(f"spring force {s['spring_force_N']} against friction {mu * N}")
print("equilibrium (normal force, friction = mu N, springs hold it back): ok")

xs = sorted({round(float(r["x_m"]), 9) for r in rows})
ys = sorted({round(float(r["y_m"]), 9) for r in rows})
p = {(round(float(r["x_m"]), 9), round(float(r["y_m"]), 9)): float(r["p_N_Pa"])
     for r in rows}
total = 0.
for i in range(len(xs) - 1):
    for j in range(len(ys) - 1):
        corners = [p[(xs[a], ys[b])] for a in (i, i + 1) for b in (j, j + 1)]
        total += (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]) * sum(corners) / 4
if abs(total / N - 1) > 0.10:
    fail(f"trapezoid integral of the nodal pressures {total} N, not {N} N")
p_peak = max(float(r["p_N_Pa"]) for r in rows)
for r in rows:
    if abs(float(r["t_T1_Pa"]) - mu * float(r["p_N_Pa"])) > 1e-6 * p_peak:
        fail("steady sliding: the friction traction field is not mu p_N")
slip = [r for r in rows if int(r["status"]) == 2]
if not slip:
    fail("no slipping node")
lead = min(ys)
peak = max(rows, key=lambda r: float(r["p_N_Pa"]))
if abs(float(peak["y_m"]) - lead) > 1e-9:
    fail(f"pressure peak at y = {peak['y_m']}, not at the leading edge {lead}")
row_mean = [sum(p[(x, y)] for x in xs) / len(xs) for y in ys]
if any(b >= a for a, b in zip(row_mean, row_mean[1:])):
    fail(f"the mean pressure of the rows does not fall from the leading to "
         f"the trailing edge: {row_mean}")
print(f"pressures integrate to {total:.2f} N; peak at the leading edge, "
      "falling towards the trailing edge: ok")

# The normal contact law: penalty (the default, k_n = Interface/Normal
# stiffness, the CEA interface's law) against hard.
k_n = 2.5895e12
if s["normal_contact_law"] != "penalty":
    fail(f"default normal contact law {s['normal_contact_law']}, not penalty")
pen = {key: -float(r["gap_m"]) if int(r["status"]) else 0.
       for key, r in zip(p, rows)}
if any(int(r["status"]) and float(r["gap_m"]) >= 0 for r in rows):
    fail("penalty: a node in contact without penetration")
if any(not int(r["status"]) and float(r["gap_m"]) < 0 for r in rows):
    fail("penalty: a separated node penetrates")
carried = 0.
for i in range(len(xs) - 1):
    for j in range(len(ys) - 1):
        corners = [pen[(xs[a], ys[b])] for a in (i, i + 1) for b in (j, j + 1)]
        carried += k_n * (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]) * sum(corners) / 4
if abs(carried / N - 1) > 0.10:
    fail(f"penalty: k_n x penetration integrates to {carried} N, not {N} N")
if abs(s["largest_penetration_m"] - max(pen.values())) > 1e-6 * max(pen.values()):
    fail(f"penalty: largest penetration {s['largest_penetration_m']} in the "
         f"summary, {max(pen.values())} in contact.csv")
outh, sh, rh = run("hard", "subsection Preload\n  set Normal contact law = hard\nend\n")
gap_scale = max(pen.values())
if sh["normal_contact_law"] != "hard" or abs(sh["normal_force_N"] / N - 1) > 1e-8:
    fail(f"hard: {sh}")
if any(int(r["status"]) and abs(float(r["gap_m"])) > 1e-9 * gap_scale for r in rh):
    fail("hard: a node in contact has a gap")
trailing = [r for r in rh if abs(float(r["y_m"]) - max(ys)) < 1e-9]
if any(int(r["status"]) != 0 for r in trailing):
    fail("hard: the trailing edge stays in contact")
open_pen = sum(not int(r["status"]) for r in rows)
open_hard = sum(not int(r["status"]) for r in rh)
if not 0 < open_pen <= open_hard:
    fail(f"separated nodes: penalty {open_pen}, hard {open_hard}")
print(f"normal contact law: penalty (default) k_n x penetration integrates to "
      f"{carried:.2f} N, largest penetration {gap_scale:.3e} m, {open_pen} "
      f"nodes separated; hard: no gap in contact, {open_hard} separated: ok")

_, s0, _ = run("frictionless", "subsection Preload\n  set Friction = frictionless\nend\n")
if abs(s0["friction_force_N"]) > 1e-12 or abs(s0["spring_force_N"]) > 1e-6:
    fail(f"frictionless: friction {s0['friction_force_N']}, springs {s0['spring_force_N']}")
if abs(s0["normal_force_N"] / N - 1) > 1e-8:
    fail(f"frictionless normal force {s0['normal_force_N']}")
print("frictionless: no friction, springs unloaded: ok")

out4, s4, _ = run("steps", "subsection Preload\n  set Load steps = 4\nend\n")
for k in range(1, 5):
    if not os.path.isfile(os.path.join(out4, f"contact_step_{k:03d}.csv")):
        fail(f"missing contact_step_{k:03d}.csv")
ok, said = pvd_loads(squeal, os.path.join(out4, "contact.pvd"))
if not ok or not said.startswith("contact.pvd: 4 entries load"):
    fail(f"contact.pvd does not list 4 load steps that load through VTK: {said}")
if abs(s4["normal_force_N"] / N - 1) > 1e-8 or s4["load_steps"] != 4:
    fail(f"4 steps: normal force {s4['normal_force_N']}")
if abs(s4["friction_force_N"] - s["friction_force_N"]) > 1e-8 * N:
    fail("steady sliding in 4 steps ends elsewhere than in one")
print("preload in 4 load steps: a table and a pad-face file per step, the "
      "same final state as in one step: ok")

# Coulomb stick/slip, disc at rest: per load step, the iterations and the
# slip residuals of the tail in which no node changes set.
_, sc, rc = run("coulomb", "subsection Preload\n  set Friction = coulomb\n"
                "  set Load steps = 2\nend\n")
steps, current = [], []
for line in run.stdout.splitlines():
    if "active-set iteration" in line:
        changed = int(line.split("), ")[1].split()[0])
        res = float(line.split("slip residual ")[1].split(",")[0])
        current.append((changed, res))
    elif "load factor 1 converged" in line:
        steps.append(current)
        current = []
if len(steps) != 2:
    fail(f"coulomb: {len(steps)} converged load steps, not 2")
for k, its in enumerate(steps):
    if len(its) > 15:
        fail(f"coulomb: load step {k + 1} took {len(its)} iterations (> 15)")
    tail = []
    for changed, res in reversed(its):
        if changed:
            break
        tail.insert(0, res)
    if tail[-1] > 1e-10:
        fail(f"coulomb: load step {k + 1} ends at slip residual {tail[-1]}")
    # residuals at rounding (< 1e-13) say nothing about the rate
    nonzero = [r for r in tail if r > 1e-13]
    ratios = [b / a for a, b in zip(nonzero, nonzero[1:])]
    if any(q2 >= q1 for q1, q2 in zip(ratios, ratios[1:])):
        fail(f"coulomb: load step {k + 1} residuals {tail} not super-linear")
    print(f"coulomb load step {k + 1}: {len(its)} iterations, slip residuals "
          f"of the fixed sets {', '.join(f'{r:.2e}' for r in tail)}")
status = [int(r["status"]) for r in rc]
if abs(sc["normal_force_N"] / N - 1) > 1e-8 or 1 not in status or 2 not in status:
    fail(f"coulomb: normal force {sc['normal_force_N']}, statuses {set(status)}")
print(f"coulomb, disc at rest: {status.count(1)} stick, {status.count(2)} slip, "
      "converged super-linearly: ok")

_, st, rt = run("coulomb_turning", "subsection Preload\n  set Friction = coulomb\n"
                "  set Load steps = 2\n  set Disc slip per step = 0.1\nend\n")
if any(int(a["status"]) != (2 if int(b["status"]) else 0) for a, b in zip(rt, rows)):
    fail("coulomb, disc turning: not every node in contact slips, or the "
         "contact zone differs from steady sliding")
worst = max(abs(float(a[k]) - float(b[k])) for a, b in zip(rt, rows)
            for k in ("p_N_Pa", "t_T1_Pa", "t_T2_Pa"))
if worst > 5e-3 * p_peak:
    fail(f"coulomb, disc turning: {worst / p_peak:.2e} of the peak pressure "
         "from steady sliding")
if abs(st["friction_force_N"] / (mu * N) - 1) > 1e-3 or \
        abs(st["spring_force_N"] / (mu * N) - 1) > 1e-3:
    fail(f"coulomb, disc turning: friction {st['friction_force_N']}, "
         f"springs {st['spring_force_N']}")
print(f"coulomb, disc turning 0.1 m per step: steady sliding within "
      f"{worst / p_peak:.1e} of the peak pressure: ok")

# MPI: the same states on 2 ranks.
for name, extra, serial_rows, serial_s in [
        ("sliding_np2", "", rows, s),
        ("coulomb_np2", "subsection Preload\n  set Friction = coulomb\n"
         "  set Load steps = 2\nend\n", rc, sc)]:
    out2, s2, r2 = run(name, extra, mpi=2)
    worst = max(abs(float(a[k]) - float(b[k])) for a, b in zip(r2, serial_rows)
                for k in ("p_N_Pa", "t_T1_Pa", "t_T2_Pa"))
    if len(r2) != len(serial_rows) or worst > 1e-8 * p_peak or \
            any(a["status"] != b["status"] for a, b in zip(r2, serial_rows)):
        fail(f"{name}: {worst / p_peak:.2e} of the peak pressure from the "
             "serial run, or other statuses")
    for key in ("normal_force_N", "friction_force_N", "spring_force_N"):
        if abs(s2[key] - serial_s[key]) > 1e-8 * N:
            fail(f"{name}: {key} {s2[key]} against {serial_s[key]} serial")
    if not os.path.isfile(os.path.join(out2, "displacement.vtu")):
        fail(f"{name}: no displacement.vtu")
    print(f"{name}: mpirun -np 2 = serial ({worst / p_peak:.1e} of the peak "
          "pressure): ok")

again = subprocess.run([squeal, "sliding.prm"], capture_output=True, text=True)
if again.returncode == 0 or "exists" not in again.stderr:
    fail("a second run into the same directory was not refused")
print("existing output refused: ok")
print("all checks passed")
