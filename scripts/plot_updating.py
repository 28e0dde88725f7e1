#!/usr/bin/env python3
"""Before/after plot of a squeal model updating: each measured mode's
frequency error of the start and the fitted model (per cent), and the MAC
matrix of the measured against the fitted model's modes (with measurement
points).
Usage: plot_updating.py OUTPUT_DIR   (reads targets.csv and mac.csv, writes
updating.png)"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def rows(out, name):
    with open(os.path.join(out, name), newline="") as f:
        return list(csv.DictReader(f))


def main(out):
    targets = rows(out, "targets.csv")
    labels = [t["label"] for t in targets]
    before = [float(t["initial_error_percent"]) for t in targets]
    after = [float(t["error_percent"]) for t in targets]
    mac_file = os.path.join(out, "mac.csv")
    has_mac = os.path.exists(mac_file)
    fig, axes = plt.subplots(1, 2 if has_mac else 1,
                             figsize=(14 if has_mac else 8, 5), squeeze=False)
    ax = axes[0][0]
    y = np.arange(len(labels))
    ax.barh(y + 0.2, before, 0.4, label="start", color="lightgrey")
    ax.barh(y - 0.2, after, 0.4, label="fitted", color="tab:blue")
    ax.set_yticks(y)
    ax.set_yticklabels(
        [f"{lab} ({float(t['measured_Hz']):.0f} Hz)" for lab, t in
         zip(labels, targets)], fontsize=8)
    ax.invert_yaxis()
    ax.axvline(0, color="k", lw=0.8)
    ax.set_xlabel("model - measured frequency [%]")
    ax.legend()
    ax.set_title("frequency residuals")
    if has_mac:
        with open(mac_file, newline="") as f:
            table = list(csv.reader(f))
        modes = table[0][1:]
        values = np.array([[float(v) for v in r[1:]] for r in table[1:]])
        ax = axes[0][1]
        im = ax.imshow(values, vmin=0, vmax=1, cmap="Blues", aspect="auto")
        fig.colorbar(im, ax=ax, shrink=0.85, label="MAC")
        ax.set_yticks(range(len(table) - 1))
        ax.set_yticklabels([r[0] for r in table[1:]], fontsize=8)
        ax.set_xticks(range(len(modes)))
        ax.set_xticklabels(modes, rotation=90, fontsize=6)
        ax.set_title("MAC: measured (rows) against fitted model modes")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "updating.png"), dpi=120)
    print(os.path.join(out, "updating.png"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
