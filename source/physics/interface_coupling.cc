// Segment-based (mortar) integration of the linear friction interface. Both
// contact faces lie in the slave (pad) face's plane, and every face is seen
// in that plane's coordinates (scene::ContactPair::to_plane): each pad face
// is clipped against
// the disc faces it overlaps, every overlap polygon is cut into a fan of
// triangles, and a Gauss rule on each triangle gives points whose reference
// coordinates are found in both cells. Exact integration over the overlap is
// what makes the mortar coupling pass the patch test where node-to-segment
// collocation does not.

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>

#include <squeal/physics/interface_coupling.h>
#include <squeal/physics/polygon.h>

#include <array>
#include <cmath>
#include <set>
#include <stdexcept>

namespace squeal
{
  namespace physics
  {
    using namespace dealii;

    namespace
    {
      // The points a line's hanging children add between its two vertices,
      // in the order from vertex(0) to vertex(1).
      void
      hanging_points(const typename DoFHandler<3>::line_iterator &line,
                     std::vector<Point<3>>                       &out)
      {
        if (!line->has_children())
          return;
        hanging_points(line->child(0), out);
        out.push_back(line->child(0)->vertex(1));
        hanging_points(line->child(1), out);
      }

      // The outline of a face in the pair's plane, counter-clockwise. With
      // @p follow_hanging, the vertices that refined neighbours hang on its
      // edges are included: on the curved disc face a coarse face's chord
      // and its refined neighbours' chords would otherwise leave slivers
      // uncovered (or covered twice) beside every hanging edge. Such an
      // outline may have a shallow dent, so it is star-shaped about its
      // centroid but not always convex (see fan()).
      Polygon
      face_outline(const typename DoFHandler<3>::face_iterator &face,
                   const scene::ContactPair                    &pair,
                   const bool                                   follow_hanging)
      {
        // deal.II numbers quadrilateral vertices lexicographically; the
        // outline 0 -> 1 -> 3 -> 2 runs along lines 2, 1, 3 (backwards) and
        // 0 (backwards).
        const std::array<std::pair<unsigned int, bool>, 4> edges{
          {{2u, true}, {1u, true}, {3u, false}, {0u, false}}};
        const std::array<unsigned int, 4> start{{0u, 1u, 3u, 2u}};
        Polygon                           p;
        for (unsigned int e = 0; e < 4; ++e)
          {
            p.push_back(pair.to_plane(face->vertex(start[e])));
            if (!follow_hanging)
              continue;
            std::vector<Point<3>> between;
            hanging_points(face->line(edges[e].first), between);
            if (!edges[e].second)
              std::reverse(between.begin(), between.end());
            for (const auto &x : between)
              p.push_back(pair.to_plane(x));
          }
        return counter_clockwise(p);
      }

      // Convex pieces of a star-shaped outline for the Sutherland-Hodgman
      // clipping: a plain quadrilateral face itself, else the triangles from
      // the centroid to each edge.
      std::vector<Polygon>
      fan(const Polygon &p)
      {
        if (p.size() == 4)
          return {p};
        Point<2> c;
        for (const auto &x : p)
          c += x / double(p.size());
        std::vector<Polygon> pieces;
        for (unsigned int i = 0; i < p.size(); ++i)
          pieces.push_back({c, p[i], p[(i + 1) % p.size()]});
        return pieces;
      }

      struct FaceRef
      {
        DoFHandler<3>::active_cell_iterator cell;
        unsigned int                        face;
        Polygon                             outline;
        BoundingBox<2>                      box;
      };

      std::vector<FaceRef>
      contact_faces(const DoFHandler<3>      &dof_handler,
                    const types::boundary_id  id,
                    const scene::ContactPair &pair,
                    const bool                only_owned,
                    const bool                follow_hanging)
      {
        std::vector<FaceRef> faces;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (!only_owned || cell->is_locally_owned())
            for (const auto f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() == id)
                {
                  FaceRef               r{cell,
                            f,
                            face_outline(cell->face(f), pair, follow_hanging),
                            {}};
                  std::vector<Point<2>> pts(r.outline.begin(), r.outline.end());
                  r.box = BoundingBox<2>(pts);
                  faces.push_back(r);
                }
        return faces;
      }

      bool
      boxes_overlap(const BoundingBox<2> &a, const BoundingBox<2> &b)
      {
        const auto &pa = a.get_boundary_points(), &pb = b.get_boundary_points();
        for (unsigned int d = 0; d < 2; ++d)
          if (pa.second[d] < pb.first[d] || pb.second[d] < pa.first[d])
            return false;
        return true;
      }

      bool
      to_unit(const Mapping<3>                          &mapping,
              const DoFHandler<3>::active_cell_iterator &cell,
              const Point<3>                            &p,
              Point<3>                                  &unit)
      {
        try
          {
            unit = mapping.transform_real_to_unit_cell(cell, p);
          }
        catch (const typename Mapping<3>::ExcTransformationFailed &)
          {
            return false;
          }
        return GeometryInfo<3>::is_inside_unit_cell(unit, 1e-6);
      }
    } // namespace

    std::vector<CouplingPoint>
    interface_quadrature(const DoFHandler<3>      &dof_handler,
                         const Mapping<3>         &mapping,
                         const scene::ContactPair &pair,
                         const std::string        &rule,
                         const unsigned int        n_points)
    {
      const auto pad_faces =
        contact_faces(dof_handler, pair.slave, pair, true, false);
      const auto disc_faces =
        contact_faces(dof_handler, pair.master, pair, false, true);

      std::vector<CouplingPoint> points;
      double                     covered = 0, pad_area = 0;
      for (const auto &pf : pad_faces)
        {
          pad_area += std::abs(signed_area(pf.outline));
          if (rule == "nodal")
            {
              // Gauss-Lobatto points of the pad face, each on the disc face
              // below it.
              const QGaussLobatto<2> q(n_points);
              FEFaceValues<3>        fv(mapping,
                                 dof_handler.get_fe(),
                                 q,
                                 update_quadrature_points | update_JxW_values);
              fv.reinit(pf.cell, pf.face);
              for (unsigned int k = 0; k < q.size(); ++k)
                {
                  const Point<3> x = fv.quadrature_point(k);
                  Point<3>       pu, du;
                  const bool     on_pad = to_unit(mapping, pf.cell, x, pu);
                  Assert(on_pad, ExcInternalError());
                  (void)on_pad;
                  for (const auto &df : disc_faces)
                    if (df.box.point_inside(pair.to_plane(x), 1e-9) &&
                        to_unit(mapping, df.cell, x, du))
                      {
                        points.push_back({pf.cell, df.cell, pu, du, fv.JxW(k)});
                        covered += fv.JxW(k);
                        break;
                      }
                }
              continue;
            }
          // deal.II 9.4 has simplex Gauss rules of 1-4 points per direction
          // (exact to degree 7; a larger request gave an empty rule and no
          // coupling at all): degree 1-3 faces are integrated exactly.
          const QGaussSimplex<2> tri(std::min(n_points, 4u));
          AssertThrow(tri.size() > 0, ExcMessage("empty simplex rule"));
          for (const auto &df : disc_faces)
            {
              if (!boxes_overlap(pf.box, df.box))
                continue;
              for (const Polygon &piece : fan(df.outline))
                {
                  const Polygon overlap = clip_polygon(piece, pf.outline);
                  if (overlap.size() < 3)
                    continue;
                  const double area = std::abs(signed_area(overlap));
                  if (area < 1e-14 * std::abs(signed_area(pf.outline)))
                    continue;
                  for (const auto &[x2, w] : polygon_quadrature(overlap, tri))
                    {
                      const Point<3> x = pair.from_plane(x2);
                      Point<3>       pu, du;
                      // The straight-sided outline can stray outside a
                      // curved disc cell by a sliver; the point then still
                      // belongs to this cell's polynomial extension.
                      pu = mapping.transform_real_to_unit_cell(pf.cell, x);
                      du = mapping.transform_real_to_unit_cell(df.cell, x);
                      points.push_back({pf.cell, df.cell, pu, du, w});
                      covered += w;
                    }
                }
            }
        }
      if (!pad_faces.empty() && covered < (1 - 1e-6) * pad_area)
        throw std::runtime_error(
          "contact pair '" + pair.name + "': only " +
          std::to_string(100 * covered / pad_area) +
          " % of the slave face lies over the master face; check that the "
          "two face sets face each other (Geometry/Pad radius for the "
          "TriboBrake)");
      return points;
    }

    void
    add_interface_sparsity(const std::vector<CouplingPoint> &points,
                           const AffineConstraints<double>  &constraints,
                           DynamicSparsityPattern           &dsp)
    {
      std::set<std::pair<DoFHandler<3>::active_cell_iterator,
                         DoFHandler<3>::active_cell_iterator>>
        pairs;
      for (const auto &p : points)
        pairs.emplace(p.pad_cell, p.disc_cell);
      for (const auto &[pad, disc] : pairs)
        {
          const unsigned int n = pad->get_fe().n_dofs_per_cell();
          std::vector<types::global_dof_index> dofs(2 * n), d(n);
          pad->get_dof_indices(d);
          std::copy(d.begin(), d.end(), dofs.begin());
          disc->get_dof_indices(d);
          std::copy(d.begin(), d.end(), dofs.begin() + n);
          constraints.add_entries_local_to_global(dofs, dsp, false);
        }
    }

    void
    assemble_interface(const std::vector<CouplingPoint> &points,
                       const AffineConstraints<double>  &constraints,
                       const double                      k,
                       const double                      k_s,
                       const scene::ContactPair         &pair,
                       PETScWrappers::MPI::SparseMatrix &K_n,
                       PETScWrappers::MPI::SparseMatrix &K_t,
                       PETScWrappers::MPI::SparseMatrix *K_st)
    {
      // Points come grouped by (pad cell, disc cell) pair: accumulate each
      // pair's local matrices and distribute them once.
      if (points.empty())
        return;
      const Tensor<1, 3> &tangent = pair.sliding;
      const Tensor<1, 3> &normal  = pair.normal;
      const auto         &fe      = points[0].pad_cell->get_fe();
      const unsigned int  n       = fe.n_dofs_per_cell();
      FullMatrix<double>  local_n(2 * n, 2 * n), local_t(2 * n, 2 * n),
        local_s(2 * n, 2 * n);
      std::vector<double>                g(2 * n), f(2 * n);
      std::array<std::vector<double>, 2> h{
        {std::vector<double>(2 * n), std::vector<double>(2 * n)}};
      std::vector<types::global_dof_index> dofs(2 * n), d(n);

      const auto flush = [&](const CouplingPoint &p) {
        p.pad_cell->get_dof_indices(d);
        std::copy(d.begin(), d.end(), dofs.begin());
        p.disc_cell->get_dof_indices(d);
        std::copy(d.begin(), d.end(), dofs.begin() + n);
        constraints.distribute_local_to_global(local_n, dofs, K_n);
        constraints.distribute_local_to_global(local_t, dofs, K_t);
        if (K_st)
          constraints.distribute_local_to_global(local_s, dofs, *K_st);
        local_n = 0;
        local_t = 0;
        local_s = 0;
      };

      for (unsigned int q = 0; q < points.size(); ++q)
        {
          const CouplingPoint &p = points[q];
          // g: gap (u(disc) - u(pad)) . n; f: friction force pattern, -t on
          // the pad rows (internal force of the traction +mu p t on the pad)
          // and +t on the disc rows.
          for (unsigned int i = 0; i < n; ++i)
            {
              const unsigned int c  = fe.system_to_component_index(i).first;
              const double       vp = fe.shape_value(i, p.pad_unit);
              const double       vd = fe.shape_value(i, p.disc_unit);
              g[i]                  = -normal[c] * vp;
              g[n + i]              = normal[c] * vd;
              f[i]                  = -tangent[c] * vp;
              f[n + i]              = tangent[c] * vd;
              // h_a: in-plane relative displacement (u(disc) - u(pad)) . a
              for (unsigned int a = 0; a < 2; ++a)
                {
                  h[a][i]     = -pair.plane_axes[a][c] * vp;
                  h[a][n + i] = pair.plane_axes[a][c] * vd;
                }
            }
          const double kw = k * p.weight, sw = k_s * p.weight;
          for (unsigned int i = 0; i < 2 * n; ++i)
            for (unsigned int j = 0; j < 2 * n; ++j)
              {
                if (g[j] != 0.)
                  {
                    local_n(i, j) += kw * g[i] * g[j];
                    local_t(i, j) += kw * f[i] * g[j];
                  }
                if (K_st)
                  local_s(i, j) += sw * (h[0][i] * h[0][j] + h[1][i] * h[1][j]);
              }
          const bool last = q + 1 == points.size() ||
                            points[q + 1].pad_cell != p.pad_cell ||
                            points[q + 1].disc_cell != p.disc_cell;
          if (last)
            flush(p);
        }
    }
  } // namespace physics
} // namespace squeal
