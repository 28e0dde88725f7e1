// Mode tracking and the unstable regions of a sweep (see the header).

#include <squeal/eigen/tracking.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace squeal
{
  namespace eigen
  {
    std::vector<std::vector<int>>
    track_modes(const std::vector<std::vector<std::complex<double>>> &lambdas,
                const std::vector<Eigen::MatrixXd>                   &macs,
                int                                                  &next_id,
                const double                                          weight,
                const double mac_threshold)
    {
      const double                  reject = 1.5;
      std::vector<std::vector<int>> tracks(lambdas.size());
      for (unsigned int p = 0; p < lambdas.size(); ++p)
        {
          tracks[p].assign(lambdas[p].size(), -1);
          if (p > 0)
            {
              // rows: the modes of point p, columns: those of point p - 1
              Eigen::MatrixXd cost(lambdas[p].size(), lambdas[p - 1].size());
              for (unsigned int j = 0; j < lambdas[p].size(); ++j)
                for (unsigned int i = 0; i < lambdas[p - 1].size(); ++i)
                  {
                    const double jump =
                      std::abs(lambdas[p][j] - lambdas[p - 1][i]) /
                      std::abs(lambdas[p - 1][i]);
                    const double c = (1 - macs[p](i, j)) + weight * jump;
                    cost(j, i) = macs[p](i, j) >= mac_threshold && c < reject ?
                                   c :
                                   2 * reject;
                  }
              const auto link = optimal_assignment(cost, reject);
              for (unsigned int j = 0; j < lambdas[p].size(); ++j)
                if (link[j] >= 0)
                  tracks[p][j] = tracks[p - 1][link[j]];
            }
          for (auto &t : tracks[p])
            if (t < 0)
              t = next_id++;
        }
      return tracks;
    }

    std::vector<int>
    optimal_assignment(const Eigen::MatrixXd &cost, const double reject)
    {
      const int m = cost.rows(), n = cost.cols(), k = std::max(m, n);
      if (m == 0 || n == 0)
        return std::vector<int>(m, -1);
      // square, padded: a forbidden or dummy entry costs more than any
      // assignment of real, allowed pairs
      double largest = 0.;
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < n; ++j)
          if (cost(i, j) <= reject)
            largest = std::max(largest, std::abs(cost(i, j)));
      const double    big = 2. * (largest + 1.) * (k + 1);
      Eigen::MatrixXd a   = Eigen::MatrixXd::Constant(k, k, big);
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < n; ++j)
          if (cost(i, j) <= reject)
            a(i, j) = cost(i, j);
      // shortest augmenting paths with row potentials u and column
      // potentials v (1-based, column 0 the virtual start)
      std::vector<double> u(k + 1, 0.), v(k + 1, 0.);
      std::vector<int>    row_of(k + 1, 0), way(k + 1, 0);
      for (int i = 1; i <= k; ++i)
        {
          row_of[0]              = i;
          int                 j0 = 0;
          std::vector<double> slack(k + 1, 1e308);
          std::vector<bool>   done(k + 1, false);
          do
            {
              done[j0]        = true;
              const int i0    = row_of[j0];
              double    delta = 1e308;
              int       j1    = 0;
              for (int j = 1; j <= k; ++j)
                if (!done[j])
                  {
                    const double c = a(i0 - 1, j - 1) - u[i0] - v[j];
                    if (c < slack[j])
                      {
                        slack[j] = c;
                        way[j]   = j0;
                      }
                    if (slack[j] < delta)
                      {
                        delta = slack[j];
                        j1    = j;
                      }
                  }
              for (int j = 0; j <= k; ++j)
                if (done[j])
                  {
                    u[row_of[j]] += delta;
                    v[j] -= delta;
                  }
                else
                  slack[j] -= delta;
              j0 = j1;
            }
          while (row_of[j0] != 0);
          do
            {
              const int j1 = way[j0];
              row_of[j0]   = row_of[j1];
              j0           = j1;
            }
          while (j0 != 0);
        }
      std::vector<int> column(m, -1);
      for (int j = 1; j <= k; ++j)
        {
          const int i = row_of[j] - 1;
          if (i < m && j - 1 < n && cost(i, j - 1) <= reject)
            column[i] = j - 1;
        }
      return column;
    }

    std::vector<UnstableRegion>
    find_unstable_regions(
      const double                                          second,
      const std::vector<double>                            &first,
      const std::vector<unsigned int>                      &point_index,
      const std::vector<std::vector<std::complex<double>>> &lambdas,
      const std::vector<std::vector<int>>                  &tracks,
      const double                                          tolerance,
      const double                                          relative_tolerance)
    {
      std::vector<UnstableRegion>   regions;
      std::map<int, UnstableRegion> open; // by track
      const auto                    close = [&](const int track) {
        auto it = open.find(track);
        if (it != open.end())
          {
            regions.push_back(it->second);
            open.erase(it);
          }
      };
      for (unsigned int p = 0; p < lambdas.size(); ++p)
        {
          std::vector<int> unstable_now;
          for (unsigned int m = 0; m < lambdas[p].size(); ++m)
            {
              const auto   l = lambdas[p][m];
              const double f = l.imag() / (2 * M_PI);
              if (!is_unstable(l, tolerance, relative_tolerance))
                continue;
              const int t = tracks[p][m];
              unstable_now.push_back(t);
              auto it = open.find(t);
              if (it == open.end())
                it = open
                       .emplace(t,
                                UnstableRegion{second,
                                               first[p],
                                               first[p],
                                               f,
                                               f,
                                               l.real(),
                                               t,
                                               -1,
                                               point_index[p],
                                               point_index[p],
                                               point_index[p]})
                       .first;
              auto &r      = it->second;
              r.first_max  = first[p];
              r.last_point = point_index[p];
              r.f_min      = std::min(r.f_min, f);
              r.f_max      = std::max(r.f_max, f);
              if (l.real() > r.max_re)
                {
                  r.max_re       = l.real();
                  r.point_of_max = point_index[p];
                  // partner: the stable mode nearest in frequency here
                  double best = 1e300;
                  for (unsigned int k = 0; k < lambdas[p].size(); ++k)
                    if (k != m && lambdas[p][k].real() < 0 &&
                        std::abs(lambdas[p][k].imag() - l.imag()) < best)
                      {
                        best = std::abs(lambdas[p][k].imag() - l.imag());
                        r.partner_track = tracks[p][k];
                      }
                }
            }
          std::vector<int> to_close;
          for (const auto &[t, r] : open)
            if (std::find(unstable_now.begin(), unstable_now.end(), t) ==
                unstable_now.end())
              to_close.push_back(t);
          for (const int t : to_close)
            close(t);
        }
      std::vector<int> rest;
      for (const auto &[t, r] : open)
        rest.push_back(t);
      for (const int t : rest)
        close(t);
      std::sort(regions.begin(),
                regions.end(),
                [](const auto &a, const auto &b) {
                  return std::tie(a.f_min, a.first_min) <
                         std::tie(b.f_min, b.first_min);
                });
      return regions;
    }
  } // namespace eigen
} // namespace squeal
