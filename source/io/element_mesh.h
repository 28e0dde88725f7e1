// Private to io/: a hexahedral mesh as a file lists it (nodes, elements in
// Abaqus node order, named sets), the common ground of the .inp reader and
// the .vtu reader; build_element_mesh() makes the triangulation and the
// named sets from it.
#ifndef squeal_io_element_mesh_h
#define squeal_io_element_mesh_h

#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <squeal/io/named_sets.h>

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace squeal
{
  namespace io
  {
    namespace internal
    {
      /** Nodes, hexahedral elements and named sets of a mesh file. */
      struct ElementMesh
      {
        /** One hexahedron. */
        struct Element
        {
          long                id = 0;  ///< as the file numbers it
          std::array<long, 8> corners; ///< node ids, Abaqus C3D8 order
          /// 12 mid-side node ids (Abaqus C3D20 order) or none
          std::vector<long> midside;
        };
        std::map<long, dealii::Point<3>> nodes; ///< id -> position [file unit]
        std::vector<Element>             elements; ///< the hexahedra
        /// named element sets: element ids
        std::map<std::string, std::vector<long>> element_sets;
        /// named node sets: node ids
        std::map<std::string, std::vector<long>> node_sets;
        /// named surfaces: (element id, Abaqus face 1-6)
        std::map<std::string, std::vector<std::pair<long, unsigned int>>>
          surfaces;
      };

      /// the faces of hexahedra by their sorted corner node ids
      using FaceIndex =
        std::map<std::array<long, 4>, std::pair<long, unsigned int>>;

      /**
       * Every face of @p mesh's hexahedra: its sorted corner node ids ->
       * (element id, Abaqus face 1-6).
       */
      FaceIndex
      hexahedron_faces(const ElementMesh &mesh);

      /**
       * Adds the quadrilateral with corner node ids @p corners to the
       * surface @p name of @p mesh as the face of @p faces it is.
       * @throws std::runtime_error naming @p where and @p name if it is no
       * face of a hexahedron.
       */
      void
      add_quadrilateral(ElementMesh        &mesh,
                        const FaceIndex    &faces,
                        const std::string  &name,
                        std::array<long, 4> corners,
                        const std::string  &where);

      /**
       * The triangulation of @p mesh in @p tria (coordinates times @p unit
       * [m per file unit]; quadratic elements curved as in
       * read_mesh_file()) and its named sets.
       * @throws std::runtime_error naming @p file on a degenerate or
       * inverted element, a missing node or element, or no element.
       */
      NamedSets
      build_element_mesh(const ElementMesh        &mesh,
                         const std::string        &file,
                         double                    unit,
                         dealii::Triangulation<3> &tria);

      /**
       * Whether the Gmsh file @p file holds second-order hexahedra (Gmsh
       * element types 17 or 12); false if Gmsh cannot read it.
       */
      bool
      has_second_order_hexahedra(const std::string &file);

      /**
       * Reads the Gmsh file @p file through Gmsh's API: hexahedra of first
       * and second order, volume physical groups as cell sets, surface
       * groups as face sets.
       * @throws std::runtime_error naming the file on an element type squeal
       * cannot use or a surface element that is no face of a hexahedron.
       */
      ElementMesh
      read_gmsh_second_order(const std::string &file);

      /**
       * Reads the VTK unstructured grid @p file (.vtu, through VTK's XML
       * reader) as described in read_mesh_file().
       * @throws std::runtime_error naming the file on an unreadable file,
       * a cell type squeal cannot use, or no hexahedron.
       */
      ElementMesh
      read_vtu(const std::string &file);
    } // namespace internal
  }   // namespace io
} // namespace squeal

#endif
