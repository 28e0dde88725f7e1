// Meshes from VTK unstructured grids (.vtu). The test writes its own grids
// as ASCII VTK XML (not through VTK, so that the reader meets a file
// another program wrote):
// 1. a bar of 6 x 2 x 2 hexahedra with quadrilaterals on its ends and one
//    side, cell data arrays BAR (0/1: a cell set), END (1 and 2 on the two
//    end quads: face sets END=1 and END=2) and point data TIP (a node set):
//    the sets have the expected members;
// 2. the same bar as an Abaqus .inp (io::write_abaqus) and as a .vtu, in mm
//    (Length unit 1e-3), clamped at one end: the cantilever's undamped
//    frequencies are the same from both files (1e-10);
// 3. a grid with a tetrahedron, and a file that is no VTK grid, get one
//    error naming the file and the problem.

#include <deal.II/grid/grid_generator.h>

#include <squeal/io/mesh_file.h>

#include "test_tools.h"

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace squeal;
using test_tools::check;
using test_tools::error_of;

namespace
{
  const double L = 60., b = 10.; // mm

  // the bar in mm, colorized: x faces 0, 1; y faces 2, 3
  void
  make_bar(Triangulation<3> &tria)
  {
    GridGenerator::subdivided_hyper_rectangle(
      tria, {6, 2, 2}, Point<3>(), Point<3>(L, b, b), true);
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_material_id(0);
  }

  // ASCII VTK XML: hexahedra in VTK (= Abaqus) node order, quadrilaterals
  // for the faces of the x ends (END = 1, 2) and y = 0 (SIDE), data arrays
  // as described above; with @p tetra a tetrahedron is added.
  void
  write_vtu(const Triangulation<3> &tria,
            const std::string      &file,
            const bool              tetra = false)
  {
    static const unsigned int vtk_of_dealii[8] = {0, 1, 3, 2, 4, 5, 7, 6};
    std::vector<std::vector<unsigned int>> cells;
    std::vector<int>                       types, bar, end, side;
    for (const auto &cell : tria.active_cell_iterators())
      {
        std::vector<unsigned int> v(8);
        for (unsigned int k = 0; k < 8; ++k)
          v[vtk_of_dealii[k]] = cell->vertex_index(k);
        cells.push_back(v);
        types.push_back(12);
        bar.push_back(1);
        end.push_back(0);
        side.push_back(0);
      }
    for (const auto &cell : tria.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() != 4 &&
            cell->face(f)->boundary_id() != 5 &&
            cell->face(f)->boundary_id() != 3)
          {
            // deal.II face vertices 0, 1, 3, 2 go around the quad
            const auto                face = cell->face(f);
            std::vector<unsigned int> v    = {face->vertex_index(0),
                                              face->vertex_index(1),
                                              face->vertex_index(3),
                                              face->vertex_index(2)};
            cells.push_back(v);
            types.push_back(9);
            bar.push_back(0);
            end.push_back(face->boundary_id() < 2 ? face->boundary_id() + 1 :
                                                    0);
            side.push_back(face->boundary_id() == 2 ? 1 : 0);
          }
    const unsigned int n_points = tria.n_vertices();
    if (tetra)
      {
        cells.push_back({0, 1, 2, 3});
        types.push_back(10);
        bar.push_back(0);
        end.push_back(0);
        side.push_back(0);
      }
    std::ofstream out(file);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
           "version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n"
        << "<Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\""
        << cells.size() << "\">\n<Points>\n<DataArray type=\"Float64\" "
        << "NumberOfComponents=\"3\" format=\"ascii\">\n"
        << std::setprecision(17);
    for (const Point<3> &x : tria.get_vertices())
      out << x[0] << ' ' << x[1] << ' ' << x[2] << '\n';
    out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" "
           "Name=\"connectivity\" format=\"ascii\">\n";
    unsigned int offset = 0;
    std::string  offsets;
    for (const auto &c : cells)
      {
        for (const unsigned int v : c)
          out << v << ' ';
        out << '\n';
        offset += c.size();
        offsets += std::to_string(offset) + ' ';
      }
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
           "format=\"ascii\">\n"
        << offsets
        << "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
           "format=\"ascii\">\n";
    for (const int t : types)
      out << t << ' ';
    out << "\n</DataArray>\n</Cells>\n<CellData>\n";
    for (const auto &[name, values] :
         {std::pair<std::string, const std::vector<int> *>{"BAR", &bar},
          {"END", &end},
          {"SIDE", &side}})
      {
        out << "<DataArray type=\"Int32\" Name=\"" << name
            << "\" format=\"ascii\">\n";
        for (const int v : *values)
          out << v << ' ';
        out << "\n</DataArray>\n";
      }
    out << "</CellData>\n<PointData>\n<DataArray type=\"Int32\" Name=\"TIP\" "
           "format=\"ascii\">\n";
    for (const Point<3> &x : tria.get_vertices())
      out << (std::abs(x[0] - L) < 1e-9 ? 1 : 0) << ' ';
    out << "\n</DataArray>\n</PointData>\n</Piece>\n</UnstructuredGrid>\n"
           "</VTKFile>\n";
  }

  std::vector<double>
  cantilever(const std::string &mesh, const std::string &end)
  {
    std::ofstream("bar.prm")
      << "subsection Scene\n  set Type = mesh file\n"
         "  subsection Mesh file\n    set File = "
      << mesh
      << "\n    set Length unit = 1e-3\n"
         "    set Bodies = bar: set=BAR, E=200e9, nu=0.3, rho=7800\n"
         "    set Holds = clamp: set="
      << end
      << "\n  end\nend\n"
         "subsection Mesh\n  set Finite element degree = 2\nend\n";
    ParameterHandler          handler;
    parameters::AllParameters prm;
    prm.read(handler, "bar.prm");
    return test_tools::undamped_frequencies(prm, 100., 40000.);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Triangulation<3>                 tria;
  make_bar(tria);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      write_vtu(tria, "bar.vtu");
      write_vtu(tria, "tetra.vtu", true);
      io::NamedSets sets;
      sets.source = "the test's bar";
      sets.collect_from_ids(tria, {{0, "bar"}}, {{0, "end1"}});
      io::write_abaqus(tria, sets, "bar.inp");
      std::ofstream("garbage.vtu") << "this is no VTK file\n";
    }
  MPI_Barrier(MPI_COMM_WORLD);

  {
    Triangulation<3>    read;
    const io::NamedSets s = io::read_mesh_file("bar.vtu", 1e-3, read);
    check("cell set BAR: every hexahedron",
          s.cell_sets.count("BAR") ? s.cell_sets.at("BAR").size() : 0,
          24,
          0.);
    check("face set END=1: the 4 quads of x = 0",
          s.face_sets.count("END=1") ? s.face_sets.at("END=1").size() : 0,
          4,
          0.);
    check("face set END=2: the 4 quads of x = L",
          s.face_sets.count("END=2") ? s.face_sets.at("END=2").size() : 0,
          4,
          0.);
    check("face set SIDE: the 12 quads of y = 0",
          s.face_sets.count("SIDE") ? s.face_sets.at("SIDE").size() : 0,
          12,
          0.);
    check("node set TIP: the 9 nodes of x = L",
          s.node_sets.count("TIP") ? s.node_sets.at("TIP").size() : 0,
          9,
          0.);
    check("no other sets", s.cell_sets.size() + s.face_sets.size(), 4, 0.);
    double x_max = 0.;
    for (const Point<3> &x : read.get_vertices())
      x_max = std::max(x_max, x[0]);
    check("length unit: the bar ends at 0.06 m", x_max, 0.06, 1e-14);
  }

  const auto from_inp = cantilever("bar.inp", "END1");
  const auto from_vtu = cantilever("bar.vtu", "END=1");
  check("cantilever: as many modes below 40 kHz from .vtu as from .inp",
        from_vtu.size(),
        from_inp.size(),
        0.);
  check("cantilever: at least 6 modes",
        std::min<double>(from_inp.size(), 6),
        6,
        0.);
  double worst = from_inp.empty() ? 1. : 0.;
  for (unsigned int i = 0; i < std::min(from_inp.size(), from_vtu.size()); ++i)
    worst = std::max(worst, std::abs(from_vtu[i] - from_inp[i]) / from_inp[i]);
  check("cantilever: the same frequencies from .vtu and .inp (1e-10)",
        worst,
        0.,
        1e-10,
        1.);

  for (const auto &[file, expect] :
       {std::pair<std::string, std::string>{"tetra.vtu",
                                            "is a tetrahedron, which squeal "
                                            "cannot use"},
        {"garbage.vtu", "not a VTK XML unstructured grid"}})
    {
      Triangulation<3>  t;
      const std::string e =
        error_of([&]() { io::read_mesh_file(file, 1., t); });
      test_tools::check_message(file +
                                  ": one error naming the file and the problem",
                                e,
                                {"'" + file + "'", expect});
    }
  return test_tools::finish();
}
