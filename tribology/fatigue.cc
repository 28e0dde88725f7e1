// Rainflow counting and fatigue-damage indices of contact-stress histories.
//
// The rainflow pass is the three-point algorithm of ASTM E1049-85 § 5.4.4 run
// on the reversals of the signal; it is exact (ranges are differences of
// samples) and linear in the number of samples, which matters because a
// contact history holds 1e4-1e6 samples for each of hundreds of nodes.
// The damage sums follow the critical-plane reading of fretting and
// contact fatigue (Findley 1959; Socie & Marquis, Multiaxial Fatigue, 2000):
// on the contact plane the shear traction cycles while the pressure clamps
// the crack faces, and separation (p = 0) removes that clamping.

#include <squeal/tribology/fatigue.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

namespace squeal
{
  namespace tribology
  {
    Residue
    residue_from_string(const std::string &name)
    {
      if (name == "half cycles")
        return Residue::half_cycles;
      if (name == "repeating")
        return Residue::repeating;
      throw std::invalid_argument("unknown rainflow residue convention '" +
                                  name + "' (allowed: half cycles, repeating)");
    }

    namespace
    {
      // Keeps from @p seq (indices into x) the points that are turning
      // points of the sequence of their values, and its two ends; equal
      // consecutive values count once.
      std::vector<std::size_t>
      turning_points(const std::vector<double>      &x,
                     const std::vector<std::size_t> &seq)
      {
        std::vector<std::size_t> distinct;
        for (const std::size_t i : seq)
          if (distinct.empty() || x[i] != x[distinct.back()])
            distinct.push_back(i);
        if (distinct.size() <= 2)
          return distinct;
        std::vector<std::size_t> out{distinct.front()};
        for (std::size_t j = 1; j + 1 < distinct.size(); ++j)
          {
            const double a = x[out.back()], b = x[distinct[j]],
                         c = x[distinct[j + 1]];
            if ((b - a) * (c - b) < 0.)
              out.push_back(distinct[j]);
          }
        out.push_back(distinct.back());
        return out;
      }

      Cycle
      make_cycle(const std::vector<double> &x,
                 std::size_t                from,
                 std::size_t                to,
                 double                     count)
      {
        return {
          std::abs(x[to] - x[from]), 0.5 * (x[to] + x[from]), count, from, to};
      }
    } // namespace

    std::vector<std::size_t>
    reversals(const std::vector<double> &x)
    {
      std::vector<std::size_t> all(x.size());
      for (std::size_t i = 0; i < x.size(); ++i)
        all[i] = i;
      return turning_points(x, all);
    }

    std::vector<Cycle>
    rainflow(const std::vector<double> &x, const Residue residue)
    {
      std::vector<std::size_t> seq = reversals(x);
      if (residue == Residue::repeating && seq.size() > 2)
        {
          // Restart the periodic history at its largest absolute value: no
          // range can then stay open, and every cycle is a full one.
          const auto top =
            std::max_element(seq.begin(),
                             seq.end(),
                             [&](std::size_t a, std::size_t b) {
                               return std::abs(x[a]) < std::abs(x[b]);
                             });
          std::vector<std::size_t> rotated(top, seq.end());
          rotated.insert(rotated.end(), seq.begin(), top + 1);
          seq = turning_points(x, rotated);
        }

      std::vector<Cycle>       cycles;
      std::vector<std::size_t> stack;
      for (const std::size_t k : seq)
        {
          stack.push_back(k);
          while (stack.size() >= 3)
            {
              const std::size_t n = stack.size();
              const double      X = std::abs(x[stack[n - 1]] - x[stack[n - 2]]);
              const double      Y = std::abs(x[stack[n - 2]] - x[stack[n - 3]]);
              if (X < Y)
                break;
              if (n == 3 && residue == Residue::half_cycles)
                {
                  // Y contains the starting point: half a cycle.
                  cycles.push_back(make_cycle(x, stack[0], stack[1], 0.5));
                  stack.erase(stack.begin());
                }
              else
                {
                  cycles.push_back(
                    make_cycle(x, stack[n - 3], stack[n - 2], 1.0));
                  stack.erase(stack.end() - 3, stack.end() - 1);
                }
            }
        }
      if (residue == Residue::half_cycles)
        for (std::size_t i = 0; i + 1 < stack.size(); ++i)
          cycles.push_back(make_cycle(x, stack[i], stack[i + 1], 0.5));
      return cycles;
    }

    namespace
    {
      void
      require_same_length(const std::vector<double> &p,
                          std::size_t                n,
                          const char                *what)
      {
        if (p.size() != n)
          throw std::invalid_argument(
            std::string(what) + ": histories of different lengths (" +
            std::to_string(p.size()) + " and " + std::to_string(n) + ")");
      }

      // Smallest p over the samples a cycle spans, wrapping when it crosses
      // the end of a repeating record.
      double
      min_over_cycle(const std::vector<double> &p, const Cycle &c)
      {
        if (c.start <= c.end)
          return *std::min_element(p.begin() + c.start, p.begin() + c.end + 1);
        return std::min(*std::min_element(p.begin() + c.start, p.end()),
                        *std::min_element(p.begin(), p.begin() + c.end + 1));
      }
    } // namespace

    FindleyDamage
    findley_damage(const std::vector<double> &p,
                   const std::vector<double> &q,
                   const FindleyParameters   &par)
    {
      require_same_length(p, q.size(), "Findley damage");
      FindleyDamage d;
      for (const Cycle &c : rainflow(q, par.residue))
        {
          const double tau =
            std::max(0., 0.5 * c.range - par.k * min_over_cycle(p, c));
          d.relative += c.count * std::pow(tau, par.m);
          d.miner += c.count * 2. * std::pow(tau / par.tau_f, par.m);
          d.max_tau_eq = std::max(d.max_tau_eq, tau);
          d.n_cycles += c.count;
        }
      return d;
    }

    namespace
    {
      using Point = std::array<double, 2>;

      struct Circle
      {
        double x, y, r;
        bool
        contains(const Point &p) const
        {
          return std::hypot(p[0] - x, p[1] - y) <= r * (1. + 1e-12) + 1e-300;
        }
      };

      Circle
      circle_of(const Point &a, const Point &b)
      {
        return {0.5 * (a[0] + b[0]),
                0.5 * (a[1] + b[1]),
                0.5 * std::hypot(a[0] - b[0], a[1] - b[1])};
      }

      Circle
      circle_of(const Point &a, const Point &b, const Point &c)
      {
        const double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0],
                     cy = c[1] - a[1];
        const double d  = 2. * (bx * cy - by * cx);
        if (std::abs(d) < 1e-300)
          {
            // collinear: the circle on the two farthest points
            Circle best = circle_of(a, b);
            for (const Circle &k : {circle_of(a, c), circle_of(b, c)})
              if (k.r > best.r)
                best = k;
            return best;
          }
        const double ux =
                       (cy * (bx * bx + by * by) - by * (cx * cx + cy * cy)) /
                       d,
                     uy =
                       (bx * (cx * cx + cy * cy) - cx * (bx * bx + by * by)) /
                       d;
        return {a[0] + ux, a[1] + uy, std::hypot(ux, uy)};
      }

      // Radius of the minimum enclosing circle (Welzl's randomised
      // incremental algorithm, expected linear time, in double precision:
      // OpenCV's minEnclosingCircle works in float and pads the radius).
      double
      min_enclosing_radius(std::vector<Point> pts)
      {
        std::mt19937 rng(12345); // deterministic shuffle
        std::shuffle(pts.begin(), pts.end(), rng);
        Circle c{pts[0][0], pts[0][1], 0.};
        for (std::size_t i = 1; i < pts.size(); ++i)
          if (!c.contains(pts[i]))
            {
              c = {pts[i][0], pts[i][1], 0.};
              for (std::size_t j = 0; j < i; ++j)
                if (!c.contains(pts[j]))
                  {
                    c = circle_of(pts[i], pts[j]);
                    for (std::size_t k = 0; k < j; ++k)
                      if (!c.contains(pts[k]))
                        c = circle_of(pts[i], pts[j], pts[k]);
                  }
            }
        return c.r;
      }
    } // namespace

    CrosslandIndex
    crossland_index(const std::vector<double> &p,
                    const std::vector<double> &q,
                    const double               nu,
                    const double               alpha)
    {
      require_same_length(p, q.size(), "Crossland index");
      if (!(nu >= 0. && nu < 0.5))
        throw std::invalid_argument(
          "Crossland index: Poisson ratio must lie in [0, 0.5), got " +
          std::to_string(nu));
      CrosslandIndex c;
      if (p.empty())
        return c;
      // Deviatoric plane coordinates with sqrt(J2) as Euclidean length.
      const double a     = std::sqrt(3.) * (1. - 2. * nu) / (3. * (1. - nu));
      double       scale = 0.;
      for (std::size_t i = 0; i < p.size(); ++i)
        scale = std::max({scale, std::abs(a * p[i]), std::abs(q[i])});
      if (scale > 0.)
        {
          std::vector<Point> path(p.size());
          for (std::size_t i = 0; i < p.size(); ++i)
            path[i] = {{a * p[i] / scale, q[i] / scale}};
          c.sqrt_j2_amplitude = min_enclosing_radius(path) * scale;
        }
      const double p_min = *std::min_element(p.begin(), p.end());
      c.hydrostatic_max  = -(1. + nu) / (3. * (1. - nu)) * p_min;
      c.index            = c.sqrt_j2_amplitude + alpha * c.hydrostatic_max;
      return c;
    }

    NodeStatistics
    node_statistics(const std::vector<double> &p,
                    const std::vector<int>    &status,
                    const double               sampling_rate)
    {
      if (p.empty())
        throw std::invalid_argument("node statistics: empty history");
      if (status.size() != p.size())
        throw std::invalid_argument(
          "node statistics: pressure and status histories of different "
          "lengths");
      NodeStatistics s;
      const auto [lo, hi] = std::minmax_element(p.begin(), p.end());
      double sum          = 0.;
      for (const double v : p)
        sum += v;
      s.mean_pressure = sum / p.size();
      s.max_pressure  = *hi;
      s.relative_oscillation =
        s.mean_pressure > 0. ? (*hi - *lo) / s.mean_pressure : 0.;
      for (const int st : status)
        {
          s.separated_fraction += (st == 0);
          s.stick_fraction += (st == 1);
          s.slip_fraction += (st == 2);
        }
      s.separated_fraction /= p.size();
      s.stick_fraction /= p.size();
      s.slip_fraction /= p.size();
      const std::vector<Cycle> cycles  = rainflow(p, Residue::half_cycles);
      double                   largest = 0.;
      for (const Cycle &c : cycles)
        largest = std::max(largest, c.range);
      double count = 0.;
      if (largest > 0.)
        for (const Cycle &c : cycles)
          count += (c.range > 0.1 * largest) ? c.count : 0.;
      s.cycles_per_second = count * sampling_rate / p.size();
      return s;
    }
  } // namespace tribology
} // namespace squeal
