// The modes of the symmetric problem (K_s, M) below a frequency, by SLEPc
// (shift-and-invert Krylov-Schur), PARPACK or squeal's block Lanczos, each
// with a factorisation of K_s - sigma M that the caller reuses (the full
// solver for its corrections, see full_solver.h; solve_undamped() for its
// purification). Included by full_solver.cc, qep_solver.cc and
// block_lanczos.cc only.

#ifndef squeal_eigen_symmetric_modes_h
#define squeal_eigen_symmetric_modes_h

#include <deal.II/lac/parpack_solver.h>
#include <deal.II/lac/solver_control.h>

#include <squeal/base/memory_estimate.h>
#include <squeal/eigen/qep_solver.h>

#include <slepceps.h>

#include "dense_block.h"

#include <algorithm>
#include <complex>
#include <iomanip>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace squeal
{
  namespace eigen
  {
    namespace internal
    {
      // The symmetric eigensolver that BandOptions::symmetric_solver
      // names; `auto`: block Lanczos (one pass through the factors per
      // block of vectors, in core and out of core)
      inline std::string
      symmetric_solver_for(const std::string &choice)
      {
        return choice == "auto" ? "block" : choice;
      }

      inline void
      check_eps(const PetscErrorCode ierr, const char *what)
      {
        check_petsc(ierr, "full solver", what);
      }

      // MODES in ascending order of omega^2
      inline std::vector<UndampedMode>
      sorted_by_omega2(std::vector<UndampedMode> modes)
      {
        std::sort(modes.begin(), modes.end(), [](const auto &a, const auto &b) {
          return a.omega2.real() < b.omega2.real();
        });
        return modes;
      }

      // The symmetric modes up to the basis frequency, by shift-and-invert
      // Krylov-Schur with a Cholesky factorisation that stays alive as the
      // preconditioner P^-1 of the refinement.
      class SymmetricModes
      {
      public:
        SymmetricModes(const PETScMatrix &K,
                       const PETScMatrix &M,
                       const double       sigma,
                       const double       tolerance)
        {
          check_eps(EPSCreate(M.get_mpi_communicator(), &eps), "EPSCreate");
          check_eps(EPSSetOperators(eps, K, M), "EPSSetOperators");
          check_eps(EPSSetProblemType(eps, EPS_GHEP), "EPSSetProblemType");
          check_eps(EPSSetType(eps, EPSKRYLOVSCHUR), "EPSSetType");
          check_eps(EPSSetTarget(eps, sigma), "EPSSetTarget");
          check_eps(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE),
                    "EPSSetWhichEigenpairs");
          check_eps(EPSSetTolerances(eps, tolerance, 2000), "EPSSetTolerances");
          // the caller purifies the eigenvectors in one block solve
          // (solve_full); SLEPc's purification is one solve per vector
          check_eps(EPSSetPurify(eps, PETSC_FALSE), "EPSSetPurify");
          ST st;
          check_eps(EPSGetST(eps, &st), "EPSGetST");
          ksp = static_cast<KSP>(internal::shift_invert_with_mumps(st, true));
          check_eps(EPSSetFromOptions(eps), "EPSSetFromOptions");
        }

        ~SymmetricModes()
        {
          EPSDestroy(&eps);
        }

        // Frees the eigensolver's Krylov basis (some 2 x wanted vectors)
        // once the modes are copied out; the factorisation of solver()
        // stays (destroying the EPS would reset it with the ST's KSP).
        void
        release_basis()
        {
          BV bv;
          check_eps(EPSGetBV(eps, &bv), "EPSGetBV");
          check_eps(BVResize(bv, 1, PETSC_FALSE), "BVResize");
        }

        SymmetricModes(const SymmetricModes &) = delete;
        SymmetricModes &
        operator=(const SymmetricModes &) = delete;

        // The eigenpairs with omega^2 below @p top, M-orthonormal, sorted;
        // @p wanted of them exist (the inertia count).
        std::vector<UndampedMode>
        solve(const PETScMatrix &M, const unsigned int wanted, const double top)
        {
          std::vector<UndampedMode> modes;
          for (unsigned int attempt = 0; attempt < 2; ++attempt)
            {
              const PetscInt nev =
                std::min<PetscInt>(M.m(), wanted + 2 + 10 * attempt);
              check_eps(
                EPSSetDimensions(eps, nev, PETSC_DEFAULT, PETSC_DEFAULT),
                "EPSSetDimensions");
              check_eps(EPSSolve(eps), "EPSSolve");
              PetscInt nconv;
              check_eps(EPSGetConverged(eps, &nconv), "EPSGetConverged");
              modes.clear();
              PETScVector xr(M.locally_owned_range_indices(),
                             M.get_mpi_communicator());
              for (PetscInt i = 0; i < nconv; ++i)
                {
                  PetscScalar kr, ki;
                  check_eps(EPSGetEigenpair(eps, i, &kr, &ki, xr, nullptr),
                            "EPSGetEigenpair");
                  if (kr < top)
                    modes.push_back({{kr, 0.}, xr, PETScVector()});
                }
              if (modes.size() == wanted)
                break;
            }
          return sorted_by_omega2(std::move(modes));
        }

        // the factorised K - sigma M
        void *
        solver() const
        {
          return ksp;
        }

      private:
        EPS eps;
        KSP ksp;
      };

      // K - sigma M and its MUMPS Cholesky (LDL^T) factorisation
      struct ShiftedCholesky
      {
        ShiftedCholesky(const PETScMatrix &K,
                        const PETScMatrix &M,
                        const double       sigma)
        {
          P.reinit(K);
          P.copy_from(K);
          add_scaled(P, -sigma, M);
          solver = std::make_unique<DirectSolver>(P, true);
        }

        PETScMatrix                   P;
        std::unique_ptr<DirectSolver> solver;
      };

      // The same with PARPACK (implicitly restarted Lanczos, mode 3:
      // shift-and-invert of the symmetric pencil) through deal.II's
      // PArpackSolver, the factorisation a DirectSolver (MUMPS Cholesky).
      class ArpackModes
      {
      public:
        ArpackModes(const PETScMatrix &K,
                    const PETScMatrix &M,
                    const double       sigma,
                    const double       tolerance)
          : K(K)
          , sigma(sigma)
          , tolerance(tolerance)
          , shifted(K, M, sigma)
        {}

        std::vector<UndampedMode>
        solve(const PETScMatrix &M, const unsigned int wanted, const double top)
        {
          // x = (K - sigma M)^-1 b for PARPACK
          struct Inverse
          {
            const DirectSolver &solver;
            void
            vmult(PETScVector &x, const PETScVector &b) const
            {
              solver.solve(b, x);
            }
          } inverse{*shifted.solver};
          const dealii::IndexSet    owned = M.locally_owned_range_indices();
          const MPI_Comm            comm  = M.get_mpi_communicator();
          std::vector<UndampedMode> modes;
          for (unsigned int attempt = 0; attempt < 2; ++attempt)
            {
              const unsigned int nev =
                std::min<unsigned int>(M.m() / 2 - 1,
                                       wanted + 2 + 10 * attempt);
              using Arpack = dealii::PArpackSolver<PETScVector>;
              dealii::SolverControl        control(10000, tolerance);
              const Arpack::AdditionalData data(
                std::min<unsigned int>(2 * nev + 2, M.m()),
                Arpack::largest_magnitude,
                true,
                3);
              Arpack arpack(control, comm, data);
              arpack.reinit(owned);
              arpack.set_shift(sigma);
              std::vector<std::complex<double>> lambda(nev);
              std::vector<PETScVector> x(nev, PETScVector(owned, comm));
              try
                {
                  arpack.solve(K, M, inverse, lambda, x, nev);
                }
              catch (const std::exception &e)
                {
                  throw std::runtime_error(
                    std::string("full solver: PARPACK failed: ") + e.what());
                }
              modes.clear();
              for (unsigned int i = 0; i < nev; ++i)
                if (lambda[i].real() < top)
                  modes.push_back(
                    {{lambda[i].real(), 0.}, x[i], PETScVector()});
              if (modes.size() == wanted)
                break;
            }
          return sorted_by_omega2(std::move(modes));
        }

        void *
        solver() const
        {
          return shifted.solver->handle();
        }

      private:
        const PETScMatrix &K;
        const double       sigma, tolerance;
        ShiftedCholesky    shifted;
      };

      // The same by thick-restart block Lanczos on the shift-and-invert
      // operator OP = (K - sigma M)^-1 M in the M inner product, the
      // factorisation a DirectSolver (MUMPS Cholesky): each step applies
      // OP to a block of vectors with one KSPMatSolve, a single pass
      // through the factors (in core a solve costs about a quarter per
      // column of a single one; out of core the factors are read from disk
      // once per block where Krylov-Schur and PARPACK read them once per
      // vector). Full block reorthogonalisation (block classical
      // Gram-Schmidt twice, then Cholesky QR twice), restarts keeping the
      // wanted Ritz vectors and one block more (Krylov-Schur restarts,
      // Stewart, SIAM J. Matrix Anal. Appl. 23 (2001), in their block
      // form), Ritz pairs converged when ||OP x - theta x||_M <= tolerance
      // theta. In core the basis' mass products M V are kept beside it, so
      // a step makes one sparse product (M of the new block); out of core
      // (memory short) they are not, and a step makes three. The basis
      // holds at most max(2 wanted + 2 b, wanted + 3 b) vectors (b the
      // block size, block_and_basis()). In block_lanczos.cc.
      class BlockModes
      {
      public:
        BlockModes(const PETScMatrix &K,
                   const PETScMatrix &M,
                   const double       sigma,
                   const double       tolerance);

        // The eigenpairs with omega^2 below @p top, M-orthonormal, sorted;
        // @p wanted of them exist (the inertia count).
        // @throws std::runtime_error if they do not converge in 100
        // restarts.
        std::vector<UndampedMode>
        solve(const PETScMatrix &M,
              const unsigned int wanted,
              const double       top);

        void *
        solver() const
        {
          return shifted.solver->handle();
        }

        // The block size and the largest basis for @p wanted modes of a
        // problem of size @p N (solve() uses them; held_vectors() counts
        // them). In core about wanted / 12 (measured on the TriboBrake,
        // 102 modes: blocks of 8 took 4.4 s, of 35 7.9 s, Krylov-Schur
        // 13 s; more columns in all as the block grows, each cheaper);
        // out of core about wanted / 3 (each block solve reads the
        // factors from disk: fewer, larger blocks), at most 64.
        static std::pair<std::size_t, std::size_t>
        block_and_basis(const std::size_t wanted,
                        const std::size_t N,
                        const bool        out_of_core)
        {
          const std::size_t c = wanted;
          const std::size_t b = std::max<std::size_t>(
            1,
            std::min<std::size_t>({64,
                                   out_of_core ?
                                     (c + 2) / 3 + 1 :
                                     std::max<std::size_t>(4, (c + 2) / 12 + 1),
                                   N / 4}));
          const std::size_t largest =
            std::min<std::size_t>(N - std::min(N, b),
                                  std::max(2 * c + 2 * b, c + 3 * b));
          return {b, largest};
        }

        // of the last solve: block size, block solves, restarts, seconds
        // in the block solves (the rest: orthogonalisation, restarts)
        unsigned int block_size = 0, block_solves = 0, restarts = 0;
        double       seconds_solves = 0.;

      private:
        const double    sigma, tolerance;
        ShiftedCholesky shifted;
      };

      // The eigensolver that BandOptions::symmetric_solver names
      // (symmetric_solver_for()), one of the three above, with its
      // factorisation of K - sigma M.
      class SymmetricEigensolver
      {
      public:
        SymmetricEigensolver(const PETScMatrix &K,
                             const PETScMatrix &M,
                             const double       sigma,
                             const double       tolerance,
                             const std::string &choice)
          : name(symmetric_solver_for(choice))
          , K(K)
          , sigma(sigma)
          , tolerance(tolerance)
          , automatic(choice == "auto")
        {
          if (name == "arpack")
            arpack = std::make_unique<ArpackModes>(K, M, sigma, tolerance);
          else if (name == "block")
            block = std::make_unique<BlockModes>(K, M, sigma, tolerance);
          else
            slepc = std::make_unique<SymmetricModes>(K, M, sigma, tolerance);
        }

        // see SymmetricModes::solve(); under `auto`, a problem too small
        // for block Lanczos (its basis and a block more than half the
        // space, where the Krylov space can run out: a model of a few
        // hundred DoFs) goes to Krylov-Schur
        std::vector<UndampedMode>
        solve(const PETScMatrix &M, const unsigned int wanted, const double top)
        {
          if (block && automatic)
            {
              const auto [b, largest] =
                BlockModes::block_and_basis(wanted,
                                            M.m(),
                                            factors_out_of_core());
              if (largest < wanted + b || 2 * (largest + b) > M.m())
                {
                  block.reset();
                  slepc =
                    std::make_unique<SymmetricModes>(K, M, sigma, tolerance);
                  name = "slepc";
                }
            }
          return arpack ? arpack->solve(M, wanted, top) :
                 block  ? block->solve(M, wanted, top) :
                          slepc->solve(M, wanted, top);
        }

        // the factorised K - sigma M
        void *
        solver() const
        {
          return arpack ? arpack->solver() :
                 block  ? block->solver() :
                          slepc->solver();
        }

        // frees Krylov-Schur's basis (the factorisation stays)
        void
        release_basis()
        {
          if (slepc)
            slepc->release_basis();
        }

        // The most vectors of the problem's size that solve() holds at
        // once for @p wanted modes of a problem of size @p N, the returned
        // modes included: Krylov-Schur's default basis of max(2 nev, nev +
        // 15) vectors (nev = wanted + 2), PARPACK's 2 nev + 2 and its nev
        // eigenvectors and three work vectors, block Lanczos's basis (and
        // in core its mass products) and four blocks (the next block, its
        // mass product, the operator's result and its mass product)
        static double
        held_vectors(const std::string &name,
                     const std::size_t  wanted,
                     const std::size_t  N)
        {
          const double nev = std::min<double>(N, wanted + 2);
          if (name == "arpack")
            return 2. * nev + 2. + nev + 3. + wanted;
          if (name == "block")
            {
              const bool out_of_core = factors_out_of_core();
              const auto [b, largest] =
                BlockModes::block_and_basis(wanted, N, out_of_core);
              return (out_of_core ? 1. : 2.) * double(largest) + 4. * b +
                     wanted;
            }
          return std::min<double>(N, std::max(2. * nev, nev + 15.)) + wanted;
        }

        // the name, and block Lanczos's counts and time of its last solve
        std::string
        summary() const
        {
          if (!block)
            return name;
          std::ostringstream text;
          text << name << ": " << block->block_solves << " block solves of "
               << block->block_size << " vectors in " << std::setprecision(3)
               << block->seconds_solves << " s, " << block->restarts
               << " restarts";
          return text.str();
        }

        std::string name;

      private:
        const PETScMatrix              &K;
        const double                    sigma, tolerance;
        const bool                      automatic;
        std::unique_ptr<SymmetricModes> slepc;
        std::unique_ptr<ArpackModes>    arpack;
        std::unique_ptr<BlockModes>     block;
      };
    } // namespace internal
  }   // namespace eigen
} // namespace squeal

#endif
