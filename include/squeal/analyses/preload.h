#ifndef squeal_analyses_preload_h
#define squeal_analyses_preload_h

/**
 * @file
 * The static preload (Scene/Analysis = preload): every load of the scene
 * presses its body; each contact pair's slave face and master face are
 * coupled by mortar frictional contact (contact/mortar.h,
 * contact/contact_solver.h) with the friction of Preload/Friction and
 * Interface/Friction coefficient along the pairs' common sliding direction.
 * The structure is the CEA's (physics::StructuralModel: bodies, springs,
 * holds) at the nominal parameters of the file; the scene's point holds hold
 * single components (the TriboBrake's loading arm).
 *
 * MUMPS's LU solves the augmented contact system: serially on the one
 * process, under mpirun with the structure's rows distributed.
 */

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <squeal/contact/contact_solver.h>
#include <squeal/contact/mortar.h>
#include <squeal/contact/scene_contact.h>
#include <squeal/physics/structural_model.h>

#include <string>
#include <utility>
#include <vector>

namespace squeal
{
  namespace analyses
  {
    /** The preload analysis (tutorial shape: setup_system, assemble_load,
     * solve, output_results, run). */
    class PreloadAnalysis
    {
    public:
      /** Keeps references to @p prm and @p handler (echoed into the output
       * folder). */
      PreloadAnalysis(const parameters::AllParameters &prm,
                      const dealii::ParameterHandler  &handler,
                      MPI_Comm                         comm);

      /**
       * Runs the preload; results in Output/Directory (written to
       * DIRECTORY.partial, renamed at the end): contact.csv (per pad node:
       * x, y, z [m], p_N, t_T1 (along the sliding direction), t_T2 [Pa] as
       * nodal fields (contact::MortarOperators::nodal_pressure), gap [m],
       * status 0 separated / 1 stick / 2 slip) of the final state and
       * contact_step_NNN.csv of every load step, preload_summary.txt,
       * contact.pvd (the pad face with its contact fields at every load
       * step, time = load factor) + contact_surface*.vtu, displacement.vtu.
       * Under mpirun the structure's rows are distributed and the
       * augmented contact system is solved by MUMPS; the contact state is
       * the same on every rank.
       * @throws std::runtime_error on an existing output folder without Output/Overwrite, or when the
       * contact solve fails (nothing is renamed then).
       */
      void
      run();

      /** The converged contact state (after run()). */
      const contact::ContactSolution &
      solution() const
      {
        return state;
      }
      /** The mortar operators of the pad-disc interface (after run()). */
      const contact::MortarOperators &
      interface() const
      {
        return mortar;
      }
      /** Force the support's springs take along the sliding direction [N]
       * (after run()), from the spring matrix alone: in equilibrium it
       * balances the friction force. */
      double
      spring_force() const
      {
        return spring_reaction;
      }

    private:
      void
      setup_system();
      void
      assemble_load();
      void
      solve();
      void
      output_results() const;
      /** The largest -g_j / D_jj over the nodes in contact [m]: the
       *  penetration of the penalty law (0 to rounding for the hard one). */
      double
      largest_penetration() const;
      /** displacement.vtu, written by all ranks together. */
      void
      write_displacement() const;
      /** Writes the current state's contact table and pad-face fields. */
      void
      write_contact(const std::string &csv_name,
                    const std::string &vtu_name) const;

      const parameters::AllParameters &prm;
      const dealii::ParameterHandler  &handler;
      MPI_Comm                         comm;
      dealii::ConditionalOStream       pcout;
      mutable dealii::TimerOutput      timer;
      std::string                      work_dir;

      physics::StructuralModel          model;
      dealii::AffineConstraints<double> constraints; ///< model's + radial hold
      dealii::SparsityPattern           pattern;
      dealii::SparseMatrix<double>      stiffness; ///< K_s at the nominal point
      physics::PETScMatrix     stiffness_mpi;      ///< the same, under mpirun
      dealii::Vector<double>   load;               ///< N
      contact::MortarOperators mortar;
      contact::ContactSolution state;
      double                   spring_reaction = 0.;
      /// (load factor, pad-face file) of every load step, for contact.pvd
      std::vector<std::pair<double, std::string>> steps;
    };
  } // namespace analyses
} // namespace squeal

#endif
