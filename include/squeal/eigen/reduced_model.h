#ifndef squeal_eigen_reduced_model_h
#define squeal_eigen_reduced_model_h

/**
 * @file
 * Reduced-order complex eigenvalue analysis for parameter sweeps.
 *
 * Basis (verification.md A6): the real modes of the symmetric system
 * (K(p) without friction, M(p)) up to band_factor * f_max at a few sample
 * points p of the swept structural parameters, enriched with the static
 * responses K(p)^{-1} K_t Phi_p to the friction forces of those modes and
 * K(p)^{-1} K_n Phi_p to their interface forces (the Rayleigh damping
 * beta K_s is not proportional to K_s + K_n, so the damped shapes need it),
 * made
 * M-orthonormal (M at the reference point) by an eigen-decomposition
 * of the Gram matrix of the vectors scaled to unit M-norm (directions with
 * relative M-norm^2 below 1e-10 dropped).
 * All matrix parts of physics::MatrixParts are projected once; a sweep point
 * is then the dense 2r x 2r companion eigenproblem of
 * (lambda^2 M_r + lambda C_r + K_r) q = 0
 * (LAPACK dgeev). The residual of every reduced eigenpair on the full model,
 * ||(lambda^2 M + lambda C + K) V q|| / (|lambda|^2 ||M V q|| + |lambda|
 * ||C V q|| + ||K V q||), is evaluated exactly from precomputed Gram matrices
 * of the projected parts, at O(r^2) cost per eigenpair.
 */

#include <deal.II/base/conditional_ostream.h>

#include <squeal/eigen/qep_solver.h>
#include <squeal/physics/structural_model.h>

#include <Eigen/Dense>

#include <array>
#include <complex>
#include <vector>

namespace squeal
{
  namespace eigen
  {
    /** One eigenpair of the reduced problem: lambda [1/s], coordinates q. */
    struct ReducedEigenPair
    {
      std::complex<double> lambda;
      Eigen::VectorXcd     q; ///< length r, reduced coordinates
      double
        residual; ///< relative residual on the full model (-1: not computed)
    };

    /**
     * The reduced basis at one parameter point: V (locally owned rows x r,
     * M-orthonormal at the reference point), the products M(p) V, C(p) V,
     * K(p) V (local rows; empty when not asked for) and the projected r x r
     * matrices V^T M(p) V,
     * V^T C(p) V, V^T K(p) V (every rank holds them whole).
     */
    struct Projection
    {
      Eigen::MatrixXd V, MV, CV, KV, Mr, Cr, Kr;
      /// the modal damping C_modal = U diag(d) U^T (physics::MatrixParts::
      /// ModalDamping) of the reduced model at the point: U = M V Psi
      /// (local rows x m), d = 2 zeta omega [1/s] (m); empty without it
      Eigen::MatrixXd modal_U;
      Eigen::VectorXd modal_d; ///< see modal_U
    };

    /**
     * Modes of the symmetric problem (K_s, M) already found at some point
     * (by a full solve, eigen::solve_full()), which a basis sample with the
     * same M and K_s takes instead of solving again.
     */
    struct KnownSymmetricModes
    {
      /// the coefficients of M and K_s where the modes were found
      /// (physics::MatrixParts::coefficients(); one per part)
      physics::MatrixParts::Coefficients mass, symmetric_stiffness;
      /// every mode of (K_s, M) below this frequency is in @ref modes
      /// (counted by Sylvester inertia) [Hz]
      double top_hz = 0.;
      /// sorted by omega^2 [1/s^2], M-normalised, vectors of length n
      std::vector<UndampedMode> modes;
    };

    /** The projected model of a StructuralModel. */
    class ReducedModel
    {
    public:
      /**
       * Builds the basis and projects every matrix part.
       * @param samples the parameter points of the basis samples (only the
       *   structural parameters matter: pad modulus, stiffnesses, density)
       * @param band f_max * band_factor is the highest basis mode [Hz]
       * @param enrichment_depth number of friction enrichment levels per
       *   mode phi: (K^-1 K_t)^l phi for l = 1..depth (0: real modes only;
       *   1: the static response to the friction forces of verification A6;
       *   with depth >= 1 the response K^-1 K_n phi to the interface forces
       *   is added too)
       * @param known modes found before (or nullptr): a sample whose M and
       *   K_s coefficients equal theirs, and whose band they cover, takes
       *   them (those below f_max * band_factor) instead of an eigensolve
       * @throws std::runtime_error if an eigensolve or factorisation fails.
       */
      void
      build(const physics::MatrixParts                 &model,
            const std::vector<parameters::ScalarPoint> &samples,
            const BandOptions                          &band,
            const double                                band_factor,
            const unsigned int                          enrichment_depth,
            dealii::ConditionalOStream                 &pcout,
            const KnownSymmetricModes                  *known = nullptr);

      /**
       * Projects on the span of the given vectors (length n each; linearly
       * dependent ones are dropped) instead of building a basis.
       */
      void
      build_from_vectors(const physics::MatrixParts     &model,
                         const std::vector<PETScVector> &vectors,
                         const bool                      with_residuals = true);

      /**
       * Eigenpairs with Im lambda > 0 and frequency in [f_min, f_max] [Hz]
       * at the parameter point @p p, sorted by frequency.
       * @throws std::runtime_error if LAPACK fails.
       */
      std::vector<ReducedEigenPair>
      solve(const parameters::ScalarPoint &p,
            const double                   f_min,
            const double                   f_max) const;

      /**
       * The basis and its products at the point @p p, combined from the
       * parts' products A_k V on their rows, which the first call forms
       * (one sparse product per part, collective) and keeps until
       * release_products(); without @p with_products, Projection::MV, CV
       * and KV are left empty (three n x r blocks less, and no part's
       * product is formed or kept unless modal damping needs M V, which is
       * then formed part by part).
       * @throws std::runtime_error if @p p lacks a parameter of the model.
       */
      Projection
      projection(const parameters::ScalarPoint &p,
                 const bool                     with_products = true) const;

      /**
       * Frees the Gram matrices of the parts' products and the products
       * kept by projection() once no more sweep point is solved: expand(),
       * size() and projected_part() stay valid.
       * solve() and projection() throw std::logic_error until
       * build() or build_from_vectors() is called again.
       */
      void
      release_products();

      /** The full-model vector V q, real and imaginary parts (length n). */
      void
      expand(const Eigen::VectorXcd &q,
             physics::PETScVector   &re,
             physics::PETScVector   &im) const;

      /**
       * The full-model vectors V q_j of several coefficient vectors at
       * once, one pass over V for each 16 of them (a single expand() reads
       * V, n x r, once per mode): @p pairs[j].re and .im (length n,
       * re-initialised) for @p q[j] (length r), and .lambda from
       * @p lambda[j] [1/s].
       * @throws std::logic_error if @p lambda and @p q differ in length.
       */
      void
      expand(const std::vector<Eigen::VectorXcd>     &q,
             const std::vector<std::complex<double>> &lambda,
             std::vector<EigenPair>                  &pairs) const;

      /** The largest number of real modes of one basis sample. */
      unsigned int
      sample_mode_count() const
      {
        return largest_sample;
      }

      /** Number of basis vectors r. */
      unsigned int
      size() const
      {
        return V.cols();
      }

      /**
       * The projected part V^T A_k V of the model's part @p k (r x r, on
       * every rank; zero for a part that is empty), for callers that combine
       * the parts themselves (model updating's symmetric problem).
       */
      const Eigen::MatrixXd &
      projected_part(const unsigned int k) const
      {
        return Ar.at(k);
      }

    private:
      void
      project(const physics::MatrixParts &model,
              Eigen::MatrixXd            &B,
              const bool                  with_residuals);

      /// The mass matrix at the reference point, for M-orthonormality.
      void
      make_reference_mass(const physics::MatrixParts &model);

      physics::MatrixParts parts;  ///< non-owning
      PETScMatrix          M_ref;  ///< M at the reference
      std::vector<bool>    active; ///< part is non-zero
      bool has_residuals = false;  ///< G is complete for the current basis
      bool released      = false;  ///< see release_products()
      unsigned int    largest_sample = 0; ///< see sample_mode_count()
      Eigen::MatrixXd V;                  ///< n_local x r, M-orthonormal
      std::vector<Eigen::MatrixXd> Ar;    ///< V^T A_k V
      /// the local rows where A_k has a nonzero entry (ascending)
      std::vector<std::vector<int>>             rows;
      std::vector<std::vector<Eigen::MatrixXd>> G; ///< (A_k V)^T (A_l V)
      /// A_k V on rows[k] only (|rows[k]| x r), formed by the first
      /// projection() with products and kept for the next ones (a
      /// certification asks for one per point); empty until then
      mutable std::vector<Eigen::MatrixXd> W;
      dealii::IndexSet                     owned;
      MPI_Comm                             comm;
    };

  } // namespace eigen
} // namespace squeal

#endif
