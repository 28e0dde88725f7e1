#ifndef squeal_analyses_mode_naming_h
#define squeal_analyses_mode_naming_h

/**
 * @file
 * Names of disc modes in the brake-squeal convention of the thesis'
 * Table 3.1, "(circles,diameters+-)": nodal circles, then nodal diameters;
 * "+" when the reference point of the disc
 * (the pad's centre, at theta = 0 of the disc's polar frame) sits on an
 * antinode of the axial displacement, "-" on a node (Massi's thesis, 2006,
 * Table 3.1; Kinkaid, O'Reilly & Papadopoulos, J. Sound Vib. 267, 2003).
 */

#include <squeal/physics/structural_model.h>
#include <squeal/scene/scene.h>

#include <string>
#include <vector>

namespace squeal
{
  namespace analyses
  {
    /**
     * The name of a disc mode from the axial displacement of the disc's
     * naming face: "(m,n+)" or "(m,n-)" with n the dominant angular harmonic
     * of the axial displacement on the face's outer rim and m the sign
     * changes along the radius through the rim's largest amplitude;
     * "in-plane" when the axial motion is small against the in-plane
     * motion; "" when the naming face has no vertex. Collective over the
     * model's communicator.
     * @param model the structure (DoFs, scene, locally owned DoFs)
     * @param disc a body of the scene declared a disc (its axis, centre,
     * reference direction and naming face)
     * @param re, im the mode's real and imaginary parts (n_dofs, ghosted or
     * owned entries readable) [m, any scale]
     */
    std::string
    disc_mode_name(const physics::StructuralModel &model,
                   const scene::Body              &disc,
                   const physics::PETScVector     &re,
                   const physics::PETScVector     &im);

    /**
     * The name of the mode re + i im of @p model at the parameter point
     * @p values: disc_mode_name() when the scene's disc carries more than
     * half of the mode's kinetic energy, else the name of the body that
     * carries the most of it besides the disc, followed with
     * @p with_direction by the axis (`x`, `y` or `z`) along which that
     * body's DoFs move most (sum of squares), as `support y`. With
     * @p shares, each body's share of the kinetic energy in [0, 1] (scene
     * order, summing to 1). Collective over the model's communicator.
     * @param re, im the mode's real and imaginary parts (n_dofs, locally
     * owned entries) [m, any scale]
     * @param energy the mode's kinetic energy by body, as
     * physics::kinetic_energy_by_body() gives it (computed here when null)
     */
    std::string
    mode_name(const physics::StructuralModel &model,
              const parameters::ScalarPoint  &values,
              const physics::PETScVector     &re,
              const physics::PETScVector     &im,
              std::vector<double>            *shares         = nullptr,
              bool                            with_direction = false,
              const std::vector<double>      *energy         = nullptr);
  } // namespace analyses
} // namespace squeal

#endif
