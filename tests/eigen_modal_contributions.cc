// Modal contributions (eigen/modal_contribution.h) on the two-degree-of-
// freedom model of Hoffmann et al. (verification A2), undamped, M = I:
// the frictionless modes are the eigenvectors of K_sym = [[a, c], [c, b]]
// (frequencies omega^2 = (a + b -+ sqrt((a - b)^2 + 4 c^2)) / 2, 333.1614
// and 409.4347 Hz, to 1e-12), and a complex mode x of K x = -lambda^2 x
// (an eigenvector of the non-symmetric K, Eigen's dense solver) has the
// shares |phi_k^T x|^2 / x^H x. At mu = 0.2 (stable) and mu = 0.5 (the
// unstable pair, locked in) the shares of squeal's full-solver modes equal
// the dense ones to 1e-10 and the two modes capture all of x (1e-12).

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/modal_contribution.h>

#include <Eigen/Eigenvalues>

#include "test_tools.h"

using namespace dealii;
using namespace squeal;
using test_tools::check;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);
  using TwoDof       = test_tools::HoffmannTwoDof;
  constexpr double a = TwoDof::a, b = TwoDof::b, c = TwoDof::c, k3 = TwoDof::k3;
  const TwoDof     model;
  const eigen::BandOptions band{1., 1e4, 1., 1e-12, 2};

  // the frictionless modes: closed-form frequencies
  const auto modes = eigen::frictionless_modes(
    model.parts(), TwoDof::point(b, 0.5), band, 1.5, quiet);
  check("frictionless modes: count", modes.frequency.size(), 2, 0);
  const double root = std::sqrt((a - b) * (a - b) + 4 * c * c);
  for (unsigned int k = 0; k < 2; ++k)
    check("frictionless mode " + std::to_string(k) + " closed form",
          modes.frequency[k],
          std::sqrt((a + b + (k == 0 ? -root : root)) / 2) / (2 * M_PI),
          1e-12);

  Eigen::Matrix2d K_sym;
  K_sym << a, c, c, b;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> symmetric(K_sym);
  for (const double mu : {0.2, 0.5})
    {
      const std::string at = "mu = " + std::to_string(mu).substr(0, 3);
      Eigen::Matrix2d   K  = K_sym;
      K(0, 1) -= mu * k3;
      const Eigen::EigenSolver<Eigen::Matrix2d> dense(K);
      const auto                                pairs =
        eigen::solve_full(model.parts(), TwoDof::point(b, mu), band, quiet);
      check(at + ": modes in the band", pairs.size(), 2, 0);
      for (const auto &x : pairs)
        {
          const auto contributions = eigen::modal_contributions(modes, x);
          // the dense mode with the same -lambda^2
          const std::complex<double> target = -x.lambda * x.lambda;
          int                        j      = 0;
          for (int i = 1; i < 2; ++i)
            if (std::abs(dense.eigenvalues()[i] - target) <
                std::abs(dense.eigenvalues()[j] - target))
              j = i;
          const Eigen::Vector2cd v     = dense.eigenvectors().col(j);
          const double           norm2 = v.squaredNorm();
          const std::string      name =
            at + ", " + std::to_string(int(x.lambda.imag() / (2 * M_PI))) +
            " Hz";
          for (unsigned int k = 0; k < 2; ++k)
            {
              const std::complex<double> projection =
                symmetric.eigenvectors()
                  .col(k)
                  .cast<std::complex<double>>()
                  .dot(v);
              check(name + ": share of frictionless mode " + std::to_string(k),
                    std::norm(contributions.coefficient[k]),
                    std::norm(projection) / norm2,
                    1e-10,
                    1.);
            }
          check(name + ": captured = 1", contributions.captured, 1., 1e-12);
        }
    }
  return test_tools::finish();
}
