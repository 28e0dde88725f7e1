#!/usr/bin/python3
"""Speed against error of the TriboBrake CEA at the Table 3.1 point.

usage: /usr/bin/python3 benchmarks/speed_vs_error/run_tribobrake.py [SQUEAL] [WORKDIR] [adaptive]

Runs build/squeal (full solver) at E_pad = 25 GPa, mu = 0.5 on uniform disc
meshes of degree 2 and 3 (pad 4 x 4 x 2, support 4 x 4 x 10 as in the
default) and compares the frequencies and growth rates of the modes in
900-20 000 Hz with those of the finest run (degree 3, 48 x 6 x 2): each
reference mode against the computed mode nearest in frequency. Prints a Markdown table: DoFs, wall time,
largest and median frequency difference, largest growth-rate difference
(in 1/s and in % of |Re| + 1 1/s). The adaptive rows start from a uniform
mesh and refine by Kelly's indicator on the modes of this point
(`Mesh/Adaptive cycles`, fixed cell fraction); their DoFs and time are those
of the final mesh's solve and of the whole run. With `adaptive` as the third
argument only the reference and the adaptive rows run.
"""
import re
import os
import statistics
import sys

from common import disc_mesh, read_run, run_squeal, single_point_sweep

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..", "..")
squeal = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "squeal")
work = sys.argv[2] if len(sys.argv) > 2 else "/tmp/squeal_tribobrake_sequence"
MESHES = [(2, 48, 6, 2), (2, 64, 10, 2), (3, 32, 4, 1), (3, 48, 6, 2)]
# (degree, disc cells around, radial, thick, cycles, fraction)
ADAPTIVE = [(2, 64, 10, 2, 2, 0.15)]


def run(degree, around, radial, thick):
    out = os.path.join(work, f"d{degree}_{around}x{radial}x{thick}")
    stdout, seconds = run_squeal(squeal, disc_mesh(degree, around, radial, thick) + f"""subsection Eigensolver
  set Method = full
end
""" + single_point_sweep("pad modulus", 25e9, "friction coefficient", 0.5), out)
    dofs, modes = read_run(stdout, out)
    return dict(mesh=os.path.basename(out), dofs=dofs, seconds=seconds,
                modes=modes)


def run_adaptive(degree, around, radial, thick, cycles, fraction):
    out = os.path.join(work, f"d{degree}_{around}x{radial}x{thick}_"
                       f"adaptive{cycles}x{fraction}")
    stdout, seconds = run_squeal(squeal, disc_mesh(degree, around, radial, thick)
                                 .replace("end\n", f"""  set Adaptive cycles = {cycles}
  set Refinement fraction = {fraction}
end
""", 1) + """subsection Eigensolver
  set Method = full
end
""" + single_point_sweep("pad modulus", 25e9, "friction coefficient", 0.5), out)
    _, modes = read_run(stdout, out)
    # the final mesh: the last adaptive cycle's report
    dofs = int(re.findall(r"Adaptive cycle \d+: \d+ cells, (\d+) DoFs",
                          stdout)[-1])
    return dict(mesh=os.path.basename(out), dofs=dofs, seconds=seconds,
                modes=modes)


def main():
    os.makedirs(work, exist_ok=True)
    only_adaptive = len(sys.argv) > 3 and sys.argv[3] == "adaptive"
    runs = [run(*m) for m in (MESHES[-1:] if only_adaptive else MESHES)]
    ref = runs[-1]["modes"]
    runs += [run_adaptive(*a) for a in ADAPTIVE]
    print("| mesh | DoFs | wall time [s] | modes | largest freq. diff. | "
          "median freq. diff. | largest growth diff. |")
    print("|---|---|---|---|---|---|---|")
    for r in runs:
        # each reference mode against the computed mode nearest in frequency
        # (counts differ by a mode at the band edges)
        df, dre = [], []
        for f_ref, re_ref in ref:
            f, re = min(r["modes"], key=lambda m: abs(m[0] - f_ref))
            df.append(abs(f - f_ref) / f_ref)
            dre.append(abs(re - re_ref) / (abs(re_ref) + 1))
        print(f"| {r['mesh']} | {r['dofs']} | {r['seconds']:.0f} | "
              f"{len(r['modes'])} | {100 * max(df):.3f} % | "
              f"{100 * statistics.median(df):.3f} % | {100 * max(dre):.2g} % |",
              flush=True)


if __name__ == "__main__":
    main()
