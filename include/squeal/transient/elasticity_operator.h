#ifndef squeal_transient_elasticity_operator_h
#define squeal_transient_elasticity_operator_h

/**
 * @file
 * The stiffness product K u of linear elasticity without an assembled
 * matrix: deal.II's MatrixFree with sum factorisation, vectorised over cell
 * batches and multithreaded (Kronbichler & Kormann, Computers & Fluids 63,
 * 2012), for isotropic bodies (Lame constants per cell) and anisotropic ones
 * (a stiffness tensor per quadrature point), plus the few entries of the
 * discrete springs (to the ground or between two bodies). The explicit
 * integrator needs one such product per time step; see
 * benchmarks/transient/README.md for its speed against the sparse matrix.
 */

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace squeal
{
  namespace transient
  {
    /** K u = (elasticity + springs) u, matrix-free, for FE_Q^3 of degree 1-3.
     */
    class ElasticityOperator
    {
    public:
      /// one entry k [N/m] of the springs' matrix: row, column (global DoFs)
      struct SpringEntry
      {
        dealii::types::global_dof_index row, column;
        double                          k;
      };
      /// the stiffness tensor [Pa] of an anisotropic material id at a point
      /// [m] in the global frame, or nothing for an isotropic one
      using TensorOf = std::function<
        std::optional<dealii::SymmetricTensor<4, 3>>(dealii::types::material_id,
                                                     const dealii::Point<3> &)>;

      /**
       * Over the locally owned cells of @p dof_handler (any triangulation,
       * serial or parallel::shared / distributed), with MPI vectors.
       * Quadrature: Gauss with degree + 1 points per direction, as the
       * assembled stiffness matrix.
       * @param constraints homogeneous Dirichlet constraints only (at least
       * for the locally relevant DoFs); the product is zero in constrained
       * rows
       * @param lame (lambda, mu) [Pa] of an isotropic cell's material id
       * @param springs the nonzero entries of the springs' matrix in this
       * rank's locally owned rows (diagonal entries ground a DoF, pairs of
       * off-diagonal entries join two DoFs, which may be owned by other
       * ranks); rows of constrained DoFs are skipped
       * @param tensor the stiffness tensor of the anisotropic bodies, by
       * material id and point; empty or returning nothing: every body
       * isotropic. Cells of an anisotropic body store C at every
       * quadrature point (36 numbers each).
       * @throws std::runtime_error for a degree outside 1-3
       */
      ElasticityOperator(const dealii::DoFHandler<3>             &dof_handler,
                         const dealii::Mapping<3>                &mapping,
                         const dealii::AffineConstraints<double> &constraints,
                         const std::function<std::pair<double, double>(
                           dealii::types::material_id)>          &lame,
                         const std::vector<SpringEntry>          &springs,
                         const TensorOf                          &tensor = {});

      using VectorType = dealii::LinearAlgebra::distributed::Vector<double>;

      /** dst = K src [N] from src [m]: vectors of any layout with this
       * rank's locally owned DoFs (their ghosts are not touched);
       * collective under MPI. */
      void
      vmult(VectorType &dst, const VectorType &src) const;

      /** The product's own input vector: this rank's owned entries [m],
       * in the order of its owned DoFs (n_locally_owned values). */
      double *
      input_buffer() const
      {
        return in.begin();
      }
      /** output_buffer() = K input_buffer() (vmult without its copies);
       * collective under MPI. */
      void
      apply_buffers() const;
      /** The product's own output vector: this rank's owned entries [N]
       * after apply_buffers(). */
      const double *
      output_buffer() const
      {
        return out.begin();
      }

    private:
      template <int degree>
      void
      apply(VectorType &dst, const VectorType &src) const;

      dealii::MatrixFree<3, double> data;
      std::vector<std::pair<dealii::VectorizedArray<double>,
                            dealii::VectorizedArray<double>>>
        cell_lame; ///< per cell batch: lambda, mu
      /// per cell batch: empty (isotropic cells only) or C at each
      /// quadrature point (isotropic lanes hold their isotropic tensor)
      std::vector<std::vector<
        dealii::SymmetricTensor<4, 3, dealii::VectorizedArray<double>>>>
        cell_tensor;
      /// this rank's spring entries: row as a local index of the product's
      /// vectors, column as an index into spring_values, k [N/m]
      struct LocalSpring
      {
        unsigned int row, column;
        double       k;
      };
      std::vector<LocalSpring> springs;
      /// per column of the springs on any rank (sorted by global index):
      /// its local index in the product's vectors if this rank owns it,
      /// else numbers::invalid_unsigned_int; each product sums the values
      /// over the ranks (each column is owned by one)
      std::vector<unsigned int> spring_column_local;
      /// scratch: the values at the springs' columns
      mutable std::vector<double> spring_values;
      unsigned int                degree;
      /// the MatrixFree layout's vectors the product works on
      mutable VectorType in, out;
    };
  } // namespace transient
} // namespace squeal

#endif
