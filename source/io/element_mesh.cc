// The faces of an element mesh's hexahedra, shared by the .vtu and the
// second-order Gmsh readers to turn quadrilaterals into face sets.

#include "element_mesh.h"

#include "abaqus_numbering.h"

#include <algorithm>
#include <stdexcept>

namespace squeal
{
  namespace io
  {
    namespace internal
    {
      FaceIndex
      hexahedron_faces(const ElementMesh &mesh)
      {
        FaceIndex faces;
        for (const auto &e : mesh.elements)
          for (unsigned int f = 0; f < 6; ++f)
            {
              std::array<long, 4> key;
              for (unsigned int k = 0; k < 4; ++k)
                key[k] = e.corners[abaqus_face[f][k]];
              std::sort(key.begin(), key.end());
              faces.emplace(key, std::make_pair(e.id, f + 1));
            }
        return faces;
      }

      void
      add_quadrilateral(ElementMesh        &mesh,
                        const FaceIndex    &faces,
                        const std::string  &name,
                        std::array<long, 4> corners,
                        const std::string  &where)
      {
        std::sort(corners.begin(), corners.end());
        const auto it = faces.find(corners);
        if (it == faces.end())
          throw std::runtime_error(where + ": a quadrilateral of face set '" +
                                   name +
                                   "' is no face of a hexahedron (its nodes "
                                   "must be the face's corner nodes)");
        mesh.surfaces[name].push_back(it->second);
      }
    } // namespace internal
  }   // namespace io
} // namespace squeal
