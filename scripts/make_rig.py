#!/usr/bin/env python3
"""Generates the TriboBrake as built (F. Massi, PhD thesis 2006, sec. 4.2.1;
../shared/spec/rig_experiments.md) as a hexahedral mesh with named bodies
and sets, and the squeal scene that goes with it.

    scripts/make_rig.py [--pad MM] [--out DIR] [--help]

writes DIR/rig.msh (Gmsh 4.1 through Gmsh's Python API, in mm) and
DIR/rig_scene.prm (subsection Scene of a squeal parameter file that reads
it). The default DIR is prm/rig_pad<MM>.

The rig (z is the shaft axis, the pad sits at +x; lengths in mm):
- disc: steel annulus, inner radius 50, outer radius 120, 10 thick
  (z = 0 ... 10), its upper face the friction face;
- clamp: the two thick hubs clamp the disc's inner 15 mm (radius
  50 ... 65) from both faces. The hubs themselves are rigid in the band
  (thesis); their contact with the disc is not (the thesis' own updating
  found the hub connection not perfectly rigid, and the measured (1,m)
  modes sit lower than a clamped inner edge gives). So each face of the
  clamped ring carries a 2 mm elastic layer held on its far face (the
  rigid hub): its modulus `clamp.E` sets the clamping's axial and shear
  stiffness, its low density keeps its own modes far above the band;
- pad: friction material, a --pad x --pad x 10 block (default 10) centred
  at radius 100 on the disc;
- force transducer: a 20 x 20 x 10 steel block on the pad (the tri-axial
  force transducer between pad and support), sharing its nodes;
- support: a steel 40 x 40 x 200 column on the transducer (2.5 kg: the
  support's own 25 N), tied to it (dual mortar mesh tying: the support's
  mesh is coarser);
- weights: the lumped mass `weights` spread over the support's top face,
  (F - 25 N) / g for a normal load F (`weights.m` [kg]);
- accelerometer: the lumped mass `accelerometer` of 2.4 g (Bruel & Kjaer
  4393) at the centre of the pad's leading face (the disc turns
  counterclockwise: the leading face is the pad's -y face);
- thin plates: two rows of 11 springs on each side face (y = -20 and +20)
  of the support, tangential (`plates.k`, y) and radial (`plates radial.k`,
  x: the plates are stiff in their plane), none normal (their negligible
  normal stiffness): the chapter-3 model's four rows of 11.

The pad's friction face and the disc's upper face are the contact pair
`pad on disc`. The support's geometry is not given in the thesis: its
section, height and density are things to update (`support.E`,
`support.rho`); so are the plates', the clamp's and the interface's
stiffnesses.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_brake import Mesh, between, breaks, division, write_msh  # noqa

# --- dimensions [mm] (thesis sec. 4.2.1; the hub and support: see above) --
DISC_R_IN, DISC_R_OUT, DISC_THICKNESS = 50.0, 120.0, 10.0
CLAMP_R_OUT, CLAMP_THICKNESS = 65.0, 2.0
PAD_RADIUS, PAD_HEIGHT = 100.0, 10.0
TRANSDUCER_SIDE, TRANSDUCER_HEIGHT = 20.0, 10.0
SUPPORT_SIDE, SUPPORT_HEIGHT = 40.0, 200.0
PLATE_ROWS_X = (-15.0, 15.0)         # rows on each side face, from the axis
PLATE_STATIONS = 11                  # springs per row, evenly along z
# --- materials (SI) --------------------------------------------------------
STEEL = dict(E=210e9, nu=0.3, rho=7800)
PAD = dict(E=10e9, nu=0.3, rho=2500)  # friction material (start value)
# the clamping layer (start value; rho: 1/8 of steel's, its modes > 100 kHz)
CLAMP = dict(E=2e10, nu=0.3, rho=1000)
# --- lumped masses [kg] and springs [N/m] -----------------------------------
ACCELEROMETER = 2.4e-3               # Bruel & Kjaer 4393
WEIGHTS = 200.0 / 9.81               # 225 N (the support's 25 N + 200 N)
K_PLATES = 8.422e6                   # per spring: the chapter-3 model's
N_THETA = 32                         # disc cells along the circumference


class RigMesh(Mesh):
    """make_brake's structured boxes, in (r, theta, z) for the disc and the
    clamp, in (x, y, z) for the pad, the transducer and the support."""

    cartesian = ("pad", "support")

    def node(self, group, a, b, z):
        if group not in self.cartesian:
            return Mesh.node(self, group, a, b, z)
        key = (group,) + tuple(round(c, 6) + 0.0 for c in (a, b, z))
        if key not in self.index:
            self.index[key] = len(self.coords)
            self.coords.append((a, b, z))
        return self.index[key]


def build(pad):
    m = RigMesh()
    # --- disc and clamp layers: one bonded group on one (r, theta, z)
    # lattice
    ts = [2 * math.pi * j / N_THETA for j in range(N_THETA + 1)]
    r_lat = breaks([DISC_R_IN, CLAMP_R_OUT, DISC_R_OUT], 14.0)
    R = lambda a, b: between(r_lat, a, b)  # noqa: E731
    # the friction face: the upper face outside the clamp
    m.box("disc", "disc", R(DISC_R_IN, CLAMP_R_OUT), ts, [0.0, DISC_THICKNESS])
    m.box("disc", "disc", R(CLAMP_R_OUT, DISC_R_OUT), ts, [0.0, DISC_THICKNESS],
          {"disc face": "z1"})
    m.box("clamp", "disc", R(DISC_R_IN, CLAMP_R_OUT), ts,
          [-CLAMP_THICKNESS, 0.0], {"hub faces": "z0"})
    m.box("clamp", "disc", R(DISC_R_IN, CLAMP_R_OUT), ts,
          [DISC_THICKNESS, DISC_THICKNESS + CLAMP_THICKNESS],
          {"hub faces": "z1"})

    # --- pad and transducer (one group, shared nodes) ---------------------
    h = pad / 2
    t_half = TRANSDUCER_SIDE / 2
    xs = breaks([PAD_RADIUS - t_half, PAD_RADIUS - pad / 2,
                 PAD_RADIUS + pad / 2, PAD_RADIUS + t_half], h)
    ys = breaks([-t_half, -pad / 2, pad / 2, t_half], h)
    z_pad = DISC_THICKNESS + PAD_HEIGHT
    z_tr = z_pad + TRANSDUCER_HEIGHT
    m.box("pad", "pad", between(xs, PAD_RADIUS - pad / 2, PAD_RADIUS + pad / 2),
          between(ys, -pad / 2, pad / 2), division(DISC_THICKNESS, z_pad, h),
          {"pad face": "z0"})
    m.box("transducer", "pad", xs, ys, division(z_pad, z_tr, TRANSDUCER_HEIGHT),
          {"transducer top": "z1"})

    # --- support column (its own group: tied to the transducer) -----------
    s_half = SUPPORT_SIDE / 2
    z_top = z_tr + SUPPORT_HEIGHT
    m.box("support", "support",
          division(PAD_RADIUS - s_half, PAD_RADIUS + s_half, 20.0),
          division(-s_half, s_half, 20.0), division(z_tr, z_top, 20.0),
          {"support bottom": "z0", "support top": "z1"})
    return m


def start_values():
    """The scene's named parameters at the file's (start) values."""
    v = {"disc.E": STEEL["E"], "disc.rho": STEEL["rho"],
         "clamp.E": CLAMP["E"], "clamp.rho": CLAMP["rho"],
         "pad.E": PAD["E"], "pad.rho": PAD["rho"],
         "transducer.E": STEEL["E"], "transducer.rho": STEEL["rho"],
         "support.E": STEEL["E"], "support.rho": STEEL["rho"],
         "weights.m": WEIGHTS, "accelerometer.m": ACCELEROMETER,
         "plates.k": K_PLATES, "plates radial.k": K_PLATES}
    return v


def scene_text(pad, mesh_name, values=None, header=None, extra=None):
    """The Scene subsection for the rig with a --pad mm pad, reading
    mesh_name, at the named parameters' values (start_values() updated by
    values); extra: {body: "key=value, ..."} added to a body's entry."""
    v = start_values()
    v.update(values or {})
    mm = 1e-3
    z_tr = DISC_THICKNESS + PAD_HEIGHT + TRANSDUCER_HEIGHT

    def point(x, y, z):
        return f"{x * mm:.6g} {y * mm:.6g} {z * mm:.6g}"

    def body(name, nu):
        more = (extra or {}).get(name)
        return (f"E={v[name + '.E']:.10g}, nu={nu:g}, "
                f"rho={v[name + '.rho']:.10g}" + (f", {more}" if more else ""))

    s_half = SUPPORT_SIDE / 2
    dz = SUPPORT_HEIGHT / (PLATE_STATIONS + 1)
    stations = " | ".join(
        point(PAD_RADIUS + dx, side * s_half, z_tr + (i + 1) * dz)
        for side in (-1, 1) for dx in PLATE_ROWS_X
        for i in range(PLATE_STATIONS))
    accelerometer = point(PAD_RADIUS, -pad / 2,
                          DISC_THICKNESS + PAD_HEIGHT / 2)
    if header is None:
        header = f"""# The TriboBrake as built, {pad:g} x {pad:g} mm pad, from
# scripts/make_rig.py (written by it: do not edit; rerun the script).
# Lengths of the mesh in mm; the file's values are start values of the
# updating (prm/rig_updating.prm).
"""
    return header + f"""subsection Scene
  set Type = mesh file
  subsection Mesh file
    set File = {mesh_name}
    set Length unit = 1e-3
    set Bodies = disc: set=disc, {body("disc", STEEL["nu"])}, type=disc, \\
                       face=disc face, axis=0 0 1, centre=0 0 0, \\
                       manifold=cylindrical; \\
                 clamp: set=clamp, {body("clamp", CLAMP["nu"])}, \\
                        manifold=cylindrical; \\
                 pad: set=pad, {body("pad", PAD["nu"])}; \\
                 transducer: set=transducer, {body("transducer", STEEL["nu"])}; \\
                 support: set=support, {body("support", STEEL["nu"])}
    set Contact pairs = pad on disc: slave=pad face, master=disc face
    set Ties = transducer on support: slave=transducer top, \\
                                      master=support bottom
    set Holds = hubs: set=hub faces
    set Masses = weights: set=support top, mass={v["weights.m"]:.10g}; \\
                 accelerometer: mass={v["accelerometer.m"]:.10g}, \\
                                point={accelerometer}
    set Springs = plates: body=support, direction=0 1 0, \\
                          k={v["plates.k"]:.10g}, points={stations}; \\
                  plates radial: body=support, direction=1 0 0, \\
                          k={v["plates radial.k"]:.10g}, points={stations}
  end
end
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pad", type=float, default=10.0,
                        help="pad side [mm] (the rig's 8 or 10)")
    parser.add_argument("--out", help="folder (default prm/rig_pad<MM>)")
    args = parser.parse_args()
    if not (2.0 <= args.pad <= TRANSDUCER_SIDE):
        sys.exit(f"make_rig.py: --pad must lie in [2, {TRANSDUCER_SIDE:g}] mm")
    here = os.path.dirname(os.path.abspath(__file__))
    out = args.out or os.path.normpath(
        os.path.join(here, "..", "prm", f"rig_pad{args.pad:g}"))
    os.makedirs(out, exist_ok=True)
    m = build(args.pad)
    write_msh(m, os.path.join(out, "rig.msh"))
    with open(os.path.join(out, "rig_scene.prm"), "w") as f:
        f.write(scene_text(args.pad, "rig.msh"))
    print(f"make_rig.py: {out}/rig.msh and rig_scene.prm: {m.describe()}")


if __name__ == "__main__":
    main()
