// Correlation statistics of pad-face maps: Pearson, Spearman and ROC AUC
// against independently computed values (SciPy 1.10: pearsonr, spearmanr,
// roc_auc_score on the same vectors), Moran's I on maps with known values,
// and the toroidal-shift test: on 100 pairs of independent smooth random
// fields its p-values are uniform (fewer than 10 % below 0.05, while the
// naive t-test p-value of the same correlations falls below 0.05 far more
// often), and a damage map that drives a synthetic crack density is found
// (AUC > 0.7, p < 0.01).

#include <squeal/tribology/correlation.h>

#include "check.h"

#include <cmath>
#include <random>

using namespace squeal::tribology;
using test_tools::check;

namespace
{
  // A smooth random field on an n x n torus: white noise convolved with a
  // periodic Gaussian of width sigma cells.
  GridMap
  smooth_field(unsigned int n, double sigma, std::mt19937 &rng)
  {
    std::normal_distribution<double> N(0., 1.);
    std::vector<double>              white(n * n);
    for (double &w : white)
      w = N(rng);
    GridMap             m(n, n, 0., 0., 1.);
    const int           reach = int(3 * sigma) + 1;
    std::vector<double> kernel(2 * reach + 1);
    for (int k = -reach; k <= reach; ++k)
      kernel[k + reach] = std::exp(-0.5 * k * k / (sigma * sigma));
    std::vector<double> rows(n * n, 0.);
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int i = 0; i < n; ++i)
        for (int k = -reach; k <= reach; ++k)
          rows[i + n * j] += kernel[k + reach] * white[(i + n + k) % n + n * j];
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int i = 0; i < n; ++i)
        {
          double s = 0.;
          for (int k = -reach; k <= reach; ++k)
            s += kernel[k + reach] * rows[i + n * ((j + n + k) % n)];
          m(i, j) = s;
        }
    return m;
  }

  // Two-sided p-value of the naive t-test of a Pearson r over n pairs
  // (normal approximation of the t distribution, n is large).
  double
  naive_p(double r, std::size_t n)
  {
    const double t = r * std::sqrt((n - 2.) / (1. - r * r));
    return std::erfc(std::abs(t) / std::sqrt(2.));
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();

  // Small vectors with values from SciPy; a NaN pair is skipped.
  {
    const std::vector<double> a{1., 2., 3., 4., 5., 6., nan, 8.},
      b{2.1, 3.9, 6.2, 7.8, 9.9, 14., 3., 12.};
    check("pearson (SciPy 0.928296)", pearson(a, b), 0.9282956310238, 1e-12);
    check("spearman (SciPy 0.964286)", spearman(a, b), 0.9642857142857, 1e-12);
    const std::vector<double> s{0.1, 0.4, 0.35, 0.8, 0.7, 0.2},
      l{0., 0., 1., 1., 1., 0.};
    check("roc auc (SciPy 0.888889)", roc_auc(s, l), 8. / 9., 1e-12);
    const std::vector<double> tie{0.5, 0.5, 0.5, 0.5};
    check("roc auc with all scores tied = 0.5",
          roc_auc(tie, std::vector<double>{0., 1., 0., 1.}),
          0.5,
          1e-15);
    const auto curve = roc_curve(s, l);
    check("roc curve ends at (1, 1)",
          curve.back().first + curve.back().second,
          2.,
          0.);
  }

  // Moran's I with queen weights: on a chequerboard every orthogonal pair is
  // unlike (-1) and every diagonal pair alike (+1), so I = (n_diag - n_orth)
  // / (n_diag + n_orth) over the ordered pairs; a ramp against a direct
  // double sum.
  {
    const unsigned int n = 8;
    GridMap            chess(n, n, 0., 0., 1.), ramp(n, n, 0., 0., 1.);
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int i = 0; i < n; ++i)
        {
          chess(i, j) = ((i + j) % 2) ? 1. : -1.;
          ramp(i, j)  = i;
        }
    const double orth = 2. * 2. * n * (n - 1),
                 diag = 2. * 2. * (n - 1) * (n - 1);
    check("Moran's I of a chequerboard",
          morans_i(chess),
          (diag - orth) / (diag + orth),
          1e-14);
    // ramp: direct double sum
    double mean = (n - 1) / 2., num = 0., den = 0., w = 0.;
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int i = 0; i < n; ++i)
        {
          den += (i - mean) * (i - mean);
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di)
              {
                const int ii = int(i) + di, jj = int(j) + dj;
                if ((di || dj) && ii >= 0 && jj >= 0 && ii < int(n) &&
                    jj < int(n))
                  {
                    num += (i - mean) * (ii - mean);
                    w += 1.;
                  }
              }
        }
    check("Moran's I of a ramp", morans_i(ramp), n * n / w * num / den, 1e-14);
  }

  // Toroidal-shift test on independent smooth fields: honest p-values.
  {
    std::mt19937 rng(2026);
    unsigned int below = 0, naive_below = 0;
    const auto   sp = [](const std::vector<double> &a,
                       const std::vector<double> &b) { return spearman(a, b); };
    for (int trial = 0; trial < 100; ++trial)
      {
        const GridMap a      = smooth_field(24, 2.5, rng),
                      b      = smooth_field(24, 2.5, rng);
        const ToroidalTest t = toroidal_test(a, b, sp);
        below += (t.p_value < 0.05);
        naive_below +=
          naive_p(pearson(a.values, b.values), a.values.size()) < 0.05;
      }
    test_tools::verbose() << "independent fields: toroidal p < 0.05 in "
                          << below
                          << " of 100 (one-sided), naive two-sided p < 0.05 in "
                          << naive_below << std::endl;
    check("independent fields: toroidal p < 0.05 in fewer than 10 of 100",
          std::min(below, 9u),
          below,
          0.);
    check("independent fields: naive p-values overconfident (> 20 of 100)",
          std::max(naive_below, 21u),
          naive_below,
          0.);
  }

  // A damage map driving the crack density: found with AUC > 0.7, p < 0.01.
  {
    std::mt19937        rng(7);
    const GridMap       damage = smooth_field(32, 3., rng);
    std::vector<double> sorted(damage.values);
    std::sort(sorted.begin(), sorted.end());
    GridMap cracks = damage.empty_like(), cracked = damage.empty_like();
    for (std::size_t c = 0; c < damage.values.size(); ++c)
      {
        const double q =
          double(
            std::lower_bound(sorted.begin(), sorted.end(), damage.values[c]) -
            sorted.begin()) /
          (sorted.size() - 1);
        std::poisson_distribution<int> P(0.05 + 3. * q * q);
        cracks.values[c] = P(rng);
      }
    std::vector<double> c_sorted(cracks.values);
    std::nth_element(c_sorted.begin(),
                     c_sorted.begin() + c_sorted.size() / 2,
                     c_sorted.end());
    const double median = c_sorted[c_sorted.size() / 2];
    for (std::size_t c = 0; c < cracks.values.size(); ++c)
      cracked.values[c] = cracks.values[c] > median;
    const auto         au = [](const std::vector<double> &a,
                       const std::vector<double> &b) { return roc_auc(a, b); };
    const ToroidalTest t  = toroidal_test(damage, cracked, au);
    test_tools::verbose() << "damage-driven cracks: AUC " << t.observed
                          << ", p " << t.p_value << " over " << t.n_shifts
                          << " shifts" << std::endl;
    check("damage-driven cracks: AUC > 0.7",
          std::max(t.observed, 0.7),
          t.observed,
          0.);
    check("damage-driven cracks: toroidal p < 0.01",
          std::min(t.p_value, 0.0099),
          t.p_value,
          0.);
    check("damage-driven cracks: 1024 shifts", t.n_shifts, 1024., 0.);
  }

  // Grid lookup: cell_of on the edges.
  {
    const GridMap g(4, 3, -2e-3, 1e-3, 1e-3);
    check("cell_of inside", g.cell_of(-1.5e-3, 1.5e-3), 0., 0.);
    check("cell_of last cell", g.cell_of(1.9e-3, 3.9e-3), 11., 0.);
    check("cell_of outside", g.cell_of(2.1e-3, 1.5e-3), -1., 0.);
  }
  return test_tools::finish();
}
