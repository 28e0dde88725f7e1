// A scene's coarse mesh and named sets written as an Abaqus/CalculiX input
// file (C3D8 elements, element sets, element-face surfaces, node sets), so
// that the same model runs in CalculiX or Abaqus.

#include <deal.II/grid/grid_tools.h>

#include <squeal/io/mesh_file.h>

#include "abaqus_numbering.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace io
  {
    using namespace dealii;
    using internal::abaqus_face_of;
    using internal::abaqus_node;

    std::string
    abaqus_name(const std::string &name)
    {
      std::string out = name;
      for (char &c : out)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      for (char &c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' &&
            c != '-' && c != '.')
          c = '_';
      if (!out.empty() && std::isdigit(static_cast<unsigned char>(out[0])))
        out = "S_" + out;
      return out;
    }

    void
    write_abaqus(const Triangulation<3> &tria,
                 const io::NamedSets    &sets,
                 const std::string      &filename,
                 const double            length_unit)
    {
      if (tria.n_levels() > 1)
        throw std::runtime_error("write_abaqus: '" + filename +
                                 "' needs the coarse mesh (this one is "
                                 "refined)");
      const std::string partial = filename + ".partial";
      {
        std::ofstream out(partial);
        out << std::setprecision(17);
        out << "** written by squeal from " << sets.source << "\n"
            << "** C3D8 elements; units: m / " << length_unit << "\n";
        out << "*NODE\n";
        const auto &used = tria.get_used_vertices();
        for (unsigned int i = 0; i < tria.n_vertices(); ++i)
          if (used[i])
            {
              const Point<3> x = tria.get_vertices()[i] / length_unit;
              out << i + 1 << ", " << x[0] << ", " << x[1] << ", " << x[2]
                  << "\n";
            }
        out << "*ELEMENT, TYPE=C3D8\n";
        for (const auto &cell : tria.cell_iterators_on_level(0))
          {
            out << cell->index() + 1;
            for (unsigned int k = 0; k < 8; ++k)
              out << ", " << cell->vertex_index(abaqus_node[k]) + 1;
            out << "\n";
          }
        for (const auto &[name, cells] : sets.cell_sets)
          {
            out << "*ELSET, ELSET=" << abaqus_name(name) << "\n";
            for (unsigned int k = 0; k < cells.size(); ++k)
              out << cells[k] + 1
                  << ((k % 16 == 15 || k + 1 == cells.size()) ? "\n" : ", ");
          }
        for (const auto &[name, faces] : sets.face_sets)
          {
            out << "*SURFACE, NAME=" << abaqus_name(name) << ", TYPE=ELEMENT\n";
            for (const auto &[c, f] : faces)
              out << c + 1 << ", S" << abaqus_face_of[f] << "\n";
          }
        for (const auto &[name, points] : sets.node_sets)
          {
            out << "*NSET, NSET=" << abaqus_name(name) << "\n";
            const double tol = 1e-9 * GridTools::diameter(tria);
            for (unsigned int k = 0; k < points.size(); ++k)
              {
                unsigned int best = 0;
                double       d    = std::numeric_limits<double>::max();
                for (unsigned int i = 0; i < tria.n_vertices(); ++i)
                  if (used[i] && tria.get_vertices()[i].distance(points[k]) < d)
                    {
                      d    = tria.get_vertices()[i].distance(points[k]);
                      best = i;
                    }
                if (d > tol)
                  throw std::runtime_error("write_abaqus: node set '" + name +
                                           "' has a point that is no mesh "
                                           "vertex");
                out << best + 1
                    << ((k % 16 == 15 || k + 1 == points.size()) ? "\n" : ", ");
              }
          }
        if (!out)
          throw std::runtime_error("write_abaqus: cannot write '" + partial +
                                   "'");
      }
      std::filesystem::rename(partial, filename);
    }
  } // namespace io
} // namespace squeal
