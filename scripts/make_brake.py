#!/usr/bin/env python3
"""Generates a parametric passenger-car front disc brake as a hexahedral mesh
with named bodies and sets, and the squeal scene that goes with it.

    scripts/make_brake.py [--size coarse|default|fine] [--ventilated]
                          [--out DIR] [--element-size MM] [--help]

writes DIR/brake.msh (Gmsh 4.1, written through Gmsh's Python API from
Debian's python3-gmsh, in mm) and DIR/brake_scene.prm (subsection Scene of a
squeal parameter file that reads it; INCLUDE it from an analysis file, as
prm/brake_cea.prm does). The default DIR is prm/brake_<size>.

The brake (z is the hub axis, the caliper sits at +x; all lengths in mm):
- disc: a solid grey-iron friction ring (outer radius 150, 25 thick, faces
  z = 0 inboard and z = 25 outboard) on a hat (wall at radius 80-86, hub
  flange z = 39-45, bore radius 33), held at its hub face (flange top,
  radius 33-60: the wheel bolts clamp it); with --ventilated, two 9 mm
  cheeks (faces z = 0 and 28) joined by 36 radial vanes, the hat on the
  outboard cheek (DIR defaults to prm/brake_<size>_ventilated);
- two pads: friction material 10 thick (radius 100-148, 100 mm long at the
  mean radius), bonded to 5 mm steel backplates with ears that reach the
  anchor bracket's abutments;
- a fist caliper (housing behind the inner pad, bridge over the disc at
  radius 155-170, fingers bonded to the outer backplate) and a piston bonded
  to the inner backplate; the brake pressure pushes the piston towards the
  disc and the caliper's bore bottom the other way (the hydraulic force
  pair), so the caliper closes the force loop through the fingers;
- an anchor bracket (inboard and outboard abutments joined by a bridge over
  the disc) held at its two mounting faces (the knuckle bolts);
- springs: each backplate ear against its abutment (tangential: the pad's
  drag; radial), the piston in its bore (the seal), the caliper on its two
  guide pins (radial and tangential stiff, axial soft: the pins slide).

The meshes of the bodies in contact (pads on disc) do not match; the bodies
bonded to each other share nodes (friction material and backplate, piston
and inner backplate, fingers and outer backplate).

Dimensions, materials and stiffnesses are the constants below, each with
its source. Everything is structured in (r, theta, z), so the element size
sets the DoF count: at degree 2, coarse 91 374 DoFs, default 199 584,
fine 1 176 456.
"""
import argparse
import math
import os
import sys

# --- dimensions [mm] -------------------------------------------------------
# A 300 x 25 mm solid front disc and ~100 x 50 x 10 mm pads on 5 mm steel
# backplates are the typical sizes of a compact-class front axle brake
# (Breuer & Bill, Brake Technology Handbook, SAE 2008, ch. 7-8).
DISC_R_OUT = 150.0      # friction ring outer radius
DISC_THICKNESS = 25.0   # friction ring (solid disc), faces z = 0 and 25
# The ventilated option (--ventilated): two 9 mm cheeks joined by 36
# straight radial vanes, 28 mm overall, the hat on the outboard cheek only
# (the channels open at the ring's inner radius); vented front discs of
# this size are 22-32 mm thick with 6-10 mm cheeks and 30-48 vanes (Breuer
# & Bill, ch. 7; Limpert, Brake Design and Safety, SAE 2011, ch. 4).
VENTED_THICKNESS = 28.0
CHEEK_THICKNESS = 9.0
VANES = 36
VANE_ANGLE = 4.0        # degrees: 10.5 mm wide at r = 150, 6 mm at r = 86
HAT_R_IN, HAT_R_OUT = 80.0, 86.0   # hat wall
HUB_R_BORE = 33.0       # centre bore
HUB_R_BOLT = 60.0       # the clamped hub face: bore to beyond the bolt circle
HAT_TOP = 45.0          # hub flange top face (outboard)
FLANGE_THICKNESS = 6.0
PAD_R_IN, PAD_R_OUT = 100.0, 148.0
PAD_LENGTH = 100.0      # at the pad's mean radius
PAD_THICKNESS = 10.0
BACKPLATE_THICKNESS = 5.0
EAR_LENGTH = 9.0        # backplate beyond the friction material, each end
ABUTMENT_LENGTH = 14.0  # bracket abutment, along the arc
PISTON_R_IN, PISTON_R_OUT = 108.0, 140.0   # piston footprint (~54 mm bore)
PISTON_HALF_LENGTH = 27.0                  # at the mean radius
PISTON_LENGTH = 12.0    # along z, behind the inner backplate
HOUSING_THICKNESS = 18.0
BRIDGE_R_IN, BRIDGE_R_OUT = 155.0, 170.0   # caliper and bracket bridges
FINGER_THICKNESS = 12.0
BRACKET_LUG = 15.0      # bracket mounting lugs below the inner abutment

# --- materials (SI) --------------------------------------------------------
# Grey cast iron EN-GJL-200 (EN 1561: E 103-118 GPa, nu 0.26, 7200 kg/m^3).
DISC = dict(E=110e9, nu=0.26, rho=7200)
# Steel (EN 10025 S355: E 210 GPa, nu 0.3, 7850 kg/m^3): backplates,
# piston, caliper and bracket.
STEEL = dict(E=210e9, nu=0.3, rho=7850)
# Friction material, transversely isotropic about the pad normal: stiff in
# the plane of the pad, several times softer through its thickness, as the
# measured organic and low-metallic materials are (Yuan, SAE 960993 (1996);
# Hornig, PhD thesis, TU Darmstadt (2015), table 3.2: in-plane 5-12 GPa,
# through-thickness 1-5 GPa, 2000-2700 kg/m^3).
PAD = dict(E=8e9, nu=0.25, Et=3e9, nut=0.12, Gt=1.5e9, rho=2500)
# Springs [N/m]: ear/abutment contact stiffness of order 1e7-1e8 N/m
# (Kung, Dunlap & Ballinger, SAE 2000-01-0444: pad abutment springs);
# piston seal and guide pins radially/tangentially stiff, the pins nearly
# free axially (a sliding caliper).
K_ABUTMENT_T, K_ABUTMENT_R, K_AXIAL_SOFT = 1e8, 1e7, 1e5
K_SEAL, K_PIN = 5e7, 1e8
# Brake pressure: 2 MPa on a 54 mm piston, ~4.6 kN per pad (a moderate
# stop; Breuer & Bill, ch. 3).
PISTON_FORCE = 2e6 * math.pi * 0.054 ** 2 / 4

SIZES = {"coarse": 10.0, "default": 7.5, "fine": 4.0}   # element size [mm]


class Mesh:
    """Hexahedra and quadrilaterals on structured (r, theta, z) boxes. Nodes
    are shared within a bonding group only (coincident nodes of different
    groups stay apart: those bodies touch without being bonded)."""

    def __init__(self):
        self.coords = []         # (x, y, z) [mm]
        self.index = {}          # (group, rounded x, y, z) -> node
        self.cells = {}          # body -> [8 nodes]
        self.faces = {}          # face set -> [4 nodes]

    def describe(self):
        """'N nodes, M hexahedra <body> <count>, ...'"""
        n_cells = sum(len(c) for c in self.cells.values())
        return (f"{len(self.coords)} nodes, {n_cells} hexahedra " +
                ", ".join(f"{b} {len(c)}" for b, c in self.cells.items()))

    def node(self, group, r, t, z):
        x, y = r * math.cos(t), r * math.sin(t)
        key = (group,) + tuple(round(c, 6) + 0.0 for c in (x, y, z))
        if key not in self.index:
            self.index[key] = len(self.coords)
            self.coords.append((x, y, z))
        return self.index[key]

    def box(self, body, group, rs, ts, zs, faces=None):
        """Cells of body on the lattice rs x ts x zs (increasing lists of
        node coordinates); faces: {set: side} with side one of r0, r1, t0,
        t1, z0, z1 adds that side's quadrilaterals to the face set."""
        nid = {}
        for i, r in enumerate(rs):
            for j, t in enumerate(ts):
                for k, z in enumerate(zs):
                    nid[i, j, k] = self.node(group, r, t, z)
        cells = self.cells.setdefault(body, [])
        nr, nt, nz = len(rs) - 1, len(ts) - 1, len(zs) - 1
        for i in range(nr):
            for j in range(nt):
                for k in range(nz):
                    # (r, theta, z) is right-handed: bottom face counter-
                    # clockwise, then the top face (Gmsh's hexahedron)
                    cells.append([nid[i + a, j + b, k + c] for c in (0, 1)
                                  for a, b in ((0, 0), (1, 0), (1, 1),
                                               (0, 1))])
        for name, side in (faces or {}).items():
            quads = self.faces.setdefault(name, [])
            axis, end = side[0], int(side[1])
            n = {"r": nr, "t": nt, "z": nz}
            fixed = {"r": 0, "t": 1, "z": 2}[axis]
            others = [a for a in range(3) if a != fixed]
            counts = [(nr, nt, nz)[a] for a in others]
            for p in range(counts[0]):
                for q in range(counts[1]):
                    quad = []
                    for dp, dq in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        ijk = [0, 0, 0]
                        ijk[fixed] = end * n[axis]
                        ijk[others[0]] = p + dp
                        ijk[others[1]] = q + dq
                        quad.append(nid[tuple(ijk)])
                    quads.append(quad)


def division(a, b, h, least=1):
    """Points from a to b in steps of about h (at least LEAST steps)."""
    n = max(least, int(round(abs(b - a) / h)))
    return [a + (b - a) * i / n for i in range(n + 1)]


def breaks(points, h, least=1):
    """A lattice through every break point, steps of about h between
    (at least LEAST between two break points)."""
    out = [points[0]]
    for a, b in zip(points, points[1:]):
        out += division(a, b, h, least)[1:]
    return out


def between(lattice, a, b):
    """The lattice points from a to b (both lattice points)."""
    return [x for x in lattice if a - 1e-9 <= x <= b + 1e-9]


def build(h, ventilated=False, disc_layers=None, min_cells=1):
    """The brake's mesh and spring groups at element size h [mm];
    disc_layers: cells through the solid disc's friction ring and hat wall
    (default: its 25 mm thickness over h, at least one); min_cells: the
    fewest cells between two break points of a lattice (the thin parts:
    backplates, hat wall, flange, ears, abutments)."""
    m = Mesh()
    # --- disc: its (r, z) profile turned about z ------------------------
    thickness = VENTED_THICKNESS if ventilated else DISC_THICKNESS
    if ventilated:
        # theta breaks at both edges of every vane
        pitch, width = 2 * math.pi / VANES, math.radians(VANE_ANGLE)
        ts = breaks([a for k in range(VANES)
                     for a in (k * pitch, k * pitch + width)] +
                    [2 * math.pi], h / DISC_R_OUT, min_cells)
        cheeks = [CHEEK_THICKNESS, thickness - CHEEK_THICKNESS]
    else:
        n_theta = 4 * max(3, int(round(2 * math.pi * DISC_R_OUT / h / 4)))
        ts = [2 * math.pi * j / n_theta for j in range(n_theta + 1)]
        cheeks = []
    r_lat = breaks([HUB_R_BORE, HUB_R_BOLT, HAT_R_IN, HAT_R_OUT, DISC_R_OUT],
                   h, min_cells)
    z_lat = breaks([0.0] + cheeks + [thickness, HAT_TOP - FLANGE_THICKNESS,
                                     HAT_TOP], h, min_cells)
    if disc_layers and not ventilated:
        z_lat = ([thickness * k / disc_layers for k in range(disc_layers)] +
                 between(z_lat, thickness, HAT_TOP))
    ring_r = between(r_lat, HAT_R_OUT, DISC_R_OUT)
    if ventilated:
        m.box("disc", "disc", ring_r, ts, between(z_lat, 0, cheeks[0]),
              {"disc inboard face": "z0"})
        for k in range(VANES):
            m.box("disc", "disc", ring_r,
                  between(ts, k * pitch, k * pitch + width),
                  between(z_lat, cheeks[0], cheeks[1]))
        m.box("disc", "disc", ring_r, ts, between(z_lat, cheeks[1],
                                                  thickness),
              {"disc outboard face": "z1"})
    else:
        m.box("disc", "disc", ring_r, ts, between(z_lat, 0, thickness),
              {"disc inboard face": "z0", "disc outboard face": "z1"})
    m.box("disc", "disc", between(r_lat, HAT_R_IN, HAT_R_OUT), ts,
          between(z_lat, cheeks[1] if ventilated else 0, HAT_TOP))
    m.box("disc", "disc", between(r_lat, HUB_R_BORE, HUB_R_BOLT), ts,
          between(z_lat, HAT_TOP - FLANGE_THICKNESS, HAT_TOP),
          {"disc hub": "z1"})
    m.box("disc", "disc", between(r_lat, HUB_R_BOLT, HAT_R_IN), ts,
          between(z_lat, HAT_TOP - FLANGE_THICKNESS, HAT_TOP))

    # --- caliper region: one lattice in (r, theta, z) -------------------
    r_mean = 0.5 * (PAD_R_IN + PAD_R_OUT)
    a_pad = 0.5 * PAD_LENGTH / r_mean
    a_piston = PISTON_HALF_LENGTH / r_mean
    a_ear = a_pad + EAR_LENGTH / r_mean
    a_abut = a_ear + ABUTMENT_LENGTH / r_mean
    h_t = h / r_mean
    t_lat = breaks([-a_abut, -a_ear, -a_pad, -a_piston, a_piston, a_pad,
                    a_ear, a_abut], h_t, min_cells)
    rc_lat = breaks([PAD_R_IN, PISTON_R_IN, PISTON_R_OUT, PAD_R_OUT,
                     BRIDGE_R_IN, BRIDGE_R_OUT], h, min_cells)
    z_in_bp = -PAD_THICKNESS - BACKPLATE_THICKNESS
    z_piston = z_in_bp - PISTON_LENGTH
    z_housing = z_piston - HOUSING_THICKNESS
    z_out_pad = thickness + PAD_THICKNESS
    z_out_bp = z_out_pad + BACKPLATE_THICKNESS
    z_finger = z_out_bp + FINGER_THICKNESS
    z_lug = z_in_bp - BRACKET_LUG
    zc_lat = breaks(sorted({z_housing, z_piston, z_lug, z_in_bp,
                            -PAD_THICKNESS, 0.0, thickness, z_out_pad,
                            z_out_bp, z_finger}), h, min_cells)
    R, T, Z = (lambda a, b: between(rc_lat, a, b),
               lambda a, b: between(t_lat, a, b),
               lambda a, b: between(zc_lat, a, b))
    pad_r, pad_t = R(PAD_R_IN, PAD_R_OUT), T(-a_pad, a_pad)
    # inner pad (group "inner": friction material, backplate, piston)
    m.box("friction material", "inner", pad_r, pad_t, Z(-PAD_THICKNESS, 0),
          {"inner pad face": "z1"})
    m.box("backplates", "inner", pad_r, T(-a_ear, a_ear),
          Z(z_in_bp, -PAD_THICKNESS))
    m.box("piston", "inner", R(PISTON_R_IN, PISTON_R_OUT),
          T(-a_piston, a_piston), Z(z_piston, z_in_bp),
          {"piston back": "z0"})
    # outer pad and caliper (group "caliper": the fingers hold the pad)
    m.box("friction material", "caliper", pad_r, pad_t,
          Z(thickness, z_out_pad), {"outer pad face": "z0"})
    m.box("backplates", "caliper", pad_r, T(-a_ear, a_ear),
          Z(z_out_pad, z_out_bp))
    m.box("caliper", "caliper", R(PAD_R_IN, BRIDGE_R_OUT), pad_t,
          Z(z_out_bp, z_finger))                               # fingers
    m.box("caliper", "caliper", R(BRIDGE_R_IN, BRIDGE_R_OUT), pad_t,
          Z(z_piston, z_out_bp))                               # bridge
    # housing: its bore bottom (under the piston) faces the piston's back
    for rs in (R(PAD_R_IN, PISTON_R_IN), R(PISTON_R_IN, PISTON_R_OUT),
               R(PISTON_R_OUT, BRIDGE_R_OUT)):
        for ts_ in (T(-a_pad, -a_piston), T(-a_piston, a_piston),
                    T(a_piston, a_pad)):
            bore = rs[0] == PISTON_R_IN and ts_[0] == -a_piston
            m.box("caliper", "caliper", rs, ts_, Z(z_housing, z_piston),
                  {"caliper bore": "z1"} if bore else None)
    # anchor bracket (group "bracket"), one arm each side of the pads
    for s in (-1, 1):
        ts_ = T(min(s * a_ear, s * a_abut), max(s * a_ear, s * a_abut))
        m.box("bracket", "bracket", R(PAD_R_IN, BRIDGE_R_IN), ts_,
              Z(z_lug, -PAD_THICKNESS), {"bracket mounts": "z0"})
        m.box("bracket", "bracket", R(PAD_R_IN, BRIDGE_R_IN), ts_,
              Z(z_out_pad, z_out_bp))
        m.box("bracket", "bracket", R(BRIDGE_R_IN, BRIDGE_R_OUT), ts_,
              Z(z_lug, z_out_bp))
    geometry = dict(r_mean=r_mean, a_pad=a_pad, a_ear=a_ear,
                    a_piston=a_piston, z_in_bp=z_in_bp, z_out_pad=z_out_pad,
                    z_out_bp=z_out_bp, z_piston=z_piston,
                    z_housing=z_housing, z_lug=z_lug)
    return m, geometry


def write_msh(m, path):
    """The mesh through Gmsh's API: one discrete volume per body, one
    discrete surface per face set, each its physical group."""
    import gmsh
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("brake")
        holder = gmsh.model.addDiscreteEntity(3)
        gmsh.model.mesh.addNodes(
            3, holder, list(range(1, len(m.coords) + 1)),
            [c for p in m.coords for c in p])
        # (dimension, Gmsh element type, name, node lists): hexahedra are
        # type 5, quadrilaterals type 3
        groups = [(3, 5, b, c) for b, c in m.cells.items()] + \
            [(2, 3, f, q) for f, q in m.faces.items()]
        for tag, (dim, kind, name, items) in enumerate(groups, start=1):
            e = gmsh.model.addDiscreteEntity(dim)
            gmsh.model.mesh.addElementsByType(
                e, kind, [], [n + 1 for item in items for n in item])
            gmsh.model.addPhysicalGroup(dim, [e], tag)
            gmsh.model.setPhysicalName(dim, tag, name)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.SaveAll", 0)
        gmsh.write(path)
    finally:
        gmsh.finalize()


def vec(*v):
    return " ".join(f"{x:.6g}" for x in v)


def write_scene(g, path, mesh_name):
    """The Scene subsection for the mesh (points in m)."""
    mm = 1e-3
    rm = g["r_mean"]

    def cyl(r, t, z):
        return vec(r * math.cos(t) * mm, r * math.sin(t) * mm, z * mm)

    def radial(t):
        return vec(math.cos(t), math.sin(t), 0)

    def tangential(t):
        return vec(-math.sin(t), math.cos(t), 0)

    springs = []
    # backplate ears against the bracket abutments, both pads, both ends
    for pad, z in (("inner", g["z_in_bp"] + 0.5 * BACKPLATE_THICKNESS),
                   ("outer", g["z_out_pad"] + 0.5 * BACKPLATE_THICKNESS)):
        for end, s in (("leading", 1), ("trailing", -1)):
            t = s * g["a_ear"]
            for d, k, direction in (("t", K_ABUTMENT_T, tangential(t)),
                                    ("r", K_ABUTMENT_R, radial(t)),
                                    ("z", K_AXIAL_SOFT, "0 0 1")):
                springs.append(
                    f"{pad} {end} ear {d}: body=backplates, to=bracket, "
                    f"direction={direction}, k={k:g}, "
                    f"points={cyl(rm, t, z)}")
    # the piston in its bore (seal) and the caliper on its guide pins
    zp = g["z_piston"]
    for d, direction in (("r", "1 0 0"), ("t", "0 1 0")):
        springs.append(f"piston seal {d}: body=piston, to=caliper, "
                       f"direction={direction}, k={K_SEAL:g}, "
                       f"points={cyl(rm, 0, zp)}")
    zh = 0.5 * (g["z_housing"] + g["z_piston"])
    pins = " | ".join(cyl(BRIDGE_R_IN, s * g["a_pad"], zh) for s in (-1, 1))
    for d, k, direction in (("x", K_PIN, "1 0 0"), ("y", K_PIN, "0 1 0"),
                            ("z", K_AXIAL_SOFT, "0 0 1")):
        springs.append(f"guide pins {d}: body=caliper, to=bracket, "
                       f"direction={direction}, k={k:g}, points={pins}")
    join = "; \\\n                 "
    text = f"""# The brake of scripts/make_brake.py (written by it: do not edit; rerun
# the script). Bodies, contact pairs, holds, the brake pressure's force
# pair and the springs; lengths of the mesh in mm.
subsection Scene
  set Type = mesh file
  subsection Mesh file
    set File = {mesh_name}
    set Length unit = 1e-3
    set Bodies = disc: set=disc, E={DISC['E']:g}, nu={DISC['nu']:g}, \\
                       rho={DISC['rho']:g}, type=disc, \\
                       face=disc outboard face, axis=0 0 1, centre=0 0 0, \\
                       manifold=cylindrical; \\
                 friction material: set=friction material, \\
                       law=transversely isotropic, E={PAD['E']:g}, \\
                       nu={PAD['nu']:g}, Et={PAD['Et']:g}, \\
                       nut={PAD['nut']:g}, Gt={PAD['Gt']:g}, \\
                       rho={PAD['rho']:g}; \\
                 backplates: set=backplates, E={STEEL['E']:g}, \\
                       nu={STEEL['nu']:g}, rho={STEEL['rho']:g}; \\
                 piston: set=piston, E={STEEL['E']:g}, \\
                       nu={STEEL['nu']:g}, rho={STEEL['rho']:g}; \\
                 caliper: set=caliper, E={STEEL['E']:g}, \\
                       nu={STEEL['nu']:g}, rho={STEEL['rho']:g}; \\
                 bracket: set=bracket, E={STEEL['E']:g}, \\
                       nu={STEEL['nu']:g}, rho={STEEL['rho']:g}
    set Contact pairs = inner pad: slave=inner pad face, \\
                                   master=disc inboard face; \\
                        outer pad: slave=outer pad face, \\
                                   master=disc outboard face
    set Holds = hub: set=disc hub; bracket mounts: set=bracket mounts
    # the hydraulic force pair: on the piston towards the disc, on the
    # caliper's bore bottom away from it
    set Loads = piston: set=piston back, direction=0 0 1, \\
                        force={PISTON_FORCE:.6g}; \\
                bore: set=caliper bore, direction=0 0 -1, \\
                      force={PISTON_FORCE:.6g}
    set Springs = {join.join(springs)}
  end
end
"""
    with open(path, "w") as f:
        f.write(text)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--size", choices=sorted(SIZES), default="default")
    parser.add_argument("--element-size", type=float,
                        help="element size [mm] (overrides --size)")
    parser.add_argument("--ventilated", action="store_true",
                        help="a ventilated disc (two cheeks and 36 vanes)")
    parser.add_argument("--disc-layers", type=int,
                        help="cells through the solid disc's thickness, "
                        "1 to 32 (default: its 25 mm over the element size, "
                        "rounded)")
    parser.add_argument("--min-cells", type=int, default=1,
                        help="the fewest cells between two break points of "
                        "a lattice, 1 to 8 (default 1: a 5 mm backplate "
                        "gets one cell at any element size above 3.3 mm)")
    parser.add_argument("--out", help="folder (default prm/brake_<size>, "
                        "prm/brake_<size>_ventilated with --ventilated)")
    args = parser.parse_args()
    h = args.element_size if args.element_size else SIZES[args.size]
    if not (h > 0.5):
        sys.exit("make_brake.py: --element-size must be > 0.5 mm")
    if args.disc_layers is not None and not 1 <= args.disc_layers <= 32:
        sys.exit("make_brake.py: --disc-layers must be 1 to 32")
    if args.disc_layers is not None and args.ventilated:
        sys.exit("make_brake.py: --disc-layers is for the solid disc (the "
                 "ventilated disc's cheeks and vanes set its layers)")
    if not 1 <= args.min_cells <= 8:
        sys.exit("make_brake.py: --min-cells must be 1 to 8")
    here = os.path.dirname(os.path.abspath(__file__))
    out = args.out or os.path.normpath(
        os.path.join(here, "..", "prm", f"brake_{args.size}" +
                     ("_ventilated" if args.ventilated else "")))
    os.makedirs(out, exist_ok=True)
    m, g = build(h, args.ventilated, args.disc_layers,
                 args.min_cells)
    write_msh(m, os.path.join(out, "brake.msh"))
    write_scene(g, os.path.join(out, "brake_scene.prm"), "brake.msh")
    print(f"make_brake.py: {out}/brake.msh and brake_scene.prm: "
          f"{m.describe()}")


if __name__ == "__main__":
    main()
