#!/usr/bin/python3
"""Plots of a squeal complex eigenvalue analysis (thesis Fig. 3.6-3.12, 3.24).

usage: /usr/bin/python3 scripts/plot_cea.py OUTPUT_DIR

Reads OUTPUT_DIR/eigenvalues.csv and unstable_regions.csv; writes
frequency_vs_modulus.png (frequency against log10 E_pad per mu, unstable
eigenvalues in black), locus.png (Re lambda against frequency of the branches
that become unstable) and stability_map.png (unstable regions over
(log10 E_pad, mu), coloured by frequency). Files are written under a
temporary name and renamed.
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


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    try:
        rows = read_csv(os.path.join(out, "eigenvalues.csv"))
        regions = read_csv(os.path.join(out, "unstable_regions.csv"))
    except OSError as e:
        sys.exit(f"plot_cea.py: cannot read results in '{out}': {e}")
    mus = sorted({float(r["mu"]) for r in rows})

    # 1. frequency against log10(E_pad), one panel per mu
    n = len(mus)
    cols = min(3, n)
    nrows = math.ceil(n / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(5 * cols, 4 * nrows),
                             squeeze=False, sharey=True)
    for k, mu in enumerate(mus):
        ax = axes[k // cols][k % cols]
        sel = [r for r in rows if float(r["mu"]) == mu]
        for unstable, style in ((0, dict(s=4, c="0.7")), (1, dict(s=10, c="k"))):
            pts = [r for r in sel if int(r["unstable"]) == unstable]
            ax.scatter([math.log10(float(r["E_pad_Pa"])) for r in pts],
                       [float(r["freq_Hz"]) / 1e3 for r in pts], **style,
                       label="unstable" if unstable else "stable")
        ax.set_title(f"mu = {mu:g}")
        ax.set_xlabel("log10(E_pad / Pa)")
        ax.set_ylabel("frequency [kHz]")
        ax.grid(alpha=0.3)
    axes[0][0].legend(loc="upper left")
    for k in range(n, nrows * cols):
        axes[k // cols][k % cols].axis("off")
    fig.suptitle("Complex eigenvalues against pad modulus (unstable in black)")
    fig.tight_layout()
    save(fig, os.path.join(out, "frequency_vs_modulus.png"))

    # 2. locus of the branches that become unstable
    fig, ax = plt.subplots(figsize=(7, 5))
    for mu in mus:
        tracks = {int(r["track"]) for r in rows
                  if float(r["mu"]) == mu and int(r["unstable"])}
        for t in sorted(tracks):
            pts = [r for r in rows if float(r["mu"]) == mu and int(r["track"]) == t]
            ax.plot([float(r["freq_Hz"]) / 1e3 for r in pts],
                    [float(r["re_per_s"]) for r in pts], ".-", ms=3,
                    label=f"mu={mu:g}, track {t}")
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xlabel("frequency [kHz]")
    ax.set_ylabel("Re(lambda) [1/s]")
    ax.set_title("Locus of the unstable branches over the E_pad sweep")
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
        k = stacked.setdefault(float(r["mu"]), [0])
        r["_offset"] = 0.02 * k[0]
        k[0] += 1
    for r in regions:
        mu = float(r["mu"]) + r["_offset"]
        x0 = math.log10(float(r["E_pad_min_Pa"]))
        x1 = math.log10(float(r["E_pad_max_Pa"]))
        f = 0.5 * (float(r["freq_min_Hz"]) + float(r["freq_max_Hz"]))
        ax.plot([x0, x1 if x1 > x0 else x0 + 0.02], [mu, mu], lw=8,
                color=cmap(f / fmax), solid_capstyle="butt")
        ax.annotate(f"{f / 1e3:.1f} kHz", (x1, mu), fontsize=6,
                    ha="left", va="center", xytext=(3, 0),
                    textcoords="offset points")
    ax.set_yticks(mus)
    ax.set_xlim(math.log10(min(float(r["E_pad_Pa"]) for r in rows)) - 0.05,
                math.log10(max(float(r["E_pad_Pa"]) for r in rows)) + 0.05)
    ax.set_xlabel("log10(E_pad / Pa)")
    ax.set_ylabel("friction coefficient mu")
    ax.set_title("Unstable regions (mode lock-in)")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, os.path.join(out, "stability_map.png"))


if __name__ == "__main__":
    main()
