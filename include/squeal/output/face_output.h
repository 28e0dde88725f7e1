#ifndef squeal_output_face_output_h
#define squeal_output_face_output_h

/**
 * @file
 * ParaView output of one boundary surface (the pad's contact face): deal.II's
 * DataOutFaces restricted to the faces of one boundary id, so that contact
 * fields (pressure, traction, status) are written on the surface they live on.
 */

#include <deal.II/numerics/data_out_faces.h>

namespace squeal
{
  namespace output
  {
    /** DataOutFaces over the boundary faces with id @p id only. */
    class BoundaryFaceOutput : public dealii::DataOutFaces<3>
    {
    public:
      /** @param id the boundary id of the faces to write */
      explicit BoundaryFaceOutput(const dealii::types::boundary_id id)
        : dealii::DataOutFaces<3>(false)
        , id(id)
      {}

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
                  cell->face(f)->boundary_id() == id)
                return {cell, f};
        return {};
      }

      const dealii::types::boundary_id id;
    };
  } // namespace output
} // namespace squeal

#endif
