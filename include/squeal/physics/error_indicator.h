#ifndef squeal_physics_error_indicator_h
#define squeal_physics_error_indicator_h

/**
 * @file
 * The traction-jump indicator of the discretisation error of displacement
 * fields (the modes of the CEA) on a mesh of several bonded materials.
 */

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <vector>

namespace squeal
{
  namespace physics
  {
    /**
     * The stiffness tensor C [Pa] (sigma = C : eps, global frame) of the
     * material of a cell (its material id) at a point [m].
     */
    using StiffnessOf =
      std::function<dealii::SymmetricTensor<4, 3>(dealii::types::material_id,
                                                  const dealii::Point<3> &)>;

    /**
     * The face-jump part of the residual error estimator of linear
     * elasticity (Verfuerth, A Posteriori Error Estimation Techniques for
     * Finite Element Methods, OUP 2013, Sec. 4.3: the jump of the normal
     * stress across interior faces), with Kelly's face scaling: for every
     * interior face F of @p dof_handler's active mesh,
     *   e_F = h / 24 int_F |sigma_1 n - sigma_2 n|^2 dA / E_F,
     * h the diameter of the finer of the two cells, sigma_i = C_i : eps_i
     * on side i (C_i of @p stiffness at the face's quadrature points, taken
     * once per face for all the solutions), n the normal, E_F the mean of
     * the two sides' @p modulus [Pa]; e_F is added to the squares of both
     * cells (an energy [J] per unit of the field's scale squared). Unlike
     * the jump of the gradient (Kelly), the traction is continuous across
     * a bonded interface between two materials in the exact solution, so
     * such interfaces are marked only where the mesh misses the field.
     * Faces at the boundary, including between bodies that share no
     * nodes, contribute nothing. Quadrature: Gauss with degree + 1 points
     * per direction.
     *
     * Parallel: over the locally owned cells of a triangulation held
     * whole on every rank (parallel::shared or serial; active cell
     * indices global); each face is integrated on exactly one rank, so
     * the squares of @p eta summed over the ranks are the indicator.
     *
     * @param solutions fields [m] with ghost entries for the locally
     * relevant DoFs and hanging-node constraints distributed (FE_Q^3)
     * @param eta one vector per solution, resized to the number of active
     * cells: the square root of the sum this rank added to each cell
     */
    void
    traction_jump_indicator(
      const dealii::Mapping<3>                                &mapping,
      const dealii::DoFHandler<3>                             &dof_handler,
      const StiffnessOf                                       &stiffness,
      const std::function<double(dealii::types::material_id)> &modulus,
      const std::vector<const dealii::PETScWrappers::MPI::Vector *> &solutions,
      std::vector<dealii::Vector<float>>                            &eta);
  } // namespace physics
} // namespace squeal

#endif
