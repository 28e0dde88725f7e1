#!/usr/bin/python3
"""End-to-end check of the braking simulation (Scene/Analysis = braking).

usage: check_braking.py SQUEAL SQUEAL_TRIBOLOGY PRM WORKDIR

Runs build/squeal on the coarse TriboBrake for 6 ms and checks:
- the output files (forces.csv, probes.csv, spectrum.csv, envelope.csv,
  summary.csv, contact_history.h5, transient.pvd, contact.pvd, animation.pvd,
  parameters.prm), every entry of the .pvd files loading through VTK's
  reader (squeal-check-pvd), and scripts/plot_braking.py;
- the memory estimate printed after the set-up within a factor 2 of the
  peak the run measures at its end;
- Coulomb's law in the sums: |F_T| <= mu F_N at every sample (1e-9), and
  F_T = mu F_N (1e-3: each node's slip direction follows the small
  transverse vibration velocities besides the disc's sliding) while every
  contact node slips (after the ramp, before any instability has grown);
- the mean normal force over the last 2 ms equals the 100 N load within 2 %
  (the momentum balance of a bounded motion);
- the summary's verdict fields and the time step below its limit;
- the contact history is read by squeal-tribology (damage per node);
- the matrix-free stiffness product gives the same run as the sparse one
  (forces to 1e-6 relative over the first 3 ms);
- MPI: `mpirun -np 2` (matrix-free) gives the serial matrix-free run's
  force history within 1e-8 of its largest value, and its probe history;
  the sparse product is refused under mpirun;
- restart: a run killed (SIGKILL) after its first checkpoint and continued
  with `squeal --resume DIR` writes the same forces.csv and probes.csv (17
  significant digits) as the uninterrupted run, bit for bit; before that, a
  plain rerun into its folder is refused and leaves the checkpoint intact
  (hash), a checkpoint with one damaged byte and an edited parameters.prm
  are refused by --resume; --resume of a finished run or of nothing is
  refused;
- SIGTERM during the time loop: the run writes a checkpoint, exits non-zero
  naming the step and publishes nothing; --resume then gives the
  uninterrupted run's forces.csv and probes.csv bit for bit;
- a grid (Transient/Grid) of mu = 0.3, 0.5 writes a folder per point and
  one stability table; each point runs at its own mu (F_T = mu F_N in full
  slip) and the mu = 0.5 point equals the single run (forces to 1e-12);
  scripts/plot_braking_grid.py draws stability_map.png;
- a time step above the stability limit is refused with the limit in the
  message; a second run into the same directory is refused.
"""
import csv
import hashlib
import os
import shutil
import signal
import subprocess
import sys
import time

from checks import check, finish, memory_estimate_holds, pvd_loads  # noqa: E402

squeal, tribology, prm, work = sys.argv[1:5]
prm = os.path.abspath(prm)
here = os.path.dirname(os.path.abspath(__file__))
plot = os.path.join(here, "..", "..", "scripts", "plot_braking.py")
os.makedirs(work, exist_ok=True)
os.chdir(work)


def run(name, extra="", expect_ok=True, mpi=0):
    out = os.path.abspath(name)
    if expect_ok:
        shutil.rmtree(out, ignore_errors=True)
    with open(name + ".prm", "w") as f:
        f.write(f"include {prm}\n{extra}subsection Output\n  set Directory = {out}\nend\n")
    launcher = ["mpirun", "-np", str(mpi)] if mpi else []
    r = subprocess.run(launcher + [squeal, name + ".prm"], capture_output=True, text=True)
    if expect_ok and r.returncode != 0:
        print(f"FAILED: {name}: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
        sys.exit(1)
    return out, r


def table(path):
    with open(path) as f:
        return list(csv.DictReader(l for l in f if not l.startswith("#")))


out, r = run("sparse")
ok, said = memory_estimate_holds(r.stdout)
check("the memory estimate after the set-up within 2x of the peak", ok, said,
      show=True)
files = ["forces.csv", "probes.csv", "spectrum.csv", "envelope.csv", "summary.csv",
         "contact_history.h5", "transient.pvd", "contact.pvd", "animation.pvd",
         "parameters.prm"]
check("output files", all(os.path.isfile(os.path.join(out, f)) for f in files))
for pvd, least in (("transient.pvd", 3), ("contact.pvd", 3), ("animation.pvd", 4)):
    ok, said = pvd_loads(squeal, os.path.join(out, pvd))
    n = int(said.split(": ")[1].split()[0]) if ok else 0
    check(f"{pvd}: at least {least} entries, each loads through VTK's reader",
          ok and n >= least, said)

forces = table(os.path.join(out, "forces.csv"))
mu, load = 0.5, 100.
excess = max(abs(float(r["tangential_force_N"])) - mu * float(r["normal_force_N"]) for r in forces)
check("|F_T| <= mu F_N at every sample", excess <= 1e-9 * load, f"excess {excess}")
steady = [r for r in forces if 2.2e-3 <= float(r["time_s"]) <= 3e-3 and int(r["n_stick"]) == 0
          and float(r["normal_force_N"]) > 0]
err = max(abs(float(r["tangential_force_N"]) - mu * float(r["normal_force_N"])) for r in steady)
check("F_T = mu F_N while every contact node slips (1e-3)",
      len(steady) > 10 and err <= 1e-3 * mu * load,
      f"{len(steady)} samples, error {err}")
late = [float(r["normal_force_N"]) for r in forces if float(r["time_s"]) >= 4e-3]
mean = sum(late) / len(late)
check("mean normal force over the last 2 ms = load (2 %)", abs(mean - load) <= 0.02 * load,
      f"mean {mean}")

summary = {r["quantity"]: r["value"] for r in table(os.path.join(out, "summary.csv"))}
check("summary: verdict and growth fields",
      all(k in summary for k in ("verdict", "dominant_frequency_Hz", "growth_rate_per_s",
                                 "separated", "leading_edge_p_max_over_mean")))
check("time step below its stability limit",
      0 < float(summary["time_step_s"]) <= float(summary["critical_time_step_s"]))
probes = table(os.path.join(out, "probes.csv"))
check("probes.csv has every sample", len(probes) == len(forces) and len(probes) > 1000)

r = subprocess.run(["/usr/bin/python3", plot, out], capture_output=True, text=True)
check("plot_braking.py writes braking.png",
      r.returncode == 0 and os.path.isfile(os.path.join(out, "braking.png")), r.stderr)

with open("tribology.prm", "w") as f:
    f.write(f"subsection Contact history\n  set File = {out}/contact_history.h5\nend\n"
            "subsection Images\n  set Files =\nend\n"
            f"subsection Output\n  set Directory = {os.path.abspath('tribology')}\n"
            "  set Overwrite = true\nend\n")
r = subprocess.run([tribology, "tribology.prm"], capture_output=True, text=True)
damage = os.path.join("tribology", "damage.csv")
ok = r.returncode == 0 and os.path.isfile(damage)
check("squeal-tribology reads the contact history", ok, r.stdout[-2000:] + r.stderr[-2000:])
if ok:
    rows = table(damage)
    check("a damage row per pad-face node (25)", len(rows) == 25, str(len(rows)))

mf, _ = run("matrix_free", "subsection Transient\n  set Stiffness product = matrix-free\n"
            "  set End time = 0.003\nend\n")
f2 = table(os.path.join(mf, "forces.csv"))
diff = max(abs(float(a["normal_force_N"]) - float(b["normal_force_N"]))
           for a, b in zip(forces, f2) if float(a["time_s"]) <= 3e-3)
check("matrix-free run = sparse run (1e-6 of the load)", diff <= 1e-6 * load, f"diff {diff}")

mf_text = "subsection Transient\n  set Stiffness product = matrix-free\n  set End time = 0.003\nend\n"
par, _ = run("matrix_free_np2", mf_text, mpi=2)
f3 = table(os.path.join(par, "forces.csv"))
for key in ("normal_force_N", "tangential_force_N", "radial_force_N"):
    scale = max(abs(float(a[key])) for a in f2)
    d = max(abs(float(a[key]) - float(b[key])) for a, b in zip(f2, f3))
    check(f"mpirun -np 2 = serial: {key} (1e-8 of its largest value)",
          len(f3) == len(f2) and d <= 1e-8 * scale, f"diff {d}, scale {scale}")
p2 = table(os.path.join(mf, "probes.csv"))
p3 = table(os.path.join(par, "probes.csv"))
scale = max(abs(float(a["u_z_m"])) for a in p2)
d = max(abs(float(a["u_z_m"]) - float(b["u_z_m"])) for a, b in zip(p2, p3))
check("mpirun -np 2 = serial: probe displacement (1e-8)", d <= 1e-8 * scale, f"diff {d}")
_, r = run("sparse_np2", "", expect_ok=False, mpi=2)
check("the sparse product is refused under mpirun",
      r.returncode != 0 and "use matrix-free under mpirun" in r.stderr, r.stderr[-500:])

# A grid of two braking runs.
grid_plot = os.path.join(here, "..", "..", "scripts", "plot_braking_grid.py")
grid, _ = run("grid", "subsection Transient\n  set Grid = true\n  set End time = 0.003\nend\n"
              "subsection Sweep\n  set First parameter = pad.E\n"
              "  set First values = 25.1e9\n  set Second parameter = pad on disc.mu\n"
              "  set Second values = 0.3, 0.5\nend\n")
stab = table(os.path.join(grid, "stability_table.csv"))
check("stability table: a row per point with its parameters",
      len(stab) == 2 and [float(r["pad_on_disc.mu"]) for r in stab] == [0.3, 0.5]
      and all(float(r["pad.E_Pa"]) == 25.1e9 for r in stab)
      and all(r["verdict"] and not r["verdict"].startswith("failed") for r in stab), str(stab))
for r, m in zip(stab, (0.3, 0.5)):
    pf = table(os.path.join(grid, r["folder"], "forces.csv"))
    slip = [x for x in pf if 2.2e-3 <= float(x["time_s"]) <= 3e-3 and int(x["n_stick"]) == 0
            and float(x["normal_force_N"]) > 0]
    e = max(abs(float(x["tangential_force_N"]) - m * float(x["normal_force_N"])) for x in slip)
    check(f"grid point mu = {m}: F_T = mu F_N in full slip", len(slip) > 10 and e <= 1e-3 * m * load,
          f"{len(slip)} samples, error {e}")
pf = table(os.path.join(grid, stab[1]["folder"], "forces.csv"))
d = max(abs(float(a["normal_force_N"]) - float(b["normal_force_N"])) for a, b in zip(forces, pf))
check("grid point mu = 0.5 = the single run", len(pf) > 100 and d <= 1e-12 * load, f"diff {d}")
r = subprocess.run(["/usr/bin/python3", grid_plot, grid], capture_output=True, text=True)
check("plot_braking_grid.py writes stability_map.png",
      r.returncode == 0 and os.path.isfile(os.path.join(grid, "stability_map.png")), r.stderr)

# Restart: kill a run right after its first checkpoint, resume it.
def fresh_run(name, interval):
    """NAME.prm: the coarse run into a fresh folder NAME, checkpoints every
    INTERVAL steps; returns the folder's absolute path."""
    folder = os.path.abspath(name)
    for d in (folder, folder + ".partial"):
        shutil.rmtree(d, ignore_errors=True)
    with open(name + ".prm", "w") as f:
        f.write(f"include {prm}\nsubsection Transient\n  set Checkpoint interval = "
                f"{interval}\nend\nsubsection Output\n  set Directory = {folder}\nend\n")
    return folder


killed = fresh_run("killed", 1000)
state = os.path.join(killed + ".partial", "checkpoint", "latest")
proc = subprocess.Popen([squeal, "killed.prm"], stdout=subprocess.DEVNULL,
                        stderr=subprocess.DEVNULL)
while proc.poll() is None and not os.path.exists(state):
    time.sleep(0.002)
proc.kill()
proc.wait()
check("a run is killed after its first checkpoint",
      os.path.exists(state) and not os.path.exists(killed))


def digest(folder):
    h = hashlib.sha256()
    for root, dirs, files in sorted(os.walk(folder)):
        dirs.sort()
        for name in sorted(files):
            with open(os.path.join(root, name), "rb") as fh:
                h.update(name.encode() + fh.read())
    return h.hexdigest()


before = digest(killed + ".partial")
r = subprocess.run([squeal, "killed.prm"], capture_output=True, text=True)
check("a plain rerun over a stopped run's checkpoint is refused",
      r.returncode != 0 and "--resume" in r.stderr, r.stderr)
check("the refused rerun leaves the checkpoint as it was",
      digest(killed + ".partial") == before)
with open(state) as fh:
    step = fh.read().split()[0]
state_bin = os.path.join(killed + ".partial", "checkpoint", f"state.{step}.0.bin")
with open(state_bin, "rb") as fh:
    good = fh.read()
damaged = bytearray(good)
damaged[len(damaged) // 2] ^= 0x40
with open(state_bin, "wb") as fh:
    fh.write(damaged)
r = subprocess.run([squeal, "--resume", "killed"], capture_output=True, text=True)
check("--resume of a checkpoint with a damaged byte is refused",
      r.returncode != 0 and "CRC-32" in r.stderr and not os.path.exists(killed), r.stderr)
with open(state_bin, "wb") as fh:
    fh.write(good)
used = os.path.join(killed + ".partial", "parameters.prm")
with open(used) as fh:
    original = fh.read()
with open(used, "w") as fh:
    fh.write(original.replace("set Normal force", "set Normal force = 150 #", 1))
r = subprocess.run([squeal, "--resume", "killed"], capture_output=True, text=True)
check("--resume after parameters.prm was edited is refused",
      r.returncode != 0 and "differs from the parameters the run started with" in r.stderr,
      r.stderr)
with open(used, "w") as fh:
    fh.write(original)
r = subprocess.run([squeal, "--resume", "killed"], capture_output=True, text=True)
check("squeal --resume continues it", r.returncode == 0 and "resumed at step" in r.stdout,
      r.stdout[-1000:] + r.stderr)
for name in ("forces.csv", "probes.csv"):
    with open(os.path.join(out, name)) as a, open(os.path.join(killed, name)) as b:
        check(f"resumed {name} = uninterrupted {name}, bit for bit", a.read() == b.read())
check("the checkpoint is removed at the end",
      not os.path.exists(os.path.join(killed, "checkpoint")))

# SIGTERM in the time loop: a checkpoint, a clear stop, then --resume.
termed = fresh_run("termed", 0)
proc = subprocess.Popen([squeal, "termed.prm"], stdout=subprocess.PIPE,
                        stderr=subprocess.PIPE, text=True)
for line in proc.stdout:
    if line.startswith("Time loop"):
        break
time.sleep(0.5)
proc.send_signal(signal.SIGTERM)
_, err = proc.communicate()
check("SIGTERM stops the run with a non-zero exit naming the step",
      proc.returncode != 0 and "SIGTERM received" in err and "--resume" in err, err)
check("the stopped run publishes nothing and leaves a checkpoint",
      not os.path.exists(termed)
      and os.path.exists(os.path.join(termed + ".partial", "checkpoint", "latest")))
r = subprocess.run([squeal, "--resume", "termed"], capture_output=True, text=True)
check("squeal --resume continues the SIGTERM-stopped run", r.returncode == 0, r.stderr)
for name in ("forces.csv", "probes.csv"):
    with open(os.path.join(out, name)) as a, open(os.path.join(termed, name)) as b:
        check(f"SIGTERM + resume: {name} = uninterrupted {name}, bit for bit",
              a.read() == b.read())

r = subprocess.run([squeal, "--resume", "killed"], capture_output=True, text=True)
check("--resume of a finished run is refused",
      r.returncode != 0 and "holds a finished run" in r.stderr, r.stderr)
r = subprocess.run([squeal, "--resume", "nowhere"], capture_output=True, text=True)
check("--resume of nothing is refused",
      r.returncode != 0 and "no run in progress" in r.stderr, r.stderr)

_, r = run("too_large", "subsection Transient\n  set Time step = 1e-5\nend\n", expect_ok=False)
check("a time step above the limit is refused",
      r.returncode != 0 and "exceeds the stability limit" in r.stderr, r.stderr)
_, r = run("sparse", expect_ok=False)
check("an existing output directory is refused",
      r.returncode != 0 and "exists" in r.stderr, r.stderr)
finish()
