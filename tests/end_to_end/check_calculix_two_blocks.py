"""squeal's friction-coupled CEA against an independent code: CalculiX 2.20
(Debian's calculix-ccx, installed by scripts/setup.sh) on the two-block
scene of benchmarks/calculix_friction/two_blocks.py, the same trilinear
mesh (4 455 DoFs, 855 of them held) in both codes. CalculiX: static preload
with Coulomb friction (the base moved 10 mm under the block, a 10 N
traction so that its preload's stress stiffening stays below 1e-5), then
the perturbed, unsymmetric *FREQUENCY; squeal: the preloaded CEA with
steady sliding.

Checks (measured values in benchmarks/calculix_friction/README.md):
- without friction the first 12 frequencies agree to 1e-4 (measured 4e-5):
  the same element matrices and the same penalty contact stiffness;
- at mu = 0.2 both codes find the one mode lock-in below 100 kHz, at the
  same frequency within 1 % (measured 0.29 %; 0.3-0.6 % whatever the
  increments of CalculiX's static step) and with growth rates within a
  factor 2 (measured 8461 and 7537 1/s; CalculiX's moves between 3583 and
  7708 1/s with its increments, squeal's steady-sliding tangent has no
  such history).

usage: check_calculix_two_blocks.py SQUEAL WORKDIR
"""
import os
import shutil
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "..", "benchmarks",
                                "calculix_friction"))
from checks import check, finish  # noqa: E402
import two_blocks  # noqa: E402

SLIDE, FORCE, STICK_SLOPE, MODES = 10.0, 10.0, 1.0, 12


def main():
    squeal, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    if shutil.which("ccx") is None:
        print("FAILED: CalculiX (ccx) is missing: bash scripts/setup.sh "
              "installs calculix-ccx")
        sys.exit(1)
    os.makedirs(work, exist_ok=True)
    runs = {}
    for mu in (0.0, 0.2):
        runs[mu] = (
            two_blocks.run_squeal(squeal, mu, FORCE, SLIDE, f"squeal_{mu:g}",
                                  work),
            two_blocks.run_calculix(
                two_blocks.calculix_deck(mu, FORCE, SLIDE, STICK_SLOPE),
                f"ccx_{mu:g}", work))
        for code, values in zip(("squeal", "CalculiX"), runs[mu]):
            print(f"mu = {mu:g}, {code}: " + " ".join(
                f"{f:.1f}" + (f"{re:+.1f}" if abs(re) > 1 else "")
                for f, re in values[:MODES]))

    s, c = runs[0.0]
    check("both codes return at least 12 modes without friction",
          len(s) >= MODES and len(c) >= MODES, f"{len(s)}, {len(c)}")
    worst = max(abs(a[0] - b[0]) / b[0] for a, b in zip(c[:MODES], s[:MODES]))
    check("without friction the first 12 frequencies agree to 1e-4",
          worst < 1e-4, f"largest difference {worst:.2e}", show=True)
    check("without friction neither code finds an unstable mode",
          max(re for _, re in s + c) < 1.0,
          f"largest Re lambda {max(re for _, re in s + c):.3g} 1/s")

    s, c = runs[0.2]
    unstable = [[v for v in values if v[0] < 1e5 and v[1] > 1.0]
                for values in (s, c)]
    check("at mu = 0.2 each code finds exactly one unstable mode below "
          "100 kHz", [len(u) for u in unstable] == [1, 1],
          f"squeal {unstable[0]}, CalculiX {unstable[1]}", show=True)
    if [len(u) for u in unstable] == [1, 1]:
        (fs, rs), (fc, rc) = unstable[0][0], unstable[1][0]
        check("the lock-in frequencies agree within 1 %",
              abs(fs - fc) / fs < 1e-2,
              f"squeal {fs:.1f} Hz, CalculiX {fc:.1f} Hz", show=True)
        check("the growth rates agree within a factor 2",
              0.5 < rc / rs < 2.0,
              f"squeal {rs:.1f} 1/s, CalculiX {rc:.1f} 1/s", show=True)
    finish()


if __name__ == "__main__":
    main()
