// The full solver's band when a mode from far above it is damped so much
// that its Im lambda falls inside (include/squeal/eigen/full_solver.h,
// step 3): three unit masses, x1 and x2 on springs to ground (1 and 2 kHz),
// x3 on a stiff spring (100 kHz) whose stiffness-proportional damping
// (beta3 k3, zeta = 0.99955) is its own part, and a soft spring joining x2
// to x3. The undamped band [500, 5000] Hz holds two modes (Sylvester
// inertia); the dense companion solve (LAPACK dgeev) has a third pair with
// Im lambda / 2 pi = 3.03 kHz, in the band, whose modulus |lambda| / 2 pi is
// 100 kHz. The coupling puts x3 in the static corrections P^-1 C Phi, so
// the projected problem holds that pair; the solver must leave it out (a
// mode from above its basis cutoff 1.5 f_max) and return exactly the two
// band modes, equal to the dense solve's to 1e-9 of |lambda|.

#include <squeal/eigen/full_solver.h>

#include "check.h"
#include "dense_qep.h"

#include <algorithm>
#include <cmath>
#include <complex>

using namespace dealii;
using namespace squeal;
using test_tools::check;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);
  const double                     two_pi = 2 * M_PI;
  const double k1 = std::pow(two_pi * 1e3, 2), k2 = std::pow(two_pi * 2e3, 2),
               k3 = std::pow(two_pi * 1e5, 2), kc = 0.05 * k2;
  const double zeta3 = 0.99955, beta3 = 2 * zeta3 / (two_pi * 1e5);

  // parts: M, K (springs to ground at x1, x2 and the coupling), K3 (x3's
  // spring, damped by beta3)
  IndexSet owned(3);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    owned.add_range(0, 3);
  DynamicSparsityPattern dsp(3, 3);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      dsp.add(i, j);
  eigen::PETScMatrix M, K, K3;
  for (auto *A : {&M, &K, &K3})
    A->reinit(owned, owned, dsp, MPI_COMM_WORLD);
  Eigen::MatrixXd Md = Eigen::MatrixXd::Identity(3, 3), Kd(3, 3), K3d(3, 3);
  Kd << k1, 0, 0, 0, k2 + kc, -kc, 0, -kc, kc;
  K3d.setZero();
  K3d(2, 2) = k3;
  if (owned.n_elements() > 0)
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          M.set(i, j, Md(i, j));
          K.set(i, j, Kd(i, j));
          K3.set(i, j, K3d(i, j));
        }
  for (auto *A : {&M, &K, &K3})
    A->compress(VectorOperation::insert);
  using Kind = physics::MatrixParts::Kind;
  physics::MatrixParts parts;
  parts.parts = {{&M, Kind::mass, "M", "", 1., "", ""},
                 {&K, Kind::stiffness, "K", "", 1., "", ""},
                 {&K3, Kind::stiffness, "K3", "", 1., "", "beta3"}};
  parameters::ScalarPoint p;
  p.add("beta3", beta3);
  parts.reference = p;

  eigen::BandOptions band;
  band.f_min            = 500.;
  band.f_max            = 5000.;
  band.target_frequency = 100.;

  // the dense reference: every eigenvalue of the damped problem
  std::vector<std::complex<double>> in_band;
  std::complex<double>              from_above = 0.;
  for (const auto &l :
       test_tools::dense_qep_eigenvalues_cholesky(Md, beta3 * K3d, Kd + K3d))
    if (l.imag() > 0 && l.imag() / two_pi >= band.f_min &&
        l.imag() / two_pi <= band.f_max)
      {
        if (std::abs(l) / two_pi > band.basis_factor * band.f_max)
          from_above = l;
        else
          in_band.push_back(l);
      }
  std::sort(in_band.begin(), in_band.end(), [](const auto &a, const auto &b) {
    return a.imag() < b.imag();
  });
  check("dense: a pair from above the basis cutoff has Im lambda in the band "
        "(about 3 kHz, |lambda| / 2 pi = 100 kHz)",
        from_above.imag() / two_pi,
        3e3,
        0.05);
  check("dense: two more pairs in the band", in_band.size(), 2, 0);

  eigen::FullSolveReport report;
  const auto pairs = eigen::solve_full(parts, p, band, quiet, &report);
  check("inertia: two undamped modes in the band",
        report.symmetric_in_band,
        2,
        0);
  check("full solver: exactly the two band modes, not the pair from above",
        pairs.size(),
        2,
        0);
  for (unsigned int i = 0; i < std::min<std::size_t>(2, pairs.size()); ++i)
    check("full solver: band mode " + std::to_string(i + 1) +
            " equals the dense solve's (1e-9 of |lambda|)",
          std::abs(pairs[i].lambda - in_band[i]) / std::abs(in_band[i]),
          0.,
          1e-9,
          1.);
  return test_tools::finish();
}
