#!/usr/bin/python3
"""End-to-end check of the modal damping (Damping/Modal damping ratios) on
modal_damping.prm: the coarse TriboBrake sweep with modal damping alone
(0.2 % at 1 kHz falling linearly to 0.05 % at 10 kHz, no Rayleigh damping).

usage: check_modal_damping.py SQUEAL PRM WORKDIR

Runs the program serially and with `mpirun -np 2`, then checks:
- both exit 0 (so the run's own reduced-against-full check and the
  certification of the near-threshold modes on the full model passed),
  their modes.pvd load in VTK, and the log states the modal damping;
- at mu = 0.01 the friction barely couples the modes, so every mode's
  damping ratio zeta = -Re lambda / |lambda| is the given ratio at its
  undamped frequency f / sqrt(1 - zeta^2) within 1e-3 (relative; the
  friction's own share is about 1e-5 here), for at least 100 rows;
- at mu = 0.7 there is an unstable region, and check_full.csv pairs every
  full eigenvalue with a reduced one within 1e-4 of |lambda|;
- the 2-rank run gives the serial eigenvalues within 1e-3 in frequency and
  2 % of |Re| + 1 1/s in growth rate (as check_run.py).
Exits non-zero on the first failure.
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import run_squeal  # noqa: E402

squeal, prm, work = sys.argv[1:4]
os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
os.makedirs(work, exist_ok=True)
os.chdir(work)


def fail(msg):
    print("FAILED:", msg)
    sys.exit(1)


def read(out, name):
    with open(os.path.join(out, name)) as f:
        return list(csv.DictReader(f))


def ratio(f):
    """The prm's ratios: 0.2 % at 1 kHz to 0.05 % at 10 kHz, linear."""
    if f <= 1000.:
        return 0.002
    if f >= 10000.:
        return 0.0005
    return 0.002 + (0.0005 - 0.002) * (f - 1000.) / 9000.


serial, log = run_squeal(squeal, prm, "serial")
if "Modal damping of the frictionless modes up to 25000 Hz" not in log:
    fail("the log does not state the modal damping")
ev = read(serial, "eigenvalues.csv")
weak = [r for r in ev if float(r["pad_on_disc.mu"]) == 0.01]
if len(weak) < 100:
    fail(f"only {len(weak)} eigenvalues at mu = 0.01")
worst = 0.
for r in weak:
    zeta, f = float(r["zeta"]), float(r["freq_Hz"])
    undamped = f / (1. - zeta * zeta) ** 0.5
    worst = max(worst, abs(zeta - ratio(undamped)) / ratio(undamped))
print(f"mu = 0.01: {len(weak)} modes, largest relative deviation of zeta "
      f"from the modal ratio {worst:.3g}")
if worst > 1e-3:
    fail(f"zeta deviates from the modal ratios by {worst:.3g} > 1e-3")

regions = read(serial, "unstable_regions.csv")
if not regions or any(float(r["pad_on_disc.mu"]) != 0.7 for r in regions):
    fail(f"expected unstable regions at mu = 0.7 only, got {regions}")
check = read(serial, "check_full.csv")
if not check:
    fail("check_full.csv is empty")
largest = max(float(r["lambda_rel_error"]) for r in check
              if r["reduced_freq_Hz"] != "")
if any(r["reduced_freq_Hz"] == "" for r in check) or largest > 1e-4:
    fail(f"reduced against full: unmatched pairs or error {largest:.3g}")
print(f"mu = 0.7: {len(regions)} unstable region(s); reduced against full "
      f"{largest:.3g} of |lambda| over {len(check)} pairs")

parallel, _ = run_squeal(squeal, prm, "np2", mpi=2)
ev2 = read(parallel, "eigenvalues.csv")
if len(ev2) != len(ev):
    fail(f"{len(ev2)} eigenvalues on 2 ranks, {len(ev)} serially")
for a, b in zip(ev, ev2):
    fa, fb = float(a["freq_Hz"]), float(b["freq_Hz"])
    ra, rb = float(a["re_per_s"]), float(b["re_per_s"])
    if abs(fa - fb) > 1e-3 * fa or abs(ra - rb) > 0.02 * abs(ra) + 1.:
        fail(f"np = 2 differs at point {a['point']} mode {a['mode']}: "
             f"{fa} / {fb} Hz, {ra} / {rb} 1/s")
print(f"np = 2: {len(ev2)} eigenvalues equal to the serial run: ok")
print("all checks passed")
