// The Scene subsection (scene type, mesh file and its lists), the
// TriboBrake's Geometry and the Mesh subsection (refinement, degree,
// adaptivity).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <squeal/parameters/parameters.h>

#include "entries.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace parameters
  {
    using namespace dealii;
    using internal::check;
    using internal::str;
    void
    MeshFileScene::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Mesh file");
      prm.declare_entry("File",
                        file,
                        Patterns::Anything(),
                        "The hexahedral mesh: Gmsh .msh (ASCII 2.2 or 4.1; "
                        "physical groups name the cell and face sets), "
                        "Abaqus/CalculiX .inp (*ELSET, *SURFACE, *NSET; "
                        "exported names are upper case) or VTK .vtu "
                        "(hexahedra, quadrilaterals naming faces, cell and "
                        "point data arrays naming sets). A relative path is "
                        "taken from the parameter file's folder.");
      prm.declare_entry("Length unit",
                        str(length_unit),
                        Patterns::Double(0.,
                                         Patterns::Double::max_double_value),
                        "Metres per mesh unit (1e-3 for a mesh in mm).");
      prm.declare_entry(
        "Bodies",
        bodies,
        Patterns::Anything(),
        "name: key=value, ...; one item per body. Keys: set (cell set, "
        "default the name), rho [kg/m^3] (required), law = isotropic "
        "(default: E [Pa], nu) | orthotropic (E1, E2, E3, G12, G13, G23 "
        "[Pa], nu12, nu13, nu23) | transversely isotropic (E, nu in the "
        "plane of isotropy; Et [Pa], nut, Gt [Pa] along its axis, material "
        "axis 3), frame = cartesian (axis1, axis2: the material axes 1 and 2, "
        "default 1 0 0 and 0 1 0) | cylindrical (axes radial, tangential, "
        "axial about axis through centre), "
        "alpha [1/s], beta [s] (the body's own Rayleigh damping, "
        "C_body = alpha M_body + beta K_body; default Damping/Alpha and "
        "Beta), type = other | disc (disc: its modes are named (n,m+-)), "
        "and for a disc: face (the face "
        "set whose axial motion names the modes, required), axis (default "
        "0 0 1), centre [m] (default 0 0 0), manifold = none | cylindrical "
        "(refinement and the mapping follow the circle about the axis). "
        "Every cell must belong to exactly one body. The body's named "
        "parameters (Sweep): <name>.E (for an anisotropic law, a factor "
        "E / E1 or E / E on its whole tensor), <name>.rho, and with its own "
        "damping <name>.alpha and <name>.beta.");
      prm.declare_entry(
        "Contact pairs",
        contact_pairs,
        Patterns::Anything(),
        "name: slave=<face set>, master=<face set>[, sliding=tx ty tz, "
        "mu=<friction coefficient>, k_n=<N/m^3>, k_t=<N/m^3>]; the "
        "slave face set must be plane (the pad's friction face), the master "
        "(the disc's face) in reach of it. Without sliding, the master turns "
        "about the disc's axis in Interface/Rotation sense. mu, k_n and k_t "
        "default to Interface/Friction coefficient, Normal stiffness and "
        "Tangential stiffness; named parameters <name>.mu, <name>.k_n and "
        "<name>.k_t, and with two or more pairs contact.mu, which sets every "
        "pair's mu at once.");
      prm.declare_entry(
        "Ties",
        ties,
        Patterns::Anything(),
        "name: slave=<face set>, master=<face set>: a bonded interface "
        "between bodies meshed apart (a friction material on its backplate): "
        "every slave node moves with the master surface, u_j = sum_l "
        "(M_jl / sum_l M_jl) u_l by dual mortar (the operators of the "
        "contact pairs, Preload/Search distance as the reach). The slave "
        "is best the finer side. Not in the braking run.");
      prm.declare_entry("Holds",
                        holds,
                        Patterns::Anything(),
                        "name: set=<face set>[, components=xyz]: the faces "
                        "held fixed in the given displacement components "
                        "(default all three).");
      prm.declare_entry("Point holds",
                        point_holds,
                        Patterns::Anything(),
                        "name: point=x y z [m], component=x|y|z: one "
                        "displacement component held at the node nearest "
                        "the point (a loading arm).");
      prm.declare_entry("Loads",
                        loads,
                        Patterns::Anything(),
                        "name: set=<face set>, direction=dx dy dz[, force=F "
                        "[N] | pressure=p [Pa], ramp=T [s]]: a uniform "
                        "traction on the faces along the direction, of F in "
                        "all, of p, or (neither given) the preload's and the "
                        "braking run's normal force in all; a braking run "
                        "ramps it up over T (default Transient/Ramp "
                        "duration).");
      prm.declare_entry(
        "Springs",
        springs,
        Patterns::Anything(),
        "name: body=<body>, direction=dx dy dz, points=x y z | x y z | ... "
        "or nodes=<node set>[, radius=a [m], k=<N/m>, to=<body>]: springs to "
        "ground of stiffness k each (default Springs/Stiffness), on the "
        "body's boundary faces through the points, each spread over radius "
        "a (default Springs/Attachment radius; 0: the nearest node); with "
        "to=, each spring joins the node of the body nearest its point to "
        "the node of the other body nearest it (no radius). Named "
        "parameter <name>.k.");
      prm.declare_entry("Probes",
                        probes,
                        Patterns::Anything(),
                        "name: point=x y z [m]: named points.");
      prm.declare_entry(
        "Masses",
        masses,
        Patterns::Anything(),
        "name: mass=m [kg], point=x y z [m] | set=<face set>: lumped masses "
        "(an accelerometer, a weight): at the node nearest the point (all "
        "three directions), or spread evenly over the face set's area "
        "(a consistent surface mass). They enter every analysis' mass.");
      prm.leave_subsection();
    }

    void
    MeshFileScene::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh file");
      file          = prm.get("File");
      length_unit   = prm.get_double("Length unit");
      bodies        = prm.get("Bodies");
      contact_pairs = prm.get("Contact pairs");
      ties          = prm.get("Ties");
      holds         = prm.get("Holds");
      point_holds   = prm.get("Point holds");
      loads         = prm.get("Loads");
      springs       = prm.get("Springs");
      probes        = prm.get("Probes");
      masses        = prm.get("Masses");
      prm.leave_subsection();
    }

    void
    Scene::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Scene");
      prm.declare_entry("Type",
                        type,
                        Patterns::Selection("tribobrake|disc|mesh file"),
                        "tribobrake: disc, pad, support and springs with the "
                        "friction interface (Geometry, Mesh, Materials, "
                        "Springs); disc: the clamped disc alone; mesh file: "
                        "the scene of subsection Mesh file.");
      prm.declare_entry("Analysis",
                        analysis,
                        Patterns::Selection(
                          "cea|preload|preloaded cea|braking|model updating"),
                        "cea: complex eigenvalue analysis over the sweep; "
                        "preload: the static frictional contact of the pad "
                        "on the disc under Preload/Normal force (mortar "
                        "contact), written as contact.csv and ParaView "
                        "fields; preloaded cea: the preload at the file's "
                        "nominal parameters, then the CEA with the interface "
                        "stiffness and friction coupling only where the pad "
                        "stayed in contact (serial); braking: the transient "
                        "braking simulation (subsection Transient); model "
                        "updating: the named parameters of subsection Model "
                        "updating fitted to measured natural frequencies of "
                        "the frictionless assembly. Preload, preloaded cea "
                        "and braking need a scene with one contact pair and "
                        "one load.");
      mesh_file.declare_parameters(prm);
      prm.leave_subsection();
    }

    void
    Scene::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Scene");
      type     = prm.get("Type");
      analysis = prm.get("Analysis");
      mesh_file.parse_parameters(prm);
      prm.leave_subsection();
      if (type == "mesh file" && mesh_file.file.empty())
        throw std::runtime_error(
          "Scene/Type = mesh file needs Scene/Mesh file/File");
    }

    void
    Geometry::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Geometry");
      // a length a brake can have: 10 micrometres to 10 m (0 gives a
      // singular mesh, 1e308 overflows the mapping)
      const Patterns::Double length(1e-5, 10.);
      prm.declare_entry("Disc inner radius",
                        str(disc_inner_radius),
                        length,
                        "Radius of the clamped inner face of the disc [m].");
      prm.declare_entry("Disc outer radius",
                        str(disc_outer_radius),
                        length,
                        "Outer radius of the disc [m].");
      prm.declare_entry("Disc thickness",
                        str(disc_thickness),
                        length,
                        "Disc thickness [m]; the disc occupies -h <= z <= 0.");
      prm.declare_entry("Pad size",
                        str(pad_size),
                        length,
                        "Edge of the cubic pad [m].");
      prm.declare_entry("Pad radius",
                        str(pad_radius),
                        length,
                        "Radius of the pad face centre on the disc [m] (the "
                        "thesis does not state it).");
      prm.declare_entry("Support length",
                        str(support_length),
                        length,
                        "Length of the support beam along the disc axis [m].");
      prm.leave_subsection();
    }

    void
    Geometry::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      disc_inner_radius = prm.get_double("Disc inner radius");
      disc_outer_radius = prm.get_double("Disc outer radius");
      disc_thickness    = prm.get_double("Disc thickness");
      pad_size          = prm.get_double("Pad size");
      pad_radius        = prm.get_double("Pad radius");
      support_length    = prm.get_double("Support length");
      prm.leave_subsection();
      check(disc_inner_radius < disc_outer_radius,
            "Geometry/Disc inner radius must be below Disc outer radius");
      check(pad_radius - pad_size / 2 >= disc_inner_radius &&
              pad_radius + pad_size / 2 <= disc_outer_radius,
            "Geometry/Pad radius: the pad face must lie on the disc annulus");
    }

    void
    Mesh::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Mesh");
      prm.declare_entry("Finite element degree",
                        std::to_string(fe_degree),
                        Patterns::Integer(1, 4),
                        "Polynomial degree of the Lagrange hexahedra (1-4).");
      prm.declare_entry("Disc cells circumference",
                        std::to_string(disc_cells_circumference),
                        Patterns::Integer(8, 1024),
                        "Cells around the disc (the disc mesh is "
                        "axisymmetric so that doublets stay exact).");
      prm.declare_entry("Disc cells radial",
                        std::to_string(disc_cells_radial),
                        Patterns::Integer(1, 256),
                        "Cells across the annulus.");
      prm.declare_entry("Disc cells thickness",
                        std::to_string(disc_cells_thickness),
                        Patterns::Integer(1, 64),
                        "Cells through the disc.");
      prm.declare_entry("Pad cells side",
                        std::to_string(pad_cells_side),
                        Patterns::Integer(1, 64),
                        "Cells along each edge of the pad face (the support "
                        "shares them).");
      prm.declare_entry("Pad cells thickness",
                        std::to_string(pad_cells_thickness),
                        Patterns::Integer(1, 64),
                        "Cells through the pad.");
      prm.declare_entry("Support cells length",
                        std::to_string(support_cells_length),
                        Patterns::Integer(1, 400),
                        "Cells along the support; a multiple of (springs "
                        "per row - 1) puts a node at every spring station.");
      prm.declare_entry("Disc refinements under pad",
                        std::to_string(disc_refinements_under_pad),
                        Patterns::Integer(0, 4),
                        "Local refinement cycles of the disc cells under the "
                        "pad footprint (hanging nodes are constrained).");
      prm.declare_entry(
        "Contact refinements",
        std::to_string(contact_refinements),
        Patterns::Integer(0, 4),
        "Scene/Analysis = preloaded cea: refinement cycles of the contact "
        "region driven by the preload's contact pressure, before the "
        "adaptive cycles. Each refines Contact refinement fraction of the "
        "cells with a face on the pad face or the disc track under it: "
        "those over whose contact face the preload's nodal pressure varies "
        "most (max - min over the pad nodes in the face's footprint and "
        "nearest its vertices, i.e. the pressure gradient times the cell "
        "size), so the pad's leading edge and its separation front are "
        "refined, not the whole disc (contact_refinement.csv). 0: none. "
        "Without a preload use Disc refinements under pad (geometry).");
      prm.declare_entry("Contact refinement fraction",
                        str(contact_refinement_fraction),
                        Patterns::Double(0.01, 1.),
                        "Per contact refinement cycle: the fraction of the "
                        "contact-face cells (pad and disc track) refined, "
                        "those of largest pressure variation.");
      prm.declare_entry("Adaptive cycles",
                        std::to_string(adaptive_cycles),
                        Patterns::Integer(0, 10),
                        "CEA: refinement cycles before the sweep. Each solves "
                        "the first sweep point with the full solver, prints "
                        "its DoFs, time and how far each mode's frequency "
                        "moved from the previous mesh (adaptive_cycles.csv; "
                        "a trend, not an error bound), and refines the cells "
                        "with the largest error indicator (Error "
                        "indicator on the modes, mesh_error.vtu). 0: the "
                        "mesh as built. The "
                        "braking simulation needs a conforming mesh and "
                        "ignores it.");
      prm.declare_entry("Refinement fraction",
                        str(refinement_fraction),
                        Patterns::Double(0.01, 1.),
                        "Per adaptive cycle: with Marking = cells, the "
                        "fraction of the cells refined (those with the "
                        "largest error indicator); with Marking = error, the "
                        "fraction of the squared indicator the refined cells "
                        "carry. Either way the cells whose indicator is "
                        "within 1e-3 of the last one marked are refined too "
                        "(a symmetric mesh's tied cells together).");
      prm.declare_entry(
        "Estimate solver",
        estimate_solver,
        Patterns::Selection("full|projected"),
        "The degree + 1 eigenvalues of the Frequency tolerance estimate. "
        "projected: Rayleigh-Ritz of the degree + 1 model on the degree-p "
        "modes carried to it plus three steps of shift-and-invert iteration "
        "from each (one factorisation per octave of the band); full: the "
        "full solver on the degree + 1 model. On the four cases of "
        "benchmarks/speed_vs_error both took the same decisions and "
        "projected was 2.2-2.7x faster on the TriboBrake (1.1-1.3x on the "
        "disc alone); its estimates can only be lower "
        "(a subspace's Ritz values fall short of the degree + 1 "
        "eigenvalues), by at most 14 % there.");
      prm.declare_entry("Marking",
                        marking,
                        Patterns::Selection("cells|error"),
                        "cells: refine a fixed fraction of the cells each "
                        "cycle; error: refine the fewest cells whose squared "
                        "indicators sum to Refinement fraction of the total "
                        "(Doerfler's bulk criterion), so that a few "
                        "concentrated errors (spring attachments, the pad "
                        "edge) refine a few cells.");
      prm.declare_entry(
        "Error indicator",
        error_indicator,
        Patterns::Selection("kelly|traction jump"),
        "The indicator of the modes' discretisation error per cell "
        "(mesh_error.vtu, adaptive cycles). kelly: deal.II's Kelly "
        "estimator, the jump of the displacement gradient across the "
        "faces (Kelly, Gago, Zienkiewicz & Babuska 1983); at a bonded "
        "interface between two materials that gradient jumps in the exact "
        "solution too, so kelly marks such interfaces whatever the mesh. "
        "traction jump: the jump of the traction sigma n across the "
        "faces, h_F / 24 times its square integrated over the face and "
        "divided by the mean Young's modulus of the two sides (an energy "
        "density, as the residual estimators of elasticity), which "
        "vanishes at such interfaces when the mesh resolves the mode. "
        "Faces between bodies that do not share nodes (ties, contact) are "
        "boundaries for both.");
      prm.declare_entry("Frequency tolerance",
                        str(frequency_tolerance),
                        Patterns::Double(0., 0.5),
                        "CEA: relative error wanted for every eigenvalue "
                        "of the band at the first sweep point (0.005 = "
                        "0.5 %), as |d lambda| / |lambda|: it bounds the "
                        "relative frequency error and holds the growth rate "
                        "to the same fraction of 2 pi f. Each cycle "
                        "estimates each mode's error as 1.5 x its distance "
                        "to the same mesh at degree + 1 (modes paired by "
                        "shape; modes closer to each other than three times "
                        "their shifts share the largest estimate among them) "
                        "and refines, driven by the modes above the "
                        "tolerance, until every estimate is below it or "
                        "Adaptive cycles refinements are spent (a warning "
                        "then). 0: off (the cycles run their fixed number). "
                        "Needs Finite element degree <= 3.");
      prm.declare_entry("Check estimate",
                        check_estimate ? "true" : "false",
                        Patterns::Bool(),
                        "CEA with a Frequency tolerance: after the last "
                        "cycle, solve the final mesh at degree + 2 as well "
                        "and write each mode's error against it beside its "
                        "estimate (adaptive_modes.csv): the estimate checked "
                        "against a much richer discretisation. Needs "
                        "Finite element degree <= 2; costly.");
      prm.declare_entry(
        "Degree adaptivity",
        degree_adaptivity ? "true" : "false",
        Patterns::Bool(),
        "CEA with a Frequency tolerance: choose between h and p. After an "
        "h step (Kelly refinement) the rate at which the largest estimate "
        "fell, log(e_before / e_after) / log(N_after / N_before), is "
        "compared with the rate degree + 1 on the same mesh is predicted to "
        "give (a third of the error for the DoFs its estimate already "
        "counted: log 3 / log(N_p+1 / N_p)); where the latter is larger the "
        "next cycle raises the degree on the same mesh instead of refining "
        "(up to degree 3; 2 with Check estimate). The first step is always "
        "h, to measure its rate. adaptive_cycles.csv has the degree of "
        "each cycle.");
      prm.leave_subsection();
    }

    void
    Mesh::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh");
      fe_degree                = prm.get_integer("Finite element degree");
      disc_cells_circumference = prm.get_integer("Disc cells circumference");
      disc_cells_radial        = prm.get_integer("Disc cells radial");
      disc_cells_thickness     = prm.get_integer("Disc cells thickness");
      pad_cells_side           = prm.get_integer("Pad cells side");
      pad_cells_thickness      = prm.get_integer("Pad cells thickness");
      support_cells_length     = prm.get_integer("Support cells length");
      disc_refinements_under_pad =
        prm.get_integer("Disc refinements under pad");
      contact_refinements = prm.get_integer("Contact refinements");
      contact_refinement_fraction =
        prm.get_double("Contact refinement fraction");
      adaptive_cycles     = prm.get_integer("Adaptive cycles");
      refinement_fraction = prm.get_double("Refinement fraction");
      marking             = prm.get("Marking");
      error_indicator     = prm.get("Error indicator");
      estimate_solver     = prm.get("Estimate solver");
      frequency_tolerance = prm.get_double("Frequency tolerance");
      check_estimate      = prm.get_bool("Check estimate");
      degree_adaptivity   = prm.get_bool("Degree adaptivity");
      check(frequency_tolerance == 0. || fe_degree <= 3,
            "Mesh/Frequency tolerance = " + str(frequency_tolerance) +
              " estimates the error at Finite element degree + 1, which must "
              "be at most 4: set Finite element degree to 1, 2 or 3 (it is " +
              std::to_string(fe_degree) + ")");
      check(!check_estimate || (frequency_tolerance > 0. && fe_degree <= 2),
            "Mesh/Check estimate = true needs Mesh/Frequency tolerance > 0 "
            "and Finite element degree <= 2 (the check solves at degree + 2, "
            "at most 4)");
      prm.leave_subsection();
    }
  } // namespace parameters
} // namespace squeal
