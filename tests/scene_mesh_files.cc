// Meshes with named sets from files (io/mesh_file.h).
// 1. Verification B1, the contact patch test, on two blocks read from
//    Gmsh files (written by Gmsh's own API, formats 2.2 and 4.1, one of them
//    in mm) and from an Abaqus/CalculiX file (written here: C3D8 on the
//    slave side, C3D20R on the master side, continuation lines, GENERATE,
//    surfaces on element sets), their bodies and faces found by name: the
//    dual mortar multipliers must equal the pressure to 1e-8.
// 2. The TriboBrake generator's mesh and sets written as .inp (in mm) and
//    read back: the same cells, vertices (1e-12 m), sets and ids.
// 3. Bad meshes: one clear error each (element type, inverted element,
//    missing node, missing set, tetrahedra, unknown format, parts).

#include <deal.II/grid/grid_tools.h>

#include <squeal/contact/contact_solver.h>
#include <squeal/contact/mortar.h>
#include <squeal/io/mesh_file.h>
#include <squeal/scene/tribobrake_mesh.h>

#include <gmsh.h>

#include "check.h"
#include "contact_two_blocks.h"

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace dealii;
using namespace squeal;
using test_tools::check;
using test_tools::error_of;

namespace
{
  const double p = 0.625; // Pa (scaled units)

  // Two boxes [0,1]^2 x [0,1] (upper, n_upper^2 x 2 cells) and
  // [0,1]^2 x [-1,0] (lower), meshed by Gmsh as transfinite hexahedra, not
  // fragmented (the blocks share no node), lengths times @p scale.
  void
  write_gmsh_blocks(const std::string &file,
                    const double       version,
                    const double       scale,
                    const unsigned int n_upper,
                    const unsigned int n_lower,
                    const bool         recombine = true)
  {
    gmsh::initialize();
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::model::add("blocks");
    const int up = gmsh::model::occ::addBox(0, 0, 0, scale, scale, scale);
    const int lo = gmsh::model::occ::addBox(0, 0, -scale, scale, scale, scale);
    gmsh::model::occ::synchronize();
    std::map<std::string, std::vector<int>> groups;
    for (const auto &[volume, n] :
         {std::pair{up, n_upper}, std::pair{lo, n_lower}})
      {
        gmsh::vectorpair surfaces;
        gmsh::model::getBoundary({{3, volume}}, surfaces, false, false, false);
        for (const auto &[dim, s] : surfaces)
          {
            gmsh::vectorpair curves;
            gmsh::model::getBoundary({{2, s}}, curves, false, false, false);
            for (const auto &[cdim, c] : curves)
              {
                double x0, y0, z0, x1, y1, z1;
                gmsh::model::getBoundingBox(
                  1, std::abs(c), x0, y0, z0, x1, y1, z1);
                gmsh::model::mesh::setTransfiniteCurve(
                  std::abs(c), z1 - z0 > 1e-3 * scale ? 3 : n + 1);
              }
            gmsh::model::mesh::setTransfiniteSurface(s);
            if (recombine)
              gmsh::model::mesh::setRecombine(2, s);
            double x0, y0, z0, x1, y1, z1;
            gmsh::model::getBoundingBox(2, s, x0, y0, z0, x1, y1, z1);
            const double tol = 1e-3 * scale;
            if (std::abs(z1 - z0) < tol)
              {
                if (volume == up)
                  groups[std::abs(z0) < tol ? "contact slave" : "top"]
                    .push_back(s);
                else
                  groups[std::abs(z0) < tol ? "contact master" : "bottom"]
                    .push_back(s);
              }
            else if (std::abs(x1 - x0) < tol && std::abs(x0) < tol)
              groups["x0"].push_back(s);
            else if (std::abs(y1 - y0) < tol && std::abs(y0) < tol)
              groups["y0"].push_back(s);
          }
        gmsh::model::mesh::setTransfiniteVolume(volume);
      }
    for (const auto &[name, tags] : groups)
      gmsh::model::setPhysicalName(2,
                                   gmsh::model::addPhysicalGroup(2, tags),
                                   name);
    gmsh::model::setPhysicalName(3,
                                 gmsh::model::addPhysicalGroup(3, {up}),
                                 "upper block");
    gmsh::model::setPhysicalName(3,
                                 gmsh::model::addPhysicalGroup(3, {lo}),
                                 "lower block");
    gmsh::model::mesh::generate(3);
    gmsh::option::setNumber("Mesh.MshFileVersion", version);
    gmsh::write(file);
    gmsh::finalize();
  }

  // The same two blocks as an Abaqus input file: the upper block of C3D8
  // (elements 1 ...), the lower of C3D20R (mid-side nodes of their own),
  // element sets by GENERATE and by list, surfaces on sets and elements.
  void
  write_inp_blocks(const std::string &file,
                   const unsigned int n_upper,
                   const unsigned int n_lower)
  {
    std::ofstream out(file);
    out << std::setprecision(17) << "** two blocks for the patch test\n*NODE\n";
    long                                     node = 0, element = 0;
    std::vector<std::string>                 element_lines[2];
    std::map<std::string, std::vector<long>> surface_elements;
    for (unsigned int b = 0; b < 2; ++b)
      {
        const unsigned int n     = b == 0 ? n_upper : n_lower;
        const double       z0    = b == 0 ? 0. : -1.;
        const long         first = node + 1;
        const auto id = [&](unsigned int i, unsigned int j, unsigned int k) {
          return first + (k * (n + 1) + j) * (n + 1) + i;
        };
        for (unsigned int k = 0; k <= 2; ++k)
          for (unsigned int j = 0; j <= n; ++j)
            for (unsigned int i = 0; i <= n; ++i)
              out << ++node << ", " << double(i) / n << ", " << double(j) / n
                  << ", " << z0 + 0.5 * k << "\n";
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int j = 0; j < n; ++j)
            for (unsigned int i = 0; i < n; ++i)
              {
                const std::array<long, 8> c{{id(i, j, k),
                                             id(i + 1, j, k),
                                             id(i + 1, j + 1, k),
                                             id(i, j + 1, k),
                                             id(i, j, k + 1),
                                             id(i + 1, j, k + 1),
                                             id(i + 1, j + 1, k + 1),
                                             id(i, j + 1, k + 1)}};
                std::ostringstream        line;
                line << ++element;
                for (const long v : c)
                  line << ", " << v;
                if (b == 1) // 12 mid-side nodes, on a continuation line
                  {
                    line << ",\n";
                    for (unsigned int m = 0; m < 12; ++m)
                      line << (m ? ", " : "") << 100000 + 12 * element + m;
                  }
                element_lines[b].push_back(line.str());
                if (i == 0)
                  surface_elements[b == 0 ? "X0_UPPER" : "X0_LOWER"].push_back(
                    element);
                if (j == 0)
                  surface_elements[b == 0 ? "Y0_UPPER" : "Y0_LOWER"].push_back(
                    element);
              }
      }
    // the mid-side nodes (their positions do not matter: corners make cells)
    for (long e = 1; e <= element; ++e)
      for (unsigned int m = 0; m < 12; ++m)
        out << 100000 + 12 * e + m << ", 0.5, 0.5, 0.0\n";
    out << "*ELEMENT, TYPE=C3D8, ELSET=Upper\n";
    for (const auto &l : element_lines[0])
      out << l << "\n";
    out << "*Element, type=C3D20R, elset=LOWER\n";
    for (const auto &l : element_lines[1])
      out << l << "\n";
    const long nu = 2 * n_upper * n_upper, nl = 2 * n_lower * n_lower;
    out << "*ELSET, ELSET=UPPER_BOTTOM, GENERATE\n1, " << n_upper * n_upper
        << ", 1\n*ELSET, ELSET=UPPER_TOP, GENERATE\n"
        << n_upper * n_upper + 1 << ", " << nu << "\n"
        << "*ELSET, ELSET=LOWER_BOTTOM, GENERATE\n"
        << nu + 1 << ", " << nu + n_lower * n_lower
        << ", 1\n*ELSET, ELSET=LOWER_TOP, GENERATE\n"
        << nu + n_lower * n_lower + 1 << ", " << nu + nl << ", 1\n"
        << "*ELSET, ELSET=BOTH\nUPPER, LOWER\n"
        << "*SURFACE, NAME=SLAVE, TYPE=ELEMENT\nUPPER_BOTTOM, S1\n"
        << "*SURFACE, NAME=MASTER\nlower_top, S2\n"
        << "*SURFACE, NAME=TOP\nUPPER_TOP, S2\n"
        << "*SURFACE, NAME=BOTTOM\nLOWER_BOTTOM, S1\n*SURFACE, NAME=X0\n";
    for (const auto *s : {"X0_UPPER", "X0_LOWER"})
      for (const long e : surface_elements[s])
        out << e << ", S6\n";
    out << "*SURFACE, NAME=Y0\n";
    for (const auto *s : {"Y0_UPPER", "Y0_LOWER"})
      for (const long e : surface_elements[s])
        out << e << ", S3\n";
    out << "*NSET, NSET=CORNER\n1\n*MATERIAL, NAME=IGNORED\n*ELASTIC\n1, 0.3\n";
  }

  // The patch test on a mesh read from @p file with the given set names.
  void
  patch_test(const std::string                &label,
             const std::string                &file,
             const double                      unit,
             const unsigned int                degree,
             const std::array<std::string, 8> &names)
  {
    io::NamedSets sets;
    TwoBlocks     b(degree,
                200.,
                0.3,
                100.,
                0.25,
                Tensor<1, 3>({0., 0., -p}),
                [&](Triangulation<3> &tria) {
                  sets = io::read_mesh_file(file, unit, tria);
                  sets.assign_material(names[0], 0, tria);
                  sets.assign_material(names[1], 1, tria);
                  const types::boundary_id ids[6] = {1, 2, 3, 4, 10, 11};
                  for (unsigned int k = 0; k < 6; ++k)
                    sets.assign_boundary(names[2 + k], ids[k], tria);
                });
    check(label + ": block volumes 1 m^3 each",
          GridTools::volume(b.tria),
          2.,
          1e-12);
    const contact::MortarOperators op =
      contact::build_mortar_operators(b.dofs, b.mapping, 10, 11, 0.1);
    check(label + ": covered area 1 m^2", op.covered_area, 1., 1e-12);
    const contact::ContactSolution s = contact::solve_static_contact(
      b.K, b.f, b.constraints, op, contact::ContactSettings());
    double       worst    = 0.;
    unsigned int n_active = 0;
    for (unsigned int j = 0; j < op.n_slave(); ++j)
      {
        worst = std::max({worst,
                          std::abs(s.pressure[j] - p) / p,
                          std::abs(s.nodal_pressure[j] - p) / p});
        n_active += s.status[j] != 0;
      }
    test_tools::verbose() << label << ": " << op.n_slave()
                          << " slave nodes, largest relative error " << worst
                          << std::endl;
    check(label + ": every slave node in contact", n_active, op.n_slave(), 0.);
    check(label + ": slave nodes exist", op.n_slave() > 0, 1., 0.);
    check(label + ": multipliers and nodal pressures = p to 1e-8",
          worst,
          0.,
          1e-8,
          1.);
    check(label + ": normal force = p x area", s.normal_force, p, 1e-10);
  }

  void
  check_error(const std::string &name,
              const std::string &message,
              const std::string &expected)
  {
    test_tools::verbose() << name << ": " << message << std::endl;
    check(name + " gives its error",
          message.find(expected) != std::string::npos,
          1.,
          0.);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::filesystem::path      dir = "scene_mesh_files_data";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);

  // 1. B1 from files
  const std::array<std::string, 8> gmsh_names{{"upper block",
                                               "lower block",
                                               "top",
                                               "bottom",
                                               "x0",
                                               "y0",
                                               "contact slave",
                                               "contact master"}};
  write_gmsh_blocks(dir / "blocks22.msh", 2.2, 1., 5, 3);
  write_gmsh_blocks(dir / "blocks41_mm.msh", 4.1, 1000., 2, 3);
  patch_test("Gmsh 2.2, degree 1, slave 5x5 on master 3x3",
             dir / "blocks22.msh",
             1.,
             1,
             gmsh_names);
  patch_test("Gmsh 4.1 in mm, degree 2, slave 2x2 on master 3x3",
             dir / "blocks41_mm.msh",
             1e-3,
             2,
             gmsh_names);
  {
    Triangulation<3> tria;
    const auto sets = io::read_mesh_file(dir / "blocks41_mm.msh", 1e-3, tria);
    check("Gmsh 4.1: 8 + 18 cells", tria.n_active_cells(), 26., 0.);
    check("Gmsh 4.1: slave set has 4 faces",
          sets.faces("contact slave").size(),
          4.,
          0.);
    check("Gmsh 4.1: upper block has 8 cells",
          sets.cells("upper block").size(),
          8.,
          0.);
  }

  write_inp_blocks(dir / "blocks.inp", 4, 3);
  const std::array<std::string, 8> inp_names{
    {"Upper", "LOWER", "TOP", "BOTTOM", "X0", "Y0", "SLAVE", "MASTER"}};
  patch_test("Abaqus C3D8 on C3D20R, degree 1, slave 4x4 on master 3x3",
             dir / "blocks.inp",
             1.,
             1,
             inp_names);
  patch_test("Abaqus C3D8 on C3D20R, degree 2, slave 4x4 on master 3x3",
             dir / "blocks.inp",
             1.,
             2,
             inp_names);
  {
    Triangulation<3> tria;
    const auto       sets = io::read_mesh_file(dir / "blocks.inp", 1., tria);
    check("Abaqus: the set of sets holds both blocks",
          sets.cells("BOTH").size(),
          50.,
          0.);
    check("Abaqus: x0 surface of both blocks",
          sets.faces("X0").size(),
          2 * 4 + 2 * 3,
          0.);
    check("Abaqus: node set at the origin",
          sets.nodes("CORNER").at(0).norm(),
          0.,
          0.,
          1.);
  }

  // 2. TriboBrake -> .inp (mm) -> back
  {
    parameters::Geometry g;
    parameters::Mesh     m;
    m.disc_cells_circumference = 24;
    m.disc_cells_radial        = 3;
    m.disc_cells_thickness     = 1;
    m.pad_cells_side           = 2;
    m.pad_cells_thickness      = 1;
    m.support_cells_length     = 4;
    Triangulation<3> original;
    scene::tribobrake::make_tribobrake_mesh(g, m, true, original);
    auto sets                    = scene::tribobrake::tribobrake_sets(original);
    sets.node_sets["pad corner"] = {
      Point<3>(g.pad_radius - g.pad_size / 2, -g.pad_size / 2, 0.)};
    io::write_abaqus(original, sets, (dir / "tribobrake.inp").string(), 1e-3);
    Triangulation<3> read;
    auto back = io::read_mesh_file(dir / "tribobrake.inp", 1e-3, read);
    check("TriboBrake .inp: same cell count",
          read.n_active_cells(),
          original.n_active_cells(),
          0.);
    double       worst         = 0.;
    unsigned int id_mismatches = 0, n_faces = 0;
    const std::map<std::string, types::material_id> bodies{{"disc", 0},
                                                           {"pad", 1},
                                                           {"support", 2}};
    const std::map<std::string, types::boundary_id> faces{{"disc hub", 1},
                                                          {"pad face", 2},
                                                          {"disc face", 3},
                                                          {"support top", 4}};
    for (const auto &[name, id] : bodies)
      back.assign_material(io::abaqus_name(name), id, read);
    for (const auto &[name, id] : faces)
      back.assign_boundary(io::abaqus_name(name), id, read);
    auto a = original.begin_active();
    for (const auto &cell : read.active_cell_iterators())
      {
        for (unsigned int v = 0; v < 8; ++v)
          {
            double nearest = 1.;
            for (unsigned int w = 0; w < 8; ++w)
              nearest =
                std::min(nearest, cell->vertex(v).distance(a->vertex(w)));
            worst = std::max(worst, nearest);
          }
        id_mismatches += cell->material_id() != a->material_id();
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              ++n_faces;
              bool matched = false;
              for (const unsigned int h : a->face_indices())
                matched =
                  matched ||
                  (a->face(h)->center().distance(cell->face(f)->center()) <
                     1e-12 &&
                   a->face(h)->boundary_id() == cell->face(f)->boundary_id());
              id_mismatches += !matched;
            }
        ++a;
      }
    check("TriboBrake .inp: vertices within 1e-12 m", worst, 0., 1e-12, 1.);
    check("TriboBrake .inp: every material and boundary id as generated",
          id_mismatches,
          0.,
          0.);
    check("TriboBrake .inp: boundary faces compared", n_faces > 100, 1., 0.);
    check("TriboBrake .inp: pad face set size",
          back.faces("PAD_FACE").size(),
          sets.faces("pad face").size(),
          0.);
    check(
      "TriboBrake .inp: node set point",
      back.nodes("PAD_CORNER").at(0).distance(sets.node_sets["pad corner"][0]),
      0.,
      1e-12,
      1.);
  }

  // 3. Bad meshes
  const auto inp = [&](const std::string &name, const std::string &text) {
    const std::string file = (dir / name).string();
    std::ofstream(file) << text;
    return file;
  };
  const std::string cube_nodes =
    "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n"
    "5, 0, 0, 1\n6, 1, 0, 1\n7, 1, 1, 1\n8, 0, 1, 1\n";
  {
    Triangulation<3> tria;
    const auto       sets =
      io::read_mesh_file(inp("good.inp",
                             cube_nodes + "*ELEMENT, TYPE=C3D8, ELSET=BLOCK\n"
                                          "1, 1, 2, 3, 4, 5, 6, 7, 8\n"),
                         1.,
                         tria);
    check("a unit cube from .inp has volume 1",
          GridTools::volume(tria),
          1.,
          1e-14);
    check_error("a missing set",
                error_of([&] { sets.faces("CONTACT"); }),
                "has no face set 'CONTACT' (its face sets: none)");
    check_error("a missing body",
                error_of([&] { sets.cells("PAD"); }),
                "has no cell set 'PAD' (its cell sets: 'BLOCK')");
  }
  Triangulation<3> tria;
  check_error("tetrahedra in .inp",
              error_of([&] {
                io::read_mesh_file(inp("tet.inp",
                                       cube_nodes +
                                         "*ELEMENT, TYPE=C3D10\n"
                                         "1, 1, 2, 3, 5, 1, 2, 3, 4, 5, 6\n"),
                                   1.,
                                   tria);
              }),
              "line 10: element type 'C3D10' cannot be used: squeal needs "
              "hexahedral solid elements");
  check_error("an inverted element",
              error_of([&] {
                io::read_mesh_file(inp("inverted.inp",
                                       cube_nodes +
                                         "*ELEMENT, TYPE=C3D8\n"
                                         "7, 5, 6, 7, 8, 1, 2, 3, 4\n"),
                                   1.,
                                   tria);
              }),
              "line 11: element 7 is inverted");
  check_error("a degenerate element",
              error_of([&] {
                io::read_mesh_file(inp("flat.inp",
                                       cube_nodes +
                                         "*ELEMENT, TYPE=C3D8\n"
                                         "3, 1, 2, 3, 4, 1, 2, 3, 4\n"),
                                   1.,
                                   tria);
              }),
              "element 3 is degenerate");
  check_error("a missing node",
              error_of([&] {
                io::read_mesh_file(inp("node.inp",
                                       cube_nodes +
                                         "*ELEMENT, TYPE=C3D8\n"
                                         "1, 1, 2, 3, 4, 5, 6, 7, 9\n"),
                                   1.,
                                   tria);
              }),
              "element 1 refers to node 9, which no *NODE defines");
  check_error("a surface on an unknown set",
              error_of([&] {
                io::read_mesh_file(inp("surface.inp",
                                       cube_nodes +
                                         "*ELEMENT, TYPE=C3D8\n"
                                         "1, 1, 2, 3, 4, 5, 6, 7, 8\n"
                                         "*SURFACE, NAME=S\nPADS, S1\n"),
                                   1.,
                                   tria);
              }),
              "line 13: surface 'S' refers to 'PADS', neither an element nor "
              "an element set");
  check_error("a part",
              error_of([&] {
                io::read_mesh_file(inp("part.inp", "*PART, NAME=DISC\n"),
                                   1.,
                                   tria);
              }),
              "line 1: *PART is not supported: squeal reads flat input files");
  write_gmsh_blocks(dir / "tets.msh", 4.1, 1., 2, 2, false);
  check_error("tetrahedra in .msh",
              error_of([&] { io::read_mesh_file(dir / "tets.msh", 1., tria); }),
              "; squeal needs hexahedra (in Gmsh: transfinite volumes");
  check_error("an unknown format",
              error_of([&] {
                io::read_mesh_file(inp("brake.stl", "solid"), 1., tria);
              }),
              "unknown format '.stl'; squeal reads Gmsh (.msh), "
              "Abaqus/CalculiX (.inp) and VTK (.vtu) meshes");
  check_error("a missing file",
              error_of(
                [&] { io::read_mesh_file("no_such_mesh.msh", 1., tria); }),
              "mesh file 'no_such_mesh.msh': no such file");
  check_error("a zero length unit",
              error_of(
                [&] { io::read_mesh_file(dir / "blocks.inp", 0., tria); }),
              "the length unit must be positive");
  return test_tools::finish();
}
