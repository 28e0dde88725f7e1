#ifndef squeal_io_named_sets_h
#define squeal_io_named_sets_h

/**
 * @file
 * The named parts of a scene's mesh: cell sets (bodies are made of them),
 * face sets (holds, loads, contact surfaces) and node sets (springs, masses,
 * probes), each addressed by the name the mesh file or the scene generator
 * gave it. A mesh file may put one cell or face in several sets (Abaqus
 * `*ELSET`s overlap freely), so the sets are kept as lists; the scene turns
 * the sets it uses into deal.II material and boundary ids with
 * assign_material() and assign_boundary(), on the coarse mesh, before any
 * refinement, so that every child cell and face inherits them.
 */

#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace squeal
{
  namespace io
  {
    /** A face of a coarse cell: (coarse cell index, deal.II face number
     * 0-5). */
    using CellFace = std::pair<unsigned int, unsigned int>;

    /**
     * Named cell, face and node sets of one coarse hexahedral mesh. Cell
     * indices are the level-0 cell indices of the triangulation the sets
     * belong to; points are in m.
     */
    struct NamedSets
    {
      /// where the mesh came from ("mesh file 'brake.inp'", "the TriboBrake
      /// generator"), for error messages
      std::string source;
      /// name -> coarse cell indices (sorted, unique)
      std::map<std::string, std::vector<unsigned int>> cell_sets;
      /// name -> coarse boundary faces (sorted, unique)
      std::map<std::string, std::vector<CellFace>> face_sets;
      /// name -> node positions [m]
      std::map<std::string, std::vector<dealii::Point<3>>> node_sets;

      /**
       * The cells of set @p name.
       * @throws std::runtime_error naming the source, the set and the cell
       * sets it does have, if there is no such set.
       */
      const std::vector<unsigned int> &
      cells(const std::string &name) const;

      /** The faces of set @p name. @throws as cells(). */
      const std::vector<CellFace> &
      faces(const std::string &name) const;

      /** The nodes of set @p name [m]. @throws as cells(). */
      const std::vector<dealii::Point<3>> &
      nodes(const std::string &name) const;

      /**
       * Sets the material id of every cell of set @p name to @p id.
       * @throws std::runtime_error if the set is missing or @p tria is
       * refined (the ids must be set on the coarse mesh).
       */
      void
      assign_material(const std::string         &name,
                      dealii::types::material_id id,
                      dealii::Triangulation<3>  &tria) const;

      /**
       * Sets the boundary id of every face of set @p name to @p id.
       * @throws std::runtime_error if the set is missing, a face of it is
       * not on the boundary, or @p tria is refined.
       */
      void
      assign_boundary(const std::string         &name,
                      dealii::types::boundary_id id,
                      dealii::Triangulation<3>  &tria) const;

      /**
       * Fills cell_sets and face_sets from the material and boundary ids of
       * the coarse cells of @p tria: cell set @p cell_names[m] holds the
       * cells with material id m, face set @p face_names[b] the boundary
       * faces with boundary id b. Ids without a name form no set.
       */
      void
      collect_from_ids(
        const dealii::Triangulation<3>                          &tria,
        const std::map<dealii::types::material_id, std::string> &cell_names,
        const std::map<dealii::types::boundary_id, std::string> &face_names);
    };
  } // namespace io
} // namespace squeal

#endif
