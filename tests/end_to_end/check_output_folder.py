#!/usr/bin/python3
"""The output-folder contract on paths a user types (issue: data loss).

usage: check_output_folder.py SQUEAL WORKDIR

A one-point CEA of the coarse clamped disc (a few seconds) is run with:
- Output/Directory = `out/` (trailing slash): the result is published as
  `out`, nothing is left inside it or beside it as `.partial`; a second run
  without overwriting is refused and leaves `out` byte for byte as it was;
  with --overwrite it replaces it;
- Output/Directory = `.` and `sub/..` with Overwrite = true: refused with one
  error naming the working directory; the working directory keeps every
  file (its input included);
- Output/Directory = the working directory's parent: refused the same way;
- a file-size limit one byte below the result's largest file (a full disk):
  the run fails naming the file and publishes nothing.
Exits non-zero on the first failure.
"""
import hashlib
import os
import resource
import shutil
import signal
import subprocess
import sys

squeal, work = sys.argv[1:3]
work = os.path.abspath(work)
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
os.chdir(work)

DISC = """subsection Scene
  set Type = disc
end
subsection Mesh
  set Finite element degree = 1
  set Disc cells circumference = 16
  set Disc cells radial = 2
  set Disc cells thickness = 1
end
subsection Eigensolver
  set Maximum frequency = 20000
end
subsection Sweep
  set First parameter = disc.E
  set First values = 210e9
  set Second parameter = damping.alpha
  set Second values = 0
end
subsection Output
  set Directory = {directory}
  set Overwrite = {overwrite}
end
"""


def fail(msg):
    print("FAILED:", msg)
    sys.exit(1)


def write(directory, overwrite="false"):
    with open("case.prm", "w") as f:
        f.write(DISC.format(directory=directory, overwrite=overwrite))


def execute(extra=()):
    return subprocess.run([squeal, *extra, "case.prm"], capture_output=True,
                          text=True)


def run(directory, overwrite="false", extra=()):
    write(directory, overwrite)
    return execute(extra)


def digest(folder):
    h = hashlib.sha256()
    for root, dirs, files in sorted(os.walk(folder)):
        dirs.sort()
        for name in sorted(files):
            path = os.path.join(root, name)
            h.update(path.encode())
            with open(path, "rb") as f:
                h.update(f.read())
    return h.hexdigest()


r = run("out/")
if r.returncode != 0:
    fail(f"out/ exited {r.returncode}:\n{r.stderr}")
if not os.path.isfile("out/eigenvalues.csv"):
    fail("out/ was not published as out")
if os.path.exists("out.partial") or os.path.exists("out/out.partial"):
    fail("a .partial folder was left behind")
print("trailing slash: published as out: ok")

before = digest("out")
r = run("out/")
if r.returncode == 0 or "exists" not in r.stderr:
    fail(f"a second run into out/ was not refused:\n{r.stderr}")
if digest("out") != before:
    fail("the refused run changed out")
print("trailing slash: a second run is refused, out unchanged: ok")

r = run("out/", extra=["--overwrite"])
if r.returncode != 0 or not os.path.isfile("out/eigenvalues.csv"):
    fail(f"--overwrite into out/ failed:\n{r.stderr}")
print("trailing slash: --overwrite replaces out: ok")

# in work/outer/inner, so that a regression replacing ".." touches only
# work/outer
os.makedirs("outer/inner")
os.chdir("outer/inner")
with open("marker.txt", "w") as f:
    f.write("keep me\n")
for directory in [".", "sub/..", ".."]:
    write(directory, overwrite="true")
    here = digest("..")
    r = execute()
    if r.returncode == 0:
        fail(f"Output/Directory = {directory} was accepted")
    if "working directory or contains it" not in r.stderr:
        fail(f"Output/Directory = {directory}: unclear error:\n{r.stderr}")
    if r.stderr.count("\n") > 2:
        fail(f"Output/Directory = {directory}: not one error:\n{r.stderr}")
    if digest("..") != here or not os.path.isfile("case.prm"):
        fail(f"Output/Directory = {directory} changed the working directory")
    print(f"Output/Directory = {directory} with Overwrite: refused, nothing "
          "touched: ok")

# A full disk, played by a file-size limit (ulimit -f) with SIGXFSZ ignored
# so that writes fail with EFBIG instead of killing the run, on a finer disc
# whose mode files are larger than parameters.prm: a limit one byte below
# the largest file of its result must fail the run with one message naming a
# file, and publish nothing. (PMIx keeps its data in a hash, not in shared
# memory files that the limit would break.)
os.chdir(work)
FINE = DISC.replace("degree = 1", "degree = 2").replace(
    "circumference = 16", "circumference = 24").replace(
    "radial = 2", "radial = 3")


def run_fine(directory, preexec=None):
    with open("fine.prm", "w") as f:
        f.write(FINE.format(directory=directory, overwrite="false"))
    env = dict(os.environ, PMIX_MCA_gds="hash")
    return subprocess.run([squeal, "fine.prm"], capture_output=True, text=True,
                          preexec_fn=preexec, env=env)


r = run_fine("sized")
if r.returncode != 0:
    fail(f"the fine disc failed:\n{r.stderr}")
sizes = {os.path.join(root, name): os.path.getsize(os.path.join(root, name))
         for root, _, files in os.walk("sized") for name in files}
largest = max(sizes.values())
if largest <= sizes[os.path.join("sized", "parameters.prm")]:
    fail("parameters.prm is the largest file: the limit would test nothing new")


def limited():
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (largest - 1, largest - 1))


r = run_fine("full", limited)
if r.returncode == 0:
    fail("a run whose largest file could not be written exited 0")
if "could not write" not in r.stderr or "not published" not in r.stderr \
        or r.stderr.count("\n") > 2:
    fail(f"a failed write gave an unclear error:\n{r.stderr}")
if os.path.exists("full"):
    fail("a run with a failed write published its folder")
print("file-size limit one byte below the largest file: the run fails naming "
      "the file, nothing published: ok")
