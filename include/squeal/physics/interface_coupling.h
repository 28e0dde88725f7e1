#ifndef squeal_physics_interface_coupling_h
#define squeal_physics_interface_coupling_h

/**
 * @file
 * The linear friction coupling of the complex eigenvalue analysis (thesis
 * § 1.5.1, eq. 3-1), integrated over the pad face by mortar projection onto
 * the disc face. With the gap g = (u(disc) - u(pad)) . n (n the pair's
 * normal from the disc into the pad; positive in compression), the
 * interface pressure is p = k g and the friction traction on
 * the pad is mu p t, t the disc's sliding direction; on the disc it is the
 * opposite. Its stiffness is K_f(mu) = K_n + mu K_t with
 *   K_n = int_Gamma k (n.N_d - n.N_p)^T (n.N_d - n.N_p) dA        (symmetric)
 *   K_t = int_Gamma k (t.N_d - t.N_p)^T (n.N_d - n.N_p) dA        (not)
 * Both faces lie in one plane, the pair's (scene::ContactPair: its normal,
 * in-plane axes and sliding direction t). A tangential (shear) stiffness
 * k_s of the contact layer adds the symmetric
 *   K_s,t = int_Gamma k_s sum_a (a.N_d - a.N_p)^T (a.N_d - a.N_p) dA
 * over the two in-plane axes a (zero unless k_s > 0: eq. 3-1 has none).
 */

#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_sparse_matrix.h>

#include <squeal/scene/scene.h>

#include <string>
#include <vector>

namespace squeal
{
  namespace physics
  {
    /**
     * One quadrature point of the interface: a point of the pad face with
     * its reference coordinates in the pad cell and in the disc cell below
     * it, and its weight [m^2].
     */
    struct CouplingPoint
    {
      dealii::DoFHandler<3>::active_cell_iterator pad_cell;
      dealii::DoFHandler<3>::active_cell_iterator disc_cell;
      dealii::Point<3>                            pad_unit;
      dealii::Point<3>                            disc_unit;
      double                                      weight;
    };

    /**
     * Quadrature of the interface for the locally owned pad cells.
     * `mortar`: segment-based: each pad face is clipped against every disc
     * face it overlaps (Sutherland-Hodgman in the pair's plane), the overlap
     * is split into triangles and each gets a Gauss rule of n_points^2-type
     * accuracy (QGaussSimplex with min(@p n_points, 4) per direction, exact to
     * degree 7). `nodal`: the
     * Gauss-Lobatto rule with @p n_points per direction on each pad face,
     * each point projected on the disc face below it; for degree 1 on
     * matching meshes this is the thesis' node-pair element.
     * Pad faces have boundary id @p pair.slave, disc faces @p pair.master.
     * @throws std::runtime_error naming the pair if less than all of the
     * pad face lies over the disc face (to 1e-6 of its area).
     */
    std::vector<CouplingPoint>
    interface_quadrature(const dealii::DoFHandler<3> &dof_handler,
                         const dealii::Mapping<3>    &mapping,
                         const scene::ContactPair    &pair,
                         const std::string           &rule,
                         const unsigned int           n_points);

    /** Adds the couplings of every (pad cell, disc cell) pair of @p points. */
    void
    add_interface_sparsity(const std::vector<CouplingPoint>        &points,
                           const dealii::AffineConstraints<double> &constraints,
                           dealii::DynamicSparsityPattern          &dsp);

    /**
     * Assembles K_n, K_t (per unit mu) and the tangential K_s,t of the
     * header into the three matrices, each n_dofs x n_dofs on the
     * interface's sparsity (added; call compress afterwards).
     * @param normal_stiffness interface stiffness per area k [N/m^3]
     * @param tangential_stiffness shear stiffness per area k_s [N/m^3]
     * @param pair its normal n, in-plane axes and sliding direction t (unit
     * vectors)
     * @param K_st the tangential part, or nullptr to skip it
     */
    void
    assemble_interface(const std::vector<CouplingPoint>        &points,
                       const dealii::AffineConstraints<double> &constraints,
                       const double              normal_stiffness,
                       const double              tangential_stiffness,
                       const scene::ContactPair &pair,
                       dealii::PETScWrappers::MPI::SparseMatrix &K_n,
                       dealii::PETScWrappers::MPI::SparseMatrix &K_t,
                       dealii::PETScWrappers::MPI::SparseMatrix *K_st);
  } // namespace physics
} // namespace squeal

#endif
