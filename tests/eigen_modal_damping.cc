// Modal damping (Damping/Modal damping ratios; physics::MatrixParts::
// ModalDamping) in the full and the reduced solver, on a small TriboBrake
// (degree 1, about 1 600 DoFs) with the ratios 0.5 % at 1 kHz falling
// linearly to 0.1 % at 10 kHz (constant beyond), modes up to 25 kHz damped.
// Checks:
// 1. Without friction and Rayleigh damping, C = sum 2 zeta omega M phi
//    phi^T M is diagonal in the modes, so every eigenvalue is exactly
//    lambda = omega (-zeta + i sqrt(1 - zeta^2)): |lambda| = omega and
//    -Re lambda / |lambda| = zeta(omega / 2 pi) (1e-8), in both solvers,
//    with the full solver's count equal to the inertia count of the band.
// 2. With friction (mu = 0.6, a locked-in pair) and the Rayleigh damping,
//    the full solver against an independent dense solve: the modes of
//    (K_s, M) by Eigen's dense generalized eigensolver, the modal C built
//    from them, every eigenvalue of the quadratic problem by LAPACK's dgeev
//    (tests/dense_qep.h);
//    one-to-one matching, frequencies within 1e-8, real parts within
//    1e-6 |lambda|; the modal damping moves the growth rates (by more than
//    1 1/s against the same model without it).
// 3. The reduced model against the full solver there: same count, growth
//    rates within 1e-4 |lambda|, frequencies within 2e-5; its full-model
//    residuals from Gram matrices equal those of the projection's
//    products (C V with the modal damping) within 1e-6.

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/reduced_model.h>
#include <squeal/eigen/tracking.h>
#include <squeal/physics/structural_model.h>

#include "dense_qep.h"
#include "test_tools.h"

#include <algorithm>

using namespace dealii;
using namespace squeal;

namespace
{
  Eigen::MatrixXd
  dense(const physics::PETScMatrix &A)
  {
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(A.m(), A.n());
    for (unsigned int i = 0; i < A.m(); ++i)
      for (auto it = A.begin(i); it != A.end(i); ++it)
        D(i, it->column()) = it->value();
    return D;
  }

  // the largest relative differences of frequency and real part over a
  // one-to-one matching of @p a to @p b (unmatched: returned as a count)
  struct Comparison
  {
    unsigned int unmatched = 0;
    double       frequency = 0., real_part = 0.;
  };

  Comparison
  compare(const std::vector<std::complex<double>> &a,
          const std::vector<std::complex<double>> &b)
  {
    Eigen::MatrixXd cost(a.size(), b.size());
    for (unsigned int i = 0; i < a.size(); ++i)
      for (unsigned int j = 0; j < b.size(); ++j)
        cost(i, j) = std::abs(b[j] - a[i]) / std::abs(a[i]);
    const auto match = eigen::optimal_assignment(cost);
    Comparison c;
    for (unsigned int i = 0; i < a.size(); ++i)
      {
        if (match[i] < 0)
          {
            ++c.unmatched;
            continue;
          }
        const auto d = b[match[i]];
        c.frequency =
          std::max(c.frequency, std::abs(a[i].imag() - d.imag()) / d.imag());
        c.real_part =
          std::max(c.real_part, std::abs(a[i].real() - d.real()) / std::abs(d));
      }
    return c;
  }

  // the eigenvalues of full (eigen::EigenPair) or reduced pairs
  template <typename Pair>
  std::vector<std::complex<double>>
  eigenvalues(const std::vector<Pair> &pairs)
  {
    std::vector<std::complex<double>> l;
    for (const auto &p : pairs)
      l.push_back(p.lambda);
    return l;
  }

  // the largest |zeta - zeta(f)| of eigenvalues that must be
  // omega (-zeta + i sqrt(1 - zeta^2))
  double
  ratio_error(const std::vector<std::complex<double>>  &lambda,
              const physics::MatrixParts::ModalDamping &modal)
  {
    double e = 0.;
    for (const auto &l : lambda)
      e = std::max(e,
                   std::abs(-l.real() / std::abs(l) -
                            modal.ratio(std::abs(l) / (2 * M_PI))));
    return e;
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
  prm.eigensolver.f_max         = 20000.;
  prm.eigensolver.reduced_band_factor = 1.25;
  prm.damping.modal_ratios            = {{1000., 0.005}, {10000., 0.001}};
  physics::StructuralModel model(prm, MPI_COMM_WORLD);
  model.setup_and_assemble(quiet);
  const auto  parts = model.parts();
  const auto &modal = parts.modal;
  check("modal cutoff = 1.25 f_max [Hz]", modal.cutoff, 25000., 1e-15);
  check("ratio at 5.5 kHz (midway)", modal.ratio(5500.), 0.003, 1e-14);
  check("ratio below the first frequency", modal.ratio(10.), 0.005, 1e-15);
  check("ratio above the last frequency", modal.ratio(3e4), 0.001, 1e-15);

  const double       f_min = 900., f_max = 20000.;
  eigen::BandOptions band{f_min, f_max, 100., 1e-10, 60};

  // 1. no friction, no Rayleigh damping: the closed form
  {
    parameters::ScalarPoint p = model.scene->nominal_point();
    p.set("pad on disc.mu", 0.);
    p.set("damping.alpha", 0.);
    p.set("damping.beta", 0.);
    eigen::FullSolveReport report;
    const auto full = eigen::solve_full(parts, p, band, quiet, &report);
    test_tools::verbose() << "no friction: " << full.size() << " modes (full), "
                          << report.symmetric_in_band
                          << " by inertia; largest ratio error "
                          << ratio_error(eigenvalues(full), modal) << std::endl;
    check("no friction: full modes = inertia count",
          full.size(),
          report.symmetric_in_band,
          0);
    check("no friction: at least 10 modes",
          std::min<double>(full.size(), 10),
          10,
          0);
    check("no friction, full: -Re lambda / |lambda| = zeta(f) to 1e-8",
          std::max(ratio_error(eigenvalues(full), modal), 1e-8),
          1e-8,
          0);

    eigen::ReducedModel reduced;
    reduced.build(parts, {p}, band, 1.25, 1, quiet);
    const auto red = reduced.solve(p, f_min, f_max);
    const auto c   = compare(eigenvalues(red), eigenvalues(full));
    test_tools::verbose() << "no friction, reduced: " << red.size()
                          << " modes; ratio error "
                          << ratio_error(eigenvalues(red), modal)
                          << ", against full: frequency " << c.frequency
                          << ", real part " << c.real_part << std::endl;
    check("no friction, reduced: -Re lambda / |lambda| = zeta(f) to 1e-8",
          std::max(ratio_error(eigenvalues(red), modal), 1e-8),
          1e-8,
          0);
    check("no friction: reduced modes = full", red.size(), full.size(), 0);
    check("no friction: reduced frequencies within 1e-6 of full",
          std::max(c.frequency, 1e-6),
          1e-6,
          0);
  }

  // 2. friction and Rayleigh damping: against the dense solve
  parameters::ScalarPoint       point = model.scene->nominal_point();
  std::vector<eigen::EigenPair> full;
  point.set("pad on disc.mu", 0.6);
  const auto unstable = [](const std::vector<std::complex<double>> &l) {
    return std::count_if(l.begin(), l.end(), [](const auto &x) {
      return x.real() > 1e-6 * std::abs(x);
    });
  };
  for (const double E : {25e9, 10e9, 40e9, 63e9, 100e9, 5e9})
    {
      point.set("pad.E", E);
      full = eigen::solve_full(parts, point, band, quiet);
      if (unstable(eigenvalues(full)) > 0)
        break;
    }

  physics::PETScMatrix Mp, Cp, Kp, Ksp;
  parts.mass(point, Mp);
  parts.damping(point, Cp);
  parts.stiffness(point, Kp);
  parts.symmetric_stiffness(point, Ksp);
  const Eigen::MatrixXd M = dense(Mp), K = dense(Kp), Ks = dense(Ksp);
  Eigen::MatrixXd       C = dense(Cp);
  {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ks, M);
    const double top    = std::pow(2 * M_PI * modal.cutoff, 2);
    unsigned int damped = 0;
    for (int i = 0; i < es.eigenvalues().size(); ++i)
      {
        const double w2 = es.eigenvalues()[i];
        if (!(w2 > 0.) || w2 > top)
          continue;
        const double          zeta = modal.ratio(std::sqrt(w2) / (2 * M_PI));
        const Eigen::VectorXd Mphi = M * es.eigenvectors().col(i);
        C += 2. * zeta * std::sqrt(w2) * Mphi * Mphi.transpose();
        ++damped;
      }
    test_tools::verbose() << "dense: " << M.rows() << " DoFs, " << damped
                          << " modally damped modes, E_pad = "
                          << point.get("pad.E") << " Pa" << std::endl;
  }
  std::vector<std::complex<double>> dense_band;
  for (const auto &l : test_tools::dense_qep_eigenvalues_cholesky(M, C, K))
    if (l.imag() > 0 && l.imag() / (2 * M_PI) >= f_min &&
        l.imag() / (2 * M_PI) <= f_max)
      dense_band.push_back(l);
  const auto c = compare(eigenvalues(full), dense_band);
  test_tools::verbose() << "friction: " << full.size() << " modes (full), "
                        << dense_band.size() << " (dense), "
                        << unstable(eigenvalues(full))
                        << " unstable; frequency error " << c.frequency
                        << ", real-part error " << c.real_part << std::endl;
  check("friction: modes in the band full = dense",
        full.size(),
        dense_band.size(),
        0);
  check("friction: every full eigenvalue matched", c.unmatched, 0, 0);
  check("friction: frequencies within 1e-8",
        std::max(c.frequency, 1e-8),
        1e-8,
        0);
  check("friction: real parts within 1e-6 |lambda|",
        std::max(c.real_part, 1e-6),
        1e-6,
        0);
  check("friction: an unstable mode in the dense solve",
        std::min<long>(unstable(dense_band), 1),
        1,
        0);
  check("friction: unstable modes full = dense",
        unstable(eigenvalues(full)),
        unstable(dense_band),
        0);
  {
    physics::MatrixParts rayleigh_only = parts;
    rayleigh_only.modal.ratios.clear();
    const auto without = eigen::solve_full(rayleigh_only, point, band, quiet);
    const auto d       = compare(eigenvalues(full), eigenvalues(without));
    double     shift   = 0.;
    for (const auto &p : full)
      {
        double nearest = 1e300, re = 0.;
        for (const auto &q : without)
          if (std::abs(q.lambda - p.lambda) < nearest)
            {
              nearest = std::abs(q.lambda - p.lambda);
              re      = q.lambda.real();
            }
        shift = std::max(shift, std::abs(p.lambda.real() - re));
      }
    test_tools::verbose() << "largest change of a growth rate by the modal "
                          << "damping: " << shift << " 1/s (" << d.real_part
                          << " of |lambda| matched)" << std::endl;
    check("friction: the modal damping moves a growth rate by > 1 1/s",
          std::min(shift, 1.),
          1.,
          0);
  }

  // 3. the reduced model at this point
  {
    eigen::ReducedModel reduced;
    reduced.build(parts, {point}, band, 1.25, 1, quiet);
    const auto red = reduced.solve(point, f_min, f_max);
    const auto d   = compare(eigenvalues(red), eigenvalues(full));
    // the residuals from the Gram matrices against the products of the
    // projection (C V holds the modal damping (M V) B)
    const eigen::Projection P              = reduced.projection(point);
    double                  worst_residual = 0., residual_error = 0.;
    for (const auto &p : red)
      {
        worst_residual           = std::max(worst_residual, p.residual);
        const auto             l = p.lambda;
        const Eigen::VectorXcd m = P.MV * p.q, cv = P.CV * p.q, k = P.KV * p.q;
        const double           direct =
          (l * l * m + l * cv + k).norm() /
          (std::norm(l) * m.norm() + std::abs(l) * cv.norm() + k.norm());
        // the Gram form loses about 1e-8 (relative) to cancellation
        residual_error =
          std::max(residual_error, std::abs(p.residual - direct));
      }
    test_tools::verbose() << "reduced residuals, Gram against direct: "
                          << residual_error << std::endl;
    check("friction: reduced residuals (Gram) = direct within 1e-6",
          std::max(residual_error, 1e-6),
          1e-6,
          0);
    check("friction: a reduced residual above 1e-6 (the comparison sees "
          "the basis error)",
          std::min(worst_residual, 1e-6),
          1e-6,
          0);
    test_tools::verbose() << "friction, reduced: " << red.size()
                          << " modes; against full: frequency " << d.frequency
                          << ", real part " << d.real_part
                          << "; largest full-model residual " << worst_residual
                          << std::endl;
    check("friction: reduced modes = full", red.size(), full.size(), 0);
    check("friction: reduced eigenvalues all matched", d.unmatched, 0, 0);
    check("friction: reduced frequencies within 2e-5",
          std::max(d.frequency, 2e-5),
          2e-5,
          0);
    check("friction: reduced real parts within 1e-4 |lambda|",
          std::max(d.real_part, 1e-4),
          1e-4,
          0);
    check("friction: reduced unstable modes = full",
          unstable(eigenvalues(red)),
          unstable(eigenvalues(full)),
          0);

    // the products released (as the CEA does before its check): the basis
    // still expands a mode, a further solve is refused
    physics::PETScVector before_re, before_im, after_re, after_im;
    reduced.expand(red[0].q, before_re, before_im);
    reduced.release_products();
    reduced.expand(red[0].q, after_re, after_im);
    const double norm = before_re.l2_norm();
    after_re -= before_re;
    test_tools::check_true("released: the basis expands a mode unchanged",
                           norm > 0. && after_re.l2_norm() == 0.);
    bool refused = false;
    try
      {
        reduced.solve(point, f_min, f_max);
      }
    catch (const std::logic_error &)
      {
        refused = true;
      }
    test_tools::check_true("released: a further reduced solve is refused",
                           refused);
  }
  return test_tools::finish();
}
