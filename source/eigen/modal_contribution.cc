// Modal contributions (see modal_contribution.h): the frictionless
// assembly's modes by the symmetric eigensolver, and the projections of a
// complex mode on them.

#include <deal.II/base/numbers.h>

#include <squeal/eigen/modal_contribution.h>

#include <cmath>
#include <stdexcept>

namespace squeal
{
  namespace eigen
  {
    using namespace dealii;

    FrictionlessModes
    frictionless_modes(const physics::MatrixParts    &model,
                       const parameters::ScalarPoint &p,
                       const BandOptions             &band,
                       const double                   factor,
                       ConditionalOStream            &pcout)
    {
      FrictionlessModes result;
      result.M = std::make_shared<PETScMatrix>();
      PETScMatrix K;
      model.mass(p, *result.M);
      // on its nonzeros (a third of the common pattern): the eigensolver
      // multiplies by it a few hundred times, and it is kept with the modes
      physics::store_nonzeros_only(*result.M,
                                   result.M->locally_owned_range_indices(),
                                   result.M->get_mpi_communicator());
      model.symmetric_stiffness(p, K);
      for (auto &mode : solve_undamped(*result.M, K, band, factor, true, pcout))
        {
          result.frequency.push_back(
            std::sqrt(std::max(mode.omega2.real(), 0.)) / (2 * numbers::PI));
          result.shape.push_back(std::move(mode.re));
        }
      return result;
    }

    ModalContributions
    modal_contributions(const FrictionlessModes &modes, const EigenPair &x)
    {
      PETScVector Mr(x.re), Mi(x.im);
      modes.M->vmult(Mr, x.re);
      modes.M->vmult(Mi, x.im);
      // ||x||_M^2 = x^H M x = re^T M re + im^T M im (M symmetric)
      const double norm2 = (x.re * Mr) + (x.im * Mi);
      if (!(norm2 > 0.))
        throw std::logic_error("modal contributions of a zero mode");
      const double       scale = 1. / std::sqrt(norm2);
      ModalContributions result;
      for (const auto &phi : modes.shape)
        {
          const std::complex<double> c{phi * Mr, phi * Mi};
          result.coefficient.push_back(c * scale);
          result.captured += std::norm(c) / norm2;
        }
      return result;
    }
  } // namespace eigen
} // namespace squeal
