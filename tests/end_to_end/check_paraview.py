"""ParaView renders a squeal run (issue 24, section 4): a preloaded CEA of
the two-block scene (prm/two_blocks.msh, degree 2, one point), then
scripts/paraview_modes.py through scripts/paraview.sh (pvbatch off-screen on
a virtual display). Checks:
- the frames of one period of the most unstable mode exist, are not blank
  (more than 2 % of the pixels differ from the white background, more than
  100 distinct colours) and move: the frame at half a period (displacement
  reversed) differs from the first in more than 0.5 % of its pixels;
- the preload's contact pressure image is not blank;
- a run folder without modes.pvd gives one message and exit status 2.
Exits 77 (ctest: skipped) when ParaView is not set up
(bash scripts/setup.sh --paraview; the test command sets it up).
Usage: check_paraview.py SQUEAL WORK_DIR"""
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from checks import check, finish, run_squeal  # noqa: E402

squeal, work = sys.argv[1], sys.argv[2]
root = os.path.join(here, "..", "..")
runner = os.path.join(root, "scripts", "paraview.sh")
script = os.path.join(root, "scripts", "paraview_modes.py")
os.makedirs(work, exist_ok=True)
os.chdir(work)

probe = subprocess.run(["bash", runner, "--version"], capture_output=True,
                       text=True)
if probe.returncode == 77:
    print(probe.stderr.strip())
    sys.exit(77)

mesh = os.path.abspath(os.path.join(root, "prm", "two_blocks.msh"))
with open("base.prm", "w") as f:
    f.write(f"""subsection Scene
  set Type = mesh file
  set Analysis = preloaded cea
  subsection Mesh file
    set File        = {mesh}
    set Length unit = 1e-3
    set Bodies = base: E=210e9, nu=0.3, rho=7800; \\
                 block: E=10e9, nu=0.25, rho=2500
    set Contact pairs = block on base: slave=block bottom, \\
                        master=base top, sliding=1 0 0
    set Holds = base bottom: set=base bottom; \\
                block top: set=block top, components=xy
    set Loads = press: set=block top, direction=0 0 -1
  end
end
subsection Mesh
  set Finite element degree = 2
end
subsection Interface
  set Normal stiffness = 1e13
  # the preload's (the CEA's mu is the sweep's)
  set Friction coefficient = 0.4
end
subsection Preload
  set Normal force = 1000
  set Friction = steady sliding
  set Search distance = 1e-4
end
subsection Eigensolver
  set Method = full
  set Minimum frequency = 1000
  set Maximum frequency = 60000
end
subsection Sweep
  set First parameter  = block on base.mu
  set First values     = 0.6
  set Second parameter = block.E
  set Second values    = 10e9
end
""")
run, _ = run_squeal(squeal, "base.prm", "run",
                    "subsection Output\n  set Mode shapes = all\nend\n")

frames = 8
r = subprocess.run(["bash", runner, script, run, "png", "--frames",
                    str(frames), "--size", "640,480"],
                   capture_output=True, text=True)
check("paraview_modes.py runs", r.returncode == 0,
      (r.stdout + r.stderr)[-2000:])
print(r.stdout.strip())

import numpy as np  # noqa: E402
from matplotlib import image  # noqa: E402


def load(name):
    path = os.path.join("png", name)
    return image.imread(path)[:, :, :3] if os.path.isfile(path) else None


def not_blank(picture):
    if picture is None:
        return False, "missing"
    drawn = np.any(np.abs(picture - 1.0) > 0.02, axis=2).mean()
    colours = len(np.unique((picture * 255).astype(int).reshape(-1, 3),
                            axis=0))
    return drawn > 0.02 and colours > 100, \
        f"{100 * drawn:.1f} % drawn, {colours} colours"


shots = [load(f"mode_frame_{k:03d}.png") for k in range(frames)]
verdicts = [not_blank(s) for s in shots]
check("every frame drawn", all(ok for ok, _ in verdicts),
      "; ".join(said for _, said in verdicts[:3]), show=True)
if shots[0] is not None and shots[frames // 2] is not None:
    moved = np.any(np.abs(shots[0] - shots[frames // 2]) > 0.02,
                   axis=2).mean()
else:
    moved = 0.
check("the mode moves over the period", moved > 0.005,
      f"{100 * moved:.2f} % of the pixels differ at half a period", show=True)
ok, said = not_blank(load("contact_pressure.png"))
check("contact pressure drawn", ok, said, show=True)

os.makedirs("empty", exist_ok=True)
r = subprocess.run(["bash", runner, script, "empty", "png_empty"],
                   capture_output=True, text=True)
check("a folder without modes.pvd: one message, exit 2",
      r.returncode == 2 and "modes.pvd" in r.stderr and
      not os.path.exists("png_empty"), f"exit {r.returncode}: {r.stderr}")
finish()
