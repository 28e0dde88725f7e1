#!/usr/bin/env python3
"""Stability map of a braking grid (squeal, Transient/Grid = true).

usage: plot_braking_grid.py OUTPUT_DIR [CEA_DIR]

Reads OUTPUT_DIR/stability_table.csv and writes OUTPUT_DIR/stability_map.png:
one marker per braking run at its two swept parameters, filled red where the
run was unstable and blue where it was stable, labelled with the dominant
frequency and the growth rate at it. With CEA_DIR (the output of a CEA of the
same file, e.g. Scene/Analysis = preloaded cea), the CEA's unstable regions
(unstable_regions.csv) are drawn underneath as horizontal bars, so the two
methods are compared at a glance.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(l for l in f if not l.startswith("#")))


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    out = sys.argv[1]
    table = rows(os.path.join(out, "stability_table.csv"))
    if not table:
        sys.exit(f"{out}/stability_table.csv has no rows")
    x_name, y_name = list(table[0].keys())[2:4]
    fig, ax = plt.subplots(figsize=(7, 5))
    if len(sys.argv) == 3:
        regions = rows(os.path.join(sys.argv[2], "unstable_regions.csv"))
        for r in regions:
            keys = list(r.keys())
            y = float(r[keys[0]])
            lo, hi = float(r[keys[1]]), float(r[keys[2]])
            ax.plot([lo, hi], [y, y], color="0.75", lw=8, solid_capstyle="butt",
                    zorder=1, label="CEA unstable" if r is regions[0] else None)
    for r in table:
        x, y = float(r[x_name]), float(r[y_name])
        if r["verdict"].startswith("failed"):
            ax.scatter([x], [y], marker="x", color="k", zorder=3)
            continue
        unstable = r["verdict"].startswith("unstable")
        ax.scatter([x], [y], s=120, zorder=3, color="tab:red" if unstable else "tab:blue",
                   edgecolors="k")
        f = float(r["dominant_frequency_Hz"])
        g = float(r["growth_rate_at_dominant_frequency_per_s"] if unstable
                  else r["growth_rate_per_s"])
        ax.annotate(f"{f / 1e3:.2f} kHz\n{g:+.0f} 1/s", (x, y), textcoords="offset points",
                    xytext=(8, 6), fontsize=8)
    xs = [float(r[x_name]) for r in table]
    if min(xs) > 0 and max(xs) / min(xs) > 20:
        ax.set_xscale("log")
    ax.set_xlabel(x_name)
    ax.set_ylabel(y_name)
    ax.scatter([], [], color="tab:red", edgecolors="k", label="braking: unstable")
    ax.scatter([], [], color="tab:blue", edgecolors="k", label="braking: stable")
    ax.legend(loc="center", fontsize=8)
    ax.set_title("Braking runs: stability (growth rate at the dominant frequency)")
    ax.grid(True, alpha=0.3)
    ax.margins(x=0.15, y=0.2)
    fig.tight_layout()
    path = os.path.join(out, "stability_map.png")
    fig.savefig(path + ".tmp.png", dpi=120)
    os.replace(path + ".tmp.png", path)
    print("wrote", path)


if __name__ == "__main__":
    main()
