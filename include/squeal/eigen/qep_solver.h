#ifndef squeal_eigen_qep_solver_h
#define squeal_eigen_qep_solver_h

/**
 * @file
 * Sparse eigensolvers on SLEPc, for PETSc built with real scalars.
 *
 * solve_undamped() finds every mode of K phi = omega^2 M phi up to a
 * frequency: one real shift sigma = -(2 pi f_t)^2 (f_t small, default
 * 100 Hz) with a MUMPS factorisation of K - sigma M (Cholesky for a
 * symmetric pencil, LU otherwise). A symmetric pencil's modes below the
 * frequency are counted first by Sylvester inertia and asked for at once
 * from the eigensolver that BandOptions::symmetric_solver names;
 * otherwise shift-and-invert Krylov-Schur is asked for more eigenvalues
 * until the farthest converged one lies beyond the wanted frequency. The
 * reduced basis (reduced_model.h) uses it on the symmetric problem. The full
 * solver of the damped quadratic problem, with its inertia count, is in
 * full_solver.h. A negative shift keeps K - sigma M regular when K is singular
 * (a free rigid-body motion).
 */

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <complex>
#include <string>
#include <vector>

namespace squeal
{
  namespace eigen
  {
    using PETScMatrix = dealii::PETScWrappers::MPI::SparseMatrix;
    using PETScVector = dealii::PETScWrappers::MPI::Vector;

    /** The band and accuracy of a solve. */
    struct BandOptions
    {
      double       f_min            = 900.;   ///< Hz
      double       f_max            = 20000.; ///< Hz
      double       target_frequency = 100.;   ///< Hz; shift tau = -2 pi f_t
      double       tolerance        = 1e-10;  ///< relative, SLEPc
      unsigned int initial_nev      = 40; ///< first guess of eigenvalues wanted
      /// Largest relative residual on the full damped model that the full
      /// solver accepts (eigen/full_solver.h).
      double residual_tolerance = 1e-10;
      /// The full solver's basis holds every mode of the symmetric problem
      /// up to this times f_max.
      double basis_factor = 1.5;
      /// Refinement rounds of the full solver before it gives up.
      unsigned int max_rounds = 20;
      /// The eigensolver of the symmetric problem (the full solver's basis
      /// and solve_undamped() of a symmetric pencil), each on a MUMPS
      /// Cholesky (LDL^T) factorisation of K - sigma M: `slepc`
      /// (Krylov-Schur), `arpack` (PARPACK's implicitly restarted Lanczos
      /// through deal.II's PArpackSolver), both shift-and-invert, or
      /// `block` (thick-restart block Lanczos on the shift-and-invert
      /// operator, blocks of up to 64 vectors, one pass through the
      /// factors per block), or `auto` (`block`).
      std::string symmetric_solver = "auto";
      /// The full solver keeps the products M V, C V, K V of its subspace
      /// V (true: four n x r blocks, no sparse product to test a Ritz
      /// pair) or forms them when needed (false: one block).
      bool store_products = true;
    };

    /**
     * One eigenpair lambda, phi = re + i im of (lambda^2 M + lambda C + K)
     * phi = 0; lambda in 1/s (Im lambda = omega in rad/s), phi of length n.
     */
    struct EigenPair
    {
      std::complex<double> lambda;
      PETScVector          re;
      PETScVector          im;
      double               residual = 0.; ///< relative, on the full model
    };

    /** One eigenpair of K phi = omega^2 M phi (omega^2 in 1/s^2). */
    struct UndampedMode
    {
      std::complex<double> omega2;
      PETScVector          re;
      /// zero unless omega2 is complex; empty (size 0) for the modes of a
      /// symmetric pencil, which are real
      PETScVector im;
    };

    /**
     * Every eigenpair of K phi = omega^2 M phi with Re omega^2 below
     * (factor f_max 2 pi)^2, sorted by Re omega^2 (rigid modes included).
     * When @p symmetric: GHEP, exactly as many modes as
     * count_eigenvalues_below() gives, by BandOptions::symmetric_solver
     * (shift-and-invert or preconditioned at sigma = -(2 pi f_t)^2 with a
     * MUMPS Cholesky factorisation; BandOptions::initial_nev is not used),
     * each purified by one step of inverse iteration and M-normalised.
     * Otherwise GNHEP by SLEPc's Krylov-Schur, shift-and-invert with MUMPS
     * LU; of a complex pair only the member with Im omega^2 > 0 is
     * returned. Matrices n x n, M in kg, K in N/m.
     * @throws std::runtime_error if SLEPc or PARPACK fails, returns fewer
     * or more modes than the inertia count, or cannot cover the band.
     */
    std::vector<UndampedMode>
    solve_undamped(const PETScMatrix          &M,
                   const PETScMatrix          &K,
                   const BandOptions          &options,
                   const double                factor,
                   const bool                  symmetric,
                   dealii::ConditionalOStream &pcout);

    /**
     * A sparse LU or Cholesky factorisation (MUMPS through PETSc) kept for
     * repeated solves with one matrix.
     */
    class DirectSolver
    {
    public:
      /**
       * Factorises @p A (n x n): LU, or when @p symmetric MUMPS' symmetric
       * LDL^T (A symmetric, positive definite or indefinite: MUMPS SYM = 2,
       * PETSc's default for a matrix not flagged SPD).
       * @throws std::runtime_error on failure.
       */
      explicit DirectSolver(const PETScMatrix &A, const bool symmetric = false);
      ~DirectSolver();
      DirectSolver(const DirectSolver &) = delete;
      DirectSolver &
      operator=(const DirectSolver &) = delete;
      /** x = A^{-1} b; x must have A's row layout. */
      void
      solve(const PETScVector &b, PETScVector &x) const;
      /** The factorised PETSc KSP (a KSP cast to void*), for block solves. */
      void *
      handle() const
      {
        return ksp;
      }

    private:
      void *ksp;
    };
  } // namespace eigen
} // namespace squeal

#endif
