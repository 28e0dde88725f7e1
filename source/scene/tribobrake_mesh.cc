// The TriboBrake mesher. The disc is built vertex by vertex in polar
// coordinates (not by merging deal.II's generators) so that every cell
// subtends the same angle, which keeps the two members of each doublet
// equal, and so that the pad's face and the disc's face stay two separate
// sets of vertices: merge_triangulations would glue coincident vertices.

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <squeal/scene/tribobrake_mesh.h>

#include <cmath>

namespace squeal
{
  namespace scene
  {
    namespace tribobrake
    {
      using namespace dealii;

      namespace
      {
        // Appends the hexahedra of a structured block given the vertex index
        // function idx(i, j, k) over n0 x n1 x n2 cells.
        template <typename Index>
        void
        add_block_cells(const unsigned int n0,
                        const unsigned int n1,
                        const unsigned int n2,
                        const Index       &idx,
                        const std::function<types::material_id(unsigned int)>
                                                 &material_of_layer,
                        std::vector<CellData<3>> &cells)
        {
          for (unsigned int k = 0; k < n2; ++k)
            for (unsigned int j = 0; j < n1; ++j)
              for (unsigned int i = 0; i < n0; ++i)
                {
                  CellData<3> c;
                  c.vertices    = {idx(i, j, k),
                                   idx(i + 1, j, k),
                                   idx(i, j + 1, k),
                                   idx(i + 1, j + 1, k),
                                   idx(i, j, k + 1),
                                   idx(i + 1, j, k + 1),
                                   idx(i, j + 1, k + 1),
                                   idx(i + 1, j + 1, k + 1)};
                  c.material_id = material_of_layer(k);
                  cells.push_back(c);
                }
        }
      } // namespace

      void
      make_tribobrake_mesh(const parameters::Geometry &g,
                           const parameters::Mesh     &m,
                           const bool                  with_pad_and_support,
                           Triangulation<3>           &tria)
      {
        std::vector<Point<3>>    vertices;
        std::vector<CellData<3>> cells;

        // Disc: xi along r, eta along theta, zeta along z (right-handed).
        const unsigned int nt = m.disc_cells_circumference,
                           nr = m.disc_cells_radial,
                           nz = m.disc_cells_thickness;
        for (unsigned int k = 0; k <= nz; ++k)
          for (unsigned int j = 0; j <= nr; ++j)
            for (unsigned int i = 0; i < nt; ++i)
              {
                const double r =
                  g.disc_inner_radius +
                  (g.disc_outer_radius - g.disc_inner_radius) * j / nr;
                const double t = 2. * numbers::PI * i / nt;
                vertices.emplace_back(r * std::cos(t),
                                      r * std::sin(t),
                                      -g.disc_thickness +
                                        g.disc_thickness * k / nz);
              }
        const auto disc_index =
          [&](unsigned int j, unsigned int i, unsigned int k) {
            return (k * (nr + 1) + j) * nt + (i % nt);
          };
        add_block_cells(
          nr,
          nt,
          nz,
          disc_index,
          [](unsigned int) { return material::disc; },
          cells);

        // Pad and support: one block, the pad's layers first.
        const unsigned int ns = m.pad_cells_side, np = m.pad_cells_thickness,
                           nl = m.support_cells_length;
        if (with_pad_and_support)
          {
            const unsigned int  offset = vertices.size();
            std::vector<double> z_levels;
            for (unsigned int k = 0; k <= np; ++k)
              z_levels.push_back(g.pad_size * k / np);
            for (unsigned int k = 1; k <= nl; ++k)
              z_levels.push_back(g.pad_size + g.support_length * k / nl);
            for (const double z : z_levels)
              for (unsigned int j = 0; j <= ns; ++j)
                for (unsigned int i = 0; i <= ns; ++i)
                  vertices.emplace_back(g.pad_radius - g.pad_size / 2 +
                                          g.pad_size * i / ns,
                                        -g.pad_size / 2 + g.pad_size * j / ns,
                                        z);
            const auto block_index =
              [&](unsigned int i, unsigned int j, unsigned int k) {
                return offset + (k * (ns + 1) + j) * (ns + 1) + i;
              };
            add_block_cells(
              ns,
              ns,
              np + nl,
              block_index,
              [np](unsigned int k) {
                return k < np ? material::pad : material::support;
              },
              cells);
          }

        tria.create_triangulation(vertices, cells, SubCellData());

        for (const auto &cell : tria.active_cell_iterators())
          if (cell->material_id() == material::disc)
            cell->set_all_manifold_ids(disc_manifold);
        tria.set_manifold(disc_manifold, CylindricalManifold<3>(2));

        const auto set_boundary_ids = [&]() {
          const double tol = 1e-6 * g.pad_size;
          for (const auto &cell : tria.active_cell_iterators())
            for (const auto f : cell->face_indices())
              if (cell->face(f)->at_boundary())
                {
                  const Point<3>     c  = cell->face(f)->center();
                  types::boundary_id id = boundary::free;
                  if (cell->material_id() == material::disc)
                    {
                      bool inner = true;
                      for (const auto v : cell->face(f)->vertex_indices())
                        inner =
                          inner &&
                          std::abs(std::hypot(cell->face(f)->vertex(v)[0],
                                              cell->face(f)->vertex(v)[1]) -
                                   g.disc_inner_radius) < tol;
                      if (inner)
                        id = boundary::clamped;
                      else if (std::abs(c[2]) < tol)
                        id = boundary::disc_contact;
                    }
                  else if (cell->material_id() == material::pad &&
                           std::abs(c[2]) < tol)
                    id = boundary::pad_contact;
                  else if (cell->material_id() == material::support &&
                           std::abs(c[2] - g.pad_size - g.support_length) < tol)
                    id = boundary::support_top;
                  cell->face(f)->set_boundary_id(id);
                }
        };
        set_boundary_ids();

        // Local refinement of the disc under the pad footprint (plus a margin
        // of half a pad), through the thickness.
        for (unsigned int cycle = 0; cycle < m.disc_refinements_under_pad;
             ++cycle)
          {
            const double half = g.pad_size;
            for (const auto &cell : tria.active_cell_iterators())
              if (cell->material_id() == material::disc)
                {
                  const Point<3> c = cell->center();
                  if (std::abs(c[0] - g.pad_radius) < half &&
                      std::abs(c[1]) < half)
                    cell->set_refine_flag();
                }
            tria.execute_coarsening_and_refinement();
          }
        set_boundary_ids();
      }

      io::NamedSets
      tribobrake_sets(const Triangulation<3> &tria)
      {
        io::NamedSets sets;
        sets.source = "the TriboBrake generator";
        sets.collect_from_ids(tria,
                              {{material::disc, "disc"},
                               {material::pad, "pad"},
                               {material::support, "support"}},
                              {{boundary::clamped, "disc hub"},
                               {boundary::pad_contact, "pad face"},
                               {boundary::disc_contact, "disc face"},
                               {boundary::support_top, "support top"}});
        return sets;
      }
    } // namespace tribobrake
  }   // namespace scene
} // namespace squeal
