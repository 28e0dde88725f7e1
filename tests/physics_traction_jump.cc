// The traction-jump error indicator (physics/error_indicator.h) on fields
// with known face jumps, on a parallel::shared mesh (the indicator's
// squares summed over the ranks; also run on two ranks):
// 1. Two bonded materials in uniaxial stress (nu = 0, E_0 = 10 E_1, the
//    interface at x = 1 normal to the stress): u_x piecewise linear, so
//    degree 2 holds it exactly. The traction sigma n is continuous:
//    every cell's indicator is zero (1e-12 of the interface cells' Kelly
//    scale). Kelly's estimator on the same field marks the interface
//    cells with (h_K / 24) (sigma / E_1 - sigma / E_0)^2 A_F each (1e-6:
//    both estimators return single-precision values):
//    the jump of the gradient that bonded materials have in the exact
//    solution.
// 2. One material, degree 1, u = (x^2, 0, 0) on cubes of side h: the
//    interpolant's strain jumps by 2 h at each face normal to x, so each
//    such interior face gives (sqrt(3) h / 24) (2 h E)^2 h^2 / E =
//    sqrt(3) h^5 E / 6 to both its cells (1e-6); no other face jumps.
// 3. Hanging nodes: one cell refined, degree 2, u = (0, 0, x y) (in the
//    space, so every jump is zero when both sides are evaluated at the same
//    points of the subfaces): zero (1e-12 of the scale of 2).

#include <deal.II/base/function.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/vector_tools.h>

#include <squeal/physics/error_indicator.h>

#include "check.h"

#include <cmath>
#include <functional>

using namespace dealii;
using namespace squeal;
using test_tools::check;

namespace
{
  using Field = std::function<Tensor<1, 3>(const Point<3> &)>;

  Tensor<1, 3>
  vec(const double x, const double y, const double z)
  {
    Tensor<1, 3> t;
    t[0] = x;
    t[1] = y;
    t[2] = z;
    return t;
  }

  class VectorField : public Function<3>
  {
  public:
    explicit VectorField(Field u)
      : Function<3>(3)
      , u(std::move(u))
    {}
    double
    value(const Point<3> &p, const unsigned int c) const override
    {
      return u(p)[c];
    }

  private:
    Field u;
  };

  // the 2 m x 1 m x 1 m bar of every case: 4 x 2 x 2 cubes of side 0.5 m
  void
  bar(Triangulation<3> &tria)
  {
    GridGenerator::subdivided_hyper_rectangle(tria,
                                              {4, 2, 2},
                                              Point<3>(),
                                              Point<3>(2., 1., 1.));
  }

  // squares of the indicator per cell, summed over the ranks; KELLY: the
  // same of deal.II's Kelly estimator
  struct Result
  {
    Vector<double> traction, kelly;
  };

  Result
  indicators(parallel::shared::Triangulation<3>              &tria,
             const unsigned int                               degree,
             const std::function<double(types::material_id)> &E,
             const Field                                     &u)
  {
    const MPI_Comm comm = MPI_COMM_WORLD;
    FESystem<3>    fe(FE_Q<3>(degree), 3);
    MappingQ<3>    mapping(1);
    DoFHandler<3>  dofs(tria);
    dofs.distribute_dofs(fe);
    const IndexSet owned = dofs.locally_owned_dofs();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(dofs, relevant);
    AffineConstraints<double> hanging(relevant);
    DoFTools::make_hanging_node_constraints(dofs, hanging);
    hanging.close();
    PETScWrappers::MPI::Vector x(owned, comm), ghosted(owned, relevant, comm);
    VectorTools::interpolate(mapping, dofs, VectorField(u), x);
    hanging.distribute(x);
    ghosted = x;
    // nu = 0: sigma = E eps
    const physics::StiffnessOf stiffness = [&](const types::material_id id,
                                               const Point<3> &) {
      return SymmetricTensor<4, 3>(E(id) * identity_tensor<3>());
    };
    std::vector<Vector<float>> eta;
    physics::traction_jump_indicator(
      mapping, dofs, stiffness, E, {&ghosted}, eta);
    Vector<float> kelly(tria.n_active_cells());
    // on a shared mesh Kelly estimates every cell unless told this rank's
    KellyErrorEstimator<3>::estimate(mapping,
                                     dofs,
                                     QGauss<2>(degree + 1),
                                     {},
                                     ghosted,
                                     kelly,
                                     ComponentMask(),
                                     nullptr,
                                     numbers::invalid_unsigned_int,
                                     tria.locally_owned_subdomain());
    Result r{Vector<double>(tria.n_active_cells()),
             Vector<double>(tria.n_active_cells())};
    for (unsigned int c = 0; c < r.traction.size(); ++c)
      {
        r.traction[c] = double(eta[0][c]) * eta[0][c];
        r.kelly[c]    = double(kelly[c]) * kelly[c];
      }
    Utilities::MPI::sum(r.traction, comm, r.traction);
    Utilities::MPI::sum(r.kelly, comm, r.kelly);
    return r;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double                     h = 0.5, sigma = 1e6, E0 = 1e11, E1 = 1e10;
  const auto one_material = [&](const types::material_id) { return E0; };

  // 1. two bonded materials in uniaxial stress
  {
    parallel::shared::Triangulation<3> tria(MPI_COMM_WORLD);
    bar(tria);
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_material_id(cell->center()[0] > 1. ? 1 : 0);
    const auto E = [&](const types::material_id id) {
      return id == 0 ? E0 : E1;
    };
    const auto u = [&](const Point<3> &p) {
      return vec(p[0] < 1. ? sigma * p[0] / E0 :
                             sigma / E0 + sigma * (p[0] - 1.) / E1,
                 0.,
                 0.);
    };
    const Result r       = indicators(tria, 2, E, u);
    const double jump    = sigma / E1 - sigma / E0;
    const double kelly   = std::sqrt(3.) * h / 24. * jump * jump * h * h;
    double       largest = 0., interface_kelly = 0.;
    unsigned int interface_cells = 0;
    for (const auto &cell : tria.active_cell_iterators())
      {
        const unsigned int c = cell->active_cell_index();
        largest              = std::max(largest, r.traction[c]);
        if (std::abs(std::abs(cell->center()[0] - 1.) - h / 2.) < 1e-12)
          {
            ++interface_cells;
            interface_kelly =
              std::max(interface_kelly, std::abs(r.kelly[c] - kelly) / kelly);
          }
      }
    // the scale: a traction jump of sigma over one face
    const double scale = std::sqrt(3.) * h / 24. * sigma * sigma * h * h / E1;
    check("bimaterial, uniaxial stress: traction jump zero",
          largest,
          0.,
          1e-12,
          scale);
    check("bimaterial: Kelly's gradient jump at the 8 interface cells",
          interface_cells == 8 ? interface_kelly : 1.,
          0.,
          1e-6,
          1.);
  }

  // 2. u = (x^2, 0, 0) at degree 1
  {
    parallel::shared::Triangulation<3> tria(MPI_COMM_WORLD);
    bar(tria);
    const auto u = [&](const Point<3> &p) { return vec(p[0] * p[0], 0., 0.); };
    const Result r     = indicators(tria, 1, one_material, u);
    const double face  = std::sqrt(3.) * std::pow(h, 5) * E0 / 6.;
    double       error = 0.;
    for (const auto &cell : tria.active_cell_iterators())
      {
        const double x = cell->center()[0];
        // end cells have one interior face normal to x, the others two
        const double want = (x < h || x > 2. - h ? 1. : 2.) * face;
        error             = std::max(
          error, std::abs(r.traction[cell->active_cell_index()] - want) / face);
      }
    check("u = x^2 at degree 1: sqrt(3) h^5 E / 6 per face normal to x",
          error,
          0.,
          1e-6,
          1.);
  }

  // 3. hanging nodes
  {
    parallel::shared::Triangulation<3> tria(MPI_COMM_WORLD);
    bar(tria);
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->center().distance(Point<3>(0.75, 0.25, 0.25)) < 1e-12)
        cell->set_refine_flag();
    tria.execute_coarsening_and_refinement();
    const auto u = [&](const Point<3> &p) { return vec(0., 0., p[0] * p[1]); };
    const Result r = indicators(tria, 2, one_material, u);
    check("hanging nodes, u = (0, 0, x y) at degree 2: traction jump zero",
          r.traction.linfty_norm(),
          0.,
          1e-12,
          std::sqrt(3.) * h / 24. * E0 * E0 * h * h / E0);
    check("hanging nodes: 15 + 8 active cells", tria.n_active_cells(), 23., 0.);
  }
  return test_tools::finish();
}
