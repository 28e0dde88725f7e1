#!/usr/bin/python3
"""End-to-end check of build/squeal on coarse_sweep.prm (or other_pair.prm).

usage: check_run.py SQUEAL PRM WORKDIR [--other-pair]

With --other-pair (other_pair.prm: spring stiffness against support density)
it runs serially only and checks the extra columns of the swept parameters,
the headers named after them, the values of the log-spaced axis, the reduced
solver against the full one at the run's check points (0.1 % in frequency,
2 % of |Re| + 1 in growth rate, from check_full.csv) and the plots.

Runs the program serially and with `mpirun -np 2`, then checks:
- the output files of the CEA contract exist, with the contract's header;
- every eigenvalue row is consistent (freq > 0, zeta = -re/|lambda|,
  unstable = re > tolerance) and no eigenvalue is unstable at mu = 0.01;
- each unstable region's rows are unstable in eigenvalues.csv;
- the 2-rank run gives the same eigenvalues as the serial one within the
  reduced solver's accuracy (0.1 % in frequency, 2 % of |Re| + 1 1/s in
  growth rate: the basis of each run comes from its own SLEPc solves, and
  the modes at the top of the band are where the reduced model is least
  accurate; the full solver's 1e-8 agreement is tested in
  cea_tribobrake_coarse.mpirun=2);
- every entry of modes.pvd (serial and 2 ranks) loads through VTK's XML
  readers (squeal-check-pvd): the .pvtu and its pieces exist, hold points
  and both mode fields;
- with a frequency tolerance (the mesh check's full solve of the first
  point) the reduced basis takes that solve's symmetric modes for its
  first sample, which has the same mass and stiffness, instead of solving
  again: the run says so, and its eigenvalues are the serial run's to
  1e-5 of |lambda| (the same modes from another SLEPc run, whose
  eigenvectors agree to the eigensolver's tolerance and a doublet's pair
  within its plane; the reduced eigenvalues follow such changes of the
  basis at about 3e-7 here, below the reduced model's own error);
- before each basis sample's undamped eigensolve the run estimates its
  memory for the inertia count's modes: at least what is in use and
  within 2x of the run's peak;
- plot_cea.py makes its three PNG files.
Exits non-zero on the first failure.
"""
import csv
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import pvd_loads  # noqa: E402

squeal, prm, work = sys.argv[1:4]
other_pair = sys.argv[4:] == ["--other-pair"]
here = os.path.dirname(os.path.abspath(__file__))
plot = os.path.join(here, "..", "..", "scripts", "plot_cea.py")
HEADER = "point,pad.E_Pa,pad_on_disc.mu,mode,re_per_s,freq_Hz,zeta,unstable,track"
REGIONS = ("pad_on_disc.mu,pad.E_min_Pa,pad.E_max_Pa,freq_min_Hz,freq_max_Hz,"
           "max_re_per_s,track")


def fail(msg):
    print("FAILED:", msg)
    sys.exit(1)


def run(cmd, out, extra=""):
    shutil.rmtree(out, ignore_errors=True)
    with open(out + ".prm", "w") as f:
        f.write(f"include {prm}\n{extra}subsection Output\n"
                f"  set Directory = {out}\nend\n")
    r = subprocess.run(cmd + [out + ".prm"], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"{' '.join(cmd)} exited {r.returncode}:\n{r.stdout}\n{r.stderr}")
    return r.stdout


def distance(ev, ev2):
    """Largest |lambda - lambda_2| / |lambda| over the paired rows."""
    worst = 0.
    for a, b in zip(ev, ev2):
        la = complex(float(a["re_per_s"]), 2 * math.pi * float(a["freq_Hz"]))
        lb = complex(float(b["re_per_s"]), 2 * math.pi * float(b["freq_Hz"]))
        worst = max(worst, abs(la - lb) / abs(la))
    return worst


def rows(out, header_expected=HEADER):
    with open(os.path.join(out, "eigenvalues.csv")) as f:
        header = f.readline().strip()
        if header != header_expected:
            fail(f"eigenvalues.csv header is '{header}'")
    with open(os.path.join(out, "eigenvalues.csv")) as f:
        return list(csv.DictReader(f))


# OpenMPI refuses to start as root unless told (CI runs as root).
os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
def pvd_entries_load(out):
    """Every DataSet of modes.pvd loads through VTK's XML readers
    (squeal-check-pvd) with points and the mode_real / mode_imag fields."""
    ok, said = pvd_loads(squeal, os.path.join(out, "modes.pvd"),
                         ("mode_real", "mode_imag"))
    if not ok:
        fail(said)
    print(f"{said} through VTK's reader: ok")


def plots(out):
    r = subprocess.run(["/usr/bin/python3", plot, out], capture_output=True,
                       text=True)
    for png in ("frequency_vs_modulus.png", "locus.png", "stability_map.png"):
        if r.returncode != 0 or not os.path.exists(os.path.join(out, png)):
            fail(f"plot_cea.py did not make {png}: {r.stderr}")
    print("plots: ok")


def check_other_pair():
    out = os.path.join(work, "other_pair")
    run([squeal], out)
    ev = rows(out, "point,support_springs.k_N_per_m,support.rho_kg_per_m3,"
              "mode,re_per_s,freq_Hz,zeta,unstable,track")
    springs = sorted({float(r["support_springs.k_N_per_m"]) for r in ev})
    expected = [2e6 * (5e7 / 2e6) ** (i / 4) for i in range(5)]
    if len(springs) != 5 or any(abs(a - b) > 1e-9 * b
                                for a, b in zip(springs, expected)):
        fail(f"spring stiffness values {springs}, expected {expected}")
    if {float(r["support.rho_kg_per_m3"]) for r in ev} != {7800.0, 76500.0}:
        fail("support density column")
    with open(os.path.join(out, "unstable_regions.csv")) as f:
        header = f.readline().strip()
    want = ("support.rho_kg_per_m3,support_springs.k_min_N_per_m,"
            "support_springs.k_max_N_per_m,"
            "freq_min_Hz,freq_max_Hz,max_re_per_s,track")
    if header != want:
        fail(f"unstable_regions.csv header '{header}'")
    with open(os.path.join(out, "check_full.csv")) as f:
        check = list(csv.DictReader(f))
    # the most unstable point and the edges of the unstable regions, at
    # most Check points = 2; every full eigenvalue has a reduced partner
    if not 1 <= len({r["point"] for r in check}) <= 2:
        fail("check_full.csv must hold 1 or 2 check points")
    if any(r["reduced_freq_Hz"] == "" for r in check):
        fail("check_full.csv: a full eigenvalue without a reduced partner")
    df = max(float(r["freq_rel_error"]) for r in check)
    dre = max(float(r["re_error_per_abs_re_plus_1"]) for r in check)
    if df > 1e-3 or dre > 2e-2:
        fail(f"reduced against full: {df:.3g} in frequency, {dre:.3g} in "
             "growth rate")
    print(f"other pair: {len(ev)} eigenvalues, reduced against full "
          f"{df:.2g} / {dre:.2g}: ok")
    plots(out)


os.makedirs(work, exist_ok=True)
if other_pair:
    check_other_pair()
    sys.exit(0)
serial = os.path.join(work, "serial")
log = run([squeal], serial)
for name in ("eigenvalues.csv", "unstable_regions.csv", "check_full.csv",
             "modes.pvd", "parameters.prm", "mode_participation.csv"):
    if not os.path.exists(os.path.join(serial, name)):
        fail(f"{name} missing")
if "Unstable regions" not in log or "point 12 of 12" not in log:
    fail("the run did not print its progress and unstable regions")
ev = rows(serial)
if len(ev) < 12 * 40:
    fail(f"only {len(ev)} eigenvalues in 12 sweep points")
for r in ev:
    re, f = float(r["re_per_s"]), float(r["freq_Hz"])
    lam = math.hypot(re, 2 * math.pi * f)
    if f <= 0 or abs(float(r["zeta"]) + re / lam) > 1e-9:
        fail(f"inconsistent row {r}")
    # Eigensolver/Unstable tolerance 1e-3 1/s and relative tolerance 1e-6
    if int(r["unstable"]) != (re > max(1e-3, 1e-6 * lam)):
        fail(f"unstable flag wrong in {r}")
    if float(r["pad_on_disc.mu"]) == 0.01 and int(r["unstable"]):
        fail(f"unstable eigenvalue at mu = 0.01: {r}")
with open(os.path.join(serial, "unstable_regions.csv")) as f:
    if f.readline().strip() != REGIONS:
        fail("unstable_regions.csv header")
with open(os.path.join(serial, "unstable_regions.csv")) as f:
    regions = list(csv.DictReader(f))
for g in regions:
    hits = [r for r in ev if r["track"] == g["track"] and int(r["unstable"])]
    if not hits or max(float(r["re_per_s"]) for r in hits) != float(g["max_re_per_s"]):
        fail(f"region {g} does not match eigenvalues.csv")
print(f"serial: {len(ev)} eigenvalues, {len(regions)} unstable regions: ok")

# The memory estimate printed before each basis sample's undamped
# eigensolve: for as many modes as the inertia count then gives the
# eigensolver, at least what is in use, within 2x of the run's peak.
lines = log.splitlines()
estimates = [(i, l.strip()) for i, l in enumerate(lines)
             if "with the undamped eigensolver (" in l]
if len(estimates) != 2:  # Reduced samples = 2
    fail(f"{len(estimates)} eigensolver memory estimates, not one per basis "
         "sample (2)")
peak = next(float(l.split()[2]) for l in lines if l.startswith("Peak memory: "))
for i, line in estimates:
    use = float(line.split()[1])
    estimate = float(line.split("estimated peak ")[1].split()[0])
    count = int(line.split("with the undamped eigensolver (")[1]
                .split(", ")[1].split()[0])
    solved = next(l for l in lines[i:] if "undamped eigensolver: " in l)
    if f": {count} modes up to" not in solved:
        fail(f"the estimate was for {count} modes, the eigensolver: {solved}")
    if not (use <= estimate and peak / 2 <= estimate <= 2 * peak):
        fail(f"eigensolver memory estimate {estimate} MB (in use {use} MB) "
             f"not within 2x of the peak {peak} MB")
print(f"eigensolver memory estimates: {len(estimates)}, each for the "
      f"inertia count's modes, within 2x of the peak {peak:.0f} MB: ok")

parallel = os.path.join(work, "mpirun2")
run(["mpirun", "-np", "2", squeal], parallel)
ev2 = rows(parallel)
if len(ev2) != len(ev):
    fail(f"mpirun -np 2 found {len(ev2)} eigenvalues, serial {len(ev)}")
worst_f = worst_re = 0.0
for a, b in zip(ev, ev2):
    fa, fb = float(a["freq_Hz"]), float(b["freq_Hz"])
    ra, rb = float(a["re_per_s"]), float(b["re_per_s"])
    worst_f = max(worst_f, abs(fa - fb) / fa)
    worst_re = max(worst_re, abs(ra - rb) / (abs(ra) + 1))
if worst_f > 1e-3 or worst_re > 2e-2:
    fail(f"mpirun -np 2 differs from serial by {worst_f:.3g} in frequency, "
         f"{worst_re:.3g} in growth rate")
print("mpirun -np 2 reproduces the serial eigenvalues within the reduced "
      "solver's accuracy: ok")

# The error indicator of the first point's modes: a share per body that
# sums to 1, the same on 2 ranks (each rank estimates its own cells).
shares = []
for d in (serial, parallel):
    with open(os.path.join(d, "mesh_error.csv")) as f:
        shares.append({r["body"]: float(r["share_of_squared_indicator"])
                       for r in csv.DictReader(f)})
    if not os.path.isfile(os.path.join(d, "mesh_error.vtu")):
        fail("mesh_error.vtu missing")
# (the file prints 6 significant digits: three roundings of <= 5e-7 each)
if sorted(shares[0]) != ["disc", "pad", "support"] or abs(sum(shares[0].values()) - 1) > 2e-6:
    fail(f"mesh_error.csv shares {shares[0]}")
if any(abs(shares[0][b] - shares[1][b]) > 1e-3 for b in shares[0]):
    fail(f"error indicator shares differ under mpirun: {shares}")
print(f"error indicator shares {shares[0]}, the same on 2 ranks: ok")

reuse = os.path.join(work, "reuse")
log = run([squeal], reuse,
          "subsection Mesh\n  set Frequency tolerance = 0.5\nend\n")
ev3 = rows(reuse)
if "the full solve's" not in log or "reused" not in log:
    fail("the basis did not reuse the first point's symmetric modes:\n" + log)
if len(ev3) != len(ev) or distance(ev, ev3) > 1e-5:
    fail(f"the basis on the reused modes: {len(ev3)} eigenvalues against "
         f"{len(ev)}, largest difference {distance(ev, ev3):.3g} of |lambda|")
print(f"basis on the mesh check's symmetric modes: the same eigenvalues "
      f"({distance(ev, ev3):.2g} of |lambda|): ok")

for d in (serial, parallel):
    pvd_entries_load(d)
plots(serial)
