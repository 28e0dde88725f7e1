// Mesh files with named sets. Gmsh files are read by deal.II's GridIn (its
// physical tags become ids); only the names of the physical groups, which
// GridIn does not keep, are read here. Abaqus/CalculiX files are read here:
// GridIn::read_abaqus derives ids from the digits in set names and keeps no
// names, no overlapping sets and no element-based surfaces, which is what a
// brake model exported from a pre-processor is made of. Faces of surfaces
// are found by their corner vertices after the triangulation is built,
// because deal.II may renumber a cell's vertices to orient it consistently.

#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>

#include <squeal/io/mesh_file.h>
#include <squeal/io/quadratic_hex_manifold.h>

#include "abaqus_numbering.h"
#include "element_mesh.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace io
  {
    using namespace dealii;
    using internal::abaqus_face;
    using internal::abaqus_face_of;
    using internal::abaqus_node;

    namespace
    {
      std::string
      upper(std::string s)
      {
        for (char &c : s)
          c = std::toupper(static_cast<unsigned char>(c));
        return s;
      }

      std::string
      trim(const std::string &s)
      {
        const auto b = s.find_first_not_of(" \t\r");
        if (b == std::string::npos)
          return "";
        return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
      }

      std::vector<std::string>
      split_commas(const std::string &s)
      {
        std::vector<std::string> out;
        std::stringstream        in(s);
        std::string              item;
        while (std::getline(in, item, ','))
          out.push_back(trim(item));
        if (!s.empty() && s.back() == ',')
          out.push_back("");
        return out;
      }

      /// The smallest Jacobian determinant of the trilinear map of a
      /// hexahedron at its corners (deal.II vertex order) over the cube of
      /// its longest edge: <= 0 for an inverted or degenerate cell.
      double
      corner_jacobian_ratio(const std::array<Point<3>, 8> &v)
      {
        double longest = 0.;
        for (unsigned int d = 0; d < 3; ++d)
          for (unsigned int i = 0; i < 8; ++i)
            if (!(i & (1u << d)))
              longest = std::max(longest, v[i].distance(v[i | (1u << d)]));
        double smallest = std::numeric_limits<double>::max();
        for (unsigned int corner = 0; corner < 8; ++corner)
          {
            Tensor<1, 3> edge[3];
            for (unsigned int d = 0; d < 3; ++d)
              {
                const unsigned int low = corner & ~(1u << d);
                edge[d]                = v[low | (1u << d)] - v[low];
              }
            smallest =
              std::min(smallest, edge[0] * cross_product_3d(edge[1], edge[2]));
          }
        return longest > 0. ? smallest / std::pow(longest, 3) : 0.;
      }

      /// Below this ratio a cell counts as degenerate (a corner angle of
      /// about 1e-6 rad).
      constexpr double degenerate_ratio = 1e-6;

      std::string
      degenerate_message(const std::string &where, const double ratio)
      {
        std::ostringstream m;
        m << where << " is " << (ratio < 0 ? "inverted" : "degenerate")
          << " (smallest corner Jacobian determinant " << ratio
          << " of its longest edge cubed); squeal needs hexahedra with "
             "positive volume, their nodes numbered as Abaqus' C3D8 "
             "(1-4 counter-clockwise seen from 5-8)";
        return m.str();
      }

      // ----------------------------------------------------------------
      // Gmsh
      // ----------------------------------------------------------------

      /// The names of the physical groups, (dimension, tag) -> name.
      std::map<std::pair<int, int>, std::string>
      physical_names(const std::string &text, const std::string &file)
      {
        std::map<std::pair<int, int>, std::string> names;
        const auto start = text.find("$PhysicalNames");
        if (start == std::string::npos)
          return names;
        std::istringstream in(text.substr(start));
        std::string        line;
        std::getline(in, line);
        unsigned int n = 0;
        if (!(in >> n))
          throw std::runtime_error("mesh file '" + file +
                                   "': malformed $PhysicalNames section");
        std::getline(in, line);
        for (unsigned int k = 0; k < n; ++k)
          {
            std::getline(in, line);
            std::istringstream l(line);
            int                dim = 0, tag = 0;
            if (!(l >> dim >> tag))
              throw std::runtime_error("mesh file '" + file +
                                       "': malformed $PhysicalNames line '" +
                                       line + "'");
            std::string rest;
            std::getline(l, rest);
            const auto a = rest.find('"'), b = rest.rfind('"');
            names[{dim, tag}] = (a != std::string::npos && b > a) ?
                                  rest.substr(a + 1, b - a - 1) :
                                  trim(rest);
          }
        return names;
      }

      io::NamedSets
      read_gmsh(const std::string &file,
                const double       unit,
                Triangulation<3>  &tria)
      {
        // second-order hexahedra: through Gmsh's API (GridIn reads first
        // order only)
        if (internal::has_second_order_hexahedra(file))
          return internal::build_element_mesh(
            internal::read_gmsh_second_order(file), file, unit, tria);
        std::ifstream     in(file);
        std::stringstream buffer;
        buffer << in.rdbuf();
        const std::string text  = buffer.str();
        const auto        names = physical_names(text, file);

        GridIn<3> grid_in;
        grid_in.attach_triangulation(tria);
        std::istringstream stream(text);
        try
          {
            grid_in.read_msh(stream);
          }
        catch (const ExceptionBase &e)
          {
            throw std::runtime_error(
              "mesh file '" + file +
              "' could not be read as a Gmsh ASCII mesh (format 2.2 or 4.1; "
              "a physical group on an interior face is not allowed): " +
              trim(e.get_exc_name()) + " " + trim(e.what()).substr(0, 400));
          }
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->reference_cell() != ReferenceCells::Hexahedron)
            throw std::runtime_error(
              "mesh file '" + file + "': cell " +
              std::to_string(cell->index()) + " is a " +
              (cell->reference_cell() == ReferenceCells::Tetrahedron ?
                 std::string("tetrahedron") :
               cell->reference_cell() == ReferenceCells::Wedge ?
                 std::string("wedge") :
                 std::string("pyramid")) +
              "; squeal needs hexahedra (in Gmsh: transfinite volumes with "
              "Mesh.RecombineAll = 1, or Mesh.SubdivisionAlgorithm = 2)");
        GridTools::scale(unit, tria);

        std::map<types::material_id, std::string> cell_names;
        std::map<types::boundary_id, std::string> face_names;
        for (const auto &cell : tria.active_cell_iterators())
          {
            std::array<Point<3>, 8> v;
            for (unsigned int i = 0; i < 8; ++i)
              v[i] = cell->vertex(i);
            if (const double r = corner_jacobian_ratio(v); r < degenerate_ratio)
              {
                std::ostringstream where;
                where << "mesh file '" << file << "': the cell at "
                      << cell->center();
                throw std::runtime_error(degenerate_message(where.str(), r));
              }
            if (cell->material_id() != 0)
              {
                const auto it = names.find({3, int(cell->material_id())});
                cell_names[cell->material_id()] =
                  it != names.end() ? it->second :
                                      std::to_string(cell->material_id());
              }
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() != 0)
                {
                  const auto id = cell->face(f)->boundary_id();
                  const auto it = names.find({2, int(id)});
                  face_names[id] =
                    it != names.end() ? it->second : std::to_string(id);
                }
          }
        io::NamedSets sets;
        sets.source = "mesh file '" + file + "'";
        sets.collect_from_ids(tria, cell_names, face_names);
        for (const auto &cell : tria.active_cell_iterators())
          {
            cell->set_material_id(0);
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary())
                cell->face(f)->set_boundary_id(0);
          }
        return sets;
      }

      // ----------------------------------------------------------------
      // Abaqus / CalculiX
      // ----------------------------------------------------------------

      struct InpElement
      {
        long                id;
        std::array<long, 8> corners; // Abaqus order
        std::vector<long>   midside; // 12 for C3D20/C3D20R, Abaqus order
        unsigned int        line;
      };

      /// A named set as read: its name as first written, its members.
      struct InpSet
      {
        std::string       name;
        std::vector<long> ids;
        /// other sets named in its data lines (elsets only), by upper name
        std::vector<std::string> includes;
      };

      struct InpSurfaceFace
      {
        std::string  target; // an element id or an elset name (upper)
        unsigned int face;   // 1-6
        unsigned int line;
      };

      class InpReader
      {
      public:
        explicit InpReader(const std::string &file)
          : file(file)
        {}

        /// Takes the nodes, elements and sets of @p mesh (a file read
        /// elsewhere) instead of read().
        void
        load(const internal::ElementMesh &mesh)
        {
          nodes = mesh.nodes;
          for (const auto &e : mesh.elements)
            {
              if (!element_ids.insert(e.id).second)
                fail("element " + std::to_string(e.id) + " is defined twice");
              elements.push_back({e.id, e.corners, e.midside, 0});
            }
          for (const auto &[name, ids] : mesh.element_sets)
            elsets[upper(name)] = {name, ids, {}};
          for (const auto &[name, ids] : mesh.node_sets)
            nsets[upper(name)] = {name, ids, {}};
          for (const auto &[name, faces] : mesh.surfaces)
            {
              auto &s = surfaces[upper(name)];
              s.first = name;
              for (const auto &[element, face] : faces)
                s.second.push_back({std::to_string(element), face, 0});
            }
        }

        void
        read()
        {
          std::ifstream in(file);
          std::string   raw;
          while (std::getline(in, raw))
            {
              ++line_number;
              const std::string line = trim(raw);
              if (line.empty() || line.rfind("**", 0) == 0)
                continue;
              if (line[0] == '*')
                keyword(line);
              else
                data(line);
            }
          if (!pending.empty())
            fail("the last element's node list is incomplete");
        }

        // Quadratic elements whose mid-side nodes leave the straight
        // edges: their coarse cell, faces and edges get a manifold of
        // their own (ids 1000 + cell index) that carries the curvature.
        void
        attach_quadratic_geometry(
          const double                                        unit,
          const std::vector<unsigned int>                    &cell_of,
          const std::vector<Triangulation<3>::cell_iterator> &coarse,
          Triangulation<3>                                   &tria) const
        {
          // Abaqus edges of the 12 mid-side nodes (0-based corners)
          static const unsigned int edge[12][2] = {{0, 1},
                                                   {1, 2},
                                                   {2, 3},
                                                   {3, 0},
                                                   {4, 5},
                                                   {5, 6},
                                                   {6, 7},
                                                   {7, 4},
                                                   {0, 4},
                                                   {1, 5},
                                                   {2, 6},
                                                   {3, 7}};
          for (unsigned int e = 0; e < elements.size(); ++e)
            {
              const InpElement &el = elements[e];
              if (el.midside.size() != 12)
                continue;
              std::array<Point<3>, 20> x;
              double                   size = 0., bow = 0.;
              for (unsigned int i = 0; i < 20; ++i)
                {
                  const long id = i < 8 ? el.corners[i] : el.midside[i - 8];
                  const auto it = nodes.find(id);
                  if (it == nodes.end())
                    fail_at(el.line,
                            "element " + std::to_string(el.id) +
                              " refers to node " + std::to_string(id) +
                              ", which no *NODE defines");
                  x[i] = unit * it->second;
                }
              for (unsigned int k = 0; k < 12; ++k)
                {
                  const Point<3> &a = x[edge[k][0]], &b = x[edge[k][1]];
                  size = std::max(size, a.distance(b));
                  bow  = std::max(bow, x[8 + k].distance(a + 0.5 * (b - a)));
                }
              if (bow <= 1e-12 * size)
                continue; // straight: the cell's trilinear map is exact
              const types::manifold_id id = 1000 + cell_of[e];
              coarse[cell_of[e]]->set_all_manifold_ids(id);
              tria.set_manifold(id, QuadraticHexManifold(x));
            }
        }

        io::NamedSets
        build(const double unit, Triangulation<3> &tria)
        {
          // the corner nodes used by the elements become the vertices
          std::map<long, unsigned int> vertex_of;
          std::vector<Point<3>>        vertices;
          std::vector<CellData<3>>     cells(elements.size());
          for (unsigned int e = 0; e < elements.size(); ++e)
            {
              const InpElement       &el = elements[e];
              std::array<Point<3>, 8> v;
              for (unsigned int d = 0; d < 8; ++d)
                {
                  const long node = el.corners[abaqus_node[d]];
                  const auto it   = nodes.find(node);
                  if (it == nodes.end())
                    fail_at(el.line,
                            "element " + std::to_string(el.id) +
                              " refers to node " + std::to_string(node) +
                              ", which no *NODE defines");
                  const auto [pos, fresh] =
                    vertex_of.emplace(node, vertices.size());
                  if (fresh)
                    vertices.push_back(unit * it->second);
                  cells[e].vertices[d] = pos->second;
                  v[d]                 = unit * it->second;
                }
              if (const double r = corner_jacobian_ratio(v);
                  r < degenerate_ratio)
                throw std::runtime_error(
                  degenerate_message("mesh file '" + file + "', line " +
                                       std::to_string(el.line) + ": element " +
                                       std::to_string(el.id),
                                     r));
            }
          if (cells.empty())
            fail_at(line_number,
                    "no hexahedral element (*ELEMENT) in the file");

          // Cells are identified after creation by their sorted vertices:
          // deal.II may renumber the vertices within a cell.
          std::map<std::array<unsigned int, 8>, unsigned int> element_of;
          for (unsigned int e = 0; e < cells.size(); ++e)
            {
              std::array<unsigned int, 8> key;
              std::copy(cells[e].vertices.begin(),
                        cells[e].vertices.end(),
                        key.begin());
              std::sort(key.begin(), key.end());
              if (!element_of.emplace(key, e).second)
                fail_at(elements[e].line,
                        "element " + std::to_string(elements[e].id) +
                          " has the same nodes as element " +
                          std::to_string(elements[element_of[key]].id));
            }
          GridTools::consistently_order_cells(cells);
          try
            {
              tria.create_triangulation(vertices, cells, SubCellData());
            }
          catch (const ExceptionBase &e)
            {
              throw std::runtime_error("mesh file '" + file +
                                       "': deal.II cannot build a mesh from "
                                       "its elements: " +
                                       trim(e.what()).substr(0, 400));
            }
          std::vector<unsigned int>                    cell_of(elements.size());
          std::vector<Triangulation<3>::cell_iterator> coarse;
          for (const auto &cell : tria.cell_iterators_on_level(0))
            {
              std::array<unsigned int, 8> key;
              for (unsigned int v = 0; v < 8; ++v)
                key[v] = cell->vertex_index(v);
              std::sort(key.begin(), key.end());
              cell_of[element_of.at(key)] = cell->index();
              coarse.push_back(cell);
            }
          std::map<long, unsigned int> element_index;
          for (unsigned int e = 0; e < elements.size(); ++e)
            element_index[elements[e].id] = e;
          attach_quadratic_geometry(unit, cell_of, coarse, tria);

          return named_sets(unit, cell_of, coarse, vertex_of, element_index);
        }

        // The element sets, node sets and surfaces as named sets of the
        // coarse cells (cell_of: element index -> cell index) and faces.
        io::NamedSets
        named_sets(const double                                        unit,
                   const std::vector<unsigned int>                    &cell_of,
                   const std::vector<Triangulation<3>::cell_iterator> &coarse,
                   const std::map<long, unsigned int> &vertex_of,
                   const std::map<long, unsigned int> &element_index) const
        {
          io::NamedSets sets;
          sets.source = "mesh file '" + file + "'";
          for (const auto &[key, set] : elsets)
            {
              std::set<long> ids;
              collect_elset(key, ids, 0);
              auto &cells_of_set = sets.cell_sets[set.name];
              for (const long id : ids)
                {
                  const auto it = element_index.find(id);
                  if (it == element_index.end())
                    fail_at(line_number,
                            "element set '" + set.name +
                              "' refers to element " + std::to_string(id) +
                              ", which no *ELEMENT defines");
                  cells_of_set.push_back(cell_of[it->second]);
                }
              std::sort(cells_of_set.begin(), cells_of_set.end());
            }
          for (const auto &[key, set] : nsets)
            {
              auto &points = sets.node_sets[set.name];
              for (const long id : set.ids)
                {
                  const auto it = nodes.find(id);
                  if (it == nodes.end())
                    fail_at(line_number,
                            "node set '" + set.name + "' refers to node " +
                              std::to_string(id) + ", which no *NODE defines");
                  points.push_back(unit * it->second);
                }
            }
          for (const auto &[key, surface] : surfaces)
            {
              std::set<io::CellFace> faces;
              for (const InpSurfaceFace &sf : surface.second)
                {
                  std::set<long> ids;
                  if (!sf.target.empty() &&
                      std::all_of(sf.target.begin(),
                                  sf.target.end(),
                                  [](char c) { return std::isdigit(c); }))
                    ids.insert(std::stol(sf.target));
                  else if (elsets.count(sf.target))
                    collect_elset(sf.target, ids, 0);
                  else
                    fail_at(sf.line,
                            "surface '" + surface.first + "' refers to '" +
                              sf.target +
                              "', neither an element nor an "
                              "element set");
                  for (const long id : ids)
                    {
                      const auto it = element_index.find(id);
                      if (it == element_index.end())
                        fail_at(sf.line,
                                "surface '" + surface.first +
                                  "' refers to element " + std::to_string(id) +
                                  ", which no *ELEMENT defines");
                      const InpElement           &el = elements[it->second];
                      std::array<unsigned int, 4> key;
                      for (unsigned int k = 0; k < 4; ++k)
                        key[k] =
                          vertex_of.at(el.corners[abaqus_face[sf.face - 1][k]]);
                      std::sort(key.begin(), key.end());
                      const auto cell  = coarse[cell_of[it->second]];
                      bool       found = false;
                      for (const unsigned int f : cell->face_indices())
                        {
                          std::array<unsigned int, 4> fk;
                          for (unsigned int k = 0; k < 4; ++k)
                            fk[k] = cell->face(f)->vertex_index(k);
                          std::sort(fk.begin(), fk.end());
                          if (fk == key)
                            {
                              faces.emplace(cell->index(), f);
                              found = true;
                            }
                        }
                      Assert(found, ExcInternalError());
                      (void)found;
                    }
                }
              sets.face_sets[surface.first].assign(faces.begin(), faces.end());
            }
          return sets;
        }

      private:
        enum class Mode
        {
          none,
          node,
          element,
          elset,
          nset,
          surface
        };

        [[noreturn]] void
        fail(const std::string &what) const
        {
          fail_at(line_number, what);
        }

        [[noreturn]] void
        fail_at(const unsigned int line, const std::string &what) const
        {
          // line 0: a file without lines (load())
          throw std::runtime_error(
            "mesh file '" + file +
            (line > 0 ? "', line " + std::to_string(line) : std::string("'")) +
            ": " + what);
        }

        long
        to_id(const std::string &token) const
        {
          std::size_t end = 0;
          long        id  = 0;
          try
            {
              id = std::stol(token, &end);
            }
          catch (const std::exception &)
            {
              end = 0;
            }
          if (end != token.size() || token.empty())
            fail("'" + token + "' is not an integer id");
          return id;
        }

        void
        keyword(const std::string &line)
        {
          if (!pending.empty())
            fail("the previous element's node list is incomplete");
          const auto parts = split_commas(line.substr(1));
          const auto name  = upper(parts[0]);
          std::map<std::string, std::string> option;
          for (unsigned int k = 1; k < parts.size(); ++k)
            {
              const auto eq = parts[k].find('=');
              option[upper(trim(parts[k].substr(0, eq)))] =
                eq == std::string::npos ? "" : trim(parts[k].substr(eq + 1));
            }
          generate = option.count("GENERATE") > 0;
          mode     = Mode::none;
          if (name == "NODE")
            {
              mode        = Mode::node;
              current_set = option.count("NSET") ?
                              open_set(nsets, option["NSET"]) :
                              nullptr;
            }
          else if (name == "ELEMENT")
            {
              const std::string type = upper(option["TYPE"]);
              if (type == "C3D8" || type == "C3D8R" || type == "C3D8I")
                nodes_per_element = 8;
              else if (type == "C3D20" || type == "C3D20R")
                nodes_per_element = 20;
              else
                fail("element type '" + option["TYPE"] +
                     "' cannot be used: squeal needs hexahedral solid "
                     "elements (C3D8, C3D8R, C3D8I, C3D20 or C3D20R); remesh "
                     "this part with hexahedra");
              mode        = Mode::element;
              current_set = option.count("ELSET") ?
                              open_set(elsets, option["ELSET"]) :
                              nullptr;
            }
          else if (name == "ELSET" || name == "NSET")
            {
              const std::string key = name == "ELSET" ? "ELSET" : "NSET";
              if (option[key].empty())
                fail("*" + name + " needs " + key + "=<name>");
              if (option.count("INSTANCE"))
                fail("sets of part instances are not supported: export a "
                     "flat input file");
              mode = name == "ELSET" ? Mode::elset : Mode::nset;
              current_set =
                open_set(name == "ELSET" ? elsets : nsets, option[key]);
            }
          else if (name == "SURFACE")
            {
              if (option["NAME"].empty())
                fail("*SURFACE needs NAME=<name>");
              if (option.count("TYPE") && upper(option["TYPE"]) != "ELEMENT")
                fail("*SURFACE, TYPE=" + option["TYPE"] +
                     " is not supported: squeal reads element-based "
                     "surfaces (TYPE=ELEMENT, lines 'element or set, Sn')");
              mode    = Mode::surface;
              auto &s = surfaces[upper(option["NAME"])];
              if (s.first.empty())
                s.first = option["NAME"];
              current_surface = &s.second;
            }
          else if (name == "PART" || name == "INSTANCE" || name == "INCLUDE")
            fail("*" + name +
                 " is not supported: squeal reads flat input files (in "
                 "Abaqus/CAE: Model > Edit Attributes > 'Do not use parts "
                 "and assemblies in input files'; merge *INCLUDE files)");
        }

        InpSet *
        open_set(std::map<std::string, InpSet> &sets, const std::string &name)
        {
          InpSet &s = sets[upper(name)];
          if (s.name.empty())
            s.name = name;
          return &s;
        }

        void
        data(const std::string &line)
        {
          const auto tokens = split_commas(line);
          switch (mode)
            {
              case Mode::none:
                return;
              case Mode::node:
                {
                  if (tokens.size() < 4)
                    fail("a *NODE line needs 'id, x, y, z'");
                  const long id = to_id(tokens[0]);
                  Point<3>   x;
                  for (unsigned int d = 0; d < 3; ++d)
                    try
                      {
                        x[d] = std::stod(tokens[d + 1]);
                      }
                    catch (const std::exception &)
                      {
                        fail("'" + tokens[d + 1] + "' is not a coordinate");
                      }
                  if (!nodes.emplace(id, x).second)
                    fail("node " + std::to_string(id) + " is defined twice");
                  if (current_set)
                    current_set->ids.push_back(id);
                  return;
                }
              case Mode::element:
                {
                  for (const auto &t : tokens)
                    if (!t.empty())
                      pending.push_back(to_id(t));
                  if (pending.size() > nodes_per_element + 1)
                    fail("element " + std::to_string(pending[0]) + " has " +
                         std::to_string(pending.size() - 1) +
                         " nodes, its type " +
                         std::to_string(nodes_per_element));
                  if (pending.size() < nodes_per_element + 1)
                    return; // continued on the next line
                  InpElement el;
                  el.id   = pending[0];
                  el.line = line_number;
                  std::copy(pending.begin() + 1,
                            pending.begin() + 9,
                            el.corners.begin());
                  el.midside.assign(pending.begin() + 9, pending.end());
                  if (!element_ids.insert(el.id).second)
                    fail("element " + std::to_string(el.id) +
                         " is defined twice");
                  elements.push_back(el);
                  if (current_set)
                    current_set->ids.push_back(el.id);
                  pending.clear();
                  return;
                }
              case Mode::elset:
              case Mode::nset:
                {
                  if (generate)
                    {
                      if (tokens.size() < 2)
                        fail("a GENERATE line needs 'first, last[, step]'");
                      const long a = to_id(tokens[0]), b = to_id(tokens[1]),
                                 s = tokens.size() > 2 && !tokens[2].empty() ?
                                       to_id(tokens[2]) :
                                       1;
                      if (s <= 0 || b < a)
                        fail("a GENERATE line needs first <= last and a "
                             "positive step");
                      for (long id = a; id <= b; id += s)
                        current_set->ids.push_back(id);
                      return;
                    }
                  for (const auto &t : tokens)
                    if (t.empty())
                      continue;
                    else if (std::isdigit(static_cast<unsigned char>(t[0])))
                      current_set->ids.push_back(to_id(t));
                    else if (mode == Mode::elset)
                      current_set->includes.push_back(upper(t));
                    else
                      {
                        const auto it = nsets.find(upper(t));
                        if (it == nsets.end())
                          fail("node set '" + t + "' is not defined before");
                        current_set->ids.insert(current_set->ids.end(),
                                                it->second.ids.begin(),
                                                it->second.ids.end());
                      }
                  return;
                }
              case Mode::surface:
                {
                  if (tokens.size() < 2)
                    fail("a *SURFACE line needs 'element or set, S1-S6'");
                  const std::string face = upper(tokens[1]);
                  if (face.size() != 2 || face[0] != 'S' || face[1] < '1' ||
                      face[1] > '6')
                    fail("face '" + tokens[1] +
                         "' of a hexahedron must be S1 ... S6");
                  current_surface->push_back(
                    {upper(tokens[0]), unsigned(face[1] - '0'), line_number});
                  return;
                }
            }
        }

        void
        collect_elset(const std::string &key,
                      std::set<long>    &ids,
                      const unsigned int depth) const
        {
          const auto it = elsets.find(key);
          if (it == elsets.end())
            fail_at(line_number, "element set '" + key + "' is not defined");
          if (depth > 32)
            fail_at(line_number,
                    "element set '" + it->second.name + "' includes itself");
          ids.insert(it->second.ids.begin(), it->second.ids.end());
          for (const auto &other : it->second.includes)
            collect_elset(other, ids, depth + 1);
        }

        const std::string            file;
        unsigned int                 line_number       = 0;
        Mode                         mode              = Mode::none;
        bool                         generate          = false;
        unsigned int                 nodes_per_element = 8;
        std::vector<long>            pending;
        InpSet                      *current_set     = nullptr;
        std::vector<InpSurfaceFace> *current_surface = nullptr;

        std::map<long, Point<3>>      nodes;
        std::vector<InpElement>       elements;
        std::set<long>                element_ids;
        std::map<std::string, InpSet> elsets, nsets;
        std::map<std::string,
                 std::pair<std::string, std::vector<InpSurfaceFace>>>
          surfaces;
      };
    } // namespace

    io::NamedSets
    read_mesh_file(const std::string &filename,
                   const double       length_unit,
                   Triangulation<3>  &tria)
    {
      if (!(length_unit > 0.) || !std::isfinite(length_unit))
        throw std::runtime_error("mesh file '" + filename +
                                 "': the length unit must be positive [m "
                                 "per file unit], got " +
                                 std::to_string(length_unit));
      if (!std::filesystem::is_regular_file(filename))
        throw std::runtime_error("mesh file '" + filename + "': no such file");
      const std::string ext = std::filesystem::path(filename).extension();
      if (upper(ext) == ".MSH")
        return read_gmsh(filename, length_unit, tria);
      if (upper(ext) == ".INP")
        {
          InpReader reader(filename);
          reader.read();
          return reader.build(length_unit, tria);
        }
      if (upper(ext) == ".VTU")
        return internal::build_element_mesh(internal::read_vtu(filename),
                                            filename,
                                            length_unit,
                                            tria);
      throw std::runtime_error("mesh file '" + filename +
                               "': unknown format '" + ext +
                               "'; squeal reads Gmsh (.msh), "
                               "Abaqus/CalculiX (.inp) and VTK (.vtu) meshes");
    }

    namespace internal
    {
      NamedSets
      build_element_mesh(const ElementMesh &mesh,
                         const std::string &file,
                         const double       unit,
                         Triangulation<3>  &tria)
      {
        InpReader reader(file);
        reader.load(mesh);
        return reader.build(unit, tria);
      }
    } // namespace internal
  }   // namespace io
} // namespace squeal
