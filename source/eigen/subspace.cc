// The Rayleigh-Ritz subspace of the damped friction-coupled problem
// (subspace.h).

#include "subspace.h"

#include <deal.II/base/index_set.h>

#include <petscmat.h>

#include <complex>
#include <stdexcept>
#include <utility>

namespace squeal
{
  namespace eigen
  {
    namespace internal
    {
      namespace
      {
        using View = Eigen::Map<Eigen::MatrixXd>;

        // view := X, copied into @p storage if it has room (Subspace::
        // reserve()), else its memory taken over by @p storage
        void
        take(View &view, Eigen::MatrixXd &storage, Eigen::MatrixXd &&X)
        {
          const Eigen::Index n = X.rows(), r = X.cols();
          if (storage.rows() == n && storage.cols() >= r)
            {
              storage.leftCols(r) = X;
              X.resize(0, 0);
            }
          else
            storage = std::move(X);
          new (&view) View(storage.data(), n, r);
        }

        // view := [view Y], Y freed: in place while @p storage has room for
        // Y's columns, else the storage is enlarged to room for twice the
        // columns needed (only the columns written become resident; the
        // column-major storage grows at its end, so realloc keeps the
        // columns in place or moves their pages without a copy)
        void
        extend(View &view, Eigen::MatrixXd &storage, Eigen::MatrixXd &Y)
        {
          const Eigen::Index n = Y.rows(), r = view.cols(), q = Y.cols();
          if (storage.cols() < r + q)
            storage.conservativeResize(n, 2 * (r + q));
          storage.middleCols(r, q) = Y;
          Y.resize(0, 0);
          new (&view) View(storage.data(), n, r + q);
        }

        // The real and imaginary parts of the pairs' coordinates, r x m each
        void
        coordinates(const std::vector<ProjectedPair> &pairs,
                    const int                         r,
                    Eigen::MatrixXd                  &Qr,
                    Eigen::MatrixXd                  &Qi)
        {
          Qr.resize(r, pairs.size());
          Qi.resize(r, pairs.size());
          for (unsigned int j = 0; j < pairs.size(); ++j)
            {
              Qr.col(j) = pairs[j].q.real();
              Qi.col(j) = pairs[j].q.imag();
            }
        }
      } // namespace

      PointMatrices::PointMatrices(const physics::MatrixParts    &model,
                                   const parameters::ScalarPoint &point,
                                   const bool                     with_parts)
        : coefficients(model.coefficients(point))
      {
        model.mass(point, M);
        physics::store_nonzeros_only(M,
                                     M.locally_owned_range_indices(),
                                     M.get_mpi_communicator());
        if (with_parts)
          parts = std::make_unique<const PartsProduct>(model);
        else
          {
            model.stiffness(point, K);
            model.damping(point, C);
          }
        model.symmetric_stiffness(point, K_s);
      }

      Transposed::Transposed(const PETScMatrix &A)
      {
        check_petsc(MatTranspose(A, MAT_INITIAL_MATRIX, &t),
                    "full solver",
                    "MatTranspose");
      }

      Transposed::~Transposed()
      {
        MatDestroy(&t);
      }

      Subspace::Subspace(const PointMatrices &A, const bool stored)
        : M(A.M)
        , C(A.C)
        , K(A.K)
        , comm(A.M.get_mpi_communicator())
        , stored(stored)
      {
        if (A.parts)
          use_parts(*A.parts, A.coefficients);
      }

      Subspace::Subspace(const PETScMatrix &M,
                         const PETScMatrix &C,
                         const PETScMatrix &K,
                         Projection       &&start,
                         const bool         stored,
                         MPI_Comm           comm)
        : M(M)
        , C(C)
        , K(K)
        , comm(comm)
        , stored(stored)
        , Mr(std::move(start.Mr))
        , Cr(std::move(start.Cr))
        , Kr(std::move(start.Kr))
        , U(std::move(start.modal_U))
        , d(std::move(start.modal_d))
      {
        take(V, storage[0], std::move(start.V));
        take(WM, storage[1], std::move(start.MV));
        take(WC, storage[2], std::move(start.CV));
        take(WK, storage[3], std::move(start.KV));
      }

      void
      Subspace::add_modal_damping(Eigen::MatrixXd                  &CN,
                                  Eigen::Ref<const Eigen::MatrixXd> N) const
      {
        if (U.cols() == 0)
          return;
        Eigen::MatrixXd c = U.transpose() * N;
        sum_over_ranks(c, comm);
        CN += U * (d.asDiagonal() * c);
      }

      Eigen::MatrixXd
      Subspace::damping_times(const Mat                         A,
                              Eigen::Ref<const Eigen::MatrixXd> N) const
      {
        Eigen::MatrixXd CN = multiply(A, N);
        add_modal_damping(CN, N);
        return CN;
      }

      Eigen::MatrixXd
      Subspace::damping_times(Eigen::Ref<const Eigen::MatrixXd> N) const
      {
        if (parts)
          return damping_and_stiffness_times(N)[0];
        return damping_times(static_cast<Mat>(C), N);
      }

      void
      Subspace::use_parts(const PartsProduct                      &p,
                          const physics::MatrixParts::Combination &c,
                          const bool                               mass)
      {
        parts           = &p;
        coefficients    = c;
        mass_from_parts = mass;
      }

      Eigen::MatrixXd
      Subspace::mass_times(Eigen::Ref<const Eigen::MatrixXd> N) const
      {
        if (mass_from_parts)
          return parts->multiply({&coefficients.mass}, N)[0];
        return multiply(M, N);
      }

      std::array<Eigen::MatrixXd, 2>
      Subspace::damping_and_stiffness_times(
        Eigen::Ref<const Eigen::MatrixXd> N) const
      {
        if (!parts)
          return {{damping_times(static_cast<Mat>(C), N), multiply(K, N)}};
        auto CK =
          parts->multiply({&coefficients.damping, &coefficients.stiffness}, N);
        add_modal_damping(CK[0], N);
        return {{std::move(CK[0]), std::move(CK[1])}};
      }

      std::array<Eigen::MatrixXd, 3>
      Subspace::products(const Eigen::MatrixXd &Q) const
      {
        if (stored)
          return {{WM * Q, WC * Q, WK * Q}};
        const Eigen::MatrixXd X  = V * Q;
        auto                  CK = damping_and_stiffness_times(X);
        return {{mass_times(X), std::move(CK[0]), std::move(CK[1])}};
      }

      void
      Subspace::fix_modal_damping(
        const PETScMatrix                        &K_s,
        const physics::MatrixParts::ModalDamping &modal)
      {
        if (!modal.active() || V.cols() == 0)
          return;
        Eigen::MatrixXd Ksr = V.transpose() * multiply(K_s, V);
        sum_over_ranks(Ksr, comm);
        const auto m = internal::subspace_modal_damping(Mr, Ksr, modal);
        U = stored ? Eigen::MatrixXd(WM * m.Psi) : mass_times(V * m.Psi);
        d = m.d;
        if (stored)
          WC += WM * m.B;
        Cr += Mr * m.B;
      }

      void
      Subspace::append(Eigen::MatrixXd T, const bool modes)
      {
        // the part of the columns of X along V, removed: their squared
        // M-norms
        const auto remove_span = [&](Eigen::MatrixXd &X) {
          // V^T M X
          Eigen::MatrixXd coefficients =
            stored ? Eigen::MatrixXd(WM.transpose() * X) :
                     Eigen::MatrixXd(V.transpose() * mass_times(X));
          sum_over_ranks(coefficients, comm);
          coefficients = Mr.llt().solve(coefficients);
          X -= V * coefficients;
          return Eigen::VectorXd((coefficients.transpose() * Mr * coefficients)
                                   .diagonal()
                                   .cwiseMax(0.));
        };
        // two passes ("twice is enough"): the second removes what the
        // rounding of the first left along V; then one M product
        Eigen::VectorXd in_span = Eigen::VectorXd::Zero(T.cols());
        if (V.cols() > 0)
          {
            in_span = remove_span(T);
            in_span += remove_span(T);
          }
        Eigen::MatrixXd MT = mass_times(T);
        // the squared M-norms of what is left, 1 x m
        Eigen::MatrixXd remainder = T.cwiseProduct(MT).colwise().sum();
        sum_over_ranks(remainder, comm);
        // the columns kept
        std::vector<int> keep;
        for (int j = 0; j < T.cols(); ++j)
          if (remainder(0, j) > 1e-16 * (remainder(0, j) + in_span[j]))
            keep.push_back(j);
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
        const auto project = [&](Eigen::Ref<const Eigen::MatrixXd> X,
                                 Eigen::Ref<const Eigen::MatrixXd> Y) {
          Eigen::MatrixXd A = X.transpose() * Y;
          sum_over_ranks(A, comm);
          return A;
        };
        if (V.cols() == 0)
          {
            take(V, storage[0], std::move(N));
            Mr = project(V, NM);
            if (stored)
              {
                auto CK = damping_and_stiffness_times(V);
                take(WM, storage[1], std::move(NM));
                take(WC, storage[2], std::move(CK[0]));
                take(WK, storage[3], std::move(CK[1]));
                Cr = project(V, WC);
                Kr = project(V, WK);
              }
            else
              {
                auto CK = damping_and_stiffness_times(V);
                Cr      = project(V, CK[0]);
                Kr      = project(V, CK[1]);
              }
            return;
          }
        // [Ar, upper; lower, N^T A N] with upper = V^T A N and lower =
        // N^T A V
        const auto grow = [&](Eigen::MatrixXd       &Ar,
                              const Eigen::MatrixXd &AN,
                              const Eigen::MatrixXd &upper,
                              const Eigen::MatrixXd &lower) {
          const int       r = V.cols(), q = N.cols();
          Eigen::MatrixXd A(r + q, r + q);
          A << Ar, upper, lower, project(N, AN);
          Ar.swap(A);
        };
        // the same for A = sum_k c[k] A_k + (symmetric modal damping) from
        // the parts: N^T A V = (V^T A N)^T - ((A - A^T) N)^T V, whose second
        // term lives on the friction parts' rows only (a product with a few
        // rows of V instead of one with the whole A V or A^T N)
        const auto grow_from_parts =
          [&](Eigen::MatrixXd                          &Ar,
              const Eigen::MatrixXd                    &AN,
              const physics::MatrixParts::Coefficients &c) {
            const Eigen::MatrixXd upper = project(V, AN);
            Eigen::MatrixXd       lower = upper.transpose();
            const auto            skew  = parts->skew_times(c, N);
            if (skew.any)
              {
                Eigen::MatrixXd x =
                  skew.values.transpose() * V(skew.rows, Eigen::all);
                sum_over_ranks(x, comm);
                lower -= x;
              }
            grow(Ar, AN, upper, lower);
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
            auto             CK = damping_and_stiffness_times(N);
            Eigen::MatrixXd &NC = CK[0], &NK = CK[1];
            grow_mass(NM);
            if (parts)
              {
                grow_from_parts(Cr, NC, coefficients.damping);
                grow_from_parts(Kr, NK, coefficients.stiffness);
              }
            else
              {
                grow(Cr, NC, project(V, NC), project(N, WC));
                grow(Kr, NK, project(V, NK), project(N, WK));
              }
            extend(WM, storage[1], NM);
            extend(WC, storage[2], NC);
            extend(WK, storage[3], NK);
          }
        else if (parts)
          {
            grow_mass(NM);
            NM.resize(0, 0);
            const auto CK = damping_and_stiffness_times(N);
            grow_from_parts(Cr, CK[0], coefficients.damping);
            grow_from_parts(Kr, CK[1], coefficients.stiffness);
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
            const Eigen::MatrixXd CN = damping_times(N), KN = multiply(K, N);
            grow(Cr, CN, project(V, CN), project(damping_times(Ct->t, N), V));
            grow(Kr, KN, project(V, KN), project(multiply(Kt->t, N), V));
          }
        extend(V, storage[0], N);
      }

      void
      Subspace::reserve(const Eigen::Index rows, const Eigen::Index columns)
      {
        const std::array<View *, 4> views{{&V, &WM, &WC, &WK}};
        for (unsigned int k = 0; k < (stored ? 4 : 1); ++k)
          {
            Eigen::MatrixXd   &memory = storage[k];
            const Eigen::Index used   = views[k]->cols();
            if (memory.cols() >= columns && memory.rows() == rows)
              continue;
            if (used > 0 && memory.rows() != rows)
              throw std::logic_error("Subspace::reserve: wrong row count");
            memory.conservativeResize(rows, columns);
            new (views[k]) View(memory.data(), rows, used);
          }
      }

      // The relative residuals of the Ritz pairs (V q, lambda) on the full
      // model, and the residual vectors [Re r, Im r] of those above @p tol.
      std::vector<double>
      residuals(const Subspace                   &s,
                const std::vector<ProjectedPair> &pairs,
                const double                      tol,
                Eigen::MatrixXd                  &corrections)
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
      ritz_pairs(const Subspace                   &s,
                 const dealii::IndexSet           &owned,
                 const std::vector<ProjectedPair> &pairs,
                 const std::vector<double>        &res)
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
    } // namespace internal
  }   // namespace eigen
} // namespace squeal
