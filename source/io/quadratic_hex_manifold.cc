// The 20-node serendipity map of a C3D20 element and its inverse.

#include <deal.II/base/exceptions.h>

#include <squeal/io/quadratic_hex_manifold.h>

#include <algorithm>

namespace squeal
{
  namespace io
  {
    using namespace dealii;

    namespace
    {
      // Abaqus reference coordinates of the 20 nodes
      Point<3>
      node(const unsigned int i)
      {
        static const double r[20][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1},
                                        {-1, 1, -1},  {-1, -1, 1}, {1, -1, 1},
                                        {1, 1, 1},    {-1, 1, 1},  {0, -1, -1},
                                        {1, 0, -1},   {0, 1, -1},  {-1, 0, -1},
                                        {0, -1, 1},   {1, 0, 1},   {0, 1, 1},
                                        {-1, 0, 1},   {-1, -1, 0}, {1, -1, 0},
                                        {1, 1, 0},    {-1, 1, 0}};
        return Point<3>(r[i][0], r[i][1], r[i][2]);
      }

      double
      shape(const unsigned int i, const Point<3> &s)
      {
        const Point<3> n = node(i);
        if (i < 8)
          return (1 + n[0] * s[0]) * (1 + n[1] * s[1]) * (1 + n[2] * s[2]) *
                 (n[0] * s[0] + n[1] * s[1] + n[2] * s[2] - 2) / 8;
        double v = 0.25;
        for (unsigned int d = 0; d < 3; ++d)
          v *= n[d] == 0 ? 1 - s[d] * s[d] : 1 + n[d] * s[d];
        return v;
      }

      Tensor<1, 3>
      gradient(const unsigned int i, const Point<3> &s)
      {
        const Point<3> n = node(i);
        Tensor<1, 3>   g;
        if (i < 8)
          {
            const double f[3] = {1 + n[0] * s[0],
                                 1 + n[1] * s[1],
                                 1 + n[2] * s[2]};
            const double sum  = n[0] * s[0] + n[1] * s[1] + n[2] * s[2] - 2;
            for (unsigned int d = 0; d < 3; ++d)
              g[d] = n[d] * f[(d + 1) % 3] * f[(d + 2) % 3] * (sum + f[d]) / 8;
            return g;
          }
        for (unsigned int d = 0; d < 3; ++d)
          {
            double v = 0.25;
            for (unsigned int e = 0; e < 3; ++e)
              if (e == d)
                v *= n[e] == 0 ? -2 * s[e] : n[e];
              else
                v *= n[e] == 0 ? 1 - s[e] * s[e] : 1 + n[e] * s[e];
            g[d] = v;
          }
        return g;
      }
    } // namespace

    QuadraticHexManifold::QuadraticHexManifold(
      const std::array<Point<3>, 20> &x)
      : x(x)
    {}

    std::unique_ptr<Manifold<3, 3>>
    QuadraticHexManifold::clone() const
    {
      return std::make_unique<QuadraticHexManifold>(x);
    }

    Point<3>
    QuadraticHexManifold::push_forward(const Point<3> &s) const
    {
      Point<3> p;
      for (unsigned int i = 0; i < 20; ++i)
        p += shape(i, s) * x[i];
      return p;
    }

    DerivativeForm<1, 3, 3>
    QuadraticHexManifold::push_forward_gradient(const Point<3> &s) const
    {
      DerivativeForm<1, 3, 3> J;
      for (unsigned int i = 0; i < 20; ++i)
        {
          const Tensor<1, 3> g = gradient(i, s);
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int b = 0; b < 3; ++b)
              J[a][b] += x[i][a] * g[b];
        }
      return J;
    }

    Point<3>
    QuadraticHexManifold::pull_back(const Point<3> &p) const
    {
      double size = 0.;
      for (unsigned int i = 1; i < 8; ++i)
        size = std::max(size, x[i].distance(x[0]));
      Point<3> s; // the cell centre
      for (unsigned int it = 0; it < 50; ++it)
        {
          const Tensor<1, 3> r = p - push_forward(s);
          if (r.norm() <= 1e-14 * size)
            return s;
          s += invert(Tensor<2, 3>(push_forward_gradient(s))) * r;
        }
      AssertThrow(false,
                  ExcMessage("a quadratic element's geometry could "
                             "not be inverted at a point (a strongly "
                             "distorted C3D20)"));
      return s;
    }
  } // namespace io
} // namespace squeal
