#!/usr/bin/python3
"""Plots of a squeal complex eigenvalue analysis (thesis Fig. 3.6-3.12, 3.24).

usage: /usr/bin/python3 scripts/plot_cea.py OUTPUT_DIR

Reads OUTPUT_DIR/eigenvalues.csv, unstable_regions.csv and sweep_axes.csv
(which named parameters were swept); writes
frequency_vs_modulus.png (frequency against the first swept parameter, e.g.
log10 pad.E, one panel per value of the second, e.g. pad on disc.mu, unstable eigenvalues
in black), locus.png (Re lambda against frequency of the branches that become
unstable) and stability_map.png (unstable regions over the two swept
parameters, coloured by frequency). Files are written under a temporary name
and renamed.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save(fig, path):
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=130)
    os.replace(tmp, path)
    plt.close(fig)
    print("wrote", path)


class Axis:
    """A swept parameter: its name, CSV column and whether to plot log10."""

    UNITS = ("_Pa", "_N_per_m3", "_N_per_m", "_kg_per_m3", "_per_s", "_s")

    def __init__(self, name, column, log):
        self.name, self.column, self.log = name, column, log
        self.label = f"log10({column})" if log else column

    def value(self, row, column=None):
        return float(row[column or self.column])

    def x(self, v):
        return math.log10(v) if self.log else v

    def bound(self, which):
        """pad.E_Pa -> pad.E_min_Pa; pad_on_disc.mu -> pad_on_disc.mu_min
        (unstable_regions.csv)."""
        for unit in self.UNITS:
            if self.column.endswith(unit):
                return self.column[: -len(unit)] + "_" + which + unit
        return self.column + "_" + which


def read_axes(out):
    path = os.path.join(out, "sweep_axes.csv")
    axes = {r["axis"]: Axis(r["parameter"], r["column"], r["log"] == "1")
            for r in read_csv(path)}
    return axes["first"], axes["second"]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    try:
        rows = read_csv(os.path.join(out, "eigenvalues.csv"))
        regions = read_csv(os.path.join(out, "unstable_regions.csv"))
        first, second = read_axes(out)
    except (OSError, KeyError) as e:
        sys.exit(f"plot_cea.py: cannot read results in '{out}': {e}")
    mus = sorted({second.value(r) for r in rows})

    # 1. frequency against log10(E_pad), one panel per mu
    n = len(mus)
    cols = min(3, n)
    nrows = math.ceil(n / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(5 * cols, 4 * nrows),
                             squeeze=False, sharey=True)
    for k, mu in enumerate(mus):
        ax = axes[k // cols][k % cols]
        sel = [r for r in rows if second.value(r) == mu]
        for unstable, style in ((0, dict(s=4, c="0.7")), (1, dict(s=10, c="k"))):
            pts = [r for r in sel if int(r["unstable"]) == unstable]
            ax.scatter([first.x(first.value(r)) for r in pts],
                       [float(r["freq_Hz"]) / 1e3 for r in pts], **style,
                       label="unstable" if unstable else "stable")
        ax.set_title(f"{second.column} = {mu:g}")
        ax.set_xlabel(first.label)
        ax.set_ylabel("frequency [kHz]")
        ax.grid(alpha=0.3)
    axes[0][0].legend(loc="upper left")
    for k in range(n, nrows * cols):
        axes[k // cols][k % cols].axis("off")
    fig.suptitle(f"Complex eigenvalues against {first.name} (unstable in black)")
    fig.tight_layout()
    save(fig, os.path.join(out, "frequency_vs_modulus.png"))

    # 2. locus of the branches that become unstable
    fig, ax = plt.subplots(figsize=(7, 5))
    for mu in mus:
        tracks = {int(r["track"]) for r in rows
                  if second.value(r) == mu and int(r["unstable"])}
        for t in sorted(tracks):
            pts = [r for r in rows
                   if second.value(r) == mu and int(r["track"]) == t]
            ax.plot([float(r["freq_Hz"]) / 1e3 for r in pts],
                    [float(r["re_per_s"]) for r in pts], ".-", ms=3,
                    label=f"{second.column}={mu:g}, track {t}")
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xlabel("frequency [kHz]")
    ax.set_ylabel("Re(lambda) [1/s]")
    ax.set_title(f"Locus of the unstable branches over the {first.name} sweep")
    if ax.lines[1:]:
        ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, os.path.join(out, "locus.png"))

    # 3. stability map
    fig, ax = plt.subplots(figsize=(7, 4))
    cmap = plt.get_cmap("viridis")
    fmax = max([float(r["freq_max_Hz"]) for r in regions] + [1.0])
    # regions of one mu are stacked slightly apart so that none hides another
    stacked = {}
    for r in sorted(regions, key=lambda r: float(r["freq_min_Hz"])):
        k = stacked.setdefault(float(r[second.column]), [0])
        r["_offset"] = 0.02 * k[0]
        k[0] += 1
    for r in regions:
        mu = float(r[second.column]) + r["_offset"] * (
            (mus[-1] - mus[0]) / 0.7 if len(mus) > 1 and mus[-1] > mus[0] else 1)
        x0 = first.x(float(r[first.bound("min")]))
        x1 = first.x(float(r[first.bound("max")]))
        span = (first.x(max(first.value(r) for r in rows))
                - first.x(min(first.value(r) for r in rows))) or 1.0
        f = 0.5 * (float(r["freq_min_Hz"]) + float(r["freq_max_Hz"]))
        ax.plot([x0, x1 if x1 > x0 else x0 + 0.01 * span], [mu, mu], lw=8,
                color=cmap(f / fmax), solid_capstyle="butt")
        ax.annotate(f"{f / 1e3:.1f} kHz", (x1, mu), fontsize=6,
                    ha="left", va="center", xytext=(3, 0),
                    textcoords="offset points")
    ax.set_yticks(mus)
    lo = first.x(min(first.value(r) for r in rows))
    hi = first.x(max(first.value(r) for r in rows))
    pad = 0.025 * (hi - lo) if hi > lo else 0.05
    ax.set_xlim(lo - pad, hi + pad)
    ax.set_xlabel(first.label)
    ax.set_ylabel(f"{second.name} ({second.column})")
    ax.set_title("Unstable regions (mode lock-in)")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, os.path.join(out, "stability_map.png"))


if __name__ == "__main__":
    main()
