"""Shared by the speed-against-error scripts: run squeal on a parameter text."""
import subprocess
import sys
import time


def run_squeal(squeal, body, out):
    """Writes BODY plus an Output subsection (directory OUT, overwrite, no
    mode shapes) to OUT.prm, runs SQUEAL on it and returns (stdout, wall
    seconds); exits with squeal's output if it fails."""
    prm = out + ".prm"
    with open(prm, "w") as f:
        f.write(body + f"""subsection Output
  set Directory = {out}
  set Overwrite = true
  set Mode shapes = none
end
""")
    start = time.monotonic()
    r = subprocess.run([squeal, prm], capture_output=True, text=True)
    seconds = time.monotonic() - start
    if r.returncode != 0:
        sys.exit(f"{out}: squeal failed\n{r.stdout}\n{r.stderr}")
    return r.stdout, seconds


def single_point_sweep(first, first_value, second, second_value):
    """The Sweep subsection of a run at one point."""
    return f"""subsection Sweep
  set First parameter = {first}
  set First values = {first_value}
  set Second parameter = {second}
  set Second values = {second_value}
end
"""


def read_run(stdout, out):
    """(DoFs, [(freq_Hz, re_per_s)] sorted by frequency) of a finished run."""
    import csv
    import os
    import re
    dofs = int(re.search(r"(\d+) DoFs", stdout).group(1))
    with open(os.path.join(out, "eigenvalues.csv")) as f:
        modes = sorted((float(r["freq_Hz"]), float(r["re_per_s"]))
                       for r in csv.DictReader(f))
    return dofs, modes


def disc_mesh(degree, around, radial, thick):
    """The Mesh subsection: FE degree and the disc's cell counts."""
    return f"""subsection Mesh
  set Finite element degree = {degree}
  set Disc cells circumference = {around}
  set Disc cells radial = {radial}
  set Disc cells thickness = {thick}
end
"""
