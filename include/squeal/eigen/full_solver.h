#ifndef squeal_eigen_full_solver_h
#define squeal_eigen_full_solver_h

/**
 * @file
 * The full solver of the complex eigenvalue analysis: every eigenpair of
 * (lambda^2 M + lambda C + K) phi = 0 with Im lambda / 2 pi in a band, with
 * a count that proves no mode of the symmetric problem is left out and a
 * residual on the full model below a stated tolerance for each pair.
 *
 * 1. Count. K_s = K_structural + K_n (every stiffness part but friction) and
 *    M are symmetric, so the number of eigenvalues omega^2 of
 *    K_s phi = omega^2 M phi below sigma equals the number of negative
 *    pivots of the LDL^T factorisation of K_s - sigma M (Sylvester's law
 *    of inertia; MUMPS through PETSc MatGetInertia). It is taken at
 *    (2 pi f_min)^2, (2 pi f_max)^2 and (2 pi b f_max)^2 (b: the basis
 *    factor, default 1.5).
 * 2. Symmetric modes. The eigensolver of BandOptions::symmetric_solver
 *    (by default thick-restart block Lanczos; SLEPc Krylov-Schur or
 *    PARPACK on request) on the symmetric-definite pencil with
 *    shift-and-invert at -(2 pi f_t)^2 (MUMPS Cholesky) is asked for
 *    exactly as many eigenpairs as the count of step 1 puts below
 *    (2 pi b f_max)^2; the solve must return every one of them, or it fails.
 * 3. Projection. The damped friction-coupled problem is projected
 *    (Rayleigh-Ritz) on these modes Phi and their static corrections
 *    P^-1 [C Phi, (K - K_s) Phi], P = K_s + (2 pi f_t)^2 M (one block solve
 *    with the factorisation of step 2), M-orthonormalised; the projected
 *    quadratic problem is solved densely (2r x 2r companion, LAPACK dgeev).
 *    A decaying pair whose modulus |lambda| / 2 pi lies above b f_max is
 *    not sought even when its Im lambda falls in the band: a mode from
 *    above the basis' modes damped beyond zeta = sqrt(1 - 1 / b^2).
 * 4. Refinement (block Davidson). The residual r of every Ritz pair in the
 *    band whose relative residual
 *    ||r|| / (|lambda|^2 ||M x|| + |lambda| ||C x|| + ||K x||) exceeds the
 *    tolerance gives two new directions, the real and imaginary parts of
 *    (P^-1 + s P^-1 M P^-1) r with s = (2 pi f_t)^2 - lambda^2: the first
 *    two terms of the Neumann series of (K_s + lambda^2 M)^-1 = (P - s M)^-1,
 *    the pair's inverse iteration without friction and damping (the error
 *    left in the modes above the basis falls by (omega / omega_i)^4 a
 *    round; with P^-1 r alone, by (omega / omega_i)^2: on the TriboBrake
 *    5 rounds instead of 8), until every pair is below it, the round
 *    limit is reached, or no pair above it has halved its residual over
 *    two rounds (each pair against the one of nearest eigenvalue, within
 *    1e-6 of |lambda|, two rounds before; a pair new to the band keeps the
 *    rounds going): stalled at the products' rounding floor, of the order of
 *    eps (omega_max / omega)^2 for a mode omega on a mesh whose highest
 *    frequency is omega_max: 3.4e-10 for the 336 Hz mode of the 15 mm
 *    brake at degree 3 after 2 rounds, 3.6e-10 after 20. With
 *    BandOptions::store_products (the default) the residuals come from the
 *    stored products M V, C V, K V of the subspace V, so a round's sparse
 *    work is the new block's products only; without, only V is kept (a
 *    quarter of the memory) and the Ritz vectors' products are formed
 *    directly, whose rounding floor (up to 1e-10 relative for the lowest
 *    modes of the brakes measured) can cost more rounds.
 *
 * At an undamped frictionless point (every damping coefficient 0, no modal
 * damping, no friction part: C = 0 and K = K_s) the eigenvalues are
 * +-i omega of the symmetric modes, so b is taken as 1 (the basis is the
 * band's modes, counted at f_min and f_max) and step 3 adds no static
 * corrections; steps 3 and 4 still check every pair's residual.
 *
 * The products of the sparse matrices with the dense blocks are Eigen's
 * row-major sparse x dense product on PETSc's AIJ arrays
 * (eigen::internal::multiply).
 *
 * The returned pairs carry their residuals; the solver does not throw when
 * some stay above the tolerance (FullSolveReport::above_tolerance says how
 * many): the analysis decides (analyses/cea.h).
 */

#include <deal.II/base/conditional_ostream.h>

#include <squeal/eigen/qep_solver.h>
#include <squeal/eigen/reduced_model.h>
#include <squeal/parameters/parameters.h>
#include <squeal/physics/structural_model.h>

#include <memory>
#include <vector>

namespace squeal
{
  namespace eigen
  {
    namespace internal
    {
      class PartsProduct;
    }

    /** What a full solve counted, found and how far it converged. */
    struct FullSolveReport
    {
      /// modes of (K_s, M) with frequency in [f_min, f_max], by inertia
      unsigned int symmetric_in_band = 0;
      /// modes of (K_s, M) up to basis_factor f_max, by inertia; every
      /// one of them is in the basis
      unsigned int symmetric_in_basis = 0;
      unsigned int basis_size         = 0; ///< r, final subspace dimension
      unsigned int rounds             = 0; ///< refinement rounds run
      /// the rounds stopped because no pair above the tolerance had
      /// halved its residual over the last two (their rounding floor)
      bool         stalled          = false;
      double       largest_residual = 0; ///< relative, over the pairs
      unsigned int above_tolerance  = 0; ///< pairs above the tolerance
      double       seconds          = 0; ///< wall time of the solve [s]
      /// wall time of the refinement rounds [s] in the projected (dense)
      /// eigenproblems, the residuals on the full model, the block solves
      /// of the corrections and the subspace's growth (M-orthogonalisation
      /// and projection of the new vectors)
      double seconds_projected = 0, seconds_residuals = 0, seconds_solves = 0,
             seconds_growth = 0;
      /// peak resident memory of the processes so far (VmHWM summed over
      /// the ranks) [MB]: an upper bound of the solve's memory
      double peak_memory_mb = 0;
    };

    /**
     * The number of eigenvalues omega^2 < sigma of K x = omega^2 M x for
     * each sigma of @p sigmas [1/s^2], by Sylvester's law of inertia: the
     * negative pivots of an LDL^T factorisation of K - sigma M (MUMPS,
     * one symbolic factorisation for all shifts). K, M symmetric n x n,
     * M positive semi-definite. Serial and MPI.
     * @throws std::runtime_error if the factorisation fails or K - sigma M
     *   is singular (sigma an eigenvalue).
     */
    std::vector<unsigned int>
    count_eigenvalues_below(const PETScMatrix         &K,
                            const PETScMatrix         &M,
                            const std::vector<double> &sigmas);

    /**
     * Every eigenpair of (lambda^2 M + lambda C + K) phi = 0 with
     * Im lambda / 2 pi in [band.f_min, band.f_max] [Hz] at the parameter
     * point @p p, sorted by frequency, each with its relative residual on
     * the full model (see the file's description for the method; counts
     * and residuals go to @p report when given). lambda in 1/s. When
     * @p symmetric is given, the modes of (K_s, M) the basis was built on
     * (every one below its top frequency) are copied into it, for a
     * reduced basis sample with the same M and K_s.
     * @throws std::runtime_error if a factorisation or an eigensolve
     *   fails, or the symmetric solve returns fewer modes than its
     *   inertia count.
     */
    std::vector<EigenPair>
    solve_full(const physics::MatrixParts    &model,
               const parameters::ScalarPoint &p,
               const BandOptions             &band,
               dealii::ConditionalOStream    &pcout,
               FullSolveReport               *report    = nullptr,
               KnownSymmetricModes           *symmetric = nullptr);

    /** Where solve_on_iterates() spent its time. */
    struct IterateReport
    {
      unsigned int factorisations  = 0;  ///< one per shift
      unsigned int basis_size      = 0;  ///< M-orthonormal directions kept
      double factorisation_seconds = 0.; ///< MUMPS LDL^T of K_s - w^2 M [s]
      double solve_seconds         = 0.; ///< block solves and products [s]
      double projected_seconds     = 0.; ///< dense projected problem, residuals
      double seconds               = 0.; ///< the whole call [s]
    };

    /**
     * The eigenpairs in the band of (lambda^2 M + lambda C + K) phi = 0 at
     * @p p by Rayleigh-Ritz on the span of given vectors and of their
     * shift-and-invert iterates (A_i^-1 M)^l x for l = 1..@p levels, with
     * A_i = K_s(p) - (2 pi f_i)^2 M(p) and f_i the centre (on a log scale)
     * of the sub-band, at most an octave wide, that holds the vector's
     * @p frequency [Hz]: one MUMPS LDL^T factorisation per sub-band (A_i is
     * indefinite) and one multi-right-hand-side solve per level (the
     * subspace iteration of K.-J. Bathe, Finite Element Procedures, 1996,
     * Sec. 11.6, with a shift per octave). The projected quadratic problem
     * is solved as in solve_full(). Used to estimate the discretisation
     * error at a higher degree from the modes of the lower one carried to
     * it (the spaces are nested, so the start vectors alone reproduce the
     * lower degree's eigenvalues; the iterates add the richer space's
     * correction). The Ritz values of a subspace lie short of the exact
     * ones; each returned pair carries its relative residual on the full
     * model (EigenPair::residual). @p start: vectors of the model's size
     * (n), one @p frequency each. Collective.
     * @throws std::runtime_error if a factorisation or a PETSc call fails;
     *   std::logic_error if the sizes differ.
     */
    std::vector<EigenPair>
    solve_on_iterates(const physics::MatrixParts     &model,
                      const parameters::ScalarPoint  &p,
                      const BandOptions              &band,
                      const std::vector<PETScVector> &start,
                      const std::vector<double>      &frequency,
                      unsigned int                    levels,
                      IterateReport                  *report = nullptr);

    /** One eigenpair refined on the full model by PairRefiner. */
    struct RefinedPair
    {
      std::complex<double> lambda;   ///< 1/s
      double               residual; ///< relative, on the full model
      unsigned int         rounds;   ///< Davidson rounds it took
    };

    /**
     * Certifies approximate eigenpairs of a reduced sweep on the full model:
     * each pair (lambda, V q) of the reduced basis V is refined until its
     * relative residual on the full damped problem,
     * ||(lambda^2 M + lambda C + K) x|| / (|lambda|^2 ||M x|| +
     * |lambda| ||C x|| + ||K x||), is below BandOptions::residual_tolerance
     * (or BandOptions::max_rounds are spent).
     *
     * Method (Davidson with a fixed preconditioner, as in solve_full()'s
     * refinement): the subspace starts as V of
     * ReducedModel::projection() (with its products unless
     * BandOptions::store_products is false); every round adds P^-1 [Re r, Im r]
     * for each pair's residual r, P = K_s(p) + (2 pi f_t)^2 M(p) (MUMPS
     * Cholesky, factorised once for all points with the same M and K_s:
     * a sweep of the friction coefficient shares it), and each pair
     * follows its eigenvalue of the projected problem by nonlinear inverse
     * iteration from its previous value (A. Ruhe, SIAM J. Numer. Anal. 10
     * (1973) 674-689, Sec. 3: T(mu) z = T'(mu) y, mu <- mu - 1 / u^H z,
     * y <- z / u^H z; quadratic convergence for a simple eigenvalue), so no
     * dense eigenproblem of the whole subspace is solved. Collective on
     * the model's communicator.
     */
    class PairRefiner
    {
    public:
      /** @p model must outlive the refiner. */
      PairRefiner(const physics::MatrixParts &model, const BandOptions &band);
      ~PairRefiner();

      /**
       * Refines the pairs (@p lambda [1/s], @p q: coordinates in the basis
       * of @p start, one per pair) at the point @p p. The subspace starts
       * as @p start (and its products with BandOptions::store_products),
       * taken over without a copy (pass ReducedModel::projection()
       * directly or std::move it).
       * @throws std::logic_error if products are to be stored and
       * @p start has none.
       * @return one RefinedPair per input pair, in their order
       * @throws std::runtime_error if a factorisation fails.
       */
      std::vector<RefinedPair>
      refine(const parameters::ScalarPoint           &p,
             Projection                               start,
             const std::vector<std::complex<double>> &lambda,
             const std::vector<Eigen::VectorXcd>     &q);

      /** Factorisations of P so far. */
      unsigned int
      factorisations() const
      {
        return n_factorisations;
      }

      /** Wall time spent factorising P so far [s]. */
      double
      factorisation_seconds() const
      {
        return seconds_factorising;
      }

    private:
      const physics::MatrixParts   &model;
      BandOptions                   band;
      std::vector<double>           key; ///< M and K_s coefficients of P
      PETScMatrix                   P;
      std::unique_ptr<DirectSolver> solver;
      /// the model's parts for every product M N, C N, K N and C^T N,
      /// K^T N (M, C and K are never formed)
      std::unique_ptr<const internal::PartsProduct> parts;
      unsigned int                                  n_factorisations    = 0;
      double                                        seconds_factorising = 0.;
    };
  } // namespace eigen
} // namespace squeal

#endif
