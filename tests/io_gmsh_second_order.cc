// Gmsh meshes of second-order hexahedra (read through Gmsh's API). The test
// meshes a quarter annulus r = 50-120 mm, 10 mm thick, with Gmsh (6 x 3 x 1
// transfinite hexahedra, arcs of 15 degrees), once of order 2 (20-node
// hexahedra, mid-edge nodes on the circles; 27-node with
// Mesh.SecondOrderIncomplete = 0) and once of order 1, with a volume group
// "ring" and a surface group "base".
// 1. The sets: every cell in "ring", the 18 quads of z = 0 in "base".
// 2. The curvature: the volume under MappingQ(3) matches pi/4 (R^2 - r^2) h
//    to 5e-5 from the second-order files (their mid-edge nodes curve the
//    cells: a quadratic arc of 15 degrees, measured 9.8e-6), while the
//    first-order file's polygon misses it by more than 1e-3 (1.1e-2).

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>

#include <squeal/io/mesh_file.h>

#include <gmsh.h>

#include "test_tools.h"

#include <cmath>
#include <string>

using namespace dealii;
using namespace squeal;
using test_tools::check;

namespace
{
  const double r1 = 0.05, r2 = 0.12, h = 0.01;

  void
  write_ring(const std::string &file, const int order, const bool complete)
  {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::model::add("ring");
    namespace geo = gmsh::model::geo;
    const int c   = geo::addPoint(0, 0, 0);
    const int p1 = geo::addPoint(r1, 0, 0), p2 = geo::addPoint(r2, 0, 0);
    const int p3 = geo::addPoint(0, r2, 0), p4 = geo::addPoint(0, r1, 0);
    const int l1 = geo::addLine(p1, p2), a2 = geo::addCircleArc(p2, c, p3);
    const int l3 = geo::addLine(p3, p4), a4 = geo::addCircleArc(p4, c, p1);
    const int loop = geo::addCurveLoop({l1, a2, l3, a4});
    const int s    = geo::addPlaneSurface({loop});
    for (const int l : {l1, l3})
      geo::mesh::setTransfiniteCurve(l, 4);
    for (const int a : {a2, a4})
      geo::mesh::setTransfiniteCurve(a, 7);
    geo::mesh::setTransfiniteSurface(s);
    geo::mesh::setRecombine(2, s);
    gmsh::vectorpair out;
    geo::extrude({{2, s}}, 0, 0, h, out, {1}, {}, true);
    geo::synchronize();
    gmsh::model::addPhysicalGroup(3, {out[1].second}, 1);
    gmsh::model::setPhysicalName(3, 1, "ring");
    gmsh::model::addPhysicalGroup(2, {s}, 2);
    gmsh::model::setPhysicalName(2, 2, "base");
    gmsh::option::setNumber("Mesh.SecondOrderIncomplete", complete ? 0 : 1);
    gmsh::model::mesh::generate(3);
    gmsh::model::mesh::setOrder(order);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::write(file);
    gmsh::finalize();
  }

  double
  volume(const Triangulation<3> &tria)
  {
    const MappingQ<3> mapping(3);
    const FE_Q<3>     fe(1);
    FEValues<3>       fv(mapping, fe, QGauss<3>(5), update_JxW_values);
    double            v = 0.;
    for (const auto &cell : tria.active_cell_iterators())
      {
        fv.reinit(cell);
        for (unsigned int q = 0; q < fv.n_quadrature_points; ++q)
          v += fv.JxW(q);
      }
    return v;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  write_ring("ring20.msh", 2, false);
  write_ring("ring27.msh", 2, true);
  write_ring("ring8.msh", 1, false);
  const double exact = numbers::PI / 4 * (r2 * r2 - r1 * r1) * h;

  for (const std::string name : {"ring20", "ring27"})
    {
      Triangulation<3>    tria;
      const io::NamedSets s = io::read_mesh_file(name + ".msh", 1., tria);
      check(name + ": cell set ring holds every cell",
            s.cell_sets.count("ring") ? s.cell_sets.at("ring").size() : 0,
            18,
            0.);
      check(name + ": face set base holds the 18 quads of z = 0",
            s.face_sets.count("base") ? s.face_sets.at("base").size() : 0,
            18,
            0.);
      const double v = volume(tria);
      check(name + ": the mid-edge nodes curve the cells: volume within "
                   "5e-5",
            v,
            exact,
            5e-5);
      test_tools::verbose()
        << name << ": volume error " << v / exact - 1 << std::endl;
    }
  Triangulation<3> flat;
  io::read_mesh_file("ring8.msh", 1., flat);
  const double v = volume(flat);
  check("first order: the polygon misses the volume by more than 1e-3",
        std::abs(v / exact - 1) > 1e-3 ? 0. : 1.,
        0.,
        0.,
        1.);
  test_tools::verbose() << "ring8: volume error " << v / exact - 1 << std::endl;
  return test_tools::finish();
}
