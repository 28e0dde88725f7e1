// The support's springs as a Winkler layer (Springs/Attachment radius): the
// spring matrix K_s must be one model on every mesh and degree.
// - a rigid translation in the sliding direction (u_y = 1 m) stores
//   u^T K_s u = 44 k: each spring keeps its stiffness;
// - u_y = x - x_pad (rows at +-2.5 mm, stations symmetric in x, end stations
//   cut in z only) stores sum_i k (d_i^2 + s^2) with s^2 the bell's second
//   moment int w x^2 / int w, computed here by an independent 1D quadrature
//   in polar coordinates;
// - u_y = ((z - z_mid) / L)^2 stores the same energy at degree 2 and 3 and on
//   a mesh twice as fine along the support (consistent integration);
// on the coarse test TriboBrake, tolerance 1e-6 relative (the composite
// Gauss rules of sub-intervals a / 6 integrate the bell, C1 at its rim, to
// about 2e-7; lumped on the face nodes the second check is off by 3 %).

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/numerics/vector_tools.h>

#include <squeal/physics/structural_model.h>

#include "test_tools.h"

using namespace dealii;
using namespace squeal;

namespace
{
  /** u = (0, f(x), 0). */
  class SlidingField : public Function<3>
  {
  public:
    SlidingField(std::function<double(const Point<3> &)> f)
      : Function<3>(3)
      , f(std::move(f))
    {}
    double
    value(const Point<3> &p, const unsigned int c) const override
    {
      return c == 1 ? f(p) : 0.;
    }

  private:
    std::function<double(const Point<3> &)> f;
  };

  double
  energy(const physics::StructuralModel                &model,
         const std::function<double(const Point<3> &)> &f)
  {
    physics::PETScMatrix K;
    model.parts().springs(model.scene->nominal_point(), K);
    return test_tools::field_energy(model, K, SlidingField(f));
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using test_tools::check;
  ConditionalOStream quiet(std::cout, false);

  // the bell's second moment in x: int_0^a w(r) r^3 dr pi / (2 pi int_0^a w r
  // dr)
  const double    a = parameters::Springs().attachment_radius;
  const QGauss<1> gauss(20);
  double          m2 = 0, m0 = 0;
  for (unsigned int q = 0; q < gauss.size(); ++q)
    {
      const double r = a * gauss.point(q)[0];
      const double w =
        0.5 * (1. + std::cos(numbers::PI * r / a)) * a * gauss.weight(q);
      m2 += w * r * r * r * numbers::PI;
      m0 += w * r * 2. * numbers::PI;
    }
  const double s2 = m2 / m0;

  std::vector<double> quadratic;
  for (const auto &[degree, support_cells] :
       {std::pair{2u, 10u}, std::pair{3u, 10u}, std::pair{2u, 20u}})
    {
      parameters::AllParameters prm = test_tools::coarse_tribobrake(16, 2, 1);
      prm.mesh.fe_degree            = degree;
      prm.mesh.support_cells_length = support_cells;
      physics::StructuralModel model(prm, MPI_COMM_WORLD);
      model.setup_and_assemble(quiet);
      const auto  &g = prm.geometry;
      const double k = model.scene->nominal_point().get("support springs.k");
      const double d = g.pad_size / 4; // rows at x_pad +- 2.5 mm
      const std::string on = " (degree " + std::to_string(degree) + ", " +
                             std::to_string(support_cells) + " support cells)";
      check("rigid translation: u^T K_s u = 44 k" + on,
            energy(model, [](const Point<3> &) { return 1.; }),
            44 * k,
            1e-10);
      check("u_y = x - x_pad: 44 k (d^2 + s^2)" + on,
            energy(model,
                   [&](const Point<3> &p) { return p[0] - g.pad_radius; }),
            44 * k * (d * d + s2),
            1e-6);
      const double z_mid = g.pad_size + g.support_length / 2;
      quadratic.push_back(energy(model, [&](const Point<3> &p) {
        const double t = (p[2] - z_mid) / g.support_length;
        return t * t;
      }));
    }
  check("u_y = ((z - z_mid) / L)^2: degree 3 = degree 2",
        quadratic[1],
        quadratic[0],
        1e-6);
  check("u_y = ((z - z_mid) / L)^2: support cells 20 = 10",
        quadratic[2],
        quadratic[0],
        1e-6);
  test_tools::verbose() << "s^2 = " << s2 << " m^2, quadratic energies "
                        << quadratic[0] << " " << quadratic[1] << " "
                        << quadratic[2] << " J\n";
  return test_tools::finish();
}
