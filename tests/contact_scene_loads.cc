// The loads of a mesh-file scene (Scene/Mesh file/Loads): a block
// [0, L] x [0, b] x [0, b], degree 2, loaded by
//   a pressure p on x = L along +x        (pressure=),
//   a total force F on y = 0 along -y      (force=),
//   the analysis' normal force N on z = b along -z (neither given).
// Without constraints the load vector's entries of each component sum to
// the loads' totals (closed forms, 1e-12): sum_x = p b^2, sum_y = -F,
// sum_z = -N; a load alone carries its own, and the reported total is
// p b^2 + F + N. A load's ramp= is its own, else the run's. Bad loads (force
// and pressure both, a negative ramp, a negative pressure) get one error
// naming the item.

#include <deal.II/grid/grid_generator.h>

#include <squeal/contact/scene_contact.h>
#include <squeal/io/mesh_file.h>
#include <squeal/physics/structural_model.h>

#include "test_tools.h"

#include <fstream>
#include <sstream>
#include <string>

using namespace dealii;
using namespace squeal;
using test_tools::check;
using test_tools::error_of;

namespace
{
  const double L = 0.04, b = 0.01;
  const double p = 2e6, F = 30., N = 100.;

  parameters::AllParameters
  read(const std::string &loads, ParameterHandler &handler)
  {
    std::ofstream("block.prm")
      << "subsection Scene\n  set Type = mesh file\n"
         "  subsection Mesh file\n    set File = block.inp\n"
         "    set Bodies = block: set=BLOCK, E=200e9, nu=0.3, rho=7800\n"
         "    set Holds = x0: set=X0\n"
         "    set Loads = "
      << loads << "\n  end\nend\n"
      << "subsection Mesh\n  set Finite element degree = 2\nend\n";
    parameters::AllParameters prm;
    prm.read(handler, "block.prm");
    return prm;
  }

  // the sums of the x, y, z entries of @p f
  std::array<double, 3>
  sums(const physics::StructuralModel &model, const Vector<double> &f)
  {
    const auto [points, component] = physics::dof_support_points(model);
    std::array<double, 3> s{{0., 0., 0.}};
    for (unsigned int i = 0; i < f.size(); ++i)
      s[component[i]] += f[i];
    return s;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);
  {
    Triangulation<3> tria;
    GridGenerator::subdivided_hyper_rectangle(
      tria, {4, 2, 2}, Point<3>(), Point<3>(L, b, b), true);
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_material_id(0);
    io::NamedSets sets;
    sets.source = "the test's block";
    sets.collect_from_ids(tria,
                          {{0, "block"}},
                          {{0, "x0"}, {1, "x1"}, {2, "y0"}, {5, "z1"}});
    io::write_abaqus(tria, sets, "block.inp");
  }

  std::ostringstream loads;
  loads << "p: set=X1, direction=1 0 0, pressure=" << p
        << "; f: set=Y0, direction=0 -1 0, force=" << F << ", ramp=1e-3"
        << "; n: set=Z1, direction=0 0 -1";
  ParameterHandler                handler;
  const parameters::AllParameters prm = read(loads.str(), handler);
  physics::StructuralModel        model(prm, MPI_COMM_WORLD);
  model.setup_and_assemble(quiet);
  AffineConstraints<double> none; // keep every entry
  none.close();

  double     total = 0.;
  const auto all = sums(model, contact::scene_load(model, none, N, -1, &total));
  check("pressure p on x = L: sum of x entries = p b^2",
        all[0],
        p * b * b,
        1e-12);
  check("force F on y = 0: sum of y entries = -F", all[1], -F, 1e-12);
  check("the analysis' force N on z = b: sum of z entries = -N",
        all[2],
        -N,
        1e-12);
  check("total force = p b^2 + F + N", total, p * b * b + F + N, 1e-12);
  const auto only = sums(model, contact::scene_load(model, none, N, 1));
  check("load f alone: no x entries", std::abs(only[0]), 0., 0., 1.);
  check("load f alone: sum of y entries = -F", only[1], -F, 1e-12);
  check("load f's ramp is its own", model.scene->loads[1].ramp, 1e-3, 1e-15);
  check("load n takes the analysis' ramp (negative: Transient/Ramp duration)",
        model.scene->loads[2].ramp < 0. ? 0. : 1.,
        0.,
        0.,
        1.);

  for (const auto &[bad, expect] :
       {std::pair<std::string, std::string>{
          "q: set=X1, direction=1 0 0, force=1, pressure=1",
          "give force= or pressure=, not both"},
        {"q: set=X1, direction=1 0 0, ramp=-1", "ramp must be >= 0"},
        {"q: set=X1, direction=1 0 0, pressure=-5",
         "force [N] and pressure [Pa] must be >= 0"}})
    {
      ParameterHandler  h;
      const std::string e =
        error_of([&]() { scene::make_scene(read(bad, h)); });
      test_tools::check_message("bad load '" + bad +
                                  "': one error naming the item",
                                e,
                                {"Loads", "'q'", expect});
    }
  return test_tools::finish();
}
