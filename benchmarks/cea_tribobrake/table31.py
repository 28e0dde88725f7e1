#!/usr/bin/env python3
"""Compare a squeal run at the thesis Table 3.1 point with the thesis table.

Usage: table31.py OUTDIR

OUTDIR is the output directory of `build/squeal prm/tribobrake_cea_point.prm`
(E_pad = 25 GPa, mu = 0.5). Reads OUTDIR/mode_participation.csv (one row per
mode: frequency, growth rate, kinetic-energy shares of disc, pad and support,
and the name squeal gives a disc-dominated mode) and prints a Markdown table:
each thesis mode against the squeal mode of the same name nearest to it in
frequency, with the difference and the disc's share. A thesis mode without a
"+" or "-" (the thesis did not split it) takes the nearest squeal mode of
either member. Thesis modes without a named squeal counterpart are listed as
such, never paired by frequency alone.

Source of the reference values: F. Massi, PhD thesis (2006), Table 3.1, as
transcribed in shared/spec/tribobrake.md.
"""
import csv
import os
import sys

THESIS = [("(0,3-)", 2594), ("(0,3+)", 3492), ("(0,4-)", 3918),
          ("(0,4+)", 4992), ("(0,5-)", 5736), ("(0,5+)", 6659),
          ("(0,6-)", 7956), ("(0,6+)", 8594), ("(1,0)", 10126),
          ("(0,7)", 10523), ("(1,2)", 11144), ("(1,3)", 12494),
          ("(0,8+)", 13401), ("(0,8-)", 13700), ("(1,4-)", 14437),
          ("(1,4+)", 14475), ("(0,9+)", 16565), ("(0,9-)", 16724),
          ("(1,5-)", 16970), ("(1,5+)", 17036), ("(0,10+)", 19989),
          ("(0,10-)", 20018)]


def strip_sign(name):
    """(0,3+) -> (0,3); (1,2) -> (1,2)."""
    return name.replace("+", "").replace("-", "")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    path = os.path.join(sys.argv[1], "mode_participation.csv")
    if not os.path.isfile(path):
        sys.exit(f"table31.py: {path} not found (run build/squeal "
                 "prm/tribobrake_cea_point.prm first)")
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["point"] == "0"]
    if not rows:
        sys.exit(f"table31.py: {path} has no rows for sweep point 0")
    print("| mode | thesis [Hz] | squeal [Hz] | difference | disc share | "
          "Re lambda [1/s] |")
    print("|---|---|---|---|---|---|")
    missing = []
    diffs = []
    for name, f_thesis in THESIS:
        signed = name.endswith(("+)", "-)"))
        cands = [r for r in rows
                 if (r["name"] == name if signed
                     else strip_sign(r["name"]) == name)]
        if not cands:
            missing.append((name, f_thesis))
            continue
        r = min(cands, key=lambda r: abs(float(r["freq_Hz"]) - f_thesis))
        f = float(r["freq_Hz"])
        d = 100 * (f - f_thesis) / f_thesis
        diffs.append(d)
        print(f"| {name} | {f_thesis} | {f:.1f} | {d:+.1f} % | "
              f"{float(r['disc']):.2f} | {float(r['re_per_s']):.1f} |")
    if diffs:
        print(f"\n{len(diffs)} of {len(THESIS)} thesis modes named by squeal; "
              f"differences {min(diffs):+.1f} % to {max(diffs):+.1f} %.")
    if missing:
        print("Not named by squeal (no disc-dominated mode of that name): " +
              ", ".join(f"{n} ({f} Hz)" for n, f in missing) + ".")


if __name__ == "__main__":
    main()
