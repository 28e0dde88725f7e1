// Dual mortar operators between two contact surfaces (see mortar.h).
//
// The slave side carries the Lagrange multipliers. Its dual shape functions
// are built face by face from the face mass matrix (psi = D_e M_e^-1 phi), so
// that D is diagonal and the multipliers can be condensed node by node. The
// mixed matrix M is integrated segment by segment: every slave face is
// clipped against the projection of each master face onto the slave face's
// plane, the overlap is cut into triangles and each carries a simplex Gauss
// rule. On planar faces this is exact, which is what the patch test needs.

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q_eulerian.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/numerics/rtree.h>

#include <squeal/contact/mortar.h>
#include <squeal/physics/polygon.h>

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <stdexcept>

namespace squeal
{
  namespace contact
  {
    using namespace dealii;
    using physics::clip_polygon;
    using physics::counter_clockwise;
    using physics::Polygon;
    using physics::polygon_quadrature;
    using physics::signed_area;

    namespace
    {
      // One contact face: its cell, the face's nodes (node number in the
      // surface, scalar shape-function index in the cell) and its plane.
      struct Face
      {
        DoFHandler<3>::active_cell_iterator                cell;
        unsigned int                                       face_no;
        std::vector<std::pair<unsigned int, unsigned int>> nodes;
        Point<3>                                           centre;
        Tensor<1, 3>          normal;  // outward, unit
        std::vector<Point<3>> outline; // vertices, cyclic
        BoundingBox<3>        box;
      };

      // The faces with @p id and their nodes (numbered on first sight).
      std::vector<Face>
      collect(const DoFHandler<3>     &dofs,
              const Mapping<3>        &mapping,
              const types::boundary_id id,
              std::vector<Point<3>>   &points,
              std::vector<NodeDofs>   &node_dofs)
      {
        const FiniteElement<3>                         &fe = dofs.get_fe();
        std::map<types::global_dof_index, unsigned int> node_of;
        std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
        std::vector<Face>                    faces;
        const QGauss<2>                      centre_rule(1);
        FEFaceValues<3>                      centre_values(mapping,
                                      fe,
                                      centre_rule,
                                      update_normal_vectors |
                                        update_quadrature_points);
        for (const auto &cell : dofs.active_cell_iterators())
          for (const unsigned int f : cell->face_indices())
            {
              if (!cell->face(f)->at_boundary() ||
                  cell->face(f)->boundary_id() != id)
                continue;
              Face face{cell, f, {}, {}, {}, {}, {}};
              cell->get_dof_indices(cell_dofs);
              // the node of every component-0 DoF on this face
              for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
                {
                  if (fe.system_to_component_index(i).first != 0 ||
                      !fe.has_support_on_face(i, f))
                    continue;
                  const unsigned int scalar =
                    fe.system_to_component_index(i).second;
                  auto [it, added] =
                    node_of.emplace(cell_dofs[i], points.size());
                  if (added)
                    {
                      NodeDofs d;
                      for (unsigned int j = 0; j < fe.n_dofs_per_cell(); ++j)
                        if (fe.system_to_component_index(j).second == scalar)
                          d[fe.system_to_component_index(j).first] =
                            cell_dofs[j];
                      node_dofs.push_back(d);
                      points.push_back(mapping.transform_unit_to_real_cell(
                        cell, fe.unit_support_point(i)));
                    }
                  face.nodes.emplace_back(it->second, scalar);
                }
              centre_values.reinit(cell, f);
              face.centre = centre_values.quadrature_point(0);
              face.normal = centre_values.normal_vector(0);
              // the mapped vertices: a displaced (Eulerian) mapping moves them
              const auto vertices = mapping.get_vertices(cell);
              for (const unsigned int v : {0u, 1u, 3u, 2u})
                face.outline.push_back(
                  vertices[GeometryInfo<3>::face_to_cell_vertices(f, v)]);
              face.box = BoundingBox<3>(face.outline);
              faces.push_back(face);
            }
        return faces;
      }

      // Unit coordinates of x in the cell, snapped onto the face's plane of
      // the reference cell (the point lies on the face up to the face's
      // curvature).
      Point<3>
      unit_on_face(const Mapping<3>                          &mapping,
                   const DoFHandler<3>::active_cell_iterator &cell,
                   const unsigned int                         face_no,
                   const Point<3>                            &x)
      {
        Point<3> u     = mapping.transform_real_to_unit_cell(cell, x);
        u[face_no / 2] = face_no % 2;
        return u;
      }
      // The dual basis of slave face SF (Wohlmuth 2000; Popp, Gee & Wall,
      // IJNME 79, 2009, eq. 25): A = D_e M_e^-1 with M_e the face's mass
      // matrix and D_e its lumped diagonal; adds the face's area, D_e, its
      // nodal normals and M_e (to MASS) into OP.
      FullMatrix<double>
      dual_basis(const Face                          &sf,
                 FEFaceValues<3>                     &fv,
                 const Quadrature<2>                 &face_rule,
                 MortarOperators                     &op,
                 std::vector<Eigen::Triplet<double>> &mass)
      {
        // Dual basis of this face: A = D_e M_e^-1.
        const unsigned int n_f = sf.nodes.size();
        fv.reinit(typename Triangulation<3>::cell_iterator(sf.cell),
                  sf.face_no);
        FullMatrix<double>  Me(n_f, n_f), A(n_f, n_f), Mi(n_f, n_f);
        std::vector<double> De(n_f, 0.);
        for (unsigned int q = 0; q < face_rule.size(); ++q)
          {
            op.slave_area += fv.JxW(q);
            for (unsigned int a = 0; a < n_f; ++a)
              {
                const double pa = fv.shape_value(sf.nodes[a].second, q);
                De[a] += pa * fv.JxW(q);
                op.normals[sf.nodes[a].first] +=
                  pa * fv.JxW(q) * fv.normal_vector(q);
                for (unsigned int b = 0; b < n_f; ++b)
                  Me(a, b) +=
                    pa * fv.shape_value(sf.nodes[b].second, q) * fv.JxW(q);
              }
          }
        Mi.invert(Me);
        for (unsigned int a = 0; a < n_f; ++a)
          {
            op.D[sf.nodes[a].first] += De[a];
            for (unsigned int b = 0; b < n_f; ++b)
              mass.emplace_back(sf.nodes[a].first, sf.nodes[b].first, Me(a, b));
            for (unsigned int b = 0; b < n_f; ++b)
              A(a, b) = De[a] * Mi(a, b);
          }

        return A;
      }

      // The segments of slave face SF with the master faces CANDIDATES
      // (its R-tree hits): each master face that faces it within reach,
      // clipped against it in its plane, and the mortar integrals
      // M_jl += int psi_j phi_l over the overlap (Puso & Laursen 2004's
      // segment-based integration) by the triangle rule TRI. Returns
      // whether some master face overlapped.
      bool
      integrate_segments(
        const Face                                                 &sf,
        const FullMatrix<double>                                   &A,
        const std::vector<Face>                                    &master,
        const std::vector<std::pair<BoundingBox<3>, unsigned int>> &candidates,
        const Mapping<3>                                           &mapping,
        const FiniteElement<3>                                     &scalar,
        const QGaussSimplex<2>                                     &tri,
        const double                                 search_distance,
        std::vector<std::map<unsigned int, double>> &M,
        std::vector<double>                         &own_psi,
        MortarOperators                             &op)
      {
        const unsigned int n_f = sf.nodes.size();
        // The slave face's plane: origin, two tangents.
        const Tensor<1, 3> n  = sf.normal;
        Tensor<1, 3>       e1 = sf.outline[1] - sf.outline[0];
        e1 -= (e1 * n) * n;
        e1 /= e1.norm();
        const Tensor<1, 3> e2       = cross_product_3d(n, e1);
        const auto         to_plane = [&](const Point<3> &x) {
          const Tensor<1, 3> d = x - sf.centre;
          return Point<2>(d * e1, d * e2);
        };
        Polygon own;
        for (const Point<3> &x : sf.outline)
          own.push_back(to_plane(x));
        own = counter_clockwise(own);
        // the point of the plane at X2, and the dual shape functions psi_a
        // of the face at a point XS of the plane
        const auto on_plane = [&](const Point<2> &x2) {
          return sf.centre + x2[0] * e1 + x2[1] * e2;
        };
        const auto dual_values = [&](const Point<3> &xs) {
          const Point<3> us = unit_on_face(mapping, sf.cell, sf.face_no, xs);
          std::vector<double> phi(n_f), psi(n_f, 0.);
          for (unsigned int b2 = 0; b2 < n_f; ++b2)
            phi[b2] = scalar.shape_value(sf.nodes[b2].second, us);
          for (unsigned int a2 = 0; a2 < n_f; ++a2)
            for (unsigned int b2 = 0; b2 < n_f; ++b2)
              psi[a2] += A(a2, b2) * phi[b2];
          return psi;
        };
        // int psi_j over the whole face as the segments integrate it (the
        // plane of the face's corners): the measure a fully covered node's
        // row of M sums to, also on a curved face, whose plane differs from
        // the face D_j is integrated on
        for (const auto &[x2, w] : polygon_quadrature(own, tri))
          {
            const std::vector<double> psi = dual_values(on_plane(x2));
            for (unsigned int a2 = 0; a2 < n_f; ++a2)
              own_psi[sf.nodes[a2].first] += w * psi[a2];
          }

        // master faces up to one face size behind the slave face count too
        // (build_mortar_operators() asks the R-tree as far)
        const double size =
          sf.box.side_length(0) + sf.box.side_length(1) + sf.box.side_length(2);
        bool in_reach = false;
        for (const auto &candidate : candidates)
          {
            const Face &mf = master[candidate.second];
            // facing each other, and within reach along the normal
            if (mf.normal * n > -0.2)
              continue;
            const double distance = (mf.centre - sf.centre) * n;
            if (distance > search_distance ||
                distance < -std::max(search_distance, size))
              continue;
            Polygon other;
            for (const Point<3> &x : mf.outline)
              other.push_back(to_plane(x));
            const Polygon overlap = clip_polygon(own, counter_clockwise(other));
            if (overlap.size() < 3 || std::abs(signed_area(overlap)) <
                                        1e-12 * std::abs(signed_area(own)))
              continue;
            in_reach = true;
            for (const auto &[x2, w] : polygon_quadrature(overlap, tri))
              {
                const Point<3> xs = on_plane(x2);
                // along the slave normal onto the master face's plane
                const double s =
                  ((mf.centre - xs) * mf.normal) / (n * mf.normal);
                const Point<3> xm = xs + s * n;
                const Point<3> um =
                  unit_on_face(mapping, mf.cell, mf.face_no, xm);
                op.covered_area += w;
                const std::vector<double> psi = dual_values(xs);
                for (unsigned int a2 = 0; a2 < n_f; ++a2)
                  for (const auto &[l, sc] : mf.nodes)
                    M[sf.nodes[a2].first][l] +=
                      w * psi[a2] * scalar.shape_value(sc, um);
              }
          }
        return in_reach;
      }

      // The nodal data of OP from the integrals: unit normals and tangents,
      // the rows of M (a node only partly over the master takes no part),
      // the initial weighted gaps.
      void
      finish_nodes(const std::vector<std::map<unsigned int, double>> &M,
                   const std::vector<double>                         &own_psi,
                   const double     search_distance,
                   MortarOperators &op)
      {
        const unsigned int n_s = op.n_slave();
        op.tangents1.resize(n_s);
        op.tangents2.resize(n_s);
        const double inf = std::numeric_limits<double>::infinity();
        for (unsigned int j = 0; j < n_s; ++j)
          {
            Tensor<1, 3> &nj = op.normals[j];
            nj /= nj.norm();
            Tensor<1, 3> t = (std::abs(nj[0]) < 0.9) ?
                               Tensor<1, 3>({1., 0., 0.}) :
                               Tensor<1, 3>({0., 1., 0.});
            t -= (t * nj) * nj;
            op.tangents1[j] = t / t.norm();
            op.tangents2[j] = cross_product_3d(nj, op.tangents1[j]);
            double row      = 0.;
            for (const auto &[l, m] : M[j])
              {
                op.M[j].emplace_back(l, m);
                row += m;
              }
            // A node only partly over the master (at the edge of the reach)
            // has no consistent weighted gap: it takes no part in contact.
            if (row < (1. - 1e-6) * own_psi[j])
              {
                op.gap0[j] = inf;
                continue;
              }
            // sum_l M_jl (x_j - x_l): independent of where the origin is, also
            // where row differs from D_j (a curved slave face: D_j is
            // integrated on the face, M on the plane of its corners)
            Tensor<1, 3> d;
            for (const auto &[l, m] : op.M[j])
              d += m * (op.slave_points[j] - op.master_points[l]);
            op.gap0[j] = -(d * nj);
            if (op.gap0[j] < -search_distance * op.D[j])
              throw std::runtime_error(
                "contact: the bodies overlap by " +
                std::to_string(-op.gap0[j] / op.D[j]) + " m at slave node (" +
                std::to_string(op.slave_points[j][0]) + ", " +
                std::to_string(op.slave_points[j][1]) + ", " +
                std::to_string(op.slave_points[j][2]) +
                "), more than the search distance allows");
          }
      }
    } // namespace

    Vector<double>
    MortarOperators::weighted_gaps(const Vector<double> &u) const
    {
      Vector<double> g(n_slave());
      for (unsigned int j = 0; j < n_slave(); ++j)
        g[j] = gap0[j] - weighted_slip(j, u, normals[j]);
      return g;
    }

    Vector<double>
    MortarOperators::nodal_pressure(const Vector<double> &z) const
    {
      Eigen::VectorXd rhs(n_slave());
      for (unsigned int j = 0; j < n_slave(); ++j)
        rhs[j] = D[j] * (std::isfinite(z[j]) ? z[j] : 0.);
      const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(
        slave_mass);
      const Eigen::VectorXd p = solver.solve(rhs);
      Vector<double>        out(n_slave());
      for (unsigned int j = 0; j < n_slave(); ++j)
        out[j] = p[j];
      return out;
    }

    double
    MortarOperators::weighted_slip(const unsigned int    j,
                                   const Vector<double> &u,
                                   const Tensor<1, 3>   &dir) const
    {
      double s = 0.;
      for (unsigned int c = 0; c < 3; ++c)
        {
          s += dir[c] * D[j] * u[slave_dofs[j][c]];
          for (const auto &[l, m] : M[j])
            s -= dir[c] * m * u[master_dofs[l][c]];
        }
      return s;
    }

    MortarOperators
    build_mortar_operators(const DoFHandler<3>     &dofs,
                           const Mapping<3>        &mapping,
                           const types::boundary_id slave_id,
                           const types::boundary_id master_id,
                           const double             search_distance,
                           const unsigned int       n_points)
    {
      MortarOperators         op;
      const std::vector<Face> slave =
        collect(dofs, mapping, slave_id, op.slave_points, op.slave_dofs);
      const std::vector<Face> master =
        collect(dofs, mapping, master_id, op.master_points, op.master_dofs);
      if (slave.empty() || master.empty())
        throw std::runtime_error(
          "contact: the " + std::string(slave.empty() ? "slave" : "master") +
          " surface (boundary id " +
          std::to_string(slave.empty() ? slave_id : master_id) +
          ") has no faces");
      const unsigned int n_s = op.n_slave();
      op.D.reinit(n_s);
      op.gap0.reinit(n_s);
      op.M.assign(n_s, {});
      op.normals.assign(n_s, Tensor<1, 3>());
      std::vector<std::map<unsigned int, double>> M(n_s);
      std::vector<double>                         own_psi(n_s, 0.);
      std::vector<Eigen::Triplet<double>>         mass;

      const FiniteElement<3> &fe     = dofs.get_fe();
      const FiniteElement<3> &scalar = fe.base_element(0);
      const QGauss<2>         face_rule(scalar.degree + 2);
      FEFaceValues<3>         fv(mapping,
                         scalar,
                         face_rule,
                         update_values | update_JxW_values |
                           update_normal_vectors);
      const QGaussSimplex<2>  tri(std::min(std::max(n_points, 1u), 4u));

      // The master faces' bounding boxes in an R-tree (deal.II's
      // boost::geometry wrapper): each slave face asks only the boxes its
      // reach intersects.
      std::vector<std::pair<BoundingBox<3>, unsigned int>> boxes;
      for (unsigned int m = 0; m < master.size(); ++m)
        boxes.emplace_back(master[m].box, m);
      const auto tree = pack_rtree(boxes);

      unsigned int faces_in_reach = 0;
      for (const Face &sf : slave)
        {
          const FullMatrix<double> A = dual_basis(sf, fv, face_rule, op, mass);

          // Master faces up to one face size behind the slave face count
          // too, so that overlapping bodies are reported, not ignored.
          const double size = sf.box.side_length(0) + sf.box.side_length(1) +
                              sf.box.side_length(2);
          BoundingBox<3> reach = sf.box;
          reach.extend(std::max(search_distance, size));
          std::vector<std::pair<BoundingBox<3>, unsigned int>> candidates;
          tree.query(boost::geometry::index::intersects(reach),
                     std::back_inserter(candidates));
          // in the master faces' order, so that M is summed in a fixed order
          std::sort(candidates.begin(),
                    candidates.end(),
                    [](const auto &a, const auto &b) {
                      return a.second < b.second;
                    });
          faces_in_reach += integrate_segments(sf,
                                               A,
                                               master,
                                               candidates,
                                               mapping,
                                               scalar,
                                               tri,
                                               search_distance,
                                               M,
                                               own_psi,
                                               op);
        }
      if (faces_in_reach == 0)
        throw std::runtime_error(
          "contact: no slave face (boundary id " + std::to_string(slave_id) +
          ") has a master face (boundary id " + std::to_string(master_id) +
          ") within the search distance of " + std::to_string(search_distance) +
          " m");

      op.slave_id        = slave_id;
      op.master_id       = master_id;
      op.search_distance = search_distance;
      op.n_points        = n_points;
      op.slave_face_size = std::numeric_limits<double>::max();
      for (const Face &sf : slave)
        for (unsigned int a = 0; a < 4; ++a)
          op.slave_face_size =
            std::min(op.slave_face_size,
                     sf.outline[a].distance(sf.outline[(a + 1) % 4]));
      op.slave_mass.resize(n_s, n_s);
      op.slave_mass.setFromTriplets(mass.begin(), mass.end());
      finish_nodes(M, own_psi, search_distance, op);
      return op;
    }

    double
    largest_tangential_slip(const MortarOperators &op,
                            const Vector<double>  &u,
                            const Vector<double>  &u_reference)
    {
      Vector<double> du(u);
      du -= u_reference;
      double largest = 0.;
      for (unsigned int j = 0; j < op.n_slave(); ++j)
        if (std::isfinite(op.gap0[j]))
          largest =
            std::max(largest,
                     std::hypot(op.weighted_slip(j, du, op.tangents1[j]),
                                op.weighted_slip(j, du, op.tangents2[j])) /
                       op.D[j]);
      return largest;
    }

    MortarOperators
    build_mortar_operators_deformed(const DoFHandler<3>     &dofs,
                                    const Vector<double>    &u,
                                    const types::boundary_id slave_id,
                                    const types::boundary_id master_id,
                                    const double             search_distance,
                                    const unsigned int       n_points)
    {
      const MappingQEulerian<3, Vector<double>> mapping(dofs.get_fe().degree,
                                                        dofs,
                                                        u);
      MortarOperators                           op = build_mortar_operators(
        dofs, mapping, slave_id, master_id, search_distance, n_points);
      // g(v) = g0' + B'(v - u): the gaps measured from the configuration u
      for (unsigned int j = 0; j < op.n_slave(); ++j)
        if (std::isfinite(op.gap0[j]))
          op.gap0[j] += op.weighted_slip(j, u, op.normals[j]);
      return op;
    }

    MortarOperators
    merge_mortar_operators(const std::vector<MortarOperators> &pairs)
    {
      if (pairs.empty())
        throw std::runtime_error("merge_mortar_operators: no contact pair");
      if (pairs.size() == 1)
        return pairs.front();
      MortarOperators all;
      all.slave_id        = pairs.front().slave_id;
      all.master_id       = pairs.front().master_id;
      all.search_distance = pairs.front().search_distance;
      all.n_points        = pairs.front().n_points;
      all.n_pairs         = pairs.size();
      all.slave_face_size = 1e300;
      unsigned int n_s    = 0;
      for (const auto &op : pairs)
        n_s += op.n_slave();
      all.D.reinit(n_s);
      all.gap0.reinit(n_s);
      std::vector<Eigen::Triplet<double>> mass;
      unsigned int                        s0 = 0, pair_index = 0;
      for (const auto &op : pairs)
        {
          const unsigned int m0 = all.master_points.size();
          for (unsigned int j = 0; j < op.n_slave(); ++j)
            {
              all.slave_points.push_back(op.slave_points[j]);
              all.slave_dofs.push_back(op.slave_dofs[j]);
              all.slave_pair.push_back(pair_index);
              all.normals.push_back(op.normals[j]);
              all.tangents1.push_back(op.tangents1[j]);
              all.tangents2.push_back(op.tangents2[j]);
              all.D[s0 + j]                                    = op.D[j];
              all.gap0[s0 + j]                                 = op.gap0[j];
              std::vector<std::pair<unsigned int, double>> row = op.M[j];
              for (auto &[l, value] : row)
                l += m0;
              all.M.push_back(std::move(row));
            }
          all.master_points.insert(all.master_points.end(),
                                   op.master_points.begin(),
                                   op.master_points.end());
          all.master_dofs.insert(all.master_dofs.end(),
                                 op.master_dofs.begin(),
                                 op.master_dofs.end());
          for (int k = 0; k < op.slave_mass.outerSize(); ++k)
            for (Eigen::SparseMatrix<double>::InnerIterator it(op.slave_mass,
                                                               k);
                 it;
                 ++it)
              mass.emplace_back(s0 + it.row(), s0 + it.col(), it.value());
          all.slave_face_size =
            std::min(all.slave_face_size, op.slave_face_size);
          all.covered_area += op.covered_area;
          all.slave_area += op.slave_area;
          s0 += op.n_slave();
          ++pair_index;
        }
      all.slave_mass.resize(n_s, n_s);
      all.slave_mass.setFromTriplets(mass.begin(), mass.end());
      return all;
    }

    bool
    refresh_segmentation(MortarOperators      &op,
                         const DoFHandler<3>  &dofs,
                         const Vector<double> &u,
                         Vector<double>       &u_segmented,
                         const double          fraction)
    {
      if (u_segmented.size() != u.size())
        u_segmented.reinit(u.size());
      if (!(fraction > 0.) || largest_tangential_slip(op, u, u_segmented) <=
                                fraction * op.slave_face_size)
        return false;
      if (op.n_pairs > 1)
        throw std::runtime_error(
          "the slip since the last mortar segmentation exceeds Preload/"
          "Segmentation refresh, and rebuilding it on the deformed surfaces "
          "is done for one contact pair only; this scene has " +
          std::to_string(op.n_pairs) +
          " (set Segmentation refresh = 0 "
          "for small sliding)");
      op = build_mortar_operators_deformed(
        dofs, u, op.slave_id, op.master_id, op.search_distance, op.n_points);
      u_segmented = u;
      return true;
    }
  } // namespace contact
} // namespace squeal
