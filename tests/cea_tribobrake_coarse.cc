// The TriboBrake on a coarse mesh (degree 1), through the full and the
// reduced solvers:
// - A5 without damping (which would hide small growth): at mu = 0 every
//   |Re lambda| <= 1e-8 |lambda| and the mode count equals the symmetric
//   problem's inertia count; at mu = 0.01 the largest growth rate is
//   printed (SQUEAL_VERBOSE) and Re lambda <= 1e-8 |lambda| (no lock-in
//   this close to the frictionless modes: 1.8e-15 measured); with the Rayleigh
//   damping on, no eigenvalue in 0.9-20 kHz has a positive real part at mu =
//   0.01 (thesis § 3.3.2); at E_pad = 1e9, 1e10, 1e11 Pa;
// - reduced against full (verification A6) at (25 GPa, 0.5) and
//   (40 GPa, 0.2): one-to-one (optimal assignment), equal mode counts,
//   frequency within 0.1 % and growth rate within 2 % of |Re| + 1 1/s;
// - certification (eigen::PairRefiner): the pairs of a deliberately poor
//   reduced model (real modes to 1.1 f_max, no enrichment) refined on the
//   full model agree one to one with the full solver to 1e-8 of |lambda|,
//   with residuals below 1e-10;
// - the full solver with PARPACK (deal.II's PArpackSolver) for the
//   symmetric modes equals the one with SLEPc to 1e-9 of |lambda|;
// - the eigenvalues of the first point are printed to 8 digits: the
//   .mpirun=2 variant must reproduce the serial ones (numdiff, 1e-8).

#include <squeal/base/memory_estimate.h>
#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/reduced_model.h>
#include <squeal/eigen/tracking.h>
#include <squeal/physics/structural_model.h>

#include "test_tools.h"

using namespace dealii;
using namespace squeal;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using test_tools::check;
  ConditionalOStream pcout(std::cout,
                           Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) ==
                             0);
  ConditionalOStream quiet(std::cout, false);

  const parameters::AllParameters prm = test_tools::coarse_tribobrake();
  physics::StructuralModel        model(prm, MPI_COMM_WORLD);
  model.setup_and_assemble(quiet);
  const auto parts    = model.parts();
  const auto at_point = [&](const double E, const double mu) {
    parameters::ScalarPoint p = model.scene->nominal_point();
    p.set("pad.E", E);
    p.set("pad on disc.mu", mu);
    return p;
  };
  eigen::BandOptions band{900., 20000., 100., 1e-10, 60};

  for (const double mu : {0., 0.01})
    for (const double E : {1e9, 1e10, 1e11})
      {
        const std::string at = " mu = " + std::to_string(mu).substr(0, 4) +
                               ", E_pad = " + std::to_string(int(E / 1e9)) +
                               " GPa";
        auto undamped = at_point(E, mu);
        undamped.set("damping.alpha", 0.);
        undamped.set("damping.beta", 0.);
        eigen::FullSolveReport report;
        const auto             pairs =
          eigen::solve_full(parts, undamped, band, quiet, &report);
        double largest_ratio = 0., max_re = -1e300;
        for (const auto &p : pairs)
          {
            largest_ratio =
              std::max(largest_ratio, p.lambda.real() / std::abs(p.lambda));
            max_re = std::max(max_re, p.lambda.real());
          }
        test_tools::verbose()
          << "A5 undamped" << at << ": " << pairs.size()
          << " modes, largest Re lambda " << max_re << " 1/s, Re/|lambda| "
          << largest_ratio << std::endl;
        check("A5 undamped" + at + ": modes = inertia count of the band",
              pairs.size(),
              report.symmetric_in_band,
              0);
        if (mu == 0.)
          {
            double largest_abs = 0.;
            for (const auto &p : pairs)
              largest_abs =
                std::max(largest_abs,
                         std::abs(p.lambda.real()) / std::abs(p.lambda));
            check("A5 undamped" + at + ": |Re lambda| <= 1e-8 |lambda|",
                  std::max(largest_abs, 1e-8),
                  1e-8,
                  0.);
          }
        else
          check("A5 undamped" + at + ": Re lambda <= 1e-8 |lambda|",
                std::max(largest_ratio, 1e-8),
                1e-8,
                0.);
        if (mu > 0.)
          {
            const auto damped =
              eigen::solve_full(parts, at_point(E, mu), band, quiet);
            double largest = -1e300;
            for (const auto &p : damped)
              largest = std::max(largest, p.lambda.real());
            check("A5 damped" + at + ": largest Re lambda <= 0",
                  std::max(largest, 0.),
                  0.,
                  0.,
                  1.);
            check("A5 damped" + at + ": as many modes as undamped",
                  damped.size(),
                  pairs.size(),
                  0);
          }
      }

  eigen::ReducedModel reduced;
  reduced.build(parts,
                {at_point(1e9, 0), at_point(1e10, 0), at_point(1e11, 0)},
                band,
                1.5,
                true,
                quiet);
  bool first = true;
  for (const auto &[E, mu] : {std::pair{25e9, 0.5}, std::pair{40e9, 0.2}})
    {
      const auto full = eigen::solve_full(parts, at_point(E, mu), band, quiet);
      const auto red  = reduced.solve(at_point(E, mu), 900., 20000.);
      double     df = 0, dre = 0, residual = 0;
      // one to one: the assignment of least total relative distance
      Eigen::MatrixXd cost(full.size(), red.size());
      for (unsigned int i = 0; i < full.size(); ++i)
        for (unsigned int j = 0; j < red.size(); ++j)
          cost(i, j) =
            std::abs(red[j].lambda - full[i].lambda) / std::abs(full[i].lambda);
      const auto   match     = eigen::optimal_assignment(cost);
      unsigned int unmatched = 0;
      for (unsigned int i = 0; i < full.size(); ++i)
        {
          const auto &f = full[i];
          if (match[i] < 0)
            {
              ++unmatched;
              continue;
            }
          const auto &best = red[match[i]];
          df               = std::max(df,
                        std::abs(best.lambda.imag() - f.lambda.imag()) /
                          f.lambda.imag());
          dre              = std::max(dre,
                         std::abs(best.lambda.real() - f.lambda.real()) /
                           (std::abs(f.lambda.real()) + 1.));
          residual         = std::max(residual, f.residual);
        }
      const std::string at = " at E_pad = " + std::to_string(int(E / 1e9)) +
                             " GPa, mu = " + std::to_string(mu).substr(0, 3);
      check("full solver modes in the band" + at + " (at least 40)",
            std::min<double>(full.size(), 40),
            40,
            0);
      check("full solver residuals below 1e-10" + at,
            std::max(residual, 1e-10),
            1e-10,
            0);
      check("reduced: as many modes as full" + at, red.size(), full.size(), 0);
      check("reduced: every full mode matched" + at, unmatched, 0, 0);
      check("reduced frequency error below 0.1 %" + at,
            std::max(df, 1e-3),
            1e-3,
            0);
      check("reduced growth-rate error below 2 % of |Re| + 1" + at,
            std::max(dre, 2e-2),
            2e-2,
            0);
      if (first)
        {
          pcout << "Eigenvalues" << at << " (1/s):" << std::endl;
          for (unsigned int k = 0; k < std::min<std::size_t>(12, full.size());
               ++k)
            pcout << std::setprecision(8) << "  " << full[k].lambda.real()
                  << " " << full[k].lambda.imag() << std::endl;
          first = false;
        }
    }

  // the full solver with PARPACK, and with squeal's block Lanczos (the
  // default; in core with the basis' mass products, out of core without),
  // for the symmetric modes instead of SLEPc's Krylov-Schur; and the
  // reduced basis's modes of one sample by block Lanczos against
  // Krylov-Schur
  {
    const auto point              = at_point(25e9, 0.5);
    auto       krylov_schur       = band;
    krylov_schur.symmetric_solver = "slepc";
    eigen::FullSolveReport slepc_report;
    const auto             slepc =
      eigen::solve_full(parts, point, krylov_schur, quiet, &slepc_report);
    for (const std::string solver : {"arpack", "block", "block out of core"})
      {
        auto other             = band;
        other.symmetric_solver = solver.substr(0, solver.find(' '));
        if (solver == "block out of core")
          set_factor_storage("out of core", "");
        eigen::FullSolveReport report;
        const auto             other_modes =
          eigen::solve_full(parts, point, other, quiet, &report);
        set_factor_storage("in core", "");
        double largest = 0., residual = 0.;
        for (unsigned int i = 0; i < std::min(slepc.size(), other_modes.size());
             ++i)
          {
            largest =
              std::max(largest,
                       std::abs(slepc[i].lambda - other_modes[i].lambda) /
                         std::abs(slepc[i].lambda));
            residual = std::max(residual, other_modes[i].residual);
          }
        test_tools::verbose()
          << solver << " against SLEPc's Krylov-Schur: " << other_modes.size()
          << " and " << slepc.size() << " modes, largest difference " << largest
          << ", residual " << residual << std::endl;
        check(solver + ": the inertia count's symmetric modes, all found",
              report.symmetric_in_basis,
              slepc_report.symmetric_in_basis,
              0);
        check(solver + ": as many modes in the band as Krylov-Schur",
              other_modes.size(),
              slepc.size(),
              0);
        check(solver + " = Krylov-Schur to 1e-9 of |lambda|",
              std::max(largest, 1e-9),
              1e-9,
              0);
        check(solver + ": residuals below 1e-10",
              std::max(residual, 1e-10),
              1e-10,
              0);
      }
    const auto         sample = at_point(25e9, 0.);
    eigen::PETScMatrix K, M;
    parts.symmetric_stiffness(sample, K);
    parts.mass(sample, M);
    auto block             = band;
    block.symmetric_solver = "block";
    const auto krylov =
      eigen::solve_undamped(M, K, krylov_schur, 1.5, true, quiet);
    const auto blockwise = eigen::solve_undamped(M, K, block, 1.5, true, quiet);
    double     largest   = 0.;
    // relative to omega^2 - sigma (sigma = -(2 pi 100 Hz)^2, the shift):
    // the rigid-body mode's omega^2 is zero to rounding
    const double sigma = -std::pow(2. * numbers::PI * band.target_frequency, 2);
    for (unsigned int i = 0; i < std::min(krylov.size(), blockwise.size()); ++i)
      largest = std::max(largest,
                         std::abs(krylov[i].omega2 - blockwise[i].omega2) /
                           std::abs(krylov[i].omega2 - sigma));
    test_tools::verbose() << "undamped modes: " << blockwise.size()
                          << ", block Lanczos against Krylov-Schur " << largest
                          << std::endl;
    check("undamped modes to 1.5 f_max: block Lanczos as many as Krylov-Schur",
          blockwise.size(),
          krylov.size(),
          0);
    check(
      "undamped modes: block Lanczos = Krylov-Schur to 1e-9 of omega^2 - sigma",
      std::max(largest, 1e-9),
      1e-9,
      0);
  }

  // certification of a poor reduced model's pairs on the full model
  {
    eigen::ReducedModel poor;
    poor.build(parts, {at_point(25e9, 0)}, band, 1.1, 0, quiet);
    const auto point = at_point(25e9, 0.5);
    const auto red   = poor.solve(point, 900., 20000.);
    const auto full  = eigen::solve_full(parts, point, band, quiet);
    std::vector<std::complex<double>> lambda;
    std::vector<Eigen::VectorXcd>     q;
    for (const auto &r : red)
      {
        lambda.push_back(r.lambda);
        q.push_back(r.q);
      }
    eigen::PairRefiner refiner(parts, band);
    const auto         refined =
      refiner.refine(point, poor.projection(point), lambda, q);
    const auto error = [&](const auto &values) {
      Eigen::MatrixXd cost(full.size(), values.size());
      for (unsigned int i = 0; i < full.size(); ++i)
        for (unsigned int j = 0; j < values.size(); ++j)
          cost(i, j) = std::abs(values[j].lambda - full[i].lambda) /
                       std::abs(full[i].lambda);
      const auto match   = eigen::optimal_assignment(cost);
      double     largest = 0.;
      for (unsigned int i = 0; i < full.size(); ++i)
        largest = match[i] < 0 ? 1. : std::max(largest, cost(i, match[i]));
      return largest;
    };
    double largest_residual = 0.;
    for (const auto &r : refined)
      largest_residual = std::max(largest_residual, r.residual);
    test_tools::verbose() << "certification: " << red.size()
                          << " reduced pairs, error against full " << error(red)
                          << " before, " << error(refined)
                          << " after; largest residual " << largest_residual
                          << std::endl;
    check("certification: as many pairs as the full solver",
          refined.size(),
          full.size(),
          0);
    check("certification: the poor reduced model is off by more than 1e-6",
          std::min(error(red), 1e-6),
          1e-6,
          0);
    check("certification: refined = full to 1e-8 of |lambda|",
          std::max(error(refined), 1e-8),
          1e-8,
          0);
    check("certification: residuals below 1e-10",
          std::max(largest_residual, 1e-10),
          1e-10,
          0);
    check("certification: one factorisation", refiner.factorisations(), 1, 0);

    // the same with recomputed products (a projection without them)
    eigen::BandOptions lean_band = band;
    lean_band.store_products     = false;
    eigen::PairRefiner lean(parts, lean_band);
    const auto         lean_refined =
      lean.refine(point, poor.projection(point, false), lambda, q);
    double lean_residual = 0.;
    for (const auto &r : lean_refined)
      lean_residual = std::max(lean_residual, r.residual);
    test_tools::verbose() << "certification, recomputed products: error "
                          << error(lean_refined) << ", largest residual "
                          << lean_residual << std::endl;
    check("certification, recomputed products: refined = full to 1e-8",
          std::max(error(lean_refined), 1e-8),
          1e-8,
          0);
    check("certification, recomputed products: residuals below 1e-10",
          std::max(lean_residual, 1e-10),
          1e-10,
          0);
  }
  return test_tools::finish();
}
