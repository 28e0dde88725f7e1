// Thick-restart block Lanczos for the modes of a symmetric pencil (K, M)
// nearest above a shift: what makes MUMPS's factors affordable out of core
// (one pass through them per block of vectors). See BlockModes in
// symmetric_modes.h.

#include <deal.II/base/index_set.h>

#include <petscksp.h>

#include <Eigen/Dense>

#include "dense_block.h"
#include "symmetric_modes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace squeal
{
  namespace eigen
  {
    namespace internal
    {
      namespace
      {
        // A value in [-1, 1] for (global row, column seed), the same on any
        // number of ranks (splitmix64 of the pair)
        double
        start_value(const std::uint64_t row, const std::uint64_t seed)
        {
          std::uint64_t z =
            row * 0x9E3779B97F4A7C15ULL + seed * 0xBF58476D1CE4E5B9ULL + 1;
          z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
          z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
          z = z ^ (z >> 31);
          return 2. * double(z >> 11) / double(1ULL << 53) - 1.;
        }

        // column j of a block of start vectors on this rank's rows
        void
        fill_start(Eigen::Ref<Eigen::VectorXd> x,
                   const dealii::IndexSet     &owned,
                   const std::uint64_t         seed)
        {
          const std::uint64_t first = owned.nth_index_in_set(0);
          for (Eigen::Index i = 0; i < x.size(); ++i)
            x[i] = start_value(first + i, seed);
        }

        // the largest M-norm of W's columns
        double
        largest_m_norm(const PETScMatrix &M, const Eigen::MatrixXd &W)
        {
          Eigen::MatrixXd squares =
            W.cwiseProduct(multiply(M, W)).colwise().sum();
          sum_over_ranks(squares, M.get_mpi_communicator());
          return std::sqrt(std::max(0., squares.maxCoeff()));
        }

        // W -= V (V^T M W), twice (block classical Gram-Schmidt in the M
        // inner product, V M-orthonormal); returns the sum of the two
        // coefficient blocks (V.cols() x W.cols())
        Eigen::MatrixXd
        orthogonalise(const PETScMatrix     &M,
                      const Eigen::MatrixXd &V,
                      Eigen::MatrixXd       &W)
        {
          Eigen::MatrixXd H = Eigen::MatrixXd::Zero(V.cols(), W.cols());
          if (V.cols() == 0)
            return H;
          for (unsigned int pass = 0; pass < 2; ++pass)
            {
              Eigen::MatrixXd h = V.transpose() * multiply(M, W);
              sum_over_ranks(h, M.get_mpi_communicator());
              W.noalias() -= V * h;
              H += h;
            }
          return H;
        }

        // Makes W M-orthonormal and M-orthogonal to V: W_before = W R
        // (plus V's part), R returned (b x b). Directions whose M-norm
        // fell below 1e-10 of @p reference (the largest M-norm before the
        // orthogonalisation against V: the block is nearly in the span)
        // are replaced by start vectors orthogonalised against V and the
        // rest, with zero rows in R. Cholesky QR twice.
        Eigen::MatrixXd
        orthonormalise(const PETScMatrix      &M,
                       const Eigen::MatrixXd  &V,
                       Eigen::MatrixXd        &W,
                       const double            reference,
                       const dealii::IndexSet &owned,
                       std::uint64_t          &seed)
        {
          const MPI_Comm  comm = M.get_mpi_communicator();
          const int       b    = W.cols();
          Eigen::MatrixXd G    = W.transpose() * multiply(M, W);
          sum_over_ranks(G, comm);
          G = (G + G.transpose()).eval() / 2.;
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(G);
          W                 = W * es.eigenvectors();
          Eigen::MatrixXd R = es.eigenvectors().transpose();
          for (int j = 0; j < b; ++j)
            {
              const double d = std::max(0., es.eigenvalues()[j]);
              if (d > 1e-20 * reference * reference)
                {
                  W.col(j) /= std::sqrt(d);
                  R.row(j) *= std::sqrt(d);
                }
              else
                {
                  R.row(j).setZero();
                  fill_start(W.col(j), owned, seed++);
                  Eigen::MatrixXd x = W.col(j);
                  orthogonalise(M, V, x);
                  W.col(j) = x;
                }
            }
          // Cholesky QR twice (the replaced directions are orthogonalised
          // against the others here)
          for (unsigned int pass = 0; pass < 2; ++pass)
            {
              Eigen::MatrixXd G2 = W.transpose() * multiply(M, W);
              sum_over_ranks(G2, comm);
              G2 = (G2 + G2.transpose()).eval() / 2.;
              Eigen::LLT<Eigen::MatrixXd> llt(G2);
              if (llt.info() != Eigen::Success)
                throw std::runtime_error(
                  "block Lanczos: a new block lost its M-orthogonality "
                  "(Cholesky QR failed)");
              const Eigen::MatrixXd U = llt.matrixU();
              W                       = U.transpose()
                    .triangularView<Eigen::Lower>()
                    .solve(W.transpose())
                    .transpose();
              R = (U * R).eval();
            }
          return R;
        }
      } // namespace

      BlockModes::BlockModes(const PETScMatrix &K,
                             const PETScMatrix &M,
                             const double       sigma,
                             const double       tolerance)
        : sigma(sigma)
        , tolerance(tolerance)
        , shifted(K, M, sigma)
      {}

      std::vector<UndampedMode>
      BlockModes::solve(const PETScMatrix &M,
                        const unsigned int wanted,
                        const double       top)
      {
        block_solves = restarts = 0;
        seconds_solves          = 0.;
        if (wanted == 0)
          return {};
        const dealii::IndexSet owned = M.locally_owned_range_indices();
        const MPI_Comm         comm  = M.get_mpi_communicator();
        const Eigen::Index     N     = M.m();
        const Eigen::Index     n     = owned.n_elements();
        const Eigen::Index     c     = wanted;
        const auto [block, basis]    = block_and_basis(wanted, N);
        const Eigen::Index b         = block;
        const Eigen::Index largest   = basis;
        if (largest < c + b)
          throw std::runtime_error(
            "block Lanczos: " + std::to_string(wanted) +
            " modes wanted of a problem of size " + std::to_string(N) +
            ": too many for a Lanczos basis (use slepc)");
        const Eigen::Index keep      = std::min(c + b, largest - b);
        const double       theta_top = 1. / (top - sigma);
        block_size                   = b;
        // MUMPS treats the right-hand sides in blocks of ICNTL(27) (32 by
        // default): one block per step means one forward and one backward
        // pass through the factors (out of core: read from disk twice)
        {
          PC  pc;
          Mat F;
          check_petsc(KSPGetPC(static_cast<KSP>(shifted.solver->handle()), &pc),
                      "block Lanczos",
                      "KSPGetPC");
          check_petsc(PCFactorGetMatrix(pc, &F),
                      "block Lanczos",
                      "PCFactorGetMatrix");
          check_petsc(MatMumpsSetIcntl(F, 27, b),
                      "block Lanczos",
                      "MatMumpsSetIcntl");
        }
        std::uint64_t   seed = 1;
        void *const     ksp  = shifted.solver->handle();
        Eigen::MatrixXd V(n, 0), next(n, b);
        for (Eigen::Index j = 0; j < b; ++j)
          fill_start(next.col(j), owned, seed++);
        orthonormalise(M, V, next, largest_m_norm(M, next), owned, seed);
        // OP V = V T + next F (the Krylov-Schur relation)
        Eigen::MatrixXd T(0, 0), F(b, 0);
        for (;; ++restarts)
          {
            while (V.cols() + b <= largest)
              {
                const Eigen::Index k = V.cols();
                V.conservativeResize(Eigen::NoChange, k + b);
                V.rightCols(b) = next;
                T.conservativeResize(k + b, k + b);
                T.bottomLeftCorner(b, k) = F;
                T.topRightCorner(k, b)   = F.transpose();
                const auto      start    = std::chrono::steady_clock::now();
                Eigen::MatrixXd W =
                  solve_block(ksp, shifted.P, multiply(M, next));
                ++block_solves;
                seconds_solves += std::chrono::duration<double>(
                                    std::chrono::steady_clock::now() - start)
                                    .count();
                const double          reference = largest_m_norm(M, W);
                const Eigen::MatrixXd H         = orthogonalise(M, V, W);
                const Eigen::MatrixXd D         = H.bottomRows(b);
                T.bottomRightCorner(b, b)       = (D + D.transpose()) / 2.;
                const Eigen::MatrixXd R =
                  orthonormalise(M, V, W, reference, owned, seed);
                next           = std::move(W);
                F              = Eigen::MatrixXd::Zero(b, k + b);
                F.rightCols(b) = R;
              }
            // Rayleigh-Ritz: the largest theta first
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(T);
            const Eigen::VectorXd theta = es.eigenvalues().reverse();
            const Eigen::MatrixXd Y     = es.eigenvectors().rowwise().reverse();
            const Eigen::VectorXd residual =
              (F * Y).colwise().norm().transpose();
            bool done = theta[c - 1] > theta_top;
            for (Eigen::Index i = 0; i < c && done; ++i)
              done = residual[i] <= tolerance * std::abs(theta[i]);
            if (done)
              {
                multiply_in_place(V, Y.leftCols(c));
                std::vector<UndampedMode> modes(c);
                for (Eigen::Index i = 0; i < c; ++i)
                  {
                    // theta descending: omega^2 ascending
                    modes[i].omega2 = {sigma + 1. / theta[i], 0.};
                    modes[i].re.reinit(owned, comm);
                    set_local_part(modes[i].re, V.col(i));
                  }
                return modes;
              }
            if (restarts == 100)
              throw std::runtime_error(
                "block Lanczos: the " + std::to_string(wanted) +
                " modes below " + std::to_string(std::sqrt(top) / 2. / M_PI) +
                " Hz did not converge in 100 restarts (or the stiffness "
                "has an eigenvalue below the shift)");
            // keep the largest Ritz pairs and go on from next
            multiply_in_place(V, Y.leftCols(keep));
            T = theta.head(keep).asDiagonal();
            F = F * Y.leftCols(keep);
          }
      }
    } // namespace internal
  }   // namespace eigen
} // namespace squeal
