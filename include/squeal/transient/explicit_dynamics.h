#ifndef squeal_transient_explicit_dynamics_h
#define squeal_transient_explicit_dynamics_h

/**
 * @file
 * Explicit time integration of linear elastic bodies with Rayleigh damping
 * and frictional contact on dual mortar operators (contact/mortar.h):
 *
 *   M a + C v + K u = f + G^T Lambda,   C = alpha M + beta K,
 *
 * M lumped (diagonal, Gauss-Lobatto quadrature: lumped_mass()).
 *
 * Time scheme: the beta2 method (Carpenter, Taylor & Katona, IJNME 32, 1991,
 * eq. 9-10; Massi's thesis, eq. 2-6), beta2 in [1/2, 1], 1/2 being central
 * differences:
 *   u_{n+1} = u_n + dt v_n + dt^2/2 a_n,
 *   v_{n+1} = v_n + dt ((1 - beta2) a_n + beta2 a_{n+1}).
 * The damping force at t_n uses the predicted velocity
 * v~_n = v_{n-1} + dt (1 - beta2) a_{n-1} (for beta2 = 1/2 the half-step
 * velocity v_{n-1/2}, as in Belytschko's central difference scheme), so
 * every step costs one product with K: K (u_n + beta v~_n).
 *
 * Contact: the forward-increment Lagrange multiplier method (Carpenter et
 * al. 1991): the multipliers Lambda_n act at t_n and are chosen so that the
 * displacement u_{n+1} they produce satisfies the contact conditions at
 * t_{n+1}. Per slave node j (multipliers z_j >= 0 normal pressure, lambda_j
 * tangential friction traction, Pa):
 *   - normal: weighted gap g_j(u_{n+1}) >= 0, z_j >= 0, z_j g_j = 0;
 *   - Coulomb friction without regularisation on the weighted slip
 *     increment s_j of the slave against the master over the step (the
 *     elastic motion and the master's rigid sliding velocity, e.g. the
 *     disc's rotation): stick (s_j = 0) where |lambda_j| < mu z_j, slip
 *     (lambda_j = mu z_j s_j / |s_j|, the friction on the slave opposes its
 *     slip) otherwise; separated where z_j = 0.
 * The Delassus system c G M^-1 G^T (c = dt^2 (beta2 + 1/2), interface nodes
 * only) is solved by projected Gauss-Seidel, node by node: with a lumped
 * mass each node's 3 x 3 block is a multiple of the identity, so the local
 * problem (normal projection, then the radial return onto the Coulomb disc)
 * is solved exactly.
 */

#include <deal.II/base/partitioner.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <squeal/contact/mortar.h>

#include <array>
#include <functional>
#include <iosfwd>
#include <memory>
#include <vector>

namespace squeal
{
  namespace transient
  {
    /**
     * The integrator's vectors: deal.II's MPI vector, each rank owning the
     * DoFs of its cells (the whole vector on one process), with the
     * interface DoFs as ghosts.
     */
    using DistributedVector =
      dealii::LinearAlgebra::distributed::Vector<double>;

    /** A stiffness product dst = K src on vectors of one partitioner. */
    using StiffnessProduct =
      std::function<void(DistributedVector &, const DistributedVector &)>;

    /**
     * A stiffness product on buffers of its own (ElasticityOperator's):
     * the caller writes src's locally owned entries [m] to input(), in the
     * order of the owned DoFs, calls apply(), and reads (K src)'s owned
     * entries [N] from output(). A time step then needs no copies of its
     * vectors in and out of the product's.
     */
    struct BufferedStiffnessProduct
    {
      std::function<double *()>       input;
      std::function<void()>           apply;
      std::function<const double *()> output;
    };

    /**
     * The lumped (diagonal) mass of an FE_Q^3 field [kg per DoF]: the
     * consistent mass integrated with the Gauss-Lobatto rule on the element's
     * nodes (degree + 1 points per direction), which is diagonal and positive
     * for every degree (for degree 2 the row-sum mass would have negative
     * vertex entries).
     * @param density kg/m^3 of a cell
     * @return n_dofs entries, each > 0
     */
    dealii::Vector<double>
    lumped_mass(
      const dealii::DoFHandler<3> &dof_handler,
      const dealii::Mapping<3>    &mapping,
      const std::function<
        double(const dealii::DoFHandler<3>::active_cell_iterator &)> &density);

    /** The stability limit of the explicit scheme. */
    struct StableTimeStep
    {
      double omega_max = 0.; ///< largest eigenvalue of M^-1 K, sqrt [rad/s]
      double critical  = 0.; ///< largest stable time step [s]
      unsigned int lanczos_steps = 0;
    };

    /**
     * The largest stable time step of the scheme above: omega_max^2, the
     * largest eigenvalue of M^-1 K on the free DoFs, by the Lanczos process
     * of deal.II's SolverCG (its largest Ritz value) on M^-1/2 K M^-1/2; the
     * Ritz value approaches omega_max^2 from below, and the run's safety
     * factor covers the gap; then
     *   dt_c = (sqrt(2 / beta2) / omega_max) (sqrt(1 + z^2) - z),
     *   z = beta omega_max / 2
     * (Belytschko, Liu & Moran, Nonlinear Finite Elements, 2000, eq. 6.3.26
     * for central differences with stiffness-proportional damping; the
     * factor sqrt(2 / beta2) / 2 is the explicit Newmark limit for beta2
     * above 1/2).
     * @param K stiffness [N/m], symmetric, n x n
     * @param mass lumped mass [kg], n
     * @param fixed n flags: DoFs held at zero (left out)
     * @param beta Rayleigh stiffness coefficient [s]
     * @param beta2 in [1/2, 1]
     */
    StableTimeStep
    stable_time_step(const dealii::SparseMatrix<double> &K,
                     const dealii::Vector<double>       &mass,
                     const std::vector<bool>            &fixed,
                     double                              beta,
                     double                              beta2,
                     unsigned int                        lanczos_steps = 80);

    /**
     * The same with the stiffness given as a product on vectors of
     * @p partitioner (any MPI layout; collective). The Lanczos start vector
     * is a hash of each DoF's support point and component (@p points,
     * n_dofs entries), so that it, and the limit, do not depend on the DoF
     * numbering or the number of ranks.
     * @param mass, fixed n_dofs entries each (every rank holds all)
     */
    StableTimeStep
    stable_time_step(
      const StiffnessProduct &K,
      const std::shared_ptr<const dealii::Utilities::MPI::Partitioner>
                                          &partitioner,
      const dealii::Vector<double>        &mass,
      const std::vector<bool>             &fixed,
      const std::vector<dealii::Point<3>> &points,
      double                               beta,
      double                               beta2,
      unsigned int                         lanczos_steps = 80);

    /** Settings of the integrator. */
    struct ExplicitSettings
    {
      double       time_step = 0.;  ///< s, must not exceed the stable limit
      double       beta2     = 0.5; ///< in [1/2, 1]
      double       alpha     = 0.;  ///< Rayleigh, mass [1/s]
      double       beta      = 0.;  ///< Rayleigh, stiffness [s]
      double       friction_coefficient = 0.;    ///< Coulomb mu [-]
      double       pgs_tolerance        = 1e-10; ///< relative change of Lambda
      unsigned int pgs_max_iterations   = 2000;
    };

    /** The contact state of one step (n_s slave nodes). */
    struct ContactStep
    {
      dealii::Vector<double> pressure; ///< n_s, z_j [Pa]
      /// n_s: friction traction on the slave (world frame) [Pa]
      std::vector<dealii::Tensor<1, 3>> traction;
      std::vector<int>       status; ///< n_s: 0 separated, 1 stick, 2 slip
      dealii::Vector<double> slip_velocity; ///< n_s, |s_j| / (D_jj dt) [m/s]
      dealii::Tensor<1, 3>   force;         ///< on the slave body [N]
      double                 normal_force = 0.; ///< sum D_jj z_j [N]
      double                 contact_area = 0.; ///< sum D_jj over z_j > 0 [m^2]
      unsigned int           n_stick = 0, n_slip = 0, n_separated = 0;
      unsigned int           pgs_iterations = 0;
      double                 pgs_change     = 0.; ///< last relative change
    };

    /**
     * The integrator. One step() per time step; between steps the state at
     * t_n (displacement, velocity, acceleration, contact) can be read.
     */
    class ExplicitDynamics
    {
    public:
      /**
       * @param K stiffness [N/m] (kept by reference), n x n
       * @param mass lumped mass [kg], n entries > 0
       * @param fixed n flags: DoFs held at zero
       * @param dt_critical the stable limit (stable_time_step())
       * @throws std::runtime_error if settings.time_step is not positive or
       * exceeds @p dt_critical (the message gives the limit), or beta2 is
       * outside [1/2, 1].
       */
      ExplicitDynamics(const dealii::SparseMatrix<double> &K,
                       const dealii::Vector<double>       &mass,
                       const std::vector<bool>            &fixed,
                       const ExplicitSettings             &settings,
                       double                              dt_critical);

      /**
       * The same with the stiffness given as its product on vectors of
       * @p partitioner (e.g. ElasticityOperator::vmult), under MPI each rank
       * owning its part. @p mass and @p fixed have n_dofs entries on every
       * rank. Collective over the partitioner's communicator; so are
       * set_contact(), step(), the energies, save() and load().
       */
      ExplicitDynamics(
        StiffnessProduct stiffness_product,
        const std::shared_ptr<const dealii::Utilities::MPI::Partitioner>
                                     &partitioner,
        const dealii::Vector<double> &mass,
        const std::vector<bool>      &fixed,
        const ExplicitSettings       &settings,
        double                        dt_critical);

      /**
       * Makes step() compute K (u_n + beta v~_n) through @p product's
       * buffers instead of the StiffnessProduct of the constructor (the
       * same product, which the energies keep using). @p product's owned
       * entries must be this integrator's partitioner's.
       */
      void
      use_buffered_product(const BufferedStiffnessProduct &product);

      /**
       * Adds frictional contact on @p mortar (kept by reference; under MPI
       * every rank holds the whole interface, e.g. built on a
       * parallel::shared::Triangulation). Its DoFs become ghosts of every
       * rank's vectors. The slave nodes fall into independent groups
       * (connected through shared interface nodes: one per pad on a brake);
       * with two or more groups and ranks, each rank sweeps the groups
       * assigned to it (balanced by their weighted-gap entries) and the
       * ranks exchange the results once per step; otherwise every rank
       * solves the whole (small) Delassus problem. Either way each group is
       * swept in the same order with the same convergence test (the
       * largest change over all groups), so the multipliers are the same
       * on every rank and for any number of ranks.
       * @param master_velocity rigid velocity of a master point [m/s] (the
       * disc's rotation omega e_z x x); empty: at rest
       */
      void
      set_contact(
        const contact::MortarOperators &mortar,
        const std::function<dealii::Tensor<1, 3>(const dealii::Point<3> &)>
          &master_velocity = {});

      /** Initial displacement [m] and velocity [m/s] at t = 0 (n_dofs
       * entries each, every rank; each takes its own). */
      void
      initialise(const dealii::Vector<double> &u0,
                 const dealii::Vector<double> &v0);

      /**
       * Completes the state at t_n = n dt under the external force @p f_n
       * [N] (n_dofs entries on every rank): the acceleration, the velocity, the
       * contact multipliers, and the displacement at t_{n+1}. The next call
       * moves to t_{n+1} first.
       * @throws std::runtime_error if projected Gauss-Seidel does not reach
       * its tolerance within its iteration limit, or the state is not
       * finite (naming the time and the iteration count).
       */
      void
      step(const dealii::Vector<double> &f_n);

      double
      time() const
      {
        return n_step * settings.time_step;
      }
      unsigned int
      step_number() const
      {
        return n_step;
      }
      /** u_n [m], v_n [m/s], a_n [m/s^2] at time(): the owned entries
       * (and the interface ghosts of u_n) are current. */
      const DistributedVector &
      displacement() const
      {
        return u;
      }
      const DistributedVector &
      velocity() const
      {
        return v;
      }
      const DistributedVector &
      acceleration() const
      {
        return a;
      }
      /** The layout of the vectors (with the interface ghosts). */
      const std::shared_ptr<const dealii::Utilities::MPI::Partitioner> &
      partitioner() const
      {
        return layout;
      }
      /** The contact multipliers of time() (empty without contact). */
      const ContactStep &
      contact_state() const
      {
        return contact;
      }
      /**
       * The independent groups of slave nodes of set_contact() (0 without
       * contact) and whether their sweeps are split among the ranks.
       */
      std::pair<unsigned int, bool>
      contact_groups() const
      {
        return {n_groups, split_contact};
      }
      /** 1/2 v^T M v [J]. */
      double
      kinetic_energy() const;
      /** 1/2 u^T K u [J]. */
      double
      strain_energy() const;

      /**
       * Writes the state after the last step() (time step number, the
       * displacements at t_n and t_{n+1}, the velocities, the acceleration
       * and the contact multipliers used as the next warm start) to @p out:
       * this rank's owned entries, raw, so that load() into an integrator
       * built the same way (same ranks) continues bit for bit.
       */
      void
      save(std::ostream &out) const;

      /**
       * Reads a state written by save().
       * @throws std::runtime_error if the stream is short or corrupt, or
       * its sizes (owned DoFs, slave nodes) or time step differ from this
       * integrator's.
       */
      void
      load(std::istream &in);

    private:
      void
      solve_contact();

      StiffnessProduct                                           K;
      BufferedStiffnessProduct                                   buffered_K;
      std::shared_ptr<const dealii::Utilities::MPI::Partitioner> layout;
      /// 1 / m per DoF [1/kg], 0 on fixed DoFs (n_dofs, every rank)
      dealii::Vector<double> inverse_mass;
      std::vector<bool>      fixed;
      /// 1 (free) or 0 (fixed) per owned DoF: the step's mask
      std::vector<double>             owned_free;
      ExplicitSettings                settings;
      const contact::MortarOperators *mortar = nullptr;

      unsigned int n_step  = 0;
      bool         pending = false; ///< t_n complete, not advanced
      /// the interface ghosts of u equal their owners' values: u_{n+1}
      /// leaves the contact step so (every rank applies the same
      /// corrections to its owned entries and ghost copies alike)
      bool                      u_ghosts_current = false;
      DistributedVector         u, v, a, v_pred, u_next;
      mutable DistributedVector work;
      /// the serial copies of the SparseMatrix constructor's product
      mutable dealii::Vector<double> serial_in, serial_out;

      void
      reinit_vectors();

      /// dt^2 (beta2 + 1/2) [s^2]: the change of u_{n+1} per unit change
      /// of M^-1 times a force
      double
      increment_factor() const
      {
        return settings.time_step * settings.time_step * (settings.beta2 + 0.5);
      }

      /// groups the slave nodes of set_contact() and assigns them to the
      /// ranks (split_contact, own_slave, own_entry)
      void
      assign_contact_groups();

      /// The interface in compact form, for the contact step's sweeps:
      /// every node of a weighted gap (slave and master) once, its three
      /// DoFs side by side (3 n_nodes entries), so that a sweep touches a
      /// few tens of kB instead of the whole vectors.
      /// local index of each compact entry in the vectors' layout (ghosts
      /// included)
      std::vector<unsigned int> iface_local;
      /// inverse lumped mass of each compact entry [1/kg] (0 if fixed)
      std::vector<double> iface_inverse_mass;
      /// u_n and u_{n+1} on the compact entries [m], the step's scratch
      std::vector<double> iface_start, iface_next;
      /// slave node j's weighted gap in CSR form: its nodes are
      /// row_node[row_start[j] .. row_start[j+1]) (compact node numbers)
      /// with weights row_w [m^2]: the slave node (w = -D_jj) first, then
      /// its master nodes (w = M_jl)
      std::vector<unsigned int> row_start, row_node;
      std::vector<double>       row_w;
      /// per weighted-gap entry and component: dt^2 (beta2 + 1/2) w / m
      /// [m^2 s^2/kg], the update of u_{n+1} per unit multiplier
      std::vector<double> row_cwim;
      /// the contact step split among the ranks by independent groups of
      /// slave nodes (see set_contact()); own_slave and own_entry flag the
      /// slave nodes (with a weighted gap) and compact entries this rank
      /// sweeps (all if not split)
      bool                       split_contact = false;
      unsigned int               n_groups      = 0;
      std::vector<unsigned char> own_slave, own_entry;
      /// scratch of the split contact step's exchange (the compact entries,
      /// then 3 multiplier components per slave node)
      std::vector<double>               iface_exchange;
      std::vector<double>               delassus;     ///< sum w^2 / m per node
      std::vector<dealii::Tensor<1, 3>> master_slide; ///< sum M_jl V(x_l)
      std::vector<dealii::Tensor<1, 3>> multiplier;   ///< z n + lambda
      ContactStep                       contact;
    };
  } // namespace transient
} // namespace squeal

#endif
