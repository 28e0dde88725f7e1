// Gmsh meshes of second-order hexahedra through Gmsh's own API (deal.II's
// GridIn reads first-order elements only): 20-node (Gmsh type 17) and
// 27-node (type 12, its face and centre nodes dropped) hexahedra, their
// corners the cells and their mid-edge nodes the geometry as for C3D20;
// volume physical groups name cell sets, surface groups (quadrilaterals of
// types 3, 16, 10) face sets. Gmsh numbers the 12 mid-edge nodes of a
// hexahedron by the edges (0,1) (0,3) (0,4) (1,2) (1,5) (2,3) (2,6) (3,7)
// (4,5) (4,7) (5,6) (6,7) (Gmsh reference manual, "Node ordering"); its
// corner order is Abaqus'.

#include <gmsh.h>

#include "element_mesh.h"

#include <algorithm>
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
        // Abaqus' mid-side node k is Gmsh's node gmsh_midside[k]
        constexpr std::array<unsigned int, 12> gmsh_midside = {
          {8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15}};

        // Gmsh opened for one file, closed at the end (a caller must not
        // hold a Gmsh session of its own meanwhile: Gmsh 4.8 cannot tell).
        class GmshSession
        {
        public:
          explicit GmshSession(const std::string &file)
          {
            gmsh::initialize(0, nullptr, false);
            gmsh::option::setNumber("General.Terminal", 0);
            gmsh::open(file);
          }
          ~GmshSession()
          {
            try
              {
                gmsh::finalize();
              }
            catch (...)
              {}
          }
        };
      } // namespace

      bool
      has_second_order_hexahedra(const std::string &file)
      {
        try
          {
            GmshSession      session(file);
            std::vector<int> types;
            gmsh::model::mesh::getElementTypes(types, 3);
            return std::find(types.begin(), types.end(), 17) != types.end() ||
                   std::find(types.begin(), types.end(), 12) != types.end();
          }
        catch (...)
          {
            return false; // GridIn's reader gives the error
          }
      }

      ElementMesh
      read_gmsh_second_order(const std::string &file)
      {
        const std::string where = "mesh file '" + file + "'";
        GmshSession       session(file);
        ElementMesh       mesh;
        {
          std::vector<std::size_t> tags;
          std::vector<double>      x, parametric;
          gmsh::model::mesh::getNodes(tags, x, parametric);
          for (std::size_t i = 0; i < tags.size(); ++i)
            mesh.nodes[tags[i]] =
              dealii::Point<3>(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
        }
        std::vector<int>                      types;
        std::vector<std::vector<std::size_t>> elements, nodes;
        gmsh::model::mesh::getElements(types, elements, nodes, 3);
        for (unsigned int t = 0; t < types.size(); ++t)
          {
            const int type = types[t];
            if (type != 5 && type != 17 && type != 12)
              throw std::runtime_error(
                where + ": Gmsh element type " + std::to_string(type) +
                (type == 4 || type == 11 ? " (tetrahedron)" :
                 type == 6 || type == 18 ? " (prism)" :
                                           "") +
                " cannot be used: squeal needs hexahedra (in Gmsh: "
                "transfinite volumes with Mesh.RecombineAll = 1)");
            const unsigned int per = type == 5 ? 8 : type == 17 ? 20 : 27;
            for (std::size_t e = 0; e < elements[t].size(); ++e)
              {
                ElementMesh::Element el;
                el.id = elements[t][e];
                for (unsigned int k = 0; k < 8; ++k)
                  el.corners[k] = nodes[t][per * e + k];
                if (per > 8)
                  for (const unsigned int k : gmsh_midside)
                    el.midside.push_back(nodes[t][per * e + k]);
                mesh.elements.push_back(el);
              }
          }
        if (mesh.elements.empty())
          throw std::runtime_error(where + ": no hexahedron in the mesh");

        const FaceIndex  faces = hexahedron_faces(mesh);
        gmsh::vectorpair groups;
        gmsh::model::getPhysicalGroups(groups);
        for (const auto &[dim, tag] : groups)
          {
            if (dim != 2 && dim != 3)
              continue;
            std::string name;
            gmsh::model::getPhysicalName(dim, tag, name);
            if (name.empty())
              name = std::to_string(tag);
            std::vector<int> entities;
            gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
            for (const int entity : entities)
              {
                gmsh::model::mesh::getElements(
                  types, elements, nodes, dim, entity);
                for (unsigned int t = 0; t < types.size(); ++t)
                  {
                    if (dim == 3)
                      {
                        auto &set = mesh.element_sets[name];
                        set.insert(set.end(),
                                   elements[t].begin(),
                                   elements[t].end());
                        continue;
                      }
                    const int          type = types[t];
                    const unsigned int per  = type == 3  ? 4 :
                                              type == 16 ? 8 :
                                              type == 10 ? 9 :
                                                           0;
                    if (per == 0)
                      throw std::runtime_error(
                        where + ": surface group '" + name +
                        "' holds Gmsh elements of type " +
                        std::to_string(type) +
                        "; faces of hexahedra are quadrilaterals");
                    for (std::size_t e = 0; e < elements[t].size(); ++e)
                      add_quadrilateral(mesh,
                                        faces,
                                        name,
                                        {{long(nodes[t][per * e]),
                                          long(nodes[t][per * e + 1]),
                                          long(nodes[t][per * e + 2]),
                                          long(nodes[t][per * e + 3])}},
                                        where);
                  }
              }
          }
        return mesh;
      }
    } // namespace internal
  }   // namespace io
} // namespace squeal
