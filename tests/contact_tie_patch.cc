// Ties (Scene/Mesh file/Ties): two blocks meshed apart, bonded by dual
// mortar mesh tying on non-matching faces. Block L on [0, a]^2 x [0, a]
// (4 x 4 x 2 cells, the slave side, finer) under block U on
// [0, a]^2 x [a, 2a] (3 x 3 x 2 cells), one steel; L's bottom held along z,
// the rigid motions in x and y stopped at two corner nodes (point holds), a
// pressure p on U's top. The exact solution is uniaxial stress:
//   u_z = -p z / E,   u_x = nu p x / E,   u_y = nu p y / E,
// linear across the interface, so a tie that passes the patch test gives it
// at every node (1e-10 of the largest displacement), degree 1 and 2.
// Without the tie U would float: the scene refuses it by name. An analysis
// that builds its model without the tie hook is refused.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/sparse_direct.h>

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
  const double a = 0.01, E = 200e9, nu = 0.3, p = 1e6;

  // L and U as one triangulation that shares no vertex
  void
  write_blocks(const std::string &file)
  {
    Triangulation<3> lower, upper, both;
    GridGenerator::subdivided_hyper_rectangle(lower,
                                              {4, 4, 2},
                                              Point<3>(),
                                              Point<3>(a, a, a));
    GridGenerator::subdivided_hyper_rectangle(upper,
                                              {3, 3, 2},
                                              Point<3>(0, 0, a),
                                              Point<3>(a, a, 2 * a));
    auto [v, cells, sub]    = GridTools::get_coarse_mesh_description(lower);
    auto [v2, cells2, sub2] = GridTools::get_coarse_mesh_description(upper);
    const unsigned int n    = v.size();
    v.insert(v.end(), v2.begin(), v2.end());
    for (auto c : cells2)
      {
        for (auto &k : c.vertices)
          k += n;
        cells.push_back(c);
      }
    both.create_triangulation(v, cells, SubCellData());
    for (const auto &cell : both.active_cell_iterators())
      {
        const bool in_u = cell->center()[2] > a;
        cell->set_material_id(in_u ? 1 : 0);
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const double z = cell->face(f)->center()[2];
              cell->face(f)->set_boundary_id(
                std::abs(z) < 1e-12 * a         ? 1 :
                std::abs(z - a) < 1e-12 * a     ? (in_u ? 3 : 2) :
                std::abs(z - 2 * a) < 1e-12 * a ? 4 :
                                                  0);
            }
      }
    io::NamedSets sets;
    sets.source = "the test's blocks";
    sets.collect_from_ids(
      both,
      {{0, "l"}, {1, "u"}},
      {{1, "bottom"}, {2, "ltop"}, {3, "ubottom"}, {4, "top"}});
    io::write_abaqus(both, sets, file);
  }

  parameters::AllParameters
  read(const std::string &ties, const unsigned int degree, ParameterHandler &h)
  {
    std::ostringstream material;
    material << "E=" << E << ", nu=" << nu << ", rho=7800";
    std::ofstream("blocks.prm")
      << "subsection Scene\n  set Type = mesh file\n"
         "  subsection Mesh file\n    set File = blocks.inp\n"
         "    set Bodies = l: set=L, "
      << material.str() << "; u: set=U, " << material.str()
      << "\n    set Ties = " << ties
      << "\n    set Holds = bottom: set=BOTTOM, components=z\n"
         "    set Point holds = ox: point=0 0 0, component=x; oy: point=0 0 "
         "0, component=y; ay: point="
      << a
      << " 0 0, component=y\n"
         "    set Loads = press: set=TOP, direction=0 0 -1, pressure="
      << p << "\n  end\nend\nsubsection Mesh\n  set Finite element degree = "
      << degree << "\nend\n";
    parameters::AllParameters prm;
    prm.read(h, "blocks.prm");
    return prm;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);
  write_blocks("blocks.inp");
  const std::string tie = "bond: slave=LTOP, master=UBOTTOM";

  for (const unsigned int degree : {1u, 2u})
    {
      ParameterHandler                h;
      const parameters::AllParameters prm = read(tie, degree, h);
      physics::StructuralModel        model(prm, MPI_COMM_WORLD);
      model.tie_constraints = contact::add_tie_constraints;
      model.setup_and_assemble(quiet);
      SparsityPattern           pattern;
      SparseMatrix<double>      K;
      AffineConstraints<double> constraints;
      contact::contact_system(model, pattern, K, constraints);
      Vector<double>      f = contact::scene_load(model, constraints, 0.);
      Vector<double>      u(f.size());
      SparseDirectUMFPACK solver;
      solver.initialize(K);
      solver.vmult(u, f);
      constraints.distribute(u);

      const auto [points, component] = physics::dof_support_points(model);
      double worst = 0., largest = 0.;
      for (unsigned int i = 0; i < u.size(); ++i)
        {
          const Point<3> &x = points[i];
          const double    exact =
            component[i] == 2 ? -p * x[2] / E : nu * p * x[component[i]] / E;
          worst   = std::max(worst, std::abs(u[i] - exact));
          largest = std::max(largest, std::abs(exact));
        }
      const std::string d = " (degree " + std::to_string(degree) + ")";
      check("tied blocks: uniaxial stress at every node" + d,
            worst,
            0.,
            1e-10,
            largest);
      test_tools::verbose()
        << "degree " << degree << ": largest error " << worst / largest
        << " of " << largest << " m" << std::endl;
    }

  {
    ParameterHandler  h;
    const std::string e =
      error_of([&]() { scene::make_scene(read("", 1, h)); });
    test_tools::check_message("without the tie: body 'u' floats, named",
                              e,
                              {"nothing holds body 'u'"});
  }
  {
    ParameterHandler                h;
    const parameters::AllParameters prm = read(tie, 1, h);
    physics::StructuralModel        model(prm, MPI_COMM_WORLD);
    const std::string e = error_of([&]() { model.setup_and_assemble(quiet); });
    test_tools::check_message("a model built without the tie hook is refused",
                              e,
                              {"has ties"});
  }
  return test_tools::finish();
}
