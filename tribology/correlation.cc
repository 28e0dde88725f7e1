// Statistics comparing two maps of the pad face (damage against cracks):
// rank and linear correlation, ROC AUC, Moran's I and the toroidal-shift
// permutation test. Small, exact formulas; nothing here needs a library.

#include <squeal/tribology/correlation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace squeal
{
  namespace tribology
  {
    namespace
    {
      const double nan = std::numeric_limits<double>::quiet_NaN();

      // The pairs where both entries are finite.
      void
      finite_pairs(const std::vector<double> &a,
                   const std::vector<double> &b,
                   std::vector<double>       &x,
                   std::vector<double>       &y)
      {
        if (a.size() != b.size())
          throw std::invalid_argument("maps of different sizes compared");
        x.clear();
        y.clear();
        for (std::size_t i = 0; i < a.size(); ++i)
          if (std::isfinite(a[i]) && std::isfinite(b[i]))
            {
              x.push_back(a[i]);
              y.push_back(b[i]);
            }
      }

      double
      pearson_of(const std::vector<double> &x, const std::vector<double> &y)
      {
        const std::size_t n = x.size();
        if (n < 3)
          return nan;
        const double mx = std::accumulate(x.begin(), x.end(), 0.) / n,
                     my = std::accumulate(y.begin(), y.end(), 0.) / n;
        double sxy = 0., sxx = 0., syy = 0.;
        for (std::size_t i = 0; i < n; ++i)
          {
            sxy += (x[i] - mx) * (y[i] - my);
            sxx += (x[i] - mx) * (x[i] - mx);
            syy += (y[i] - my) * (y[i] - my);
          }
        return (sxx > 0. && syy > 0.) ? sxy / std::sqrt(sxx * syy) : nan;
      }

      // Average ranks (1-based), ties sharing their mean rank.
      std::vector<double>
      ranks(const std::vector<double> &x)
      {
        std::vector<std::size_t> order(x.size());
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(),
                  order.end(),
                  [&](std::size_t i, std::size_t j) { return x[i] < x[j]; });
        std::vector<double> r(x.size());
        for (std::size_t i = 0; i < order.size();)
          {
            std::size_t j = i;
            while (j + 1 < order.size() && x[order[j + 1]] == x[order[i]])
              ++j;
            for (std::size_t k = i; k <= j; ++k)
              r[order[k]] = 0.5 * (i + j) + 1.;
            i = j + 1;
          }
        return r;
      }
    } // namespace

    GridMap::GridMap(unsigned int nx,
                     unsigned int ny,
                     double       x0,
                     double       y0,
                     double       h)
      : nx(nx)
      , ny(ny)
      , x0(x0)
      , y0(y0)
      , h(h)
      , values(std::size_t(nx) * ny, nan)
    {}

    long
    GridMap::cell_of(double x, double y) const
    {
      const double fi = (x - x0) / h, fj = (y - y0) / h;
      if (!(fi >= 0. && fj >= 0. && fi < nx && fj < ny))
        return -1;
      return long(fi) + long(nx) * long(fj);
    }

    GridMap
    GridMap::empty_like() const
    {
      return GridMap(nx, ny, x0, y0, h);
    }

    double
    pearson(const std::vector<double> &a, const std::vector<double> &b)
    {
      std::vector<double> x, y;
      finite_pairs(a, b, x, y);
      return pearson_of(x, y);
    }

    double
    spearman(const std::vector<double> &a, const std::vector<double> &b)
    {
      std::vector<double> x, y;
      finite_pairs(a, b, x, y);
      if (x.size() < 3)
        return nan;
      return pearson_of(ranks(x), ranks(y));
    }

    double
    roc_auc(const std::vector<double> &score, const std::vector<double> &label)
    {
      std::vector<double> s, l;
      finite_pairs(score, label, s, l);
      const std::vector<double> r        = ranks(s);
      double                    rank_sum = 0.;
      std::size_t               n_pos    = 0;
      for (std::size_t i = 0; i < s.size(); ++i)
        if (l[i] != 0.)
          {
            rank_sum += r[i];
            ++n_pos;
          }
      const std::size_t n_neg = s.size() - n_pos;
      if (n_pos == 0 || n_neg == 0)
        return nan;
      return (rank_sum - 0.5 * n_pos * (n_pos + 1.)) / (double(n_pos) * n_neg);
    }

    std::vector<std::pair<double, double>>
    roc_curve(const std::vector<double> &score,
              const std::vector<double> &label)
    {
      std::vector<double> s, l;
      finite_pairs(score, label, s, l);
      std::vector<std::size_t> order(s.size());
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
        return s[i] > s[j];
      });
      double n_pos = 0., n_neg = 0.;
      for (double v : l)
        (v != 0. ? n_pos : n_neg) += 1.;
      std::vector<std::pair<double, double>> curve{{0., 0.}};
      double                                 tp = 0., fp = 0.;
      for (std::size_t k = 0; k < order.size(); ++k)
        {
          (l[order[k]] != 0. ? tp : fp) += 1.;
          if (k + 1 == order.size() || s[order[k + 1]] != s[order[k]])
            curve.emplace_back(n_neg > 0. ? fp / n_neg : 0.,
                               n_pos > 0. ? tp / n_pos : 0.);
        }
      return curve;
    }

    double
    morans_i(const GridMap &m)
    {
      double      mean = 0.;
      std::size_t n    = 0;
      for (double v : m.values)
        if (std::isfinite(v))
          {
            mean += v;
            ++n;
          }
      if (n < 3)
        return nan;
      mean /= n;
      double num = 0., den = 0., w = 0.;
      for (unsigned int j = 0; j < m.ny; ++j)
        for (unsigned int i = 0; i < m.nx; ++i)
          {
            const double zi = m(i, j) - mean;
            if (!std::isfinite(zi))
              continue;
            den += zi * zi;
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di)
                {
                  const int ii = int(i) + di, jj = int(j) + dj;
                  if ((!di && !dj) || ii < 0 || jj < 0 || ii >= int(m.nx) ||
                      jj >= int(m.ny) || !std::isfinite(m(ii, jj)))
                    continue;
                  num += zi * (m(ii, jj) - mean);
                  w += 1.;
                }
          }
      return (w > 0. && den > 0.) ? (double(n) / w) * num / den : nan;
    }

    ToroidalTest
    toroidal_test(
      const GridMap                                            &a,
      const GridMap                                            &b,
      const std::function<double(const std::vector<double> &,
                                 const std::vector<double> &)> &statistic)
    {
      if (a.nx != b.nx || a.ny != b.ny)
        throw std::invalid_argument("toroidal test: maps on different grids");
      ToroidalTest        t;
      std::vector<double> shifted(b.values.size());
      std::vector<double> stats;
      for (unsigned int dj = 0; dj < b.ny; ++dj)
        for (unsigned int di = 0; di < b.nx; ++di)
          {
            for (unsigned int j = 0; j < b.ny; ++j)
              for (unsigned int i = 0; i < b.nx; ++i)
                shifted[i + b.nx * j] = b((i + di) % b.nx, (j + dj) % b.ny);
            const double s = statistic(a.values, shifted);
            if (di == 0 && dj == 0)
              t.observed = s;
            if (std::isfinite(s))
              stats.push_back(s);
          }
      t.n_shifts = stats.size();
      if (!std::isfinite(t.observed) || stats.empty())
        {
          t.p_value = nan;
          return t;
        }
      std::size_t extreme = 0;
      // A relative tolerance keeps ties with the observed value (the
      // aligned shift itself) counted despite rounding.
      const double tol = 1e-12 * std::max(1., std::abs(t.observed));
      for (double s : stats)
        extreme += (s >= t.observed - tol);
      t.p_value = double(extreme) / stats.size();
      return t;
    }
  } // namespace tribology
} // namespace squeal
