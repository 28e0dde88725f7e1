#!/usr/bin/env python3
"""Pad-face maps of a squeal preload: contact pressure with the separated
area marked, friction traction, and contact status.
Usage: plot_contact.py OUTPUT_DIR   (reads contact.csv, writes contact_pressure.png)"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402


def main(out):
    with open(os.path.join(out, "contact.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    x = np.array([float(r["x_m"]) for r in rows]) * 1e3
    y = np.array([float(r["y_m"]) for r in rows]) * 1e3
    p = np.array([float(r["p_N_Pa"]) for r in rows]) / 1e6
    t = np.array([float(r["t_T1_Pa"]) for r in rows]) / 1e6
    st = np.array([int(r["status"]) for r in rows])
    tri = mtri.Triangulation(x, y)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    for ax, v, title, cmap in [
            (axes[0], p, "contact pressure p_N [MPa]", "viridis"),
            (axes[1], t, "friction traction along the sliding direction [MPa]",
             "plasma")]:
        c = ax.tricontourf(tri, v, levels=20, cmap=cmap)
        fig.colorbar(c, ax=ax, shrink=0.85)
        sep = st == 0
        ax.plot(x[sep], y[sep], "wx", ms=7, label="separated")
        ax.set_title(title, fontsize=10)
    names = {0: "separated", 1: "stick", 2: "slip"}
    for s, colour in [(0, "lightgrey"), (1, "tab:blue"), (2, "tab:red")]:
        m = st == s
        if m.any():
            axes[2].scatter(x[m], y[m], c=colour, s=60, marker="s",
                            label=names[s])
    axes[2].legend(loc="upper right", fontsize=8)
    axes[2].set_title("contact status", fontsize=10)
    for ax in axes:
        ax.set_xlabel("x [mm] (radius)")
        ax.set_ylabel("y [mm] (sliding direction)")
        ax.set_aspect("equal")
    area = (st != 0).mean() * 100
    fig.suptitle(f"Pad face after the preload: {area:.0f} % of the nodes in "
                 f"contact, peak pressure {p.max():.2f} MPa, mean over the "
                 f"contact nodes {p[st != 0].mean():.2f} MPa")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "contact_pressure.png"), dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
