#!/usr/bin/python3
"""squeal's preloaded CEA of the passenger-car brake against CalculiX 2.20's
brake-squeal practice (static preload with Coulomb friction, then a
perturbed, unsymmetric *FREQUENCY), same mesh, same machine.

usage: /usr/bin/python3 benchmarks/real_brake/run_friction.py [SQUEAL] [WORKDIR]
           [--mu MU] [--increment DT]

The model, the same in both codes: every body and material of
brake_scene.prm on the 10 mm mesh, the pads in penalty contact with the disc
(k_n = 1e13 N/m^3) with Coulomb friction mu (0.4 unless --mu), no springs, the piston's
back and the caliper's bore held in x and y (they take the springs' place),
the disc held at its hub and the bracket at its mounts, the brake pressure's
force pair, no damping.
- squeal: `Scene/Analysis = preloaded cea`, steady sliding, degree 2, the
  full solver in 500-16 000 Hz, 1 MPI rank;
- CalculiX: calculix_deck.py's C3D20R deck with `friction=`: the static
  step presses the pads with 1 % of the force (its perturbation step adds
  the preload's stress stiffness, which squeal's CEA has not; the penalty
  contact's state does not depend on the load's size) and turns the disc by
  one cell of its mesh (3.75 degrees, so that the pads slip; the disc's mesh
  then lies on itself), stick slope 1 N/mm^3; then *FREQUENCY with 200
  eigenvalues from 500 Hz, OMP_NUM_THREADS=1.
Prints the unstable eigenvalues of both (Re lambda > 1 1/s) and pairs each
of squeal's with CalculiX's nearest in frequency.
"""
import math
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "calculix_friction"))
import calculix_deck  # noqa: E402
import run_modes  # noqa: E402
import two_blocks  # noqa: E402

H, K_N, FORCE = 10.0, 1e13, 4580.44
F_MIN, F_MAX = 500.0, 16000.0


def squeal_run(squeal, work, mu):
    out = os.path.join(work, f"squeal_friction_{mu:g}")

    def run():
        mesh = run_modes.mesh_dir(work, H)
        with open(out + ".prm", "w") as f:
            f.write(f"""INCLUDE {mesh}/brake_scene.prm
subsection Scene
  set Analysis = preloaded cea
  subsection Mesh file
    set Springs =
    set Holds = hub: set=disc hub; bracket mounts: set=bracket mounts; \\
                piston back: set=piston back, components=xy; \\
                caliper bore: set=caliper bore, components=xy
  end
end
subsection Mesh
  set Finite element degree = 2
end
subsection Interface
  set Normal stiffness = {K_N:g}
  set Friction coefficient = {mu:g}
end
subsection Preload
  set Friction = steady sliding
end
subsection Damping
  set Alpha = 0
  set Beta = 0
end
subsection Eigensolver
  set Method = full
  set Minimum frequency = {F_MIN:g}
  set Maximum frequency = {F_MAX:g}
end
subsection Sweep
  set First parameter  = contact.mu
  set First values     = {mu:g}
  set Second parameter = friction material.E
  set Second values    = 8e9
end
subsection Output
  set Directory = {out}
  set Overwrite = true
  set Mode shapes = none
end
""")
        _, seconds, mb, values = run_modes.run_squeal(squeal, out, work)
        return dict(code="squeal", seconds=seconds, memory_MB=mb,
                    values=values)
    return run_modes.cached(out + ".json", run)


def calculix_run(work, mu, increment=None):
    name = f"ccx_friction_{mu:g}" + \
        (f"_increment_{increment:g}" if increment else "")

    def run():
        text, _ = calculix_deck.deck(
            H, F_MAX, 200, friction=dict(
                k_n=K_N, mu=max(mu, 1e-9), stick_slope=1.0, force=0.01 * FORCE,
                theta=2 * math.pi / 96, f_min=F_MIN, increment=increment))
        measured = {}

        def timed(args, cwd):
            env = dict(os.environ, OMP_NUM_THREADS="1",
                       OPENBLAS_NUM_THREADS="1")
            r, measured["seconds"], measured["memory_MB"] = \
                run_modes.timed(args, cwd, env)
            return r
        values = two_blocks.run_calculix(text, name, work, timed)
        return dict(code="CalculiX", values=values, **measured)
    return run_modes.cached(os.path.join(work, name + ".json"), run)


def main():
    root = os.path.normpath(os.path.join(here, "..", ".."))
    args = sys.argv[1:]
    options = {"--mu": 0.4, "--increment": None}
    for option in options:
        if option in args:
            i = args.index(option)
            options[option] = float(args[i + 1])
            del args[i:i + 2]
    mu, increment = options["--mu"], options["--increment"]
    squeal = os.path.abspath(args[0]) if args else \
        os.path.join(root, "build", "squeal")
    work = os.path.abspath(args[1] if len(args) > 1 else
                           os.path.join(root, "output", "real_brake_modes"))
    os.makedirs(work, exist_ok=True)
    if subprocess.run(["which", "ccx"], capture_output=True).returncode:
        sys.exit("run_friction.py needs CalculiX (calculix-ccx)")
    s, c = squeal_run(squeal, work, mu), calculix_run(work, mu, increment)
    for r in (s, c):
        band = [v for v in r["values"] if F_MIN <= v[0] <= F_MAX]
        print(f"{r['code']}: {len(band)} eigenvalues in {F_MIN:g}-"
              f"{F_MAX:g} Hz, {r['seconds']:.0f} s, peak memory "
              f"{r['memory_MB']:.0f} MB")
    bands = [[v for v in r["values"] if F_MIN <= v[0] <= F_MAX]
             for r in (s, c)]
    nearest = sorted(min(abs(x[0] - y[0]) / y[0] for x in bands[1])
                     for y in bands[0])
    print(f"each of squeal's frequencies against CalculiX's nearest: median "
          f"{100 * nearest[len(nearest) // 2]:.2f} %, 90 % of them within "
          f"{100 * nearest[int(0.9 * len(nearest))]:.2f} %, largest "
          f"{100 * nearest[-1]:.2f} %")
    unstable = [[v for v in band if v[1] > 1.0] for band in bands]
    print("| squeal f [Hz] | Re lambda [1/s] | CalculiX unstable within 2 % "
          "[Hz] | Re lambda [1/s] | difference |")
    print("|---|---|---|---|---|")
    for f, re in unstable[0]:
        near = [v for v in unstable[1] if abs(v[0] - f) <= 0.02 * f]
        if not near:
            print(f"| {f:.1f} | {re:.1f} | none | - | - |")
            continue
        g, rg = min(near, key=lambda v: abs(v[0] - f))
        print(f"| {f:.1f} | {re:.1f} | {g:.1f} | {rg:.1f} | "
              f"{100 * (g - f) / f:+.2f} % |")
    print("CalculiX's unstable: " + ", ".join(
        f"{f:.1f} ({re:.1f})" for f, re in unstable[1]))

if __name__ == "__main__":
    main()
