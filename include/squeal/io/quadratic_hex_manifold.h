#ifndef squeal_io_quadratic_hex_manifold_h
#define squeal_io_quadratic_hex_manifold_h

/**
 * @file
 * The curved geometry of one 20-node hexahedron (Abaqus/CalculiX C3D20,
 * C3D20R) as a deal.II chart manifold, so that refinement and a
 * higher-degree MappingQ follow the element's mid-side nodes instead of the
 * chords between its corners (io::read_mesh_file() attaches one per curved
 * element).
 */

#include <deal.II/base/point.h>
#include <deal.II/grid/manifold.h>

#include <array>
#include <memory>

namespace squeal
{
  namespace io
  {
    /**
     * push_forward maps the reference cube [-1, 1]^3 through the 20-node
     * serendipity shape functions (O. C. Zienkiewicz, R. L. Taylor, The
     * Finite Element Method, vol. 1, 6th ed., 2005, § 6.4.1); pull_back
     * inverts it by Newton's method from the cell centre. Lengths in m.
     */
    class QuadraticHexManifold : public dealii::ChartManifold<3, 3, 3>
    {
    public:
      /** @param x the 20 nodes in Abaqus order (corners 1-8, then the
       * mid-side nodes of edges 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8, 8-5,
       * 1-5, 2-6, 3-7, 4-8) [m] */
      explicit QuadraticHexManifold(const std::array<dealii::Point<3>, 20> &x);

      /** A copy (deal.II's manifold interface). */
      std::unique_ptr<dealii::Manifold<3, 3>>
      clone() const override;

      /** The point [m] of the reference point @p s in [-1, 1]^3. */
      dealii::Point<3>
      push_forward(const dealii::Point<3> &s) const override;

      /** d x / d s at @p s [m]. */
      dealii::DerivativeForm<1, 3, 3>
      push_forward_gradient(const dealii::Point<3> &s) const override;

      /**
       * The reference point of @p p [m]: Newton's method to 1e-14 of the
       * element's size.
       * @throws dealii::ExceptionBase if it does not converge in 50 steps
       * (a strongly distorted element).
       */
      dealii::Point<3>
      pull_back(const dealii::Point<3> &p) const override;

    private:
      std::array<dealii::Point<3>, 20> x;
    };
  } // namespace io
} // namespace squeal

#endif
