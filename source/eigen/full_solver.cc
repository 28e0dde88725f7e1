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
#include "subspace.h"
#include "symmetric_modes.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace squeal
{
  namespace eigen
  {
    using namespace dealii;
    using internal::multiply;
    using internal::PointMatrices;
    using internal::residuals;
    using internal::ritz_pairs;
    using internal::Subspace;
    using internal::sum_over_ranks;

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

      // Davidson's directions for the Ritz pairs whose residual is above
      // TOL, from Y = P^-1 [Re r_j, Im r_j] (two columns per pair, in the
      // pairs' order; P = K_s + w_t^2 M, factorised in FACTORS): the second
      // term of the Neumann series (P - s_j M)^-1 = P^-1 + s_j P^-1 M P^-1
      // + ... with s_j = w_t^2 - lambda_j^2 added to each, so that Y
      // approximates T(lambda_j)^-1 r_j without friction and damping to
      // second order in the frequency instead of first (an error left in
      // the modes above the basis falls by (omega_j / omega_i)^4 a round
      // instead of (omega_j / omega_i)^2)
      void
      add_second_neumann_term(void              *factors,
                              const PETScMatrix &P,
                              const Subspace    &s,
                              const std::vector<internal::ProjectedPair> &pairs,
                              const std::vector<double>                  &res,
                              const double                                tol,
                              const double                                w_t,
                              Eigen::MatrixXd                            &Y)
      {
        Eigen::MatrixXd term =
          internal::solve_block(factors, P, s.mass_times(Y));
        int a = 0;
        for (unsigned int j = 0; j < pairs.size(); ++j)
          if (res[j] > tol)
            {
              const std::complex<double> shift =
                w_t * w_t - pairs[j].lambda * pairs[j].lambda;
              Y.col(2 * a) += shift.real() * term.col(2 * a) -
                              shift.imag() * term.col(2 * a + 1);
              Y.col(2 * a + 1) += shift.real() * term.col(2 * a + 1) +
                                  shift.imag() * term.col(2 * a);
              ++a;
            }
        if (2 * a != Y.cols())
          throw std::logic_error(
            "full solver: one residual pair per open mode");
      }

      // Whether NOW (lambda, residual) has pairs above TOL and every one of
      // them is stalled: its partner in BEFORE, the pair of nearest
      // lambda, lies within 1e-6 |lambda| and had less than twice its
      // residual.
      bool
      stalled(
        const std::vector<std::pair<std::complex<double>, double>> &now,
        const std::vector<std::pair<std::complex<double>, double>> &before,
        const double                                                tol)
      {
        bool open = false;
        for (const auto &[lambda, residual] : now)
          {
            if (!(residual > tol))
              continue;
            open            = true;
            double distance = std::numeric_limits<double>::infinity(),
                   partner  = 0.;
            for (const auto &[l, res] : before)
              if (std::abs(l - lambda) < distance)
                {
                  distance = std::abs(l - lambda);
                  partner  = res;
                }
            if (!(distance <= 1e-6 * std::abs(lambda)) ||
                residual < 0.5 * partner)
              return false;
          }
        return open;
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
               FullSolveReport               *report,
               KnownSymmetricModes           *symmetric_modes)
    {
      const auto          start = std::chrono::steady_clock::now();
      const PointMatrices A(model, point, band.store_products);
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
          const double factor =
            factorisation_bytes(K_s.n_nonzero_elements(), M.m(), true);
          report_memory_estimate(
            M.get_mpi_communicator(),
            pcout.is_active() ? &pcout.get_stream() : nullptr,
            M.m(),
            factor + (band.store_products ? 43. : 22.) * n_dofs * m,
            "the full solver's LDL^T and its subspace of about " +
              std::to_string(int(m)) +
              (band.store_products ? " vectors with their M, C and K products" :
                                     " vectors (products recomputed)"),
            factor);
        }

      const double                   t_count = seconds_since(start);
      internal::SymmetricEigensolver eigensolver(
        K_s, M, sigma, band.tolerance, band.symmetric_solver);
      std::vector<UndampedMode> modes =
        eigensolver.solve(M, r.symmetric_in_basis, top);
      void *const factorised        = eigensolver.solver();
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
      // eigenvector purification, for all of them in one block (as
      // solve_undamped() does for the reduced basis): a step of inverse
      // iteration x <- (K_s - sigma M)^-1 M x removes what the Krylov
      // basis left along the other eigenvectors (the close doublets of a
      // disc need it after Krylov-Schur); it scales an eigenvector by
      // 1 / (omega^2 - sigma), undone here (append() below
      // M-orthonormalises them)
      Phi = internal::solve_block(eigensolver.solver(), K_s, multiply(M, Phi));
      Phi *= (omega2.array() - sigma).matrix().asDiagonal();
      // the modes live on in Phi (and in the caller's copy); the
      // eigensolver's basis is not needed
      if (symmetric_modes)
        {
          symmetric_modes->mass                = c.mass;
          symmetric_modes->symmetric_stiffness = c.symmetric_stiffness;
          symmetric_modes->top_hz              = f_top;
          symmetric_modes->modes               = std::move(modes);
        }
      modes.clear();
      modes.shrink_to_fit();
      eigensolver.release_basis();
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
      // each round's pairs (lambda, residual): the rounds stop when every
      // pair above the tolerance has a partner two rounds earlier (the
      // nearest eigenvalue there, within 1e-6 of |lambda|) whose residual
      // it has not halved: stalled at the rounding floor of the products,
      // of the order of eps (omega_max / omega)^2 for a mode of frequency
      // omega on a mesh whose highest is omega_max. A pair that has just
      // entered the band has no partner and keeps the rounds going.
      std::vector<std::vector<std::pair<std::complex<double>, double>>> history;
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
          history.emplace_back();
          for (unsigned int j = 0; j < pairs.size(); ++j)
            history.back().emplace_back(pairs[j].lambda, res[j]);
          r.stalled = history.size() > 2 && stalled(history.back(),
                                                    history[history.size() - 3],
                                                    band.residual_tolerance);
          if (corrections.cols() == 0 || r.rounds == band.max_rounds ||
              r.stalled)
            break;
          Eigen::MatrixXd directions =
            internal::solve_block(factorised, K_s, corrections);
          corrections.resize(0, 0);
          add_second_neumann_term(factorised,
                                  K_s,
                                  s,
                                  pairs,
                                  res,
                                  band.residual_tolerance,
                                  w_t,
                                  directions);
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
            << (r.stalled ? ", stalled: none of them halved its residual "
                            "in two rounds" :
                            "")
            << "); " << t_count << " s count, " << t_symmetric - t_count
            << " s symmetric modes, " << t_projection << " s projection, "
            << r.seconds - t_symmetric - t_projection << " s refinement ("
            << r.seconds_projected << " s projected eigenproblems, "
            << r.seconds_residuals << " s residuals, " << r.seconds_solves
            << " s block solves, " << r.seconds_growth << " s subspace growth; "
            << eigensolver.name << " for the symmetric modes); peak memory "
            << r.peak_memory_mb << " MB (" << 1024. * r.peak_memory_mb / M.m()
            << " kB per DoF)" << std::endl;
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
      const PointMatrices AP(model, point, band.store_products);
      const PETScMatrix  &M = AP.M, &K_s = AP.K_s;
      const IndexSet      owned = M.locally_owned_range_indices();
      const int           n     = owned.n_elements();
      IterateReport       r;
      Subspace            s(AP, band.store_products);
      // room for every block below: none is copied as the subspace grows
      s.reserve(n, start.size() * (levels + 1));
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
    {
      // M, C and K at a point are never formed (three matrices of the
      // common pattern): every product comes from the parts
      parts = std::make_unique<const internal::PartsProduct>(model);
    }

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
      // M(p), C(p) and K(p) are never formed (M only for P): the
      // subspace's products come from the parts
      const PETScMatrix M, C, K;
      if (!solver || k != key)
        {
          // P = K_s + (2 pi f_t)^2 M: positive definite, one Cholesky
          const auto start = std::chrono::steady_clock::now();
          solver.reset();
          model.symmetric_stiffness(point, P);
          {
            PETScMatrix mass;
            model.mass(point, mass);
            const double w_t = 2. * numbers::PI * band.target_frequency;
            internal::add_scaled(P, w_t * w_t, mass);
          }
          solver = std::make_unique<DirectSolver>(P, true);
          key    = k;
          ++n_factorisations;
          seconds_factorising += seconds_since(start);
        }
      if (band.store_products && start.MV.cols() != start.V.cols())
        throw std::logic_error(
          "PairRefiner::refine: the projection has no products "
          "(ReducedModel::projection(p, true) with stored products)");
      Subspace s(M,
                 C,
                 K,
                 std::move(start),
                 band.store_products,
                 model.matrix(0).get_mpi_communicator());
      s.use_parts(*parts, c, true);
      const unsigned int                   n_pairs = lambda.size();
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
