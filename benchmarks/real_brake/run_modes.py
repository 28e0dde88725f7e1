#!/usr/bin/python3
"""squeal against CalculiX 2.20 on the real modes of the passenger-car brake
(scripts/make_brake.py), same machine, one run after the other.

usage: /usr/bin/python3 benchmarks/real_brake/run_modes.py [SQUEAL] [WORKDIR]

The model, the same in both codes: the brake's frictionless assembly with
each pad face tied to its disc face (squeal: Ties, dual mortar; CalculiX:
*TIE), every body and material of brake_scene.prm, the disc held at its hub
face and the bracket at its mounts, no springs, no damping.
- CalculiX: calculix_deck.py's C3D20R decks of the generator's meshes at
  element sizes 10, 7.5 and 6 mm, and 10 mm with at least four cells
  between two break points (make_brake.py --min-cells 4: the thin parts
  refined), `ccx -i` with OMP_NUM_THREADS=2,
  OPENBLAS_NUM_THREADS=1, *FREQUENCY (SPOOLES + ARPACK) up to 16 kHz;
- squeal: the same meshes (brake.msh) at degree 2 (10, 7.5 and 6 mm; 7.5
  mm and 6 mm with two and three cells at least between breaks, 10 mm
  with three and four) and 3 (15, 12.5 and 10 mm, the 10 mm mesh with
  three cells through the disc's thickness instead of two, the 15 and
  12.5 mm meshes with two cells at least between breaks, and the 15, 12.5 and
  10 mm meshes refined by adaptive cycles with the traction-jump
  indicator), the reduced solver with the undamped symmetric modes up to
  16 kHz as its basis (without
  friction and damping its eigenvalues are those modes; no
  certification), no mesh_error output (Output/Error indicator = false:
  the runs time the modes), 1 MPI rank.
The reference is REFERENCE below (the 10 mm mesh at degree 3 with one
adaptive cycle);
error = the relative difference of the k-th frequency below 16 kHz from the
k-th of the reference: the largest, the median, and how many of the
reference's modes are within 0.5 %. Wall time and peak memory (maximum
resident set size, /usr/bin/time -v) of each whole run.

A finished run is kept in WORKDIR (its log, time and memory in a .json), so
an interrupted benchmark resumes. Prints the table and writes
WORKDIR/modes.csv.
"""
import csv
import json
import os
import re
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.normpath(os.path.join(here, "..", ".."))
sys.path.insert(0, here)
import calculix_deck  # noqa: E402

F_MAX = 16000.0
# (element size [mm], degree, cells through the disc or None for the
# generator's default, 25 mm over the element size, None or the
# adaptive cycles before the solve: (cycles, fraction of the cells refined
# per cycle by the traction-jump indicator), and optionally the generator's
# --min-cells, the fewest cells between two break points of its lattices:
# the thin parts' cells, default 1)
SQUEAL_RUNS = [(10.0, 2, None, None), (7.5, 2, None, None),
               (6.0, 2, None, None), (7.5, 2, None, None, 2),
               (7.5, 2, None, None, 3), (6.0, 2, None, None, 2),
               (6.0, 2, None, None, 3),
               (10.0, 2, None, None, 3), (10.0, 2, None, None, 4),
               (15.0, 3, None, None, 2), (12.5, 3, None, None, 2),
               (15.0, 3, None, None), (12.5, 3, None, None),
               (10.0, 3, None, None), (10.0, 3, 3, None),
               (15.0, 3, None, (2, 0.1)), (12.5, 3, None, (1, 0.1)),
               (12.5, 3, None, (1, 0.05)), (10.0, 3, None, (1, 0.05))]
# the reference: the 10 mm mesh at degree 3 with one adaptive cycle
REFERENCE = (10.0, 3, None, (1, 0.05))
# the best estimate: per mode the lowest of these runs' frequencies (the
# reference's thin parts have one cell; these have two to four)
BEST = [REFERENCE, (12.5, 3, None, None, 2), (10.0, 2, None, None, 4),
        (6.0, 2, None, None, 3)]
# (element size [mm], --min-cells)
CALCULIX_RUNS = [(10.0, 1), (7.5, 1), (6.0, 1), (10.0, 4)]


def timed(command, cwd, env=None):
    """Runs COMMAND under /usr/bin/time -v; (CompletedProcess, wall s,
    peak memory MB)."""
    start = time.monotonic()
    r = subprocess.run(["/usr/bin/time", "-v"] + command, cwd=cwd, env=env,
                       capture_output=True, text=True)
    seconds = time.monotonic() - start
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", r.stderr)
    return r, seconds, int(m.group(1)) / 1024 if m else float("nan")


def cached(record, run):
    """The json RECORD if present, else RUN() saved into it."""
    if os.path.exists(record):
        with open(record) as f:
            return json.load(f)
    result = run()
    with open(record + ".tmp", "w") as f:
        json.dump(result, f)
    os.replace(record + ".tmp", record)
    return result


def run_squeal(squeal, out, work):
    """Runs SQUEAL on OUT.prm (results into the folder OUT) with one BLAS
    thread, timed; stops on a failure. (CompletedProcess, wall s, peak
    memory MB, sorted [(frequency [Hz], Re lambda [1/s])] of
    eigenvalues.csv)."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    r, seconds, mb = timed([squeal, out + ".prm"], work, env)
    if r.returncode != 0:
        sys.exit(f"{out}: squeal failed\n{r.stdout[-3000:]}\n{r.stderr}")
    with open(os.path.join(out, "eigenvalues.csv")) as f:
        values = sorted((float(row["freq_Hz"]), float(row["re_per_s"]))
                        for row in csv.DictReader(f))
    return r, seconds, mb, values


def default_layers(h, min_cells=1):
    """The generator's cells through the disc's 25 mm at element size H
    with at least MIN_CELLS between two break points."""
    return max(min_cells, int(round(25.0 / h)))


def layers_suffix(layers, min_cells=1):
    return (f"_L{layers}" if layers else "") + \
        (f"_c{min_cells}" if min_cells > 1 else "")


def mesh_dir(work, h, layers=None, min_cells=1):
    """The generator's mesh at element size H [mm] (with LAYERS cells
    through the disc if given, and at least MIN_CELLS cells between two
    break points of its lattices) in WORKDIR, made once."""
    out = os.path.join(work, f"mesh_{h:g}" + layers_suffix(layers, min_cells))
    if not os.path.isfile(os.path.join(out, "brake_scene.prm")):
        subprocess.run([sys.executable,
                        os.path.join(root, "scripts", "make_brake.py"),
                        "--element-size", str(h), "--out", out,
                        "--min-cells", str(min_cells)] +
                       (["--disc-layers", str(layers)] if layers else []),
                       check=True, capture_output=True)
    return out


def squeal_run(squeal, work, h, degree, layers=None, adapt=None,
               min_cells=1):
    name = f"squeal_h{h:g}_q{degree}" + layers_suffix(layers, min_cells) + \
        (f"_a{adapt[0]}f{adapt[1]:g}" if adapt else "")
    out = os.path.join(work, name)
    adaptive = f"""
  set Adaptive cycles = {adapt[0]}
  set Refinement fraction = {adapt[1]:g}
  set Error indicator = traction jump""" if adapt else ""

    def run():
        mesh = mesh_dir(work, h, layers, min_cells)
        with open(out + ".prm", "w") as f:
            f.write(f"""INCLUDE {mesh}/brake_scene.prm
subsection Scene
  set Analysis = cea
  subsection Mesh file
    set Contact pairs =
    set Springs =
    set Ties = inner tie: slave=inner pad face, master=disc inboard face; \\
               outer tie: slave=outer pad face, master=disc outboard face
  end
end
subsection Mesh
  set Finite element degree = {degree}{adaptive}
end
subsection Damping
  set Alpha = 0
  set Beta = 0
end
subsection Eigensolver
  set Method = reduced
  set Minimum frequency = 1
  set Maximum frequency = {F_MAX:g}
  set Reduced band factor = 1
  set Reduced enrichment = false
  set Check points = 0
  set Certify stability map = false
end
subsection Sweep
  set First parameter = damping.alpha
  set First values = 0
  set Second parameter = damping.beta
  set Second values = 0
end
subsection Output
  set Directory = {out}
  set Overwrite = true
  set Mode shapes = none
  set Error indicator = false
end
""")
        r, seconds, mb, values = run_squeal(squeal, out, work)
        # the final mesh's (after the adaptive cycles)
        dofs = int(re.findall(r"(\d+) DoFs", r.stdout)[-1])
        freqs = sorted(f for f, _ in values)
        element = f"degree {degree}" + (
            f", {adapt[0]} adaptive cycle{'s' if adapt[0] > 1 else ''} "
            f"({100 * adapt[1]:g} %, traction jump)" if adapt else "")
        return dict(code="squeal", mesh_mm=h, element=element,
                    disc_layers=layers or default_layers(h, min_cells),
                    min_cells=min_cells, dofs=dofs,
                    seconds=seconds, memory_MB=mb, freqs=freqs)
    return cached(out + ".json", run)


def calculix_run(work, h, min_cells=1):
    name = f"ccx_h{h:g}" + layers_suffix(None, min_cells)
    inp = os.path.join(work, name + ".inp")

    def run():
        text, dofs = calculix_deck.deck(h, F_MAX, 300,
                                        min_cells=min_cells)
        with open(inp, "w") as f:
            f.write(text)
        env = dict(os.environ, OMP_NUM_THREADS="2", OPENBLAS_NUM_THREADS="1")
        r, seconds, mb = timed(["ccx", "-i", name], work, env)
        if r.returncode != 0 or "Job finished" not in r.stdout:
            sys.exit(f"{inp}: ccx failed\n{r.stdout[-3000:]}\n{r.stderr}")
        freqs = []
        with open(os.path.join(work, name + ".dat")) as f:
            table = f.read().split("E I G E N V A L U E   O U T P U T", 1)[1]
        for line in table.split("P A R T I C I P A T I O N", 1)[0] \
                .splitlines():
            cols = line.split()
            if len(cols) == 5 and cols[0].isdigit():
                freqs.append(float(cols[3]))
        return dict(code="CalculiX", mesh_mm=h, element="C3D20R",
                    disc_layers=default_layers(h, min_cells),
                    min_cells=min_cells,
                    dofs=dofs,
                    seconds=seconds, memory_MB=mb,
                    freqs=sorted(v for v in freqs if v <= F_MAX))
    return cached(os.path.join(work, name + ".json"), run)


def main():
    squeal = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else \
        os.path.join(root, "build", "squeal")
    work = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else
                           os.path.join(root, "output", "real_brake_modes"))
    os.makedirs(work, exist_ok=True)
    if subprocess.run(["which", "ccx"], capture_output=True).returncode:
        sys.exit("run_modes.py needs CalculiX: apt-get install calculix-ccx")
    runs = [squeal_run(squeal, work, *run) for run in SQUEAL_RUNS]
    runs += [calculix_run(work, *run) for run in CALCULIX_RUNS]
    finest = runs[SQUEAL_RUNS.index(REFERENCE)]
    band = [f for f in finest["freqs"] if f <= F_MAX]
    print(f"reference: squeal {finest['element']}, {finest['mesh_mm']:g} mm "
          f"mesh, {finest['disc_layers']} cells through the disc, "
          f"{finest['dofs']} DoFs: {len(band)} modes below "
          f"{F_MAX:g} Hz ({band[0]:.1f} ... {band[-1]:.1f} Hz)")
    best = [min(v) for v in zip(*(runs[SQUEAL_RUNS.index(b)]["freqs"]
                                  for b in BEST))][:len(band)]
    print("| code | mesh [mm] | cells through the disc | fewest cells "
          "between breaks | element | DoFs | modes below 16 kHz | "
          "wall time [s] | peak memory [MB] | largest error | median error "
          "| modes within 0.5 % | largest error, best estimate "
          "| within 0.5 % of it |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for r in runs:
        f = r["freqs"]
        n = min(len(f), len(band))
        errors = sorted(abs(f[k] - band[k]) / band[k] for k in range(n))
        largest = errors[-1] if errors else float("nan")
        median = errors[len(errors) // 2] if errors else float("nan")
        count = sum(1 for v in f if v <= F_MAX)
        within = sum(1 for e in errors if e <= 5e-3)
        to_best = [abs(f[k] - best[k]) / best[k]
                   for k in range(min(len(f), len(best)))]
        print(f"| {r['code']} | {r['mesh_mm']:g} | {r['disc_layers']} | "
              f"{r.get('min_cells', 1)} | {r['element']} | "
              f"{r['dofs']} | {count} | {r['seconds']:.1f} | "
              f"{r['memory_MB']:.0f} | {100 * largest:.3f} % | "
              f"{100 * median:.3f} % | {within} of {len(band)} | "
              f"{100 * max(to_best):.3f} % | "
              f"{sum(1 for e in to_best if e <= 5e-3)} of {len(best)} |")
        rows.append(dict(code=r["code"], mesh_mm=r["mesh_mm"],
                         disc_layers=r["disc_layers"],
                         min_cells=r.get("min_cells", 1),
                         element=r["element"],
                         dofs=r["dofs"], modes=count,
                         seconds=r["seconds"], memory_MB=r["memory_MB"],
                         largest_error=largest, median_error=median,
                         within_half_percent=within,
                         largest_error_best=max(to_best),
                         within_half_percent_best=sum(
                             1 for e in to_best if e <= 5e-3)))
    with open(os.path.join(work, "modes.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
