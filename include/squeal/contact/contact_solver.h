#ifndef squeal_contact_contact_solver_h
#define squeal_contact_contact_solver_h

/**
 * @file
 * Static unilateral contact of linear elastic bodies on dual mortar
 * operators, by the primal-dual active-set method (Hintermueller, Ito &
 * Kunisch, SIAM J. Optim. 13, 2003; for dual mortar contact Hueber &
 * Wohlmuth, CMAME 194, 2005), a semi-smooth Newton method on the normal
 * complementarity function
 *   C_j(u, z) = z_j - max(0, z_j - c_j g_j(u)) = 0,
 * z_j >= 0 the contact pressure of slave node j [Pa], g_j its weighted gap
 * [m^3] (mortar.h). For a linear structure each iteration solves
 *   K u - (B_A + mu G_A)^T z_A = f,   B_A u = -g0_A,   z_j = 0 off A,
 * with A = {j : z_j - c_j g_j > 0} of the previous iterate, until A no
 * longer changes (finitely many steps). With the steady-sliding option the
 * friction traction on every active slave node is mu z_j tau_j (tau_j the
 * master's sliding direction projected on the node's tangent plane), as in
 * the preload of a complex eigenvalue analysis: G_j u = tau_j . (D_jj u_j -
 * sum_l M_jl u_l). The augmented system is solved by UMFPACK.
 */

#include <deal.II/base/tensor.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <squeal/contact/mortar.h>

#include <ostream>
#include <string>
#include <vector>

namespace squeal
{
  namespace contact
  {
    /** Settings of the static contact solver. */
    struct ContactSettings
    {
      /// Coulomb coefficient of the steady-sliding friction [-]; 0:
      /// frictionless
      double friction_coefficient = 0.;
      /// sliding direction of the master surface against the slave
      /// (unit vector), projected on each slave node's tangent plane
      dealii::Tensor<1, 3> sliding_direction;
      unsigned int max_iterations = 50; ///< active-set iterations
    };

    /** One active-set iteration, for the convergence report. */
    struct ContactIteration
    {
      unsigned int active = 0;      ///< nodes in contact
      unsigned int changed = 0;     ///< nodes that changed set
      double       penetration = 0.;///< largest -g_j / D_jj [m] off A
      double       tension = 0.;    ///< largest -z_j [Pa] on A
    };

    /** The converged state. */
    struct ContactSolution
    {
      dealii::Vector<double> displacement; ///< n_dofs, m
      /// n_dofs: the contact forces on both bodies [N] (normal and friction)
      dealii::Vector<double> contact_force;
      dealii::Vector<double> pressure;     ///< n_s, multipliers z_j [Pa]
      /// n_s, the pressure field at the nodes (MortarOperators::nodal_pressure)
      dealii::Vector<double> nodal_pressure;
      std::vector<int>       status; ///< n_s: 0 separated, 1 closed, 2 slip
      dealii::Vector<double> gap;    ///< n_s, g_j / D_jj [m]
      double normal_force = 0.;      ///< sum_j D_jj z_j [N]
      double tangential_force = 0.;  ///< |sum_j D_jj mu z_j tau_j| [N]
      double contact_area = 0.;      ///< sum of D_jj over A [m^2]
      std::vector<ContactIteration> history;
    };

    /**
     * Solves the static contact problem K u = f + contact forces.
     * @param K stiffness [N/m], n x n, assembled with @p constraints
     * (Dirichlet constraints only: constrained rows carry their diagonal)
     * @param f load [N], n
     * @param log if given, one line per iteration
     * @throws std::runtime_error naming the iteration count and the
     * active-set sizes if the active set does not settle within
     * `max_iterations`, or if the direct solver fails (a body not held).
     */
    ContactSolution
    solve_static_contact(const dealii::SparseMatrix<double>      &K,
                         const dealii::Vector<double>            &f,
                         const dealii::AffineConstraints<double> &constraints,
                         const MortarOperators                   &mortar,
                         const ContactSettings                   &settings,
                         std::ostream                            *log = nullptr);
  } // namespace contact
} // namespace squeal

#endif
