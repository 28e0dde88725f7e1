#!/usr/bin/python3
"""End-to-end check of build/squeal-tribology on prm/tribology_synthetic.prm.

usage: check_tribology.py SQUEAL_TRIBOLOGY PRM WORKDIR

The PNG maps come from scripts/plot_tribology.py run on the output folder,
as the README says.

Runs the whole chain and checks:
- every output file of the contract exists (CSV tables, VTU, PNG plots,
  overlays, the written contact history, the echoed parameters);
- the largest Findley damage sits at the leading edge on the inner radius,
  and equals verification C4's 3.607364580e6 scaled by p_mean^m (the
  synthetic history there is C3 times p_mean, q = 0.4 p): 1e-9 relative;
- the crack map found in the synthetic images (drawn with a density that
  follows the damage rank) correlates with the damage map: ROC AUC > 0.7 and
  toroidal-shift p < 0.01 (400 shifts on the 0.5 mm grid);
- a second run into the same directory is refused and changes nothing;
- images without a crack (a crack map without variance) fail the run with
  one error naming the map, and nothing is published;
- the contact_history.h5 the run wrote, read back as an input file, gives
  the same damage.csv;
- one of the written field images with its sidecar, analysed alone, gives
  the same crack length as in the full run.
Exits non-zero on the first failure.
"""
import csv
import os
import shutil
import subprocess
import sys

exe, prm, work = sys.argv[1:4]
plot_script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                           "..", "scripts", "plot_tribology.py")
prm = os.path.abspath(prm)
os.makedirs(work, exist_ok=True)
os.chdir(work)


def fail(msg):
    print("FAILED:", msg)
    sys.exit(1)


def run(name, body, expect_ok=True):
    with open(name + ".prm", "w") as f:
        f.write(body)
    r = subprocess.run([exe, name + ".prm"], capture_output=True, text=True)
    if expect_ok and r.returncode != 0:
        fail(f"{name} exited {r.returncode}:\n{r.stdout}\n{r.stderr}")
    return r


def table(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


out = os.path.abspath("synthetic")
shutil.rmtree(out, ignore_errors=True)
r = run("synthetic", f"include {prm}\nsubsection Output\n  set Directory = {out}\nend\n")
print(r.stdout.split("Verdict:")[1].split("\n")[0][:200] if "Verdict:" in r.stdout
      else fail("no verdict printed"))
p = subprocess.run([sys.executable, plot_script, out], capture_output=True,
                   text=True)
if p.returncode != 0:
    fail(f"plot_tribology.py exited {p.returncode}:\n{p.stdout}\n{p.stderr}")
for f in ["damage.csv", "damage_sensitivity.csv", "images.csv", "maps.csv",
          "correlation.csv", "roc.csv", "verdict.txt", "pad_face_maps.vtu",
          "parameters.prm", "contact_history.h5", "damage_maps.png",
          "image_maps.png", "correlation.png", "images/field_0_0.png",
          "images/field_0_0.prm", "images/field_0_0_overlay.png"]:
    if not os.path.isfile(os.path.join(out, f)):
        fail(f"missing output {f}")
print("output files: ok")

damage = table(os.path.join(out, "damage.csv"))
top = max(damage, key=lambda d: float(d["D_star_Pa_pow_m"]))
s_min = min(float(d["s_m"]) for d in damage)
r_min = min(float(d["r_m"]) for d in damage)
if abs(float(top["s_m"]) - s_min) > 1e-12 or abs(float(top["r_m"]) - r_min) > 1e-12:
    fail(f"largest damage at s = {top['s_m']}, r = {top['r_m']}, not at the "
         "leading edge on the inner radius")
print("largest damage at the leading edge, inner radius: ok")
expected = 3.607364580e6 * (1e6) ** 10
if abs(float(top["D_star_Pa_pow_m"]) / expected - 1.) > 1e-9:
    fail(f"D* there is {top['D_star_Pa_pow_m']}, expected {expected:.9e}")
print("D* there = C4 value * p_mean^m: ok")

stats = {row["statistic"]: row for row in table(os.path.join(out, "correlation.csv"))}
auc = float(stats["roc_auc_log_damage_predicts_cracked"]["value"])
p = float(stats["spearman_log_damage_vs_crack_density"]["p_value"])
shifts = int(stats["spearman_log_damage_vs_crack_density"]["shifts"])
if not (auc > 0.7 and p < 0.01 and shifts == 400):
    fail(f"correlation AUC {auc}, p {p}, {shifts} shifts")
print("damage predicts the synthetic cracks (AUC > 0.7, p < 0.01): ok")

again = run("synthetic", open("synthetic.prm").read(), expect_ok=False)
if again.returncode == 0 or "exists" not in again.stderr:
    fail("a second run into the same directory was not refused")
if not os.path.isfile(os.path.join(out, "damage.csv")):
    fail("the refused run destroyed the earlier result")
print("existing output refused and kept: ok")

# Images without a single crack: the crack-density map has no ranks, so the
# run fails naming the map instead of printing rho = nan as a finding.
flat = os.path.abspath("no_cracks")
shutil.rmtree(flat, ignore_errors=True)
r = run("no_cracks", f"""include {prm}
subsection Synthetic images
  set Cracks per cell = 0
end
subsection Output
  set Directory = {flat}
end
""", expect_ok=False)
if r.returncode == 0 or "crack-density map is 0 in all" not in r.stderr \
        or os.path.exists(flat):
    fail(f"a crack map without variance was not refused:\n{r.stderr}")
print("a crack map without variance is refused, nothing published: ok")

out2 = os.path.abspath("from_file")
shutil.rmtree(out2, ignore_errors=True)
run("from_file", f"""include {prm}
subsection Contact history
  set File = {os.path.join(out, 'contact_history.h5')}
end
subsection Images
  set Files =
end
subsection Output
  set Directory = {out2}
end
""")
a = open(os.path.join(out, "damage.csv")).read()
b = open(os.path.join(out2, "damage.csv")).read()
if a != b:
    fail("damage.csv from the written contact_history.h5 differs")
print("contact_history.h5 read back gives the same damage.csv: ok")

out3 = os.path.abspath("one_image")
shutil.rmtree(out3, ignore_errors=True)
run("one_image", f"""include {prm}
subsection Contact history
  set File =
end
subsection Images
  set Files = {os.path.join(out, 'images', 'field_0_0.png')}
end
subsection Output
  set Directory = {out3}
end
""")
first = {row["file"]: row for row in table(os.path.join(out, "images.csv"))}
alone = {row["file"]: row for row in table(os.path.join(out3, "images.csv"))}
if abs(float(first["field_0_0.png"]["crack_length_mm"]) -
       float(alone["field_0_0.png"]["crack_length_mm"])) > 1e-9:
    fail("the image analysed alone gives another crack length")
print("image analysed alone: same cracks: ok")
print("all checks passed")
