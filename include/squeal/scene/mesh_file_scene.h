#ifndef squeal_scene_mesh_file_scene_h
#define squeal_scene_mesh_file_scene_h

/**
 * @file
 * A scene read from a mesh file (Scene/Type = mesh file): a Gmsh or
 * Abaqus/CalculiX hexahedral mesh (io/mesh_file.h) whose named sets the
 * parameter file's lists (parameters::MeshFileScene) turn into bodies,
 * contact pairs, holds, point holds, loads, springs and probes.
 *
 * List syntax: `name: key=value, key=value; name: ...` (blanks around names,
 * keys and values are ignored; a vector is three numbers separated by
 * blanks; springs' `points` separates points by `|`).
 *
 * Everything the analyses need is derived from the mesh: a contact pair's
 * centre (area-weighted centroid of the slave faces), normal (the slave
 * faces' mean inward normal: from the master into the slave), plane frame
 * and size (square root of the slave area); a disc's inner and outer radius
 * (its vertices' distances from its axis) and reference direction (towards
 * the first contact pair's centre); each spring station's face normal (the
 * body's boundary face through it).
 *
 * The constructor checks the scene against the mesh, and every failure is
 * one std::runtime_error naming the entry, the item and the set: a missing
 * set or body (the error lists those that exist), a cell in no body or in
 * two, overlapping bodies (a vertex, face or cell centre of one more than
 * 1 % of a cell deep inside a cell of another), a face in two face sets
 * the scene uses, a
 * body nothing holds (no
 * hold, point hold, spring, contact pair or shared node connects it to the
 * ground: named), a slave face set that is not plane, a master face set
 * that does not face the slave or lies beyond Preload/Search distance, a
 * spring station on no boundary face of its body, malformed items, unknown
 * keys (the allowed ones are listed).
 */

#include <squeal/io/named_sets.h>
#include <squeal/scene/scene.h>

#include <map>
#include <string>

namespace squeal
{
  namespace scene
  {
    /** The scene of Scene/Mesh file: see the file comment. */
    class MeshFileScene : public Scene
    {
    public:
      /**
       * Reads the mesh of @p prm.scene.mesh_file and builds and checks the
       * scene's lists.
       * @throws std::runtime_error as the file comment says.
       */
      explicit MeshFileScene(const parameters::AllParameters &prm);

      /** Reads the file again into @p tria and sets the ids and manifolds. */
      void
      make_mesh(dealii::Triangulation<3> &tria) const override;

      std::string
      description() const override;

      /** The named sets of the file. */
      io::NamedSets
      named_sets(const dealii::Triangulation<3> &tria) const override;

    private:
      std::string   file;
      double        length_unit;
      io::NamedSets sets;
      /// face set name -> boundary id of the face sets the scene uses
      std::map<std::string, dealii::types::boundary_id> face_ids;
      /// body index -> its cell set name
      std::vector<std::string> body_sets;
      /// body index -> cylindrical manifold wanted
      std::vector<bool> cylindrical;

      /// material and boundary ids and manifolds on a freshly read mesh
      void
      apply_ids(dealii::Triangulation<3> &tria) const;
    };
  } // namespace scene
} // namespace squeal

#endif
