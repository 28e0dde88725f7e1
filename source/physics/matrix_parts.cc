// The matrix parts of a model (physics::MatrixParts, structural_model.h):
// their coefficients at a parameter point, their combinations into M, C,
// K_s and K, and the modal damping's ratios.

#include <squeal/physics/structural_model.h>

#include <petscmat.h>

#include <algorithm>
#include <cmath>

namespace squeal
{
  namespace physics
  {
    using namespace dealii;

    double
    MatrixParts::ModalDamping::ratio(const double f) const
    {
      if (ratios.empty())
        return 0.;
      if (f <= ratios.front().first)
        return ratios.front().second;
      for (std::size_t k = 1; k < ratios.size(); ++k)
        if (f <= ratios[k].first)
          {
            const auto [f0, z0] = ratios[k - 1];
            const auto [f1, z1] = ratios[k];
            return z0 + (z1 - z0) * (f - f0) / (f1 - f0);
          }
      return ratios.back().second;
    }

    double
    MatrixParts::ModalDamping::coefficient(const double omega2) const
    {
      const double omega = std::sqrt(std::max(omega2, 0.));
      if (!(omega2 > 0.) || omega > 2. * numbers::PI * cutoff)
        return 0.;
      return 2. * ratio(omega / (2. * numbers::PI)) * omega;
    }

    MatrixParts::Combination
    MatrixParts::coefficients(const parameters::ScalarPoint &p) const
    {
      for (const auto &[name, value] : fixed)
        if (p.get(name) != value)
          throw std::runtime_error(
            "parameter " + name + " = " + std::to_string(p.get(name)) +
            " differs from " + std::to_string(value) +
            ", the value the model was assembled at: the model does not vary "
            "it (list it in StructuralModel::varied)");
      const std::size_t n = parts.size();
      Combination       c{Coefficients(n, 0.),
                    Coefficients(n, 0.),
                    Coefficients(n, 0.),
                    Coefficients(n, 0.),
                    Coefficients(n, 0.),
                    Coefficients(n, 0.)};
      for (std::size_t k = 0; k < n; ++k)
        {
          const Part  &q = parts[k];
          const double s =
            (q.scale.empty() ? 1. : p.get(q.scale) / q.reference) *
            (q.factor.empty() ? 1. : p.get(q.factor));
          const double d = q.damping.empty() ? 0. : p.get(q.damping) * s;
          switch (q.kind)
            {
              case Kind::mass:
                c.mass[k]    = s;
                c.damping[k] = d;
                break;
              case Kind::stiffness:
                c.structural[k] = c.symmetric_stiffness[k] = c.stiffness[k] = s;
                c.damping[k]                                                = d;
                if (q.springs)
                  c.springs[k] = s;
                break;
              case Kind::interface_normal:
                c.symmetric_stiffness[k] = c.stiffness[k] = s;
                break;
              case Kind::interface_friction:
                c.stiffness[k] = s;
                break;
            }
        }
      return c;
    }

    void
    MatrixParts::combine(const Coefficients &c, PETScMatrix &result) const
    {
      if (bodies_released)
        throw std::logic_error(
          "matrix parts: the bodies' parts were released "
          "(StructuralModel::release_body_parts); no combination can be "
          "formed");
      // The first part is on the common pattern: copy it and add the
      // others, on the same pattern or on their own nonzeros within it
      // (own_pattern). PETScMatrix::add() (DIFFERENT_NONZERO_PATTERN) would
      // rebuild the pattern for every part, 15x slower; a part of another
      // pattern (a transposed copy) is added that way.
      result.reinit(matrix(0));
      result.copy_from(matrix(0));
      result *= c[0];
      const auto stored = [](const PETScMatrix &A) {
        MatInfo info;
        MatGetInfo(A, MAT_GLOBAL_SUM, &info);
        return info.nz_used;
      };
      const double n_stored = stored(result);
      for (unsigned int k = 1; k < size(); ++k)
        if (c[k] != 0.)
          if (MatAXPY(result,
                      c[k],
                      matrix(k),
                      parts[k].own_pattern ? SUBSET_NONZERO_PATTERN :
                      stored(matrix(k)) == n_stored ?
                                             SAME_NONZERO_PATTERN :
                                             DIFFERENT_NONZERO_PATTERN) != 0)
            throw std::runtime_error("matrix parts: MatAXPY failed");
    }

    bool
    MatrixParts::sum(const Kind kind, PETScMatrix &result) const
    {
      Coefficients c(size(), 0.);
      bool         any = false;
      for (unsigned int k = 0; k < size(); ++k)
        if (parts[k].kind == kind)
          c[k] = 1., any = true;
      if (any)
        combine(c, result);
      return any;
    }

    void
    MatrixParts::springs(const parameters::ScalarPoint &p, PETScMatrix &K) const
    {
      combine(coefficients(p).springs, K);
    }

    void
    MatrixParts::spring_product(const parameters::ScalarPoint &p,
                                const PETScVector             &u,
                                PETScVector                   &result) const
    {
      const Coefficients c = coefficients(p).springs;
      PETScVector        t(result);
      result = 0.;
      for (unsigned int k = 0; k < size(); ++k)
        if (c[k] != 0.)
          {
            matrix(k).vmult(t, u);
            result.add(c[k], t);
          }
    }

    void
    MatrixParts::mass(const parameters::ScalarPoint &p, PETScMatrix &M) const
    {
      combine(coefficients(p).mass, M);
    }

    void
    MatrixParts::stiffness(const parameters::ScalarPoint &p,
                           PETScMatrix                   &K) const
    {
      combine(coefficients(p).stiffness, K);
    }

    void
    MatrixParts::symmetric_stiffness(const parameters::ScalarPoint &p,
                                     PETScMatrix                   &K) const
    {
      combine(coefficients(p).symmetric_stiffness, K);
    }

    void
    MatrixParts::damping(const parameters::ScalarPoint &p, PETScMatrix &C) const
    {
      combine(coefficients(p).damping, C);
    }
  } // namespace physics
} // namespace squeal
