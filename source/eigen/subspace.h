// The Rayleigh-Ritz subspace of the damped friction-coupled problem, shared
// by the full solver, its solve on iterates and the pair refiner: an
// M-orthonormal block V over the locally owned rows, the projected
// matrices V^T A V as V grows, and the Ritz pairs' residuals on the full
// model.

#ifndef squeal_eigen_subspace_h
#define squeal_eigen_subspace_h

#include <squeal/eigen/full_solver.h>
#include <squeal/physics/structural_model.h>

#include <Eigen/Dense>

#include "dense_block.h"

#include <array>
#include <memory>
#include <vector>

namespace squeal
{
  namespace eigen
  {
    namespace internal
    {
      /**
       * M, C, K and K_s of a model at a point (n x n each); M on its
       * nonzeros only (a third of the common pattern: no coupling between
       * displacement components), which every M product of the
       * eigensolvers and the subspace reads. With parts, the model's
       * parts for the products C N and K N (PartsProduct) instead of C
       * and K, which stay empty (for a subspace with stored products,
       * which never needs their transposes).
       * @throws std::runtime_error if PETSc fails.
       */
      struct PointMatrices
      {
        PETScMatrix                         M, C, K, K_s;
        physics::MatrixParts::Combination   coefficients;
        std::unique_ptr<const PartsProduct> parts;

        PointMatrices(const physics::MatrixParts    &model,
                      const parameters::ScalarPoint &point,
                      const bool                     with_parts);
      };

      /** The transpose of a sparse matrix, owned (freed with it). */
      struct Transposed
      {
        Mat t = nullptr;

        /** @throws std::runtime_error if PETSc fails. */
        explicit Transposed(const PETScMatrix &A);
        ~Transposed();
        Transposed(const Transposed &) = delete;
        Transposed &
        operator=(const Transposed &) = delete;
      };

      /**
       * The subspace V of a Rayleigh-Ritz projection of
       * (lambda^2 M + lambda C + K) x = 0 (local rows of an n x r block,
       * V M-orthonormal) and the projected r x r matrices V^T A V. With
       * stored products, M V, C V and K V are kept too (four n x r blocks);
       * otherwise a product is formed when a block is appended or a Ritz
       * vector is tested (one block).
       */
      struct Subspace
      {
        const PETScMatrix &M, &C, &K;
        MPI_Comm           comm;
        bool               stored;
        /**
         * V and, with stored products, M V, C V and K V (n x r each): views
         * of the leading columns of #storage.
         */
        Eigen::Map<Eigen::MatrixXd> V{nullptr, 0, 0}, WM{nullptr, 0, 0},
          WC{nullptr, 0, 0}, WK{nullptr, 0, 0};
        /** The projected r x r matrices V^T M V, V^T C V, V^T K V. */
        Eigen::MatrixXd Mr, Cr, Kr;
        /**
         * The memory behind V, WM, WC and WK, in this order: room for
         * twice the columns in use whenever a block outgrows it, so that
         * the blocks grow in place (columns never written take no
         * physical memory) and are copied a logarithmic number of times.
         */
        std::array<Eigen::MatrixXd, 4> storage;
        /** The modal damping U diag(d) U^T once fixed (local rows of U). */
        Eigen::MatrixXd U;
        Eigen::VectorXd d;
        /**
         * Without stored products: C^T and K^T, made when the subspace
         * first grows (the new rows of the projection are
         * N^T A V = (A^T N)^T V).
         */
        std::unique_ptr<const Transposed> Ct, Kt;
        /**
         * With parts (use_parts()): C N and K N of new blocks and Ritz
         * vectors from the model's parts and the point's coefficients, one
         * pass over the parts instead of products with C and K, which
         * are then not read (#Ct, #Kt are not made: append() forms the
         * projection's new rows from the parts, see there).
         */
        const PartsProduct               *parts = nullptr;
        physics::MatrixParts::Combination coefficients;
        /** M N from #parts too (M is then not read at all). */
        bool mass_from_parts = false;

        /** An empty subspace of the model at a point. */
        Subspace(const PointMatrices &A, const bool stored);

        /**
         * The subspace of a reduced basis (with its products if stored),
         * its vectors distributed over @p comm.
         */
        Subspace(const PETScMatrix &M,
                 const PETScMatrix &C,
                 const PETScMatrix &K,
                 Projection       &&start,
                 const bool         stored,
                 MPI_Comm           comm);

        /** Not copied or moved: V, WM, WC and WK point into #storage. */
        Subspace(const Subspace &) = delete;
        Subspace &
        operator=(const Subspace &) = delete;

        /**
         * C N and K N from @p p with the point's coefficients @p c (see
         * #parts); @p p must outlive the subspace.
         */
        void
        use_parts(const PartsProduct                      &p,
                  const physics::MatrixParts::Combination &c,
                  const bool                               mass = false);

        /** M N (n x m for the local rows of an n x m N). */
        Eigen::MatrixXd
        mass_times(Eigen::Ref<const Eigen::MatrixXd> N) const;

        /** CN += U diag(d) U^T N: the modal damping's part of C N. */
        void
        add_modal_damping(Eigen::MatrixXd                  &CN,
                          Eigen::Ref<const Eigen::MatrixXd> N) const;

        /** C N and K N (n x m each for the local rows of an n x m N). */
        std::array<Eigen::MatrixXd, 2>
        damping_and_stiffness_times(Eigen::Ref<const Eigen::MatrixXd> N) const;

        /**
         * A N + U diag(d) U^T N (n x m for the local rows of an n x m
         * block N): the sparse (Rayleigh) C or C^T and the modal damping.
         */
        Eigen::MatrixXd
        damping_times(const Mat A, Eigen::Ref<const Eigen::MatrixXd> N) const;

        /** C N. */
        Eigen::MatrixXd
        damping_times(Eigen::Ref<const Eigen::MatrixXd> N) const;

        /** M V Q, C V Q and K V Q (n x columns of the r x m block Q). */
        std::array<Eigen::MatrixXd, 3>
        products(const Eigen::MatrixXd &Q) const;

        /**
         * Fixes the modal damping of @p modal on the current span (its
         * Ritz modes of K_s, M: the exact modes when the span holds them)
         * and adds it to V^T C V (and C V).
         */
        void
        fix_modal_damping(const PETScMatrix                        &K_s,
                          const physics::MatrixParts::ModalDamping &modal);

        /**
         * Room for @p columns columns of @p rows local rows in V (and in
         * M V, C V and K V with stored products), so that appending up to
         * that many copies no block; the columns in use are kept.
         * @throws std::logic_error if @p rows is not V's local row count.
         */
        void
        reserve(const Eigen::Index rows, const Eigen::Index columns);

        /**
         * Appends the part of the n x m block T M-orthogonal to V: two
         * passes of T -= V (V^T M V)^-1 V^T M T with the stored M V (or
         * one M product each without), exact whatever V's
         * orthonormality (the second removes what the first's rounding
         * left: "twice is enough", Giraud et al. 2005), then one M
         * product of what is left; columns whose remainder is below 1e-8
         * of their M-norm are dropped, the rest M-orthonormalised among
         * themselves (a first
         * block of nearly M-orthonormal @p modes by a Cholesky factor of
         * its Gram matrix, which keeps them nearly as they are; otherwise
         * by orthonormalising_transform, which drops dependent directions).
         * The projected matrices grow by V^T A N, N^T A N and N^T A V; with
         * #parts, N^T A V = (V^T A N)^T - ((A - A^T) N)^T V for C and K,
         * the second term on the friction parts' rows only
         * (PartsProduct::skew_times), instead of a product with the stored
         * A V or with the transposed parts.
         * @throws std::runtime_error if a first block of @p modes is
         * linearly dependent, or if PETSc fails.
         */
        void
        append(Eigen::MatrixXd T, const bool modes = false);
      };

      /**
       * The relative residuals ||(lambda^2 M + lambda C + K) x|| /
       * (|lambda|^2 ||M x|| + |lambda| ||C x|| + ||K x||) of the Ritz pairs
       * (lambda, x = V q) on the full model, one per pair, and the residual
       * vectors [Re r, Im r] of those above @p tol as the columns of
       * @p corrections (n x 2 per pair above).
       */
      std::vector<double>
      residuals(const Subspace                   &s,
                const std::vector<ProjectedPair> &pairs,
                const double                      tol,
                Eigen::MatrixXd                  &corrections);

      /**
       * The Ritz pairs (lambda, V q) of the subspace as distributed vectors
       * (laid out on @p owned), with their relative residuals @p res.
       */
      std::vector<EigenPair>
      ritz_pairs(const Subspace                   &s,
                 const dealii::IndexSet           &owned,
                 const std::vector<ProjectedPair> &pairs,
                 const std::vector<double>        &res);
    } // namespace internal
  }   // namespace eigen
} // namespace squeal

#endif
