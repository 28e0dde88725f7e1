#ifndef squeal_contact_preload_h
#define squeal_contact_preload_h

/**
 * @file
 * The static preload of the TriboBrake (Scene/Analysis = preload): the
 * normal force on the support's top presses the pad on the disc; the pad
 * face (slave) and the disc face (master) are coupled by mortar frictional
 * contact (mortar.h, contact_solver.h) with the friction of Preload/Friction
 * and Interface/Friction coefficient along the disc's sliding direction. The
 * structure is the CEA's (physics::StructuralModel: disc, pad, support,
 * springs, clamped disc) at the nominal parameters of the file.
 *
 * The support is free along the radius in the thesis' model (its springs act
 * along the sliding direction only): a sliding contact does not hold it
 * there, so the radial displacement of the centre of the support's top is
 * held (the loading arm of the rig).
 *
 * Serial: the contact solve is a direct solve of the whole augmented system.
 */

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <squeal/contact/contact_solver.h>
#include <squeal/contact/mortar.h>
#include <squeal/physics/structural_model.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace squeal
{
  namespace contact
  {
    /**
     * The one contact pair of the model's scene.
     * @throws std::runtime_error if the scene has none or several (the
     * contact refinement of the preloaded CEA handles one).
     */
    const scene::ContactPair &
    single_pair(const scene::Scene &scene);

    /**
     * The sliding direction shared by all the scene's contact pairs (unit).
     * @throws std::runtime_error if the scene has no pair, or two pairs
     * slide along directions more than 1e-9 apart.
     */
    dealii::Tensor<1, 3>
    common_sliding(const scene::Scene &scene);

    /** The boundary ids of the slave faces of all the scene's pairs. */
    std::set<dealii::types::boundary_id>
    slave_ids(const scene::Scene &scene);

    /**
     * The dual mortar operators of all the scene's contact pairs, merged
     * (merge_mortar_operators(); one pair: build_mortar_operators() itself),
     * each pair's slave nodes and areas reported on @p pcout.
     * @param model its scene's pairs, DoFs and mapping
     * @param search_distance contact search reach [m]
     * @param pcout where the report goes
     * @throws std::runtime_error as build_mortar_operators().
     */
    MortarOperators
    scene_mortar(const physics::StructuralModel &model,
                 double                          search_distance,
                 dealii::ConditionalOStream     &pcout);

    /**
     * The scene's structural stiffness K_s at the file's nominal point
     * (bodies and springs; no linear interface) as a serial matrix [N/m] on
     * a new @p pattern, and its constraints: the model's (the scene's holds,
     * hanging nodes) plus, for each of the scene's point holds, its
     * component at the nearest node held at zero (the TriboBrake's loading
     * arm: a sliding contact does not hold the support along the radius).
     * @return the last held DoF and its position [m] (invalid index and the
     * origin without point holds)
     */
    std::pair<dealii::types::global_dof_index, dealii::Point<3>>
    contact_system(const physics::StructuralModel    &model,
                              dealii::SparsityPattern           &pattern,
                              dealii::SparseMatrix<double>      &stiffness,
                              dealii::AffineConstraints<double> &constraints);

    /**
     * The same system distributed over @p comm: @p stiffness the PETSc
     * matrix of K_s (each rank its own rows; the held DoFs' rows reduced to
     * their diagonals), @p constraints on all DoFs and identical on every
     * rank (hanging nodes, the holds, the point holds), built from the
     * whole parallel::shared mesh. Collective.
     * @return the held DoF's position [m]
     */
    dealii::Point<3>
    contact_system(const physics::StructuralModel    &model,
                              physics::PETScMatrix              &stiffness,
                              dealii::AffineConstraints<double> &constraints,
                              MPI_Comm                           comm);

    /**
     * The load vector [N]: for each of the scene's loads, @p force [N]
     * spread uniformly over its faces along its direction (the TriboBrake:
     * the support's top, pushing the pad towards the disc, -z; two pads of
     * a caliper: each pressed by @p force), with @p constraints.
     * @throws std::runtime_error if the scene has no load or a load's face
     * set is empty.
     */
    dealii::Vector<double>
    scene_load(const physics::StructuralModel          &model,
                     const dealii::AffineConstraints<double> &constraints,
                     double                                   force);

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
       * nodal fields (MortarOperators::nodal_pressure), gap [m], status 0
       * separated / 1 stick / 2 slip) of the final state and
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
      const ContactSolution &
      solution() const
      {
        return state;
      }
      /** The mortar operators of the pad-disc interface (after run()). */
      const MortarOperators &
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
      void setup_system();
      void assemble_load();
      void solve();
      void output_results() const;
      /** displacement.vtu, written by all ranks together. */
      void write_displacement() const;
      /** Writes the current state's contact table and pad-face fields. */
      void write_contact(const std::string &csv_name,
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
      physics::PETScMatrix              stiffness_mpi; ///< the same, under mpirun
      dealii::Vector<double>            load;      ///< N
      MortarOperators                   mortar;
      ContactSolution                   state;
      double                            spring_reaction = 0.;
      /// (load factor, pad-face file) of every load step, for contact.pvd
      std::vector<std::pair<double, std::string>> steps;
    };
  } // namespace contact
} // namespace squeal

#endif
