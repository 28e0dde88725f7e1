// The scene's springs to ground: each spread over the body's face within its
// attachment radius as a Winkler layer with cosine-bell weights, or at the
// nearest node when no face is in reach.

#include <deal.II/base/qprojector.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <squeal/physics/structural_model.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace squeal
{
  namespace physics
  {
    using namespace dealii;

    void
    StructuralModel::add_springs(const scene::SpringSet &s,
                                 PETScMatrix            &K,
                                 const double            k,
                                 ConditionalOStream     &pcout)
    {
      if (s.to_body)
        {
          // k d d^T on the relative displacement of the two nodes
          const auto         pairs = two_body_spring_nodes(s);
          FullMatrix<double> local(6, 6);
          for (unsigned int i = 0; i < 6; ++i)
            for (unsigned int j = 0; j < 6; ++j)
              local(i, j) = (i / 3 == j / 3 ? k : -k) * s.direction[i % 3] *
                            s.direction[j % 3];
          for (const auto &dofs : pairs)
            if (locally_owned_dofs.is_element(dofs[0]))
              {
                std::vector<types::global_dof_index> d(dofs.begin(),
                                                       dofs.end());
                constraints.distribute_local_to_global(local, d, K);
              }
          K.compress(VectorOperation::add);
          pcout << "Springs '" << s.name << "': " << pairs.size() << " x " << k
                << " N/m along (" << s.direction
                << ") between two bodies, node to node" << std::endl;
          return;
        }
      const std::vector<Point<3>> &stations = s.stations;
      if (stations.empty())
        return;
      if (s.station_normals.size() != stations.size())
        throw std::runtime_error("springs '" + s.name +
                                 "': one face normal per station needed");
      // the components the springs act along (for the point springs: one)
      std::vector<unsigned int> acting;
      for (unsigned int c = 0; c < 3; ++c)
        if (s.direction[c] != 0.)
          acting.push_back(c);

      std::vector<double>               total(stations.size(), 0.);
      std::vector<unsigned int>         faces_per_spring(stations.size(), 0);
      const std::vector<SpringFaceRule> rules =
        spring_face_rules(s, total, faces_per_spring);
      {
        const std::vector<double> local = total;
        Utilities::MPI::sum(local, comm, total);
      }
      assemble_spread_springs(s, rules, total, K, k);
      const bool any_point =
        std::find(total.begin(), total.end(), 0.) != total.end();
      if (any_point && acting.size() != 1)
        throw std::runtime_error(
          "springs '" + s.name +
          "': a station has no face within the "
          "attachment radius, and a spring at one node needs a direction "
          "along a coordinate axis; give a radius that reaches the faces");
      const auto [worst, n_point] =
        any_point ? add_nearest_node_springs(s, total, acting[0], K, k) :
                    std::pair<double, unsigned int>(0., 0u);
      const double a = s.radius;
      K.compress(VectorOperation::add);
      // faces per spread spring (a report, not an input)
      std::vector<unsigned int> counts(stations.size());
      Utilities::MPI::sum(faces_per_spring, comm, counts);
      unsigned int n_min = std::numeric_limits<unsigned int>::max(), n_max = 0;
      for (unsigned int i = 0; i < stations.size(); ++i)
        if (total[i] > 0.)
          {
            n_min = std::min(n_min, counts[i]);
            n_max = std::max(n_max, counts[i]);
          }
      pcout << "Springs: " << stations.size() << " x " << s.stiffness
            << " N/m along (" << s.direction << "), ";
      if (n_point == stations.size())
        pcout << "each at the nearest node";
      else
        pcout << stations.size() - n_point << " spread over radius " << 1e3 * a
              << " mm ("
              << (lumped_springs ? "lumped on the face nodes" :
                                   "consistent Winkler layer")
              << ", " << n_min << "-" << n_max << " faces each)"
              << (n_point > 0 ? ", " + std::to_string(n_point) +
                                  " at the nearest node (none inside)" :
                                "");
      if (worst > 1e-9)
        pcout << " (WARNING: a station lies " << worst
              << " m from the nearest node; choose mesh counts that put "
                 "nodes at the stations)";
      pcout << std::endl;
    }

    // One record per face the bells touch: the quadrature points some
    // bell covers, in the cell's unit coordinates, each with its (spring,
    // bell x JxW [m^2]) pairs, and the shape functions of the acting
    // components nonzero on the face.
    struct StructuralModel::SpringFaceRule
    {
      DoFHandler<3>::active_cell_iterator                       cell;
      std::vector<Point<3>>                                     unit;
      std::vector<std::vector<std::pair<unsigned int, double>>> weights;
      std::vector<unsigned int>                                 shapes;
    };

    std::vector<std::pair<DoFHandler<3>::active_cell_iterator, unsigned int>>
    StructuralModel::spring_faces(const scene::SpringSet &s) const
    {
      std::vector<std::pair<DoFHandler<3>::active_cell_iterator, unsigned int>>
        faces;
      if (!(s.radius > 0.) || s.to_body)
        return faces;
      if (s.station_normals.size() != s.stations.size())
        throw std::runtime_error("springs '" + s.name +
                                 "': one face normal per station needed");
      const auto off_plane = [&](const Point<3> &x, const unsigned int i) {
        return std::abs((x - s.stations[i]) * s.station_normals[i]);
      };
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() && cell->material_id() == s.body)
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const auto   face   = cell->face(f);
                const double h      = face->diameter();
                const auto   centre = face->center();
                for (unsigned int i = 0; i < s.stations.size(); ++i)
                  if (off_plane(centre, i) < s.tolerance &&
                      centre.distance(s.stations[i]) < s.radius + h / 2)
                    {
                      faces.emplace_back(cell, f);
                      break;
                    }
              }
      return faces;
    }

    void
    StructuralModel::add_spring_sparsity(const scene::SpringSet &s,
                                         DynamicSparsityPattern &dsp) const
    {
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      if (s.to_body)
        for (const auto &pair : two_body_spring_nodes(s))
          {
            std::vector<types::global_dof_index> d(pair.begin(), pair.end());
            constraints.add_entries_local_to_global(d, dsp, false);
          }
      else
        for (const auto &[cell, f] : spring_faces(s))
          {
            cell->get_dof_indices(dofs);
            constraints.add_entries_local_to_global(dofs, dsp, false);
          }
    }

    // The points of the face rule @p q2 (unit coordinates of face @p f,
    // made of n_sub x n_sub equal sub-squares) that may lie within the
    // attachment radius of a station of @p s, in their order in @p q2: a
    // sub-square is dropped when each of its corners is farther from every
    // station, in the station's plane, than the radius plus twice the
    // largest distance between its mapped corners (the in-plane distance
    // changes no faster than the point moves). The dropped points have a
    // bell weight of zero, so the rule is the same; the iterated rule
    // reaches 10^5 points on a face, a few hundred of them under a bell.
    Quadrature<2>
    StructuralModel::near_a_station(
      const DoFHandler<3>::active_cell_iterator &cell,
      const unsigned int                         f,
      const Quadrature<2>                       &q2,
      const unsigned int                         n_sub,
      const scene::SpringSet                    &s) const
    {
      if (n_sub <= 2)
        return q2;
      std::vector<Point<2>> corners;
      for (unsigned int j = 0; j <= n_sub; ++j)
        for (unsigned int i = 0; i <= n_sub; ++i)
          corners.emplace_back(double(i) / n_sub, double(j) / n_sub);
      FEValues<3> at_corners(
        mapping,
        fe,
        QProjector<3>::project_to_face(ReferenceCells::Hexahedron,
                                       Quadrature<2>(corners),
                                       f),
        update_quadrature_points);
      at_corners.reinit(cell);
      const auto corner = [&](const unsigned int i, const unsigned int j) {
        return at_corners.quadrature_point(j * (n_sub + 1) + i);
      };
      // in-plane distance of x from station k
      const auto in_plane = [&](const Point<3> &x, const unsigned int k) {
        const Tensor<1, 3> d = x - s.stations[k];
        return (d - (d * s.station_normals[k]) * s.station_normals[k]).norm();
      };
      std::vector<bool> kept(n_sub * n_sub, false);
      for (unsigned int j = 0; j < n_sub; ++j)
        for (unsigned int i = 0; i < n_sub; ++i)
          {
            const std::array<Point<3>, 4> c{{corner(i, j),
                                             corner(i + 1, j),
                                             corner(i, j + 1),
                                             corner(i + 1, j + 1)}};
            double                        size = 0.;
            for (const Point<3> &x : c)
              for (const Point<3> &y : c)
                size = std::max(size, x.distance(y));
            for (unsigned int k = 0;
                 k < s.stations.size() && !kept[j * n_sub + i];
                 ++k)
              for (const Point<3> &x : c)
                if (in_plane(x, k) < s.radius + 2. * size)
                  kept[j * n_sub + i] = true;
          }
      std::vector<Point<2>> points;
      std::vector<double>   weights;
      for (unsigned int q = 0; q < q2.size(); ++q)
        {
          const Point<2>    &x = q2.point(q);
          const unsigned int i =
            std::min(n_sub - 1, static_cast<unsigned int>(x[0] * n_sub));
          const unsigned int j =
            std::min(n_sub - 1, static_cast<unsigned int>(x[1] * n_sub));
          if (kept[j * n_sub + i])
            {
              points.push_back(x);
              weights.push_back(q2.weight(q));
            }
        }
      return Quadrature<2>(points, weights);
    }

    // Each spring spread over the disc of the body's face within the
    // attachment radius of its station, with cosine-bell weights normalised
    // to the spring's stiffness: a Winkler layer of stiffness density
    // k bell(x) / int(bell) [N/m^3] along the spring's direction. Consistent
    // (default): integrated exactly enough by composite Gauss rules of
    // sub-intervals a / 6 on every face the bell touches, so the model is
    // the same on every mesh and degree and a finer space can only lower its
    // frequencies. Lumped (explicit dynamics): the Gauss-Lobatto rule on the
    // face's FE_Q support points, a diagonal that changes with the node
    // spacing.
    std::vector<StructuralModel::SpringFaceRule>
    StructuralModel::spring_face_rules(
      const scene::SpringSet    &s,
      std::vector<double>       &total,
      std::vector<unsigned int> &faces_per_spring) const
    {
      const std::vector<Point<3>> &stations = s.stations;
      const double                 a        = s.radius;
      // distance of x from station i's plane, and within that plane
      const auto off_plane = [&](const Point<3> &x, const unsigned int i) {
        return std::abs((x - stations[i]) * s.station_normals[i]);
      };
      const auto bell = [&](const Point<3> &x, const unsigned int i) {
        if (off_plane(x, i) > s.tolerance)
          return 0.;
        const Tensor<1, 3> d = x - stations[i];
        const Tensor<1, 3> v =
          d - (d * s.station_normals[i]) * s.station_normals[i];
        // |v| by hypot (no overflow; exact when a component is 0)
        const double r = std::hypot(std::hypot(v[0], v[1]), v[2]);
        return r < a ? 0.5 * (1. + std::cos(numbers::PI * r / a)) : 0.;
      };
      const unsigned int          n = fe.n_dofs_per_cell();
      std::vector<SpringFaceRule> rules;
      const QGauss<1>             gauss(fe.degree + 1);
      for (const auto &[cell, f] : spring_faces(s))
        {
          const auto   face = cell->face(f);
          const double h    = face->diameter();
          // the face must be a parallelogram (weights = unit weights
          // times its area)
          const Tensor<1, 3> d = face->vertex(0) + face->vertex(3) -
                                 face->vertex(1) - face->vertex(2);
          if (!(d.norm() < 1e-9 * h))
            throw std::runtime_error(
              "springs '" + s.name +
              "': a face they spread over is "
              "not a parallelogram; set their attachment radius to 0 "
              "(point springs) or remesh the face");
          const unsigned int n_sub =
            lumped_springs ?
              1u :
              std::min(200u, static_cast<unsigned int>(std::ceil(6. * h / a)));
          const Quadrature<2> q2 =
            near_a_station(cell,
                           f,
                           lumped_springs ?
                             Quadrature<2>(QGaussLobatto<2>(fe.degree + 1)) :
                             Quadrature<2>(QIterated<2>(gauss, n_sub)),
                           n_sub,
                           s);
          const Quadrature<3> q3 =
            QProjector<3>::project_to_face(ReferenceCells::Hexahedron, q2, f);
          SpringFaceRule    rule;
          std::vector<bool> touched(stations.size(), false);
          rule.cell = cell;
          // the real points of the whole rule from one evaluation of
          // the cell's mapping (not one per point)
          std::optional<FEValues<3>> points;
          if (q3.size() > 0)
            {
              points.emplace(mapping, fe, q3, update_quadrature_points);
              points->reinit(cell);
            }
          for (unsigned int q = 0; q < q3.size(); ++q)
            {
              const Point<3> &x = points->quadrature_point(q);
              std::vector<std::pair<unsigned int, double>> w;
              for (unsigned int i = 0; i < stations.size(); ++i)
                if (const double b = bell(x, i); b > 0.)
                  {
                    w.emplace_back(i, b * q3.weight(q) * face->measure());
                    total[i] += w.back().second;
                    touched[i] = true;
                  }
              if (w.empty())
                continue;
              rule.unit.push_back(q3.point(q));
              rule.weights.push_back(std::move(w));
            }
          for (unsigned int i = 0; i < stations.size(); ++i)
            faces_per_spring[i] += touched[i];
          for (unsigned int k = 0; k < n; ++k)
            if (s.direction[fe.system_to_component_index(k).first] != 0. &&
                fe.has_support_on_face(k, f))
              rule.shapes.push_back(k);
          rules.push_back(std::move(rule));
        }
      return rules;
    }

    void
    StructuralModel::assemble_spread_springs(
      const scene::SpringSet            &s,
      const std::vector<SpringFaceRule> &rules,
      const std::vector<double>         &total,
      PETScMatrix                       &K,
      const double                       k)
    {
      const unsigned int                   n = fe.n_dofs_per_cell();
      FullMatrix<double>                   cell_k(n, n);
      std::vector<types::global_dof_index> dofs(n);
      std::vector<double>                  phi;
      for (const auto &rule : rules)
        {
          cell_k = 0;
          phi.resize(rule.shapes.size());
          for (unsigned int q = 0; q < rule.unit.size(); ++q)
            {
              double c = 0.;
              for (const auto &[i, w] : rule.weights[q])
                c += k * w / total[i];
              for (unsigned int k = 0; k < phi.size(); ++k)
                {
                  const unsigned int comp =
                    fe.system_to_component_index(rule.shapes[k]).first;
                  phi[k] =
                    s.direction[comp] * fe.shape_value_component(rule.shapes[k],
                                                                 rule.unit[q],
                                                                 comp);
                }
              for (unsigned int k = 0; k < phi.size(); ++k)
                for (unsigned int l = 0; l < phi.size(); ++l)
                  cell_k(rule.shapes[k], rule.shapes[l]) += c * phi[k] * phi[l];
            }
          if (!rule.unit.empty())
            {
              rule.cell->get_dof_indices(dofs);
              constraints.distribute_local_to_global(cell_k, dofs, K);
            }
        }
    }

    std::vector<std::array<types::global_dof_index, 6>>
    StructuralModel::two_body_spring_nodes(const scene::SpringSet &s) const
    {
      const unsigned int                   n = fe.n_dofs_per_cell();
      std::vector<types::global_dof_index> dofs(n);
      const auto                          &unit = fe.get_unit_support_points();
      std::vector<std::array<types::global_dof_index, 6>> result(
        s.stations.size());
      for (unsigned int side = 0; side < 2; ++side)
        {
          const types::material_id body = side == 0 ? s.body : s.other;
          std::vector<double>      best(s.stations.size(), 1e300);
          for (const auto &cell : dof_handler.active_cell_iterators())
            if (!cell->is_artificial() && cell->material_id() == body)
              {
                cell->get_dof_indices(dofs);
                for (unsigned int k = 0; k < n; ++k)
                  if (fe.system_to_component_index(k).first == 0 &&
                      !(constraints.is_constrained(dofs[k]) &&
                        !constraints.get_constraint_entries(dofs[k])->empty()))
                    {
                      const Point<3> x =
                        mapping.transform_unit_to_real_cell(cell, unit[k]);
                      const unsigned int base =
                        fe.system_to_component_index(k).second;
                      for (unsigned int i = 0; i < s.stations.size(); ++i)
                        {
                          const double d = x.distance(s.stations[i]);
                          if (d < best[i] - 1e-12 ||
                              (d < best[i] + 1e-12 &&
                               dofs[k] < result[i][3 * side]))
                            {
                              best[i] = std::min(best[i], d);
                              for (unsigned int c = 0; c < 3; ++c)
                                result[i][3 * side + c] =
                                  dofs[fe.component_to_system_index(c, base)];
                            }
                        }
                    }
              }
          for (const double d : best)
            if (d == 1e300)
              throw std::runtime_error("springs '" + s.name +
                                       "': a body they join has no node");
        }
      return result;
    }

    // Stations with no node inside the radius (or radius 0): the nearest
    // unconstrained support node takes the whole spring (its DoF of the
    // acting component); among nodes at the same distance the lowest DoF
    // index, the same on every rank.
    std::pair<double, unsigned int>
    StructuralModel::add_nearest_node_springs(const scene::SpringSet    &s,
                                              const std::vector<double> &total,
                                              const unsigned int component,
                                              PETScMatrix       &K,
                                              const double       k)
    {
      const std::vector<Point<3>>         &stations = s.stations;
      const unsigned int                   n        = fe.n_dofs_per_cell();
      std::vector<types::global_dof_index> dofs(n);
      const auto                          &unit = fe.get_unit_support_points();
      std::vector<double>                  best(stations.size(), 1e300);
      std::vector<types::global_dof_index> best_dof(
        stations.size(), std::numeric_limits<types::global_dof_index>::max());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial() && cell->material_id() == s.body)
          {
            cell->get_dof_indices(dofs);
            for (unsigned int k = 0; k < n; ++k)
              if (fe.system_to_component_index(k).first == component &&
                  !constraints.is_constrained(dofs[k])) // not hanging
                {
                  const Point<3> x =
                    mapping.transform_unit_to_real_cell(cell, unit[k]);
                  for (unsigned int i = 0; i < stations.size(); ++i)
                    {
                      const double d = x.distance(stations[i]);
                      if (d < best[i] - 1e-12 ||
                          (d < best[i] + 1e-12 && dofs[k] < best_dof[i]))
                        {
                          best[i]     = std::min(best[i], d);
                          best_dof[i] = dofs[k];
                        }
                    }
                }
          }
      double       worst   = 0;
      unsigned int n_point = 0;
      for (unsigned int i = 0; i < stations.size(); ++i)
        if (total[i] == 0.)
          {
            ++n_point;
            const double d = Utilities::MPI::min(best[i], comm);
            const types::global_dof_index dof = Utilities::MPI::min(
              best[i] < d + 1e-12 ?
                best_dof[i] :
                std::numeric_limits<types::global_dof_index>::max(),
              comm);
            worst = std::max(worst, d);
            if (locally_owned_dofs.is_element(dof))
              K.add(dof,
                    dof,
                    k * s.direction[component] * s.direction[component]);
          }
      return {worst, n_point};
    }
  } // namespace physics
} // namespace squeal
