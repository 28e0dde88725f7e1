#ifndef squeal_contact_polygon_h
#define squeal_contact_polygon_h

/**
 * @file
 * Plane polygon helpers of the segment-based mortar integration: signed
 * area, and the clipping of one convex polygon by another
 * (Sutherland-Hodgman). Coordinates in m, in a plane of the contact surface.
 */

#include <deal.II/base/point.h>

#include <algorithm>
#include <vector>

namespace squeal
{
  namespace contact
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
  } // namespace contact
} // namespace squeal

#endif
