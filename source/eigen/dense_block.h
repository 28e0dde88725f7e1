// Dense blocks of vectors over the locally owned rows of a distributed
// PETSc layout, shared by the reduced model and the full solver: products
// with sparse matrices, sums over the ranks, M-orthonormalisation and the
// dense companion eigenproblem of a projected quadratic problem.

#ifndef squeal_eigen_dense_block_h
#define squeal_eigen_dense_block_h

#include <deal.II/base/index_set.h>

#include <squeal/eigen/qep_solver.h>
#include <squeal/physics/structural_model.h>

#include <Eigen/Dense>

#include <complex>
#include <memory>
#include <vector>

namespace squeal
{
  namespace eigen
  {
    namespace internal
    {
      /** A := sum of A over the ranks of @p comm. */
      void
      sum_over_ranks(Eigen::MatrixXd &A, MPI_Comm comm);

      /**
       * The 2-norms of the columns of a dense n x m block of which @p B
       * holds the locally owned rows (summed over the ranks of @p comm).
       */
      Eigen::VectorXd
      column_norms(const Eigen::MatrixXd &B, MPI_Comm comm);

      /**
       * A B for a sparse n x n matrix A and the locally owned rows of a
       * dense n x m block B, as the local rows of the result.
       * @throws std::runtime_error if PETSc fails.
       */
      Eigen::MatrixXd
      multiply(const PETScMatrix &A, Eigen::Ref<const Eigen::MatrixXd> B);

      /** The same for a PETSc AIJ matrix (MATSEQAIJ or MATMPIAIJ). */
      Eigen::MatrixXd
      multiply(Mat A, Eigen::Ref<const Eigen::MatrixXd> B);

      /**
       * R += a A B (R := A B for @p a = 0) for a sparse n x n PETSc AIJ
       * matrix A and the locally owned rows of dense n x m blocks B and R,
       * without a temporary n x m block.
       * @throws std::runtime_error if PETSc fails.
       */
      void
      multiply_add(Mat                               A,
                   double                            a,
                   Eigen::Ref<const Eigen::MatrixXd> B,
                   Eigen::Ref<Eigen::MatrixXd>       R);

      /** A dense block stored row by row. */
      using RowMatrix =
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

      /**
       * Chosen rows of A V for a sparse n x n matrix A and the locally
       * owned rows of a dense n x r block V stored row by row, without
       * forming A V: a row of the product reads A's row and the rows of V
       * it names, so that the products of a model's parts can be formed
       * and used a block of rows at a time (the reduced basis' projection
       * holds V and one block of rows per part, not A_k V).
       */
      class RowProduct
      {
      public:
        /**
         * Gathers V's rows that A's off-process columns name (MPIAIJ;
         * collective). @p V must outlive the object.
         * @throws std::runtime_error if A is not a PETSc AIJ matrix or
         * PETSc fails.
         */
        RowProduct(const PETScMatrix &A, const RowMatrix &V);
        ~RowProduct();
        RowProduct(const RowProduct &) = delete;
        RowProduct &
        operator=(const RowProduct &) = delete;

        /**
         * (A V)(rows, :): |rows| x r, @p rows local row indices (not
         * collective).
         */
        RowMatrix
        rows(const std::vector<int> &rows) const;

      private:
        struct Data;
        std::unique_ptr<Data> data;
      };

      /**
       * B := B T in place, a block of rows at a time (no second n x m
       * block): B the locally owned rows of an n x m block, T m x k with
       * k <= m; B keeps its first k columns' storage.
       * @throws std::logic_error if T's size does not fit.
       */
      void
      multiply_in_place(Eigen::MatrixXd &B, const Eigen::MatrixXd &T);

      /**
       * The same into the first k columns of @p B, whose size stays
       * (B n x m, a view such as a block's leading columns; T m x k).
       * @throws std::logic_error if T's size does not fit.
       */
      void
      multiply_into_leading_columns(Eigen::Ref<Eigen::MatrixXd> B,
                                    const Eigen::MatrixXd      &T);

      /**
       * Products of a model's parts with dense blocks: sum_k c_k A_k B for
       * several coefficient vectors c at once (M(p) B, C(p) B and K(p) B of
       * a point p without forming M(p), C(p) or K(p)), one pass over each
       * part's nonzero entries. Each part's rows that hold a nonzero value
       * are copied once, their nonzeros only (a part on the common pattern
       * stores zeros outside its body), with the ghost columns of all
       * parts in one numbering, so that a block's ghost rows are gathered
       * once for every part. The cost of a product is about that of M(p)
       * and K_s(p) on their nonzeros, against M(p), C(p) and K(p) for
       * three products (C(p) = alpha M + beta K_s on the whole pattern).
       * Memory: 12 bytes per nonzero of the parts (twice for a friction
       * part).
       */
      class PartsProduct
      {
      public:
        /**
         * The parts of @p model, copied (the model may change afterwards).
         * @throws std::runtime_error if a part is not a PETSc AIJ matrix or
         * PETSc fails.
         */
        explicit PartsProduct(const physics::MatrixParts &model);
        ~PartsProduct();
        PartsProduct(const PartsProduct &) = delete;
        PartsProduct &
        operator=(const PartsProduct &) = delete;

        /**
         * sum_k c[i][k] A_k B for each coefficient vector c[i] (one per
         * part), for the locally owned rows of a dense n x m block B, as
         * the local rows of n x m results (collective); with
         * @p transposed, sum_k c[i][k] A_k^T B (the friction parts, the
         * only ones that are not symmetric, are kept transposed too).
         */
        std::vector<Eigen::MatrixXd>
        multiply(
          const std::vector<const physics::MatrixParts::Coefficients *> &c,
          Eigen::Ref<const Eigen::MatrixXd>                              B,
          const bool transposed = false) const;

        /** ((A - A^T) N)(rows, :) for A = sum_k c[k] A_k (skew_times()). */
        struct Skew
        {
          /// false when every part with c[k] != 0 is symmetric (then A - A^T =
          /// 0)
          bool any = false;
          /// the local rows where (A - A^T) N can be nonzero, ascending
          std::vector<int> rows;
          /// ((A - A^T) N)(rows, :), rows.size() x m
          Eigen::MatrixXd values;
        };

        /**
         * (A - A^T) N on the rows of the parts that are not symmetric (the
         * friction parts: their rows and columns; every other kind of part
         * is symmetric as physics::MatrixParts assembles it, and taken so) with
         * c[k] != 0, for A = sum_k c[k] A_k and the locally owned rows of an n
         * x m block N (collective; the same Skew::any on every rank).
         */
        Skew
        skew_times(const physics::MatrixParts::Coefficients &c,
                   Eigen::Ref<const Eigen::MatrixXd>         N) const;

      private:
        struct Data;
        std::unique_ptr<Data> data;
      };

      /**
       * The locally owned rows of the sparse matrix @p A that hold a
       * nonzero value, as indices into the local range (ascending).
       * @throws std::runtime_error if PETSc fails.
       */
      std::vector<int>
      nonzero_rows(const PETScMatrix &A);

      /**
       * The positions in @p x and in @p y (both ascending) of the values
       * they have in common, in ascending order of the values.
       */
      void
      common_positions(const std::vector<int> &x,
                       const std::vector<int> &y,
                       std::vector<int>       &in_x,
                       std::vector<int>       &in_y);

      /**
       * X = A^-1 B with a factorised solver for the locally owned rows of a
       * dense n x m block B (one multi-right-hand-side solve).
       * @throws std::runtime_error if PETSc fails.
       */
      Eigen::MatrixXd
      solve_block(void *ksp, const PETScMatrix &A, const Eigen::MatrixXd &B);

      /**
       * The same into @p X, a block of B's size whose columns are adjacent
       * in memory (a matrix or a range of its columns, not @p B).
       * @throws std::logic_error if X's size differs from B's or X's
       * columns are not adjacent; std::runtime_error if PETSc fails.
       */
      void
      solve_block(void                             *ksp,
                  const PETScMatrix                &A,
                  Eigen::Ref<const Eigen::MatrixXd> B,
                  Eigen::Ref<Eigen::MatrixXd>       X);

      /**
       * T such that B T is M-orthonormal, from the Gram matrix B^T M B:
       * every vector is first scaled to unit M-norm, then directions with
       * relative M-norm^2 below 1e-10 are dropped.
       */
      Eigen::MatrixXd
      orthonormalising_transform(Eigen::MatrixXd gram);

      /**
       * Throws std::runtime_error "<who>: PETSc/SLEPc call failed: <what>
       * (error code <ierr>)" when @p ierr is not 0.
       */
      void
      check_petsc(const int ierr, const char *who, const char *what);

      /**
       * A += a B (n x n each): on A's pattern when B stores as many entries
       * (the combinations of one model's parts all copy the first part's
       * pattern) or fewer (B on its own nonzeros within A's pattern, as the
       * full solver's mass matrix), PETSc's MatAXPY with
       * SAME_NONZERO_PATTERN or SUBSET_NONZERO_PATTERN; else with a new
       * pattern. deal.II's add() always builds a new pattern (7 s for
       * one K - sigma M at degree 4 on the TriboBrake).
       * @throws std::runtime_error if PETSc fails.
       */
      void
      add_scaled(PETScMatrix &A, double a, const PETScMatrix &B);

      /**
       * Makes the PETSc KSP @p ksp (cast to void*) a direct solve: one
       * application (KSPPREONLY) of a MUMPS factorisation, Cholesky when
       * @p cholesky (a symmetric matrix) else LU.
       * @throws std::runtime_error if PETSc fails.
       */
      void
      use_mumps(void *ksp, const bool cholesky);

      /**
       * Makes the SLEPc spectral transformation @p st (an ST cast to
       * void*) shift-and-invert with a direct MUMPS factorisation, Cholesky
       * for a symmetric pencil (@p cholesky) else LU, applied once per
       * iteration (KSPPREONLY). Call it after EPSSetOperators: A - sigma B
       * is then formed on A's pattern when B's is the same or within it
       * (B storing as many or fewer entries).
       * @return its KSP (cast to void*), which the ST owns
       * @throws std::runtime_error if SLEPc or PETSc fails.
       */
      void *
      shift_invert_with_mumps(void *st, const bool cholesky);

      /**
       * The locally owned entries of @p v, in the order of @p owned (the
       * contiguous range PETSc owns on this rank).
       * @throws std::runtime_error if @p v does not own @p owned's size.
       */
      Eigen::VectorXd
      local_part(const PETScVector &v, const dealii::IndexSet &owned);

      /**
       * Sets the locally owned entries of @p v (already laid out) to @p x,
       * in the order of its owned range; no communication.
       * @throws std::runtime_error if the sizes differ.
       */
      void
      set_local_part(PETScVector &v, const Eigen::VectorXd &x);

      /** One eigenpair lambda [1/s], coordinates q of a projected problem. */
      struct ProjectedPair
      {
        std::complex<double> lambda;
        Eigen::VectorXcd     q; ///< unit 2-norm
      };

      /**
       * The eigenpairs with Im lambda > 0 and Im lambda / 2 pi in
       * [f_min, f_max] [Hz] of (lambda^2 M + lambda C + K) q = 0, r x r
       * dense, through the 2r x 2r companion matrix (LAPACK dgeev), sorted
       * by frequency. With a real @p shift tau != 0 [1/s] the companion is
       * that of the reversed problem in mu = 1 / (lambda - tau),
       * mu^2 P(tau) + mu (C + 2 tau M) + M = 0, P(tau) = tau^2 M + tau C + K:
       * the eigenvalues nearest tau are then the largest, and are computed
       * to a relative accuracy that the high frequencies of the subspace do
       * not spoil. With @p f_sought > 0 [Hz], a decaying pair whose
       * modulus |lambda| / 2 pi (its undamped frequency) exceeds f_sought
       * is left out: a heavily damped (zeta > sqrt(1 - (f_max /
       * f_sought)^2)) mode from above the sought modes whose small
       * Im lambda falls in the band. @throws std::runtime_error if LAPACK
       * fails or M (or P(tau)) is singular.
       */
      std::vector<ProjectedPair>
      projected_eigenpairs(const Eigen::MatrixXd &M,
                           const Eigen::MatrixXd &C,
                           const Eigen::MatrixXd &K,
                           const double           f_min,
                           const double           f_max,
                           const double           shift    = 0.,
                           const double           f_sought = 0.);

      /**
       * Modal damping on a subspace V (physics::MatrixParts::ModalDamping):
       * Psi (r x m) are the Ritz modes of (Ksr, Mr) = (V^T K_s V, V^T M V)
       * (r x r, K_s the stiffness without friction), Mr-normalised, whose
       * coefficient d_i = 2 zeta(f_i) omega_i [1/s] is not 0, and
       * B = Psi diag(d) Psi^T Mr (r x r): the modal damping
       * C = (M V Psi) diag(d) (M V Psi)^T gives C V = (M V) B and
       * V^T C V = Mr B.
       */
      struct SubspaceModalDamping
      {
        Eigen::MatrixXd Psi; ///< r x m
        Eigen::VectorXd d;   ///< m, 2 zeta omega [1/s]
        Eigen::MatrixXd B;   ///< r x r
      };

      /**
       * The modal damping of @p modal on the subspace of @p Mr, @p Ksr
       * (see SubspaceModalDamping).
       * @throws std::runtime_error if Mr is not positive definite.
       */
      SubspaceModalDamping
      subspace_modal_damping(const Eigen::MatrixXd                    &Mr,
                             const Eigen::MatrixXd                    &Ksr,
                             const physics::MatrixParts::ModalDamping &modal);
    } // namespace internal
  }   // namespace eigen
} // namespace squeal

#endif
