#ifndef squeal_physics_structural_model_h
#define squeal_physics_structural_model_h

/**
 * @file
 * The linear structural model of a scene: mesh, FE space, constraints and
 * the matrices of the equations of motion M u'' + C u' + K u = 0, assembled
 * once and stored in parts so that a sweep over any of the scalar parameters
 * of parameters::ScalarPoint only recombines them (see MatrixParts).
 * Matrices are PETSc MPI matrices on a parallel::shared::Triangulation, so
 * the same code runs serially and under mpirun.
 */

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <squeal/parameters/parameters.h>
#include <squeal/scene/scene.h>

#include <array>
#include <complex>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace squeal
{
  namespace physics
  {
    /// the distributed sparse matrix of every matrix part
    using PETScMatrix = dealii::PETScWrappers::MPI::SparseMatrix;
    /// the distributed vector of DoF values and mode shapes
    using PETScVector = dealii::PETScWrappers::MPI::Vector;

    /** The Lame constants (lambda, mu) [Pa] of Young's modulus @p E [Pa]
     * and Poisson's ratio @p nu. */
    inline std::pair<double, double>
    lame_constants(const double E, const double nu)
    {
      return {E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))};
    }

    /**
     * Adds to @p cell_k the stiffness of isotropic linear elasticity (Lame
     * constants @p lambda, @p mu [Pa]) and to @p cell_m the consistent mass
     * (@p density [kg/m^3]) of the cell @p fe_values was last reinit'ed on
     * (an FE_Q^3 system; both n x n, n its DoFs per cell; N/m and kg).
     */
    void
    add_cell_elasticity(const dealii::FEValues<3>  &fe_values,
                        double                      lambda,
                        double                      mu,
                        double                      density,
                        dealii::FullMatrix<double> &cell_k,
                        dealii::FullMatrix<double> &cell_m);

    /**
     * The matrix parts of a linear model (n x n each, one sparsity pattern;
     * mass parts in kg, stiffness parts in N/m), each assembled at a
     * reference value of the named parameter that scales it, and their
     * affine combinations at a point p (parameters::ScalarPoint):
     *   M(p)   = sum over mass parts      s_k(p) M_k,
     *   K_s(p) = sum over stiffness parts s_k(p) K_k   (bodies, springs),
     *   K(p)   = K_s(p) + sum over pairs (k_n / k_n,ref) (K_n + mu K_t),
     *   C(p)   = sum over mass parts alpha_k(p) s_k(p) M_k
     *          + sum over stiffness parts beta_k(p) s_k(p) K_k,
     * with s_k = p[scale] / reference (1 without a scale) and alpha_k,
     * beta_k the Rayleigh coefficients named by the part's damping (a
     * body's own or the scene's: per-body Rayleigh damping). K_t is a
     * pair's friction part per unit mu (thesis eq. 3-1). Non-owning.
     */
    struct MatrixParts
    {
      /** What a part is. */
      enum class Kind
      {
        mass,      ///< enters M (and C through alpha) [kg]
        stiffness, ///< enters K_s, K (and C through beta) [N/m]
        /// a pair's K_n at its k_n,ref, or its tangential (shear) part at
        /// k_t,ref: enters K_s + K_n and K, not K_s [N/m]
        interface_normal,
        interface_friction, ///< a pair's K_t per unit mu at k_n,ref [N/m]
      };
      /** One assembled part. */
      struct Part
      {
        const PETScMatrix *matrix = nullptr;    ///< n x n
        Kind               kind   = Kind::mass; ///< see Kind
        std::string        name;  ///< for logs, e.g. `stiffness of pad`
        std::string        scale; ///< parameter scaling it, "" for none
        double             reference = 1.; ///< its value at assembly
        std::string        factor;         ///< friction: the pair's `<pair>.mu`
        std::string        damping; ///< mass: an alpha, stiffness: a beta
        bool               springs = false; ///< a spring set's stiffness
        /// stored on its own nonzero entries, a subset of the first part's
        /// pattern (false: stored on the common pattern)
        bool own_pattern = false;
      };
      /// One coefficient per part.
      using Coefficients = std::vector<double>;

      /// true once StructuralModel::release_body_parts() dropped the
      /// bodies' (common-pattern) parts: only the spring sets' and the
      /// interfaces' parts remain, and combine() (every combination of the
      /// model) throws; spring_product() still works
      bool bodies_released = false;

      /** The coefficients of M, K_s, K and C at one point. */
      struct Combination
      {
        Coefficients mass;                ///< M(p) [kg]
        Coefficients structural;          ///< K_s(p): bodies and springs [N/m]
        Coefficients stiffness;           ///< K(p): K_s + K_n + mu K_t [N/m]
        Coefficients symmetric_stiffness; ///< K_s + K_n (no friction) [N/m]
        Coefficients damping;             ///< C(p) [N s/m]
        Coefficients springs;             ///< the spring sets' parts [N/m]
      };

      /**
       * Modal damping of the complex eigenvalue analysis (parameter
       * Damping/Modal damping ratios), added to the Rayleigh C(p):
       *   C_modal(p) = sum_i 2 zeta(f_i) omega_i M phi_i phi_i^T M
       * over the modes (omega_i = 2 pi f_i [rad/s], phi_i M-normalised) of
       * the frictionless assembly (K_s + K_n, M) at p up to @ref cutoff.
       * A dense n x n matrix of rank m: never assembled; each eigensolver
       * applies it on its subspace from that subspace's Ritz modes of
       * (K_s + K_n, M), which are the exact modes in the full solver (its
       * subspace contains them) and their reduced-basis approximations in
       * the reduced model (eigen/dense_block.h: subspace_modal_damping()).
       */
      struct ModalDamping
      {
        /// (f [Hz], zeta [-]) ascending; zeta linear in f between them,
        /// constant beyond the ends; empty: no modal damping
        std::vector<std::pair<double, double>> ratios;
        /// highest damped mode [Hz]: Eigensolver/Maximum frequency x
        /// Reduced band factor
        double cutoff = 0.;

        /** Whether any modal damping is given. */
        bool
        active() const
        {
          return !ratios.empty();
        }

        /** zeta(f) [-] at @p f [Hz] (0 without ratios). */
        double
        ratio(double f) const;

        /**
         * The modal damping coefficient 2 zeta(f) omega [1/s] of a mode
         * with eigenvalue @p omega2 = omega^2 [1/s^2]; 0 at or below 0 and
         * above (2 pi cutoff)^2.
         */
        double
        coefficient(double omega2) const;
      };

      /// modal damping (none unless Damping/Modal damping ratios is given)
      ModalDamping modal;

      /// the parts; the first is a mass part on the common pattern, the
      /// others on it or on their own nonzeros within it (own_pattern)
      std::vector<Part> parts;
      /// Parameters held at a value in parts of coefficient 1 (a body's E
      /// or rho when the model does not vary it): every point must have
      /// these values.
      std::vector<std::pair<std::string, double>> fixed;
      /// the nominal point of the model (its M is the reduced solver's
      /// reference mass)
      parameters::ScalarPoint reference;

      /** Number of parts. */
      unsigned int
      size() const
      {
        return parts.size();
      }
      /** The matrix of part @p k. */
      const PETScMatrix &
      matrix(const unsigned int k) const
      {
        return *parts[k].matrix;
      }
      /**
       * Coefficients of every combination at @p p.
       * @throws std::runtime_error if @p p lacks a parameter a part names,
       * or moves one of @ref fixed (the model must be built varying it).
       */
      Combination
      coefficients(const parameters::ScalarPoint &p) const;
      /** sum_k c[k] part_k into @p result (re-initialised). */
      void
      combine(const Coefficients &c, PETScMatrix &result) const;
      /** M(p). */
      void
      mass(const parameters::ScalarPoint &p, PETScMatrix &M) const;
      /** K(p), non-symmetric when mu != 0. */
      void
      stiffness(const parameters::ScalarPoint &p, PETScMatrix &K) const;
      /** K(p) without the friction parts (symmetric). */
      void
      symmetric_stiffness(const parameters::ScalarPoint &p,
                          PETScMatrix                   &K) const;
      /** C(p). */
      void
      damping(const parameters::ScalarPoint &p, PETScMatrix &C) const;
      /** The spring sets' stiffness at @p p. */
      void
      springs(const parameters::ScalarPoint &p, PETScMatrix &K) const;
      /**
       * @p result = (the spring sets' stiffness at @p p) @p u, from each
       * spring part's own nonzeros (no matrix of the common pattern is
       * formed; works after StructuralModel::release_body_parts()).
       * @p u, @p result: locally owned vectors of n entries [m], [N].
       */
      void
      spring_product(const parameters::ScalarPoint &p,
                     const PETScVector             &u,
                     PETScVector                   &result) const;
      /**
       * The sum of the parts of kind @p kind, each with coefficient 1 (the
       * interface parts at their reference stiffness, for the reduced
       * basis' enrichment); false (and @p result untouched) if there is
       * none.
       */
      bool
      sum(Kind kind, PETScMatrix &result) const;
    };

    /**
     * Mesh, DoFs and assembled matrix parts of one scene. Sizes: every
     * matrix is n x n with n = dof_handler.n_dofs() (3 displacement
     * components per node, m). Units: M in kg, K parts in N/m.
     */
    class StructuralModel
    {
    public:
      /** Stores the parameters; nothing is built yet. */
      StructuralModel(const parameters::AllParameters &prm, MPI_Comm comm);

      /**
       * Makes the scene, then builds its mesh, the DoFs, the constraints
       * (the scene's holds, hanging nodes) and the common sparsity pattern of
       * all matrix parts, then assembles every part of MatrixParts at the
       * nominal parameter values of the file (a zero one is replaced by 1 in
       * its unit). Constrained rows get K_ii = d (the mean diagonal of K_rest
       * over the free rows) and M_ii = d / (2 pi 1e3 f_max)^2, which puts their
       * spurious eigenvalues a thousand times above the band (deal.II step-36).
       */
      void
      setup_and_assemble(dealii::ConditionalOStream &pcout);

      /**
       * setup_and_assemble() on the coarse mesh refined first by the steps
       * of another model's refinement_history (same scene, possibly another
       * degree), which this model's refinement_history then holds; the
       * DoFs, constraints and matrix parts are built once, on the refined
       * mesh: afterwards both models have the same cells in the same order.
       * @throws std::runtime_error if a step does not fit the mesh (a
       * different scene).
       */
      void
      setup_and_assemble(const std::vector<std::vector<bool>> &history,
                         dealii::ConditionalOStream           &pcout);

      /**
       * Refines the cells with the largest @p indicator (one value per
       * active cell, the same on every rank), then builds the DoFs,
       * constraints and matrix parts again on the new mesh (as
       * setup_and_assemble() without rebuilding the coarse mesh). Marking:
       * with @p by_error false, @p fraction of the cells (fixed number);
       * with it true, the fewest cells whose squared indicators sum to
       * @p fraction of the total (fixed fraction, Doerfler's bulk
       * criterion: W. Doerfler, SIAM J. Numer. Anal. 33, 1996, eq. 4.1);
       * either way also every cell whose indicator is within a relative
       * 1e-3 of the smallest one marked (cells tied by the mesh's symmetry
       * are refined together, whatever the rounding).
       * @throws std::runtime_error if @p indicator does not have one entry
       * per active cell.
       */
      void
      refine(const dealii::Vector<float> &indicator,
             double                       fraction,
             bool                         by_error,
             dealii::ConditionalOStream  &pcout);

      /// The refine flags of every refine() so far (deal.II's
      /// save_refine_flags: 3 bits per active cell of the mesh before that
      /// step), for setup_and_assemble() of another model on the same mesh.
      std::vector<std::vector<bool>> refinement_history;

      /**
       * Frees the bodies' mass and stiffness parts (the matrices on the
       * common pattern, two to four whole matrices: 4 GB at a million
       * DoFs) once an analysis has taken what it needs of them (the
       * preload its contact system); the spring sets' and interfaces'
       * parts stay. parts() then has MatrixParts::bodies_released set and
       * its combinations throw std::logic_error.
       */
      void
      release_body_parts();

      /** The assembled parts, for the eigensolvers. */
      MatrixParts
      parts() const
      {
        return assembled;
      }

      /**
       * The named parameters (scene::Scene::parameters()) the model's parts
       * let vary: a body's stiffness and mass are parts of their own only
       * when its `.E` or `.rho` is listed (or it has its own damping); the
       * others are summed into common parts at their nominal values. Set
       * it before setup_and_assemble(); unset (the default) varies every
       * parameter. The interface and spring parts always vary, except a
       * pair's tangential part: it exists only when its `.k_t` is nonzero
       * or listed.
       */
      std::optional<std::set<std::string>> varied;

      /**
       * Nominal values that replace the scene's (scene::Scene::set_nominal())
       * when setup_and_assemble() makes it: a braking grid's point.
       */
      std::vector<std::pair<std::string, double>> nominal_overrides;

      /**
       * Adds the constraints of the scene's ties (scene::Scene::ties,
       * bonded interfaces) to the model's: a higher layer's
       * (contact::add_tie_constraints, dual mortar). Set it before
       * setup_and_assemble() when the scene has ties; setup_and_assemble()
       * throws std::runtime_error if it has ties and this is unset.
       */
      std::function<void(const StructuralModel &,
                         dealii::AffineConstraints<double> &)>
        tie_constraints;

      /** Number of degrees of freedom. */
      dealii::types::global_dof_index
      n_dofs() const
      {
        return dof_handler.n_dofs();
      }

      const parameters::AllParameters &prm;  ///< the run's parameters
      MPI_Comm                         comm; ///< the ranks sharing the model

      /// The scene the model was built from (scene::make_scene() of the
      /// parameters at setup_and_assemble(); null before): bodies, contact
      /// pairs, holds, loads, springs.
      std::unique_ptr<const scene::Scene> scene;

      /**
       * Optional weight of the linear friction interface at a point of the
       * pad face (m): each interface quadrature point's weight is
       * multiplied by it before K_n and K_t are assembled. Set it before
       * setup_and_assemble(); unset means 1 everywhere. A CEA about a preload
       * sets it to 1 where the preload's pad nodes are in contact and 0
       * where they separated, so that the interface stiffness and the
       * friction coupling live on the active set only; a CEA about a
       * braking run's contact history sets it to the nearest pad node's
       * fraction of time in contact (in [0, 1]). A point of weight 0 is
       * dropped.
       */
      std::function<double(const dealii::Point<3> &)> interface_mask;

      /**
       * The scene's mesh, whole on every rank (refined by the CEA), each
       * rank owning a METIS part. Shared rather than distributed because
       * it was measured to hold less (benchmarks/scale/README.md, "Which
       * parallel triangulation"): a mesh file's cells are all coarse
       * cells, which p4est keeps on every rank too, with twice the
       * memory; a fully distributed triangulation cannot be refined
       * (deal.II 9.4); the whole mesh and DoF handler of the
       * 1.2-million-DoF brake take 35 MB per rank at degree 2.
       */
      dealii::parallel::shared::Triangulation<3> triangulation;
      /// FE_Q^3 of Mesh/Finite element degree
      const dealii::FESystem<3> fe;
      /// of the same degree: curved faces follow the scene's manifolds
      const dealii::MappingQ<3> mapping;
      /// the displacement DoFs (3 per node)
      dealii::DoFHandler<3> dof_handler;
      /// hanging nodes and the scene's holds (homogeneous)
      dealii::AffineConstraints<double> constraints;
      /// the DoFs this rank owns
      dealii::IndexSet locally_owned_dofs;
      /// the DoFs this rank's cells touch
      dealii::IndexSet locally_relevant_dofs;

      /// the matrices of the parts (see parts()), in their order
      std::vector<std::unique_ptr<PETScMatrix>> part_matrices;

      /**
       * How the springs spread over their attachment discs are integrated
       * (set before setup_and_assemble()). false (default): consistently,
       * a Winkler layer of stiffness density k w(x) / int(w) [N/m^3]
       * (w the cosine bell of Springs/Attachment radius) by composite Gauss
       * rules fine enough for the bell, so the spring model is the same on
       * every mesh and degree (what the tolerance-driven mesh needs). true:
       * lumped on the face's FE_Q support points (Gauss-Lobatto rule), which
       * keeps the springs' parts diagonal, as the explicit dynamics' grounded
       * springs need, at the price of a model that moves with the node
       * spacing.
       */
      bool lumped_springs = false;


      /** A point mass of the scene at its node (see setup_and_assemble()). */
      struct PointMass
      {
        std::array<dealii::types::global_dof_index, 3> dofs;      ///< x, y, z
        double                                         mass = 0.; ///< kg
        dealii::types::material_id body = 0; ///< the body it sits on
        std::string                name;     ///< the scene's LumpedMass::name
      };
      /// the scene's point masses, each at the unconstrained node nearest
      /// its point (the lowest DoF index among equally near ones); the same
      /// on every rank
      std::vector<PointMass> point_masses;
      double                 constrained_diagonal = 1.; ///< d above [N/m]

    private:
      void
      setup_dofs_and_assemble(dealii::ConditionalOStream &pcout);
      /// the lumped mass @p m into its own mass part @p M (at its nominal
      /// value): a face set's as a consistent surface mass of density
      /// m / area, a point's on the diagonal of its node's three DoFs
      /// (recorded in point_masses)
      void
      add_mass(const scene::LumpedMass &m, PETScMatrix &M);
      /// the parts of the bodies (one mass and one stiffness part per
      /// group of bodies that share their varied parameters and damping)
      /// into part_matrices and @p parts; returns the common (fixed) mass
      /// and stiffness parts' indices
      std::pair<unsigned int, unsigned int>
      assemble_elasticity(const parameters::ScalarPoint &nominal,
                          MatrixParts                   &parts);
      /// adds one spring set of the scene to @p K at @p k [N/m] per spring
      /// @throws std::runtime_error if a face the springs spread over is
      /// not a parallelogram, or a point spring has an oblique direction
      void
      add_springs(const scene::SpringSet     &springs,
                  PETScMatrix                &K,
                  double                      k,
                  dealii::ConditionalOStream &pcout);
      /// springs between two bodies (scene::SpringSet::to_body): per
      /// station the x, y, z DoFs of the node of the first body nearest it,
      /// then those of the second body's (unconstrained-by-hanging nodes;
      /// the lowest DoF among equally near ones), the same on every rank
      /// @throws std::runtime_error if a body has no node
      std::vector<std::array<dealii::types::global_dof_index, 6>>
      two_body_spring_nodes(const scene::SpringSet &s) const;
      /// a new zero part matrix: on the common pattern, or, given @p own,
      /// on the entries @p own adds to an empty pattern of the locally
      /// relevant rows and the diagonal of every owned row (a part of a
      /// few hundred rows: a copy of the common pattern costs a whole
      /// matrix of memory writes, 1.3 GB at degree 4 on the TriboBrake)
      PETScMatrix &
      new_part_matrix(
        const std::function<void(dealii::DynamicSparsityPattern &)> &own = {});
      /// the boundary faces of body s.body on a station's plane within the
      /// attachment radius plus half the face's diameter of the station
      /// (locally owned cells; the faces spread springs of @p s may touch)
      std::vector<
        std::pair<dealii::DoFHandler<3>::active_cell_iterator, unsigned int>>
      spring_faces(const scene::SpringSet &s) const;
      /// adds to @p dsp the entries of the spring set @p s (its faces'
      /// cells, the node pairs of springs between bodies), condensed
      void
      add_spring_sparsity(const scene::SpringSet         &s,
                          dealii::DynamicSparsityPattern &dsp) const;
      /// the common sparsity pattern of every part
      std::unique_ptr<dealii::DynamicSparsityPattern> pattern;
      /// an empty PETSc matrix on that pattern, duplicated for each part
      /// (walking the dynamic pattern once per part cost seconds at
      /// degree 4)
      std::unique_ptr<PETScMatrix> part_template;
      /// see parts()
      MatrixParts assembled;
      /// part_matrices used so far in the current assembly
      unsigned int next_part = 0;
      /// the quadrature of one face the springs' bells touch
      struct SpringFaceRule;
      /// the faces the springs of @p s spread over with their bell-weighted
      /// quadrature; adds each spring's integrated bell [m^2] to @p total
      /// and the faces it touches to @p faces_per_spring (local cells)
      std::vector<SpringFaceRule>
      spring_face_rules(const scene::SpringSet    &s,
                        std::vector<double>       &total,
                        std::vector<unsigned int> &faces_per_spring) const;
      /// the points of the face rule @p q2 on face @p f of @p cell (n_sub x
      /// n_sub sub-squares) that may lie under a bell of @p s (see
      /// springs.cc), in their order
      dealii::Quadrature<2>
      near_a_station(const dealii::DoFHandler<3>::active_cell_iterator &cell,
                     unsigned int                                       f,
                     const dealii::Quadrature<2>                       &q2,
                     unsigned int                                       n_sub,
                     const scene::SpringSet &s) const;
      /// the Winkler layers of @p rules into @p K at @p k per spring, each
      /// spring's bell normalised by its @p total
      void
      assemble_spread_springs(const scene::SpringSet            &s,
                              const std::vector<SpringFaceRule> &rules,
                              const std::vector<double>         &total,
                              PETScMatrix                       &K,
                              double                             k);
      /// the springs with no face in reach (total 0) at the nearest
      /// unconstrained node, along the one acting component @p component;
      /// returns the largest station-node distance [m] and their number
      std::pair<double, unsigned int>
      add_nearest_node_springs(const scene::SpringSet    &s,
                               const std::vector<double> &total,
                               unsigned int               component,
                               PETScMatrix               &K,
                               double                     k);
    };

    /**
     * Twice the kinetic energy per unit angular frequency squared of the
     * mode re + i im of @p model in each body, at the point @p p:
     * e_b = int_{body b} rho_b(p) (|u_re|^2 + |u_im|^2) dV [kg m^2 per unit
     * modal amplitude squared], by Gauss quadrature of degree + 1 on the
     * cells of body b (material id b; n entries, n the largest id + 1), the
     * hanging-node values filled in. The e_b sum to re^T M(p) re +
     * im^T M(p) im of the assembled mass: the shares e_b / sum e_b use the
     * whole mass of the point, every body at its density.
     * @p re, @p im: locally owned vectors of n_dofs entries [m].
     */
    std::vector<double>
    kinetic_energy_by_body(const StructuralModel         &model,
                           const parameters::ScalarPoint &p,
                           const PETScVector             &re,
                           const PETScVector             &im);

    /**
     * kinetic_energy_by_body() of several modes in one pass over the cells
     * (the mapped quadrature of a cell computed once for all of them):
     * entry j for the mode @p re[j] + i @p im[j] at the point @p p[j].
     * Collective.
     * @throws std::logic_error if @p p, @p re and @p im differ in length.
     */
    std::vector<std::vector<double>>
    kinetic_energy_by_body(
      const StructuralModel                              &model,
      const std::vector<const parameters::ScalarPoint *> &p,
      const std::vector<const PETScVector *>             &re,
      const std::vector<const PETScVector *>             &im);

    /**
     * The support point [m] and the component (0, 1, 2) of every DoF of
     * @p model, from all cells of its mesh (every rank holds the whole
     * parallel::shared mesh, so every rank gets all n_dofs entries).
     */
    std::pair<std::vector<dealii::Point<3>>, std::vector<unsigned int>>
    dof_support_points(const StructuralModel &model);

    /**
     * n_dofs flags: whether a DoF lies on a boundary face with id @p id, from
     * all cells of the mesh (the same on every rank of a parallel::shared
     * mesh).
     */
    std::vector<bool>
    dofs_on_boundary(const StructuralModel     &model,
                     dealii::types::boundary_id id);

    /**
     * The area [m^2] of the boundary faces with id @p id (mapped geometry;
     * the same on every rank). Collective.
     */
    double
    boundary_area(const StructuralModel &model, dealii::types::boundary_id id);

    /**
     * Adds the scene's lumped masses to the lumped (diagonal) mass
     * @p lumped of the explicit dynamics (n_dofs entries, every rank, kg): a
     * face set's surface mass by the Gauss-Lobatto rule on the face nodes,
     * a point mass on its node's three DoFs. Collective.
     */
    void
    add_lumped_masses(const StructuralModel  &model,
                      dealii::Vector<double> &lumped);

    /** The DoFs the scene's holds fix (see held_dofs()). */
    struct HeldDofs
    {
      /// n_dofs flags: on a hold's faces, in one of its held components
      std::vector<bool> on_holds;
      /// per point hold of the scene: the DoF of its component nearest its
      /// point (the lowest index among equally near ones)
      std::vector<dealii::types::global_dof_index> point_held;
    };

    /**
     * The DoFs fixed by the holds and point holds of @p model's scene, from
     * all cells of the mesh (the same on every rank), given the support
     * points and components of dof_support_points(). The one place that
     * turns the scene's holds into DoFs for the contact systems and the
     * braking run.
     */
    HeldDofs
    held_dofs(const StructuralModel               &model,
              const std::vector<dealii::Point<3>> &points,
              const std::vector<unsigned int>     &component);

    /**
     * A complex displacement field of @p from (one value per DoF of
     * @p from, constraints already distributed, m) evaluated at the support
     * points of every DoF of @p to (the component of that DoF): the field
     * carried to another degree on the same mesh, for comparing mode shapes
     * between discretisations (complex MAC). Every rank returns all
     * to.n_dofs() values.
     * @throws std::runtime_error if the two models' meshes differ (cell
     * count or a cell centre more than 1e-9 m apart) or @p field has not
     * from.n_dofs() entries.
     */
    std::vector<std::complex<double>>
    transfer_field(const StructuralModel                   &from,
                   const std::vector<std::complex<double>> &field,
                   const StructuralModel                   &to);

    /**
     * The largest number of DoFs of any StructuralModel set up so far in
     * this process (0 before the first): the size a run's memory is set
     * against (its peak per DoF).
     */
    dealii::types::global_dof_index
    largest_model_size();

    /**
     * Re-stores @p matrix (n x n, rows @p owned on this process of
     * @p comm) on its nonzero entries only: the pattern shrinks to them, the
     * values stay. Entries that are exactly zero leave the pattern, except
     * the diagonal of a row without any other (one stored zero per empty
     * row, so that building the pattern stays linear in n).
     * @throws dealii::ExcMessage if PETSc cannot read a row.
     */
    void
    store_nonzeros_only(PETScMatrix            &matrix,
                        const dealii::IndexSet &owned,
                        MPI_Comm                comm);

    /**
     * Copies a (serial, one-process) PETSc matrix into a deal.II sparse
     * matrix with the same pattern (built into @p pattern), for the serial
     * direct and explicit solvers.
     */
    void
    copy_to_serial(const PETScMatrix            &source,
                   dealii::SparsityPattern      &pattern,
                   dealii::SparseMatrix<double> &target);

    /**
     * Sets the diagonal entry of every locally owned constrained row of
     * @p matrix to @p value (rows and columns are otherwise zero).
     */
    void
    set_constrained_diagonal(
      const dealii::AffineConstraints<double> &constraints,
      const dealii::IndexSet                  &locally_owned,
      const double                             value,
      PETScMatrix                             &matrix);
  } // namespace physics
} // namespace squeal

#endif
