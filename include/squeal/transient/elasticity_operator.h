#ifndef squeal_transient_elasticity_operator_h
#define squeal_transient_elasticity_operator_h

/**
 * @file
 * The stiffness product K u of isotropic linear elasticity without an
 * assembled matrix: deal.II's MatrixFree with sum factorisation, vectorised
 * over cell batches and multithreaded (Kronbichler & Kormann, Computers &
 * Fluids 63, 2012), plus a diagonal of discrete springs. The explicit
 * integrator needs one such product per time step; see
 * benchmarks/transient/README.md for its speed against the sparse matrix.
 */

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <functional>
#include <memory>
#include <utility>

namespace squeal
{
  namespace transient
  {
    /** K u = (elasticity + springs) u, matrix-free, for FE_Q^3 of degree 1-3.
     */
    class ElasticityOperator
    {
    public:
      /**
       * Over the locally owned cells of @p dof_handler (any triangulation,
       * serial or parallel::shared / distributed), with MPI vectors.
       * @param constraints homogeneous Dirichlet constraints only (at least
       * for the locally relevant DoFs); the product is zero in constrained
       * rows
       * @param lame (lambda, mu) [Pa] of a cell's material id
       * @param spring_diagonal n_dofs entries [N/m] added to the diagonal
       * (discrete springs to the ground; only the locally owned entries are
       * read); may be empty
       * @throws std::runtime_error for a degree outside 1-3
       */
      ElasticityOperator(const dealii::DoFHandler<3>             &dof_handler,
                         const dealii::Mapping<3>                &mapping,
                         const dealii::AffineConstraints<double> &constraints,
                         const std::function<std::pair<double, double>(
                           dealii::types::material_id)>          &lame,
                         const dealii::Vector<double> &spring_diagonal);

      using VectorType = dealii::LinearAlgebra::distributed::Vector<double>;

      /** dst = K src [N] from src [m]: vectors of any layout with this
       * rank's locally owned DoFs (their ghosts are not touched);
       * collective under MPI. */
      void
      vmult(VectorType &dst, const VectorType &src) const;

    private:
      template <int degree>
      void
      apply(VectorType &dst, const VectorType &src) const;

      dealii::MatrixFree<3, double> data;
      std::vector<std::pair<dealii::VectorizedArray<double>,
                            dealii::VectorizedArray<double>>>
                             cell_lame; ///< per cell batch: lambda, mu
      dealii::Vector<double> springs;
      unsigned int           degree;
      /// the MatrixFree layout's vectors the product works on
      mutable VectorType in, out;
    };
  } // namespace transient
} // namespace squeal

#endif
