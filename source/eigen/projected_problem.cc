// The dense small-matrix work of the subspace eigensolvers (see
// dense_block.h): the M-orthonormalising transform of a Gram matrix, the
// modal damping on a subspace, and the projected quadratic eigenproblem by
// its companion linearisation (LAPACK dgeev).

#include <squeal/base/lapack.h>

#include "dense_block.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace squeal
{
  namespace eigen
  {
    namespace internal
    {
      Eigen::MatrixXd
      orthonormalising_transform(Eigen::MatrixXd gram)
      {
        gram = (gram + gram.transpose()).eval() / 2;
        Eigen::VectorXd scale(gram.cols());
        for (int j = 0; j < gram.cols(); ++j)
          scale[j] = gram(j, j) > 0 ? 1. / std::sqrt(gram(j, j)) : 0.;
        gram = scale.asDiagonal() * gram * scale.asDiagonal();
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(gram);
        const double                                   largest =
          gram.cols() > 0 ? es.eigenvalues().maxCoeff() : 0.;
        std::vector<int> keep;
        for (int i = 0; i < es.eigenvalues().size(); ++i)
          if (es.eigenvalues()[i] > 1e-10 * largest)
            keep.push_back(i);
        Eigen::MatrixXd T(gram.cols(), keep.size());
        for (unsigned int j = 0; j < keep.size(); ++j)
          T.col(j) = scale.asDiagonal() * es.eigenvectors().col(keep[j]) /
                     std::sqrt(es.eigenvalues()[keep[j]]);
        return T;
      }

      SubspaceModalDamping
      subspace_modal_damping(const Eigen::MatrixXd                    &Mr,
                             const Eigen::MatrixXd                    &Ksr,
                             const physics::MatrixParts::ModalDamping &modal)
      {
        const int            r = Mr.rows();
        SubspaceModalDamping result{Eigen::MatrixXd(r, 0),
                                    Eigen::VectorXd(0),
                                    Eigen::MatrixXd::Zero(r, r)};
        if (!modal.active() || r == 0)
          return result;
        const Eigen::MatrixXd sym_M = (Mr + Mr.transpose()) / 2,
                              sym_K = (Ksr + Ksr.transpose()) / 2;
        const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(
          sym_K, sym_M);
        if (es.info() != Eigen::Success)
          throw std::runtime_error(
            "modal damping: the projected mass matrix of the subspace is "
            "not positive definite");
        std::vector<std::pair<int, double>> keep; // (mode, 2 zeta omega)
        for (int i = 0; i < r; ++i)
          if (const double d = modal.coefficient(es.eigenvalues()[i]); d != 0.)
            keep.emplace_back(i, d);
        result.Psi.resize(r, keep.size());
        result.d.resize(keep.size());
        for (unsigned int j = 0; j < keep.size(); ++j)
          {
            result.Psi.col(j) = es.eigenvectors().col(keep[j].first);
            result.d[j]       = keep[j].second;
          }
        result.B =
          result.Psi * result.d.asDiagonal() * result.Psi.transpose() * sym_M;
        return result;
      }

      std::vector<ProjectedPair>
      projected_eigenpairs(const Eigen::MatrixXd &M,
                           const Eigen::MatrixXd &C,
                           const Eigen::MatrixXd &K,
                           const double           f_min,
                           const double           f_max,
                           const double           shift,
                           const double           f_sought)
      {
        const int r = M.rows();
        if (r == 0)
          return {};
        Eigen::MatrixXd A      = Eigen::MatrixXd::Zero(2 * r, 2 * r);
        A.topRightCorner(r, r) = Eigen::MatrixXd::Identity(r, r);
        if (shift == 0.)
          {
            const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
            A.bottomLeftCorner(r, r)  = -lu.solve(K);
            A.bottomRightCorner(r, r) = -lu.solve(C);
          }
        else
          {
            // lambda = tau + 1/mu: mu^2 P(tau) + mu (C + 2 tau M) + M = 0
            const Eigen::MatrixXd P = shift * shift * M + shift * C + K;
            const Eigen::PartialPivLU<Eigen::MatrixXd> lu(P);
            A.bottomLeftCorner(r, r)  = -lu.solve(M);
            A.bottomRightCorner(r, r) = -lu.solve(C + 2. * shift * M);
          }
        if (!A.allFinite())
          throw std::runtime_error(
            "projected eigenproblem: the projected mass matrix is singular");

        const int           n = 2 * r;
        std::vector<double> wr(n), wi(n), vr(n * n), work(1);
        int                 lwork = -1, info = 0, one = 1;
        double              dummy;
        // LAPACK's two calls: the workspace size, then the eigenproblem
        const auto geev = [&]() {
          dgeev_("N",
                 "V",
                 &n,
                 A.data(),
                 &n,
                 wr.data(),
                 wi.data(),
                 &dummy,
                 &one,
                 vr.data(),
                 &n,
                 work.data(),
                 &lwork,
                 &info);
        };
        geev();
        lwork = static_cast<int>(work[0]);
        work.resize(lwork);
        geev();
        if (info != 0)
          throw std::runtime_error(
            "projected eigenproblem: LAPACK dgeev failed, info = " +
            std::to_string(info));

        std::vector<ProjectedPair> pairs;
        for (int j = 0; j < n; ++j)
          {
            // one of each conjugate pair: the column with Im lambda > 0
            // (Im mu < 0 when lambda = tau + 1/mu)
            if (wi[j] <= 0.)
              continue;
            const std::complex<double> mu(wr[j], wi[j]);
            const std::complex<double> lambda =
              shift == 0. ? mu : shift + 1. / std::conj(mu);
            const double f = lambda.imag() / (2 * M_PI);
            if (f < f_min || f > f_max ||
                (f_sought > 0. && lambda.real() < 0. &&
                 std::abs(lambda) > 2 * M_PI * f_sought))
              continue;
            Eigen::VectorXcd q(r);
            for (int i = 0; i < r; ++i)
              q[i] = {vr[i + j * n],
                      (shift == 0. ? 1. : -1.) * vr[i + (j + 1) * n]};
            q.normalize();
            pairs.push_back({lambda, q});
          }
        std::sort(pairs.begin(), pairs.end(), [](const auto &a, const auto &b) {
          return a.lambda.imag() < b.lambda.imag();
        });
        return pairs;
      }
    } // namespace internal
  }   // namespace eigen
} // namespace squeal
