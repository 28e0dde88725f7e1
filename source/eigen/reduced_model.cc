// The reduced-order model of the complex eigenvalue analysis: basis
// construction from real modes plus friction enrichment, projection of every
// matrix part with one sparse-times-dense product each, and the dense
// companion eigenproblem of a sweep point. Residuals on the full model come
// from Gram matrices of the projected parts, so checking every reduced
// eigenpair costs no sparse work per sweep point.

#include <deal.II/base/mpi.h>

#include <squeal/eigen/reduced_model.h>
#include <squeal/physics/structural_model.h>

#include <petscmat.h>

#include "dense_block.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace squeal
{
  namespace eigen
  {
    using namespace dealii;
    using Kind = physics::MatrixParts::Kind;
    using Eigen::all;

    using internal::local_part;
    using internal::multiply;
    using internal::orthonormalising_transform;
    using internal::sum_over_ranks;

    namespace
    {
      // sum_k a_k V^T A_k V over the active parts (r x r)
      Eigen::MatrixXd
      projected_sum(const std::vector<Eigen::MatrixXd>       &Ar,
                    const std::vector<bool>                  &active,
                    const physics::MatrixParts::Coefficients &a,
                    const int                                 r)
      {
        Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(r, r);
        for (unsigned int k = 0; k < active.size(); ++k)
          if (active[k] && a[k] != 0.)
            sum += a[k] * Ar[k];
        return sum;
      }

      void
      require_products(const bool released)
      {
        if (released)
          throw std::logic_error(
            "reduced model: the parts' products were released");
      }
    } // namespace

    void
    ReducedModel::make_reference_mass(const physics::MatrixParts &model)
    {
      parts = model;
      comm  = model.matrix(0).get_mpi_communicator();
      owned = model.matrix(0).locally_owned_range_indices();
      model.mass(model.reference, M_ref);
      physics::store_nonzeros_only(M_ref, owned, comm);
      const unsigned int n_parts = model.size();
      active.assign(n_parts, false);
      rows.assign(n_parts, std::vector<int>());
      for (unsigned int k = 0; k < n_parts; ++k)
        {
          active[k] = model.matrix(k).frobenius_norm() > 0.;
          if (active[k])
            rows[k] = internal::nonzero_rows(model.matrix(k));
        }
      released = false;
      Ar.assign(n_parts, Eigen::MatrixXd());
      std::vector<Eigen::MatrixXd>().swap(W);
      G.assign(n_parts, std::vector<Eigen::MatrixXd>(n_parts));
    }

    void
    ReducedModel::build(const physics::MatrixParts                 &model,
                        const std::vector<parameters::ScalarPoint> &samples,
                        const BandOptions                          &band,
                        const double                                band_factor,
                        const unsigned int         enrichment_depth,
                        ConditionalOStream        &pcout,
                        const KnownSymmetricModes *known)
    {
      make_reference_mass(model);
      // the basis vectors, sample after sample
      Eigen::MatrixXd B(owned.n_elements(), 0);
      BandOptions     sample_band = band;
      // every pair's K_n and K_t (at their reference stiffness)
      PETScMatrix K_n, K_t;
      const bool  has_normal  = model.sum(Kind::interface_normal, K_n),
                 has_friction = model.sum(Kind::interface_friction, K_t);
      // a combination has the whole pattern (2 GB at a million DoFs); the
      // interfaces' few hundred rows are kept
      if (has_normal)
        physics::store_nonzeros_only(K_n, owned, comm);
      if (has_friction)
        physics::store_nonzeros_only(K_t, owned, comm);
      const auto reference_mass = model.coefficients(model.reference).mass;
      for (unsigned int i = 0; i < samples.size(); ++i)
        {
          const auto &s = samples[i];
          const auto  c = model.coefficients(s);
          PETScMatrix K, M_sample;
          model.symmetric_stiffness(s, K);
          // the reference mass unless the sample changes it
          const bool         own_mass = c.mass != reference_mass;
          const PETScMatrix &M        = own_mass ? M_sample : M_ref;
          if (own_mass)
            {
              model.mass(s, M_sample);
              // on its nonzeros: the eigensolver multiplies by M some 600
              // times
              physics::store_nonzeros_only(M_sample, owned, comm);
            }
          pcout << "  reduced basis: sample " << i + 1 << " of "
                << samples.size() << std::endl;
          const double              top = band_factor * band.f_max;
          std::vector<UndampedMode> modes;
          if (known && known->top_hz >= top && known->mass == c.mass &&
              known->symmetric_stiffness == c.symmetric_stiffness)
            {
              const double w_top = 2. * numbers::PI * top;
              for (const UndampedMode &mode : known->modes)
                if (mode.omega2.real() < w_top * w_top)
                  modes.push_back(mode);
              pcout << "  the full solve's " << modes.size() << " modes up to "
                    << top << " Hz at these mass and stiffness, reused"
                    << std::endl;
            }
          else
            modes = solve_undamped(M, K, sample_band, band_factor, true, pcout);
          largest_sample = std::max<unsigned int>(largest_sample, modes.size());
          // Enrichment, one block solve per level with a Cholesky
          // factorisation of K_s. Rayleigh damping beta K_s is not
          // proportional to K_s + K_n: the static response to the
          // interface forces K^-1 K_n phi corrects the damped shapes; the
          // friction forces give K^-1 K_t phi, K^-1 K_t K^-1 K_t phi, ...
          // (each force scaled to unit norm; a zero force adds nothing and
          // ends its mode's chain). The sample's vectors in one block of
          // blocks [Phi, K^-1 K_n Phi, K^-1 K_t Phi, ...], each response
          // solved into its place.
          const int          m = modes.size();
          const unsigned int n_normal =
                               enrichment_depth > 0 && has_normal ? 1 : 0,
                             n_friction = has_friction ? enrichment_depth : 0;
          Eigen::MatrixXd S(owned.n_elements(),
                            m * (1 + n_normal + n_friction));
          for (int j = 0; j < m; ++j)
            S.col(j) = local_part(modes[j].re, owned);
          std::vector<UndampedMode>().swap(modes);
          std::vector<bool>             alive(S.cols(), true);
          std::unique_ptr<DirectSolver> solver;
          if (n_normal + n_friction > 0)
            solver = std::make_unique<DirectSolver>(K, true);
          // block @p to := K^-1 F for the forces F = A (block @p from)
          // scaled to unit norm; a zero force (or a dead chain) leaves a
          // dead column
          const auto respond =
            [&](const PETScMatrix &A, const int from, const int to) {
              Eigen::MatrixXd       F = multiply(A, S.middleCols(from * m, m));
              const Eigen::VectorXd norms = internal::column_norms(F, comm);
              for (int j = 0; j < m; ++j)
                {
                  alive[to * m + j] = alive[from * m + j] && norms[j] > 0.;
                  if (alive[to * m + j])
                    F.col(j) /= norms[j];
                  else
                    F.col(j).setZero();
                }
              internal::solve_block(solver->handle(),
                                    K,
                                    F,
                                    S.middleCols(to * m, m));
            };
          if (n_normal > 0)
            respond(K_n, 0, 1);
          for (unsigned int level = 0; level < n_friction; ++level)
            respond(K_t,
                    level == 0 ? 0 : n_normal + level,
                    1 + n_normal + level);
          solver.reset();
          // the live columns, moved to the front in place
          Eigen::Index live = 0;
          for (Eigen::Index j = 0; j < S.cols(); ++j)
            if (alive[j])
              {
                if (live != j)
                  S.col(live) = S.col(j);
                ++live;
              }
          S.conservativeResize(Eigen::NoChange, live);
          if (B.cols() == 0)
            B.swap(S);
          else
            {
              const Eigen::Index before = B.cols();
              B.conservativeResize(Eigen::NoChange, before + live);
              B.rightCols(live) = S;
            }
        }
      if (Utilities::MPI::max(B.cols(), comm) == 0)
        throw std::runtime_error(
          "reduced basis: no undamped mode in " + std::to_string(band.f_min) +
          "-" + std::to_string(band_factor * band.f_max) +
          " Hz at any basis sample: nothing to project on (check "
          "Eigensolver/Minimum and Maximum frequency against the materials "
          "and the mesh)");
      const Eigen::Index n_vectors = B.cols();
      project(model, B, true);
      pcout << "  reduced basis: " << n_vectors << " vectors, " << V.cols()
            << " M-orthonormal directions kept" << std::endl;
    }

    void
    ReducedModel::build_from_vectors(const physics::MatrixParts     &model,
                                     const std::vector<PETScVector> &vectors,
                                     const bool with_residuals)
    {
      make_reference_mass(model);
      Eigen::MatrixXd B(owned.n_elements(), vectors.size());
      for (unsigned int j = 0; j < vectors.size(); ++j)
        B.col(j) = local_part(vectors[j], owned);
      project(model, B, with_residuals);
    }

    void
    ReducedModel::project(const physics::MatrixParts &model,
                          Eigen::MatrixXd            &B,
                          const bool                  with_residuals)
    {
      // Orthonormalise first, so that the sparse products act on the kept
      // directions only (often a third of the vectors); B becomes V in
      // place (the Gram matrix from blocks of 64 columns of M B).
      {
        constexpr Eigen::Index width = 64;
        Eigen::MatrixXd        gram(B.cols(), B.cols());
        for (Eigen::Index c = 0; c < B.cols(); c += width)
          {
            const Eigen::Index w = std::min(width, B.cols() - c);
            gram.middleCols(c, w).noalias() =
              B.transpose() * multiply(M_ref, B.middleCols(c, w));
          }
        sum_over_ranks(gram, comm);
        internal::multiply_in_place(B, orthonormalising_transform(gram));
        V.swap(B);
        B.resize(0, 0);
        // the reference mass served its purpose (a third of the common
        // pattern: 0.7 GB at a million DoFs)
        M_ref.clear();
      }
      // V^T A_k V and the Gram matrices (A_k V)^T (A_l V) on the rows
      // where A_k has entries (a spring set's few rows, an interface's
      // face, a body's own DoFs), a block of rows at a time: A_k V is
      // never held whole (n x r for a body's part)
      const unsigned int n_parts = active.size();
      const int          r       = V.cols();
      for (unsigned int k = 0; k < n_parts; ++k)
        {
          Ar[k] = Eigen::MatrixXd::Zero(r, r);
          for (unsigned int l = 0; l < n_parts; ++l)
            G[k][l] = with_residuals && l >= k && active[k] && active[l] ?
                        Eigen::MatrixXd::Zero(r, r) :
                        Eigen::MatrixXd();
        }
      {
        const internal::RowMatrix                                Vr = V;
        std::vector<std::unique_ptr<const internal::RowProduct>> products(
          n_parts);
        for (unsigned int k = 0; k < n_parts; ++k)
          if (active[k])
            products[k] =
              std::make_unique<const internal::RowProduct>(model.matrix(k), Vr);
        constexpr int                    height = 4096;
        std::vector<std::size_t>         next(n_parts, 0);
        std::vector<std::vector<int>>    in_block(n_parts);
        std::vector<internal::RowMatrix> P(n_parts);
        std::vector<int>                 in_k, in_l;
        for (int first = 0; first < Vr.rows(); first += height)
          {
            const int end = std::min<int>(first + height, Vr.rows());
            for (unsigned int k = 0; k < n_parts; ++k)
              {
                in_block[k].clear();
                if (!active[k])
                  continue;
                for (; next[k] < rows[k].size() && rows[k][next[k]] < end;
                     ++next[k])
                  in_block[k].push_back(rows[k][next[k]]);
                if (in_block[k].empty())
                  continue;
                P[k] = products[k]->rows(in_block[k]);
                Ar[k].noalias() += Vr(in_block[k], all).transpose() * P[k];
              }
            for (unsigned int k = 0; k < n_parts && with_residuals; ++k)
              for (unsigned int l = k; l < n_parts; ++l)
                if (!in_block[k].empty() && !in_block[l].empty())
                  {
                    internal::common_positions(in_block[k],
                                               in_block[l],
                                               in_k,
                                               in_l);
                    G[k][l].noalias() +=
                      P[k](in_k, all).transpose() * P[l](in_l, all);
                  }
          }
      }
      for (unsigned int k = 0; k < n_parts; ++k)
        {
          sum_over_ranks(Ar[k], comm);
          for (unsigned int l = k; l < n_parts && with_residuals; ++l)
            if (active[k] && active[l])
              sum_over_ranks(G[k][l], comm);
        }
      has_residuals = with_residuals;
    }

    std::vector<ReducedEigenPair>
    ReducedModel::solve(const parameters::ScalarPoint &point,
                        const double                   f_min,
                        const double                   f_max) const
    {
      require_products(released);
      const int          r       = V.cols();
      const unsigned int n_parts = active.size();
      const auto         c       = parts.coefficients(point);
      const auto combine = [&](const physics::MatrixParts::Coefficients &a) {
        return projected_sum(Ar, active, a, r);
      };
      const Eigen::MatrixXd M = combine(c.mass), K = combine(c.stiffness);
      Eigen::MatrixXd       C = combine(c.damping);
      // the modal damping: C V = (M V) B, V^T C V = M_r B
      const bool            modal = parts.modal.active();
      const Eigen::MatrixXd B =
        modal ? internal::subspace_modal_damping(M,
                                                 combine(c.symmetric_stiffness),
                                                 parts.modal)
                  .B :
                Eigen::MatrixXd();
      if (modal)
        C += M * B;
      using Complex = std::complex<double>;
      std::vector<ReducedEigenPair> pairs;
      for (auto &pair : internal::projected_eigenpairs(M, C, K, f_min, f_max))
        pairs.push_back({pair.lambda, std::move(pair.q), -1.});
      if (has_residuals && !pairs.empty())
        {
          // A residual is sum_k A_k V (a_k q + b_k B q) (b = 0 without the
          // modal damping, which adds lambda M V B q): over the extended
          // parts e = (v, k), v = 0 for q and 1 for B q, its squared norm
          // is sum_ef conj(a_e) a_f h_ef with h_ef = x_v^H G_kl x_w and
          // h_fe = conj(h_ef) (G_lk = G_kl^T); all pairs at once, as real
          // matrix products.
          const int                    m       = pairs.size();
          const unsigned int           n_sides = modal ? 2 : 1;
          const unsigned int           n_ext   = n_sides * n_parts;
          std::vector<Eigen::MatrixXd> Xr(n_sides, Eigen::MatrixXd(r, m)),
            Xi(n_sides, Eigen::MatrixXd(r, m));
          for (int j = 0; j < m; ++j)
            {
              Xr[0].col(j) = pairs[j].q.real();
              Xi[0].col(j) = pairs[j].q.imag();
            }
          if (modal)
            {
              Xr[1] = B * Xr[0];
              Xi[1] = B * Xi[0];
            }
          std::vector<std::vector<std::vector<Complex>>> h(
            m,
            std::vector<std::vector<Complex>>(n_ext,
                                              std::vector<Complex>(n_ext)));
          for (unsigned int k = 0; k < n_parts; ++k)
            for (unsigned int l = k; l < n_parts; ++l)
              if (active[k] && active[l])
                for (unsigned int w = 0; w < n_sides; ++w)
                  {
                    const Eigen::MatrixXd A  = G[k][l] * Xr[w],
                                          Bi = G[k][l] * Xi[w];
                    for (unsigned int v = 0; v < n_sides; ++v)
                      {
                        const Eigen::VectorXd re =
                          (Xr[v].cwiseProduct(A) + Xi[v].cwiseProduct(Bi))
                            .colwise()
                            .sum();
                        const Eigen::VectorXd im =
                          (Xr[v].cwiseProduct(Bi) - Xi[v].cwiseProduct(A))
                            .colwise()
                            .sum();
                        const unsigned int e = v * n_parts + k,
                                           f = w * n_parts + l;
                        for (int j = 0; j < m; ++j)
                          {
                            h[j][e][f] = {re[j], im[j]};
                            h[j][f][e] = std::conj(h[j][e][f]);
                          }
                      }
                  }
          using Vector = std::vector<Complex>;
          // the extended coefficients of sum_k a_k A_k V q (+ b_k A_k V B q)
          const auto extended =
            [&](const physics::MatrixParts::Coefficients &a,
                const physics::MatrixParts::Coefficients *b) {
              Vector x(n_ext, 0.);
              for (unsigned int k = 0; k < n_parts; ++k)
                {
                  x[k] = a[k];
                  if (modal && b)
                    x[n_parts + k] = (*b)[k];
                }
              return x;
            };
          const Vector mass      = extended(c.mass, nullptr),
                       damping   = extended(c.damping, &c.mass),
                       stiffness = extended(c.stiffness, nullptr);
          for (int j = 0; j < m; ++j)
            {
              const auto norm = [&](const Vector &a) {
                Complex sum = 0;
                for (unsigned int e = 0; e < n_ext; ++e)
                  if (a[e] != 0.)
                    for (unsigned int f = 0; f < n_ext; ++f)
                      sum += std::conj(a[e]) * a[f] * h[j][e][f];
                return std::sqrt(std::max(0., sum.real()));
              };
              const Complex lambda = pairs[j].lambda;
              Vector        total(n_ext);
              for (unsigned int e = 0; e < n_ext; ++e)
                total[e] = lambda * lambda * mass[e] + lambda * damping[e] +
                           stiffness[e];
              pairs[j].residual =
                norm(total) /
                (std::norm(lambda) * norm(mass) +
                 std::abs(lambda) * norm(damping) + norm(stiffness));
            }
        }
      return pairs;
    }

    Projection
    ReducedModel::projection(const parameters::ScalarPoint &p,
                             const bool                     with_products) const
    {
      require_products(released);
      const auto         c       = parts.coefficients(p);
      const unsigned int n_parts = active.size();
      const int          r       = V.cols();
      const auto combine = [&](const physics::MatrixParts::Coefficients &a) {
        return projected_sum(Ar, active, a, r);
      };
      // sum_k a_k A_k V: from the kept products on their rows, or one
      // sparse product per part (collective)
      if (with_products && W.empty())
        {
          W.assign(n_parts, Eigen::MatrixXd());
          for (unsigned int k = 0; k < n_parts; ++k)
            if (active[k])
              W[k] = multiply(parts.matrix(k), V)(rows[k], all);
        }
      const auto expand = [&](const physics::MatrixParts::Coefficients &a) {
        Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(V.rows(), V.cols());
        for (unsigned int k = 0; k < n_parts; ++k)
          if (active[k] && a[k] != 0.)
            {
              if (!W.empty())
                sum(rows[k], all) += a[k] * W[k];
              else
                internal::multiply_add(parts.matrix(k), a[k], V, sum);
            }
        return sum;
      };
      Projection result;
      result.V = V;
      if (with_products)
        {
          result.MV = expand(c.mass);
          result.CV = expand(c.damping);
          result.KV = expand(c.stiffness);
        }
      result.Mr = combine(c.mass);
      result.Cr = combine(c.damping);
      result.Kr = combine(c.stiffness);
      if (parts.modal.active())
        {
          const auto m =
            internal::subspace_modal_damping(result.Mr,
                                             combine(c.symmetric_stiffness),
                                             parts.modal);
          result.modal_U =
            with_products ? result.MV * m.Psi : expand(c.mass) * m.Psi;
          result.modal_d = m.d;
          if (with_products)
            result.CV += result.MV * m.B;
          result.Cr += result.Mr * m.B;
        }
      return result;
    }

    void
    ReducedModel::release_products()
    {
      for (auto &row : G)
        for (auto &g : row)
          Eigen::MatrixXd().swap(g);
      std::vector<Eigen::MatrixXd>().swap(W);
      has_residuals = false;
      released      = true;
    }

    void
    ReducedModel::expand(const Eigen::VectorXcd &q,
                         physics::PETScVector   &re,
                         physics::PETScVector   &im) const
    {
      std::vector<EigenPair> pair;
      expand({q}, {std::complex<double>()}, pair);
      re.reinit(owned, comm);
      im.reinit(owned, comm);
      re = pair[0].re;
      im = pair[0].im;
    }

    void
    ReducedModel::expand(const std::vector<Eigen::VectorXcd>     &q,
                         const std::vector<std::complex<double>> &lambda,
                         std::vector<EigenPair>                  &pairs) const
    {
      if (lambda.size() != q.size())
        throw std::logic_error(
          "ReducedModel::expand: " + std::to_string(q.size()) +
          " coefficient vectors, " + std::to_string(lambda.size()) +
          " eigenvalues");
      // the real and imaginary parts of 16 modes side by side: one
      // matrix-matrix product with V instead of 32 matrix-vector ones
      constexpr std::size_t batch = 16;
      pairs.resize(q.size());
      Eigen::MatrixXd Q, X;
      for (std::size_t first = 0; first < q.size(); first += batch)
        {
          const std::size_t m = std::min(batch, q.size() - first);
          Q.resize(V.cols(), 2 * m);
          for (std::size_t j = 0; j < m; ++j)
            {
              Q.col(2 * j)     = q[first + j].real();
              Q.col(2 * j + 1) = q[first + j].imag();
            }
          X.noalias() = V * Q;
          for (std::size_t j = 0; j < m; ++j)
            {
              EigenPair &pair = pairs[first + j];
              pair.lambda     = lambda[first + j];
              pair.re.reinit(owned, comm);
              pair.im.reinit(owned, comm);
              internal::set_local_part(pair.re, X.col(2 * j));
              internal::set_local_part(pair.im, X.col(2 * j + 1));
            }
        }
    }
  } // namespace eigen
} // namespace squeal
