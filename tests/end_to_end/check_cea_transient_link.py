#!/usr/bin/python3
"""The CEA/transient link on a coarse TriboBrake (tests/braking/link.prm).

usage: check_cea_transient_link.py SQUEAL PRM WORKDIR

Unstable point (E_pad = 25.1 GPa, mu = 0.5):
- the CEA about the preload (full solver, 900-20 000 Hz, hard-contact
  interface stiffness) has an unstable eigenvalue;
- a 10 ms braking run at the same point grows: its dominant frequency is
  within 2 % of an unstable CEA eigenfrequency, and its growth rate at that
  frequency (summary.csv, growth_rate_at_dominant_frequency_per_s) within
  20 % of the eigenvalue's real part.
Stable point (mu = 0.1):
- the CEA has no unstable eigenvalue in the band;
- a braking run seeded with an axial velocity of 0.01 m/s decays (negative
  growth rate of the probe velocity's envelope after the ramp).
"""
import csv
import os
import sys

from checks import check, finish, full_solver_point, run_squeal

squeal, prm, work = sys.argv[1:4]
prm = os.path.abspath(prm)
os.makedirs(work, exist_ok=True)
os.chdir(work)


def run(name, text):
    return run_squeal(squeal, prm, name,
                      text + "subsection Output\n  set Mode shapes = none\nend\n")[0]


def cea(name, mu):
    out = run(name, f"""subsection Scene
  set Analysis = preloaded cea
end
subsection Interface
  set Friction coefficient = {mu}
end
""" + full_solver_point(mu, 20000, 25.1e9, 900))
    with open(os.path.join(out, "eigenvalues.csv")) as f:
        rows = list(csv.DictReader(f))
    return [(float(r["freq_Hz"]), float(r["re_per_s"])) for r in rows
            if int(r["unstable"])]


def braking(name, mu, end, seed):
    out = run(name, f"""subsection Scene
  set Analysis = braking
end
subsection Interface
  set Friction coefficient = {mu}
end
subsection Transient
  set End time = {end}
  set Initial perturbation = {seed}
end
""")
    with open(os.path.join(out, "summary.csv")) as f:
        return {r["quantity"]: r["value"] for r in csv.DictReader(f)}


unstable = cea("cea_unstable", 0.5)
print("CEA unstable eigenvalues (Hz, 1/s):", unstable)
check("the CEA at mu = 0.5 has an unstable eigenvalue", len(unstable) > 0, str(unstable), True)
s = braking("braking_unstable", 0.5, 0.010, 0)
f_t = float(s["dominant_frequency_Hz"])
rate = float(s["growth_rate_at_dominant_frequency_per_s"])
print(f"braking: {s['verdict']}, dominant frequency {f_t} Hz, growth rate at it {rate} 1/s")
check("the braking run grows", s["verdict"].startswith("unstable"), s["verdict"], True)
if unstable:
    f_c, re_c = min(unstable, key=lambda e: abs(e[0] - f_t))
    check("dominant frequency within 2 % of the CEA's unstable eigenfrequency",
          abs(f_t - f_c) <= 0.02 * f_c, f"{f_t:.1f} Hz vs {f_c:.1f} Hz "
          f"({100 * (f_t / f_c - 1):+.2f} %)", True)
    check("growth rate within 20 % of the eigenvalue's real part",
          abs(rate - re_c) <= 0.2 * re_c, f"{rate:.1f} 1/s vs {re_c:.1f} 1/s "
          f"({100 * (rate / re_c - 1):+.1f} %)", True)

stable = cea("cea_stable", 0.1)
check("the CEA at mu = 0.1 has no unstable eigenvalue", len(stable) == 0, str(stable), True)
s = braking("braking_stable", 0.1, 0.005, 0.01)
g = float(s["growth_rate_per_s"])
print(f"braking at mu = 0.1: {s['verdict']}, envelope growth rate {g} 1/s")
check("the seeded vibration decays at the stable point",
      g < 0 and s["verdict"].startswith("stable"), f"{s['verdict']}, {g} 1/s", True)
finish()
