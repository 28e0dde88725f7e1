// SLEPc-based sparse eigensolvers: the generalised problem whose real modes
// build the reduced basis (EPS/Krylov-Schur with one real shift, asking for
// more eigenvalues until the band is covered) and a kept MUMPS LU
// factorisation.

#include <deal.II/base/exceptions.h>

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/qep_solver.h>

#include <petscksp.h>
#include <slepceps.h>

#include "dense_block.h"
#include "symmetric_modes.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace squeal
{
  namespace eigen
  {
    using namespace dealii;

    namespace
    {
      void
      check(const PetscErrorCode ierr, const char *what)
      {
        internal::check_petsc(ierr, "eigensolver", what);
      }

      PETScVector
      make_vector(const PETScMatrix &A)
      {
        PETScVector v(A.locally_owned_range_indices(),
                      A.get_mpi_communicator());
        return v;
      }

      // The memory the symmetric eigensolver is about to allocate, printed
      // before it does: K - sigma M (12 bytes per nonzero in PETSc's AIJ
      // storage), PETSc's triplets of its upper triangle for MUMPS (8 per
      // nonzero), the LDL^T (factorisation_bytes()) and the vectors the
      // eigensolver holds (held_vectors(), 8 bytes per entry); the count
      // of modes is known from the inertia
      void
      report_eigensolver_memory(const PETScMatrix  &M,
                                const PETScMatrix  &K,
                                const unsigned int  count,
                                const std::string  &choice,
                                ConditionalOStream &pcout)
      {
        const std::size_t nonzeros = K.n_nonzero_elements();
        const double      factor   = factorisation_bytes(nonzeros, K.m(), true);
        // once more if this estimate sent the factors out of core (under
        // `auto` storage), which changes `auto`'s eigensolver
        for (std::string name = internal::symmetric_solver_for(choice);;)
          {
            const double vectors =
              internal::SymmetricEigensolver::held_vectors(name, count, M.m());
            report_memory_estimate(
              M.get_mpi_communicator(),
              pcout.is_active() ? &pcout.get_stream() : nullptr,
              M.m(),
              factor + 20. * double(nonzeros) + 8. * vectors * double(M.m()),
              "the undamped eigensolver (" + name + ", " +
                std::to_string(count) +
                " modes): the LDL^T of K - sigma M, its copy and " +
                std::to_string(int(vectors)) + " vectors",
              factor);
            const std::string now = internal::symmetric_solver_for(choice);
            if (now == name)
              return;
            name = now;
          }
      }

      // The symmetric pencil's modes below f_top: exactly as many as the
      // Sylvester inertia count gives, by the eigensolver that
      // options.symmetric_solver names, then purified.
      std::vector<UndampedMode>
      symmetric_undamped(const PETScMatrix  &M,
                         const PETScMatrix  &K,
                         const BandOptions  &options,
                         const double        sigma,
                         const double        f_top,
                         ConditionalOStream &pcout)
      {
        const double       w_1   = 2. * numbers::PI * f_top;
        const double       top   = w_1 * w_1;
        const unsigned int count = count_eigenvalues_below(K, M, {top})[0];
        report_eigensolver_memory(M, K, count, options.symmetric_solver, pcout);
        internal::SymmetricEigensolver eigensolver(
          K, M, sigma, options.tolerance, options.symmetric_solver);
        std::vector<UndampedMode> modes = eigensolver.solve(M, count, top);
        // the eigensolver's vectors are not needed any more; the
        // factorisation stays for the purification
        eigensolver.release_basis();
        void *const       ksp    = eigensolver.solver();
        const std::string solver = eigensolver.name;
        if (modes.size() != count)
          throw std::runtime_error("undamped eigensolver (" + solver +
                                   "): " + std::to_string(modes.size()) +
                                   " modes below " + std::to_string(f_top) +
                                   " Hz where the Sylvester inertia count "
                                   "gives " +
                                   std::to_string(count));
        // one step of inverse iteration for all of them, x <- (K - sigma
        // M)^-1 M x (it removes what the eigensolver's basis left along
        // the other eigenvectors, as SLEPc's purification does), then unit
        // M-norm; 64 modes at a time (three blocks of them in memory)
        const IndexSet        owned = M.locally_owned_range_indices();
        constexpr std::size_t width = 64;
        for (std::size_t j0 = 0; j0 < modes.size(); j0 += width)
          {
            const std::size_t w = std::min(width, modes.size() - j0);
            Eigen::MatrixXd   X(owned.n_elements(), w);
            for (std::size_t j = 0; j < w; ++j)
              X.col(j) = internal::local_part(modes[j0 + j].re, owned);
            X = internal::solve_block(ksp, K, internal::multiply(M, X));
            Eigen::MatrixXd norms =
              X.cwiseProduct(internal::multiply(M, X)).colwise().sum();
            internal::sum_over_ranks(norms, M.get_mpi_communicator());
            for (std::size_t j = 0; j < w; ++j)
              {
                X.col(j) /= std::sqrt(norms(0, j));
                internal::set_local_part(modes[j0 + j].re, X.col(j));
              }
          }
        pcout << "  undamped eigensolver: " << modes.size() << " modes up to "
              << f_top << " Hz, as many as the inertia count ("
              << eigensolver.summary() << ")" << std::endl;
        return modes;
      }
    } // namespace

    std::vector<UndampedMode>
    solve_undamped(const PETScMatrix  &M,
                   const PETScMatrix  &K,
                   const BandOptions  &options,
                   const double        factor,
                   const bool          symmetric,
                   ConditionalOStream &pcout)
    {
      const double   w_t    = 2. * numbers::PI * options.target_frequency;
      const double   sigma  = -w_t * w_t;
      const double   w_1    = 2. * numbers::PI * options.f_max * factor;
      const double   needed = w_1 * w_1 - sigma;
      const PetscInt n      = M.m();
      if (symmetric)
        return symmetric_undamped(
          M, K, options, sigma, options.f_max * factor, pcout);
      PetscInt nev = std::min<PetscInt>(options.initial_nev, n);
      for (unsigned int attempt = 0;; ++attempt)
        {
          EPS eps;
          check(EPSCreate(M.get_mpi_communicator(), &eps), "EPSCreate");
          check(EPSSetOperators(eps, K, M), "EPSSetOperators");
          check(EPSSetProblemType(eps, EPS_GNHEP), "EPSSetProblemType");
          check(EPSSetType(eps, EPSKRYLOVSCHUR), "EPSSetType");
          check(EPSSetTarget(eps, sigma), "EPSSetTarget");
          check(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE),
                "EPSSetWhichEigenpairs");
          ST st;
          check(EPSGetST(eps, &st), "EPSGetST");
          internal::shift_invert_with_mumps(st, false);
          check(EPSSetDimensions(eps, nev, PETSC_DEFAULT, PETSC_DEFAULT),
                "EPSSetDimensions");
          check(EPSSetTolerances(eps, options.tolerance, 2000),
                "EPSSetTolerances");
          check(EPSSolve(eps), "EPSSolve");
          PetscInt nconv;
          check(EPSGetConverged(eps, &nconv), "EPSGetConverged");
          std::vector<UndampedMode> modes;
          double                    farthest = 0;
          PETScVector               xr = make_vector(M), xi = make_vector(M);
          for (PetscInt i = 0; i < nconv; ++i)
            {
              PetscScalar kr, ki;
              check(EPSGetEigenpair(eps, i, &kr, &ki, xr, xi),
                    "EPSGetEigenpair");
              farthest = std::max(farthest, std::hypot(kr - sigma, ki));
              if (kr <= w_1 * w_1 && ki >= 0)
                {
                  UndampedMode m{{kr, ki}, xr, xi};
                  if (ki == 0)
                    m.im = 0;
                  modes.push_back(std::move(m));
                }
            }
          const bool covered = farthest >= needed || nconv >= n;
          EPSDestroy(&eps);
          if (covered)
            {
              std::sort(modes.begin(),
                        modes.end(),
                        [](const auto &a, const auto &b) {
                          return a.omega2.real() < b.omega2.real();
                        });
              pcout << "  undamped eigensolver: " << nconv
                    << " eigenvalues converged, " << modes.size()
                    << " modes up to " << options.f_max * factor << " Hz"
                    << std::endl;
              return modes;
            }
          if (attempt > 8)
            throw std::runtime_error(
              "undamped eigensolver: could not converge eigenvalues up to " +
              std::to_string(options.f_max * factor) + " Hz");
          // The count of modes grows roughly linearly with omega for
          // plate-like structures (omega^2 ratio square-rooted); aim beyond.
          const double ratio = farthest > 0 ? std::sqrt(needed / farthest) : 2.;
          nev                = std::min<PetscInt>(
            n, std::max<PetscInt>(nev + 10, nconv * ratio * 1.25 + 10));
          pcout << "  undamped eigensolver: band not covered, asking for "
                << nev << " eigenvalues" << std::endl;
        }
    }

    DirectSolver::DirectSolver(const PETScMatrix &A, const bool symmetric)
    {
      KSP k;
      check(KSPCreate(A.get_mpi_communicator(), &k), "KSPCreate");
      check(KSPSetOperators(k, A, A), "KSPSetOperators");
      internal::use_mumps(k, symmetric);
      check(KSPSetUp(k), "KSPSetUp");
      ksp = k;
    }

    DirectSolver::~DirectSolver()
    {
      KSP k = static_cast<KSP>(ksp);
      KSPDestroy(&k);
    }

    void
    DirectSolver::solve(const PETScVector &b, PETScVector &x) const
    {
      check(KSPSolve(static_cast<KSP>(ksp), b, x), "KSPSolve");
    }
  } // namespace eigen
} // namespace squeal
