// The full solver's two counting tools against independent computations:
// 1. count_eigenvalues_below (Sylvester inertia of K - sigma M, MUMPS
//    LDL^T) against a dense count of the generalised eigenvalues of a
//    stiffness-mass pair with a double eigenvalue (a doublet, as in a disc),
//    a zero eigenvalue (a rigid mode) and a wide spread (Eigen's
//    GeneralizedSelfAdjointEigenSolver), at shifts between the eigenvalues.
// 2. optimal_assignment (Hungarian) against every permutation of square and
//    rectangular cost matrices, with and without a rejection threshold.
// 3. track_modes on three points whose links a greedy choice gets wrong
//    (the cheapest link first leaves a mode unlinked) and with a mode whose
//    MAC to every predecessor is below the threshold (a new track).

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/tracking.h>

#include "test_tools.h"

#include <algorithm>
#include <numeric>
#include <random>

using namespace dealii;
using namespace squeal;

namespace
{
  void
  check_inertia()
  {
    // K = Q^T D Q with Q a chain of plane rotations, M = diag(m): the
    // eigenvalues of (K, M) are spread, with a double one and a zero one
    const unsigned int                     n = 40;
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> uniform(0., 1.);
    Eigen::VectorXd                        d(n), m(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        d[i] = std::pow(10., 6. * uniform(random));
        m[i] = 0.5 + uniform(random);
      }
    d[3] = d[4]       = 2.5e3; // a doublet
    d[0]              = 0.;    // a rigid mode
    Eigen::MatrixXd Q = Eigen::MatrixXd::Identity(n, n);
    for (unsigned int i = 0; i + 1 < n; ++i)
      {
        const double    t = 2 * M_PI * uniform(random);
        Eigen::MatrixXd G = Eigen::MatrixXd::Identity(n, n);
        G(i, i) = G(i + 1, i + 1) = std::cos(t);
        G(i, i + 1)               = std::sin(t);
        G(i + 1, i)               = -std::sin(t);
        Q                         = G * Q;
      }
    // K = M^1/2 Q^T D Q M^1/2 keeps the eigenvalues of (K, M) equal to d
    const Eigen::MatrixXd S  = m.cwiseSqrt().asDiagonal();
    const Eigen::MatrixXd Kd = S * Q.transpose() * d.asDiagonal() * Q * S;

    IndexSet owned(n);
    owned.add_range(0, n);
    DynamicSparsityPattern dsp(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        dsp.add(i, j);
    eigen::PETScMatrix K, M;
    K.reinit(owned, owned, dsp, MPI_COMM_WORLD);
    M.reinit(owned, owned, dsp, MPI_COMM_WORLD);
    for (unsigned int i = 0; i < n; ++i)
      {
        for (unsigned int j = 0; j < n; ++j)
          K.set(i, j, Kd(i, j));
        M.set(i, i, m[i]);
      }
    K.compress(VectorOperation::insert);
    M.compress(VectorOperation::insert);

    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(
      Kd, Eigen::MatrixXd(m.asDiagonal()));
    const Eigen::VectorXd eigenvalues = dense.eigenvalues();
    // shifts half-way (in log) between consecutive distinct eigenvalues
    std::vector<double> sigmas = {-1.};
    for (int i = 1; i + 1 < eigenvalues.size(); i += 3)
      if (eigenvalues[i + 1] > 1.001 * eigenvalues[i])
        sigmas.push_back(
          std::sqrt(std::max(eigenvalues[i], 1e-3) * eigenvalues[i + 1]));
    sigmas.push_back(1e7);
    const auto counts = eigen::count_eigenvalues_below(K, M, sigmas);
    using test_tools::check;
    check("inertia: at least 10 shifts", sigmas.size() >= 10, 1, 0);
    for (unsigned int k = 0; k < sigmas.size(); ++k)
      {
        const unsigned int expected = (eigenvalues.array() < sigmas[k]).count();
        test_tools::verbose() << "shift " << sigmas[k] << ": inertia "
                              << counts[k] << ", dense " << expected << '\n';
        check("inertia count = dense count at shift " + std::to_string(k),
              counts[k],
              expected,
              0);
      }
    check("inertia: none below -1", counts.front(), 0, 0);
    check("inertia: all 40 below 1e7", counts.back(), n, 0);
    // the count through the doublet: both members on one side
    const auto across = eigen::count_eigenvalues_below(K, M, {2.4e3, 2.6e3});
    check("inertia: the doublet at 2.5e3 counts twice",
          across[1] - across[0],
          2,
          0);
  }

  // the least total cost over every injective map of the smaller side
  double
  brute_force(const Eigen::MatrixXd &cost, const double reject)
  {
    const int        m = cost.rows(), n = cost.cols();
    std::vector<int> columns(std::max(m, n));
    std::iota(columns.begin(), columns.end(), 0);
    double best = 1e300;
    do
      {
        double total = 0;
        for (int i = 0; i < m; ++i)
          if (columns[i] < n && cost(i, columns[i]) <= reject)
            total += cost(i, columns[i]);
          else
            total += 1e6; // unassigned: as many as possible are assigned
        best = std::min(best, total);
      }
    while (std::next_permutation(columns.begin(), columns.end()));
    return best;
  }

  void
  check_assignment()
  {
    std::mt19937                           random(11);
    std::uniform_real_distribution<double> uniform(-1., 2.);
    for (const auto &[m, n] : std::vector<std::pair<int, int>>{
           {6, 6}, {5, 7}, {7, 5}, {1, 4}, {8, 8}})
      for (const double reject : {1e300, 1.5})
        {
          Eigen::MatrixXd cost(m, n);
          for (int i = 0; i < m; ++i)
            for (int j = 0; j < n; ++j)
              cost(i, j) = uniform(random);
          const auto       column = eigen::optimal_assignment(cost, reject);
          double           total  = 0;
          std::vector<int> used(n, 0);
          for (int i = 0; i < m; ++i)
            if (column[i] >= 0)
              {
                total += cost(i, column[i]);
                ++used[column[i]];
              }
            else
              total += 1e6;
          const bool injective =
            std::all_of(used.begin(), used.end(), [](int u) { return u <= 1; });
          const std::string tag = "assignment " + std::to_string(m) + " x " +
                                  std::to_string(n) +
                                  (reject < 1e300 ? " with rejection" : "");
          test_tools::check(tag + ": one-to-one", injective, 1, 0);
          test_tools::check(tag + ": least total cost",
                            total,
                            brute_force(cost, reject),
                            1e-12,
                            1.);
        }
  }

  void
  check_tracking()
  {
    // point 0: A, B; point 1: a, b (same eigenvalues, so cost = 1 - MAC).
    // Greedy takes A-a (cost 0.05), then B-b is rejected (MAC 0.2) and B
    // is lost; the optimal links are A-b and B-a (0.1 + 0.1).
    // point 2: c, d with MAC 0.9 to b and at most 0.25 to a: c continues
    // b, d starts a new track.
    const std::vector<std::vector<std::complex<double>>> lambdas = {
      {{-1., 1e4}, {-1., 1e4}},
      {{-1., 1e4}, {-1., 1e4}},
      {{-1., 1e4}, {-1., 1e4}}};
    Eigen::MatrixXd m1(2, 2), m2(2, 2);
    m1 << 0.95, 0.9, 0.9, 0.2;
    m2 << 0.25, 0.1, 0.9, 0.2;
    int        next = 0;
    const auto tracks =
      eigen::track_modes(lambdas, {Eigen::MatrixXd(), m1, m2}, next);
    test_tools::check("tracking: A continues as b",
                      tracks[1][1],
                      tracks[0][0],
                      0);
    test_tools::check("tracking: B continues as a",
                      tracks[1][0],
                      tracks[0][1],
                      0);
    test_tools::check("tracking: c continues b", tracks[2][0], tracks[1][1], 0);
    test_tools::check("tracking: d (MAC 0.2 < 0.3) starts a track",
                      tracks[2][1],
                      2,
                      0);
    test_tools::check("tracking: three tracks", next, 3, 0);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_inertia();
  check_assignment();
  check_tracking();
  return test_tools::n_failures == 0 ? 0 : 1;
}
