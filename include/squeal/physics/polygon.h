#ifndef squeal_physics_polygon_h
#define squeal_physics_polygon_h

/**
 * @file
 * Plane polygon helpers of the segment-based mortar integration: signed
 * area, and the clipping of one convex polygon by another
 * (Sutherland-Hodgman). Coordinates in m, in a plane of the contact surface.
 */

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace squeal
{
  namespace physics
  {
    /** A plane polygon, vertices in order. */
    using Polygon = std::vector<dealii::Point<2>>;

    /** (a - o) x (b - o): twice the signed area of triangle o, a, b [m^2]. */
    inline double
    cross(const dealii::Point<2> &o,
          const dealii::Point<2> &a,
          const dealii::Point<2> &b)
    {
      return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    }

    /** Signed area [m^2], positive when counter-clockwise. */
    inline double
    signed_area(const Polygon &p)
    {
      double a = 0;
      for (unsigned int i = 0; i < p.size(); ++i)
        {
          const auto &u = p[i], &v = p[(i + 1) % p.size()];
          a += u[0] * v[1] - v[0] * u[1];
        }
      return a / 2;
    }

    /** @p p in counter-clockwise order. */
    inline Polygon
    counter_clockwise(Polygon p)
    {
      if (signed_area(p) < 0)
        std::reverse(p.begin(), p.end());
      return p;
    }

    /**
     * Sutherland-Hodgman: the part of the convex polygon @p subject inside
     * the convex polygon @p clip (both counter-clockwise). Empty, or fewer
     * than 3 vertices, when they do not overlap.
     */
    inline Polygon
    clip_polygon(const Polygon &subject, const Polygon &clip)
    {
      Polygon out = subject;
      for (unsigned int e = 0; e < clip.size() && !out.empty(); ++e)
        {
          const dealii::Point<2> a = clip[e], b = clip[(e + 1) % clip.size()];
          const Polygon          in = out;
          out.clear();
          for (unsigned int i = 0; i < in.size(); ++i)
            {
              const dealii::Point<2> p = in[i], q = in[(i + 1) % in.size()];
              const double           cp = cross(a, b, p), cq = cross(a, b, q);
              if (cp >= 0)
                out.push_back(p);
              if ((cp >= 0) != (cq >= 0))
                out.push_back(p + (q - p) * (cp / (cp - cq)));
            }
        }
      return out;
    }

    /**
     * Quadrature of a convex polygon: the fan of triangles from its first
     * vertex, each carrying @p triangle_rule (a rule on the reference
     * triangle, weights summing to 1/2, e.g. QGaussSimplex<2>).
     * @return (point, weight [m^2]) pairs; the weights sum to the area.
     */
    inline std::vector<std::pair<dealii::Point<2>, double>>
    polygon_quadrature(const Polygon               &p,
                       const dealii::Quadrature<2> &triangle_rule)
    {
      std::vector<std::pair<dealii::Point<2>, double>> q;
      for (unsigned int t = 1; t + 1 < p.size(); ++t)
        {
          const dealii::Point<2> a = p[0], b = p[t], c = p[t + 1];
          const double           area = std::abs(cross(a, b, c)) / 2;
          for (unsigned int k = 0; k < triangle_rule.size(); ++k)
            {
              const dealii::Point<2> r = triangle_rule.point(k);
              q.emplace_back(a + (b - a) * r[0] + (c - a) * r[1],
                             2. * area * triangle_rule.weight(k));
            }
        }
      return q;
    }
  } // namespace physics
} // namespace squeal

#endif
