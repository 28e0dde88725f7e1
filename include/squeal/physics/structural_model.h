#ifndef squeal_physics_structural_model_h
#define squeal_physics_structural_model_h

/**
 * @file
 * The linear structural model of a scene: mesh, FE space, constraints and
 * the matrices of the equations of motion M u'' + C u' + K u = 0, assembled
 * once and stored in parts so that a sweep only recombines them:
 *   K(E_pad, mu) = K_rest + (E_pad / E_ref) K_pad + K_n + mu K_t,
 *   C(E_pad)     = alpha M + beta (K_rest + (E_pad / E_ref) K_pad).
 * Matrices are PETSc MPI matrices on a parallel::shared::Triangulation, so
 * the same code runs serially and under mpirun.
 */

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <squeal/parameters/parameters.h>

#include <memory>

namespace squeal
{
  namespace physics
  {
    using PETScMatrix = dealii::PETScWrappers::MPI::SparseMatrix;
    using PETScVector = dealii::PETScWrappers::MPI::Vector;

    /**
     * The matrix parts of a linear model (n x n each; M in kg, the K parts
     * in N/m) and their combinations
     *   K(E_pad, mu) = K_rest + (E_pad / E_ref) K_pad + K_n + mu K_t,
     *   C(E_pad)     = alpha M + beta (K_rest + (E_pad / E_ref) K_pad).
     * All parts must share one sparsity pattern. Non-owning.
     */
    struct MatrixParts
    {
      const PETScMatrix *mass;
      const PETScMatrix *rest;
      const PETScMatrix *pad;
      const PETScMatrix *normal;
      const PETScMatrix *friction;
      double             E_ref; ///< Pa

      /** K(E_pad, mu) into @p K (re-initialised). E_pad in Pa. */
      void
      stiffness(const double E_pad, const double mu, PETScMatrix &K) const;
      /** K_rest + (E_pad/E_ref) K_pad + K_n (no friction; symmetric). */
      void
      symmetric_stiffness(const double E_pad, PETScMatrix &K) const;
      /** C(E_pad) with alpha [1/s], beta [s]. */
      void
      damping(const double E_pad,
              const double alpha,
              const double beta,
              PETScMatrix &C) const;
    };

    /**
     * Mesh, DoFs and assembled matrix parts of one scene. Sizes: every
     * matrix is n x n with n = dof_handler.n_dofs() (3 displacement
     * components per node, m). Units: M in kg, K parts in N/m.
     */
    class StructuralModel
    {
    public:
      /** Stores the parameters; nothing is built yet. */
      StructuralModel(const parameters::AllParameters &prm, MPI_Comm comm);

      /**
       * Builds the mesh, the DoFs, the constraints (clamped inner face,
       * hanging nodes) and the common sparsity pattern of all matrix parts,
       * then assembles M, K_rest (with the springs), K_pad and the interface
       * parts K_n, K_t. Constrained rows get K_ii = d (the mean diagonal of
       * K) and M_ii = d / (2 pi 1e3 f_max)^2, which puts their spurious
       * eigenvalues a thousand times above the band (deal.II step-36).
       */
      void
      setup_and_assemble(dealii::ConditionalOStream &pcout);

      /** The assembled parts, for the eigensolvers. */
      MatrixParts
      parts() const
      {
        return {&mass, &stiffness_rest, &stiffness_pad, &interface_normal,
                &interface_friction, E_ref};
      }

      /** Number of degrees of freedom. */
      dealii::types::global_dof_index
      n_dofs() const
      {
        return dof_handler.n_dofs();
      }

      const parameters::AllParameters &prm;
      MPI_Comm                         comm;

      dealii::parallel::shared::Triangulation<3> triangulation;
      const dealii::FESystem<3>                  fe;
      const dealii::MappingQ<3>                  mapping;
      dealii::DoFHandler<3>                      dof_handler;
      dealii::AffineConstraints<double>          constraints;
      dealii::IndexSet                           locally_owned_dofs;
      dealii::IndexSet                           locally_relevant_dofs;

      PETScMatrix mass;               ///< M [kg]
      PETScMatrix stiffness_rest;     ///< disc, support, springs [N/m]
      PETScMatrix stiffness_pad;      ///< pad at E_ref [N/m]
      PETScMatrix interface_normal;   ///< K_n [N/m]
      PETScMatrix interface_friction; ///< K_t per unit mu [N/m]

      double E_ref = 1.;              ///< pad modulus of stiffness_pad [Pa]
      double constrained_diagonal = 1.; ///< d above [N/m]

    private:
      void
      assemble_elasticity();
      void
      add_springs(dealii::ConditionalOStream &pcout);
    };

    /**
     * Sets the diagonal entry of every locally owned constrained row of
     * @p matrix to @p value (rows and columns are otherwise zero).
     */
    void
    set_constrained_diagonal(const dealii::AffineConstraints<double> &constraints,
                             const dealii::IndexSet &locally_owned,
                             const double            value,
                             PETScMatrix &           matrix);
  } // namespace physics
} // namespace squeal

#endif
