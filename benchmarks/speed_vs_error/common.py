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
