// The checks of a mesh-file scene against its mesh: overlapping bodies,
// contact pairs whose faces are plane and face each other within reach,
// bodies that nothing holds.

#include <deal.II/fe/mapping_q.h>
#include <deal.II/numerics/rtree.h>

#include "mesh_file_items.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace squeal
{
  namespace scene
  {
    namespace internal
    {
      namespace
      {
        // Union-find over the bodies plus the ground (index n).
        struct Connectivity
        {
          std::vector<unsigned int> parent;
          explicit Connectivity(const unsigned int n)
            : parent(n + 1)
          {
            std::iota(parent.begin(), parent.end(), 0u);
          }
          unsigned int
          root(unsigned int i)
          {
            while (parent[i] != i)
              i = parent[i] = parent[parent[i]];
            return i;
          }
          void
          join(const unsigned int a, const unsigned int b)
          {
            parent[root(a)] = root(b);
          }
        };
      } // namespace

      // Overlapping bodies: a vertex, face centre or cell centre of one body
      // inside a cell of another by more than 1 % of that cell (touching
      // bodies, such as a pad on a disc, meet on each other's faces, at
      // depth 0).
      void
      check_overlap(const Triangulation<3>                             &coarse,
                    const std::vector<Triangulation<3>::cell_iterator> &cells,
                    const std::vector<int>                             &owner,
                    const std::vector<Body>                            &bodies,
                    const std::string &description)
      {
        std::vector<std::set<int>> vertex_bodies(coarse.n_vertices());
        for (unsigned int c = 0; c < cells.size(); ++c)
          for (const auto v : cells[c]->vertex_indices())
            vertex_bodies[cells[c]->vertex_index(v)].insert(owner[c]);
        std::vector<std::pair<BoundingBox<3>, unsigned int>> boxes;
        for (unsigned int c = 0; c < cells.size(); ++c)
          boxes.emplace_back(cells[c]->bounding_box(), c);
        const auto        tree = pack_rtree(boxes);
        const MappingQ<3> q1(1);
        // the points tested: every vertex (for the bodies that do not use
        // it), every face centre and cell centre (for the other bodies)
        const auto &vertices = coarse.get_vertices();
        std::vector<std::pair<Point<3>, std::set<int>>> probes;
        for (unsigned int v = 0; v < vertices.size(); ++v)
          if (!vertex_bodies[v].empty())
            probes.emplace_back(vertices[v], vertex_bodies[v]);
        for (unsigned int c = 0; c < cells.size(); ++c)
          {
            probes.emplace_back(cells[c]->center(), std::set<int>{owner[c]});
            for (const auto f : cells[c]->face_indices())
              probes.emplace_back(cells[c]->face(f)->center(),
                                  std::set<int>{owner[c]});
          }
        for (const auto &[x, own] : probes)
          {
            std::vector<std::pair<BoundingBox<3>, unsigned int>> near;
            tree.query(boost::geometry::index::intersects(x),
                       std::back_inserter(near));
            for (const auto &[box, c] : near)
              {
                if (own.count(owner[c]) > 0)
                  continue;
                Point<3> unit;
                try
                  {
                    unit = q1.transform_real_to_unit_cell(cells[c], x);
                  }
                catch (const Mapping<3>::ExcTransformationFailed &)
                  {
                    continue;
                  }
                double depth = 1.;
                for (unsigned int d = 0; d < 3; ++d)
                  depth = std::min({depth, unit[d], 1. - unit[d]});
                if (depth > 0.01)
                  throw std::runtime_error(
                    description + ": bodies '" + bodies[*own.begin()].name +
                    "' and '" + bodies[owner[c]].name +
                    "' overlap: a point of the first at (" +
                    Utilities::to_string(x[0]) + ", " +
                    Utilities::to_string(x[1]) + ", " +
                    Utilities::to_string(x[2]) +
                    ") m lies inside a cell of the second (" +
                    Utilities::to_string(100. * depth, 3) +
                    " % of it deep); remesh or move the bodies apart");
              }
          }
      }

      // The contact plane of PAIR from its slave faces SLAVE: centre, normal
      // (into the slave body), size, in-plane axes; the faces must be plane.
      void
      plane_frame(const Item                                         &item,
                  const std::vector<io::CellFace>                    &slave,
                  const std::vector<Triangulation<3>::cell_iterator> &cells,
                  ContactPair                                        &pair)
      {
        double       area = 0.;
        Tensor<1, 3> weighted_centre, outward;
        for (const auto &[c, f] : slave)
          {
            const auto [n, a] = outward_normal(cells[c], f);
            area += a;
            weighted_centre += a * cells[c]->face(f)->center();
            outward += a * n;
          }
        pair.centre = Point<3>(weighted_centre / area);
        pair.normal = -outward / outward.norm();
        pair.size   = std::sqrt(area);
        // the plane: through the centre; origin where the normal through
        // the coordinate origin meets it
        pair.plane_origin = Point<3>((pair.centre * pair.normal) * pair.normal);
        unsigned int least = 0;
        for (unsigned int d = 1; d < 3; ++d)
          if (std::abs(pair.normal[d]) < std::abs(pair.normal[least]))
            least = d;
        Tensor<1, 3> e;
        e[least]           = 1.;
        e                  = e - (e * pair.normal) * pair.normal;
        pair.plane_axes[0] = e / e.norm();
        pair.plane_axes[1] = cross_product_3d(pair.normal, pair.plane_axes[0]);
        const double tol   = 1e-6 * pair.size;
        for (const auto &[c, f] : slave)
          for (const auto v : cells[c]->face(f)->vertex_indices())
            if (std::abs((cells[c]->face(f)->vertex(v) - pair.centre) *
                         pair.normal) > tol)
              throw std::runtime_error(
                item.where() + ": the slave face set '" + item.text("slave") +
                "' is not plane (a vertex lies " +
                Utilities::to_string(
                  (cells[c]->face(f)->vertex(v) - pair.centre) * pair.normal) +
                " m off its mean plane); the linear friction coupling "
                "integrates on a plane");
      }

      // The master faces MASTER under the slave faces SLAVE of PAIR: some
      // exist, they face the slave, and they lie within SEARCH_DISTANCE [m].
      void
      check_master(const Item                                         &item,
                   const ContactPair                                  &pair,
                   const std::vector<io::CellFace>                    &slave,
                   const std::vector<io::CellFace>                    &master,
                   const std::vector<Triangulation<3>::cell_iterator> &cells,
                   const double search_distance)
      {
        BoundingBox<2> slave_box;
        {
          std::vector<Point<2>> pts;
          for (const auto &[c, f] : slave)
            for (const auto v : cells[c]->face(f)->vertex_indices())
              pts.push_back(pair.to_plane(cells[c]->face(f)->vertex(v)));
          slave_box = BoundingBox<2>(pts);
        }
        unsigned int under    = 0;
        double       farthest = 0., facing = 0.;
        for (const auto &[c, f] : master)
          {
            // the face's in-plane box overlaps the slave's in an area
            std::vector<Point<2>> pts;
            for (const auto v : cells[c]->face(f)->vertex_indices())
              pts.push_back(pair.to_plane(cells[c]->face(f)->vertex(v)));
            const BoundingBox<2> box(pts);
            bool                 overlap = true;
            for (unsigned int d = 0; d < 2; ++d)
              overlap =
                overlap &&
                std::min(box.upper_bound(d), slave_box.upper_bound(d)) -
                    std::max(box.lower_bound(d), slave_box.lower_bound(d)) >
                  1e-6 * pair.size;
            if (!overlap)
              continue;
            ++under;
            for (const auto v : cells[c]->face(f)->vertex_indices())
              farthest =
                std::max(farthest,
                         std::abs((cells[c]->face(f)->vertex(v) - pair.centre) *
                                  pair.normal));
            facing += outward_normal(cells[c], f).first * pair.normal;
          }
        if (under == 0)
          throw std::runtime_error(
            item.where() + ": no face of the master set '" +
            item.text("master") + "' lies under the slave set '" +
            item.text("slave") + "'; the two do not face each other");
        if (facing / under < 0.5)
          throw std::runtime_error(
            item.where() + ": the master set '" + item.text("master") +
            "' faces away from the slave set '" + item.text("slave") +
            "' (mean cosine of their normals " +
            Utilities::to_string(facing / under) + ")");
        if (farthest > search_distance)
          throw std::runtime_error(
            item.where() + ": the master set '" + item.text("master") +
            "' lies up to " + Utilities::to_string(farthest) +
            " m from the slave's plane, beyond Preload/Search distance = " +
            Utilities::to_string(search_distance) +
            " m; the two are out of reach");
      }


      // Nothing may float free: every body of SCENE connected to the ground
      // through holds, point holds, springs, contact pairs or shared
      // vertices.
      void
      check_grounded(const Scene                                     &scene,
                     const std::map<std::string, types::boundary_id> &face_ids,
                     const io::NamedSets                             &sets,
                     const std::vector<Triangulation<3>::cell_iterator> &cells,
                     const std::vector<int>                             &owner,
                     const std::string &description)
      {
        const auto                 &bodies = scene.bodies;
        Connectivity                net(bodies.size());
        const unsigned int          ground = bodies.size();
        std::map<unsigned int, int> vertex_owner;
        for (unsigned int c = 0; c < cells.size(); ++c)
          for (const auto v : cells[c]->vertex_indices())
            {
              const auto [at, fresh] =
                vertex_owner.emplace(cells[c]->vertex_index(v), owner[c]);
              if (!fresh)
                net.join(at->second, owner[c]);
            }
        const auto body_of_faces = [&](const types::boundary_id id) {
          std::set<unsigned int> found;
          for (const auto &[name, bid] : face_ids)
            if (bid == id)
              for (const auto &[c, f] : sets.faces(name))
                found.insert(owner[c]);
          return found;
        };
        for (const Hold &hold : scene.holds)
          for (const unsigned int b : body_of_faces(hold.id))
            net.join(b, ground);
        for (const SpringSet &s : scene.springs)
          net.join(s.body, s.to_body ? s.other : ground);
        for (const PointHold &hold : scene.point_holds)
          {
            unsigned int best = 0;
            double       d    = 1e300;
            for (unsigned int c = 0; c < cells.size(); ++c)
              if (cells[c]->center().distance(hold.point) < d)
                {
                  d    = cells[c]->center().distance(hold.point);
                  best = owner[c];
                }
            net.join(best, ground);
          }
        for (const Tie &tie : scene.ties)
          for (const unsigned int a : body_of_faces(tie.slave))
            for (const unsigned int b : body_of_faces(tie.master))
              net.join(a, b);
        for (const ContactPair &pair : scene.contact_pairs)
          for (const unsigned int a : body_of_faces(pair.slave))
            for (const unsigned int b : body_of_faces(pair.master))
              net.join(a, b);
        std::string free;
        for (unsigned int b = 0; b < bodies.size(); ++b)
          if (net.root(b) != net.root(ground))
            free += (free.empty() ? "'" : ", '") + bodies[b].name + "'";
        if (!free.empty())
          throw std::runtime_error(
            description + ": nothing holds body " + free +
            " (free-floating): give it a hold, a point hold, springs, a "
            "contact pair or a tie, or share nodes with a held body");
      }
    } // namespace internal
  }   // namespace scene
} // namespace squeal
