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
 * longer changes (finitely many steps).
 *
 * Friction (Coulomb, constant mu), on the tangential traction t_j of slave
 * node j (2 components in its tangent frame, Pa) and its weighted slip
 * increment s_j = T_j (u - u_prev), T_j = tau . (D_jj e_j - sum_l M_jl e_l):
 * - `steady sliding`: every active node slips along the master's sliding
 *   direction, t_j = mu z_j tau_j, as in the preload of a complex eigenvalue
 *   analysis;
 * - `coulomb`: stick (s_j = 0) where the trial traction t_j - c_j s_j lies
 *   inside the cone mu z_j, slip (t_j = mu z_j d_j, d_j the trial
 *   traction's direction) outside it: the return map of Alart & Curnier
 *   (CMAME 92, 1991) in the set form of Hueber, Stadler & Wohlmuth (SIAM J.
 *   Sci. Comput. 30, 2008). The slip condition t_j = mu z_j y_j / |y_j|,
 *   y_j = t_j - c_j s_j, is linearised at the last iterate (semi-smooth
 *   Newton): (I - a_j P_j) t_j - mu n_j z_j + a_j c_j P_j s_j = 0 with
 *   n_j = y_j / |y_j|, P_j = I - n_j n_j^T, a_j = mu z_j / |y_j|, so the
 *   iteration converges super-linearly once the sets stop changing; it
 *   stops when no node changes set and the slip residual
 *   |t_j - mu z_j n_j| is below 1e-10 mu max z.
 * A compliant normal law (ContactSettings::normal_stiffness k_j > 0,
 * pressure k_j times the penetration -g_j / D_jj) is the same iteration on
 * the perturbed constraint g_j + (D_jj / k_j) z_j = 0 of the active nodes
 * (a perturbed Lagrangian: the compliance D_jj / k_j [m^5/N] on the
 * multiplier's diagonal) and the complementarity function
 *   C_j(u, z) = z_j - max(0, z_j - c_j (g_j + (D_jj / k_j) z_j)),
 * so that an active node's pressure is exactly k_j times its penetration,
 * and k_j -> infinity gives the hard law back (first order in 1/k_j).
 *
 * The augmented system is solved by MUMPS's LU, on one process or under
 * MPI (each rank its rows of the structure, the contact rows replicated;
 * the active sets are updated identically on every rank from the gathered
 * solution).
 */

#include <deal.II/base/tensor.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <squeal/contact/mortar.h>

#include <array>
#include <ostream>
#include <string>
#include <vector>

namespace squeal
{
  namespace contact
  {
    /**
     * The structure's stiffness [N/m] as the contact solver sees it: a
     * serial deal.II matrix or a distributed PETSc matrix whose rows each
     * rank owns in contiguous ranges. Either way the augmented system is
     * solved by MUMPS's LU (on the one process, or across the ranks: the
     * contact rows are built identically on every rank and owned by the
     * last one, the solution gathered on every rank). Both are n x n,
     * assembled with the constraints given to the solver.
     */
    struct ContactStiffness
    {
      /// serial: keeps a reference to @p K
      ContactStiffness(const dealii::SparseMatrix<double> &K);
      /// distributed over @p comm: keeps a reference to @p K
      ContactStiffness(const dealii::PETScWrappers::MPI::SparseMatrix &K,
                       MPI_Comm                                        comm);
      /// number of rows n
      unsigned int
      size() const;
      /// the diagonal entries of @p dofs, on every rank (collective when
      /// distributed)
      std::vector<double>
      diagonal(const std::vector<dealii::types::global_dof_index> &dofs) const;

      const dealii::SparseMatrix<double>             *serial      = nullptr;
      const dealii::PETScWrappers::MPI::SparseMatrix *distributed = nullptr;
      MPI_Comm                                        comm;
    };

    /** Friction law of the static contact solver. */
    enum class FrictionModel
    {
      frictionless,
      steady_sliding, ///< every contact node slips along sliding_direction
      coulomb         ///< stick / slip from the incremental Coulomb law
    };

    /** Settings of the static contact solver. */
    struct ContactSettings
    {
      FrictionModel friction = FrictionModel::frictionless;
      /// Coulomb coefficient [-]
      double friction_coefficient = 0.;
      /// sliding direction of the master surface against the slave
      /// (unit vector), projected on each slave node's tangent plane
      dealii::Tensor<1, 3> sliding_direction;
      unsigned int         max_iterations = 50; ///< active-set iterations
      /// `coulomb`: the displacement of the previous load step (slip
      /// increments are measured from it), n_dofs; empty: zero
      dealii::Vector<double> previous_displacement;
      /// `coulomb`: rigid displacement of the master surface during the
      /// load step [m] (a turning disc: its slip under the pad), added to
      /// every node's slip; zero: the master at rest
      dealii::Tensor<1, 3> master_slip;
      /// the status (0 separated, 1 stick, 2 slip) of each slave node at
      /// the previous load step, the first guess of the sets; empty: the
      /// nodes closed in the reference state, stuck
      std::vector<int> initial_status;
      /// n_s x 2, with initial_status: the tangential traction of the
      /// previous load step; a slipping node's first slip direction
      std::vector<std::array<double, 2>> initial_traction;
      /// The normal contact law, per slave node: k_j [N/m^3] > 0 makes it
      /// compliant (penalty), p_j = k_j max(0, -g_j / D_jj), the law of the
      /// CEA's linear interface (thesis eq. 3-1) with the same k; 0 makes it
      /// hard (no penetration, p_j a Lagrange multiplier). Empty: hard
      /// everywhere; otherwise n_s entries, each finite and >= 0.
      std::vector<double> normal_stiffness;
    };

    /** One active-set iteration, for the convergence report. */
    struct ContactIteration
    {
      unsigned int active      = 0;  ///< nodes in contact
      unsigned int changed     = 0;  ///< nodes that changed set
      unsigned int stick       = 0;  ///< nodes that stick
      double       penetration = 0.; ///< largest -g_j / D_jj [m] off A
      double       tension     = 0.; ///< largest -z_j [Pa] on A
      /// Coulomb: largest |t_j - mu z_j n_j| over the slip nodes, relative
      /// to mu max z (n_j the direction of the trial traction)
      double slip_residual = 0.;
    };

    /** The converged state. */
    struct ContactSolution
    {
      dealii::Vector<double> displacement; ///< n_dofs, m
      /// n_dofs: the contact forces on both bodies [N] (normal and friction)
      dealii::Vector<double> contact_force;
      dealii::Vector<double> pressure; ///< n_s, multipliers z_j [Pa]
      /// n_s, the pressure field at the nodes (MortarOperators::nodal_pressure)
      dealii::Vector<double> nodal_pressure;
      std::vector<int>       status; ///< n_s: 0 separated, 1 closed, 2 slip
      dealii::Vector<double> gap;    ///< n_s, g_j / D_jj [m]
      /// n_s x 2: tangential traction on the slave in (tangents1,
      /// tangents2) [Pa] (coefficients of the dual functions)
      std::vector<std::array<double, 2>> tangential_traction;
      /// n_s x 2: weighted slip increment / D_jj [m] in the same frame
      std::vector<std::array<double, 2>> slip;
      double normal_force     = 0.; ///< sum_j D_jj z_j [N]
      double tangential_force = 0.; ///< |sum_j D_jj t_j| [N]
      double contact_area     = 0.; ///< sum of D_jj over A [m^2]
      std::vector<ContactIteration> history;
    };

    /**
     * Solves the static contact problem K u = f + contact forces.
     * @param K stiffness [N/m], n x n, assembled with @p constraints
     * (Dirichlet constraints only on the contact surfaces, no hanging
     * nodes there: constrained rows carry their diagonal; a contact
     * condition on constrained DoFs only is met by them)
     * @param f load [N], n
     * @param log if given, one line per iteration
     * @throws std::runtime_error naming the iteration count and the
     * active-set sizes if the active set does not settle within
     * `max_iterations`, if the direct solver fails (a body not held), if
     * mu < 0, or if `settings.normal_stiffness` is neither empty nor n_s
     * finite values >= 0.
     */
    ContactSolution
    solve_static_contact(const ContactStiffness                  &K,
                         const dealii::Vector<double>            &f,
                         const dealii::AffineConstraints<double> &constraints,
                         const MortarOperators                   &mortar,
                         const ContactSettings                   &settings,
                         std::ostream *log = nullptr);

    /**
     * Load stepping for path-dependent (Coulomb) contact: the load goes
     * from @p f_start (already carried by @p start, the converged state at
     * f_start) to @p f_end in @p n_steps equal increments; each step starts
     * from the previous step's displacement and stick/slip sets. A step
     * whose active set does not settle, or whose system is singular, is cut
     * in half, at most @p max_cuts times in a row.
     * @return the state at f_end; its history holds every step's iterations.
     * @throws std::runtime_error naming the load factor reached, the step
     * size and the last error when the cuts are exhausted; nothing is
     * returned that would look like a converged result.
     */
    ContactSolution
    solve_contact_load_steps(
      const ContactStiffness                  &K,
      const dealii::Vector<double>            &f_start,
      const dealii::Vector<double>            &f_end,
      const ContactSolution                   &start,
      const dealii::AffineConstraints<double> &constraints,
      const MortarOperators                   &mortar,
      ContactSettings                          settings,
      unsigned int                             n_steps,
      unsigned int                             max_cuts = 6,
      std::ostream                            *log      = nullptr);
  } // namespace contact
} // namespace squeal

#endif
