#ifndef squeal_io_face_output_h
#define squeal_io_face_output_h

/**
 * @file
 * ParaView output of one boundary surface (the pad's contact face): deal.II's
 * DataOutFaces restricted to the faces of one boundary id, so that contact
 * fields (pressure, traction, status) are written on the surface they live on.
 */

#include <deal.II/numerics/data_out_faces.h>

#include <squeal/io/output_directory.h>

#include <set>
#include <utility>

namespace squeal
{
  namespace io
  {
    /** DataOutFaces over the boundary faces with the given ids only. */
    class BoundaryFaceOutput : public dealii::DataOutFaces<3>
    {
    public:
      /** @param id the boundary id of the faces to write */
      explicit BoundaryFaceOutput(const dealii::types::boundary_id id)
        : BoundaryFaceOutput(std::set<dealii::types::boundary_id>{id})
      {}

      /** @param ids the boundary ids of the faces to write (the slave faces
       * of every contact pair) */
      explicit BoundaryFaceOutput(std::set<dealii::types::boundary_id> ids)
        : dealii::DataOutFaces<3>(false)
        , ids(std::move(ids))
      {
        set_flags(squeal::io::vtk_flags());
      }

      /** The first face with the boundary id (empty if none). */
      FaceDescriptor
      first_face() override
      {
        return next_from(this->triangulation->begin_active(), 0);
      }

      /** The face after @p face with the boundary id (empty if none). */
      FaceDescriptor
      next_face(const FaceDescriptor &face) override
      {
        return next_from(face.first, face.second + 1);
      }

    private:
      FaceDescriptor
      next_from(cell_iterator cell, unsigned int start) const
      {
        for (; cell != this->triangulation->end(); ++cell, start = 0)
          if (cell->is_active())
            for (unsigned int f = start; f < cell->n_faces(); ++f)
              if (cell->face(f)->at_boundary() &&
                  ids.count(cell->face(f)->boundary_id()) > 0)
                return {cell, f};
        return {};
      }

      const std::set<dealii::types::boundary_id> ids;
    };
  } // namespace io
} // namespace squeal

#endif
