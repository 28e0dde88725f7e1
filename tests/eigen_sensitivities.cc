// Eigenvalue sensitivities (eigen/sensitivity.h) against two independent
// computations:
// - the two-degree-of-freedom model of Hoffmann et al. (verification A2)
//   with Rayleigh damping C = alpha I + beta K_sym: d lambda / d p for
//   p = b, mu, alpha, beta by implicit differentiation of the
//   characteristic polynomial F(lambda, p) = det(lambda^2 M + lambda C + K),
//   d lambda / d p = -F_p / F_lambda (closed form below), to 1e-9 of
//   |d lambda / d p|, at a stable point (mu = 0.2) and an unstable one
//   (mu = 0.5); the eigenvalue condition is 1 for the symmetric undamped
//   model (mu = 0) and exceeds 100 next to the lock-in (mu = 0.99999 mu_c);
// - the coarse TriboBrake (degree 1) at E_pad = 25 GPa, mu = 0.5 with the
//   Rayleigh damping on: central differences of the full solver's
//   eigenvalues (step h = 1e-5 of the parameter, Richardson-extrapolated
//   from the steps h and h/2; a step of 1e-3 is too coarse where disc
//   modes veer near 16.5 kHz) for pad.E, pad on disc.mu, pad on disc.k_n,
//   disc.rho and damping.beta, on every mode in 0.9-20 kHz whose condition
//   is below 100 (away from coalescence): |p (d_exact - d_fd)| <=
//   1e-5 |p d_fd| + 1e-7 |lambda| (measured: at most 0.15 of it). The left
//   eigenvectors' eigenvalues equal the right ones to 1e-9 |lambda|.

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/sensitivity.h>
#include <squeal/eigen/tracking.h>
#include <squeal/physics/structural_model.h>

#include "test_tools.h"

using namespace dealii;
using namespace squeal;
using test_tools::check;

namespace
{
  using TwoDof       = test_tools::HoffmannTwoDof;
  constexpr double a = TwoDof::a, b = TwoDof::b, c = TwoDof::c, k3 = TwoDof::k3;
  using complex = std::complex<double>;

  // d lambda / d (b, mu, alpha, beta) of a root of
  // F = (s + g a)(s + g b) - g^2 c^2 + mu k3 c g, s = lambda^2 + alpha
  // lambda, g = 1 + beta lambda (m = 1; K_sym = [[a, c], [c, b]],
  // K = K_sym + mu [[0, -k3], [0, 0]], C = alpha I + beta K_sym)
  std::vector<complex>
  closed_form(const complex l,
              const double  mu,
              const double  alpha,
              const double  beta)
  {
    const complex s = l * l + alpha * l, g = 1. + beta * l, ds = 2. * l + alpha;
    const complex F_l = (ds + beta * a) * (s + g * b) +
                        (s + g * a) * (ds + beta * b) - 2. * g * beta * c * c +
                        mu * k3 * c * beta;
    const complex F_b     = g * (s + g * a);
    const complex F_mu    = k3 * c * g;
    const complex F_alpha = l * (s + g * b) + l * (s + g * a);
    const complex F_beta  = l * a * (s + g * b) + l * b * (s + g * a) -
                           2. * g * l * c * c + mu * k3 * c * l;
    return {-F_b / F_l, -F_mu / F_l, -F_alpha / F_l, -F_beta / F_l};
  }

  void
  two_dof(ConditionalOStream &quiet)
  {
    const TwoDof                   model;
    const eigen::BandOptions       band{1., 1e4, 1., 1e-12, 2};
    const std::vector<std::string> names{"b", "mu", "alpha", "beta"};
    const double                   mu_c =
      ((a - b) * (a - b) + 4 * c * c) / (4 * c * k3); // 0.3125
    struct Case
    {
      std::string name;
      double      mu, alpha, beta;
    };
    for (const Case &k : {Case{"mu=0.2 damped", 0.2, 0.02, 1e-7},
                          Case{"mu=0.5 damped", 0.5, 0.02, 1e-7},
                          Case{"mu=0.5 undamped", 0.5, 0., 0.}})
      {
        const auto p     = TwoDof::point(b, k.mu, k.alpha, k.beta);
        const auto right = eigen::solve_full(model.parts(), p, band, quiet);
        const auto left =
          eigen::left_eigenvectors(model.parts(), p, band, right, quiet);
        const auto s =
          eigen::eigenvalue_sensitivities(model.parts(), p, names, right, left);
        check("2-DOF " + k.name + ": mode count", s.size(), 2, 0);
        for (unsigned int i = 0; i < s.size(); ++i)
          {
            const auto exact = closed_form(s[i].lambda, k.mu, k.alpha, k.beta);
            for (unsigned int j = 0; j < names.size(); ++j)
              check("2-DOF " + k.name + ": mode " + std::to_string(i) +
                      " d lambda / d " + names[j],
                    std::abs(s[i].derivative[j] - exact[j]),
                    0.,
                    1e-9,
                    std::abs(exact[j]));
          }
      }
    for (const double mu : {0., 0.99999 * mu_c})
      {
        const auto p     = TwoDof::point(b, mu);
        const auto right = eigen::solve_full(model.parts(), p, band, quiet);
        const auto left =
          eigen::left_eigenvectors(model.parts(), p, band, right, quiet);
        const auto s =
          eigen::eigenvalue_sensitivities(model.parts(), p, names, right, left);
        double least = 1e300;
        for (const auto &x : s)
          least = std::min(least, x.condition);
        test_tools::verbose()
          << "2-DOF mu = " << mu << ": least condition " << least << std::endl;
        if (mu == 0.)
          check("2-DOF mu=0: condition = 1", least, 1., 1e-10);
        else
          test_tools::check_true("2-DOF next to lock-in: condition > 100",
                                 least > 100);
      }
  }

  // the eigenvalues of @p b matched one to one to those of @p a
  std::vector<complex>
  matched(const std::vector<eigen::EigenPair> &a,
          const std::vector<eigen::EigenPair> &b)
  {
    Eigen::MatrixXd cost(a.size(), b.size());
    for (unsigned int i = 0; i < a.size(); ++i)
      for (unsigned int j = 0; j < b.size(); ++j)
        cost(i, j) =
          std::abs(a[i].lambda - b[j].lambda) / std::abs(a[i].lambda);
    const auto           to = eigen::optimal_assignment(cost, 1e-2);
    std::vector<complex> l;
    for (unsigned int i = 0; i < a.size(); ++i)
      l.push_back(to[i] < 0 ? complex(NAN, NAN) : b[to[i]].lambda);
    return l;
  }

  void
  tribobrake(ConditionalOStream &quiet)
  {
    const parameters::AllParameters prm = test_tools::coarse_tribobrake();
    physics::StructuralModel        model(prm, MPI_COMM_WORLD);
    model.setup_and_assemble(quiet);
    const auto              parts = model.parts();
    parameters::ScalarPoint p     = model.scene->nominal_point();
    p.set("pad.E", 25e9);
    p.set("pad on disc.mu", 0.5);
    const eigen::BandOptions       band{900., 20000., 100., 1e-10, 60};
    const std::vector<std::string> names{
      "pad.E", "pad on disc.mu", "pad on disc.k_n", "disc.rho", "damping.beta"};
    const auto right = eigen::solve_full(parts, p, band, quiet);
    const auto left  = eigen::left_eigenvectors(parts, p, band, right, quiet);
    double     worst_pair = 0, worst_residual = 0;
    for (unsigned int i = 0; i < right.size(); ++i)
      {
        worst_pair     = std::max(worst_pair,
                              std::abs(left[i].lambda - right[i].lambda) /
                                std::abs(right[i].lambda));
        worst_residual = std::max(worst_residual, left[i].residual);
      }
    test_tools::check_true("TriboBrake: modes in the band > 40",
                           right.size() > 40);
    check(
      "TriboBrake: left eigenvalues = right ones", worst_pair, 0., 1e-9, 1.);
    check("TriboBrake: left residuals <= 1e-10", worst_residual, 0., 1e-10, 1.);
    const auto s =
      eigen::eigenvalue_sensitivities(parts, p, names, right, left);

    for (unsigned int j = 0; j < names.size(); ++j)
      {
        const double value = p.get(names[j]);
        // lambda(value + t) for the pairs of the point
        const auto at = [&](const double t) {
          parameters::ScalarPoint q = p;
          q.set(names[j], value + t);
          return matched(right, eigen::solve_full(parts, q, band, quiet));
        };
        const double h  = 1e-5 * value;
        const auto   up = at(h), down = at(-h);
        const auto   up2 = at(h / 2), down2 = at(-h / 2);
        unsigned int compared = 0;
        double       worst    = 0;
        for (unsigned int i = 0; i < right.size(); ++i)
          {
            if (s[i].condition > 100)
              continue;
            const complex d1 = (up[i] - down[i]) / (2 * h);
            const complex d2 = (up2[i] - down2[i]) / h;
            const complex fd = (4. * d2 - d1) / 3.;
            const double  error =
              value * std::abs(s[i].derivative[j] - fd) /
              (1e-5 * value * std::abs(fd) + 1e-7 * std::abs(right[i].lambda));
            worst = std::max(worst, std::isfinite(error) ? error : 1e300);
            if (error > 0.1)
              test_tools::verbose()
                << "  " << names[j] << " mode " << i << " at "
                << right[i].lambda << ": condition " << s[i].condition
                << ", exact " << s[i].derivative[j] << ", differences " << fd
                << " (h: " << d1 << ", h/2: " << d2 << ")" << std::endl;
            ++compared;
          }
        test_tools::verbose()
          << names[j] << ": " << compared
          << " modes compared, worst error / tolerance " << worst << std::endl;
        check("TriboBrake: d lambda / d " + names[j] +
                " = central differences (error / tolerance)",
              worst,
              0.,
              1.,
              1.);
        test_tools::check_true("TriboBrake: " + names[j] +
                                 ": > 40 modes compared",
                               compared > 40);
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);
  two_dof(quiet);
  tribobrake(quiet);
  return test_tools::finish();
}
