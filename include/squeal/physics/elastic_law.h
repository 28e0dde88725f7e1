#ifndef squeal_physics_elastic_law_h
#define squeal_physics_elastic_law_h

/**
 * @file
 * The cell stiffness of an anisotropic linear elastic law (its tensor from
 * scene/material_law.h): K_ij = int eps(phi_i) : C : eps(phi_j) dV.
 */

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>

#include <vector>

namespace squeal
{
  namespace physics
  {
    /**
     * Adds to @p cell_k the stiffness of the law @p C (global frame, Pa)
     * on the cell @p fe_values was last reinit'ed on (FE_Q^3; n x n, n its
     * DoFs per cell; N/m): K_ij = int eps(phi_i) : C : eps(phi_j) dV.
     */
    void
    add_cell_stiffness(const dealii::FEValues<3>           &fe_values,
                       const dealii::SymmetricTensor<4, 3> &C,
                       dealii::FullMatrix<double>          &cell_k);

    /**
     * The same with a law that varies over the cell (a cylindrical material
     * frame): @p C holds its tensor at each quadrature point of
     * @p fe_values (global frame, Pa), or one tensor for all.
     */
    void
    add_cell_stiffness(const dealii::FEValues<3> &fe_values,
                       const std::vector<dealii::SymmetricTensor<4, 3>> &C,
                       dealii::FullMatrix<double> &cell_k);
  } // namespace physics
} // namespace squeal

#endif
