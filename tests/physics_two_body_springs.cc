// Springs between two bodies (Scene/Mesh file/Springs, to=). Two steel
// blocks along x with a gap g between them, not sharing nodes: a on
// [0, 2c], b on [2c + g, 3c + g], section c x c; both slide along x only
// (their y and z faces held in y and z). Four springs of stiffness k along
// x join the facing corner nodes (stations at the gap's mid-plane).
// 1. Energies of the spring part, exact: a rigid translation of both
//    blocks stores nothing; b displaced by delta relative to a stores
//    4 k delta^2 (1e-12).
// 2. The two-mass oscillator: the blocks are far stiffer than the springs,
//    so the first non-zero mode is f = sqrt(4 k (1/m_a + 1/m_b)) / (2 pi)
//    up to the blocks' compliance under the corner forces (measured
//    1.9e-4 here, 1.9e-3 with 10 k: it scales with k; tolerance 5e-4).
// 3. A spring item with to= naming its own body, or with a radius, gets
//    one error naming the item.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/vector_tools.h>

#include <squeal/eigen/qep_solver.h>
#include <squeal/io/mesh_file.h>
#include <squeal/physics/structural_model.h>

#include "test_tools.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

using namespace dealii;
using namespace squeal;
using test_tools::check;
using test_tools::error_of;

namespace
{
  const double c = 0.01, g = 0.002; // m
  const double E = 200e9, nu = 0.3, rho = 7800.;
  const double k = 2e4; // N/m per spring

  void
  write_blocks(const std::string &file)
  {
    Triangulation<3> a, b, both;
    GridGenerator::subdivided_hyper_rectangle(a,
                                              {2, 1, 1},
                                              Point<3>(),
                                              Point<3>(2 * c, c, c));
    GridGenerator::subdivided_hyper_rectangle(b,
                                              {1, 1, 1},
                                              Point<3>(2 * c + g, 0, 0),
                                              Point<3>(3 * c + g, c, c));
    GridGenerator::merge_triangulations(a, b, both);
    // bodies by position; faces: y and z sides of each block
    for (const auto &cell : both.active_cell_iterators())
      {
        const bool in_b = cell->center()[0] > 2 * c;
        cell->set_material_id(in_b ? 1 : 0);
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const unsigned int side = f / 2; // x, y, z
              cell->face(f)->set_boundary_id(
                side == 0 ? 0 : (in_b ? 10 : 20) + side);
            }
      }
    io::NamedSets sets;
    sets.source = "the test's blocks";
    sets.collect_from_ids(both,
                          {{0, "a"}, {1, "b"}},
                          {{21, "a y"}, {22, "a z"}, {11, "b y"}, {12, "b z"}});
    io::write_abaqus(both, sets, file);
  }

  parameters::AllParameters
  read(const std::string &springs, ParameterHandler &handler)
  {
    std::ostringstream body;
    body << "E=" << E << ", nu=" << nu << ", rho=" << rho;
    std::ofstream("blocks.prm")
      << "subsection Scene\n  set Type = mesh file\n"
         "  subsection Mesh file\n    set File = blocks.inp\n"
         "    set Bodies = a: set=A, "
      << body.str() << "; b: set=B, " << body.str()
      << "\n    set Holds = ay: set=A_Y, components=y; az: set=A_Z, "
         "components=z; by: set=B_Y, components=y; bz: set=B_Z, "
         "components=z\n    set Springs = "
      << springs
      << "\n  end\nend\n"
         "subsection Mesh\n  set Finite element degree = 2\nend\n"
         "subsection Damping\n  set Alpha = 0\n  set Beta = 0\nend\n";
    parameters::AllParameters prm;
    prm.read(handler, "blocks.prm");
    return prm;
  }

  // u = (ua, 0, 0) on a, (ub, 0, 0) on b
  class Translations : public Function<3>
  {
  public:
    Translations(const double ua, const double ub)
      : Function<3>(3)
      , ua(ua)
      , ub(ub)
    {}
    double
    value(const Point<3> &x, const unsigned int comp) const override
    {
      return comp != 0 ? 0. : x[0] < 2 * c + g / 2 ? ua : ub;
    }

  private:
    const double ua, ub;
  };
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    write_blocks("blocks.inp");
  MPI_Barrier(MPI_COMM_WORLD);

  std::ostringstream springs;
  const double       x = 2 * c + g / 2;
  springs << "gap: body=a, to=b, direction=1 0 0, k=" << k << ", points=" << x
          << " 0 0 | " << x << " " << c << " 0 | " << x << " 0 " << c << " | "
          << x << " " << c << " " << c;
  ParameterHandler                handler;
  const parameters::AllParameters prm = read(springs.str(), handler);
  physics::StructuralModel        model(prm, MPI_COMM_WORLD);
  model.setup_and_assemble(quiet);
  const parameters::ScalarPoint p0 = model.scene->nominal_point();
  physics::PETScMatrix          Ks;
  model.parts().springs(p0, Ks);

  const auto energy = [&](const double ua, const double ub) {
    return test_tools::field_energy(model, Ks, Translations(ua, ub));
  };
  const double delta = 1e-5;
  check("rigid translation of both blocks: no spring energy",
        energy(delta, delta),
        0.,
        1e-12,
        4 * k * delta * delta);
  check("b moved by delta against a: u^T K u = 4 k delta^2",
        energy(0., delta),
        4 * k * delta * delta,
        1e-12);

  const double m_a = rho * 2 * c * c * c, m_b = rho * c * c * c;
  const double f = std::sqrt(4 * k * (1. / m_a + 1. / m_b)) / (2 * numbers::PI);
  const auto   freqs = test_tools::undamped_frequencies(prm, 0.2 * f, 3 * f);
  check("two-mass oscillator: first mode sqrt(4k (1/m_a + 1/m_b)) / 2 pi",
        freqs.empty() ? 0. : freqs.front(),
        f,
        5e-4);
  test_tools::verbose() << "two-mass frequency " << f << " Hz, model "
                        << (freqs.empty() ? 0. : freqs.front()) << " Hz"
                        << std::endl;

  for (const auto &[bad, expect] :
       {std::pair<std::string, std::string>{
          "s: body=a, to=a, direction=1 0 0, points=0.02 0 0",
          "must name another body"},
        {"s: body=a, to=b, direction=1 0 0, radius=0.001, points=0.02 0 0",
         "remove radius="}})
    {
      ParameterHandler  h;
      const std::string e =
        error_of([&]() { scene::make_scene(read(bad, h)); });
      test_tools::check_message("bad springs '" + bad +
                                  "': one error naming the item",
                                e,
                                {"'s'", expect});
    }
  return test_tools::finish();
}
