#!/usr/bin/python3
"""Reduced sweep: error against basis size and enrichment, and its cost.

usage: /usr/bin/python3 benchmarks/speed_vs_error/run_reduced.py [SQUEAL] [WORKDIR] [--default-mesh]

Runs build/squeal on a TriboBrake sweep (mu = 0.2, 0.5, 0.7 x 21 log-spaced
E_pad in 1e9-1e11 Pa; the coarse test mesh, degree 1, unless --default-mesh)
with the reduced solver for several basis band factors (modes up to factor x
f_max) with and without enrichment, each checked against the full solver at
3 points (the most unstable one and two more). Prints a Markdown table of the
basis size, the basis and per-point times and the largest frequency and
growth-rate errors (from check_full.csv).
"""
import csv
import os
import re
import sys

from common import disc_mesh, run_squeal

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..", "..")
args = [a for a in sys.argv[1:] if not a.startswith("--")]
squeal = args[0] if args else os.path.join(root, "build", "squeal")
work = args[1] if len(args) > 1 else "/tmp/squeal_reduced_table"
default_mesh = "--default-mesh" in sys.argv
MESH = "" if default_mesh else disc_mesh(1, 48, 6, 2)


def run(factor, enrichment):
    name = f"factor{factor}_{'enriched' if enrichment else 'modes_only'}"
    out = os.path.join(work, name)
    stdout, _ = run_squeal(squeal, MESH + f"""subsection Materials
  set Support density model = updated
end
subsection Eigensolver
  set Method = reduced
  set Reduced band factor = {factor}
  set Reduced enrichment = {'true' if enrichment else 'false'}
  set Check points = 3
end
subsection Sweep
  set First parameter = pad.E
  set First values = log 1e9 1e11 21
  set Second parameter = pad on disc.mu
  set Second values = 0.2, 0.5, 0.7
end
""", out)
    kept = int(re.search(r"(\d+) M-orthonormal directions kept", stdout).group(1))

    def section(label):
        m = re.search(r"\| " + label + r"\s*\|\s*\d+\s*\|\s*([\d.e+-]+)s", stdout)
        return float(m.group(1)) if m else float("nan")

    with open(os.path.join(out, "check_full.csv")) as f:
        rows = list(csv.DictReader(f))
    df = max(float(x["freq_rel_error"]) for x in rows)
    dre = max(float(x["re_error_per_abs_re_plus_1"]) for x in rows)
    n_points = 63
    return (factor, enrichment, kept, section("reduced basis"),
            section("reduced solve") / n_points, df, dre)


def main():
    os.makedirs(work, exist_ok=True)
    print("| band factor | enrichment | basis size | basis time [s] | "
          "time per point [s] | largest freq. error | largest growth error |")
    print("|---|---|---|---|---|---|---|")
    for factor in (1.1, 1.25, 1.5, 2.0):
        for enrichment in (False, True):
            f, e, kept, tb, tp, df, dre = run(factor, enrichment)
            print(f"| {f} | {'K^-1 K_t Phi, K^-1 K_n Phi' if e else 'none'} | "
                  f"{kept} | {tb:.1f} | {tp:.3f} | {100 * df:.2g} % | "
                  f"{100 * dre:.2g} % |", flush=True)


if __name__ == "__main__":
    main()
