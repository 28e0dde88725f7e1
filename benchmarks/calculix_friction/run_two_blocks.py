#!/usr/bin/python3
"""squeal's friction-coupled CEA against CalculiX 2.20's static friction
preload followed by a perturbed, unsymmetric *FREQUENCY, on the two-block
scene of two_blocks.py (same mesh, same trilinear elements).

usage: /usr/bin/python3 benchmarks/calculix_friction/run_two_blocks.py
           [SQUEAL] [WORKDIR]

Prints, per friction coefficient, load and CalculiX stick slope, the first
12 frequencies of both codes, their largest relative difference and the
most unstable eigenvalue of each; then CalculiX's answer at mu = 0.1 and
0.2 against the number of increments of its static step (README.md here
has the tables).
"""
import os
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import two_blocks  # noqa: E402

SLIDE = 10.0        # mm, the base's move in CalculiX's static step
MODES = 12


def show(values):
    return " ".join(f"{f:.0f}" + (f"{re:+.0f}" if abs(re) > 1 else "")
                    for f, re in values[:MODES])


def most_unstable(values):
    f, re = max(values, key=lambda v: v[1])
    return f"{f:.0f}, {re:.0f}" if re > 1 else "none"


def main():
    root = os.path.normpath(os.path.join(here, "..", ".."))
    squeal = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else \
        os.path.join(root, "build", "squeal")
    work = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else
                           os.path.join(root, "output", "calculix_friction"))
    os.makedirs(work, exist_ok=True)
    print("| mu | load [N] | stick slope [N/mm^3] | code | first 12 "
          "frequencies [Hz] (+- Re lambda [1/s]) | largest difference | "
          "most unstable: f [Hz], Re lambda [1/s] | wall time [s] |")
    print("|---|---|---|---|---|---|---|---|")
    for mu in (0.0, 0.05, 0.1, 0.2):
        for force in (10.0, 1000.0):
            start = time.monotonic()
            s = two_blocks.run_squeal(squeal, mu, force, SLIDE,
                                      f"squeal_{mu:g}_{force:g}", work)
            seconds = time.monotonic() - start
            print(f"| {mu:g} | {force:g} | - | squeal | {show(s)} | - | "
                  f"{most_unstable(s)} | {seconds:.1f} |")
            for slope in ((0.5, 1.0, 2.0) if force == 10.0 else (1.0,)):
                start = time.monotonic()
                c = two_blocks.run_calculix(
                    two_blocks.calculix_deck(mu, force, SLIDE, slope),
                    f"ccx_{mu:g}_{force:g}_{slope:g}", work)
                seconds = time.monotonic() - start
                worst = max(abs(a[0] - b[0]) / b[0]
                            for a, b in zip(c[:MODES], s[:MODES]))
                print(f"| {mu:g} | {force:g} | {slope:g} | CalculiX | "
                      f"{show(c)} | {100 * worst:.3f} % | "
                      f"{most_unstable(c)} | {seconds:.1f} |")
    # CalculiX's answer against the static step's increments (fixed, of
    # the given fraction of the step), at 10 N and stick slope 1 N/mm^3
    print()
    print("| mu | static step's increments | first two frequencies [Hz] | "
          "most unstable: f [Hz], Re lambda [1/s] |")
    print("|---|---|---|---|")
    for mu in (0.1, 0.2):
        for increment in (0.2, 0.1, 0.05, 0.02, 0.01, 0.005):
            c = two_blocks.run_calculix(
                two_blocks.calculix_deck(mu, 10.0, SLIDE, 1.0,
                                         increment=increment),
                f"ccx_{mu:g}_increment_{increment:g}", work)
            print(f"| {mu:g} | {round(1 / increment)} x {increment:g} | "
                  f"{c[0][0]:.0f}, {c[1][0]:.0f} | {most_unstable(c)} |")


if __name__ == "__main__":
    main()
