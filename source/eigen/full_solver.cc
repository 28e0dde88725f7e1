// The full solver: inertia counts of the symmetric problem, its modes up to
// the basis frequency, and the damped friction-coupled problem refined on
// their span by block Davidson rounds (see full_solver.h).

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/lac/parpack_solver.h>
#include <deal.II/lac/solver_control.h>

#include <squeal/base/memory_estimate.h>
#include <squeal/eigen/full_solver.h>
#include <squeal/physics/structural_model.h>

#include <petscksp.h>
#include <slepceps.h>

#include "dense_block.h"
#include "symmetric_modes.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace squeal
{
  namespace eigen
  {
    using namespace dealii;
    using internal::ArpackModes;
    using internal::multiply;
    using internal::sum_over_ranks;
    using internal::SymmetricModes;

    namespace
    {
      void
      check(const PetscErrorCode ierr, const char *what)
      {
        internal::check_petsc(ierr, "full solver", what);
      }

      double
      seconds_since(const std::chrono::steady_clock::time_point start)
      {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                             start)
          .count();
      }

      // M, C, K and K_s of the model at a point; M on its nonzeros only
      // (a third of the common pattern: no coupling between displacement
      // components), which every M product of the eigensolvers and the
      // subspace reads (the symmetric modes: about 630 products)
      struct PointMatrices
      {
        PETScMatrix M, C, K, K_s;

        PointMatrices(const physics::MatrixParts    &model,
                      const parameters::ScalarPoint &point)
        {
          model.mass(point, M);
          physics::store_nonzeros_only(M,
                                       M.locally_owned_range_indices(),
                                       M.get_mpi_communicator());
          model.stiffness(point, K);
          model.damping(point, C);
          model.symmetric_stiffness(point, K_s);
        }
      };

      // The transpose of a sparse matrix, owned (freed with it)
      struct Transposed
      {
        Mat t = nullptr;

        explicit Transposed(const PETScMatrix &A)
        {
          check(MatTranspose(A, MAT_INITIAL_MATRIX, &t), "MatTranspose");
        }
        ~Transposed()
        {
          MatDestroy(&t);
        }
        Transposed(const Transposed &) = delete;
        Transposed &
        operator=(const Transposed &) = delete;
      };

      // X = [X Y] (the columns of a column-major block grow in place where
      // the allocator can: no second copy of X), Y freed
      void
      extend(Eigen::MatrixXd &X, Eigen::MatrixXd &Y)
      {
        const Eigen::Index r = X.cols();
        X.conservativeResize(Y.rows(), r + Y.cols());
        X.rightCols(Y.cols()) = Y;
        Y.resize(0, 0);
      }

      // The subspace V of the refinement (local rows; V M-orthonormal) and
      // the projected matrices V^T A V. With stored products, M V, C V and
      // K V are kept too (four n x r blocks); otherwise a product is formed
      // when a block is appended or a Ritz vector is tested (one block).
      struct Subspace
      {
        const PETScMatrix &M, &C, &K;
        MPI_Comm           comm;
        bool               stored;
        Eigen::MatrixXd    V, WM, WC, WK, Mr, Cr, Kr;
        // the modal damping U diag(d) U^T once fixed (local rows of U)
        Eigen::MatrixXd U;
        Eigen::VectorXd d;
        // without stored products: C^T and K^T, made when the subspace
        // first grows (the new rows of the projection are
        // N^T A V = (A^T N)^T V)
        std::unique_ptr<const Transposed> Ct, Kt;

        // an empty subspace of the model at a point
        Subspace(const PointMatrices &A, const bool stored)
          : M(A.M)
          , C(A.C)
          , K(A.K)
          , comm(A.M.get_mpi_communicator())
          , stored(stored)
        {}

        // the subspace of a reduced basis (with its products if stored)
        Subspace(const PETScMatrix &M,
                 const PETScMatrix &C,
                 const PETScMatrix &K,
                 Projection       &&start,
                 const bool         stored)
          : M(M)
          , C(C)
          , K(K)
          , comm(M.get_mpi_communicator())
          , stored(stored)
          , V(std::move(start.V))
          , WM(std::move(start.MV))
          , WC(std::move(start.CV))
          , WK(std::move(start.KV))
          , Mr(std::move(start.Mr))
          , Cr(std::move(start.Cr))
          , Kr(std::move(start.Kr))
          , U(std::move(start.modal_U))
          , d(std::move(start.modal_d))
        {}

        // A N + U diag(d) U^T N: the sparse (Rayleigh) C or C^T and the
        // modal damping
        Eigen::MatrixXd
        damping_times(const Mat A, const Eigen::MatrixXd &N) const
        {
          Eigen::MatrixXd CN = multiply(A, N);
          if (U.cols() > 0)
            {
              Eigen::MatrixXd c = U.transpose() * N;
              sum_over_ranks(c, comm);
              CN += U * (d.asDiagonal() * c);
            }
          return CN;
        }

        // C N
        Eigen::MatrixXd
        damping_times(const Eigen::MatrixXd &N) const
        {
          return damping_times(static_cast<Mat>(C), N);
        }

        // M V Q, C V Q and K V Q (n x columns of Q each)
        std::array<Eigen::MatrixXd, 3>
        products(const Eigen::MatrixXd &Q) const
        {
          if (stored)
            return {WM * Q, WC * Q, WK * Q};
          const Eigen::MatrixXd X = V * Q;
          return {multiply(M, X), damping_times(X), multiply(K, X)};
        }

        // Fixes the modal damping of @p modal on the current span (its
        // Ritz modes of K_s, M: the exact modes when the span holds them)
        // and adds it to V^T C V (and C V).
        void
        fix_modal_damping(const PETScMatrix                        &K_s,
                          const physics::MatrixParts::ModalDamping &modal)
        {
          if (!modal.active() || V.cols() == 0)
            return;
          Eigen::MatrixXd Ksr = V.transpose() * multiply(K_s, V);
          sum_over_ranks(Ksr, comm);
          const auto m = internal::subspace_modal_damping(Mr, Ksr, modal);
          U = stored ? Eigen::MatrixXd(WM * m.Psi) : multiply(M, V * m.Psi);
          d = m.d;
          if (stored)
            WC += WM * m.B;
          Cr += Mr * m.B;
        }

        // Appends the part of the block T M-orthogonal to V: a pass of
        // T -= V (V^T M V)^-1 V^T M T, exact whatever V's orthonormality,
        // and a second one for the columns that lost more than half their
        // squared M-norm to it (Kahan's "twice is enough"); columns whose
        // remainder is below 1e-8 of their M-norm are dropped, the rest
        // M-orthonormalised among themselves (a first block of nearly
        // M-orthonormal @p modes by a Cholesky factor of its Gram matrix,
        // which keeps them nearly as they are; otherwise by
        // orthonormalising_transform, which drops dependent directions).
        void
        append(Eigen::MatrixXd T, const bool modes = false)
        {
          // the part of the columns of X along V, removed: their squared
          // M-norms
          const auto remove_span = [&](Eigen::MatrixXd &X) {
            // V^T M X
            Eigen::MatrixXd coefficients =
              stored ? Eigen::MatrixXd(WM.transpose() * X) :
                       Eigen::MatrixXd(V.transpose() * multiply(M, X));
            sum_over_ranks(coefficients, comm);
            coefficients = Mr.llt().solve(coefficients);
            X -= V * coefficients;
            return Eigen::VectorXd(
              (coefficients.transpose() * Mr * coefficients)
                .diagonal()
                .cwiseMax(0.));
          };
          Eigen::VectorXd in_span = Eigen::VectorXd::Zero(T.cols());
          if (V.cols() > 0)
            in_span = remove_span(T);
          Eigen::MatrixXd MT = multiply(M, T);
          Eigen::VectorXd remainder =
            T.cwiseProduct(MT).colwise().sum().transpose();
          {
            Eigen::MatrixXd r = remainder;
            sum_over_ranks(r, comm);
            remainder = r;
          }
          std::vector<int> keep, again;
          for (int j = 0; j < T.cols(); ++j)
            if (remainder[j] > 1e-16 * (remainder[j] + in_span[j]))
              {
                keep.push_back(j);
                if (remainder[j] < in_span[j])
                  again.push_back(j);
              }
          if (keep.empty())
            return;
          // the kept columns, in place (memory: the blocks are n x 2 k)
          for (unsigned int a = 0; a < keep.size(); ++a)
            if (int(a) != keep[a])
              {
                T.col(a)  = T.col(keep[a]);
                MT.col(a) = MT.col(keep[a]);
              }
          T.conservativeResize(Eigen::NoChange, keep.size());
          MT.conservativeResize(Eigen::NoChange, keep.size());
          if (!again.empty())
            {
              // the second pass, on the columns that need it
              Eigen::MatrixXd  X(T.rows(), again.size());
              std::vector<int> at(again.size());
              for (unsigned int a = 0; a < again.size(); ++a)
                {
                  at[a] = std::find(keep.begin(), keep.end(), again[a]) -
                          keep.begin();
                  X.col(a) = T.col(at[a]);
                }
              remove_span(X);
              const Eigen::MatrixXd MX = multiply(M, X);
              for (unsigned int a = 0; a < again.size(); ++a)
                {
                  T.col(at[a])  = X.col(a);
                  MT.col(at[a]) = MX.col(a);
                }
            }
          Eigen::MatrixXd gram_k = T.transpose() * MT;
          sum_over_ranks(gram_k, comm);
          Eigen::MatrixXd S;
          if (V.cols() == 0 && modes)
            {
              // S = L^-T, gram = L L^T
              const Eigen::LLT<Eigen::MatrixXd> llt(gram_k);
              if (llt.info() != Eigen::Success)
                throw std::runtime_error(
                  "full solver: the symmetric modes are linearly dependent");
              S = llt.matrixU().solve(
                Eigen::MatrixXd::Identity(keep.size(), keep.size()));
            }
          else
            S = internal::orthonormalising_transform(gram_k);
          // each block freed once used
          Eigen::MatrixXd N = T * S;
          T.resize(0, 0);
          Eigen::MatrixXd NM = MT * S;
          MT.resize(0, 0);
          const auto project = [&](const Eigen::MatrixXd &X,
                                   const Eigen::MatrixXd &Y) {
            Eigen::MatrixXd A = X.transpose() * Y;
            sum_over_ranks(A, comm);
            return A;
          };
          if (V.cols() == 0)
            {
              V  = std::move(N);
              Mr = project(V, NM);
              if (stored)
                {
                  WM = std::move(NM);
                  WC = damping_times(V);
                  WK = multiply(K, V);
                  Cr = project(V, WC);
                  Kr = project(V, WK);
                }
              else
                {
                  Cr = project(V, damping_times(V));
                  Kr = project(V, multiply(K, V));
                }
              return;
            }
          // [Ar, V^T A N; lower, N^T A N] with lower = N^T A V
          const auto grow = [&](Eigen::MatrixXd       &Ar,
                                const Eigen::MatrixXd &AN,
                                const Eigen::MatrixXd &lower) {
            const int       r = V.cols(), q = N.cols();
            Eigen::MatrixXd A(r + q, r + q);
            A << Ar, project(V, AN), lower, project(N, AN);
            Ar.swap(A);
          };
          // the same for M: N^T M V = (V^T M N)^T
          const auto grow_mass = [&](const Eigen::MatrixXd &MN) {
            const int             r = V.cols(), q = N.cols();
            const Eigen::MatrixXd upper = project(V, MN);
            Eigen::MatrixXd       A(r + q, r + q);
            A << Mr, upper, upper.transpose(), project(N, MN);
            Mr.swap(A);
          };
          if (stored)
            {
              Eigen::MatrixXd NC = damping_times(N), NK = multiply(K, N);
              grow_mass(NM);
              grow(Cr, NC, project(N, WC));
              grow(Kr, NK, project(N, WK));
              extend(WM, NM);
              extend(WC, NC);
              extend(WK, NK);
            }
          else
            {
              // N^T A V = (A^T N)^T V
              if (!Ct)
                {
                  Ct = std::make_unique<const Transposed>(C);
                  Kt = std::make_unique<const Transposed>(K);
                }
              grow_mass(NM);
              NM.resize(0, 0);
              grow(Cr, damping_times(N), project(damping_times(Ct->t, N), V));
              grow(Kr, multiply(K, N), project(multiply(Kt->t, N), V));
            }
          extend(V, N);
        }
      };

      // The real and imaginary parts of the pairs' coordinates, r x m each
      void
      coordinates(const std::vector<internal::ProjectedPair> &pairs,
                  const int                                   r,
                  Eigen::MatrixXd                            &Qr,
                  Eigen::MatrixXd                            &Qi)
      {
        Qr.resize(r, pairs.size());
        Qi.resize(r, pairs.size());
        for (unsigned int j = 0; j < pairs.size(); ++j)
          {
            Qr.col(j) = pairs[j].q.real();
            Qi.col(j) = pairs[j].q.imag();
          }
      }

      // The relative residuals of the Ritz pairs (V q, lambda) on the full
      // model, and the residual vectors [Re r, Im r] of those above @p tol.
      std::vector<double>
      residuals(const Subspace                             &s,
                const std::vector<internal::ProjectedPair> &pairs,
                const double                                tol,
                Eigen::MatrixXd                            &corrections)
      {
        const int       m = pairs.size();
        Eigen::MatrixXd Qr, Qi;
        coordinates(pairs, s.V.cols(), Qr, Qi);
        // the products of the Ritz vectors V [Qr Qi]
        Eigen::MatrixXd Q(Qr.rows(), 2 * m);
        Q << Qr, Qi;
        const auto AX = s.products(Q);
        const auto Mr = AX[0].leftCols(m), Mi = AX[0].rightCols(m),
                   Cr = AX[1].leftCols(m), Ci = AX[1].rightCols(m),
                   Kr = AX[2].leftCols(m), Ki = AX[2].rightCols(m);
        Eigen::MatrixXd Rr(Kr.rows(), m), Ri(Kr.rows(), m);
        for (int j = 0; j < m; ++j)
          {
            const std::complex<double> l = pairs[j].lambda, l2 = l * l;
            Rr.col(j) = Kr.col(j) + l.real() * Cr.col(j) -
                        l.imag() * Ci.col(j) + l2.real() * Mr.col(j) -
                        l2.imag() * Mi.col(j);
            Ri.col(j) = Ki.col(j) + l.real() * Ci.col(j) +
                        l.imag() * Cr.col(j) + l2.real() * Mi.col(j) +
                        l2.imag() * Mr.col(j);
          }
        // squared column norms of R, M x, C x, K x, summed over the ranks
        Eigen::MatrixXd norms(4, m);
        norms.row(0) = Rr.colwise().squaredNorm() + Ri.colwise().squaredNorm();
        norms.row(1) = Mr.colwise().squaredNorm() + Mi.colwise().squaredNorm();
        norms.row(2) = Cr.colwise().squaredNorm() + Ci.colwise().squaredNorm();
        norms.row(3) = Kr.colwise().squaredNorm() + Ki.colwise().squaredNorm();
        sum_over_ranks(norms, s.comm);
        norms = norms.cwiseSqrt();
        std::vector<double> result(m);
        std::vector<int>    above;
        for (int j = 0; j < m; ++j)
          {
            const double l = std::abs(pairs[j].lambda);
            result[j]      = norms(0, j) /
                        (l * l * norms(1, j) + l * norms(2, j) + norms(3, j));
            if (result[j] > tol)
              above.push_back(j);
          }
        corrections.resize(Rr.rows(), 2 * above.size());
        for (unsigned int a = 0; a < above.size(); ++a)
          {
            corrections.col(2 * a)     = Rr.col(above[a]);
            corrections.col(2 * a + 1) = Ri.col(above[a]);
          }
        return result;
      }

      // The Ritz pairs (lambda, V q) of the subspace as distributed
      // vectors, with their relative residuals RES.
      std::vector<EigenPair>
      ritz_pairs(const Subspace                             &s,
                 const IndexSet                             &owned,
                 const std::vector<internal::ProjectedPair> &pairs,
                 const std::vector<double>                  &res)
      {
        const int       m = pairs.size();
        Eigen::MatrixXd Qr, Qi;
        coordinates(pairs, s.V.cols(), Qr, Qi);
        const Eigen::MatrixXd  Xr = s.V * Qr, Xi = s.V * Qi;
        std::vector<EigenPair> result;
        for (int j = 0; j < m; ++j)
          {
            EigenPair p;
            p.lambda   = pairs[j].lambda;
            p.residual = res[j];
            p.re.reinit(owned, s.comm);
            p.im.reinit(owned, s.comm);
            internal::set_local_part(p.re, Xr.col(j));
            internal::set_local_part(p.im, Xi.col(j));
            result.push_back(std::move(p));
          }
        return result;
      }

      // The eigenpair of the dense (mu^2 M + mu C + K) y = 0 that nonlinear
      // inverse iteration reaches from (mu, y) (Ruhe 1973, Sec. 3; see
      // PairRefiner), in place; u = y / |y|^2 fixes the scale u^H y = 1.
      void
      follow_eigenpair(const Eigen::MatrixXd &M,
                       const Eigen::MatrixXd &C,
                       const Eigen::MatrixXd &K,
                       std::complex<double>  &mu,
                       Eigen::VectorXcd      &y)
      {
        using Complex             = std::complex<double>;
        const Eigen::MatrixXcd Mc = M.cast<Complex>(), Cc = C.cast<Complex>(),
                               Kc       = K.cast<Complex>();
        const Eigen::VectorXcd u        = y / y.squaredNorm();
        double                 previous = 1e300;
        for (unsigned int iteration = 0; iteration < 20; ++iteration)
          {
            const Eigen::MatrixXcd T = mu * mu * Mc + mu * Cc + Kc;
            const Eigen::VectorXcd z =
              T.partialPivLu().solve((2. * mu * Mc + Cc) * y);
            const Complex uz = u.dot(z);
            if (!std::isfinite(std::abs(uz)) || uz == 0.)
              return;
            const Complex step = 1. / uz;
            mu -= step;
            y = z / uz;
            // converged, or the steps stopped shrinking (round-off)
            if (std::abs(step) <= 1e-13 * std::abs(mu) ||
                std::abs(step) > 0.9 * previous)
              return;
            previous = std::abs(step);
          }
      }
    } // namespace

    std::vector<unsigned int>
    count_eigenvalues_below(const PETScMatrix         &K,
                            const PETScMatrix         &M,
                            const std::vector<double> &sigmas)
    {
      std::vector<unsigned int> counts;
      if (sigmas.empty())
        return counts;
      PETScMatrix A;
      A.reinit(K);
      Mat           F;
      IS            rows, columns;
      MatFactorInfo info;
      check(MatFactorInfoInitialize(&info), "MatFactorInfoInitialize");
      check(MatGetFactor(A, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F),
            "MatGetFactor (MUMPS LDL^T)");
      // the inertia over every rank needs MUMPS without a ScaLAPACK root
      // and the zero count needs its null-pivot detection
      check(MatMumpsSetIcntl(F, 13, 1), "MatMumpsSetIcntl");
      check(MatMumpsSetIcntl(F, 24, 1), "MatMumpsSetIcntl");
      check(MatGetOrdering(A, MATORDERINGNATURAL, &rows, &columns),
            "MatGetOrdering");
      bool symbolic = false;
      for (const double sigma : sigmas)
        {
          A.copy_from(K);
          internal::add_scaled(A, -sigma, M);
          if (!symbolic)
            check(MatCholeskyFactorSymbolic(F, A, rows, &info),
                  "MatCholeskyFactorSymbolic (MUMPS LDL^T)");
          symbolic = true;
          check(MatCholeskyFactorNumeric(F, A, &info),
                "MatCholeskyFactorNumeric (MUMPS LDL^T)");
          PetscInt negative, zero, positive;
          check(MatGetInertia(F, &negative, &zero, &positive), "MatGetInertia");
          if (zero != 0)
            {
              MatDestroy(&F);
              throw std::runtime_error(
                "inertia count: K - sigma M is singular at sigma = " +
                std::to_string(sigma) +
                " 1/s^2 (an eigenvalue lies on a band edge: move the "
                "Eigensolver frequencies by a fraction of a hertz)");
            }
          counts.push_back(negative);
        }
      ISDestroy(&rows);
      ISDestroy(&columns);
      MatDestroy(&F);
      return counts;
    }

    std::vector<EigenPair>
    solve_full(const physics::MatrixParts    &model,
               const parameters::ScalarPoint &point,
               const BandOptions             &band,
               ConditionalOStream            &pcout,
               FullSolveReport               *report)
    {
      const auto          start = std::chrono::steady_clock::now();
      const PointMatrices A(model, point);
      const PETScMatrix  &M = A.M, &K = A.K, &K_s = A.K_s;
      const double        w_t    = 2. * numbers::PI * band.target_frequency;
      const auto          square = [](const double f) {
        return std::pow(2. * numbers::PI * f, 2);
      };
      const double sigma = -w_t * w_t;
      // Undamped and frictionless at this point (C = 0, K = K_s): the
      // eigenvalues are +-i omega of the symmetric modes, so the band's
      // modes are the whole answer and the basis stops at f_max.
      const auto c        = model.coefficients(point);
      const bool undamped = !model.modal.active() &&
                            std::all_of(c.damping.begin(),
                                        c.damping.end(),
                                        [](const double d) { return d == 0.; });
      const bool symmetric = undamped && c.stiffness == c.symmetric_stiffness;
      // the basis holds the modally damped modes too
      const double f_top =
        symmetric ? band.f_max :
                    std::max(band.basis_factor * band.f_max,
                             model.modal.active() ? model.modal.cutoff : 0.);
      const double top = square(f_top);
      // (the shift-and-invert's factorisation of K_s - sigma M shows
      // whether K_s is positive semi-definite: its eigenvalues below sigma
      // are the nearest to it, or missing from the count below)
      auto counts = count_eigenvalues_below(
        K_s,
        M,
        symmetric ?
          std::vector<double>{square(band.f_min), top} :
          std::vector<double>{square(band.f_min), square(band.f_max), top});
      if (symmetric) // the top is f_max
        counts.push_back(counts.back());
      FullSolveReport r;
      r.symmetric_in_band  = counts[1] - counts[0];
      r.symmetric_in_basis = counts[2];
      // the memory the first full solve of a run will need, before it
      // needs it: the LDL^T of K_s - sigma M and the subspace of m vectors,
      // per DoF and vector 43 bytes with stored products (V, M V, C V, K V
      // and the 1.35x of growing them) and 22 bytes with recomputed ones
      // (V, the working blocks, C^T and K^T), measured on the coarse
      // passenger-car brake; m = 3 k (the k modes and their 2 k static
      // corrections) plus 6 per mode in the band for the refinement
      // (measured: 2.8 on the TriboBrake, 10.6 on the brake); m = k
      // without friction and damping
      static bool estimated = false;
      if (!estimated)
        {
          estimated      = true;
          const double k = r.symmetric_in_basis;
          const double m = symmetric ? k : 3. * k + 6. * r.symmetric_in_band;
          const double n_dofs = M.m();
          report_memory_estimate(
            M.get_mpi_communicator(),
            pcout.is_active() ? &pcout.get_stream() : nullptr,
            M.m(),
            factorisation_bytes(K_s.n_nonzero_elements(), M.m(), true) +
              (band.store_products ? 43. : 22.) * n_dofs * m,
            "the full solver's LDL^T and its subspace of about " +
              std::to_string(int(m)) +
              (band.store_products ? " vectors with their M, C and K products" :
                                     " vectors (products recomputed)"));
        }

      const double                    t_count = seconds_since(start);
      std::unique_ptr<SymmetricModes> slepc;
      std::unique_ptr<ArpackModes>    arpack;
      std::vector<UndampedMode>       modes;
      if (band.symmetric_solver == "arpack")
        {
          arpack = std::make_unique<ArpackModes>(K_s, M, sigma, band.tolerance);
          modes  = arpack->solve(M, r.symmetric_in_basis, top);
        }
      else
        {
          slepc =
            std::make_unique<SymmetricModes>(K_s, M, sigma, band.tolerance);
          modes = slepc->solve(M, r.symmetric_in_basis, top);
        }
      void *const factorised = arpack ? arpack->solver() : slepc->solver();
      const auto  not_semi_definite = [&]() {
        return "the stiffness without friction is not positive "
                "semi-definite (an eigenvalue below -(2 pi " +
               std::to_string(band.target_frequency) +
               " Hz)^2: check the materials, springs and interface "
                "stiffness)";
      };
      if (!modes.empty() && modes.front().omega2.real() < sigma)
        throw std::runtime_error("full solver: " + not_semi_definite());
      if (modes.size() != r.symmetric_in_basis)
        throw std::runtime_error(
          "full solver: the symmetric eigensolver returned " +
          std::to_string(modes.size()) + " modes below " +
          std::to_string(f_top) + " Hz where the inertia count gives " +
          std::to_string(r.symmetric_in_basis) + " (or " + not_semi_definite() +
          ")");
      const double t_symmetric = seconds_since(start);

      const IndexSet  owned = M.locally_owned_range_indices();
      const int       n     = owned.n_elements();
      Eigen::MatrixXd Phi(n, modes.size());
      Eigen::VectorXd omega2(modes.size());
      for (unsigned int j = 0; j < modes.size(); ++j)
        {
          Phi.col(j) = internal::local_part(modes[j].re, owned);
          omega2[j]  = modes[j].omega2.real();
        }
      // the modes live on in Phi; the eigensolver's basis is not needed
      modes.clear();
      modes.shrink_to_fit();
      if (slepc)
        slepc->release_basis();
      Subspace s(A, band.store_products);
      s.append(std::move(Phi), true);
      s.fix_modal_damping(K_s, model.modal);
      // static corrections of the damping and the friction forces
      // (K - K_s) Phi = K Phi - M Phi Omega^2 (V = Phi to the eigensolver's
      // tolerance: enough for a direction of the subspace)
      if (!symmetric)
        {
          const int       m = s.V.cols();
          Eigen::MatrixXd forces(n, 2 * m);
          if (s.stored)
            forces << s.WC, s.WK - s.WM * omega2.asDiagonal();
          else
            {
              forces.leftCols(m)  = s.damping_times(s.V);
              forces.rightCols(m) = multiply(K, s.V);
              forces.rightCols(m) -= multiply(M, s.V) * omega2.asDiagonal();
            }
          Eigen::MatrixXd corrections =
            internal::solve_block(factorised, K_s, forces);
          forces.resize(0, 0);
          s.append(std::move(corrections));
        }
      const double t_projection = seconds_since(start) - t_symmetric;

      std::vector<internal::ProjectedPair> pairs;
      std::vector<double>                  res;
      for (r.rounds = 0;; ++r.rounds)
        {
          auto t = std::chrono::steady_clock::now();
          // seconds since t, t reset
          const auto lap = [&t]() {
            const double dt = seconds_since(t);
            t               = std::chrono::steady_clock::now();
            return dt;
          };
          pairs = internal::projected_eigenpairs(
            s.Mr, s.Cr, s.Kr, band.f_min, band.f_max, -w_t, f_top);
          r.seconds_projected += lap();
          Eigen::MatrixXd corrections;
          res = residuals(s, pairs, band.residual_tolerance, corrections);
          r.seconds_residuals += lap();
          if (corrections.cols() == 0 || r.rounds == band.max_rounds)
            break;
          Eigen::MatrixXd directions =
            internal::solve_block(factorised, K_s, corrections);
          corrections.resize(0, 0);
          r.seconds_solves += lap();
          s.append(std::move(directions));
          r.seconds_growth += lap();
        }
      r.basis_size                  = s.V.cols();
      std::vector<EigenPair> result = ritz_pairs(s, owned, pairs, res);
      for (const EigenPair &p : result)
        {
          r.largest_residual = std::max(r.largest_residual, p.residual);
          if (p.residual > band.residual_tolerance)
            ++r.above_tolerance;
        }
      r.seconds = seconds_since(start);
      {
        Utilities::System::MemoryStats stats;
        Utilities::System::get_memory_stats(stats);
        r.peak_memory_mb =
          Utilities::MPI::sum(double(stats.VmHWM), s.comm) / 1024.;
      }
      pcout << "  full solver: " << result.size()
            << " modes in the band; symmetric problem (no friction) "
            << r.symmetric_in_band << " in the band and "
            << r.symmetric_in_basis << " up to " << f_top
            << " Hz by Sylvester inertia, all in the basis"
            << (symmetric ? " (undamped and frictionless: the band's modes "
                            "are the eigenpairs)" :
                            "")
            << "; " << r.basis_size
            << " basis vectors, largest relative residual "
            << r.largest_residual << " after " << r.rounds << " rounds ("
            << r.above_tolerance << " above " << band.residual_tolerance
            << "); " << t_count << " s count, " << t_symmetric - t_count
            << " s symmetric modes, " << t_projection << " s projection, "
            << r.seconds - t_symmetric - t_projection << " s refinement ("
            << r.seconds_projected << " s projected eigenproblems, "
            << r.seconds_residuals << " s residuals, " << r.seconds_solves
            << " s block solves, " << r.seconds_growth << " s subspace growth; "
            << band.symmetric_solver
            << " for the symmetric modes); peak memory " << r.peak_memory_mb
            << " MB (" << 1024. * r.peak_memory_mb / M.m() << " kB per DoF)"
            << std::endl;
      if (report)
        *report = r;
      return result;
    }

    std::vector<EigenPair>
    solve_on_iterates(const physics::MatrixParts     &model,
                      const parameters::ScalarPoint  &point,
                      const BandOptions              &band,
                      const std::vector<PETScVector> &start,
                      const std::vector<double>      &frequency,
                      const unsigned int              levels,
                      IterateReport                  *report)
    {
      if (frequency.size() != start.size())
        throw std::logic_error("solve_on_iterates: one frequency per vector");
      const auto          t0 = std::chrono::steady_clock::now();
      const PointMatrices AP(model, point);
      const PETScMatrix  &M = AP.M, &K_s = AP.K_s;
      const IndexSet      owned = M.locally_owned_range_indices();
      const int           n     = owned.n_elements();
      IterateReport       r;
      Subspace            s(AP, band.store_products);
      // shifts at the geometric centres of sub-bands at most an octave wide
      const double       f_lo = std::max(band.f_min, 1.), f_hi = band.f_max;
      const unsigned int n_shifts =
        std::max(1, int(std::ceil(std::log2(f_hi / f_lo) - 1e-9)));
      const double ratio = std::pow(f_hi / f_lo, 1. / n_shifts);
      for (unsigned int i = 0; i < n_shifts; ++i)
        {
          const double f_lower = f_lo * std::pow(ratio, i),
                       f_shift = f_lower * std::sqrt(ratio);
          std::vector<unsigned int> mine;
          for (unsigned int k = 0; k < start.size(); ++k)
            if ((frequency[k] >= f_lower || i == 0) &&
                (frequency[k] < f_lower * ratio || i + 1 == n_shifts))
              mine.push_back(k);
          if (mine.empty())
            continue;
          Eigen::MatrixXd X(n, mine.size());
          for (unsigned int a = 0; a < mine.size(); ++a)
            X.col(a) = internal::local_part(start[mine[a]], owned);
          const auto   t_factor = std::chrono::steady_clock::now();
          PETScMatrix  A;
          const double w = 2. * numbers::PI * f_shift;
          A.reinit(K_s);
          A.copy_from(K_s);
          internal::add_scaled(A, -w * w, M);
          const DirectSolver solver(A, true);
          r.factorisation_seconds += seconds_since(t_factor);
          ++r.factorisations;
          const auto t_solve = std::chrono::steady_clock::now();
          std::vector<Eigen::MatrixXd> blocks{X};
          for (unsigned int level = 0; level < levels; ++level)
            {
              Eigen::MatrixXd Y =
                internal::solve_block(solver.handle(),
                                      A,
                                      multiply(M, blocks.back()));
              // unit columns: the iterates grow like 1 / |omega^2 - w^2|
              const Eigen::VectorXd norms = internal::column_norms(Y, s.comm);
              for (int j = 0; j < Y.cols(); ++j)
                if (norms[j] > 0.)
                  Y.col(j) /= norms[j];
              blocks.push_back(std::move(Y));
            }
          r.solve_seconds += seconds_since(t_solve);
          for (auto &b : blocks)
            s.append(std::move(b));
        }
      const auto t_project = std::chrono::steady_clock::now();
      s.fix_modal_damping(K_s, model.modal);
      const auto pairs =
        internal::projected_eigenpairs(s.Mr,
                                       s.Cr,
                                       s.Kr,
                                       band.f_min,
                                       band.f_max,
                                       -2. * numbers::PI *
                                         band.target_frequency,
                                       band.basis_factor * band.f_max);
      Eigen::MatrixXd unused;
      const auto      res = residuals(s, pairs, 1., unused);
      r.projected_seconds = seconds_since(t_project);
      r.basis_size        = s.V.cols();
      r.seconds           = seconds_since(t0);
      if (report)
        *report = r;
      return ritz_pairs(s, owned, pairs, res);
    }

    PairRefiner::PairRefiner(const physics::MatrixParts &model,
                             const BandOptions          &band)
      : model(model)
      , band(band)
    {}

    PairRefiner::~PairRefiner() = default;

    std::vector<RefinedPair>
    PairRefiner::refine(const parameters::ScalarPoint           &point,
                        Projection                               start,
                        const std::vector<std::complex<double>> &lambda,
                        const std::vector<Eigen::VectorXcd>     &q)
    {
      const auto          c = model.coefficients(point);
      std::vector<double> k = c.mass;
      k.insert(k.end(),
               c.symmetric_stiffness.begin(),
               c.symmetric_stiffness.end());
      PETScMatrix M, C, K;
      model.mass(point, M);
      if (!solver || k != key)
        {
          // P = K_s + (2 pi f_t)^2 M: positive definite, one Cholesky
          const auto start = std::chrono::steady_clock::now();
          solver.reset();
          model.symmetric_stiffness(point, P);
          const double w_t = 2. * numbers::PI * band.target_frequency;
          internal::add_scaled(P, w_t * w_t, M);
          solver = std::make_unique<DirectSolver>(P, true);
          key    = k;
          ++n_factorisations;
          seconds_factorising += seconds_since(start);
        }
      model.damping(point, C);
      model.stiffness(point, K);
      if (band.store_products && start.MV.cols() != start.V.cols())
        throw std::logic_error(
          "PairRefiner::refine: the projection has no products "
          "(ReducedModel::projection(p, true) with stored products)");
      Subspace           s(M, C, K, std::move(start), band.store_products);
      const unsigned int n_pairs = lambda.size();
      std::vector<internal::ProjectedPair> pairs(n_pairs);
      for (unsigned int j = 0; j < n_pairs; ++j)
        pairs[j] = {lambda[j], q[j]};
      std::vector<RefinedPair> result(n_pairs, {0., 1., 0});
      std::vector<bool>        done(n_pairs, false);
      for (unsigned int round = 0;; ++round)
        {
          std::vector<internal::ProjectedPair> open;
          std::vector<unsigned int>            index;
          for (unsigned int j = 0; j < n_pairs; ++j)
            if (!done[j])
              {
                // coordinates of the new directions start at zero
                auto     &y   = pairs[j].q;
                const int old = y.size();
                y.conservativeResize(s.V.cols());
                y.tail(y.size() - old).setZero();
                follow_eigenpair(s.Mr, s.Cr, s.Kr, pairs[j].lambda, y);
                open.push_back(pairs[j]);
                index.push_back(j);
              }
          Eigen::MatrixXd corrections;
          const auto      res =
            residuals(s, open, band.residual_tolerance, corrections);
          for (unsigned int a = 0; a < open.size(); ++a)
            {
              result[index[a]] = {open[a].lambda, res[a], round};
              done[index[a]]   = res[a] <= band.residual_tolerance;
            }
          if (corrections.cols() == 0 || round == band.max_rounds)
            break;
          s.append(internal::solve_block(solver->handle(), P, corrections));
        }
      return result;
    }
  } // namespace eigen
} // namespace squeal
