#!/usr/bin/env python3
"""Plots of a squeal-tribology run: PNG maps of the pad face and the
correlation report. Usage: plot_tribology.py OUTPUT_DIR

Reads damage.csv, maps.csv, correlation.csv, roc.csv (whichever exist) and
writes damage_maps.png, image_maps.png, correlation.png into OUTPUT_DIR.
Face axes: s along the sliding direction (the disc enters the contact at the
smallest s, the leading edge), r along the radius."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) if r[k] not in ("", "nan") else math.nan
                         for r in rows]) if k not in ("file", "statistic")
            else [r[k] for r in rows] for k in (rows[0].keys() if rows else [])}


def grid(maps, column):
    i = maps["i"].astype(int)
    j = maps["j"].astype(int)
    a = np.full((j.max() + 1, i.max() + 1), np.nan)
    a[j, i] = maps[column]
    return a


def extent(maps):
    h = (maps["s_m"][1] - maps["s_m"][0]) if len(maps["s_m"]) > 1 else 1e-3
    s, r = maps["s_m"] * 1e3, maps["r_m"] * 1e3
    h *= 1e3
    return [s.min() - h / 2, s.max() + h / 2, r.min() - h / 2, r.max() + h / 2]


def face_axes(ax, title):
    ax.set_title(title, fontsize=10)
    ax.set_xlabel("s [mm] (sliding direction; leading edge at left)")
    ax.set_ylabel("r [mm] (radius)")
    ax.set_aspect("equal")


def face_name(out):
    """The analysed pad face (Contact history/Face in the run's echoed
    parameters.prm), or "" for the history's only face."""
    try:
        with open(os.path.join(out, "parameters.prm")) as f:
            for line in f:
                words = line.split("#")[0].split("=", 1)
                if len(words) == 2 and words[0].split() == ["set", "Face"]:
                    return words[1].strip()
    except OSError:
        pass
    return ""


def main(out):
    face = face_name(out)
    face_title = f"Pad face '{face}'" if face else "Pad face"
    damage_path = os.path.join(out, "damage.csv")
    maps = read(os.path.join(out, "maps.csv"))
    if os.path.exists(damage_path):
        d = read(damage_path)
        s, r = d["s_m"] * 1e3, d["r_m"] * 1e3
        fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
        panels = [
            (np.log10(np.maximum(d["D_star_Pa_pow_m"], 1e-300)),
             "Findley damage log10 D* [log10 Pa^m]", "inferno"),
            (d["p_range_rel"], "pressure range / mean pressure [-]", "viridis"),
            (d["separated_fraction"], "fraction of time separated [-]", "cividis"),
        ]
        for ax, (v, title, cmap) in zip(axes, panels):
            sc = ax.scatter(s, r, c=v, cmap=cmap, s=90, marker="s")
            fig.colorbar(sc, ax=ax, shrink=0.85)
            face_axes(ax, title)
        fig.suptitle(f"{face_title}: fatigue damage and contact-pressure "
                     "statistics per contact node")
        fig.tight_layout()
        fig.savefig(os.path.join(out, "damage_maps.png"), dpi=110)
        plt.close(fig)

    if "crack_length_per_area_mm_per_mm2" in maps and \
            np.isfinite(maps["crack_length_per_area_mm_per_mm2"]).any():
        fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
        for ax, (col, title, cmap) in zip(axes, [
                ("crack_length_per_area_mm_per_mm2",
                 "crack length per area L_A [mm/mm^2]", "magma"),
                ("exfoliated_fraction", "exfoliated area fraction [-]", "Blues"),
                ("coverage", "imaged fraction of the cell [-]", "Greys")]):
            im = ax.imshow(grid(maps, col), origin="lower", extent=extent(maps),
                           cmap=cmap, interpolation="nearest")
            fig.colorbar(im, ax=ax, shrink=0.85)
            face_axes(ax, title)
        fig.suptitle(f"{face_title}: crack and exfoliation maps from the SEM "
                     "images")
        fig.tight_layout()
        fig.savefig(os.path.join(out, "image_maps.png"), dpi=110)
        plt.close(fig)

    corr_path = os.path.join(out, "correlation.csv")
    if os.path.exists(corr_path):
        c = read(corr_path)
        stats = dict(zip(c["statistic"], zip(c["value"], c["p_value"])))
        roc = read(os.path.join(out, "roc.csv"))
        fig, axes = plt.subplots(1, 4, figsize=(19, 4.6))
        dmg = maps["log10_damage"]
        cr = maps["crack_length_per_area_mm_per_mm2"]
        ok = np.isfinite(dmg) & np.isfinite(cr)
        axes[0].scatter(dmg[ok], cr[ok], s=14)
        rho, p = stats["spearman_log_damage_vs_crack_density"]
        axes[0].set_title(f"cells: Spearman rho = {rho:.2f} (toroidal p = {p:.3g})",
                          fontsize=10)
        axes[0].set_xlabel("log10 D* (Findley)")
        axes[0].set_ylabel("L_A [mm/mm^2]")
        auc, pa = stats["roc_auc_log_damage_predicts_cracked"]
        axes[1].plot(roc["false_positive_rate"], roc["true_positive_rate"], "-")
        axes[1].plot([0, 1], [0, 1], ":", color="grey")
        axes[1].set_title(f"ROC: damage predicts cracked cells, AUC = {auc:.2f} "
                          f"(p = {pa:.3g})", fontsize=10)
        axes[1].set_xlabel("false-positive rate")
        axes[1].set_ylabel("true-positive rate")
        axes[1].set_aspect("equal")
        for ax, col, title, cmap in [
                (axes[2], "log10_damage", "log10 D* (Findley)", "inferno"),
                (axes[3], "crack_length_per_area_mm_per_mm2",
                 "L_A [mm/mm^2]", "magma")]:
            im = ax.imshow(grid(maps, col), origin="lower", extent=extent(maps),
                           cmap=cmap, interpolation="nearest")
            fig.colorbar(im, ax=ax, shrink=0.85)
            face_axes(ax, title)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "correlation.png"), dpi=110)
        plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
