#!/usr/bin/python3
"""The TriboBrake with a steel support under three contact models, over the
pad modulus (issue 26, section 0): how the preload's contact law moves the
instability's E_pad range and its growth-rate trend.

usage: run_contact_law.py [SQUEAL] [WORKDIR]   (defaults: build/squeal,
                                                output/contact_law)

For each E_pad of 1-100 GPa (9 values, log-spaced) it runs squeal on
steel_support.prm (mu = 0.5, 100 N, no damping, full solver, 0.9-16 kHz)
with
- `penalty 2.59e12`: the preload with the compliant law p = k_n x
  penetration, k_n = 2.5895e12 N/m^3, and the CEA's interface with the same
  k_n where that preload keeps the pad in contact (consistent);
- `penalty 1e14`: the same with k_n = 1e14 N/m^3, the hard-contact limit
  in both (consistent);
- `no preload`: the plain CEA with k_n = 2.5895e12 on the whole pad face
  (the thesis' practice).
The preload is computed at each E_pad (Materials/Pad is set with the sweep
point). It writes WORKDIR/contact_law.csv (one row per unstable eigenvalue,
or one row with n_unstable = 0) and contact_law.png, and prints a table.
"""
import csv
import math
import os
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
squeal = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                         os.path.join(root, "build", "squeal"))
work = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else
                       os.path.join(root, "output", "contact_law"))
base = os.path.join(here, "steel_support.prm")
os.makedirs(work, exist_ok=True)

VARIANTS = [("penalty 2.59e12", "preloaded cea", 2.5895e12),
            ("penalty 1e14", "preloaded cea", 1e14),
            ("no preload", "cea", 2.5895e12)]
MODULI = [10 ** (9 + 0.25 * i) for i in range(9)]


def run(label, analysis, k_n, e_pad):
    """One point; returns (unstable [(freq, re)], separated fraction, s)."""
    name = f"{label.replace(' ', '_')}_E{e_pad:.3e}"
    out = os.path.join(work, name)
    if not os.path.isdir(out):
        prm = os.path.join(work, name + ".prm")
        with open(prm, "w") as f:
            f.write(f"""include {base}
subsection Scene
  set Analysis = {analysis}
end
subsection Materials
  subsection Pad
    set Young's modulus = {e_pad!r}
  end
end
subsection Interface
  set Normal stiffness = {k_n!r}
end
subsection Sweep
  set First parameter = pad.E
  set First values = {e_pad!r}
  set Second parameter = pad on disc.mu
  set Second values = 0.5
end
subsection Output
  set Directory = {out}
end
""")
        start = time.time()
        r = subprocess.run([squeal, prm], capture_output=True, text=True)
        seconds = time.time() - start
        if r.returncode != 0:
            sys.exit(f"{name}: exit {r.returncode}\n{r.stdout[-2000:]}\n"
                     f"{r.stderr}")
        with open(os.path.join(out, "wall_time_s.txt"), "w") as f:
            f.write(f"{seconds:.1f}\n")
    with open(os.path.join(out, "wall_time_s.txt")) as f:
        seconds = float(f.read())
    with open(os.path.join(out, "eigenvalues.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{name}: eigenvalues.csv is empty")
    unstable = [(float(r["freq_Hz"]), float(r["re_per_s"])) for r in rows
                if r["unstable"] == "1"]
    separated = 0.
    contact = os.path.join(out, "preload", "contact.csv")
    if os.path.exists(contact):
        with open(contact, newline="") as f:
            status = [int(r["status"]) for r in csv.DictReader(f)]
        separated = sum(s == 0 for s in status) / len(status)
    return unstable, separated, seconds


results = []
for label, analysis, k_n in VARIANTS:
    for e_pad in MODULI:
        unstable, separated, seconds = run(label, analysis, k_n, e_pad)
        results.append((label, e_pad, separated, unstable, seconds))
        modes = ", ".join(f"{f:.0f} Hz {re:+.1f}/s" for f, re in unstable)
        print(f"{label:16s} E_pad {e_pad / 1e9:7.2f} GPa  separated "
              f"{100 * separated:5.1f} %  {len(unstable)} unstable: "
              f"{modes or '-'}  ({seconds:.0f} s)", flush=True)

with open(os.path.join(work, "contact_law.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["model", "pad.E_Pa", "separated_fraction", "n_unstable",
                "freq_Hz", "re_per_s", "wall_time_s"])
    for label, e_pad, separated, unstable, seconds in results:
        for freq, re in unstable or [(math.nan, math.nan)]:
            w.writerow([label, f"{e_pad:.6e}", f"{separated:.4f}",
                        len(unstable), f"{freq:.3f}", f"{re:.4f}",
                        f"{seconds:.1f}"])

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
markers = {"penalty 2.59e12": "o", "penalty 1e14": "s", "no preload": "^"}
for label, _, _ in VARIANTS:
    xs, ys, cs = [], [], []
    for lab, e_pad, _, unstable, _ in results:
        if lab == label:
            for freq, re in unstable:
                xs.append(e_pad)
                ys.append(re)
                cs.append(freq / 1e3)
    sc = a.scatter(xs, ys, c=cs, cmap="viridis", vmin=1, vmax=16,
                   marker=markers[label], label=label, edgecolors="k")
    sep = [(e, 100 * s) for lab, e, s, _, _ in results if lab == label]
    b.plot([e for e, _ in sep], [s for _, s in sep], marker=markers[label],
           label=label)
a.set_xscale("log")
a.set_yscale("log")
a.set_xlabel("E_pad [Pa]")
a.set_ylabel("Re lambda [1/s] of the unstable modes")
a.legend(fontsize=8)
fig.colorbar(sc, ax=a, label="frequency [kHz]")
b.set_xscale("log")
b.set_xlabel("E_pad [Pa]")
b.set_ylabel("pad face separated by the preload [%]")
b.legend(fontsize=8)
fig.suptitle("TriboBrake, steel support, mu = 0.5, 100 N, no damping")
fig.tight_layout()
fig.savefig(os.path.join(work, "contact_law.png"), dpi=110)
print("wrote", os.path.join(work, "contact_law.csv"), "and contact_law.png")
