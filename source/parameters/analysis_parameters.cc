// The analyses' subsections: Preload, Transient (the braking run) and
// Eigensolver.

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
    using internal::positive;
    using internal::str;

    void
    Preload::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Preload");
      prm.declare_entry("Normal force",
                        str(normal_force),
                        Patterns::Double(0.),
                        "Force on the support's top pressing the pad on the "
                        "disc [N], spread uniformly over the top face.");
      prm.declare_entry("Friction",
                        friction,
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
      prm.declare_entry("Normal contact law",
                        normal_law,
                        Patterns::Selection("penalty|hard"),
                        "penalty: the contact pressure is k_n times the "
                        "penetration, k_n each contact pair's normal "
                        "stiffness [N/m^3] (its k_n=, or Interface/Normal "
                        "stiffness): the law whose tangent the CEA's "
                        "interface is, so the preload and the CEA about it "
                        "agree (the CEA keeps the interface where this law "
                        "keeps the pad in contact); hard: no penetration "
                        "(Lagrange multipliers), for Scene/Analysis = "
                        "preload only. For the hard limit in a preloaded "
                        "CEA set a large k_n (1e14 N/m^3 for steel).");
      prm.declare_entry("Search distance",
                        str(search_distance),
                        Patterns::Double(1e-9),
                        "How far along the pad face's normal the disc face is "
                        "searched [m]; bodies overlapping by more are "
                        "refused.");
      prm.declare_entry("Load steps",
                        std::to_string(load_steps),
                        Patterns::Integer(1, 1000),
                        "Increments of the normal force; each step's "
                        "contact state is written (contact_step_NNN.csv, "
                        "contact.pvd). With coulomb the path matters.");
      prm.declare_entry("Disc slip per step",
                        str(disc_slip),
                        Patterns::Double(0.),
                        "With Friction = coulomb: how far the disc's surface "
                        "moves under the pad along Interface/Sliding "
                        "direction during each load step [m] (the disc "
                        "turning); 0 keeps the disc at rest, so only the "
                        "pad's own deformation slips. A slip much larger than "
                        "the elastic one makes every node in contact slip and "
                        "reproduces steady sliding.");
      prm.declare_entry("Segmentation refresh",
                        str(segmentation_refresh),
                        Patterns::Double(0.),
                        "Large sliding: after a load step, the mortar "
                        "segmentation is rebuilt on the deformed surfaces "
                        "when the pad's largest relative tangential "
                        "displacement against the disc since the last one "
                        "exceeds this fraction of the shortest pad face "
                        "edge (0: never). The preload's elastic slips are "
                        "far below it, so it builds the segmentation once.");
      prm.declare_entry(
        "Contact state",
        contact_state,
        Patterns::Selection("preload|braking history"),
        "The contact state a Scene/Analysis = preloaded cea is linearised "
        "about. preload: this static preload, run first; the interface "
        "(stiffness and friction coupling) is kept where the pad stays in "
        "contact. braking history: no preload; the interface at each point "
        "is scaled by the fraction of Contact history window that the "
        "nearest pad node of a braking run's contact history (Contact "
        "history) spent in contact, stick or slip: the time-averaged "
        "interface of the transient's vibration, with its partial "
        "separation.");
      prm.declare_entry("Contact history",
                        contact_history,
                        Patterns::Anything(),
                        "Contact state = braking history: the braking run's "
                        "contact_history.h5 (its pad nodes must cover this "
                        "scene's pad faces: the same scene).");
      prm.declare_entry("Contact history window",
                        "",
                        Patterns::Anything(),
                        "Contact state = braking history: start, end [s] of "
                        "the history's samples that are averaged (e.g. the "
                        "limit cycle); empty: every sample.");
      prm.leave_subsection();
    }

    void
    Preload::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Preload");
      normal_force             = prm.get_double("Normal force");
      friction                 = prm.get("Friction");
      normal_law               = prm.get("Normal contact law");
      search_distance          = prm.get_double("Search distance");
      load_steps               = prm.get_integer("Load steps");
      disc_slip                = prm.get_double("Disc slip per step");
      segmentation_refresh     = prm.get_double("Segmentation refresh");
      contact_state            = prm.get("Contact state");
      contact_history          = prm.get("Contact history");
      const std::string window = prm.get("Contact history window");
      prm.leave_subsection();
      check(contact_state != "braking history" || !contact_history.empty(),
            "Preload/Contact state = braking history needs Preload/Contact "
            "history, the braking run's contact_history.h5");
      contact_window.clear();
      if (window.find_first_not_of(" \t") != std::string::npos)
        {
          bool ok = true;
          try
            {
              contact_window = Utilities::string_to_double(
                Utilities::split_string_list(window, ','));
            }
          catch (...)
            {
              ok = false;
            }
          check(ok && contact_window.size() == 2 &&
                  std::isfinite(contact_window[0]) &&
                  std::isfinite(contact_window[1]) &&
                  contact_window[0] < contact_window[1],
                "Preload/Contact history window = '" + window +
                  "': give start, end in seconds with start < end (or "
                  "leave it empty for every sample)");
        }
      check(disc_slip == 0. || friction == "coulomb",
            "Preload/Disc slip per step = " + str(disc_slip) +
              " needs Preload/Friction = coulomb (got " + friction +
              "): the other friction laws have no slip history");
    }

    void
    Transient::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Transient");
      prm.declare_entry("Angular velocity",
                        str(angular_velocity),
                        Patterns::Double(0.),
                        "Disc speed [rad/s] (10 rpm = 1.0472). The rotation "
                        "enters as the sliding velocity omega r of the disc "
                        "face under the pad, in the disc's fixed mesh "
                        "(Interface/Rotation sense); transport terms, of "
                        "order omega / omega_mode (1e-4), are neglected.");
      prm.declare_entry("Normal force",
                        str(normal_force),
                        Patterns::Double(0.),
                        "Final force on the support's top [N].");
      prm.declare_entry("Ramp duration",
                        str(ramp_duration),
                        Patterns::Double(0.),
                        "The force rises as (1 - cos(pi t / T)) / 2 over this "
                        "time [s], so that the first contact does not excite "
                        "the structure, then is held.");
      prm.declare_entry("End time",
                        str(end_time),
                        Patterns::Double(1e-9),
                        "Simulated time [s].");
      prm.declare_entry("Time step",
                        str(time_step),
                        Patterns::Double(0.),
                        "Time step [s]; 0: Safety factor x the computed "
                        "stability limit. A step above the limit is refused.");
      prm.declare_entry("Safety factor",
                        str(safety_factor),
                        Patterns::Double(1e-3, 1.),
                        "Fraction of the stability limit used when Time step "
                        "is 0.");
      prm.declare_entry("Beta2",
                        str(beta2),
                        Patterns::Double(0.5, 1.),
                        "The beta2 parameter of the explicit scheme (thesis "
                        "eq. 2-6): 0.5 is central differences; larger values "
                        "damp high frequencies numerically.");
      prm.declare_entry("Sampling rate",
                        str(sampling_rate),
                        Patterns::Double(1.),
                        "Rate [Hz] of forces.csv, probes.csv and the contact "
                        "history (contact_history.h5); at most 1 / time step.");
      prm.declare_entry("History start",
                        str(history_start),
                        Patterns::Double(0.),
                        "Time [s] of the first sample of the contact history.");
      prm.declare_entry("Snapshot interval",
                        str(snapshot_interval),
                        Patterns::Double(0.),
                        "Time [s] between ParaView snapshots (transient.pvd: "
                        "displacement, velocity, von Mises stress; "
                        "contact.pvd: the pad face's contact fields); 0: "
                        "none besides the animation window.");
      prm.declare_entry("Animation start",
                        str(animation_start),
                        Patterns::Double(),
                        "Start [s] of a window of Animation frames snapshots "
                        "spread over Animation period (animation.pvd, for "
                        "one squeal period in ParaView); < 0: the window "
                        "ends at End time.");
      prm.declare_entry("Animation period",
                        str(animation_period),
                        Patterns::Double(0.),
                        "Length [s] of the animation window: one period of "
                        "the expected squeal (1 / 3430 Hz for the TriboBrake "
                        "of the thesis).");
      prm.declare_entry("Animation frames",
                        std::to_string(animation_frames),
                        Patterns::Integer(0, 1000),
                        "Snapshots in the animation window; 0: none.");
      prm.declare_entry("Spectrum start",
                        str(spectrum_start),
                        Patterns::Double(),
                        "Start [s] of the window of the power spectral "
                        "density (Welch) of the probe's acceleration; < 0: "
                        "the second half of the run.");
      prm.declare_entry("Contact tolerance",
                        str(contact_tolerance),
                        Patterns::Double(1e-16, 1e-2),
                        "Relative change of the contact multipliers at which "
                        "projected Gauss-Seidel stops.");
      prm.declare_entry("Contact iterations",
                        std::to_string(contact_iterations),
                        Patterns::Integer(1),
                        "Most projected Gauss-Seidel sweeps per step; more "
                        "stops the run with the time and the residual.");
      prm.declare_entry("Initial perturbation",
                        str(initial_perturbation),
                        Patterns::Double(0.),
                        "Axial velocity [m/s] given to the disc at t = 0 in "
                        "the shape of a (0,3) mode (cos 3 theta, rising with "
                        "the radius), a seed for an instability; 0: none "
                        "(the load ramp and rounding seed it).");
      prm.declare_entry("Stiffness product",
                        stiffness_product,
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
      prm.declare_entry("Grid",
                        grid ? "true" : "false",
                        Patterns::Bool(),
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
      // a given step: its count is known before the run (an automatic one
      // is checked once the stability limit is)
      check(time_step == 0. ||
              std::ceil(end_time / time_step - 1e-9) + 1. < 2e9,
            "Transient/End time = " + str(end_time) +
              " s at Time step = " + str(time_step) + " s is " +
              str(std::ceil(end_time / time_step - 1e-9) + 1.) +
              " steps, more than a run can count (2e9); shorten the run or "
              "take a larger step");
    }
    void
    Eigensolver::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Eigensolver");
      prm.declare_entry("Minimum frequency",
                        str(f_min),
                        positive,
                        "Lower end of the band [Hz].");
      prm.declare_entry("Maximum frequency",
                        str(f_max),
                        positive,
                        "Upper end of the band [Hz].");
      prm.declare_entry("Method",
                        method,
                        Patterns::Selection("full|reduced"),
                        "full: at every point, the symmetric modes counted "
                        "by Sylvester inertia and found by the Symmetric "
                        "eigensolver (MUMPS Cholesky), the damped "
                        "friction-coupled problem projected on them and "
                        "refined by Davidson to Residual tolerance; "
                        "reduced: modal basis with friction enrichment, "
                        "dense LAPACK per point, the (nearly) unstable "
                        "eigenvalues certified on the full model, checked "
                        "against full at the most unstable point and the "
                        "edges of the unstable regions.");
      prm.declare_entry("Tolerance",
                        str(tolerance),
                        Patterns::Double(1e-15, 1e-3),
                        "Relative convergence tolerance of SLEPc.");
      prm.declare_entry("Target frequency",
                        str(target_frequency),
                        positive,
                        "The real shift is -2 pi times this [Hz]: eigenvalues "
                        "are found in order of distance from it, i.e. of "
                        "frequency; it must not be an eigenvalue.");
      prm.declare_entry("Unstable tolerance",
                        str(unstable_tolerance),
                        Patterns::Double(0.,
                                         Patterns::Double::max_double_value),
                        "An eigenvalue is unstable when Re(lambda) exceeds "
                        "this [1/s] and Unstable relative tolerance times "
                        "|lambda|.");
      prm.declare_entry("Unstable relative tolerance",
                        str(unstable_relative_tolerance),
                        Patterns::Double(0., 1.),
                        "An eigenvalue is unstable when Re(lambda) / "
                        "|lambda| (minus the damping ratio) exceeds this and "
                        "Re(lambda) exceeds Unstable tolerance. The default "
                        "1e-6 lies far above the error of a certified "
                        "eigenvalue (residual 1e-10) and keeps undamped "
                        "doublets, whose Re(lambda) is round-off, stable.");
      prm.declare_entry("Certify stability map",
                        certify ? "true" : "false",
                        Patterns::Bool(),
                        "Reduced method: refine every eigenvalue within "
                        "Certification margin of the stability threshold on "
                        "the full model until its residual is below "
                        "Residual tolerance (Davidson from the reduced "
                        "pair), so that the unstable regions are drawn from "
                        "certified values; a pair that does not get there "
                        "fails the run.");
      prm.declare_entry("Certification margin",
                        str(certification_margin),
                        Patterns::Double(0.,
                                         Patterns::Double::max_double_value),
                        "Eigenvalues whose Re(lambda) lies above the "
                        "stability threshold minus this [1/s] are "
                        "certified (the reduced solver's error in "
                        "Re(lambda) is below 0.2 1/s on the TriboBrake, "
                        "benchmarks/cea_tribobrake).");
      prm.declare_entry(
        "Symmetric eigensolver",
        symmetric_solver,
        Patterns::Selection("auto|slepc|arpack|block"),
        "The eigensolver for the modes of the symmetric problem (the full "
        "solver's basis and each reduced-basis sample, as many as the "
        "inertia count gives), each on a MUMPS Cholesky factorisation of "
        "K - sigma M: auto (block), "
        "slepc (SLEPc's Krylov-Schur, shift-and-invert), "
        "arpack (PARPACK's implicitly restarted Lanczos through deal.II) or "
        "block (squeal's thick-restart block Lanczos: one solve with a "
        "block of vectors per step, one pass through the factors where the "
        "others make one per vector: cheaper per vector in memory, and "
        "read from disk once per block with the factors out of core). "
        "The results agree (cea_tribobrake_coarse).");
      prm.declare_entry(
        "Subspace products",
        subspace_products,
        Patterns::Selection("stored|recomputed"),
        "The full solver's subspace V (n x r, r up to a few thousand "
        "vectors): stored keeps its products M V, C V, K V (four n x r "
        "blocks; a Ritz pair's residual is combined from them); recomputed "
        "keeps V only (half the peak memory on the brake; the products of "
        "each new block and of the Ritz vectors are formed when needed). "
        "Its residuals are those of the returned vectors as rounded to "
        "double precision, whose floor is near 1e-10 for the lowest modes "
        "of a large model: use it with a Residual tolerance of a few "
        "1e-10 (doc/cea.md).");
      prm.declare_entry("Tracking MAC threshold",
                        str(tracking_mac_threshold),
                        Patterns::Double(0., 1.),
                        "Modes of consecutive sweep points are linked into "
                        "tracks by the one-to-one assignment of least total "
                        "cost (1 - MAC) + 10 |lambda_a - lambda_b| / "
                        "|lambda_a| (Hungarian method); a link needs a MAC "
                        "of at least this, else the mode starts a new "
                        "track.");
      prm.declare_entry("Reduced samples",
                        std::to_string(reduced_samples),
                        Patterns::Integer(1, 20),
                        "Values of each swept structural parameter (pad "
                        "modulus, interface or spring stiffness, support "
                        "density) at which real modes of the symmetric system "
                        "build the reduced basis: the ends of the sweep range "
                        "and evenly spaced values between (log-spaced for a "
                        "log sweep); with two structural parameters, every "
                        "combination. One sample at the nominal point if "
                        "neither swept parameter is structural.");
      prm.declare_entry("Reduced band factor",
                        str(reduced_band_factor),
                        Patterns::Double(1., 10.),
                        "Modes up to this factor times the maximum frequency "
                        "enter the reduced basis. With the enrichment, 1.1 "
                        "already gives 2e-6 in frequency and 7e-6 in growth "
                        "rate against the full solver "
                        "(benchmarks/speed_vs_error); 1.25 keeps a margin.");
      prm.declare_entry("Reduced enrichment",
                        reduced_enrichment ? "true" : "false",
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
      prm.declare_entry(
        "Check points",
        std::to_string(n_check_points),
        Patterns::Integer(0, 10000),
        "The most sweep points at which the reduced solver is checked "
        "against the full solver: the most unstable point, then the first "
        "and last unstable point of every unstable region's track. A check "
        "fails when the mode counts or the numbers of unstable modes "
        "differ, or a matched pair differs by more than the check "
        "tolerance; 0 checks nothing.");
      prm.declare_entry("Residual tolerance",
                        str(residual_tolerance),
                        Patterns::Double(1e-14, 1e-2),
                        "Largest relative residual ||(lambda^2 M + lambda C "
                        "+ K) x|| / (|lambda|^2 ||M x|| + |lambda| ||C x|| + "
                        "||K x||) of a full-solver eigenpair; a pair above "
                        "it fails the run.");
      prm.declare_entry("Check tolerance",
                        str(check_tolerance),
                        Patterns::Double(1e-12, 1.),
                        "Largest |lambda_reduced - lambda_full| / "
                        "|lambda_full| of a one-to-one matched pair at a "
                        "check point.");
      prm.declare_entry("Allow unverified results",
                        "false",
                        Patterns::Bool(),
                        "When a residual or a check against the full solver "
                        "fails: false stops the run with the failures "
                        "listed; true writes the results into "
                        "DIRECTORY.unverified with the failures in "
                        "UNVERIFIED.txt.");
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
      unstable_relative_tolerance =
        prm.get_double("Unstable relative tolerance");
      certify                  = prm.get_bool("Certify stability map");
      certification_margin     = prm.get_double("Certification margin");
      tracking_mac_threshold   = prm.get_double("Tracking MAC threshold");
      symmetric_solver         = prm.get("Symmetric eigensolver");
      subspace_products        = prm.get("Subspace products");
      reduced_samples          = prm.get_integer("Reduced samples");
      reduced_band_factor      = prm.get_double("Reduced band factor");
      reduced_enrichment       = prm.get_bool("Reduced enrichment");
      reduced_enrichment_depth = prm.get_integer("Reduced enrichment depth");
      n_check_points           = prm.get_integer("Check points");
      residual_tolerance       = prm.get_double("Residual tolerance");
      check_tolerance          = prm.get_double("Check tolerance");
      allow_unverified         = prm.get_bool("Allow unverified results");
      prm.leave_subsection();
      check(target_frequency > 0.,
            "Eigensolver/Target frequency = " + str(target_frequency) +
              " Hz: the shift must be > 0 Hz");
      check(f_min < f_max,
            "Eigensolver/Minimum frequency (" + str(f_min) +
              " Hz) must be below Eigensolver/Maximum frequency (" +
              str(f_max) + " Hz)");
    }
    void
    ModelUpdating::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Model updating");
      prm.declare_entry(
        "Parameters",
        parameters,
        Patterns::Anything(),
        "The named scene parameters to fit (squeal --validate lists a "
        "scene's), each with its bounds in its unit: `name: lower, upper` "
        "(fitted on a log scale, lower > 0) or `name: lower, upper, linear`, "
        "separated by `;`. `name@configuration` fits the parameter "
        "separately in that configuration (of Configurations). Example: "
        "`pad.E: 1e8, 1e11; support.rho: 7000, 8500, linear; pad on "
        "disc.k_n@loaded: 1e11, 1e15`.");
      prm.declare_entry(
        "Targets",
        targets,
        Patterns::Anything(),
        "CSV of the measured modes (relative to this file), one per line "
        "under a header naming the columns: label and frequency_Hz "
        "(needed), weight (> 0, default 1: divides the frequency's "
        "variance), name (pairs the mode with a model mode of that name: "
        "a disc mode (n,m+-), or (n,m) for either sign, or a body and "
        "direction as `support y`), configuration (one of Configurations; "
        "empty: the file's values), damping_ratio (the measured modal "
        "damping ratio zeta in (0, 1), not in %; empty: not measured; "
        "fitted with the Rayleigh damping's named parameters) and, with "
        "Measurement points, one "
        "column per point whose header starts with `shape` (in the "
        "points' order; empty values: no shape for that mode). Without "
        "shape or name a mode is paired by frequency. Quote fields "
        "holding commas.");
      prm.declare_entry(
        "Configurations",
        configurations,
        Patterns::Anything(),
        "Model configurations the Targets may name, each the file's values "
        "with some parameters that are not fitted changed: `name: "
        "parameter = value, parameter = value; name: ...` (for example "
        "`soft pad: pad.E = 1e9; Table 3.1: pad.E = 25e9`); every step "
        "solves each configuration a target names.");
      prm.declare_entry(
        "Measurement points",
        measurement_points,
        Patterns::Anything(),
        "CSV of the measurement points (relative to this file; empty: "
        "none): a header line, then per point `label,x,y,z,dx,dy,dz` "
        "[m, and a direction of any length]: the measured shapes are the "
        "displacement at the point along the direction.");
      prm.declare_entry("Measurement error",
                        str(measurement_error),
                        Patterns::Double(1e-12, 1.),
                        "Relative standard deviation of a measured "
                        "frequency of weight 1 [-]: scales the residuals and "
                        "gives the fitted parameters' uncertainty.");
      prm.declare_entry("Damping error",
                        str(damping_error),
                        Patterns::Double(1e-12, 10.),
                        "Relative standard deviation of a measured damping "
                        "ratio of weight 1 [-] (the Targets' damping_ratio "
                        "column).");
      prm.declare_entry(
        "Method",
        method,
        Patterns::Selection("reduced|full"),
        "reduced: in rounds, the Levenberg-Marquardt trials solve the model "
        "projected on the frictionless modes (to 1.5 x Maximum frequency) of "
        "the full solves at the round's point and the one before, each "
        "parameter moving by a factor of 4 at most; a full solve confirms "
        "each round's end, and the fit ends when every paired mode agrees "
        "within Reduced tolerance and no parameter is held by that limit "
        "(at most 20 rounds). full: a full eigensolve at every trial.");
      prm.declare_entry("Reduced tolerance",
                        str(reduced_tolerance),
                        Patterns::Double(1e-12, 0.1),
                        "Largest relative frequency difference of a paired "
                        "mode between the reduced model and the confirming "
                        "full solve [-] (Method = reduced).");
      prm.declare_entry("Maximum iterations",
                        std::to_string(max_iterations),
                        Patterns::Integer(0, 1000),
                        "Levenberg-Marquardt steps at most (each one "
                        "symmetric eigensolve of the full model).");
      prm.declare_entry("Tolerance",
                        str(tolerance),
                        Patterns::Double(1e-14, 0.1),
                        "Levenberg-Marquardt stops when an accepted step "
                        "lowers the cost by less than this fraction of it, "
                        "or moves the (log-scaled) parameters by less than "
                        "this relative to them [-]. Near the minimum the "
                        "cost is flat within the eigensolver's noise, and a "
                        "tighter value only creeps.");
      prm.declare_entry("MAC threshold",
                        str(mac_threshold),
                        Patterns::Double(0.01, 1.),
                        "Least MAC of a measured and a model shape that "
                        "may be paired.");
      prm.declare_entry("Frequency window",
                        str(frequency_window),
                        Patterns::Double(1e-6, 10.),
                        "Largest relative frequency distance of a pairing "
                        "without shape or name [-].");
      prm.declare_entry("Maximum frequency",
                        str(maximum_frequency),
                        Patterns::Double(0.),
                        "Highest model mode computed [Hz] (every mode below "
                        "it, counted by Sylvester inertia); 0: 1.5 times the "
                        "highest measured frequency, 2.5 times when a target "
                        "has a damping ratio (the modes above it enter the "
                        "damping ratios' derivatives in their static limit, "
                        "an error of order (f / Maximum frequency)^2).");
      prm.leave_subsection();
    }

    void
    ModelUpdating::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Model updating");
      parameters         = prm.get("Parameters");
      targets            = prm.get("Targets");
      measurement_points = prm.get("Measurement points");
      configurations     = prm.get("Configurations");
      measurement_error  = prm.get_double("Measurement error");
      damping_error      = prm.get_double("Damping error");
      max_iterations     = prm.get_integer("Maximum iterations");
      method             = prm.get("Method");
      reduced_tolerance  = prm.get_double("Reduced tolerance");
      tolerance          = prm.get_double("Tolerance");
      mac_threshold      = prm.get_double("MAC threshold");
      frequency_window   = prm.get_double("Frequency window");
      maximum_frequency  = prm.get_double("Maximum frequency");
      prm.leave_subsection();
    }
  } // namespace parameters
} // namespace squeal
