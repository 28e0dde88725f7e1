#ifndef squeal_analyses_braking_h
#define squeal_analyses_braking_h

/**
 * @file
 * The transient braking simulation of a scene (Scene/Analysis = braking;
 * thesis § 2.3, 3.2.3, 3.4): the CEA's structure (physics::StructuralModel:
 * the scene's bodies, springs and holds) at the file's nominal parameters,
 * with a lumped mass; the disc turning at Transient/Angular velocity about
 * the contact pairs' common axis, treated as steady sliding in the disc's
 * fixed mesh (the disc is axisymmetric: the rotation enters only as the
 * sliding velocity omega a x (x - x_axis) of the master faces in the
 * friction law; transport terms of order omega / omega_mode, about 1e-4 at
 * 10 rpm, are neglected); the normal force of every load ramped; each
 * pair's slave face on its master face through dual mortar contact with
 * Coulomb friction by forward-increment Lagrange multipliers; the explicit
 * beta2 scheme (explicit_dynamics.h). The scene's point holds hold single
 * components (the TriboBrake's loading arm).
 *
 * Under MPI every rank holds the whole (parallel::shared) mesh and the
 * small interface; the bulk is split among the ranks (matrix-free product on
 * each rank's cells, distributed vectors) and the contact multipliers are
 * found redundantly, the same on every rank.
 */

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <squeal/contact/mortar.h>
#include <squeal/io/contact_history.h>
#include <squeal/physics/structural_model.h>
#include <squeal/transient/elasticity_operator.h>
#include <squeal/transient/explicit_dynamics.h>
#include <squeal/transient/signal.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace squeal
{
  namespace analyses
  {
    /** What a braking run found (after run()). */
    struct BrakingSummary
    {
      unsigned int n_dofs             = 0;  ///< of the structure
      double       time_step          = 0.; ///< s, of the run
      double       critical_time_step = 0.; ///< s, the stability limit
      /// wall time of one stiffness product, assembled matrix [s]
      double sparse_product = 0.;
      /// wall time of one stiffness product, matrix-free [s]
      double       matrix_free_product = 0.;
      unsigned int n_steps             = 0;  ///< time steps taken
      double       wall_time           = 0.; ///< s, the time loop
      /// projected Gauss-Seidel sweeps of the contact step: mean and most
      /// per time step (0 without contact)
      double               mean_contact_sweeps = 0.;
      unsigned int         max_contact_sweeps  = 0;
      double               dominant_frequency  = 0.; ///< Hz, probe acceleration
      transient::GrowthFit growth; ///< envelope of the probe velocity
      /// the probe velocity's amplitude at the dominant frequency alone
      /// (transient::fit_modal_growth(): one mode where several grow)
      transient::GrowthFit modal_growth;
      bool separated = false; ///< a pad node separated after the ramp
      /// leading-edge nodes, over the spectrum window: min pressure over
      /// the nominal mean pressure (normal force / slave face area)
      double leading_min_over_mean = 0.;
      /// the same, max pressure over the mean
      double leading_max_over_mean = 0.;
      /// unstable: limit cycle | still growing at End time | growing slowly
      /// (the fitted envelope at least doubled); stable: vibration decays |
      /// no growth
      std::string verdict;
    };

    /** The braking simulation (tutorial shape: setup_system,
     * assemble_load, solve, output_results, run). */
    class BrakingAnalysis
    {
    public:
      /** Keeps references to @p prm and @p handler (echoed into the output
       * folder). */
      BrakingAnalysis(
        const parameters::AllParameters                   &prm,
        const dealii::ParameterHandler                    &handler,
        MPI_Comm                                           comm,
        const std::vector<std::pair<std::string, double>> &point = {});

      /**
       * Runs the simulation; results in Output/Directory (written to
       * DIRECTORY.partial, renamed at the end): forces.csv, probes.csv,
       * spectrum.csv, summary.csv, contact_history.h5, transient.pvd,
       * contact.pvd, animation.pvd with their .vtu files, parameters.prm.
       * @throws std::runtime_error on Stiffness product = sparse under
       * mpirun with more than one rank, on an existing output folder without
       * Output/Overwrite, on a time step above the stability limit, on a mesh
       * with hanging nodes, or when the contact multipliers do not converge
       * (nothing is renamed then).
       */
      void
      run();

      /**
       * Continues a run that was stopped (killed, out of time) from the last
       * checkpoint in Output/Directory.partial/checkpoint (see
       * Transient/Checkpoint interval): the model is rebuilt from the
       * parameters, the integrator's state, the samples and the list of
       * snapshots are read back, and the time loop goes on from the step
       * after the checkpoint. The result equals an uninterrupted run's bit
       * for bit (same build, same thread count for the matrix-free product).
       * @throws std::runtime_error if there is no checkpoint, a checkpoint
       * file fails its CRC-32 check (damaged bytes), parameters.prm differs
       * from the one the run started with, or the checkpoint was written by
       * a different model (DoFs, pad-face nodes, time step), besides the
       * errors of run().
       */
      void
      resume();

      /** The result (after run()). */
      const BrakingSummary &
      summary() const
      {
        return result;
      }

    private:
      void
      setup_system();
      void
      prepare_work_dir();
      transient::StiffnessProduct
      make_stiffness_product(
        const std::shared_ptr<const dealii::Utilities::MPI::Partitioner>
          &layout);
      void
      setup_probe(const scene::ContactPair &pair, double pair_size);
      void
      assemble_load();
      void
      solve();
      void
      output_results();
      std::pair<transient::Spectrum, transient::Spectrum>
      evaluate_run(double t_spec);
      void
      write_tables(const transient::Spectrum &spectrum,
                   const transient::Spectrum &velocity_spectrum,
                   double                     t_spec) const;
      void
      print_verdict(const transient::Spectrum &spectrum) const;
      void
      record_sample();
      void
      write_snapshot(const std::string &series, unsigned int index);
      void
      write_checkpoint(unsigned int next_step, double wall);
      /// returns the step to continue from and the wall time spent so far
      std::pair<unsigned int, double>
      read_checkpoint();
      /// CRC-32 of work_dir/parameters.prm
      std::uint32_t
      parameters_checksum() const;
      /// read_checkpoint() on this rank alone
      std::pair<unsigned int, double>
      read_checkpoint_files();
      void
      run(bool resuming);

      const parameters::AllParameters &prm;
      const dealii::ParameterHandler  &handler;
      MPI_Comm                         comm;
      dealii::ConditionalOStream       pcout;
      dealii::TimerOutput              timer;
      std::string                      work_dir;

      physics::StructuralModel          model;
      dealii::AffineConstraints<double> constraints;
      dealii::SparsityPattern           pattern;
      dealii::SparseMatrix<double>      stiffness;
      dealii::Vector<double>            mass; ///< lumped [kg]
      /// the loads at full force [N], one vector per ramp time [s]
      std::vector<std::pair<double, dealii::Vector<double>>> loads;
      double            total_load = 0.; ///< the loads' total force [N]
      double            ramp_end   = 0.; ///< the longest ramp [s]
      std::vector<bool> fixed;
      std::vector<dealii::Point<3>> points;    ///< support point per DoF
      std::vector<unsigned int>     component; ///< 0, 1, 2 per DoF
      contact::MortarOperators      mortar;
      std::unique_ptr<transient::ElasticityOperator> matrix_free;
      std::unique_ptr<transient::ExplicitDynamics>   dynamics;

      dealii::Tensor<1, 3> sliding, radial; ///< map frame
      std::array<dealii::types::global_dof_index, 3> probe_dofs;
      dealii::Point<3>                               probe_point;
      std::vector<unsigned int>                      leading_nodes;
      io::ContactHistory                             history;
      /// per sample: t, F_N, F_T (sliding), F_T (radial), area, stick,
      /// slip, separated, probe u, v, a (3 each)
      std::vector<std::array<double, 17>>         samples;
      std::vector<std::pair<double, std::string>> snapshots, frames, faces;
      unsigned int                                n_snapshots = 0, n_frames = 0;
      /// samples and history samples already in the checkpoint files
      std::size_t saved_samples = 0, saved_history = 0;
      /// CRC-32 (zlib) of the checkpoint's samples.bin and history.bin up
      /// to saved_samples and saved_history, and of the parameters.prm the
      /// run started from
      std::uint32_t samples_crc = 0, history_crc = 0, parameters_crc = 0;
      /// step of the last checkpoint written or read (0: none)
      std::uint64_t  last_checkpoint = 0;
      bool           resuming        = false;
      BrakingSummary result;
    };

    /**
     * A small grid of braking simulations (Transient/Grid = true): one
     * BrakingAnalysis at every point of the Sweep subsection (the same two
     * parameters and values a CEA of the file would sweep), each written to
     * Output/Directory/point_NN, and one stability table,
     * Output/Directory/stability_table.csv: per point the two parameters,
     * the verdict, the dominant frequency [Hz], the growth rates of the
     * envelope and at the dominant frequency [1/s], the limit-cycle
     * amplitude [m/s], separation, the leading-edge pressure range over the
     * mean and the wall time [s]. A point that fails (e.g. contact
     * multipliers not converging) is recorded as `failed` with its message
     * and the grid goes on. Checkpoints are off in a grid.
     * @throws std::runtime_error on an existing output folder without
     * Output/Overwrite, or when every point failed.
     */
    void
    run_braking_grid(const parameters::AllParameters &prm,
                     const dealii::ParameterHandler  &handler,
                     MPI_Comm                         comm);
  } // namespace analyses
} // namespace squeal

#endif
