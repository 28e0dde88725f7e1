#ifndef squeal_analyses_cea_h
#define squeal_analyses_cea_h

/**
 * @file
 * The complex eigenvalue analysis (CEA) of a scene over a sweep of pad
 * modulus and friction coefficient: the eigenvalues of
 * (lambda^2 M + lambda C + K + K_f(mu)) phi = 0 (thesis eq. 1-40 ff.), modes
 * tracked across the sweep, unstable regions (Re lambda > tolerance) and the
 * modes that lock in. Writes, into Output/Directory: eigenvalues.csv,
 * unstable_regions.csv, check_full.csv (reduced against full), modes.pvd with
 * the mode shapes, sensitivities.csv (d lambda / d p, full method, when
 * asked), parameters.prm (the resolved parameters).
 */

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/reduced_model.h>
#include <squeal/eigen/sensitivity.h>
#include <squeal/eigen/tracking.h>
#include <squeal/physics/structural_model.h>

#include <complex>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace squeal
{
  namespace analyses
  {
    /** One eigenvalue of one sweep point, as written to eigenvalues.csv. */
    struct ModeRecord
    {
      unsigned int            point;  ///< sweep point index
      parameters::ScalarPoint values; ///< the sweep point's parameters
      unsigned int            mode;   ///< index within the point, by frequency
      std::complex<double>    lambda; ///< 1/s
      double                  residual; ///< relative, on the full model
      bool                    unstable; ///< Re lambda above the tolerance
      int                     track;    ///< mode track over the sweep
      bool refined; ///< certified on the full model (reduced method)
    };

    /** The analysis; run() does everything. */
    class ComplexEigenvalueAnalysis
    {
    public:
      /**
       * @param prm the parsed parameters; @param handler the handler they
       * were parsed from (echoed into the output directory); @param comm
       * the ranks that share the run.
       */
      ComplexEigenvalueAnalysis(const parameters::AllParameters &prm,
                                const dealii::ParameterHandler  &handler,
                                MPI_Comm                         comm);

      /**
       * Builds the model, solves every sweep point, tracks the modes,
       * classifies stability and writes the outputs.
       * @throws std::runtime_error if the output directory exists and
       * overwriting was not asked for, or if a solver fails.
       */
      void
      run();

      /** Every eigenvalue of the sweep (after run()). */
      const std::vector<ModeRecord> &
      records() const
      {
        return modes;
      }
      /** The unstable regions of the sweep (after run()). */
      const std::vector<eigen::UnstableRegion> &
      unstable_regions() const
      {
        return regions;
      }

    private:
      void
      setup_system();
      void
      solve_sweep();
      void
      check_against_full();
      /// Eigensolver/Certify stability map: refines every reduced
      /// eigenvalue within the margin of the stability threshold on the
      /// full model (eigen::PairRefiner); failures go to unverified
      void
      certify();
      void
      classify();
      void
      output_results() const;
      /// sensitivities.csv (rank 0): Output/Sensitivities
      void
      write_sensitivities() const;
      /// The name of the mode re + i im at the point @p values: (s,n+-)
      /// when the disc carries most of its kinetic energy, else the body
      /// carrying most besides the disc; with @p shares, each body's share
      /// of the kinetic energy (scene order). Collective.
      std::string
      describe_mode(const parameters::ScalarPoint &values,
                    const physics::PETScVector    &re,
                    const physics::PETScVector    &im,
                    std::vector<double>           *shares = nullptr) const;
      /// Output/Modal contributions: every unstable region's mode at its
      /// largest growth rate on the frictionless assembly's modes
      /// (eigen/modal_contribution.h), into contribution_rows and the log
      void
      decompose_unstable_modes();
      /// Whether @p lambda [1/s] lies above the stability threshold minus
      /// Eigensolver/Certification margin (unstable or nearly so).
      bool
      near_unstable(const std::complex<double> lambda) const;
      /// writes each mode @p x[j] (re + i im) as modes/NAMES[j]_0.pvtu
      /// (+ one .vtu piece per rank) from one set of patches for all of
      /// them (the mapping evaluated once per cell); returns the .pvtu
      /// names relative to modes/. Throws std::logic_error if @p x and
      /// @p names differ in length.
      std::vector<std::string>
      write_modes(const std::vector<eigen::EigenPair> &x,
                  const std::vector<std::string>      &names) const;
      /// the error indicator (Mesh/Error indicator) on the first point's
      /// modes: mesh_error.vtu and the share of each body, printed
      void
      write_error_indicator() const;
      /// the error indicator (Mesh/Error indicator: Kelly's or
      /// physics::traction_jump_indicator()) of @p pairs (modes of the
      /// point @p values, each
      /// scaled to unit kinetic norm with that point's whole mass M(p)),
      /// squared and summed per active cell; with @p weights (one per pair)
      /// each mode's squared field is scaled to a sum of weight^2 over the
      /// mesh
      dealii::Vector<double>
      mode_indicator(const std::vector<eigen::EigenPair> &pairs,
                     const parameters::ScalarPoint       &values,
                     const std::vector<double>           &weights = {}) const;
      /**
       * Scene/Analysis = preloaded cea: sets the model's interface mask
       * from the contact state (Preload/Contact state: the static preload,
       * run here into preload/, or a braking run's contact history) and
       * the pad nodes' contact pressure into @p pressure (points [m],
       * pressures [Pa]: the preload's, or the history's mean over its
       * window). Returns the check to call after the model's assembly
       * (empty for the preload).
       * @throws std::runtime_error if the preload fails, or the history
       *   cannot be read, has fewer than two nodes or no sample in its
       *   window; the returned check throws if the history's nodes do not
       *   cover the scene's pad faces.
       */
      std::function<void()>
      set_contact_state(
        std::vector<std::pair<dealii::Point<3>, double>> &pressure);
      /// Mesh/Contact refinements: refine where the preload's contact
      /// pressure @p preload_pressure (points [m], pressures [Pa]) varies
      /// most; contact_refinement.csv
      void
      refine_at_contact(const std::vector<std::pair<dealii::Point<3>, double>>
                          &preload_pressure);
      /// Mesh/Degree adaptivity: whether degree + 1 on the same mesh is
      /// predicted to reduce the largest estimate faster per DoF than the
      /// last h step (@p dofs_before DoFs and estimate @p estimate_before
      /// before it, @p worst now, @p rich_dofs DoFs at degree + 1); if so
      /// the model is rebuilt at degree + 1 (raised_prm) and true returned
      bool
      raise_degree(dealii::types::global_dof_index dofs_before,
                   double                          estimate_before,
                   double                          worst,
                   dealii::types::global_dof_index rich_dofs,
                   dealii::ConditionalOStream     &quiet);
      /// one h-refinement by the error indicator on the modes @p pairs
      /// flagged in @p above (all if empty), scaled to @p weights if given
      void
      refine_by_modes(const std::vector<eigen::EigenPair> &pairs,
                      const std::vector<bool>             &above,
                      const std::vector<double>           &weights,
                      const parameters::ScalarPoint       &p0,
                      dealii::ConditionalOStream          &quiet);
      /// Mesh/Adaptive cycles and Mesh/Frequency tolerance: refine before
      /// the sweep; adaptive_cycles.csv, adaptive_modes.csv
      void
      adapt_mesh();

      const parameters::AllParameters &prm;
      const dealii::ParameterHandler  &handler;
      MPI_Comm                         comm;
      dealii::ConditionalOStream       pcout;
      mutable dealii::TimerOutput      timer;
      std::string                      work_dir; ///< written, then renamed

      /// The model of the sweep: built at Mesh/Finite element degree,
      /// rebuilt at a higher degree on the same mesh when Mesh/Degree
      /// adaptivity raises it (then from *raised_prm).
      std::unique_ptr<physics::StructuralModel> model;
      /// The parameters of a model whose degree was raised (else null).
      std::unique_ptr<parameters::AllParameters> raised_prm;
      /// The full solve of the sweep's first point on the final mesh of
      /// adapt_mesh() (its last cycle), reused as that point by the full
      /// sweep and by the check against the full solver instead of solving
      /// it again (same model, same point, same band); empty without
      /// adaptive cycles or a frequency tolerance.
      std::vector<eigen::EigenPair> first_point_full;
      /// The modes of (K_s, M) of that full solve, which the reduced
      /// basis' sample with the same M and K_s takes (empty with
      /// first_point_full).
      eigen::KnownSymmetricModes first_point_symmetric;
      eigen::ReducedModel        reduced;

      /// The reduced basis' sample points: the ends of each swept
      /// structural parameter's range and evenly spaced values between.
      std::vector<parameters::ScalarPoint>
      basis_samples() const;
      /// The named parameters the sweep varies (the model's parts let them).
      std::set<std::string>
      varied_parameters() const;
      /// Every sweep point (scene::sweep_points(); the scene must exist).
      std::vector<parameters::ScalarPoint>
      sweep_points() const;
      /// "pad.E = 1e10, pad on disc.mu = 0.2" for a point, the swept ones
      /// only.
      std::string
      describe(const parameters::ScalarPoint &p) const;

      struct Point
      {
        parameters::ScalarPoint           values;
        std::vector<std::complex<double>> lambda;
        std::vector<double>               residual;
        std::vector<bool>             refined; ///< certified on the full model
        std::vector<Eigen::VectorXcd> q;       ///< reduced coordinates
        std::vector<eigen::EigenPair> full;    ///< full-solver pairs
        /// the full solver's counts and residuals (full method only)
        eigen::FullSolveReport report;
        /// d lambda / d p of each full pair for every named parameter of
        /// the scene (Output/Sensitivities, full method only)
        std::vector<eigen::EigenvalueSensitivity> sensitivity;
      };
      std::vector<Point>                 points;
      std::vector<ModeRecord>            modes;
      std::vector<eigen::UnstableRegion> regions;
      std::vector<std::string>           check_rows;
      /// modal_contributions.csv rows (rank 0)
      std::vector<std::string> contribution_rows;
      /// Failed residuals and checks: the run stops with them, or writes
      /// DIRECTORY.unverified (Eigensolver/Allow unverified results).
      std::vector<std::string> unverified;

      /// The band, tolerances and first guess of the eigensolvers.
      eigen::BandOptions
      band_options(const unsigned int initial_nev = 40) const;
      /// Adds a failure for every pair of @p pairs at sweep point @p p
      /// whose residual exceeds Eigensolver/Residual tolerance.
      void
      check_residuals(const unsigned int                   p,
                      const std::vector<eigen::EigenPair> &pairs);
      /// The folder the results are published to: Output/Directory, or
      /// with `.unverified` appended when a check failed.
      std::string
      output_target() const;
    };
  } // namespace analyses
} // namespace squeal

#endif
