// Declaration and parsing of every run parameter. Each subsection is a struct
// whose defaults are the values in the header, so the defaults live in one
// place; this file only gives them ranges and help texts with SI units, and
// checks the few rules that join several parameters.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <squeal/parameters/parameters.h>

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

    namespace
    {
      std::string
      str(const double x)
      {
        std::ostringstream s;
        s.precision(12);
        s << x;
        return s.str();
      }

      const Patterns::Double positive(0., Patterns::Double::max_double_value);

      void
      check(const bool ok, const std::string &what)
      {
        if (!ok)
          throw std::runtime_error("invalid parameter: " + what);
      }
    } // namespace

    void
    MeshFileScene::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Mesh file");
      prm.declare_entry("File", file, Patterns::Anything(),
                        "The hexahedral mesh: Gmsh .msh (ASCII 2.2 or 4.1; "
                        "physical groups name the cell and face sets) or "
                        "Abaqus/CalculiX .inp (*ELSET, *SURFACE, *NSET; "
                        "exported names are upper case). A relative path is "
                        "taken from the parameter file's folder.");
      prm.declare_entry("Length unit", str(length_unit),
                        Patterns::Double(0., Patterns::Double::max_double_value),
                        "Metres per mesh unit (1e-3 for a mesh in mm).");
      prm.declare_entry(
        "Bodies", bodies, Patterns::Anything(),
        "name: key=value, ...; one item per body. Keys: set (cell set, "
        "default the name), E [Pa], nu, rho [kg/m^3] (all three required), "
        "type = other | disc | pad | support (pad: the sweep parameter "
        "'pad modulus' sets its E; support: 'support density' sets its rho; "
        "disc: its modes are named (n,m+-)), and for a disc: face (the face "
        "set whose axial motion names the modes, required), axis (default "
        "0 0 1), centre [m] (default 0 0 0), manifold = none | cylindrical "
        "(refinement and the mapping follow the circle about the axis). "
        "Every cell must belong to exactly one body.");
      prm.declare_entry(
        "Contact pairs", contact_pairs, Patterns::Anything(),
        "name: slave=<face set>, master=<face set>[, sliding=tx ty tz]; the "
        "slave face set must be plane (the pad's friction face), the master "
        "(the disc's face) in reach of it. Without sliding, the master turns "
        "about the disc's axis in Interface/Rotation sense. Friction "
        "coefficient and stiffness: subsection Interface.");
      prm.declare_entry("Holds", holds, Patterns::Anything(),
                        "name: set=<face set>[, components=xyz]: the faces "
                        "held fixed in the given displacement components "
                        "(default all three).");
      prm.declare_entry("Point holds", point_holds, Patterns::Anything(),
                        "name: point=x y z [m], component=x|y|z: one "
                        "displacement component held at the node nearest "
                        "the point (a loading arm).");
      prm.declare_entry("Loads", loads, Patterns::Anything(),
                        "name: set=<face set>, direction=dx dy dz: the "
                        "preload's and the braking run's normal force, spread "
                        "uniformly over the faces along the direction.");
      prm.declare_entry(
        "Springs", springs, Patterns::Anything(),
        "name: body=<body>, direction=dx dy dz, points=x y z | x y z | ... "
        "or nodes=<node set>[, radius=a [m]]: springs to ground of "
        "Springs/Stiffness each, on the body's boundary faces through the "
        "points, each spread over radius a (default Springs/Attachment "
        "radius; 0: the nearest node).");
      prm.declare_entry("Probes", probes, Patterns::Anything(),
                        "name: point=x y z [m]: named points.");
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
      holds         = prm.get("Holds");
      point_holds   = prm.get("Point holds");
      loads         = prm.get("Loads");
      springs       = prm.get("Springs");
      probes        = prm.get("Probes");
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
      prm.declare_entry("Analysis", analysis,
                        Patterns::Selection("cea|preload|preloaded cea|braking"),
                        "cea: complex eigenvalue analysis over the sweep; "
                        "preload: the static frictional contact of the pad "
                        "on the disc under Preload/Normal force (mortar "
                        "contact), written as contact.csv and ParaView "
                        "fields; preloaded cea: the preload at the file's "
                        "nominal parameters, then the CEA with the interface "
                        "stiffness and friction coupling only where the pad "
                        "stayed in contact (serial); braking: the transient "
                        "braking simulation (subsection Transient). All but "
                        "cea need a scene with one contact pair and one load.");
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
    Preload::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Preload");
      prm.declare_entry("Normal force", str(normal_force),
                        Patterns::Double(0.),
                        "Force on the support's top pressing the pad on the "
                        "disc [N], spread uniformly over the top face.");
      prm.declare_entry("Friction", friction,
                        Patterns::Selection(
                          "steady sliding|coulomb|frictionless"),
                        "steady sliding: every pad node in contact slips "
                        "along the disc's sliding direction (Interface/"
                        "Sliding direction), traction mu p, as in CEA "
                        "practice; coulomb: stick/slip from the incremental "
                        "Coulomb law (semi-smooth Newton), the load in Load "
                        "steps increments, the disc at rest or turning by "
                        "Disc slip per step; frictionless. mu is "
                        "Interface/Friction coefficient.");
      prm.declare_entry("Search distance", str(search_distance),
                        Patterns::Double(1e-9),
                        "How far along the pad face's normal the disc face is "
                        "searched [m]; bodies overlapping by more are "
                        "refused.");
      prm.declare_entry("Load steps", std::to_string(load_steps),
                        Patterns::Integer(1, 1000),
                        "Increments of the normal force; each step's "
                        "contact state is written (contact_step_NNN.csv, "
                        "contact.pvd). With coulomb the path matters.");
      prm.declare_entry("Disc slip per step", str(disc_slip),
                        Patterns::Double(0.),
                        "With Friction = coulomb: how far the disc's surface "
                        "moves under the pad along Interface/Sliding "
                        "direction during each load step [m] (the disc "
                        "turning); 0 keeps the disc at rest, so only the "
                        "pad's own deformation slips. A slip much larger than "
                        "the elastic one makes every node in contact slip and "
                        "reproduces steady sliding.");
      prm.declare_entry("Segmentation refresh", str(segmentation_refresh),
                        Patterns::Double(0.),
                        "Large sliding: after a load step, the mortar "
                        "segmentation is rebuilt on the deformed surfaces "
                        "when the pad's largest relative tangential "
                        "displacement against the disc since the last one "
                        "exceeds this fraction of the shortest pad face "
                        "edge (0: never). The preload's elastic slips are "
                        "far below it, so it builds the segmentation once.");
      prm.leave_subsection();
    }

    void
    Preload::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Preload");
      normal_force    = prm.get_double("Normal force");
      friction        = prm.get("Friction");
      search_distance = prm.get_double("Search distance");
      load_steps      = prm.get_integer("Load steps");
      disc_slip       = prm.get_double("Disc slip per step");
      segmentation_refresh = prm.get_double("Segmentation refresh");
      prm.leave_subsection();
      check(disc_slip == 0. || friction == "coulomb",
            "Preload/Disc slip per step = " + str(disc_slip) +
              " needs Preload/Friction = coulomb (got " + friction +
              "): the other friction laws have no slip history");
    }

    void
    Transient::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Transient");
      prm.declare_entry("Angular velocity", str(angular_velocity),
                        Patterns::Double(0.),
                        "Disc speed [rad/s] (10 rpm = 1.0472). The rotation "
                        "enters as the sliding velocity omega r of the disc "
                        "face under the pad, in the disc's fixed mesh "
                        "(Interface/Rotation sense); transport terms, of "
                        "order omega / omega_mode (1e-4), are neglected.");
      prm.declare_entry("Normal force", str(normal_force), Patterns::Double(0.),
                        "Final force on the support's top [N].");
      prm.declare_entry("Ramp duration", str(ramp_duration),
                        Patterns::Double(0.),
                        "The force rises as (1 - cos(pi t / T)) / 2 over this "
                        "time [s], so that the first contact does not excite "
                        "the structure, then is held.");
      prm.declare_entry("End time", str(end_time), Patterns::Double(1e-9),
                        "Simulated time [s].");
      prm.declare_entry("Time step", str(time_step), Patterns::Double(0.),
                        "Time step [s]; 0: Safety factor x the computed "
                        "stability limit. A step above the limit is refused.");
      prm.declare_entry("Safety factor", str(safety_factor),
                        Patterns::Double(1e-3, 1.),
                        "Fraction of the stability limit used when Time step "
                        "is 0.");
      prm.declare_entry("Beta2", str(beta2), Patterns::Double(0.5, 1.),
                        "The beta2 parameter of the explicit scheme (thesis "
                        "eq. 2-6): 0.5 is central differences; larger values "
                        "damp high frequencies numerically.");
      prm.declare_entry("Sampling rate", str(sampling_rate),
                        Patterns::Double(1.),
                        "Rate [Hz] of forces.csv, probes.csv and the contact "
                        "history (contact_history.h5); at most 1 / time step.");
      prm.declare_entry("History start", str(history_start),
                        Patterns::Double(0.),
                        "Time [s] of the first sample of the contact history.");
      prm.declare_entry("Snapshot interval", str(snapshot_interval),
                        Patterns::Double(0.),
                        "Time [s] between ParaView snapshots (transient.pvd: "
                        "displacement, velocity, von Mises stress; "
                        "contact.pvd: the pad face's contact fields); 0: "
                        "none besides the animation window.");
      prm.declare_entry("Animation start", str(animation_start),
                        Patterns::Double(),
                        "Start [s] of a window of Animation frames snapshots "
                        "spread over Animation period (animation.pvd, for "
                        "one squeal period in ParaView); < 0: the window "
                        "ends at End time.");
      prm.declare_entry("Animation period", str(animation_period),
                        Patterns::Double(0.),
                        "Length [s] of the animation window: one period of "
                        "the expected squeal (1 / 3430 Hz for the TriboBrake "
                        "of the thesis).");
      prm.declare_entry("Animation frames", std::to_string(animation_frames),
                        Patterns::Integer(0, 1000),
                        "Snapshots in the animation window; 0: none.");
      prm.declare_entry("Spectrum start", str(spectrum_start),
                        Patterns::Double(),
                        "Start [s] of the window of the power spectral "
                        "density (Welch) of the probe's acceleration; < 0: "
                        "the second half of the run.");
      prm.declare_entry("Contact tolerance", str(contact_tolerance),
                        Patterns::Double(1e-16, 1e-2),
                        "Relative change of the contact multipliers at which "
                        "projected Gauss-Seidel stops.");
      prm.declare_entry("Contact iterations", std::to_string(contact_iterations),
                        Patterns::Integer(1),
                        "Most projected Gauss-Seidel sweeps per step; more "
                        "stops the run with the time and the residual.");
      prm.declare_entry("Initial perturbation", str(initial_perturbation),
                        Patterns::Double(0.),
                        "Axial velocity [m/s] given to the disc at t = 0 in "
                        "the shape of a (0,3) mode (cos 3 theta, rising with "
                        "the radius), a seed for an instability; 0: none "
                        "(the load ramp and rounding seed it).");
      prm.declare_entry("Stiffness product", stiffness_product,
                        Patterns::Selection("matrix-free|sparse"),
                        "How K u is computed each step: matrix-free (deal.II "
                        "MatrixFree, sum factorisation, vectorised and "
                        "multithreaded) or sparse (the assembled matrix). "
                        "Both are timed at set-up and printed; see "
                        "benchmarks/transient/README.md.");
      prm.declare_entry("Checkpoint interval",
                        std::to_string(checkpoint_interval),
                        Patterns::Integer(0),
                        "Time steps between checkpoints, written into "
                        "DIRECTORY.partial/checkpoint/ while the run goes "
                        "(and removed when it ends); `squeal --resume "
                        "DIRECTORY` continues a killed run from the last one "
                        "and gives the same result as an uninterrupted run. "
                        "0: none.");
      prm.declare_entry("Grid", grid ? "true" : "false", Patterns::Bool(),
                        "true: one braking simulation at every point of the "
                        "Sweep subsection (its two parameters and values, as "
                        "for the CEA; keep it small), each in its own folder "
                        "under Output/Directory, and one stability table "
                        "(stability_table.csv; scripts/plot_braking_grid.py "
                        "draws stability_map.png) to lay "
                        "over the CEA's unstable regions. No checkpoints in "
                        "a grid.");
      prm.leave_subsection();
    }

    void
    Transient::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Transient");
      angular_velocity     = prm.get_double("Angular velocity");
      normal_force         = prm.get_double("Normal force");
      ramp_duration        = prm.get_double("Ramp duration");
      end_time             = prm.get_double("End time");
      time_step            = prm.get_double("Time step");
      safety_factor        = prm.get_double("Safety factor");
      beta2                = prm.get_double("Beta2");
      sampling_rate        = prm.get_double("Sampling rate");
      history_start        = prm.get_double("History start");
      snapshot_interval    = prm.get_double("Snapshot interval");
      animation_start      = prm.get_double("Animation start");
      animation_period     = prm.get_double("Animation period");
      animation_frames     = prm.get_integer("Animation frames");
      spectrum_start       = prm.get_double("Spectrum start");
      contact_tolerance    = prm.get_double("Contact tolerance");
      contact_iterations   = prm.get_integer("Contact iterations");
      initial_perturbation = prm.get_double("Initial perturbation");
      stiffness_product    = prm.get("Stiffness product");
      checkpoint_interval  = prm.get_integer("Checkpoint interval");
      grid                 = prm.get_bool("Grid");
      prm.leave_subsection();
      check(history_start < end_time,
            "Transient/History start must be below Transient/End time");
    }

    void
    Geometry::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Geometry");
      prm.declare_entry("Disc inner radius", str(disc_inner_radius), positive,
                        "Radius of the clamped inner face of the disc [m].");
      prm.declare_entry("Disc outer radius", str(disc_outer_radius), positive,
                        "Outer radius of the disc [m].");
      prm.declare_entry("Disc thickness", str(disc_thickness), positive,
                        "Disc thickness [m]; the disc occupies -h <= z <= 0.");
      prm.declare_entry("Pad size", str(pad_size), positive,
                        "Edge of the cubic pad [m].");
      prm.declare_entry("Pad radius", str(pad_radius), positive,
                        "Radius of the pad face centre on the disc [m] (the "
                        "thesis does not state it).");
      prm.declare_entry("Support length", str(support_length), positive,
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
      prm.declare_entry("Finite element degree", std::to_string(fe_degree),
                        Patterns::Integer(1, 4),
                        "Polynomial degree of the Lagrange hexahedra (1-4).");
      prm.declare_entry("Disc cells circumference",
                        std::to_string(disc_cells_circumference),
                        Patterns::Integer(8, 1024),
                        "Cells around the disc (the disc mesh is "
                        "axisymmetric so that doublets stay exact).");
      prm.declare_entry("Disc cells radial", std::to_string(disc_cells_radial),
                        Patterns::Integer(1, 256), "Cells across the annulus.");
      prm.declare_entry("Disc cells thickness",
                        std::to_string(disc_cells_thickness),
                        Patterns::Integer(1, 64), "Cells through the disc.");
      prm.declare_entry("Pad cells side", std::to_string(pad_cells_side),
                        Patterns::Integer(1, 64),
                        "Cells along each edge of the pad face (the support "
                        "shares them).");
      prm.declare_entry("Pad cells thickness",
                        std::to_string(pad_cells_thickness),
                        Patterns::Integer(1, 64), "Cells through the pad.");
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
        "Contact refinements", std::to_string(contact_refinements),
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
      prm.declare_entry("Adaptive cycles", std::to_string(adaptive_cycles),
                        Patterns::Integer(0, 10),
                        "CEA: refinement cycles before the sweep. Each solves "
                        "the first sweep point with the full solver, prints "
                        "its DoFs, time and how far each mode's frequency "
                        "moved from the previous mesh (adaptive_cycles.csv; "
                        "a trend, not an error bound), and refines the cells "
                        "with the largest error indicator (Kelly on the "
                        "modes, mesh_error.vtu). 0: the mesh as built. The "
                        "braking simulation needs a conforming mesh and "
                        "ignores it.");
      prm.declare_entry("Refinement fraction", str(refinement_fraction),
                        Patterns::Double(0.01, 1.),
                        "Per adaptive cycle: with Marking = cells, the "
                        "fraction of the cells refined (those with the "
                        "largest error indicator); with Marking = error, the "
                        "fraction of the squared indicator the refined cells "
                        "carry.");
      prm.declare_entry(
        "Estimate solver", estimate_solver,
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
      prm.declare_entry("Marking", marking, Patterns::Selection("cells|error"),
                        "cells: refine a fixed fraction of the cells each "
                        "cycle; error: refine the fewest cells whose squared "
                        "indicators sum to Refinement fraction of the total "
                        "(Doerfler's bulk criterion), so that a few "
                        "concentrated errors (spring attachments, the pad "
                        "edge) refine a few cells.");
      prm.declare_entry("Frequency tolerance", str(frequency_tolerance),
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
      prm.declare_entry("Check estimate", check_estimate ? "true" : "false",
                        Patterns::Bool(),
                        "CEA with a Frequency tolerance: after the last "
                        "cycle, solve the final mesh at degree + 2 as well "
                        "and write each mode's error against it beside its "
                        "estimate (adaptive_modes.csv): the estimate checked "
                        "against a much richer discretisation. Needs "
                        "Finite element degree <= 2; costly.");
      prm.declare_entry(
        "Degree adaptivity", degree_adaptivity ? "true" : "false",
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
      fe_degree                  = prm.get_integer("Finite element degree");
      disc_cells_circumference   = prm.get_integer("Disc cells circumference");
      disc_cells_radial          = prm.get_integer("Disc cells radial");
      disc_cells_thickness       = prm.get_integer("Disc cells thickness");
      pad_cells_side             = prm.get_integer("Pad cells side");
      pad_cells_thickness        = prm.get_integer("Pad cells thickness");
      support_cells_length       = prm.get_integer("Support cells length");
      disc_refinements_under_pad = prm.get_integer("Disc refinements under pad");
      contact_refinements        = prm.get_integer("Contact refinements");
      contact_refinement_fraction =
        prm.get_double("Contact refinement fraction");
      adaptive_cycles            = prm.get_integer("Adaptive cycles");
      refinement_fraction        = prm.get_double("Refinement fraction");
      marking                    = prm.get("Marking");
      estimate_solver            = prm.get("Estimate solver");
      frequency_tolerance        = prm.get_double("Frequency tolerance");
      check_estimate             = prm.get_bool("Check estimate");
      degree_adaptivity          = prm.get_bool("Degree adaptivity");
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

    namespace
    {
      void
      declare_material(ParameterHandler &prm,
                       const std::string &name,
                       const Material &   m,
                       const std::string &note)
      {
        prm.enter_subsection(name);
        prm.declare_entry("Young's modulus", str(m.youngs_modulus), positive,
                          "Young's modulus [Pa]." + note);
        prm.declare_entry("Poisson's ratio", str(m.poisson_ratio),
                          Patterns::Double(-0.99, 0.49), "Poisson's ratio [-].");
        prm.declare_entry("Density", str(m.density), positive,
                          "Mass density [kg/m^3].");
        prm.leave_subsection();
      }

      void
      parse_material(ParameterHandler &prm, const std::string &name, Material &m)
      {
        prm.enter_subsection(name);
        m.youngs_modulus = prm.get_double("Young's modulus");
        m.poisson_ratio  = prm.get_double("Poisson's ratio");
        m.density        = prm.get_double("Density");
        prm.leave_subsection();
      }
    } // namespace

    void
    Materials::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Materials");
      declare_material(prm, "Disc", disc, "");
      declare_material(prm, "Pad", pad,
                       " Reference value; a sweep rescales the pad stiffness.");
      declare_material(prm, "Support", support,
                       " Its Density is used only when Support density "
                       "model = steel.");
      prm.declare_entry("Support density model", support_density_model,
                        Patterns::Selection("updated|steel"),
                        "updated: the density calibrated so that the support "
                        "modes match the thesis (Support updated density); "
                        "steel: Support/Density.");
      prm.declare_entry("Support updated density", str(support_updated_density),
                        positive,
                        "Calibrated support density [kg/m^3] (model updating, "
                        "see benchmarks/cea_tribobrake/README.md).");
      prm.leave_subsection();
    }

    void
    Materials::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Materials");
      parse_material(prm, "Disc", disc);
      parse_material(prm, "Pad", pad);
      parse_material(prm, "Support", support);
      support_density_model   = prm.get("Support density model");
      support_updated_density = prm.get_double("Support updated density");
      prm.leave_subsection();
      if (support_density_model == "updated")
        support.density = support_updated_density;
    }

    void
    Springs::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Springs");
      prm.declare_entry("Rows per side", std::to_string(n_rows_per_side),
                        Patterns::Integer(0, 8),
                        "Rows of springs on each of the two support faces "
                        "normal to the sliding direction.");
      prm.declare_entry("Springs per row", std::to_string(n_per_row),
                        Patterns::Integer(1, 401),
                        "Springs along each row, evenly spaced over the "
                        "support length, both ends included.");
      prm.declare_entry("Stiffness", str(stiffness),
                        Patterns::Double(0., Patterns::Double::max_double_value),
                        "Stiffness of one spring in the sliding direction "
                        "[N/m]; far ends fixed.");
      prm.declare_entry(
        "Attachment radius", str(attachment_radius),
        Patterns::Double(0., Patterns::Double::max_double_value),
        "Radius [m] of the disc of the support face on which each spring "
        "acts: a Winkler layer in the sliding direction with cosine-bell "
        "stiffness density (largest at the station, 0 at the radius), "
        "normalised so that each spring keeps its stiffness and integrated "
        "consistently, so that the spring model is the same on every mesh "
        "and degree (the braking simulation lumps it on the face nodes, "
        "which its explicit time stepping needs). 0: the nearest node only "
        "(the thesis' point springs; a point force on a 3D body is "
        "singular, so frequencies carried by the springs drift under "
        "refinement and the tolerance-driven mesh cannot converge). A model "
        "parameter, not a discretisation one: at E_pad = 1 GPa the pad mode "
        "near 2.1 kHz moves from 2152 Hz (1.25 mm) to 2251 Hz (2.5 mm).");
      prm.leave_subsection();
    }

    void
    Springs::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Springs");
      n_rows_per_side = prm.get_integer("Rows per side");
      n_per_row       = prm.get_integer("Springs per row");
      stiffness       = prm.get_double("Stiffness");
      attachment_radius = prm.get_double("Attachment radius");
      prm.leave_subsection();
    }

    void
    Damping::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Damping");
      prm.declare_entry("Alpha", str(alpha),
                        Patterns::Double(0., Patterns::Double::max_double_value),
                        "Rayleigh mass coefficient alpha [1/s].");
      prm.declare_entry("Beta", str(beta),
                        Patterns::Double(0., Patterns::Double::max_double_value),
                        "Rayleigh stiffness coefficient beta [s] (multiplies "
                        "the structural stiffness, not the interface).");
      prm.leave_subsection();
    }

    void
    Damping::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Damping");
      alpha = prm.get_double("Alpha");
      beta  = prm.get_double("Beta");
      prm.leave_subsection();
    }

    Tensor<1, 3>
    Interface::sliding_tangent() const
    {
      Tensor<1, 3> t;
      if (sliding_direction == "rotation")
        t[1] = (rotation_sense == "counterclockwise" ? 1. : -1.);
      else
        {
          const auto v = Utilities::string_to_double(
            Utilities::split_string_list(sliding_direction, ','));
          t[0] = v[0];
          t[1] = v[1];
          t /= t.norm();
        }
      return t;
    }

    void
    Interface::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Interface");
      prm.declare_entry("Normal stiffness", str(normal_stiffness),
                        Patterns::Double(0., Patterns::Double::max_double_value),
                        "Normal interface stiffness per unit area [N/m^3]; "
                        "the thesis' 2.5895e8 N/m over 1e-4 m^2.");
      prm.declare_entry("Friction coefficient", str(friction_coefficient),
                        Patterns::Double(0., 10.),
                        "Coulomb friction coefficient [-] of every sweep "
                        "point when the sweep does not vary it.");
      prm.declare_entry("Sliding direction", sliding_direction,
                        Patterns::Anything(),
                        "`rotation` (the disc's velocity at the pad centre) "
                        "or two numbers `tx, ty`: the direction in the disc "
                        "plane in which the disc slides under the pad.");
      prm.declare_entry("Rotation sense", rotation_sense,
                        Patterns::Selection("counterclockwise|clockwise"),
                        "Sense of the disc rotation about +z.");
      prm.declare_entry("Quadrature", quadrature,
                        Patterns::Selection("mortar|nodal"),
                        "mortar: segment-based integration over the overlap "
                        "of pad and disc faces; nodal: one point per pad-face "
                        "node (node-pair elements on matching meshes).");
      prm.leave_subsection();
    }

    void
    Interface::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Interface");
      normal_stiffness  = prm.get_double("Normal stiffness");
      friction_coefficient = prm.get_double("Friction coefficient");
      sliding_direction = prm.get("Sliding direction");
      rotation_sense    = prm.get("Rotation sense");
      quadrature        = prm.get("Quadrature");
      prm.leave_subsection();
      if (sliding_direction != "rotation")
        {
          const auto parts =
            Utilities::split_string_list(sliding_direction, ',');
          bool ok = parts.size() == 2;
          double n2 = 0;
          for (const auto &p : parts)
            {
              char *end = nullptr;
              const double v = std::strtod(p.c_str(), &end);
              ok = ok && end != p.c_str() && *end == '\0';
              n2 += v * v;
            }
          check(ok && n2 > 0,
                "Interface/Sliding direction must be `rotation` or two "
                "numbers `tx, ty` not both zero, not '" +
                  sliding_direction + "'");
        }
    }

    void
    Eigensolver::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Eigensolver");
      prm.declare_entry("Minimum frequency", str(f_min), positive,
                        "Lower end of the band [Hz].");
      prm.declare_entry("Maximum frequency", str(f_max), positive,
                        "Upper end of the band [Hz].");
      prm.declare_entry("Method", method, Patterns::Selection("full|reduced"),
                        "full: at every point, SLEPc Krylov-Schur on the "
                        "undamped friction-coupled problem (real shift-and-"
                        "invert, MUMPS), then the damped problem on that "
                        "subspace, refined to relative residual 1e-8; "
                        "reduced: modal "
                        "basis with friction enrichment, dense LAPACK per "
                        "point, checked against full at a few points.");
      prm.declare_entry("Tolerance", str(tolerance),
                        Patterns::Double(1e-15, 1e-3),
                        "Relative convergence tolerance of SLEPc.");
      prm.declare_entry("Target frequency", str(target_frequency), positive,
                        "The real shift is -2 pi times this [Hz]: eigenvalues "
                        "are found in order of distance from it, i.e. of "
                        "frequency; it must not be an eigenvalue.");
      prm.declare_entry("Unstable tolerance", str(unstable_tolerance),
                        Patterns::Double(0., Patterns::Double::max_double_value),
                        "An eigenvalue is unstable when Re(lambda) exceeds "
                        "this [1/s].");
      prm.declare_entry("Reduced samples", std::to_string(reduced_samples),
                        Patterns::Integer(1, 20),
                        "Values of each swept structural parameter (pad "
                        "modulus, interface or spring stiffness, support "
                        "density) at which real modes of the symmetric system "
                        "build the reduced basis: the ends of the sweep range "
                        "and evenly spaced values between (log-spaced for a "
                        "log sweep); with two structural parameters, every "
                        "combination. One sample at the nominal point if "
                        "neither swept parameter is structural.");
      prm.declare_entry("Reduced band factor", str(reduced_band_factor),
                        Patterns::Double(1., 10.),
                        "Modes up to this factor times the maximum frequency "
                        "enter the reduced basis. With the enrichment, 1.1 "
                        "already gives 2e-6 in frequency and 7e-6 in growth "
                        "rate against the full solver "
                        "(benchmarks/speed_vs_error); 1.25 keeps a margin.");
      prm.declare_entry("Reduced enrichment", reduced_enrichment ? "true" : "false",
                        Patterns::Bool(),
                        "Add K^-1 K_t Phi (static response to the friction "
                        "forces of the basis modes) and K^-1 K_n Phi (to the "
                        "interface forces; Rayleigh damping beta K_s is not "
                        "proportional to K_s + K_n) to the basis.");
      prm.declare_entry("Reduced enrichment depth",
                        std::to_string(reduced_enrichment_depth),
                        Patterns::Integer(1, 4),
                        "Levels of friction enrichment: (K^-1 K_t)^l Phi for "
                        "l = 1..depth (with the interface response K^-1 K_n "
                        "Phi always added). 1 holds growth rates to 0.1 % up "
                        "to mu = 2 in the hard-case tests; 2 gains little.");
      prm.declare_entry("Check points", std::to_string(n_check_points),
                        Patterns::Integer(0, 100),
                        "Sweep points at which the reduced solver is checked "
                        "against the full solver.");
      prm.leave_subsection();
    }

    void
    Eigensolver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Eigensolver");
      f_min              = prm.get_double("Minimum frequency");
      f_max              = prm.get_double("Maximum frequency");
      method             = prm.get("Method");
      tolerance          = prm.get_double("Tolerance");
      target_frequency   = prm.get_double("Target frequency");
      unstable_tolerance = prm.get_double("Unstable tolerance");
      reduced_samples     = prm.get_integer("Reduced samples");
      reduced_band_factor = prm.get_double("Reduced band factor");
      reduced_enrichment  = prm.get_bool("Reduced enrichment");
      reduced_enrichment_depth = prm.get_integer("Reduced enrichment depth");
      n_check_points      = prm.get_integer("Check points");
      prm.leave_subsection();
      check(f_min < f_max,
            "Eigensolver/Minimum frequency (" + str(f_min) +
              " Hz) must be below Eigensolver/Maximum frequency (" +
              str(f_max) + " Hz)");
    }

    namespace
    {
      double &
      member(ScalarPoint &p, const std::string &name)
      {
        static const std::vector<std::pair<std::string, double ScalarPoint::*>>
          members = {{"pad modulus", &ScalarPoint::E_pad},
                     {"friction coefficient", &ScalarPoint::mu},
                     {"interface stiffness", &ScalarPoint::interface_stiffness},
                     {"spring stiffness", &ScalarPoint::spring_stiffness},
                     {"support density", &ScalarPoint::support_density},
                     {"rayleigh alpha", &ScalarPoint::alpha},
                     {"rayleigh beta", &ScalarPoint::beta}};
        for (const auto &[n, m] : members)
          if (n == name)
            return p.*m;
        sweepable_parameter(name); // throws with the allowed names
        throw std::logic_error("unreachable");
      }

      std::string
      sweepable_names()
      {
        std::string names;
        for (const auto &p : sweepable_parameters())
          names += (names.empty() ? "" : "|") + std::string(p.name);
        return names;
      }
    } // namespace

    double
    ScalarPoint::get(const std::string &name) const
    {
      return member(const_cast<ScalarPoint &>(*this), name);
    }

    void
    ScalarPoint::set(const std::string &name, const double value)
    {
      member(*this, name) = value;
    }

    const std::vector<SweepableParameter> &
    sweepable_parameters()
    {
      static const std::vector<SweepableParameter> list = {
        {"pad modulus", "E_pad", "Pa", 0., true, true},
        {"friction coefficient", "mu", "", 0., false, false},
        {"interface stiffness", "k_n", "N_per_m3", 0., false, true},
        {"spring stiffness", "k_spring", "N_per_m", 0., false, true},
        {"support density", "rho_support", "kg_per_m3", 0., true, true},
        {"rayleigh alpha", "alpha", "per_s", 0., false, false},
        {"rayleigh beta", "beta", "s", 0., false, false}};
      return list;
    }

    const SweepableParameter &
    sweepable_parameter(const std::string &name)
    {
      for (const auto &p : sweepable_parameters())
        if (name == p.name)
          return p;
      throw std::runtime_error("unknown sweep parameter '" + name +
                               "'; allowed: " + sweepable_names());
    }

    std::string
    column_name(const std::string &name, const std::string &qualifier)
    {
      const auto &p = sweepable_parameter(name);
      return std::string(p.symbol) + qualifier +
             (p.unit[0] ? "_" + std::string(p.unit) : std::string());
    }

    void
    SweepAxis::parse(const std::string &entry)
    {
      const std::string forms =
        "; allowed: 'log A B N' (N log-spaced values from A to B > 0), "
        "'linear A B N' or a comma-separated list of values";
      const auto &info = sweepable_parameter(parameter);
      std::istringstream words(values_text);
      std::string        kind;
      words >> kind;
      values.clear();
      log_spaced = kind == "log";
      if (kind == "log" || kind == "linear")
        {
          double       a, b;
          unsigned int n;
          std::string  rest;
          if (!(words >> a >> b >> n) || (words >> rest) || n == 0 ||
              n > 100000)
            throw std::runtime_error("invalid parameter: " + entry + " = '" +
                                     values_text + "'" + forms);
          if (log_spaced && (a <= 0 || b <= 0))
            throw std::runtime_error("invalid parameter: " + entry +
                                     ": a log sweep needs positive ends");
          for (unsigned int i = 0; i < n; ++i)
            {
              const double t = n == 1 ? 0. : double(i) / (n - 1);
              values.push_back(log_spaced ? a * std::pow(b / a, t) :
                                            a + (b - a) * t);
            }
        }
      else
        for (const auto &item : Utilities::split_string_list(values_text))
          {
            std::size_t used = 0;
            double      v    = 0;
            try
              {
                v = std::stod(item, &used);
              }
            catch (const std::exception &)
              {
                used = 0;
              }
            if (used == 0 || used != item.size())
              throw std::runtime_error("invalid parameter: " + entry + ": '" +
                                       item + "' is not a number" + forms);
            values.push_back(v);
          }
      if (values.empty())
        throw std::runtime_error("invalid parameter: " + entry +
                                 " is empty" + forms);
      for (const double v : values)
        check(std::isfinite(v) &&
                (info.low_open ? v > info.lowest : v >= info.lowest),
              entry + ": " + str(v) + " is out of range for the " +
                info.name + " (must be " + (info.low_open ? "> " : ">= ") +
                str(info.lowest) + ")");
    }

    bool
    SweepAxis::log_scale() const
    {
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      return !values.empty() && *lo > 0 && (log_spaced || *hi > 10 * *lo);
    }

    void
    Sweep::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Sweep");
      const std::string forms =
        " Values: 'log A B N' (N log-spaced values from A to B), "
        "'linear A B N' (N evenly spaced), or a comma-separated list.";
      prm.declare_entry("First parameter", first.parameter,
                        Patterns::Selection(sweepable_names()),
                        "The parameter along which modes are tracked and "
                        "unstable regions are intervals (the x axis of the "
                        "plots). Units: pad modulus Pa, interface stiffness "
                        "N/m^3, spring stiffness N/m, support density kg/m^3, "
                        "Rayleigh alpha 1/s, Rayleigh beta s.");
      prm.declare_entry("First values", first.values_text, Patterns::Anything(),
                        "Values of the first parameter, SI units." + forms);
      prm.declare_entry("Second parameter", second.parameter,
                        Patterns::Selection(sweepable_names()),
                        "The parameter of which each value gets its own "
                        "tracked sweep of the first (one curve family of the "
                        "plots).");
      prm.declare_entry("Second values", second.values_text,
                        Patterns::Anything(),
                        "Values of the second parameter, SI units." + forms);
      prm.leave_subsection();
    }

    void
    Sweep::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Sweep");
      first.parameter    = prm.get("First parameter");
      first.values_text  = prm.get("First values");
      second.parameter   = prm.get("Second parameter");
      second.values_text = prm.get("Second values");
      prm.leave_subsection();
      check(first.parameter != second.parameter,
            "Sweep/First parameter and Sweep/Second parameter are both '" +
              first.parameter + "'; choose two different parameters");
      first.parse("Sweep/First values");
      second.parse("Sweep/Second values");
    }

    void
    Output::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Output");
      prm.declare_entry("Directory", directory, Patterns::FileName(),
                        "Output directory; a run refuses to replace an "
                        "existing one unless Overwrite is true or --overwrite "
                        "is given.");
      prm.declare_entry("Overwrite", overwrite ? "true" : "false",
                        Patterns::Bool(),
                        "Replace an existing output directory.");
      prm.declare_entry("Mode shapes", mode_output,
                        Patterns::Selection("none|unstable and first|all"),
                        "Which mode shapes go to modes.pvd: every unstable "
                        "mode at its largest growth rate and all modes of "
                        "the first point, all modes of every point, or none.");
      prm.leave_subsection();
    }

    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      directory   = prm.get("Directory");
      overwrite   = prm.get_bool("Overwrite");
      mode_output = prm.get("Mode shapes");
      prm.leave_subsection();
      check(!directory.empty(), "Output/Directory must not be empty");
    }

    void
    AllParameters::declare_parameters(ParameterHandler &prm) const
    {
      scene.declare_parameters(prm);
      geometry.declare_parameters(prm);
      mesh.declare_parameters(prm);
      materials.declare_parameters(prm);
      springs.declare_parameters(prm);
      damping.declare_parameters(prm);
      interface.declare_parameters(prm);
      eigensolver.declare_parameters(prm);
      sweep.declare_parameters(prm);
      preload.declare_parameters(prm);
      transient.declare_parameters(prm);
      output.declare_parameters(prm);
    }

    void
    AllParameters::parse_parameters(ParameterHandler &prm)
    {
      scene.parse_parameters(prm);
      geometry.parse_parameters(prm);
      mesh.parse_parameters(prm);
      materials.parse_parameters(prm);
      springs.parse_parameters(prm);
      damping.parse_parameters(prm);
      interface.parse_parameters(prm);
      eigensolver.parse_parameters(prm);
      sweep.parse_parameters(prm);
      preload.parse_parameters(prm);
      transient.parse_parameters(prm);
      output.parse_parameters(prm);
      check(mesh.contact_refinements == 0 ||
              scene.analysis == "preloaded cea",
            "Mesh/Contact refinements = " +
              std::to_string(mesh.contact_refinements) +
              " refines by the preload's contact pressure and needs "
              "Scene/Analysis = preloaded cea (it is " + scene.analysis +
              "); without a preload set it to 0 and refine the disc track "
              "by geometry with Mesh/Disc refinements under pad");
    }

    ScalarPoint
    AllParameters::nominal_point() const
    {
      ScalarPoint p;
      p.E_pad               = materials.pad.youngs_modulus;
      p.mu                  = interface.friction_coefficient;
      p.interface_stiffness = interface.normal_stiffness;
      p.spring_stiffness    = springs.stiffness;
      p.support_density     = materials.support.density;
      p.alpha               = damping.alpha;
      p.beta                = damping.beta;
      return p;
    }

    void
    AllParameters::set_nominal_point(const ScalarPoint &p)
    {
      materials.pad.youngs_modulus     = p.E_pad;
      interface.friction_coefficient   = p.mu;
      interface.normal_stiffness       = p.interface_stiffness;
      springs.stiffness                = p.spring_stiffness;
      materials.support.density        = p.support_density;
      damping.alpha                    = p.alpha;
      damping.beta                     = p.beta;
    }

    std::vector<ScalarPoint>
    AllParameters::sweep_points() const
    {
      std::vector<ScalarPoint> points;
      for (const double s : sweep.second.values)
        for (const double f : sweep.first.values)
          {
            ScalarPoint p = nominal_point();
            p.set(sweep.second.parameter, s);
            p.set(sweep.first.parameter, f);
            points.push_back(p);
          }
      return points;
    }

    void
    AllParameters::read(ParameterHandler &prm, const std::string &filename)
    {
      std::ifstream in(filename);
      if (!in)
        throw std::runtime_error("cannot open parameter file '" + filename +
                                 "'");
      declare_parameters(prm);
      try
        {
          prm.parse_input(filename, "", false, true);
        }
      catch (const ExceptionBase &e)
        {
          // deal.II's own text names the line and the entry; keep only it.
          std::ostringstream info;
          e.print_info(info);
          // One line: fold deal.II's indented layout.
          std::istringstream words(info.str());
          std::string        folded, w;
          while (words >> w)
            folded += (folded.empty() ? "" : " ") + w;
          throw std::runtime_error("in parameter file '" + filename + "': " +
                                   folded);
        }
      try
        {
          parse_parameters(prm);
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error("in parameter file '" + filename +
                                   "': " + e.what());
        }
      // A relative mesh path is the parameter file's neighbour: made
      // absolute here, and in the handler, so that the copy of the
      // parameters a run writes (and --resume reads) finds it too.
      auto &mesh = scene.mesh_file.file;
      if (!mesh.empty() && std::filesystem::path(mesh).is_relative())
        {
          mesh = std::filesystem::absolute(
                   std::filesystem::path(filename).parent_path() / mesh)
                   .lexically_normal()
                   .string();
          prm.enter_subsection("Scene");
          prm.enter_subsection("Mesh file");
          prm.set("File", mesh);
          prm.leave_subsection();
          prm.leave_subsection();
        }
    }
  } // namespace parameters
} // namespace squeal
