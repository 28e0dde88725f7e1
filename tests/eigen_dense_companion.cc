// The full solver against an independent dense solve of the same matrices:
// a small TriboBrake (degree 1, 1 600 DoFs) at mu = 0.6 and the first pad
// modulus of a list where the full solver finds a locked-in (unstable) pair,
// non-proportional damping (Rayleigh on the bodies only, the interface
// stiffness undamped), its M, C, K exported by io::export_matrices in the
// MatrixMarket format, read back by io::read_matrix_market, and every
// eigenvalue of the scaled companion matrix of the Cholesky-congruent
// problem computed by LAPACK dgeev (tests/dense_qep.h: no projection, no
// shift, no iteration of squeal's). Checks:
// - the export round trip: the read K has the model's norm (to 1e-13);
// - the same number of eigenvalues in the band, matched one to one;
// - frequencies within 1e-8 (relative) and real parts within 1e-6 |lambda|;
// - the unstable pair is there in both, with its growth rate;
// each for the full solver with its subspace products stored and
// recomputed (BandOptions::store_products), the latter with every residual
// below 1e-10.

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/tracking.h>
#include <squeal/io/matrix_export.h>
#include <squeal/physics/structural_model.h>

#include "dense_qep.h"
#include "test_tools.h"

#include <algorithm>
#include <filesystem>

using namespace dealii;
using namespace squeal;

namespace
{
  Eigen::MatrixXd
  dense(const io::Triplets &t)
  {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(t.rows, t.columns);
    for (const auto &[i, j, v] : t.entries)
      A(i, j) += v;
    return A;
  }

  // Checks the full solver's eigenvalues @p full against the dense ones
  void
  compare(const std::string                       &label,
          const std::vector<eigen::EigenPair>     &full,
          const std::vector<std::complex<double>> &dense_band)
  {
    using test_tools::check;
    Eigen::MatrixXd cost(full.size(), dense_band.size());
    for (unsigned int i = 0; i < full.size(); ++i)
      for (unsigned int j = 0; j < dense_band.size(); ++j)
        cost(i, j) =
          std::abs(dense_band[j] - full[i].lambda) / std::abs(full[i].lambda);
    const auto   match = eigen::optimal_assignment(cost);
    double       df = 0., dre = 0.;
    unsigned int unmatched = 0, unstable_full = 0, unstable_dense = 0;
    double       growth_full = 0., growth_dense = 0.;
    for (unsigned int i = 0; i < full.size(); ++i)
      {
        const auto f = full[i].lambda;
        if (match[i] < 0)
          {
            ++unmatched;
            continue;
          }
        const auto d = dense_band[match[i]];
        df           = std::max(df, std::abs(f.imag() - d.imag()) / d.imag());
        dre = std::max(dre, std::abs(f.real() - d.real()) / std::abs(d));
        test_tools::verbose()
          << "  " << f.imag() / (2 * M_PI) << " Hz: Re " << f.real()
          << " (full), " << d.real() << " (dense)" << std::endl;
        if (f.real() > 1e-6 * std::abs(f))
          {
            ++unstable_full;
            growth_full = std::max(growth_full, f.real());
          }
      }
    for (const auto &d : dense_band)
      if (d.real() > 1e-6 * std::abs(d))
        {
          ++unstable_dense;
          growth_dense = std::max(growth_dense, d.real());
        }
    test_tools::verbose() << full.size() << " modes (full), "
                          << dense_band.size()
                          << " (dense); largest frequency error " << df
                          << ", real-part error " << dre << " of |lambda|; "
                          << "growth rate " << growth_full << " (full), "
                          << growth_dense << " (dense)" << std::endl;
    check(label + ": modes in the band: full = dense",
          full.size(),
          dense_band.size(),
          0);
    check(label + ": at least 10 modes in the band",
          std::min<double>(full.size(), 10),
          10,
          0);
    check(label + ": every full eigenvalue matched", unmatched, 0, 0);
    check(label + ": frequencies within 1e-8", std::max(df, 1e-8), 1e-8, 0);
    check(label + ": real parts within 1e-6 |lambda|",
          std::max(dre, 1e-6),
          1e-6,
          0);
    check(label + ": an unstable (locked-in) mode in the dense solve",
          std::min(unstable_dense, 1u),
          1,
          0);
    check(label + ": unstable modes: full = dense",
          unstable_full,
          unstable_dense,
          0);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using test_tools::check;
  ConditionalOStream quiet(std::cout, false);

  parameters::AllParameters prm = test_tools::coarse_tribobrake(48, 4, 1, 2, 1);
  prm.mesh.support_cells_length = 4;
  physics::StructuralModel model(prm, MPI_COMM_WORLD);
  model.setup_and_assemble(quiet);
  const auto parts = model.parts();

  const double       f_min = 900., f_max = 20000.;
  eigen::BandOptions band{f_min, f_max, 100., 1e-10, 60};
  // the first pad modulus with a locked-in (unstable) pair at mu = 0.6
  parameters::ScalarPoint       point = model.scene->nominal_point();
  std::vector<eigen::EigenPair> full;
  point.set("pad on disc.mu", 0.6);
  for (const double E : {25e9, 10e9, 40e9, 63e9, 100e9, 5e9})
    {
      point.set("pad.E", E);
      full = eigen::solve_full(parts, point, band, quiet);
      if (std::any_of(full.begin(), full.end(), [](const auto &p) {
            return p.lambda.real() > 1e-6 * std::abs(p.lambda);
          }))
        break;
    }

  const std::string dir = "matrices";
  std::filesystem::create_directories(dir);
  io::export_matrices(model, {{0, point}}, dir);
  const Eigen::MatrixXd M =
                          dense(io::read_matrix_market(dir + "/point_0_M.mtx")),
                        C =
                          dense(io::read_matrix_market(dir + "/point_0_C.mtx")),
                        K =
                          dense(io::read_matrix_market(dir + "/point_0_K.mtx"));
  {
    physics::PETScMatrix Kp;
    parts.stiffness(point, Kp);
    check("export: |K|_F read back", K.norm(), Kp.frobenius_norm(), 1e-13);
  }
  test_tools::verbose() << "dense solve of " << M.rows()
                        << " DoFs at E_pad = " << point.get("pad.E") << " Pa"
                        << std::endl;

  std::vector<std::complex<double>> dense_band;
  for (const auto &l : test_tools::dense_qep_eigenvalues_cholesky(M, C, K))
    if (l.imag() > 0 && l.imag() / (2 * M_PI) >= f_min &&
        l.imag() / (2 * M_PI) <= f_max)
      dense_band.push_back(l);


  // the full solver with its subspace products stored (the default) and
  // recomputed, each against the dense solve
  // the full solver with BAND_OF_RUN, its report printed under LABEL
  const auto solve = [&](const std::string        &label,
                         const eigen::BandOptions &band_of_run,
                         eigen::FullSolveReport   &report) {
    auto pairs = eigen::solve_full(parts, point, band_of_run, quiet, &report);
    test_tools::verbose() << label << ": largest residual "
                          << report.largest_residual << " after "
                          << report.rounds << " rounds" << std::endl;
    return pairs;
  };
  eigen::BandOptions recomputed_band = band;
  recomputed_band.store_products     = false;
  eigen::FullSolveReport recomputed_report;
  const auto             recomputed =
    solve("recomputed products", recomputed_band, recomputed_report);
  check("recomputed products: every residual below 1e-10",
        std::max(recomputed_report.largest_residual, 1e-10),
        1e-10,
        0);
  // a tolerance below the products' rounding floor: the rounds stop when
  // the largest residual has stopped falling, long before the round limit
  eigen::BandOptions unattainable = band;
  unattainable.residual_tolerance = 1e-18;
  eigen::FullSolveReport floor_report;
  const auto floored = solve("tolerance 1e-18", unattainable, floor_report);
  check("tolerance 1e-18: the rounds stop as stalled",
        floor_report.stalled ? 1 : 0,
        1,
        0);
  check("tolerance 1e-18: before the round limit of 20",
        floor_report.rounds < unattainable.max_rounds ? 1 : 0,
        1,
        0);
  check("tolerance 1e-18: every residual below 1e-10 (the floor reached)",
        std::max(floor_report.largest_residual, 1e-10),
        1e-10,
        0);
  compare("stored products", full, dense_band);
  compare("recomputed products", recomputed, dense_band);
  compare("tolerance 1e-18", floored, dense_band);
  return test_tools::finish();
}
