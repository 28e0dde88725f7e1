// Mortar operators on a curved slave face: a pad-like annular sector
// (r 100-148 mm, 40 degrees, 10 mm thick, cylindrical manifold about z, as
// the brake's bodies are) resting on a flat block, its face in the plane
// z = z0. The face is planar but its edges are arcs, so the plane of its
// corners, on which the segments are integrated, differs from the face on
// which D is integrated. Degree 2.
// - Every slave node lies over the master, so every node takes part
//   (finite initial gap), and the faces touch, so every gap is 0 (1e-9 m).
// - The gaps do not depend on where the origin is: the same scene at
//   z0 = 25 mm and at z0 = 525 mm gives the same gaps (1e-12 m).

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>

#include <squeal/contact/mortar.h>

#include "check.h"

#include <cmath>

using namespace dealii;
using namespace squeal::contact;
using test_tools::check;
using test_tools::check_true;

namespace
{
  constexpr types::boundary_id slave_id = 10, master_id = 11;

  // The sector (material 0) on the block (material 1), touching at z0.
  void
  make_scene(Triangulation<3> &tria, const double z0)
  {
    const double     pi = numbers::PI;
    Triangulation<3> sector, block;
    GridGenerator::subdivided_hyper_rectangle(sector,
                                              {4, 6, 2},
                                              Point<3>(0.100, -pi / 9, z0),
                                              Point<3>(0.148,
                                                       pi / 9,
                                                       z0 + 0.01));
    GridTools::transform(
      [](const Point<3> &p) {
        return Point<3>(p[0] * std::cos(p[1]), p[0] * std::sin(p[1]), p[2]);
      },
      sector);
    GridGenerator::subdivided_hyper_rectangle(block,
                                              {5, 7, 2},
                                              Point<3>(0.08, -0.07, z0 - 0.01),
                                              Point<3>(0.16, 0.07, z0));
    GridGenerator::merge_triangulations(sector, block, tria, 0.);
    for (const auto &cell : tria.active_cell_iterators())
      {
        cell->set_material_id(
          cell->center()[0] > 0 && cell->center()[2] > z0 ? 0 : 1);
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && std::abs(face->center()[2] - z0) < 1e-9)
            face->set_boundary_id(cell->material_id() == 0 ? slave_id :
                                                             master_id);
      }
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->material_id() == 0)
        cell->set_all_manifold_ids(1);
    tria.set_manifold(1, CylindricalManifold<3>(2));
  }

  // The initial gaps gap0_j / D_j [m] of the scene at z0.
  std::vector<double>
  gaps(const double z0)
  {
    Triangulation<3> tria;
    make_scene(tria, z0);
    const FESystem<3> fe(FE_Q<3>(2), 3);
    DoFHandler<3>     dofs(tria);
    dofs.distribute_dofs(fe);
    const MappingQ<3>     mapping(2);
    const MortarOperators op =
      build_mortar_operators(dofs, mapping, slave_id, master_id, 1e-4);
    std::vector<double> g;
    for (unsigned int j = 0; j < op.n_slave(); ++j)
      g.push_back(op.gap0[j] / op.D[j]);
    return g;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::vector<double>              near, far;
  const std::string                error = test_tools::error_of([&] {
    near = gaps(0.025);
    far  = gaps(0.525);
  });
  check_true("the operators of the curved slave face build", error.empty());
  test_tools::verbose() << error << '\n';
  check_true("117 slave nodes at z0 = 25 mm and 525 mm",
             near.size() == 117 && far.size() == 117);
  double largest = 0., difference = 0.;
  bool   finite = !near.empty();
  for (unsigned int j = 0; j < near.size() && j < far.size(); ++j)
    {
      finite     = finite && std::isfinite(near[j]) && std::isfinite(far[j]);
      largest    = std::max({largest, std::abs(near[j]), std::abs(far[j])});
      difference = std::max(difference, std::abs(near[j] - far[j]));
    }
  test_tools::verbose() << "largest gap " << largest
                        << " m, largest difference " << difference << " m\n";
  check_true("every slave node over the master takes part", finite);
  check("the touching faces' gaps are 0", largest, 0., 1e-9, 1.);
  check("the gaps do not depend on the origin", difference, 0., 1e-12, 1.);
  return test_tools::n_failures == 0 ? 0 : 1;
}
