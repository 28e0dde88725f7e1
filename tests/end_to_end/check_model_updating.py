"""End-to-end check of Scene/Analysis = model updating on the two-block scene
(tests/end_to_end/model_updating.prm): squeal itself "measures" the modes
below 90 kHz at hidden parameter values (block.E = 13 GPa, base.E = 180 GPa,
k_n = 2.5e13 N/m^3; a run with Maximum iterations = 0 writes modes.csv with
the shapes at the measurement points), the frequencies get a fixed
pseudo-random noise of at most 0.2 % and the shapes 1 % of their largest
value, and the fit from the file's values (10 GPa, 210 GPa, 1e13) must:
- converge on the reduced model (the default Method) confirmed by a full
  solve, and agree with the fit that solves the full model at every trial
  (Method = full) within 0.1 of a deviation;
- converge, with every fitted value within 3 of its stated standard
  deviations of the hidden one, the deviations below 5 %, all identifiable;
- pair every measured mode with its own (MAC >= 0.9 after the fit; the
  base's and the block's doublets by the span of their twins), every
  frequency error below 0.5 %, the cost down by 100x;
- under mpirun -np 2 with damping.beta added (no frictionless mode depends
  on it): the same fitted values (1e-6 relative) and damping.beta reported
  not identifiable, with an infinite deviation and a zero singular value;
- with a second configuration (block.rho = 3000, its interface at
  k_n = 8e13: a load step) measured too and `block on base.k_n@heavy`
  fitted beside the common parameters, both interface stiffnesses and the
  moduli within 3 deviations (below 20 %) of their hidden values;
- with damping ratios measured too (damping.alpha = 400 1/s on the base,
  the block's own beta = 4e-8 s: not proportional), both damping
  parameters and the moduli within 3 deviations (below 20 %), every ratio
  within 6 %; the sensitivities.csv of the ratios and frequencies against
  central differences of three runs (block.E: 2 % of the largest, block.beta
  1e-5);
- bad input fails with one error naming the item, and leaves no finished
  folder: an unknown parameter, a measurement point outside the mesh, a
  non-numeric frequency (file and line), a shape of the wrong length, a
  damping ratio given in per cent, no Targets, and a fit that does not
  converge within Maximum iterations.
Usage: check_model_updating.py SQUEAL BASE_PRM WORKDIR"""
import csv
import re
import shutil
import subprocess
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish, run_squeal  # noqa: E402

os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
squeal, base, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
os.chdir(work)

HIDDEN = {"block.E": 13e9, "base.E": 180e9, "block on base.k_n": 2.5e13}
SIGMA = 0.002


def rows(folder, name):
    with open(os.path.join(folder, name)) as f:
        return list(csv.DictReader(f))


def noise(state=[12345]):
    """Deterministic noise in [-1, 1] (a linear congruential sequence)."""
    state[0] = (1664525 * state[0] + 1013904223) % 2**32
    return 2 * state[0] / 2**32 - 1


# 1. the "measurement": modes at the hidden values
with open("probe.csv", "w") as f:
    f.write("label,frequency_Hz,weight,name\nprobe,50000,1,\n")


def measure(name, k_n, rho):
    """squeal's modes below 90 kHz at the hidden moduli, k_n and the
    block's density rho, with their shapes at the 7 points."""
    bodies = (f"base: E={HIDDEN['base.E']}, nu=0.3, rho=7800; "
              f"block: E={HIDDEN['block.E']}, nu=0.25, rho={rho}")
    folder, _ = run_squeal(squeal, base, name, f"""subsection Scene
  subsection Mesh file
    set Bodies = {bodies}
  end
end
subsection Interface
  set Normal stiffness = {k_n}
end
subsection Model updating
  set Targets = probe.csv
  set Maximum iterations = 0
  set Frequency window = 10
end
""")
    return [m for m in rows(folder, "modes.csv") if float(m["freq_Hz"]) < 9e4]


def write_targets(path, measured_sets):
    """measured_sets: (configuration, modes); noisy frequencies and
    shapes."""
    columns = [c for c in measured_sets[0][1][0] if c.startswith("shape ")]
    with open(path, "w") as f:
        f.write("label,frequency_Hz,weight,name,configuration" +
                "".join(f",{c}" for c in columns) + "\n")
        for configuration, modes in measured_sets:
            for m in modes:
                shape = [float(m[c]) for c in columns]
                big = max(abs(s) for s in shape)
                f.write(f"\"mode {m['mode']} ({m['name']}) {configuration}\","
                        f"{float(m['freq_Hz']) * (1 + SIGMA * noise()):.10g}"
                        f",1,,{configuration}")
                f.write("".join(f",{s + 0.01 * big * noise():.10g}"
                                for s in shape))
                f.write("\n")
    return columns


modes = measure("measured", HIDDEN["block on base.k_n"], 2500)
shape_columns = write_targets("targets_measured.csv", [("", modes)])
check("measured: modes below 90 kHz with shapes at 7 points",
      len(modes) >= 8 and len(shape_columns) == 7,
      f"{len(modes)} modes, {len(shape_columns)} shape columns", show=True)

# 2. the fit from the file's values
fit_prm = f"""subsection Model updating
  set Targets = targets_measured.csv
  set Measurement error = {SIGMA}
end
"""
fitted, log = run_squeal(squeal, base, "fitted", fit_prm)
par = {r["parameter"]: r for r in rows(fitted, "updated_parameters.csv")}
for name, hidden in HIDDEN.items():
    r = par[name]
    value, sd = float(r["fitted"]), float(r["standard_deviation"])
    check(f"{name}: within 3 deviations of the hidden value",
          abs(value - hidden) <= 3 * sd,
          f"fitted {value:.6g}, hidden {hidden:.6g}, deviation {sd:.3g}",
          show=True)
    check(f"{name}: deviation below 5 %", sd / value < 0.05,
          f"{sd / value:.3g}", show=True)
    check(f"{name}: identifiable", r["identifiable"] == "1", r)
targets = rows(fitted, "targets.csv")
check("every measured mode in targets.csv", len(targets) == len(modes),
      f"{len(targets)} of {len(modes)}")
worst_error = max(abs(float(t["error_percent"])) for t in targets)
least_mac = min(float(t["mac"]) for t in targets)
check("after the fit every frequency within 0.5 %", worst_error < 0.5,
      f"largest {worst_error:.3g} %", show=True)
check("after the fit every pairing MAC >= 0.9", least_mac >= 0.9,
      f"least {least_mac:.4f}", show=True)
start_error = max(abs(float(t["initial_error_percent"])) for t in targets)
check("the start is far (largest error above 5 %)", start_error > 5,
      f"{start_error:.3g} %", show=True)
history = rows(fitted, "history.csv")
check("the cost went down 100x",
      float(history[-1]["cost"]) < 1e-2 * float(history[0]["cost"]),
      f"{history[0]['cost']} -> {history[-1]['cost']}", show=True)
modes_after = rows(fitted, "modes.csv")
paired = {m["target"] for m in modes_after if m["target"]}
check("modes.csv names each measured mode's model mode once",
      paired == {t["label"] for t in targets})
check("mac.csv: one row per measured mode",
      len(rows(fitted, "mac.csv")) == len(targets))

# 2b. the reduced model (the default) against the full solver at every trial
with open(os.path.join(fitted, "summary.txt")) as f:
    summary = f.read()
solves = re.search(r"after (\d+) steps \((\d+) eigensolves\)", summary)
check("the reduced fit is confirmed by a full solve, in fewer eigensolves "
      "than steps", "confirmed by a full solve" in summary and solves and
      int(solves.group(2)) < int(solves.group(1)), summary, show=True)
full_fit, _ = run_squeal(squeal, base, "fitted_full", fit_prm + """subsection Model updating
  set Method = full
end
""")
par_full = {r["parameter"]: r for r in rows(full_fit, "updated_parameters.csv")}
for name in HIDDEN:
    a, b = float(par[name]["fitted"]), float(par_full[name]["fitted"])
    sd = float(par_full[name]["standard_deviation"])
    check(f"{name}: reduced and full fits agree within 0.1 deviation",
          abs(a - b) <= 0.1 * sd, f"{a:.8g} vs {b:.8g} (deviation {sd:.3g})",
          show=True)

# 3. mpirun -np 2, with a parameter no frictionless mode depends on
mpi, _ = run_squeal(squeal, base, "fitted_mpi", fit_prm + """subsection Model updating
  set Parameters = block.E: 1e9, 1e11; base.E: 5e10, 1e12; \\
                   block on base.k_n: 1e11, 1e15; damping.beta: 1e-9, 1e-5
end
""", mpi=2)
par2 = {r["parameter"]: r for r in rows(mpi, "updated_parameters.csv")}
for name in HIDDEN:
    a, b = float(par[name]["fitted"]), float(par2[name]["fitted"])
    check(f"np = 2 with damping.beta: {name} as with np = 1",
          abs(a - b) <= 1e-6 * abs(a), f"{a:.10g} vs {b:.10g}")
beta = par2["damping.beta"]
check("damping.beta: not identifiable, infinite deviation",
      beta["identifiable"] == "0" and math.isinf(float(beta["standard_deviation"])),
      beta)
ident = rows(mpi, "identifiability.csv")
check("damping.beta: a zero singular value along it",
      float(ident[-1]["relative"]) < 1e-6 and
      abs(float(ident[-1]["damping.beta"])) > 0.99, ident[-1])
with open(os.path.join(mpi, "summary.txt")) as f:
    summary = f.read()
check("summary.txt names damping.beta as not identifiable",
      "Not identifiable from these targets: damping.beta" in summary, summary)

# 3b. a parameter of one configuration: the interface of a second state
K_HEAVY = 8e13
heavy = measure("measured_heavy", K_HEAVY, 3000)
write_targets("targets_two_states.csv", [("", modes), ("heavy", heavy)])
both, _ = run_squeal(squeal, base, "fitted_two_states", f"""subsection Model updating
  set Targets = targets_two_states.csv
  set Measurement error = {SIGMA}
  set Configurations = heavy: block.rho = 3000
  set Parameters = block.E: 1e9, 1e11; base.E: 5e10, 1e12; \\
                   block on base.k_n: 1e11, 1e15; \\
                   block on base.k_n@heavy: 1e11, 1e15
end
""")
par3 = {r["parameter"]: r for r in rows(both, "updated_parameters.csv")}
for name, hidden in list(HIDDEN.items()) + [("block on base.k_n@heavy",
                                             K_HEAVY)]:
    r = par3[name]
    value, sd = float(r["fitted"]), float(r["standard_deviation"])
    check(f"two states, {name}: within 3 deviations of the hidden value",
          abs(value - hidden) <= 3 * sd and sd < 0.2 * value,
          f"fitted {value:.6g}, hidden {hidden:.6g}, deviation {sd:.3g}",
          show=True)


# 3c. modal damping as a target: the base's Rayleigh alpha (damping.alpha)
# and the block's own beta (block.beta: a damping not proportional to the
# assembly's stiffness) fitted beside the moduli from damping ratios
DAMPED = {"damping.alpha": 400.0, "block.beta": 4e-8}
DSIGMA = 0.02
# d zeta / d block.beta is exact (zeta is affine in it); d zeta / d block.E
# carries the shape change: the modes below Maximum frequency exactly, those
# above in their static limit (measured 0.8 % of the largest with the modes
# to 240 kHz, 2.7 x the highest target; 7 % with 120 kHz)
DERIVATIVE_TOLERANCE = {"block.beta": 1e-5, "block.E": 0.02}
with open("probe_damped.csv", "w") as f:
    f.write("label,frequency_Hz,weight,name,damping_ratio\n"
            "probe,50000,1,,0.01\n")


def damped_run(name, alpha, beta, block_e, extra=""):
    """A run with the block's own beta and damping.alpha on the base."""
    bodies = (f"base: E={HIDDEN['base.E']}, nu=0.3, rho=7800; "
              f"block: E={block_e}, nu=0.25, rho=2500, alpha=0, "
              f"beta={beta}")
    return run_squeal(squeal, base, name, f"""subsection Scene
  subsection Mesh file
    set Bodies = {bodies}
  end
end
subsection Interface
  set Normal stiffness = {HIDDEN['block on base.k_n']}
end
subsection Damping
  set Alpha = {alpha}
  set Beta = 0
end
{extra}""")


probe = """subsection Model updating
  set Targets = probe_damped.csv
  set Maximum iterations = 0
  set Frequency window = 10
end
"""
folder, _ = damped_run("measured_damped", DAMPED["damping.alpha"],
                       DAMPED["block.beta"], HIDDEN["block.E"], probe)
damped_modes = [m for m in rows(folder, "modes.csv")
                if float(m["freq_Hz"]) < 9e4]
with open("targets_damped.csv", "w") as f:
    f.write("label,frequency_Hz,damping_ratio\n")
    for m in damped_modes:
        f.write(f"mode {m['mode']},"
                f"{float(m['freq_Hz']) * (1 + SIGMA * noise()):.10g},"
                f"{float(m['damping_ratio']) * (1 + DSIGMA * noise()):.10g}\n")
ratios = [float(m["damping_ratio"]) for m in damped_modes]
check("damped measurement: ratios spread over the modes (not one Rayleigh "
      "curve)", min(ratios) > 0 and max(ratios) > 2 * min(ratios),
      f"{min(ratios):.4g} ... {max(ratios):.4g}", show=True)
damped_fit = f"""subsection Model updating
  set Targets = targets_damped.csv
  set Measurement error = {SIGMA}
  set Damping error = {DSIGMA}
  set Frequency window = 0.3
  set Parameters = block.E: 1e9, 1e11; base.E: 5e10, 1e12; \\
                   block on base.k_n: 1e11, 1e15; damping.alpha: 10, 1e4; \\
                   block.beta: 1e-10, 1e-6
end
"""
fitted_damped, _ = damped_run("fitted_damped", 100.0, 1e-8, 10e9, damped_fit)
par4 = {r["parameter"]: r for r in rows(fitted_damped,
                                        "updated_parameters.csv")}
for name, hidden in list(HIDDEN.items()) + list(DAMPED.items()):
    r = par4[name]
    value, sd = float(r["fitted"]), float(r["standard_deviation"])
    check(f"damping targets, {name}: within 3 deviations of the hidden value",
          abs(value - hidden) <= 3 * sd and sd < 0.2 * value,
          f"fitted {value:.6g}, hidden {hidden:.6g}, deviation {sd:.3g}",
          show=True)
worst = max(abs(float(t["model_damping_ratio"]) / float(t["measured_damping_ratio"]) - 1)
            for t in rows(fitted_damped, "targets.csv"))
check("damping targets: every fitted ratio within 3 x 2 % of the measured",
      worst < 3 * DSIGMA, f"largest {100 * worst:.3g} %", show=True)

# the damping ratios' sensitivities (sensitivities.csv at the start of a
# fit of 0 steps) against central differences of two more runs
H = 1e-4
at_start = """subsection Model updating
  set Targets = targets_damped.csv
  set Maximum iterations = 0
  set Frequency window = 0.3
  set Maximum frequency = 240000
  set Parameters = block.E: 1e9, 1e11; block.beta: 1e-10, 1e-6
end
"""


def paired(name, block_e, beta):
    folder, _ = damped_run(name, DAMPED["damping.alpha"], beta, block_e,
                           at_start)
    return folder, rows(folder, "targets.csv")


centre, _ = paired("sens_centre", HIDDEN["block.E"], DAMPED["block.beta"])
sens = rows(centre, "sensitivities.csv")
for parameter, value in (("block.E", HIDDEN["block.E"]),
                         ("block.beta", DAMPED["block.beta"])):
    runs = []
    for sign in (1, -1):
        moved = value * (1 + sign * H)
        e, beta = ((moved, DAMPED["block.beta"]) if parameter == "block.E"
                   else (HIDDEN["block.E"], moved))
        runs.append(paired(f"sens_{parameter}_{sign}", e, beta)[1])
    checks = [("damping_ratio", "model_damping_ratio",
               DERIVATIVE_TOLERANCE[parameter])]
    if parameter == "block.E":  # no frequency depends on block.beta
        checks.append(("frequency_Hz", "model_Hz", 1e-5))
    for quantity, column, tol in checks:
        analytic = [float(r["d/d " + parameter]) for r in sens
                    if r["quantity"] == quantity]
        fd = [(float(p[column]) - float(m[column])) / (2 * H * value)
              for p, m in zip(*runs)]
        scale = max(abs(x) for x in fd)
        worst = max(abs(a - b) for a, b in zip(analytic, fd)) / scale
        check(f"d {quantity} / d {parameter}: the {len(fd)} paired modes "
              f"against central differences, within {tol:g} of the largest",
              len(analytic) == len(fd) == len(damped_modes) and scale > 0
              and worst <= tol, f"worst {worst:.3g}", show=True)


# 4. bad input
def fails(name, extra, expected):
    out = os.path.abspath(name)
    for folder in (out, out + ".partial"):
        shutil.rmtree(folder, ignore_errors=True)
    with open(name + ".prm", "w") as f:
        f.write(f"include {base}\n{extra}subsection Output\n"
                f"  set Directory = {out}\nend\n")
    r = subprocess.run([squeal, name + ".prm"], capture_output=True, text=True)
    errors = [line for line in r.stderr.splitlines() if "error" in line]
    check(f"bad input {name}: one error naming it, no result",
          r.returncode != 0 and len(errors) == 1 and expected in errors[0]
          and not os.path.exists(out), f"exit {r.returncode}: {r.stderr}")


fails("unknown_parameter", fit_prm + """subsection Model updating
  set Parameters = pad.E: 1e9, 1e11
end
""", "Model updating/Parameters: unknown parameter 'pad.E'; this scene's "
   "parameters are base.E|base.rho|block.E")
with open(os.path.join(os.path.dirname(base), "model_updating_points.csv")) as f:
    lines = f.read().splitlines()
with open("far_points.csv", "w") as f:  # the last of the 7 points moved away
    f.write("\n".join(lines[:-1] + ["far,0.5,0,0,0,0,1"]) + "\n")
fails("point_outside", fit_prm + """subsection Model updating
  set Measurement points = far_points.csv
end
""", "point 'far' at (0.5 0 0) m lies outside the mesh")
with open("bad_frequency.csv", "w") as f:
    f.write("label,frequency_Hz,weight,name\na,18000,1,\nb,abc,1,\n")
fails("bad_frequency", """subsection Model updating
  set Targets = bad_frequency.csv
end
""", "bad_frequency.csv', line 3: frequency_Hz = 'abc' is not a number")
with open("short_shape.csv", "w") as f:
    f.write("label,frequency_Hz,weight,name,shape a,shape b,shape c\n"
            "a,18000,1,,1,2,3\n")
fails("short_shape", """subsection Model updating
  set Targets = short_shape.csv
end
""", "3 shape columns; give one per measurement point (7) or none")
with open("unknown_configuration.csv", "w") as f:
    f.write("label,frequency_Hz,configuration\na,18000,stiff\n")
fails("unknown_configuration", """subsection Model updating
  set Targets = unknown_configuration.csv
  set Configurations = soft: block.rho = 2000
end
""", "line 2: configuration 'stiff' is not one of Model "
   "updating/Configurations (soft)")
fails("unknown_configuration_parameter", fit_prm + """subsection Model updating
  set Parameters = block.E: 1e9, 1e11; block on base.k_n@stiff: 1e11, 1e15
  set Configurations = soft: block.rho = 2000
end
""", "Model updating/Parameters: block on base.k_n@stiff names the "
   "configuration 'stiff', which is not one of Model updating/Configurations")
with open("percent_damping.csv", "w") as f:
    f.write("label,frequency_Hz,damping_ratio\na,18000,2.5\n")
fails("percent_damping", """subsection Model updating
  set Targets = percent_damping.csv
end
""", "percent_damping.csv', line 2: damping_ratio must lie in (0, 1)")
fails("no_targets", "", "needs Model updating/Parameters")
fails("not_converged", fit_prm + """subsection Model updating
  set Maximum iterations = 1
end
""", "did not converge within Model updating/Maximum iterations = 1")
finish()
