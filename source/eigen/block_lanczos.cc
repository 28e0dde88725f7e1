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

        // A block of vectors W (this rank's rows) with its mass product
        // MW = M W, carried along every linear combination of W's columns
        struct Block
        {
          Eigen::MatrixXd W, MW;
        };

        // The Lanczos basis V, M-orthonormal, and with @p stored its mass
        // products M V, updated with V. With them a step needs one sparse
        // product, M W of the operator's new block: every projection
        // V^T M X is (M V)^T X and every combination of columns is applied
        // to both. Without them (the factors out of core, memory short) the
        // new block's M W is formed again after each Gram-Schmidt pass.
        // Both are allocated once at their largest size (n x largest; the
        // pages become resident as columns are written) and freed at once.
        class LanczosBasis
        {
        public:
          LanczosBasis(const PETScMatrix &M,
                       const bool         stored,
                       const Eigen::Index n,
                       const Eigen::Index largest)
            : M(M)
            , stored(stored)
            , V_storage(n, largest)
            , MV_storage(stored ? n : 0, stored ? largest : 0)
          {}

          const PETScMatrix &M;
          const bool         stored;

          // the basis, n x cols()
          Eigen::
            Block<const Eigen::MatrixXd, Eigen::Dynamic, Eigen::Dynamic, true>
            V() const
          {
            return V_storage.leftCols(k);
          }

          Eigen::Index
          cols() const
          {
            return k;
          }

          // V^T M X with X's mass product MX
          Eigen::MatrixXd
          project(const Eigen::MatrixXd &X, const Eigen::MatrixXd &MX) const
          {
            Eigen::MatrixXd h =
              stored ? Eigen::MatrixXd(MV_storage.leftCols(k).transpose() * X) :
                       Eigen::MatrixXd(V().transpose() * MX);
            sum_over_ranks(h, M.get_mpi_communicator());
            return h;
          }

          // X -= V (V^T M X), twice (block classical Gram-Schmidt in the M
          // inner product); returns the sum of the two coefficient blocks
          // (cols() x X.cols())
          Eigen::MatrixXd
          orthogonalise(Block &x) const
          {
            Eigen::MatrixXd H = Eigen::MatrixXd::Zero(k, x.W.cols());
            if (k == 0)
              return H;
            for (unsigned int pass = 0; pass < 2; ++pass)
              {
                const Eigen::MatrixXd h = project(x.W, x.MW);
                x.W.noalias() -= V() * h;
                if (stored)
                  x.MW.noalias() -= MV_storage.leftCols(k) * h;
                else
                  x.MW = multiply(M, x.W);
                H += h;
              }
            return H;
          }

          // V <- [V, W] (and M V)
          void
          append(const Block &w)
          {
            const Eigen::Index b = w.W.cols();
            if (k + b > V_storage.cols())
              throw std::logic_error("block Lanczos: the basis is full");
            V_storage.middleCols(k, b) = w.W;
            if (stored)
              MV_storage.middleCols(k, b) = w.MW;
            k += b;
          }

          // V <- V Y (and M V), Y cols() x m, m <= cols()
          void
          combine(const Eigen::MatrixXd &Y)
          {
            multiply_into_leading_columns(V_storage.leftCols(k), Y);
            if (stored)
              multiply_into_leading_columns(MV_storage.leftCols(k), Y);
            k = Y.cols();
          }

        private:
          Eigen::MatrixXd V_storage, MV_storage;
          Eigen::Index    k = 0;
        };

        // the largest M-norm of a block's columns
        double
        largest_m_norm(const Block &x, const MPI_Comm comm)
        {
          Eigen::MatrixXd squares = x.W.cwiseProduct(x.MW).colwise().sum();
          sum_over_ranks(squares, comm);
          return std::sqrt(std::max(0., squares.maxCoeff()));
        }

        // x.W <- x.W T, x.MW <- x.MW T
        void
        transform(Block &x, const Eigen::MatrixXd &T)
        {
          x.W  = (x.W * T).eval();
          x.MW = (x.MW * T).eval();
        }

        // Makes x.W M-orthonormal and M-orthogonal to V: W_before = W R
        // (plus V's part), R returned (b x b). Directions whose M-norm
        // fell below 1e-10 of @p reference (the largest M-norm before the
        // orthogonalisation against V: the block is nearly in the span)
        // are replaced by start vectors orthogonalised against V and the
        // rest, with zero rows in R. Cholesky QR twice, on W and M W
        // together (the transformations are b x b and well conditioned).
        Eigen::MatrixXd
        orthonormalise(const LanczosBasis     &basis,
                       Block                  &x,
                       const double            reference,
                       const dealii::IndexSet &owned,
                       std::uint64_t          &seed)
        {
          const MPI_Comm  comm = basis.M.get_mpi_communicator();
          const int       b    = x.W.cols();
          Eigen::MatrixXd G    = x.W.transpose() * x.MW;
          sum_over_ranks(G, comm);
          G = (G + G.transpose()).eval() / 2.;
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(G);
          transform(x, es.eigenvectors());
          Eigen::MatrixXd R = es.eigenvectors().transpose();
          for (int j = 0; j < b; ++j)
            {
              const double d = std::max(0., es.eigenvalues()[j]);
              if (d > 1e-20 * reference * reference)
                {
                  x.W.col(j) /= std::sqrt(d);
                  x.MW.col(j) /= std::sqrt(d);
                  R.row(j) *= std::sqrt(d);
                }
              else
                {
                  R.row(j).setZero();
                  Block y{Eigen::MatrixXd(x.W.rows(), 1), {}};
                  fill_start(y.W.col(0), owned, seed++);
                  y.MW = multiply(basis.M, y.W);
                  basis.orthogonalise(y);
                  x.W.col(j)  = y.W.col(0);
                  x.MW.col(j) = y.MW.col(0);
                }
            }
          // Cholesky QR twice (the replaced directions are orthogonalised
          // against the others here)
          for (unsigned int pass = 0; pass < 2; ++pass)
            {
              Eigen::MatrixXd G2 = x.W.transpose() * x.MW;
              sum_over_ranks(G2, comm);
              G2 = (G2 + G2.transpose()).eval() / 2.;
              Eigen::LLT<Eigen::MatrixXd> llt(G2);
              if (llt.info() != Eigen::Success)
                throw std::runtime_error(
                  "block Lanczos: a new block lost its M-orthogonality "
                  "(Cholesky QR failed)");
              const Eigen::MatrixXd U = llt.matrixU();
              const Eigen::MatrixXd U_inverse =
                U.triangularView<Eigen::Upper>().solve(
                  Eigen::MatrixXd::Identity(b, b));
              transform(x, U_inverse);
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
        // M V kept beside V unless the factors are out of core (the
        // memory is short then)
        const bool store_products = !factors_out_of_core();
        const auto [block, basis_size] =
          block_and_basis(wanted, N, !store_products);
        const Eigen::Index b       = block;
        const Eigen::Index largest = basis_size;
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
        // pass through the factors (out of core: read from disk twice).
        // The caller's block solves with the same factors (the full
        // solver's corrections, hundreds of columns) get the value back.
        PC  pc;
        Mat factors;
        check_petsc(KSPGetPC(static_cast<KSP>(shifted.solver->handle()), &pc),
                    "block Lanczos",
                    "KSPGetPC");
        check_petsc(PCFactorGetMatrix(pc, &factors),
                    "block Lanczos",
                    "PCFactorGetMatrix");
        PetscInt rhs_block = 0;
        check_petsc(MatMumpsGetIcntl(factors, 27, &rhs_block),
                    "block Lanczos",
                    "MatMumpsGetIcntl");
        check_petsc(MatMumpsSetIcntl(factors, 27, b),
                    "block Lanczos",
                    "MatMumpsSetIcntl");
        struct Restore
        {
          Mat      factors;
          PetscInt value;
          ~Restore()
          {
            MatMumpsSetIcntl(factors, 27, value);
          }
        } restore{factors, rhs_block};
        std::uint64_t seed = 1;
        void *const   ksp  = shifted.solver->handle();
        LanczosBasis  basis(M, store_products, n, largest);
        Block         next{Eigen::MatrixXd(n, b), {}};
        for (Eigen::Index j = 0; j < b; ++j)
          fill_start(next.W.col(j), owned, seed++);
        next.MW = multiply(M, next.W);
        orthonormalise(basis, next, largest_m_norm(next, comm), owned, seed);
        // OP V = V T + next F (the Krylov-Schur relation)
        Eigen::MatrixXd T(0, 0), F(b, 0);
        for (;; ++restarts)
          {
            while (basis.cols() + b <= largest)
              {
                const Eigen::Index k = basis.cols();
                basis.append(next);
                T.conservativeResize(k + b, k + b);
                T.bottomLeftCorner(b, k) = F;
                T.topRightCorner(k, b)   = F.transpose();
                const auto start         = std::chrono::steady_clock::now();
                Block      w{solve_block(ksp, shifted.P, next.MW), {}};
                ++block_solves;
                seconds_solves += std::chrono::duration<double>(
                                    std::chrono::steady_clock::now() - start)
                                    .count();
                w.MW                            = multiply(M, w.W);
                const double          reference = largest_m_norm(w, comm);
                const Eigen::MatrixXd H         = basis.orthogonalise(w);
                const Eigen::MatrixXd D         = H.bottomRows(b);
                T.bottomRightCorner(b, b)       = (D + D.transpose()) / 2.;
                const Eigen::MatrixXd R =
                  orthonormalise(basis, w, reference, owned, seed);
                next           = std::move(w);
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
                basis.combine(Y.leftCols(c));
                std::vector<UndampedMode> modes(c);
                for (Eigen::Index i = 0; i < c; ++i)
                  {
                    // theta descending: omega^2 ascending
                    modes[i].omega2 = {sigma + 1. / theta[i], 0.};
                    modes[i].re.reinit(owned, comm);
                    set_local_part(modes[i].re, basis.V().col(i));
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
            basis.combine(Y.leftCols(keep));
            T = theta.head(keep).asDiagonal();
            F = F * Y.leftCols(keep);
          }
      }
    } // namespace internal
  }   // namespace eigen
} // namespace squeal
