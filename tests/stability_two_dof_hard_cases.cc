// Numerical stability on hard cases, on the two-degree-of-freedom model of
// Hoffmann et al. (2002) (verification A2), K = [[a, c - mu k3], [c, b]],
// M = I, through the same solvers as the brake:
// - exact lock-in: at mu_c = ((a - b)^2 / 4c + c) / k3 = 0.3125 the two
//   eigenvalues coalesce (an exceptional point, parallel eigenvectors); both
//   solvers still return both, at omega^2 = (a + b) / 2 with Re ~ 0, and with
//   small residuals;
// - tracking through lock-in and lock-out: b swept linearly over 1e6-9e6
//   (41 points, the pad-modulus part of the parts carries b) at mu = 0.5:
//   closed form unstable for |a - b| < 2 sqrt(c (mu k3 - c)) = 2e6, so one
//   region over b in (3e6, 7e6): points 3.2e6-6.8e6; two tracks throughout,
//   and where stable each track moves to the nearest frequency (no swap);
// - large damping (alpha = 1e3 1/s, beta = 1e-5 s) and zero damping: every
//   eigenvalue equals an independent dense computation (Eigen's real
//   nonsymmetric solver on the 4 x 4 companion matrix) to 1e-8.

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/reduced_model.h>
#include <squeal/eigen/tracking.h>

#include <Eigen/Eigenvalues>

#include "test_tools.h"

using namespace dealii;
using namespace squeal;

namespace
{
  using Model        = test_tools::HoffmannTwoDof;
  constexpr double a = Model::a, b0 = Model::b, c = Model::c, k3 = Model::k3;

  // Independent: eigenvalues with Im > 0 of the companion matrix of
  // lambda^2 I + lambda C + K, by Eigen.
  std::vector<std::complex<double>>
  dense_reference(const double b,
                  const double mu,
                  const double alpha,
                  const double beta)
  {
    Eigen::Matrix2d K, Ks;
    Ks << a, c, c, b;
    K << a, c - mu * k3, c, b;
    const Eigen::Matrix2d C   = alpha * Eigen::Matrix2d::Identity() + beta * Ks;
    Eigen::Matrix4d       A   = Eigen::Matrix4d::Zero();
    A.topRightCorner(2, 2)    = Eigen::Matrix2d::Identity();
    A.bottomLeftCorner(2, 2)  = -K;
    A.bottomRightCorner(2, 2) = -C;
    std::vector<std::complex<double>> l;
    // the solver outlives the loop over the eigenvalues it holds
    const Eigen::EigenSolver<Eigen::Matrix4d> solver(A);
    for (const auto &x : solver.eigenvalues())
      if (x.imag() > 0)
        l.push_back(x);
    std::sort(l.begin(), l.end(), [](auto x, auto y) {
      return x.imag() < y.imag();
    });
    return l;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using test_tools::check;
  ConditionalOStream       quiet(std::cout, false);
  const Model              model;
  const eigen::BandOptions band{1., 1e4, 1., 1e-12, 2};
  eigen::ReducedModel      reduced;
  reduced.build(model.parts(), {Model::point(b0, 0.)}, band, 1.5, true, quiet);

  // 1. the exceptional point
  const double mu_c = ((a - b0) * (a - b0) / (4 * c) + c) / k3;
  const double w_c  = std::sqrt((a + b0) / 2);
  {
    const auto full =
      eigen::solve_full(model.parts(), Model::point(b0, mu_c), band, quiet);
    const auto red = reduced.solve(Model::point(b0, mu_c), 1., 1e4);
    for (const bool is_full : {true, false})
      {
        const std::string                 tag = is_full ? "full" : "reduced";
        std::vector<std::complex<double>> l;
        double                            residual = 0;
        if (is_full)
          for (const auto &p : full)
            {
              l.push_back(p.lambda);
              residual = std::max(residual, p.residual);
            }
        else
          for (const auto &p : red)
            {
              l.push_back(p.lambda);
              residual = std::max(residual, p.residual);
            }
        check("exact lock-in, " + tag + ": both eigenvalues returned",
              l.size(),
              2,
              0);
        for (unsigned int k = 0; k < std::min<std::size_t>(2, l.size()); ++k)
          {
            const std::string m = " (eigenvalue " + std::to_string(k) + ")";
            check("exact lock-in, " + tag + ": omega = sqrt((a+b)/2)" + m,
                  l[k].imag(),
                  w_c,
                  1e-7);
            // at an exceptional point round-off eps splits the eigenvalues
            // by about sqrt(eps) |lambda|
            check("exact lock-in, " + tag + ": Re lambda ~ 0" + m,
                  l[k].real(),
                  0.,
                  1e-6,
                  w_c);
          }
        // the eigenvalue of an exceptional point is only determined to
        // about sqrt(eps): residuals of that size are the best possible
        check("exact lock-in, " + tag + ": residuals below 1e-6",
              std::max(residual, 1e-6),
              1e-6,
              0);
      }
  }

  // 2. tracking through lock-in and lock-out along b at mu = 0.5
  {
    const double                                   mu = 0.5;
    std::vector<std::vector<std::complex<double>>> lambdas;
    std::vector<std::vector<Eigen::VectorXcd>>     q;
    std::vector<Eigen::MatrixXd>                   macs;
    std::vector<double>                            bs;
    std::vector<unsigned int>                      index;
    for (unsigned int k = 0; k <= 40; ++k)
      {
        const double b = 1e6 + 0.2e6 * k;
        bs.push_back(b);
        index.push_back(k);
        lambdas.emplace_back();
        q.emplace_back();
        for (const auto &p : reduced.solve(Model::point(b, mu), 1., 1e4))
          {
            lambdas.back().push_back(p.lambda);
            q.back().push_back(p.q);
          }
        macs.push_back(k > 0 ? test_tools::mac_matrix(q[k - 1], q[k]) :
                               Eigen::MatrixXd());
      }
    int        next     = 0;
    const auto tracks   = eigen::track_modes(lambdas, macs, next);
    bool       two_each = true, continuous = true;
    for (unsigned int k = 0; k < tracks.size(); ++k)
      {
        two_each =
          two_each && tracks[k].size() == 2 && tracks[k][0] != tracks[k][1];
        if (k == 0)
          continue;
        for (unsigned int j = 0; j < tracks[k].size(); ++j)
          for (unsigned int i = 0; i < tracks[k - 1].size(); ++i)
            if (tracks[k - 1][i] == tracks[k][j] &&
                std::abs(lambdas[k][j].real()) < 1e-3 &&
                std::abs(lambdas[k - 1][i].real()) < 1e-3 &&
                // leaving an exceptional point, either continuation is right
                std::abs(lambdas[k - 1][0].imag() - lambdas[k - 1][1].imag()) >
                  1e-6 * lambdas[k - 1][0].imag())
              {
                // the tracked successor is the nearest in frequency
                double nearest = 1e300;
                for (const auto &o : lambdas[k])
                  nearest =
                    std::min(nearest,
                             std::abs(o.imag() - lambdas[k - 1][i].imag()));
                const bool ok =
                  std::abs(lambdas[k][j].imag() - lambdas[k - 1][i].imag()) <=
                  nearest * (1 + 1e-9) + 1e-9;
                if (!ok)
                  std::cerr << "swap at b = " << bs[k] << ": "
                            << lambdas[k - 1][i] << " -> " << lambdas[k][j]
                            << std::endl;
                continuous = continuous && ok;
              }
      }
    check("lock-in sweep: two modes with two distinct tracks at every point",
          two_each,
          1,
          0);
    check("lock-in sweep: two tracks in all", next, 2, 0);
    check(
      "lock-in sweep: where stable, each track goes to the nearest frequency",
      continuous,
      1,
      0);
    const auto regions =
      eigen::find_unstable_regions(mu, bs, index, lambdas, tracks, 1e-3);
    check("lock-in sweep: one unstable region", regions.size(), 1, 0);
    if (regions.size() == 1)
      {
        check("lock-in sweep: region starts at b = 3.2e6 (closed form 3e6)",
              regions[0].first_min,
              3.2e6,
              1e-12);
        check("lock-in sweep: region ends at b = 6.8e6 (closed form 7e6)",
              regions[0].first_max,
              6.8e6,
              1e-12);
        check("lock-in sweep: the locking-in partner is named",
              regions[0].partner_track >= 0,
              1,
              0);
        // closed form: lambda^2 = -(a + b) / 2 +- i sqrt(-D) / 2 with
        // D = (a - b)^2 + 4 c (c - mu k3) < 0; the largest Re on the grid
        double largest = 0;
        for (const double b : bs)
          {
            const double D = (a - b) * (a - b) + 4 * c * (c - mu * k3);
            if (D < 0)
              largest =
                std::max(largest,
                         std::abs(std::sqrt(std::complex<double>(
                                              -(a + b) / 2, std::sqrt(-D) / 2))
                                    .real()));
          }
        check("lock-in sweep: largest growth rate (closed form, 1e-6)",
              regions[0].max_re,
              largest,
              1e-6);
      }
  }

  // 3. zero and large damping against an independent dense computation
  for (const auto &[alpha, beta] : {std::pair{0., 0.},
                                    std::pair{1e3, 0.},
                                    std::pair{0., 1e-5},
                                    std::pair{1e3, 1e-5}})
    for (const double mu : {0., 0.5})
      {
        const auto reference = dense_reference(b0, mu, alpha, beta);
        const auto full      = eigen::solve_full(model.parts(),
                                            Model::point(b0, mu, alpha, beta),
                                            band,
                                            quiet);
        const auto red =
          reduced.solve(Model::point(b0, mu, alpha, beta), 1., 1e4);
        std::ostringstream tag;
        tag << "alpha = " << alpha << ", beta = " << beta << ", mu = " << mu;
        check(tag.str() + ": full count", full.size(), reference.size(), 0);
        check(tag.str() + ": reduced count", red.size(), reference.size(), 0);
        // each reference eigenvalue against the nearest computed one (the
        // unstable pair has equal frequencies, so no order can be relied on)
        double worst = 0;
        for (const auto &ref : reference)
          for (const bool is_full : {true, false})
            {
              double nearest = 1e300;
              if (is_full)
                for (const auto &p : full)
                  nearest = std::min(nearest, std::abs(p.lambda - ref));
              else
                for (const auto &p : red)
                  nearest = std::min(nearest, std::abs(p.lambda - ref));
              worst = std::max(worst, nearest / std::abs(ref));
            }
        check(tag.str() + ": eigenvalues equal the dense reference (1e-8)",
              std::max(worst, 1e-8),
              1e-8,
              0);
      }
  return test_tools::finish();
}
