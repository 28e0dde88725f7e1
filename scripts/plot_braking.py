#!/usr/bin/env python3
"""Plots of a braking run (squeal Scene/Analysis = braking), thesis Fig. 3.13-3.19.

usage: plot_braking.py OUTPUT_DIR

Writes OUTPUT_DIR/braking.png: the sum of the normal and tangential contact
forces against time, the probe's (pad leading edge) velocity along the
sliding direction with its envelope and fitted growth, the power spectral
density of that acceleration, and the stick / slip / separated node counts.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    rows = []
    with open(path) as f:
        lines = [l for l in f if not l.startswith("#")]
    reader = csv.DictReader(lines)
    for r in reader:
        rows.append(r)
    return rows


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    d = sys.argv[1]
    forces = read(os.path.join(d, "forces.csv"))
    probes = read(os.path.join(d, "probes.csv"))
    spectrum = read(os.path.join(d, "spectrum.csv"))
    envelope = read(os.path.join(d, "envelope.csv"))
    summary = {r["quantity"]: r["value"] for r in read(os.path.join(d, "summary.csv"))}
    with open(os.path.join(d, "probes.csv")) as f:
        head = f.readline()
    sliding = [float(v) for v in head.split("sliding direction (")[1].split(")")[0].split(",")]

    t = [1e3 * float(r["time_s"]) for r in forces]
    fig, ax = plt.subplots(2, 2, figsize=(13, 8))
    a = ax[0][0]
    a.plot(t, [float(r["normal_force_N"]) for r in forces], label="normal")
    a.plot(t, [float(r["tangential_force_N"]) for r in forces], label="tangential (sliding direction)")
    a.set_xlabel("time [ms]")
    a.set_ylabel("sum of contact forces [N]")
    a.legend()
    a.grid(alpha=0.3)

    a = ax[0][1]
    tp = [1e3 * float(r["time_s"]) for r in probes]
    vel = [sum(s * float(r["v_%s_m_per_s" % c]) for s, c in zip(sliding, "xyz")) for r in probes]
    a.plot(tp, vel, lw=0.5, label="probe velocity")
    if envelope:
        te = [1e3 * float(r["time_s"]) for r in envelope]
        a.plot(te, [float(r["envelope_m_per_s"]) for r in envelope], "r-", lw=1, label="envelope")
        g = float(summary.get("growth_rate_per_s", 0))
        t0 = float(summary.get("growth_fit_start_s", 0))
        t1 = float(summary.get("growth_fit_end_s", 0))
        pts = [(1e3 * float(r["time_s"]), float(r["envelope_m_per_s"])) for r in envelope
               if t0 <= float(r["time_s"]) <= t1]
        if pts and g != 0:
            tm, em = pts[0]
            xs = [p[0] for p in pts]
            a.plot(xs, [em * math.exp(g * (x - tm) * 1e-3) for x in xs], "k--",
                   label="fit: growth %.0f 1/s" % g)
    a.set_xlabel("time [ms]")
    a.set_ylabel("tangential velocity, pad leading edge [m/s]")
    a.legend()
    a.grid(alpha=0.3)

    a = ax[1][0]
    f = [float(r["frequency_Hz"]) for r in spectrum]
    p = [float(r["psd_m2_per_s4_per_Hz"]) for r in spectrum]
    a.semilogy([x / 1e3 for x in f[1:]], p[1:])
    a.set_xlim(0, min(50, f[-1] / 1e3) if f else 50)
    a.set_xlabel("frequency [kHz]")
    a.set_ylabel("PSD of the acceleration [(m/s^2)^2/Hz]")
    a.set_title("dominant %.0f Hz; %s" % (float(summary["dominant_frequency_Hz"]), summary["verdict"]))
    a.grid(alpha=0.3)

    a = ax[1][1]
    for key, label in (("n_stick", "stick"), ("n_slip", "slip"), ("n_separated", "separated")):
        a.plot(t, [float(r[key]) for r in forces], label=label)
    a.set_xlabel("time [ms]")
    a.set_ylabel("pad-face nodes")
    a.legend()
    a.grid(alpha=0.3)
    fig.tight_layout()
    out = os.path.join(d, "braking.png")
    fig.savefig(out + ".tmp.png", dpi=110)
    os.replace(out + ".tmp.png", out)
    print("wrote", out)


if __name__ == "__main__":
    main()
