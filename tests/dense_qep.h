// Every eigenvalue of a dense quadratic eigenproblem by LAPACK (dgeev) on
// a scaled companion matrix: the tests' independent reference for
// squeal's eigensolvers (no projection, no shift, no iteration of squeal's).
#ifndef squeal_tests_dense_qep_h
#define squeal_tests_dense_qep_h

#include <squeal/base/lapack.h>

#include <Eigen/Dense>

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

namespace test_tools
{
  /**
   * Every eigenvalue of (lambda^2 M + lambda C + K) x = 0 (n x n, M
   * symmetric positive definite) by LAPACK's dgeev on the companion matrix
   * of the congruent problem (M = L L^T, x = L^-T y):
   * [0 I; -L^-1 K L^-T / g^2, -L^-1 C L^-T / g], lambda = g mu,
   * g = sqrt(|L^-1 K L^-T|_F / sqrt(n)) (a standard eigenproblem: about
   * 15x faster than LAPACK's QZ on the companion pencil at 1 600 DoFs).
   * @throws std::runtime_error if M is not positive definite or dgeev fails.
   */
  inline std::vector<std::complex<double>>
  dense_qep_eigenvalues_cholesky(const Eigen::MatrixXd &M,
                                 const Eigen::MatrixXd &C,
                                 const Eigen::MatrixXd &K)
  {
    const int                         n = M.rows(), n2 = 2 * n;
    const Eigen::LLT<Eigen::MatrixXd> llt(M);
    if (llt.info() != Eigen::Success)
      throw std::runtime_error("dense QEP: M is not positive definite");
    const auto congruent = [&](const Eigen::MatrixXd &A) {
      const Eigen::MatrixXd X = llt.matrixL().solve(A);
      return Eigen::MatrixXd(llt.matrixL().solve(X.transpose()).transpose());
    };
    const Eigen::MatrixXd Kt = congruent(K), Ct = congruent(C);
    const double          g = std::sqrt(Kt.norm() / std::sqrt(double(n)));
    Eigen::MatrixXd       A = Eigen::MatrixXd::Zero(n2, n2);
    A.topRightCorner(n, n).setIdentity();
    A.bottomLeftCorner(n, n)  = -Kt / (g * g);
    A.bottomRightCorner(n, n) = -Ct / g;
    std::vector<double> wr(n2), wi(n2), work(1);
    int                 lwork = -1, info = 0, one = 1, size = n2;
    double              dummy = 0;
    const auto          qr    = [&]() {
      dgeev_("N",
             "N",
             &size,
             A.data(),
             &size,
             wr.data(),
             wi.data(),
             &dummy,
             &one,
             &dummy,
             &one,
             work.data(),
             &lwork,
             &info);
    };
    qr();
    lwork = static_cast<int>(work[0]);
    work.resize(lwork);
    qr();
    if (info != 0)
      throw std::runtime_error("dgeev failed: info = " + std::to_string(info));
    std::vector<std::complex<double>> lambda;
    for (int k = 0; k < n2; ++k)
      lambda.emplace_back(g * wr[k], g * wi[k]);
    return lambda;
  }

} // namespace test_tools

#endif
