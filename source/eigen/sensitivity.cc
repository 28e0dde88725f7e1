// Eigenvalue sensitivities from left and right eigenvectors (see
// sensitivity.h): the left eigenvectors come from the full solver on the
// transposed model, the derivatives from one product per matrix part.

#include <deal.II/base/numbers.h>

#include <squeal/eigen/sensitivity.h>
#include <squeal/eigen/tracking.h>

#include <Eigen/Dense>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace eigen
  {
    using namespace dealii;

    TransposedModel::TransposedModel(const physics::MatrixParts &model)
      : transposed(model)
    {
      for (auto &part : transposed.parts)
        if (part.kind == physics::MatrixParts::Kind::interface_friction)
          {
            auto copy = std::make_unique<PETScMatrix>();
            copy->reinit(*part.matrix);
            copy->copy_from(*part.matrix);
            // K_t's pattern couples slave to master rows only; its
            // transpose may fall outside the common pattern, which
            // MatrixParts::combine() handles
            copy->transpose();
            part.matrix      = copy.get();
            part.own_pattern = false; // no longer within the common one
            copies.push_back(std::move(copy));
          }
    }

    std::vector<EigenPair>
    left_eigenvectors(const physics::MatrixParts    &model,
                      const parameters::ScalarPoint &p,
                      const BandOptions             &band,
                      const std::vector<EigenPair>  &right,
                      ConditionalOStream            &pcout)
    {
      if (right.empty())
        return {};
      const TransposedModel transposed(model);
      BandOptions           wider = band;
      wider.f_min *= 1. - 1e-3;
      wider.f_max *= 1. + 1e-3;
      std::vector<EigenPair> left =
        solve_full(transposed.parts(), p, wider, pcout);
      Eigen::MatrixXd cost(right.size(), left.size());
      for (unsigned int i = 0; i < right.size(); ++i)
        for (unsigned int j = 0; j < left.size(); ++j)
          cost(i, j) = std::abs(right[i].lambda - left[j].lambda) /
                       std::abs(right[i].lambda);
      const double           reject  = 1e-7;
      const std::vector<int> partner = optimal_assignment(cost, reject);
      std::vector<EigenPair> ordered;
      for (unsigned int i = 0; i < right.size(); ++i)
        {
          if (partner[i] < 0 || cost(i, partner[i]) > reject)
            {
              std::ostringstream what;
              what << "sensitivities: the eigenvalue " << right[i].lambda
                   << " 1/s (" << right[i].lambda.imag() / (2 * numbers::PI)
                   << " Hz) has no left eigenvector within " << reject
                   << " |lambda| in the transposed problem's " << left.size()
                   << " eigenvalues";
              throw std::runtime_error(what.str());
            }
          ordered.push_back(std::move(left[partner[i]]));
        }
      return ordered;
    }


    std::vector<physics::MatrixParts::Combination>
    coefficient_slopes(const physics::MatrixParts     &model,
                       const parameters::ScalarPoint  &p,
                       const std::vector<std::string> &names)
    {
      using Combination = physics::MatrixParts::Combination;
      // each coefficient is affine in each single parameter, so a central
      // difference of any step is its exact derivative
      std::vector<Combination> slope;
      for (const auto &name : names)
        {
          for (const auto &[fixed, value] : model.fixed)
            if (fixed == name)
              throw std::runtime_error(
                "sensitivities: the model holds " + name + " fixed at " +
                std::to_string(value) +
                "; it has no matrix part of its own to differentiate");
          const double            value = p.get(name);
          const double            h     = value != 0. ? std::abs(value) : 1.;
          parameters::ScalarPoint up = p, down = p;
          up.set(name, value + h / 2);
          down.set(name, value - h / 2);
          Combination       d  = model.coefficients(up);
          const Combination lo = model.coefficients(down);
          for (auto [a, b] :
               {std::pair{&d.mass, &lo.mass},
                std::pair{&d.damping, &lo.damping},
                std::pair{&d.stiffness, &lo.stiffness},
                std::pair{&d.structural, &lo.structural},
                std::pair{&d.symmetric_stiffness, &lo.symmetric_stiffness},
                std::pair{&d.springs, &lo.springs}})
            for (unsigned int k = 0; k < a->size(); ++k)
              (*a)[k] = ((*a)[k] - (*b)[k]) / h;
          slope.push_back(std::move(d));
        }
      return slope;
    }


    std::vector<EigenvalueSensitivity>
    eigenvalue_sensitivities(const physics::MatrixParts     &model,
                             const parameters::ScalarPoint  &p,
                             const std::vector<std::string> &names,
                             const std::vector<EigenPair>   &right,
                             const std::vector<EigenPair>   &left)
    {
      if (right.size() != left.size())
        throw std::logic_error(
          "sensitivities: " + std::to_string(right.size()) + " right but " +
          std::to_string(left.size()) + " left eigenvectors");
      using Combination                 = physics::MatrixParts::Combination;
      const Combination              at = model.coefficients(p);
      const std::vector<Combination> slope =
        coefficient_slopes(model, p, names);

      std::vector<EigenvalueSensitivity> result;
      PETScVector Px(right.empty() ? PETScVector() : right[0].re);
      for (unsigned int i = 0; i < right.size(); ++i)
        {
          const std::complex<double> l = right[i].lambda;
          const EigenPair           &x = right[i], &y = left[i];
          // y^T P_k x for every part, and z = (2 lambda M + C) x, a
          // complex vector z_re + i z_im
          std::vector<std::complex<double>> form(model.size());
          PETScVector                       z_re(x.re), z_im(x.re);
          z_re = 0.;
          z_im = 0.;
          for (unsigned int k = 0; k < model.size(); ++k)
            {
              const std::complex<double> c =
                2. * l * at.mass[k] + at.damping[k];
              model.matrix(k).vmult(Px, x.re);
              const double rr = y.re * Px, ir = y.im * Px;
              if (c != 0.)
                {
                  z_re.add(c.real(), Px);
                  z_im.add(c.imag(), Px);
                }
              model.matrix(k).vmult(Px, x.im);
              const double ri = y.re * Px, ii = y.im * Px;
              if (c != 0.)
                {
                  z_re.add(-c.imag(), Px);
                  z_im.add(c.real(), Px);
                }
              form[k] = {rr - ii, ri + ir};
            }
          std::complex<double> denominator = 0.;
          for (unsigned int k = 0; k < model.size(); ++k)
            denominator += (2. * l * at.mass[k] + at.damping[k]) * form[k];
          EigenvalueSensitivity s;
          s.lambda = l;
          for (const auto &d : slope)
            {
              std::complex<double> numerator = 0.;
              for (unsigned int k = 0; k < model.size(); ++k)
                numerator +=
                  (l * l * d.mass[k] + l * d.damping[k] + d.stiffness[k]) *
                  form[k];
              s.derivative.push_back(-numerator / denominator);
            }
          s.condition = std::hypot(y.re.l2_norm(), y.im.l2_norm()) *
                        std::hypot(z_re.l2_norm(), z_im.l2_norm()) /
                        std::abs(denominator);
          result.push_back(std::move(s));
        }
      return result;
    }
  } // namespace eigen
} // namespace squeal
