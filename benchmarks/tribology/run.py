#!/usr/bin/python3
"""Tribology benchmark: accuracy figures and run times, measured.

usage: run.py [BUILD_DIR]   (default: build/ of this repository)

1. Runs the tribology tests with SQUEAL_VERBOSE=1 and prints the measured
   values behind their pass/fail lines (crack length, skeleton F1, area
   fraction, registration error, toroidal-test calibration).
2. Runs build/squeal-tribology on prm/tribology_synthetic.prm and on the real
   micrographs of ../shared/data/micrographs (granite.prm, laminate.prm),
   printing images.csv, the correlation and the wall times.
Outputs go to output/benchmark_* (replaced).
"""
import csv
import os
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.abspath(os.path.join(here, "..", ".."))
build = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(root, "build")
exe = os.path.join(build, "squeal-tribology")
os.chdir(root)

print("== accuracy (tests, measured values) ==")
for test in ["tribology_images", "tribology_correlation"]:
    binary = os.path.join(build, "tests", f"{test}.release", f"{test}.release")
    r = subprocess.run([binary], capture_output=True, text=True,
                       env=dict(os.environ, SQUEAL_VERBOSE="1"), cwd="/tmp")
    print(f"-- {test} ({'passed' if r.returncode == 0 else 'FAILED'})")
    print("\n".join(l for l in r.stderr.splitlines() if "crack at" not in l))


def run(prm, out):
    start = time.monotonic()
    r = subprocess.run([exe, "--overwrite", "--output", out, prm],
                       capture_output=True, text=True)
    seconds = time.monotonic() - start
    if r.returncode != 0:
        sys.exit(f"{prm} failed:\n{r.stdout}\n{r.stderr}")
    return r.stdout, seconds


for name, prm in [("synthetic", "prm/tribology_synthetic.prm"),
                  ("granite", "benchmarks/tribology/granite.prm"),
                  ("laminate", "benchmarks/tribology/laminate.prm")]:
    out = os.path.join(root, "output", f"benchmark_{name}")
    stdout, seconds = run(os.path.join(root, prm), out)
    print(f"\n== {name}: {prm}, wall time {seconds:.2f} s ==")
    for line in stdout.splitlines():
        if line.startswith("| ") and line.strip("| ") and "wall time" not in line \
                and "Total" not in line:
            print(line)
    with open(os.path.join(out, "images.csv")) as f:
        rows = list(csv.DictReader(f))
    print("file, pixel um, cracks, crack length mm, L_A mm/mm^2, exfoliated %, "
          "micro/meso/macro")
    for r in rows:
        print(f"{r['file']}, {float(r['pixel_size_m']) * 1e6:.3g}, {r['cracks']}, "
              f"{float(r['crack_length_mm']):.2f}, "
              f"{float(r['crack_length_per_area_mm_per_mm2']):.3f}, "
              f"{100 * float(r['exfoliated_fraction']):.2f}, "
              f"{r['micro']}/{r['meso']}/{r['macro']}")
    verdict = os.path.join(out, "verdict.txt")
    if os.path.exists(verdict):
        print(open(verdict).read().strip())
