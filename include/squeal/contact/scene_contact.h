#ifndef squeal_contact_scene_contact_h
#define squeal_contact_scene_contact_h

/**
 * @file
 * The contact problem of a scene: its contact pairs' merged dual mortar
 * operators, their common sliding direction and slave face sets, the
 * structural stiffness with the scene's holds and point holds (serial and
 * distributed), and the load vector of the scene's loads. The preload and
 * the braking run (analyses/) build their contact problems from these.
 */

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <squeal/contact/contact_solver.h>
#include <squeal/contact/mortar.h>
#include <squeal/physics/structural_model.h>

#include <set>
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
     * The penalty law's normal stiffness of every slave node of @p op
     * (scene_mortar()'s merged operators): its contact pair's `<pair>.k_n`
     * at @p point [N/m^3], for ContactSettings::normal_stiffness.
     * @return n_s values
     * @throws std::runtime_error as ScalarPoint::get().
     */
    std::vector<double>
    pair_normal_stiffness(const scene::Scene            &scene,
                          const parameters::ScalarPoint &point,
                          const MortarOperators         &op);

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
     * The constraints of @p model's ties (bonded interfaces) into
     * @p constraints (not closed): for each tie, the dual mortar operators
     * D, M between its slave and master faces (build_mortar_operators(),
     * Preload/Search distance as the reach), and for each slave node j and
     * component c not already constrained (a hold, a hanging node)
     *   u_jc = sum_l (M_jl / sum_k M_jk) u_lc,
     * the mortar mesh tying of Wohlmuth (SIAM J. Numer. Anal. 38, 2000) with
     * dual multipliers, which condenses to these constraints because D is
     * diagonal (sum_k M_jk = D_jj where the master covers the slave node's
     * support, so a rigid motion stays rigid; normalised where it covers it
     * partly). A slave node the master does not reach stays free.
     * @throws std::runtime_error naming the tie if its faces are empty or
     * out of reach (as build_mortar_operators()).
     */
    void
    add_tie_constraints(const physics::StructuralModel    &model,
                        dealii::AffineConstraints<double> &constraints);

    /**
     * The load vector [N] of the scene's loads (all, or only load number
     * @p only), with @p constraints: each a uniform traction on its faces
     * along its direction, of @p force [N] in all (a load of magnitude
     * `analysis`: the TriboBrake's support top, pushing the pad towards
     * the disc, -z; two pads of a caliper each pressed by @p force), its
     * own force [N] in all, or its pressure [Pa]. @p total, if given,
     * receives the sum of the loads' total forces [N].
     * @throws std::runtime_error if the scene has no load or a load's face
     * set is empty.
     */
    dealii::Vector<double>
    scene_load(const physics::StructuralModel          &model,
               const dealii::AffineConstraints<double> &constraints,
               double                                   force,
               int                                      only  = -1,
               double                                  *total = nullptr);

  } // namespace contact
} // namespace squeal

#endif
