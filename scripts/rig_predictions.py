#!/usr/bin/env python3
"""Writes the complex eigenvalue analyses that predict squeal on the
TriboBrake as built (thesis sec. 4.3; ../shared/spec/rig_experiments.md)
from the fitted parameters of prm/rig_updating.prm.

    scripts/rig_predictions.py UPDATED_PARAMETERS_CSV [--out DIR]
    scripts/rig_predictions.py --summarise OUTPUT_DIR...

writes DIR/<case>.prm (default DIR prm/rig_predictions), one CEA per squeal
configuration, each sweeping the friction coefficient from 0 to the rig's
0.3 (so that the tracks show which two modes lock in) at the
configuration's load:
- S1: 10 x 10 mm pad, 200 N;  S2: 250 N;
- S3: 10 x 10 mm pad at 120, 70, 48 and 45 N (and 250 N: S2);
- S4: 8 x 8 mm pad, 25 N (the support alone);
- S5: 10 x 10 mm pad, 45 N, a rubber layer between the plates and the
  support.
--summarise prints, for each finished run, every unstable eigenvalue at
mu = 0.3 (frequency, growth rate, name) and the two modes of the
frictionless-limit point (mu = 0) that lock in: the unstable eigenvalue's
track and the track of its stable twin (the eigenvalue nearest in
frequency at the same point), each named at mu = 0.
The model is the fitted one with these changes, each a stated assumption:
- the weights: (F - 25 N) / g on the support's top (`weights.m`);
- the interface stiffness at a load F: k_n(F) = k_n(25 N) (F / 25 N)^n,
  with n = ln(k_n(225 N) / k_n(25 N)) / ln 9 through the two fitted values
  where the fit could determine both, else n = 1, and the same law for the
  tangential (shear) stiffness k_t where it was fitted, its shear kept in
  sliding (the asperities' elastic shear under the gross slip; the pad
  modes were measured in rotation too) (a rough contact of
  exponentially distributed asperity heights: stiffness proportional to
  load; J. A. Greenwood and J. B. P. Williamson, Proc. R. Soc. A 295
  (1966) 300-319);
- the rotating state: the disc turning lowers the support frequencies by
  about 500 Hz (thesis sec. 4.2.3: one end of each plate is compressed),
  taken as the plates' tangential stiffness scaled by ROTATING_PLATES;
- the Rayleigh damping fitted to Table 4.1's ratios where it was fitted
  (damping.alpha, damping.beta), else the scene's;
- S5's rubber layer in series with the plates: the plates' stiffness
  (both directions) scaled by RUBBER_PLATES, and the support's damping
  raised (its own Rayleigh beta).
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_rig import scene_text  # noqa: E402

G = 9.81
SUPPORT_WEIGHT = 25.0           # N: the support alone
MU = 0.3                        # the rig's friction coefficient (sec. 4.2.3)
# (f_II - 500 Hz)^2 / f_II^2 at the fitted support mode II (2091 Hz): the
# rigid-body support modes scale with the plates' stiffness
ROTATING_PLATES = ((2091.0 - 500.0) / 2091.0) ** 2
# a rubber layer a few times softer than the plates in series with them
RUBBER_PLATES = 0.25
RUBBER_BETA = 1e-6              # s: support damping ratio ~3 % at 5 kHz

CASES = [  # name, pad [mm], load [N], rubber layer
    ("S1", 10, 200.0, False),
    ("S2", 10, 250.0, False),
    ("S3_120N", 10, 120.0, False),
    ("S3_70N", 10, 70.0, False),
    ("S3_48N", 10, 48.0, False),
    ("S3_45N", 10, 45.0, False),
    ("S4", 8, 25.0, False),
    ("S5", 10, 45.0, True),
]


def fitted(path):
    """{parameter: fitted value}, {parameter: identifiable}"""
    with open(path) as f:
        r = list(csv.DictReader(f))
    return ({x["parameter"]: float(x["fitted"]) for x in r},
            {x["parameter"]: x["identifiable"] == "1" for x in r})


def rows(folder, name):
    with open(os.path.join(folder, name)) as f:
        return list(csv.DictReader(f))


def summarise(folders):
    for folder in folders:
        eig = rows(folder, "eigenvalues.csv")
        names = {(r["point"], r["mode"]): r["name"]
                 for r in rows(folder, "mode_participation.csv")}
        mu_col = [c for c in eig[0] if c.endswith(".mu")][0]
        last = max(float(r[mu_col]) for r in eig)
        first = min(float(r[mu_col]) for r in eig)
        at = [r for r in eig if float(r[mu_col]) == last]
        start = {r["track"]: r for r in eig if float(r[mu_col]) == first}
        unstable = [r for r in at if r["unstable"] == "1"]
        print(f"{os.path.basename(os.path.normpath(folder))}: "
              f"{len(unstable)} unstable at mu = {last:g}")
        for u in sorted(unstable, key=lambda r: float(r["freq_Hz"])):
            twin = min((r for r in at if r is not u),
                       key=lambda r: abs(float(r["freq_Hz"]) -
                                         float(u["freq_Hz"])))

            def origin(r):
                s = start.get(r["track"])
                if s is None:
                    return "track starts later"
                return (f"{float(s['freq_Hz']):.0f} Hz "
                        f"{names.get((s['point'], s['mode']), '?')}")
            print(f"  {float(u['freq_Hz']):.0f} Hz, growth "
                  f"{float(u['re_per_s']):.3g} 1/s, "
                  f"{names.get((u['point'], u['mode']), '?')}; lock-in of "
                  f"[{origin(u)}] and [{origin(twin)}]")


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--summarise":
        summarise(sys.argv[2:])
        return
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("updated_parameters")
    parser.add_argument("--out", help="folder (default prm/rig_predictions)")
    args = parser.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    out = args.out or os.path.normpath(
        os.path.join(here, "..", "prm", "rig_predictions"))
    os.makedirs(out, exist_ok=True)
    p, identifiable = fitted(args.updated_parameters)

    def load_law(name):
        """(value at 25 N, exponent n) of a stiffness fitted at 25 and
        225 N; None where it was not fitted."""
        if name not in p:
            return None
        low, high = p.pop(name), p.pop(name + "@225 N")
        both = identifiable[name] and identifiable[name + "@225 N"]
        return low, (math.log(high / low) / math.log(9.0) if both else 1.0)

    k25, exponent = load_law("pad on disc.k_n")
    shear = load_law("pad on disc.k_t")
    damping = {k: p.pop(k) for k in ("damping.alpha", "damping.beta")
               if k in p}
    for name, pad, load, rubber in CASES:
        values = dict(p)
        values["plates.k"] = p["plates.k"] * ROTATING_PLATES * (
            RUBBER_PLATES if rubber else 1.0)
        values["plates radial.k"] = p["plates.k"] * (
            RUBBER_PLATES if rubber else 1.0)
        k_n = k25 * (load / SUPPORT_WEIGHT) ** exponent
        k_t = shear[0] * (load / SUPPORT_WEIGHT) ** shear[1] if shear else 0.
        weights = (load - SUPPORT_WEIGHT) / G
        mesh = os.path.relpath(
            os.path.join(here, "..", "prm", f"rig_pad{pad:g}", "rig.msh"),
            out)
        header = (
            f"# Squeal prediction {name} on the TriboBrake as built: "
            f"{pad:g} x {pad:g} mm pad,\n# {load:g} N"
            f"{', rubber layer' if rubber else ''}, mu swept 0 -> {MU:g},"
            f" rotating state. Written by\n# scripts/rig_predictions.py "
            f"from the fitted parameters (do not edit; rerun\n# it). "
            f"k_n = {k_n:.6g} N/m^3 (load exponent {exponent:.4f}), "
            f"k_t = {k_t:.6g} N/m^3"
            f"{f' (load exponent {shear[1]:.4f})' if shear else ''}.\n"
            f"# Run: build/squeal prm/rig_predictions/{name}.prm\n")
        extra = {"support": f"alpha=0, beta={RUBBER_BETA:g}"} if rubber \
            else None
        text = scene_text(pad, mesh, values, header, extra)
        text += f"""subsection Scene
  set Analysis = cea
end
subsection Mesh
  set Finite element degree = 3
end
subsection Interface
  set Normal stiffness     = {k_n:.10g}
  set Tangential stiffness = {k_t:.10g}
  set Friction coefficient = {MU:g}
end
subsection Eigensolver
  set Method            = reduced
  set Minimum frequency = 300
  set Maximum frequency = 16000
end
subsection Sweep
  set First parameter  = pad on disc.mu
  set First values     = linear 0 {MU:g} 7
  set Second parameter = weights.m
  set Second values    = {weights:.10g}
end
subsection Output
  set Directory   = output/rig_predictions/{name}
  set Mode shapes = unstable and first
end
"""
        if damping:
            text += f"""subsection Damping
  set Alpha = {damping.get('damping.alpha', 0.02):.10g}
  set Beta  = {damping.get('damping.beta', 1e-7):.10g}
end
"""
        with open(os.path.join(out, name + ".prm"), "w") as f:
            f.write(text)
    print(f"rig_predictions.py: {len(CASES)} files in {out}; interface "
          f"stiffness exponent {exponent:.4f}"
          f"{f', shear stiffness exponent {shear[1]:.4f}' if shear else ''}")


if __name__ == "__main__":
    main()
