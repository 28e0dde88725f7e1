// Verification A2: the two-degree-of-freedom mode-coupling model of Hoffmann
// et al. (2002), M = m I, K = [[a, c - mu k3], [c, b]], solved through the
// same code path as the brake (PETSc matrix parts, solve_full, and the
// reduced model built on the full basis). Reference values: closed forms of
// verification.md A2 and an independent SciPy computation (mu_c with
// Rayleigh damping by bisection: 0.309435).

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/reduced_model.h>

#include "test_tools.h"

using namespace dealii;
using namespace squeal;

namespace
{
  using TwoDof       = test_tools::HoffmannTwoDof;
  constexpr double m = 1, a = TwoDof::a, b = TwoDof::b, c = TwoDof::c,
                   k3 = TwoDof::k3;

  std::vector<std::complex<double>>
  eigenvalues(const TwoDof &model,
              const double  mu,
              const double  alpha,
              const double  beta,
              const bool    reduced)
  {
    ConditionalOStream                quiet(std::cout, false);
    eigen::BandOptions                band{1., 1e4, 1., 1e-12, 2};
    std::vector<std::complex<double>> l;
    if (!reduced)
      for (const auto &p : eigen::solve_full(
             model.parts(), TwoDof::point(b, mu, alpha, beta), band, quiet))
        l.push_back(p.lambda);
    else
      {
        eigen::ReducedModel r;
        r.build(model.parts(), {TwoDof::point(b, 0.)}, band, 1.5, true, quiet);
        for (const auto &p :
             r.solve(TwoDof::point(b, mu, alpha, beta), 1., 1e4))
          l.push_back(p.lambda);
      }
    return l;
  }

  double
  max_re(const std::vector<std::complex<double>> &l)
  {
    double r = -1e300;
    for (const auto &x : l)
      r = std::max(r, x.real());
    return r;
  }

  double
  critical_mu(const TwoDof &model,
              const double  alpha,
              const double  beta,
              const bool    reduced)
  {
    double lo = 0.2, hi = 0.45;
    for (unsigned int i = 0; i < 40; ++i)
      {
        const double mid = (lo + hi) / 2;
        // undamped stable eigenvalues have Re at round-off level, not exactly 0
        (max_re(eigenvalues(model, mid, alpha, beta, reduced)) > 1e-4 ? hi :
                                                                        lo) =
          mid;
      }
    return (lo + hi) / 2;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using test_tools::check;
  const TwoDof model;
  const double two_pi = 2 * M_PI;
  for (const bool reduced : {false, true})
    {
      const std::string tag = reduced ? "reduced " : "full ";
      auto              l   = eigenvalues(model, 0., 0., 0., reduced);
      check(tag + "mu=0 count", l.size(), 2, 0);
      check(tag + "mu=0 f1 = 333.1614 Hz",
            l[0].imag() / two_pi,
            333.1614,
            1e-6);
      check(tag + "mu=0 f2 = 409.4347 Hz",
            l[1].imag() / two_pi,
            409.4347,
            1e-6);
      // closed form
      const double D = (a - b) * (a - b) + 4 * c * (c - 0.3 * k3);
      l              = eigenvalues(model, 0.3, 0., 0., reduced);
      check(tag + "mu=0.3 f1 closed form",
            l[0].imag(),
            std::sqrt((a + b - std::sqrt(D)) / (2 * m)),
            1e-8);
      check(tag + "mu=0.3 f2 closed form",
            l[1].imag(),
            std::sqrt((a + b + std::sqrt(D)) / (2 * m)),
            1e-8);
      check(tag + "mu=0.3 f1 = 365.5853 Hz",
            l[0].imag() / two_pi,
            365.5853,
            1e-6);
      check(tag + "mu=0.3 f2 = 380.7633 Hz",
            l[1].imag() / two_pi,
            380.7633,
            1e-6);
      check(tag + "mu=0.3 Re = 0", max_re(l), 0, 1e-9, 2352.);
      l = eigenvalues(model, 0.5, 0., 0., reduced);
      check(tag + "mu=0.5 |Re| = 184.071131",
            std::abs(l[0].real()),
            184.071131,
            1e-6);
      check(tag + "mu=0.5 Im = 2352.4205", l[0].imag(), 2352.4205, 1e-6);
      check(tag + "mu=0.5 one unstable", max_re(l), 184.071131, 1e-6);
      l = eigenvalues(model, 0.5, 0.02, 1e-7, reduced);
      std::sort(l.begin(), l.end(), [](auto x, auto y) {
        return x.real() < y.real();
      });
      check(tag + "Rayleigh mu=0.5 stable Re", l[0].real(), -184.3561, 1e-6);
      check(tag + "Rayleigh mu=0.5 stable Im", l[0].imag(), 2352.4349, 1e-6);
      check(tag + "Rayleigh mu=0.5 unstable Re", l[1].real(), 183.7861, 1e-6);
      check(tag + "Rayleigh mu=0.5 unstable Im", l[1].imag(), 2352.4060, 1e-6);
      check(tag + "mu_c undamped = 0.3125",
            critical_mu(model, 0., 0., reduced),
            0.3125,
            1e-4,
            1.);
      check(tag + "mu_c alpha=100 = 0.32625",
            critical_mu(model, 100., 0., reduced),
            0.32625,
            1e-4,
            1.);
      check(tag + "mu_c Rayleigh = 0.309435",
            critical_mu(model, 0.02, 1e-7, reduced),
            0.309435,
            1e-4,
            1.);
    }
  return test_tools::finish();
}
