#ifndef squeal_scene_tribobrake_mesh_h
#define squeal_scene_tribobrake_mesh_h

/**
 * @file
 * The TriboBrake mesher (thesis § 3.2.1): a structured polar hexahedral disc,
 * axisymmetric so that doublets stay exact, and a pad bonded to its support
 * (one block sharing nodes), sitting on the disc's top face z = 0 without
 * sharing nodes with it (the interface is handled by the contact module).
 */

#include <deal.II/grid/tria.h>

#include <squeal/io/named_sets.h>
#include <squeal/parameters/parameters.h>

namespace squeal
{
  namespace scene
  {
    namespace tribobrake
    {
      /** Material ids of the bodies. */
      namespace material
      {
        constexpr dealii::types::material_id disc    = 0;
        constexpr dealii::types::material_id pad     = 1;
        constexpr dealii::types::material_id support = 2;
      } // namespace material

      /** Boundary ids of the faces a run needs. */
      namespace boundary
      {
        constexpr dealii::types::boundary_id free         = 0;
        constexpr dealii::types::boundary_id clamped      = 1; ///< disc r = r_i
        constexpr dealii::types::boundary_id pad_contact  = 2; ///< pad z = 0
        constexpr dealii::types::boundary_id disc_contact = 3; ///< disc z = 0
        constexpr dealii::types::boundary_id support_top  = 4; ///< loaded end
      } // namespace boundary

      /** Manifold id of the disc cells (cylindrical about the z axis). */
      constexpr dealii::types::manifold_id disc_manifold = 1;

      /**
       * Fills the empty @p tria with the scene. The disc occupies
       * r_i <= r <= r_o, -h <= z <= 0; the pad the cube centred at
       * (pad_radius, 0) on 0 <= z <= pad_size; the support the beam of the
       * pad's cross-section on pad_size <= z <= pad_size + support_length. With
       * @p with_pad_and_support false only the disc is meshed. Disc cells under
       * the pad are refined Mesh::disc_refinements_under_pad times.
       * Lengths in m.
       * @throws std::runtime_error if the mesh counts cannot place the springs'
       * stations on nodes (never: nearest nodes are used and reported).
       */
      void
      make_tribobrake_mesh(const parameters::Geometry &geometry,
                           const parameters::Mesh     &mesh,
                           const bool                  with_pad_and_support,
                           dealii::Triangulation<3>   &tria);

      /**
       * The named sets of a mesh make_tribobrake_mesh() built: cell sets
       * `disc`, `pad`, `support`; face sets `disc hub` (clamped), `pad face`,
       * `disc face`, `support top`; from the coarse cells' ids.
       */
      io::NamedSets
      tribobrake_sets(const dealii::Triangulation<3> &tria);
    } // namespace tribobrake
  }   // namespace scene
} // namespace squeal

#endif
