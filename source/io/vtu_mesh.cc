// VTK unstructured grids (.vtu) as meshes with named sets, through VTK's XML
// reader. Hexahedra (linear, 20-node quadratic, 27-node triquadratic: its
// face and centre nodes are dropped) make the cells; quadrilaterals name
// faces of them; vertices and lines are skipped. Sets come from the cell
// and point data arrays of one component: an array of 0/1 values is a set
// named after it (its non-zero members), any other array one set per
// non-zero value, named "<array>=<value>" (a "gmsh:physical" or "material"
// column). VTK's node order of a hexahedron and of its 12 mid-edge nodes is
// Abaqus' (VTK file formats, "Linear cell types" and "Non-linear types").

#include <deal.II/base/utilities.h>

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "element_mesh.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

namespace squeal
{
  namespace io
  {
    namespace internal
    {
      namespace
      {
        std::string
        cell_type_name(const int type)
        {
          switch (type)
            {
              case VTK_TETRA:
              case VTK_QUADRATIC_TETRA:
                return "tetrahedron";
              case VTK_WEDGE:
              case VTK_QUADRATIC_WEDGE:
                return "wedge";
              case VTK_PYRAMID:
                return "pyramid";
              case VTK_TRIANGLE:
              case VTK_QUADRATIC_TRIANGLE:
                return "triangle";
              case VTK_POLYHEDRON:
                return "polyhedron";
              default:
                return "type " + std::to_string(type);
            }
        }

        // The sets of one data array of one component: 0/1 values give a
        // set named after the array, other values a set per value. Each
        // entry i with a non-zero value goes to its set with id(i).
        void
        collect_sets(vtkDataArray                             *array,
                     const std::vector<long>                  &ids,
                     std::map<std::string, std::vector<long>> &sets)
        {
          if (array == nullptr || array->GetNumberOfComponents() != 1 ||
              array->GetName() == nullptr)
            return;
          const std::string name   = array->GetName();
          bool              binary = true;
          for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
            if (const double v = array->GetTuple1(i); v != 0. && v != 1.)
              binary = false;
          for (std::size_t i = 0; i < ids.size(); ++i)
            {
              const double v = array->GetTuple1(i);
              if (v == 0. || ids[i] < 0)
                continue;
              const std::string set =
                binary ?
                  name :
                  name + "=" +
                    (v == std::round(v) ? std::to_string(static_cast<long>(v)) :
                                          dealii::Utilities::to_string(v));
              sets[set].push_back(ids[i]);
            }
        }

      } // namespace

      ElementMesh
      read_vtu(const std::string &file)
      {
        const std::string where = "mesh file '" + file + "'";
        {
          // VTK's reader reports a missing or malformed file on its own
          // output window only: look first.
          std::ifstream in(file);
          std::string   head(256, '\0');
          in.read(&head[0], head.size());
          if (head.find("<VTKFile") == std::string::npos ||
              head.find("UnstructuredGrid") == std::string::npos)
            throw std::runtime_error(where +
                                     ": not a VTK XML unstructured grid "
                                     "(<VTKFile type=\"UnstructuredGrid\">)");
        }
        vtkObject::GlobalWarningDisplayOff();
        vtkNew<vtkXMLUnstructuredGridReader> reader;
        reader->SetFileName(file.c_str());
        reader->Update();
        vtkUnstructuredGrid *grid = reader->GetOutput();
        if (reader->GetErrorCode() != 0 || grid == nullptr ||
            grid->GetNumberOfCells() == 0)
          throw std::runtime_error(where +
                                   ": VTK could not read a grid with cells "
                                   "from it");

        ElementMesh mesh;
        for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
          {
            double x[3];
            grid->GetPoint(i, x);
            mesh.nodes[i + 1] = dealii::Point<3>(x[0], x[1], x[2]);
          }
        // hexahedra: element ids 1, 2, ... in file order; quadrilaterals
        // remembered by their corner nodes
        std::vector<long> element_of_cell(grid->GetNumberOfCells(), -1),
          quad_of_cell(grid->GetNumberOfCells(), -1);
        std::vector<std::array<long, 4>> quads;
        vtkNew<vtkIdList>                points;
        for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
          {
            const int type = grid->GetCellType(c);
            grid->GetCellPoints(c, points);
            const auto node = [&](const int k) {
              return static_cast<long>(points->GetId(k)) + 1;
            };
            if (type == VTK_HEXAHEDRON || type == VTK_QUADRATIC_HEXAHEDRON ||
                type == VTK_TRIQUADRATIC_HEXAHEDRON)
              {
                ElementMesh::Element e;
                e.id = mesh.elements.size() + 1;
                for (unsigned int k = 0; k < 8; ++k)
                  e.corners[k] = node(k);
                if (type != VTK_HEXAHEDRON)
                  for (unsigned int k = 8; k < 20; ++k)
                    e.midside.push_back(node(k));
                element_of_cell[c] = e.id;
                mesh.elements.push_back(e);
              }
            else if (type == VTK_QUAD || type == VTK_QUADRATIC_QUAD ||
                     type == VTK_BIQUADRATIC_QUAD)
              {
                quad_of_cell[c] = quads.size();
                quads.push_back({{node(0), node(1), node(2), node(3)}});
              }
            else if (type != VTK_VERTEX && type != VTK_POLY_VERTEX &&
                     type != VTK_LINE && type != VTK_POLY_LINE &&
                     type != VTK_QUADRATIC_EDGE)
              throw std::runtime_error(
                where + ": cell " + std::to_string(c) + " is a " +
                cell_type_name(type) +
                ", which squeal cannot use: it needs hexahedra (VTK types "
                "12, 25, 29) and quadrilaterals naming their faces (9, 23, "
                "28); remesh this part with hexahedra");
          }
        if (mesh.elements.empty())
          throw std::runtime_error(where + ": no hexahedron in the grid");

        // cell sets and face sets from the cell data, node sets from the
        // point data
        std::map<std::string, std::vector<long>> quad_sets;
        vtkCellData                             *cd = grid->GetCellData();
        for (int a = 0; a < cd->GetNumberOfArrays(); ++a)
          {
            collect_sets(cd->GetArray(a), element_of_cell, mesh.element_sets);
            collect_sets(cd->GetArray(a), quad_of_cell, quad_sets);
          }
        std::vector<long> node_ids(grid->GetNumberOfPoints());
        for (std::size_t i = 0; i < node_ids.size(); ++i)
          node_ids[i] = i + 1;
        vtkPointData *pd = grid->GetPointData();
        for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
          collect_sets(pd->GetArray(a), node_ids, mesh.node_sets);

        const FaceIndex faces = hexahedron_faces(mesh);
        for (const auto &[name, members] : quad_sets)
          for (const long q : members)
            add_quadrilateral(mesh, faces, name, quads[q], where);
        return mesh;
      }
    } // namespace internal
  }   // namespace io
} // namespace squeal
