#ifndef squeal_contact_mortar_h
#define squeal_contact_mortar_h

/**
 * @file
 * Dual mortar operators between a slave and a master contact surface of one
 * vector-valued (FE_Q^3) displacement field, for small deformations.
 *
 * Slave nodes j are the support points of the slave faces; the Lagrange
 * multiplier (contact traction) is interpolated with dual shape functions
 * psi_j, biorthogonal to the slave trace space: int psi_j phi_k = delta_jk
 * int phi_k (Wohlmuth, SIAM J. Numer. Anal. 38, 2000; Popp et al., IJNME 79,
 * 2009, eq. 20-23), built per slave face as psi = D_e M_e^-1 phi. Then
 *   D_jj = int_{Gamma_s} psi_j phi_j dA = int phi_j dA           (diagonal),
 *   M_jl = int_{Gamma_s} psi_j (phi_l^m o P) dA                  (mixed),
 * the second by segment-based integration: each slave face is clipped
 * against the projections of the master faces (found through an R-tree of
 * their bounding boxes) onto its plane and the
 * overlap is triangulated and integrated exactly (for planar faces), which
 * makes the constant-pressure patch test pass to rounding.
 *
 * Per slave node: the averaged unit outward normal n_j (towards the master)
 * and two tangents, and the weighted gap
 *   g_j(u) = g0_j + B_j u,   g0_j = n_j . (sum_l M_jl x_l - D_jj x_j),
 *   B_j u  = n_j . (sum_l M_jl u_l - D_jj u_j)     [m^3],
 * positive when open. The contact force of normal pressures z >= 0 (Pa,
 * compressive positive) is B^T z: -D_jj z_j n_j on slave node j and
 * M_jl z_j n_j on master node l.
 */

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/vector.h>

#include <Eigen/Sparse>

#include <array>
#include <utility>
#include <vector>

namespace squeal
{
  namespace contact
  {
    /** The DoF indices of one node's three displacement components. */
    using NodeDofs = std::array<dealii::types::global_dof_index, 3>;

    /** The dual mortar operators of one contact pair (sizes in the
     * member comments; n_s slave nodes, n_m master nodes). */
    struct MortarOperators
    {
      std::vector<dealii::Point<3>>     slave_points;  ///< n_s, m
      std::vector<NodeDofs>             slave_dofs;    ///< n_s
      std::vector<dealii::Tensor<1, 3>> normals;       ///< n_s, unit, outward
      std::vector<dealii::Tensor<1, 3>> tangents1;     ///< n_s, unit
      std::vector<dealii::Tensor<1, 3>> tangents2;     ///< n_s, unit
      std::vector<dealii::Point<3>>     master_points; ///< n_m, m
      std::vector<NodeDofs>             master_dofs;   ///< n_m
      dealii::Vector<double>            D;             ///< n_s, m^2
      /// row j: (master node l, M_jl [m^2]) for the nonzero entries
      std::vector<std::vector<std::pair<unsigned int, double>>> M;
      /// n_s, weighted initial gap [m^3]: -n_j . sum_l M_jl (x_j - x_l), or
      /// infinity for a node only partly over the master (its row of M sums
      /// to less than the integral of its dual shape function)
      dealii::Vector<double> gap0;
      /// n_s x n_s: the standard mass matrix int phi_j phi_k of the slave
      /// surface [m^2], for the nodal pressure
      Eigen::SparseMatrix<double> slave_mass;
      double slave_face_size = 0.; ///< shortest slave face edge [m]
      /// what the operators were built from, for a rebuild
      dealii::types::boundary_id slave_id = 0, master_id = 0;
      double                     search_distance = 0.; ///< m
      unsigned int               n_points        = 4;
      double covered_area = 0.; ///< slave area over the master [m^2]
      double slave_area   = 0.; ///< m^2
      /// contact pairs merged into these operators (merge_mortar_operators);
      /// slave_id and master_id are the first pair's
      unsigned int n_pairs = 1;
      /// n_s: the contact pair (index in the merged list) of each slave
      /// node; empty for the operators of one pair
      std::vector<unsigned int> slave_pair;

      /** Number of slave nodes. */
      unsigned int
      n_slave() const
      {
        return slave_points.size();
      }
      /** g_j(u) = gap0_j + B_j u for all j [m^3]; @p u has n_dofs entries. */
      dealii::Vector<double>
      weighted_gaps(const dealii::Vector<double> &u) const;
      /**
       * The contact pressure as a continuous field of the standard slave
       * shape functions, p_h = sum_k p_k phi_k, from the multipliers z (the
       * coefficients of the dual functions): the L2 projection
       * int p_h phi_j = int (sum_i z_i psi_i) phi_j = D_jj z_j, i.e.
       * p = M_s^-1 D z (Popp et al. 2009). For quadratic faces the
       * multipliers themselves overshoot a smooth peak (the dual vertex
       * functions have negative lobes); the projection does not.
       * @param z n_s multipliers [Pa] @return n_s nodal pressures [Pa]
       */
      dealii::Vector<double>
      nodal_pressure(const dealii::Vector<double> &z) const;
      /** Weighted relative displacement of slave node j against the master
       * along @p direction: dir . (D_jj u_j - sum_l M_jl u_l) [m^3]. */
      double
      weighted_slip(unsigned int                  j,
                    const dealii::Vector<double> &u,
                    const dealii::Tensor<1, 3>   &direction) const;
    };

    /**
     * Builds the operators between the faces with boundary id @p slave_id
     * and those with @p master_id of @p dof_handler (FE_Q^3 of any degree
     * 1-3, serial triangulation). Simplex Gauss rules of @p n_points per
     * direction (1-4) on the overlap triangles.
     * @throws std::runtime_error if either surface is empty, or if a slave
     * face sees no master face within @p search_distance [m] along its
     * normal ("a slave face with no master face in reach"), or if the bodies
     * overlap by more than @p search_distance (a negative initial gap).
     */
    MortarOperators
    build_mortar_operators(const dealii::DoFHandler<3> &dof_handler,
                           const dealii::Mapping<3>    &mapping,
                           dealii::types::boundary_id   slave_id,
                           dealii::types::boundary_id   master_id,
                           double                       search_distance,
                           unsigned int                 n_points = 4);

    /**
     * The operators of several contact pairs as one: slave nodes, master
     * nodes, D, M, gaps and slave masses concatenated pair by pair (master
     * indices shifted), areas summed, the shortest slave face kept. A
     * master node shared by two pairs appears once per pair, which the
     * forces B^T z and gaps B u do not notice. One pair is returned as is.
     * @throws std::runtime_error if @p pairs is empty.
     */
    MortarOperators
    merge_mortar_operators(const std::vector<MortarOperators> &pairs);

    /**
     * The largest relative tangential displacement of a slave node against
     * the master between @p u_reference and @p u (n_dofs each) [m]:
     * max_j |(t1_j, t2_j) . (D_jj du_j - sum_l M_jl du_l)| / D_jj over the
     * nodes in reach, du = u - u_reference.
     */
    double
    largest_tangential_slip(const MortarOperators        &op,
                            const dealii::Vector<double> &u,
                            const dealii::Vector<double> &u_reference);

    /**
     * build_mortar_operators() on the configuration displaced by @p u
     * (n_dofs, m; MappingQEulerian of the FE's degree): the segmentation,
     * D, M, normals and nodes of the deformed surfaces, with gap0 shifted
     * so that weighted_gaps(v) = g0(deformed) + B (v - u) for the total
     * displacement v. The slave nodes keep their order.
     * @throws std::runtime_error as build_mortar_operators().
     */
    MortarOperators
    build_mortar_operators_deformed(const dealii::DoFHandler<3>  &dof_handler,
                                    const dealii::Vector<double> &u,
                                    dealii::types::boundary_id    slave_id,
                                    dealii::types::boundary_id    master_id,
                                    double       search_distance,
                                    unsigned int n_points = 4);

    /**
     * Large sliding: rebuilds @p op on the configuration @p u
     * (build_mortar_operators_deformed) when the largest relative tangential
     * displacement since the last segmentation, @p u_segmented (zero-sized:
     * the reference configuration), exceeds @p fraction times the shortest
     * slave face edge; then sets @p u_segmented = @p u. Small-sliding
     * problems thus build the segmentation once.
     * @param fraction > 0; 0 never rebuilds
     * @return whether the operators were rebuilt
     * @throws std::runtime_error if a rebuild is due and @p op merges
     * several pairs (large sliding is handled for one pair only)
     */
    bool
    refresh_segmentation(MortarOperators              &op,
                         const dealii::DoFHandler<3>  &dof_handler,
                         const dealii::Vector<double> &u,
                         dealii::Vector<double>       &u_segmented,
                         double                        fraction);
  } // namespace contact
} // namespace squeal

#endif
