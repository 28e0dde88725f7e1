#ifndef squeal_parameters_parameters_h
#define squeal_parameters_parameters_h

/**
 * @file
 * Run parameters, one struct per subsection of the `.prm` file. Every struct
 * has static-like `declare_parameters` and `parse_parameters` members in the
 * style of the deal.II code-gallery; every entry has a default, a Patterns::
 * range and help text with SI units. All quantities are SI (m, kg, s, Pa, N).
 */

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace squeal
{
  namespace parameters
  {
    using dealii::ParameterHandler;

    /**
     * A scene read from a mesh file (Scene/Type = mesh file): the file and
     * its length unit, and the lists that turn its named sets into bodies,
     * contact pairs, holds, point holds, loads, springs and probes. Each
     * list is `name: key=value, key=value; name: ...` (the keys are in the
     * help of each entry, --print-parameters); scene::make_scene() parses
     * and checks them against the mesh.
     */
    struct MeshFileScene
    {
      std::string file;             ///< `.msh` or `.inp`, absolute after read()
      double      length_unit = 1.; ///< m per mesh unit
      std::string bodies;           ///< the Bodies list (see its help)
      std::string contact_pairs;    ///< the Contact pairs list
      std::string ties;             ///< the Ties list (bonded interfaces)
      std::string holds;            ///< the Holds list
      std::string point_holds;      ///< the Point holds list
      std::string loads;            ///< the Loads list
      std::string springs;          ///< the Springs list
      std::string probes;           ///< the Probes list
      std::string masses;           ///< the Masses list
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * What the run acts on and which analysis it runs. Type `tribobrake`:
     * disc, pad, support and springs (thesis ch. 3); `disc`: the clamped
     * disc alone (verification A3); `mesh file`: the scene of subsection
     * Mesh file.
     */
    struct Scene
    {
      std::string type = "tribobrake"; ///< tribobrake | disc | mesh file
      /// `cea`: complex eigenvalue analysis (sweep); `preload`: the static
      /// frictional contact of the pad on the disc under the normal load;
      /// `preloaded cea`: the preload, then the CEA on its contact area;
      /// `braking`: the transient braking simulation; `model updating`:
      /// the fit of named parameters to measured modes
      std::string   analysis = "cea";
      MeshFileScene mesh_file; ///< subsection Mesh file
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Dimensions of the TriboBrake (thesis § 3.2.1), in m. */
    struct Geometry
    {
      double disc_inner_radius = 0.05; ///< m, clamped radius
      double disc_outer_radius = 0.12; ///< m
      double disc_thickness    = 0.01; ///< m, disc occupies -h <= z <= 0
      double pad_size          = 0.01; ///< m, edge of the cubic pad
      double pad_radius        = 0.10; ///< m, radius of the pad face centre
      double support_length    = 0.10; ///< m, along the disc axis z
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Mesh density per body and FE degree. */
    struct Mesh
    {
      unsigned int fe_degree = 2; ///< FE_Q degree of the displacement
      unsigned int disc_cells_circumference =
        64; ///< TriboBrake disc: cells around
      unsigned int disc_cells_radial =
        10; ///< TriboBrake disc: cells along the radius
      unsigned int disc_cells_thickness =
        2; ///< TriboBrake disc: cells through the thickness
      unsigned int pad_cells_side = 4; ///< across the pad face (x and y)
      unsigned int pad_cells_thickness =
        2; ///< TriboBrake pad: cells through the thickness
      unsigned int support_cells_length =
        10; ///< along z; 10 divides 11 spring stations
      unsigned int disc_refinements_under_pad =
        0; ///< TriboBrake disc: refinements under the pad
      /// preloaded CEA: refinement cycles of the contact region driven by
      /// the preload's contact pressure variation (0: none)
      unsigned int contact_refinements = 0;
      /// preloaded CEA: fraction of the contact-face cells refined per cycle
      double contact_refinement_fraction = 0.25;
      /// CEA: adaptive refinement cycles before the sweep (0: none)
      unsigned int adaptive_cycles = 0;
      /// CEA: fraction of the cells refined per cycle (largest indicator)
      double refinement_fraction = 0.15;
      /// CEA: `cells` (refine that fraction of the cells) or `error`
      /// (the fewest cells carrying that fraction of the squared indicator)
      std::string marking = "cells";
      /// CEA: the modes' error indicator, `kelly` (jump of the
      /// displacement gradient across faces) or `traction jump` (jump of
      /// the traction sigma n, continuous across bonded interfaces between
      /// materials in the exact solution)
      std::string error_indicator = "kelly";
      /// CEA: relative frequency tolerance of the tolerance-driven mode
      /// (0: off); the estimate solves the mesh at degree + 1
      double frequency_tolerance = 0.;
      /// CEA: the degree + 1 solve of the estimate: `projected`
      /// (Rayleigh-Ritz on the carried degree-p modes and three
      /// shift-and-invert steps, one factorisation per octave) or `full`
      /// (the full solver, 2-3x slower)
      std::string estimate_solver = "projected";
      /// CEA: check the estimate against degree + 2 on the final mesh
      bool check_estimate = false;
      /// CEA with a tolerance: after each h step, raise the degree on the
      /// same mesh instead where that is predicted to reduce the error
      /// faster per DoF (up to degree 3)
      bool degree_adaptivity = false;
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Isotropic linear elastic material, SI units. */
    struct Material
    {
      double youngs_modulus = 210e9; ///< Pa
      double poisson_ratio  = 0.3;   ///< -
      double density        = 7800.; ///< kg/m^3
    };

    /** Materials per body (thesis § 3.2.2) and the model-updating switch. */
    struct Materials
    {
      Material disc;                       ///< the disc (TriboBrake)
      Material pad{25e9, 0.3, 2500.};      ///< the pad (TriboBrake)
      Material support{210e9, 0.3, 7800.}; ///< the support (TriboBrake)
      /// `updated`: the calibrated support density; `steel`: 7800 kg/m^3.
      std::string support_density_model = "updated";
      double support_updated_density    = 76500.; ///< kg/m^3, calibrated value
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** The 4 x 11 tangential springs holding the support (thesis § 3.2.1).
     *
     * Each spring acts on a small disc of the support face around its
     * station (radius attachment_radius): a Winkler layer of stiffness
     * density k w(x) / int(w) [N/m^3] in the sliding direction, w the cosine
     * bell, so that the spring keeps its stiffness k. A force at one node of
     * a 3D body is singular (its local compliance grows without bound under
     * refinement), so the thesis' point springs have no converged answer;
     * the layer, integrated consistently (StructuralModel::lumped_springs),
     * is the same model on every mesh and degree.
     */
    struct Springs
    {
      unsigned int n_rows_per_side =
        2; ///< TriboBrake springs: rows on each side of the support
      unsigned int n_per_row = 11;      ///< TriboBrake springs: springs per row
      double       stiffness = 8.422e6; ///< N/m per spring
      /// m; 0: the node nearest to each station (point springs)
      double attachment_radius = 1.25e-3;
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * Damping of the structure: Rayleigh C = alpha M + beta K on the whole
     * structure, plus (CEA only) modal damping of the frictionless
     * assembly's modes (physics::MatrixParts::ModalDamping).
     */
    struct Damping
    {
      double alpha = 0.02; ///< 1/s
      double beta  = 1e-7; ///< s
      /// Modal damping ratios zeta(f) [-] at frequencies f [Hz]: ascending
      /// (f, zeta) pairs, linear between them and constant beyond the
      /// ends; empty: no modal damping.
      std::vector<std::pair<double, double>> modal_ratios;
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Linear friction coupling of the CEA (thesis eq. 3-1). */
    struct Interface
    {
      double normal_stiffness = 2.5895e12; ///< N/m^3 per unit area
      /// tangential (shear) stiffness per unit area [N/m^3] on the in-plane
      /// relative displacement; 0 (default) for none
      double      tangential_stiffness = 0.;
      double      friction_coefficient = 0.3;        ///< when not swept [-]
      std::string sliding_direction    = "rotation"; ///< `rotation` or "tx, ty"
      std::string rotation_sense =
        "counterclockwise"; ///< sense of the disc's rotation about its axis: counterclockwise | clockwise
      std::string quadrature = "mortar"; ///< `mortar` or `nodal`
      /// Unit sliding direction at the pad (z component 0), resolved from the
      /// above for a pad on the +x axis.
      dealii::Tensor<1, 3>
      sliding_tangent() const;
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** The eigensolvers and the frequency band. */
    struct Eigensolver
    {
      double      f_min              = 900.;      ///< Hz
      double      f_max              = 20000.;    ///< Hz
      std::string method             = "reduced"; ///< `full` or `reduced`
      double      tolerance          = 1e-10;     ///< SLEPc relative tolerance
      double      target_frequency   = 100.;      ///< Hz, real shift -2 pi f
      double      unstable_tolerance = 1e-3;      ///< 1/s on Re(lambda)
      /// and relative to |lambda|: unstable when Re(lambda) exceeds both
      double unstable_relative_tolerance = 1e-6;
      /// refine the reduced sweep's (nearly) unstable eigenvalues on the
      /// full model
      bool certify = true;
      /// 1/s: eigenvalues within this of the stability threshold are
      /// refined too
      double certification_margin = 1.;
      /// least MAC of a link between the modes of consecutive points
      double tracking_mac_threshold = 0.3;
      /// the symmetric eigensolver of the full solver and the reduced
      /// basis: `auto`, `slepc`, `arpack` or `block` (eigen::BandOptions)
      std::string symmetric_solver = "auto";
      /// the full solver's subspace products: `stored` or `recomputed`
      std::string subspace_products = "stored";
      /// Sample values per swept structural parameter for the reduced basis.
      unsigned int reduced_samples = 3;
      double reduced_band_factor   = 1.25; ///< see benchmarks/speed_vs_error
      bool   reduced_enrichment =
        true; ///< enrich the reduced basis at the sweep points
      unsigned int reduced_enrichment_depth = 1; ///< levels (K^-1 K_t)^l Phi
      /// the most points at which the reduced solver is checked against
      /// the full one (the most unstable point and the edges of every
      /// unstable region; 0: no check)
      unsigned int n_check_points = 100;
      /// largest relative residual of a full-solver eigenpair on the full
      /// damped model
      double residual_tolerance = 1e-10;
      /// largest |lambda_reduced - lambda_full| / |lambda_full| of a
      /// matched pair at a check point
      double check_tolerance = 1e-4;
      /// write results that failed a check into DIRECTORY.unverified
      /// instead of stopping the run
      bool allow_unverified = false;
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * The values of the named scalar parameters of a scene at one point
     * (scene::Scene::parameters(): `<body>.E`, `<pair>.mu`, `damping.alpha`,
     * ...), in the order they were added. The stiffness, mass and damping
     * matrices depend on them affinely (physics::MatrixParts), which is
     * what lets the reduced solver sweep any of them without re-assembly.
     */
    class ScalarPoint
    {
    public:
      /**
       * The value of the parameter called @p name, in its SI unit.
       * @throws std::runtime_error naming @p name and listing the names
       * the point has.
       */
      double
      get(const std::string &name) const;
      /** Sets the parameter called @p name. @throws as get(). */
      void
      set(const std::string &name, const double value);
      /**
       * Adds a parameter.
       * @throws std::runtime_error if the point has one called @p name.
       */
      void
      add(const std::string &name, const double value);
      /**
       * Adds @p name as a linked parameter: set() sets every one of
       * @p members (parameters of the point) to its value, get() returns
       * the first member's. A sweep over `contact.mu` moves the friction
       * coefficients of all contact pairs together this way.
       * @throws std::runtime_error if the point has a parameter called
       * @p name, or lacks a member.
       */
      void
      link(const std::string &name, const std::vector<std::string> &members);
      /** Whether the point has a parameter (or a link) called @p name. */
      bool
      has(const std::string &name) const;
      /** The names and values, in the order they were added. */
      const std::vector<std::pair<std::string, double>> &
      values() const
      {
        return named;
      }
      /** The names, separated by `|`, for error messages. */
      std::string
      names() const;

    private:
      std::vector<std::pair<std::string, double>> named;
      /// linked name -> the parameters it sets
      std::vector<std::pair<std::string, std::vector<std::string>>> links;
      const std::vector<std::string> *
      members(const std::string &name) const;
    };

    /** One axis of a sweep: which parameter and its values. */
    struct SweepAxis
    {
      std::string parameter;          ///< a name of the scene's parameters
                                      ///< (scene::Scene::parameters())
      std::string values_text;        ///< `log A B N`, `linear A B N` or a list
      bool        log_spaced = false; ///< values came from `log A B N`
      std::vector<double> values;     ///< parsed from values_text

      /**
       * Parses values_text. @throws std::runtime_error naming @p entry and
       * the allowed forms if it is malformed or a value is not finite (the
       * scene checks the range of its parameter: scene::sweep_points()).
       */
      void
      parse(const std::string &entry);

      /**
       * Whether the axis is best seen on a log scale: log-spaced, or all
       * values positive and spanning more than a factor of 10.
       */
      bool
      log_scale() const;
    };

    /**
     * A two-parameter sweep. Modes are tracked along the first parameter for
     * each value of the second, and unstable regions are intervals of the
     * first. Defaults (the TriboBrake's names): the pad's Young's modulus
     * `pad.E`, 41 log-spaced values 1-100 GPa, against the friction
     * coefficients of the thesis for the pair `pad on disc`.
     */
    struct Sweep
    {
      SweepAxis first{"pad.E",
                      "log 1e9 1e11 41",
                      true,
                      {}}; ///< the tracked axis
      /// one tracked sweep per value of this axis
      SweepAxis second{"pad on disc.mu",
                       "0.01, 0.1, 0.2, 0.3, 0.5, 0.7",
                       false,
                       {}};
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * How the sparse direct solver (MUMPS, for the preload's contact system,
     * the eigensolvers' shift-and-invert and inertia counts, the
     * certification) keeps its factors.
     */
    struct LinearSolver
    {
      /// `auto` (in memory unless the run's estimated peak exceeds the
      /// memory available, then on disk), `in core` or `out of core`
      /// (MUMPS ICNTL(22) = 1: the factors written to files, read back
      /// by each solve)
      std::string out_of_core = "auto";
      /// where the factors' files go out of core ("": MUMPS's own choice,
      /// the environment variable MUMPS_OOC_TMPDIR or else /tmp)
      std::string out_of_core_directory;
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter
       * when the directory does not exist. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Where results go. */
    struct Output
    {
      std::string directory = "output/run"; ///< the output folder (normalised,
                                            ///< never the working directory)
      bool        overwrite   = false; ///< replace an existing output folder
      std::string mode_output = "unstable and first"; ///< or `none`, `all`
      /// CEA sweep points whose matrices are exported (MatrixMarket)
      std::vector<unsigned int> export_points;
      /// CEA, full method: `none`, `unstable` (the unstable and nearly
      /// unstable modes: Re lambda within Eigensolver/Certification margin
      /// of the stability threshold) or `all` modes' d lambda / d p for
      /// every named parameter, in sensitivities.csv (eigen/sensitivity.h)
      std::string sensitivities = "none";
      /// CEA: decompose every unstable region's mode at its largest growth
      /// rate on the frictionless assembly's modes (modal_contributions.csv)
      bool modal_contributions = false;
      /// CEA: write the error indicator of the first point's modes
      /// (mesh_error.vtu, mesh_error.csv)
      bool error_indicator = true;
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * The static preload (Scene/Analysis = preload): the normal force on the
     * support's top presses the pad on the disc through mortar frictional
     * contact (contact/contact_solver.h).
     */
    struct Preload
    {
      double      normal_force = 100.;         ///< N, on the support's top
      std::string friction = "steady sliding"; ///< or `coulomb`, `frictionless`
      /// `penalty`: p = k_n x penetration with each contact pair's k_n
      /// [N/m^3], the law the CEA's interface linearises (thesis eq. 3-1);
      /// `hard`: no penetration (Lagrange multipliers), the preload alone
      std::string  normal_law      = "penalty";
      double       search_distance = 1e-3; ///< m, contact search reach
      unsigned int load_steps      = 1;    ///< increments of the load
      /// m: `coulomb` only, how far the disc turns under the pad (along
      /// Interface/Sliding direction) during each load step; 0: at rest
      double disc_slip = 0.;
      /// rebuild the mortar segmentation on the deformed surfaces after a
      /// load step once the relative tangential displacement since the
      /// last one exceeds this fraction of the shortest pad face edge
      double segmentation_refresh = 0.1;
      /// the contact state a `preloaded cea` is linearised about: `preload`
      /// (the static preload, run first) or `braking history` (each pad
      /// node's fraction of time in contact in a braking run's
      /// contact_history.h5, over contact_window; no preload is run)
      std::string contact_state = "preload";
      /// `braking history`: the braking run's contact_history.h5
      std::string contact_history;
      /// `braking history`: [start, end] of the samples used [s]; empty:
      /// every sample of the history
      std::vector<double> contact_window;
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * The transient braking simulation (Scene/Analysis = braking, thesis
     * § 2.3, 3.2.3): the disc turning at a constant angular velocity, the
     * normal force ramped on the support's top, frictional contact by
     * forward-increment Lagrange multipliers, explicit beta2 time scheme
     * (transient/explicit_dynamics.h).
     */
    struct Transient
    {
      double       angular_velocity  = 1.0471975511965976; ///< rad/s (10 rpm)
      double       normal_force      = 100.; ///< N, final value of the ramp
      double       ramp_duration     = 2e-3; ///< s, smooth (half-cosine) ramp
      double       end_time          = 0.02; ///< s
      double       time_step         = 0.;   ///< s; 0: safety factor x limit
      double       safety_factor     = 0.9;  ///< of the stable limit
      double       beta2             = 0.5;  ///< 0.5: central differences
      double       sampling_rate     = 1e6;  ///< Hz, tables and contact history
      double       history_start     = 0.;   ///< s, first sample of the history
      double       snapshot_interval = 1e-3; ///< s, transient.pvd / contact.pvd
      double       animation_start   = -1.;  ///< s; < 0: ends at end_time
      double       animation_period  = 2.9e-4; ///< s, length of the window
      unsigned int animation_frames  = 20;     ///< snapshots over one period
      double       spectrum_start = -1.; ///< s; < 0: the second half of the run
      double       contact_tolerance = 1e-10; ///< projected Gauss-Seidel
      unsigned int contact_iterations =
        2000; ///< projected Gauss-Seidel iterations per contact step, at most
      double initial_perturbation = 0.; ///< m/s, see help
      /// `matrix-free` (deal.II MatrixFree) or `sparse` (assembled matrix)
      std::string stiffness_product = "matrix-free";
      /// steps between checkpoints (squeal --resume); 0: none
      unsigned int checkpoint_interval = 20000;
      /// run one braking simulation per Sweep point (stability table)
      bool grid = false;
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * Model updating (Scene/Analysis = model updating,
     * updating/model_updating.h): the named scene parameters fitted to
     * measured natural frequencies (and shapes) of the frictionless
     * assembly.
     */
    struct ModelUpdating
    {
      /// `name: lower, upper[, linear]; ...`: the fitted named parameters
      /// with their bounds [their units]; log scale unless `linear`
      std::string parameters;
      /// CSV of the measured modes (absolute after AllParameters::read())
      std::string targets;
      /// CSV of the measurement points and directions ("": no shapes)
      std::string measurement_points;
      /// `name: parameter = value, ...; ...`: the model configurations the
      /// targets may name (values of parameters that are not fitted)
      std::string configurations;
      double      measurement_error = 0.01; ///< relative std of a frequency [-]
      double      damping_error = 0.2;  ///< relative std of a damping ratio [-]
      unsigned int max_iterations = 30; ///< Levenberg-Marquardt steps
      /// stop when a step lowers the cost by less than this fraction [-]
      double tolerance        = 1e-5;
      double mac_threshold    = 0.6; ///< least MAC of a pairing by shape
      double frequency_window = 0.5; ///< relative, pairing by frequency
      /// Hz, the highest model mode computed; 0: 1.5 x the highest target
      double maximum_frequency = 0.;
      /// `full`: every trial a full eigensolve; `reduced`: the trials on
      /// the span of the full solves' modes, a full solve confirming
      std::string method = "reduced";
      /// largest relative frequency gap of a paired mode between the
      /// reduced and the confirming full solve [-]
      double reduced_tolerance = 1e-4;
      /** Declares the subsection's entries: defaults, ranges, help (SI units).
       */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error naming the parameter when a value is not allowed. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** All parameters of a run. */
    struct AllParameters
    {
      Scene         scene;         ///< subsection Scene
      Geometry      geometry;      ///< subsection Geometry
      Mesh          mesh;          ///< subsection Mesh
      Materials     materials;     ///< subsection Materials
      Springs       springs;       ///< subsection Springs
      Damping       damping;       ///< subsection Damping
      Interface     interface;     ///< subsection Interface
      Eigensolver   eigensolver;   ///< subsection Eigensolver
      Sweep         sweep;         ///< subsection Sweep
      Preload       preload;       ///< subsection Preload
      Transient     transient;     ///< subsection Transient
      Output        output;        ///< subsection Output
      LinearSolver  linear_solver; ///< subsection Linear solver
      ModelUpdating updating;      ///< subsection Model updating

      /** Declares every subsection with defaults, ranges and help. */
      void
      declare_parameters(ParameterHandler &prm) const;
      /**
       * Reads every subsection and checks cross-parameter consistency.
       * @throws std::runtime_error naming the parameter when a value is
       * outside what is allowed (for example f_min >= f_max).
       */
      void
      parse_parameters(ParameterHandler &prm);

      /**
       * Parses @p filename into @p prm and this object.
       * @throws std::runtime_error naming the file, the line and the entry on
       * a malformed file, an unknown entry, or a value outside its range.
       */
      void
      read(ParameterHandler &prm, const std::string &filename);
    };

    /**
     * Parses the parameter file @p filename into @p prm, whose entries are
     * declared (INCLUDE directives allowed).
     * @throws std::runtime_error "cannot open parameter file 'F'", or "in
     * parameter file 'F': " and deal.II's message on one line (it names the
     * line and the entry) on a malformed line, an unknown entry or a value
     * outside its pattern.
     */
    void
    parse_file(ParameterHandler &prm, const std::string &filename);

    /**
     * Records @p file as an input of this process (parse_file() records
     * each parameter file and INCLUDE, AllParameters::read() the mesh file,
     * squeal-tribology its history and images): io::partial_directory()
     * refuses an output folder that contains one. Inputs are recorded
     * before any output starts (no locking).
     */
    void
    register_input(const std::string &file);

    /** The inputs register_input() recorded, as given. */
    const std::vector<std::string> &
    inputs();
  } // namespace parameters
} // namespace squeal

#endif
