#!/usr/bin/python3
"""End-to-end check of the CEA about a braking run's contact state
(Scene/Analysis = preloaded cea, Preload/Contact state = braking history).

usage: check_cea_contact_history.py SQUEAL PRM WORKDIR

On the coarse TriboBrake at one point (E_pad = 25 GPa, mu = 0.5, full
solver), with contact histories written here on the pad nodes of a preload
run (every node separated in the first half of the samples, in contact,
stick or slip, in the second):
- with the window on the second half every pad node was in contact all the
  time: the interface is the whole pad face and the eigenvalues equal those
  of the plain CEA (an independent run) to 1e-8 of |lambda|;
- with every sample each node was in contact half of the time: the
  interface weight is 0.5 everywhere, so the eigenvalues equal those of the
  plain CEA with half the interface's normal stiffness (the stiffness and
  the friction coupling both scale with it, thesis eq. 3-1) to 1e-8, also
  under `mpirun -np 2`;
- a window without samples, a history of another scene (its nodes 1 m
  away) and a missing file each stop the run with one error naming the
  parameter or the file.
"""
import csv
import os
import subprocess
import sys

import h5py
import numpy as np

from checks import check, finish, run_table_point

squeal, prm, work = sys.argv[1:4]
prm = os.path.abspath(prm)
os.makedirs(work, exist_ok=True)
os.chdir(work)
K_N = 2.5895e12  # the TriboBrake's interface stiffness [N/m^3]
# OpenMPI refuses to start as root unless told (CI runs as root).
os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")


def run(name, extra, mpi=0, expect_ok=True):
    out, r = run_table_point(squeal, prm, name, extra, mpi)
    if expect_ok and r.returncode != 0:
        print(f"FAILED: {name}: exit {r.returncode}\n{r.stdout[-3000:]}\n{r.stderr}")
        sys.exit(1)
    if not expect_ok:
        return r
    with open(os.path.join(out, "eigenvalues.csv"), newline="") as f:
        lam = [complex(float(row["re_per_s"]), 2 * np.pi * float(row["freq_Hz"]))
               for row in csv.DictReader(f)]
    return lam, r.stdout


def distance(lam, ref):
    """Largest |lambda - lambda_ref| / |lambda_ref| over paired rows; 1 when
    the counts differ or nothing was found."""
    if len(lam) != len(ref) or not ref:
        return 1.
    return max(abs(a - b) / abs(b) for a, b in zip(lam, ref))


def history_state(window, interface_k_n=None):
    text = f"""subsection Scene
  set Analysis = preloaded cea
end
subsection Preload
  set Contact state = braking history
  set Contact history = {os.path.abspath('history.h5')}
  set Contact history window = {window}
end
"""
    return text


# the pad nodes: a frictionless preload keeps every one in contact
out, r = run_table_point(squeal, prm, "preload", """subsection Scene
  set Analysis = preload
end
subsection Preload
  set Friction = frictionless
end
""")
if r.returncode != 0:
    print(f"FAILED: preload: exit {r.returncode}\n{r.stdout[-3000:]}\n{r.stderr}")
    sys.exit(1)
with open(os.path.join(out, "contact.csv"), newline="") as f:
    xyz = np.array([[float(row[k]) for k in ("x_m", "y_m", "z_m")]
                    for row in csv.DictReader(f)])
check("pad nodes from the preload", len(xyz) >= 9, f"{len(xyz)} nodes")


def write_history(name, coordinates, n_samples=20, rate=1e5):
    """Every node separated in the first half of the samples, in contact
    (alternately stick and slip) in the second."""
    n = len(coordinates)
    status = np.zeros((n, n_samples), dtype=np.int32)
    status[:, n_samples // 2:] = 1 + np.arange(n_samples - n_samples // 2) % 2
    p_n = np.where(status > 0, 1e6, 0.)
    with h5py.File(name, "w") as f:
        f["coordinates"] = coordinates
        f["time"] = np.arange(n_samples) / rate
        f["p_N"] = p_n
        f["t_T1"] = 0.5 * p_n
        f["t_T2"] = np.zeros_like(p_n)
        f["slip_velocity"] = np.where(status == 2, 0.1, 0.)
        f["status"] = status
        f.attrs["sampling_rate"] = rate
        f.attrs["sliding_direction"] = np.array([0., 1., 0.])
        f.attrs["radial_direction"] = np.array([1., 0., 0.])
    return (n_samples - 1) / rate


t_end = write_history("history.h5", xyz)
plain, _ = run("plain", "subsection Scene\n  set Analysis = cea\nend\n")
half, _ = run("plain_half_k_n", f"""subsection Scene
  set Analysis = cea
end
subsection Interface
  set Normal stiffness = {K_N / 2}
end
""")
check("the plain CEA finds modes", len(plain) > 5, f"{len(plain)} modes")
check("halving k_n moves the eigenvalues", distance(half, plain) > 1e-4,
      f"{distance(half, plain):.2e}")

lam, log = run("window_in_contact", history_state(f"{t_end / 2}, {t_end}"))
check("window of full contact equals the plain CEA (1e-8)",
      distance(lam, plain) < 1e-8, f"{distance(lam, plain):.2e}", show=True)
check("the run reports the history's samples",
      "10 samples" in log and "mean fraction of time in contact 1" in log,
      log[-2000:])

lam, log = run("every_sample", history_state(""))
check("half the time in contact equals k_n / 2 (1e-8)",
      distance(lam, half) < 1e-8, f"{distance(lam, half):.2e}", show=True)
check("the run reports the mean fraction 0.5",
      "mean fraction of time in contact 0.5" in log, log[-2000:])
lam2, _ = run("every_sample_np2", history_state(""), mpi=2)
check("mpirun -np 2 gives the serial eigenvalues (1e-8)",
      distance(lam2, lam) < 1e-8, f"{distance(lam2, lam):.2e}", show=True)


def refused(name, extra, words):
    r = run(name, extra, expect_ok=False)
    said = r.stdout + r.stderr
    check(f"{name} refused", r.returncode != 0 and all(w in said for w in words),
          f"exit {r.returncode}: {said[-1500:]}")


refused("empty_window", history_state(f"{2 * t_end}, {3 * t_end}"),
        ["Preload/Contact history window", "no sample"])
write_history("history.h5", xyz + np.array([1., 0., 0.]))
refused("other_scene", history_state(""),
        ["Preload/Contact history", "do not cover"])
os.remove("history.h5")
refused("missing_file", history_state(""), ["history.h5"])
finish()
