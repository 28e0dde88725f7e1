// The scene of a mesh file: the parameter file's lists parsed, checked
// against the mesh's named sets, and the geometric data the analyses need
// (pair planes, disc radii, spring face normals) derived from the mesh.

#include <deal.II/base/utilities.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/rtree.h>

#include <squeal/io/mesh_file.h>
#include <squeal/scene/material_law.h>
#include <squeal/scene/mesh_file_scene.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace scene
  {
    using namespace dealii;

    namespace
    {
      const std::string prefix = "Scene/Mesh file/";

      using Utilities::trim;

      // One item of a list: `name: key=value, key=value`.
      struct Item
      {
        std::string                        entry; // for messages
        std::string                        name;
        std::map<std::string, std::string> keys;

        std::string
        where() const
        {
          return prefix + entry + ", item '" + name + "'";
        }

        bool
        has(const std::string &key) const
        {
          return keys.count(key) > 0;
        }

        const std::string &
        text(const std::string &key) const
        {
          const auto it = keys.find(key);
          if (it == keys.end())
            throw std::runtime_error(where() + ": '" + key + "=' is required");
          return it->second;
        }

        std::string
        text(const std::string &key, const std::string &fallback) const
        {
          return has(key) ? keys.at(key) : fallback;
        }

        double
        number(const std::string &key) const
        {
          const std::string &v = text(key);
          try
            {
              std::size_t  used = 0;
              const double x    = std::stod(v, &used);
              if (trim(v.substr(used)).empty() && std::isfinite(x))
                return x;
            }
          catch (const std::exception &)
            {}
          throw std::runtime_error(where() + ": " + key + " = '" + v +
                                   "' is not a number");
        }

        double
        number(const std::string &key, const double fallback) const
        {
          return has(key) ? number(key) : fallback;
        }

        Tensor<1, 3>
        vector(const std::string &value, const std::string &key) const
        {
          std::istringstream in(value);
          Tensor<1, 3>       v;
          std::string        rest;
          if (!(in >> v[0] >> v[1] >> v[2]) || (in >> rest) ||
              !std::isfinite(v.norm()))
            throw std::runtime_error(where() + ": " + key + " = '" + value +
                                     "' is not three numbers 'x y z'");
          return v;
        }

        Tensor<1, 3>
        vector(const std::string &key) const
        {
          return vector(text(key), key);
        }

        Tensor<1, 3>
        unit(const std::string &key, const std::string &fallback) const
        {
          const Tensor<1, 3> v =
            vector(fallback.empty() ? text(key) : text(key, fallback), key);
          if (!(v.norm() > 0.))
            throw std::runtime_error(where() + ": " + key +
                                     " is the zero vector");
          return v / v.norm();
        }
      };

      std::vector<Item>
      parse_list(const std::string              &entry,
                 const std::string              &text,
                 const std::vector<std::string> &allowed)
      {
        std::vector<Item>     items;
        std::set<std::string> names;
        for (const std::string &raw : Utilities::split_string_list(text, ';'))
          {
            const std::string piece = trim(raw);
            if (piece.empty())
              continue;
            Item item;
            item.entry       = entry;
            const auto colon = piece.find(':');
            item.name        = trim(piece.substr(0, colon));
            if (colon == std::string::npos || item.name.empty())
              throw std::runtime_error(prefix + entry + ": '" + piece +
                                       "' is not 'name: key=value, key=value'");
            if (!names.insert(item.name).second)
              throw std::runtime_error(item.where() + ": the name is used "
                                                      "twice");
            for (const std::string &pair :
                 Utilities::split_string_list(piece.substr(colon + 1), ','))
              {
                if (trim(pair).empty())
                  continue;
                const auto        eq  = pair.find('=');
                const std::string key = trim(
                  pair.substr(0, eq == std::string::npos ? pair.size() : eq));
                if (eq == std::string::npos ||
                    std::find(allowed.begin(), allowed.end(), key) ==
                      allowed.end())
                  {
                    std::string list;
                    for (const auto &a : allowed)
                      list += (list.empty() ? "" : ", ") + a;
                    throw std::runtime_error(item.where() + ": '" + trim(pair) +
                                             "' is not key=value with a key "
                                             "of: " +
                                             list);
                  }
                if (!item.keys.emplace(key, trim(pair.substr(eq + 1))).second)
                  throw std::runtime_error(item.where() + ": '" + key +
                                           "' given twice");
              }
            items.push_back(item);
          }
        return items;
      }

      unsigned int
      component_of(const Item &item, const std::string &key, const char c)
      {
        if (c == 'x' || c == 'y' || c == 'z')
          return c - 'x';
        throw std::runtime_error(item.where() + ": " + key + " = '" +
                                 item.text(key) + "': use x, y or z");
      }

      // The level-0 cells by index.
      std::vector<Triangulation<3>::cell_iterator>
      coarse_cells(const Triangulation<3> &tria)
      {
        std::vector<Triangulation<3>::cell_iterator> cells;
        for (const auto &cell : tria.cell_iterators_on_level(0))
          cells.push_back(cell);
        return cells;
      }

      // Outward unit normal and area [m^2] of face f of a cell (a
      // bilinear face: the normal of its diagonals' cross product).
      std::pair<Tensor<1, 3>, double>
      outward_normal(const Triangulation<3>::cell_iterator &cell,
                     const unsigned int                     f)
      {
        const auto   face = cell->face(f);
        Tensor<1, 3> n    = cross_product_3d(face->vertex(3) - face->vertex(0),
                                          face->vertex(2) - face->vertex(1));
        if (n * (face->center() - cell->center()) < 0)
          n = -n;
        return {n / n.norm(), face->measure()};
      }

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

      // LOOKUP() (a named set of the mesh), its error prefixed with where ITEM
      // is.
      template <typename Lookup>
      const auto &
      named(const Item &item, const Lookup &lookup)
      {
        try
          {
            return lookup();
          }
        catch (const std::runtime_error &e)
          {
            throw std::runtime_error(item.where() + ": " + e.what());
          }
      }

      // The elastic law and density of a body item: law=isotropic (E, nu),
      // orthotropic (E1, E2, E3, nu12, nu13, nu23, G12, G13, G23) or
      // transversely isotropic (E, nu in the plane of isotropy; Et, nut, Gt
      // along its axis, material axis 3), in a Cartesian material frame
      // (axis1, axis2; axis 3 = axis1 x axis2) or a cylindrical one (radial,
      // tangential, axial about axis through centre).
      void
      read_law(const Item &item, Body &body)
      {
        body.material.density = item.number("rho");
        if (!(body.material.density > 0.))
          throw std::runtime_error(item.where() + ": need rho > 0");
        const std::string law = item.text("law", "isotropic");
        if (law == "isotropic")
          {
            body.material.youngs_modulus = item.number("E");
            body.material.poisson_ratio  = item.number("nu");
            if (!(body.material.youngs_modulus > 0.) ||
                !(body.material.poisson_ratio > -1.) ||
                !(body.material.poisson_ratio < 0.5))
              throw std::runtime_error(item.where() +
                                       ": need E > 0, -1 < nu < 0.5");
            return;
          }
        ElasticLaw &l = body.law;
        l.anisotropic = true;
        try
          {
            if (law == "orthotropic")
              {
                const OrthotropicConstants c{item.number("E1"),
                                             item.number("E2"),
                                             item.number("E3"),
                                             item.number("nu12"),
                                             item.number("nu13"),
                                             item.number("nu23"),
                                             item.number("G12"),
                                             item.number("G13"),
                                             item.number("G23")};
                l.C                          = orthotropic_stiffness(c);
                body.material.youngs_modulus = c.E1;
                body.material.poisson_ratio  = c.nu12;
              }
            else if (law == "transversely isotropic")
              {
                body.material.youngs_modulus = item.number("E");
                body.material.poisson_ratio  = item.number("nu");
                l.C =
                  transversely_isotropic_stiffness(body.material.youngs_modulus,
                                                   body.material.poisson_ratio,
                                                   item.number("Et"),
                                                   item.number("nut"),
                                                   item.number("Gt"));
              }
            else
              throw std::runtime_error(
                "law = '" + law +
                "': allowed are isotropic, orthotropic, transversely "
                "isotropic");
          }
        catch (const std::runtime_error &e)
          {
            const std::string what = e.what();
            throw std::runtime_error(what.rfind(item.where(), 0) == 0 ?
                                       what :
                                       item.where() + ": " + what);
          }
        const std::string frame = item.text("frame", "cartesian");
        if (frame == "cylindrical")
          {
            l.frame = ElasticLaw::Frame::cylindrical;
            l.axis  = item.unit("axis", "0 0 1");
            l.origin =
              Point<3>(item.vector(item.text("centre", "0 0 0"), "centre"));
          }
        else if (frame == "cartesian")
          {
            const Tensor<1, 3> a1 = item.unit("axis1", "1 0 0");
            Tensor<1, 3>       a2 = item.unit("axis2", "0 1 0");
            a2 -= (a2 * a1) * a1;
            if (!(a2.norm() > 1e-6))
              throw std::runtime_error(item.where() +
                                       ": axis1 and axis2 are parallel");
            a2 /= a2.norm();
            const Tensor<1, 3> a3 = cross_product_3d(a1, a2);
            for (unsigned int i = 0; i < 3; ++i)
              {
                l.axes[i][0] = a1[i];
                l.axes[i][1] = a2[i];
                l.axes[i][2] = a3[i];
              }
          }
        else
          throw std::runtime_error(item.where() + ": frame = '" + frame +
                                   "': allowed are cartesian and cylindrical");
      }

      // The bodies of BODY_ITEMS (material id = position in the list), their
      // cell sets and manifolds, the face of each disc; every cell in one
      // body. Returns the body of each coarse cell.
      std::vector<int>
      read_bodies(const std::vector<Item> &body_items,
                  const io::NamedSets     &sets,
                  const std::vector<Triangulation<3>::cell_iterator> &cells,
                  const std::string        &description,
                  std::vector<Body>        &bodies,
                  std::vector<std::string> &body_sets,
                  std::vector<bool>        &cylindrical,
                  std::vector<std::string> &disc_faces)
      {
        std::vector<int> owner(cells.size(), -1);
        for (unsigned int b = 0; b < body_items.size(); ++b)
          {
            const Item &item = body_items[b];
            Body        body;
            body.name = item.name;
            body.id   = b;
            read_law(item, body);
            const std::string type = item.text("type", "other");
            if (type != "other" && type != "disc" && type != "pad" &&
                type != "support")
              throw std::runtime_error(
                item.where() + ": type = '" + type +
                "': allowed are other, disc, pad, support");
            body.modulus_swept    = type == "pad";
            body.density_swept    = type == "support";
            body.disc             = type == "disc";
            const std::string set = item.text("set", item.name);
            body_sets.push_back(set);
            const std::string manifold = item.text("manifold", "none");
            if (manifold != "none" && manifold != "cylindrical")
              throw std::runtime_error(item.where() + ": manifold = '" +
                                       manifold +
                                       "': allowed are none and cylindrical");
            cylindrical.push_back(manifold == "cylindrical");
            if (body.disc || cylindrical.back())
              {
                body.axis = item.unit("axis", "0 0 1");
                body.centre =
                  Point<3>(item.vector(item.text("centre", "0 0 0"), "centre"));
              }
            if (body.disc)
              disc_faces[b] = item.text("face");
            for (const unsigned int c : named(
                   item, [&]() -> const auto & { return sets.cells(set); }))
              {
                if (owner[c] >= 0)
                  throw std::runtime_error(
                    item.where() + ": cell set '" + set +
                    "' shares cells with "
                    "body '" +
                    body_items[owner[c]].name + "' (first at " +
                    Utilities::to_string(cells[c]->center()[0]) + ", " +
                    Utilities::to_string(cells[c]->center()[1]) + ", " +
                    Utilities::to_string(cells[c]->center()[2]) + " m)");
                owner[c] = b;
              }
            bodies.push_back(body);
          }
        {
          const auto first = std::find(owner.begin(), owner.end(), -1);
          if (first != owner.end())
            {
              const Point<3> x = cells[first - owner.begin()]->center();
              throw std::runtime_error(
                prefix + "Bodies: " +
                std::to_string(std::count(owner.begin(), owner.end(), -1)) +
                " cells of " + description +
                " belong to no body (the first at " +
                Utilities::to_string(x[0]) + ", " + Utilities::to_string(x[1]) +
                ", " + Utilities::to_string(x[2]) +
                " m); add their cell set to the list");
            }
        }
        return owner;
      }

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

      // The sliding direction of PAIR: sliding=tx ty tz of ITEM, or the
      // rotation of DISC (SENSE +1 counterclockwise about its axis, -1
      // clockwise); in the contact plane, unit.
      void
      set_sliding(const Item  &item,
                  const Body  *disc,
                  const double sense,
                  ContactPair &pair)
      {
        pair.axis       = disc != nullptr ? disc->axis : pair.normal;
        pair.axis_point = disc != nullptr ? disc->centre : pair.centre;
        Tensor<1, 3> t;
        if (item.has("sliding"))
          t = item.vector("sliding");
        else if (disc != nullptr)
          t = sense * cross_product_3d(pair.axis, pair.radial());
        else
          throw std::runtime_error(item.where() +
                                   ": give sliding=tx ty tz (the scene has "
                                   "no disc to turn)");
        t -= (t * pair.normal) * pair.normal;
        if (!(t.norm() > 0.))
          throw std::runtime_error(item.where() +
                                   ": the sliding direction is normal to "
                                   "the contact plane");
        pair.sliding = t / t.norm();
      }

      // The tolerance of the stations of S (1e-6 of its body's extent) and
      // the outward normal of the boundary face of the body (cells
      // BODY_CELLS) that each station lies on.
      void
      place_stations(const Item                      &item,
                     const std::string               &body_name,
                     const std::vector<unsigned int> &body_cells,
                     const std::vector<Triangulation<3>::cell_iterator> &cells,
                     SpringSet                                          &s)
      {
        BoundingBox<3> box;
        {
          std::vector<Point<3>> pts;
          for (const unsigned int c : body_cells)
            for (const auto v : cells[c]->vertex_indices())
              pts.push_back(cells[c]->vertex(v));
          box = BoundingBox<3>(pts);
        }
        s.tolerance = 1e-6 * box.get_boundary_points().first.distance(
                               box.get_boundary_points().second);
        for (const Point<3> &x : s.stations)
          {
            bool found = false;
            for (const unsigned int c : body_cells)
              for (const auto f : cells[c]->face_indices())
                if (!found && cells[c]->at_boundary(f))
                  {
                    const auto n    = outward_normal(cells[c], f).first;
                    const auto face = cells[c]->face(f);
                    if (std::abs((x - face->center()) * n) > s.tolerance)
                      continue;
                    std::vector<Point<3>> pts;
                    for (const auto v : face->vertex_indices())
                      pts.push_back(face->vertex(v));
                    if (BoundingBox<3>(pts).point_inside(x, 1e-9))
                      {
                        s.station_normals.push_back(n);
                        found = true;
                      }
                  }
            if (!found)
              throw std::runtime_error(
                item.where() + ": the station at (" +
                Utilities::to_string(x[0]) + ", " + Utilities::to_string(x[1]) +
                ", " + Utilities::to_string(x[2]) +
                ") m lies on no boundary face of body '" + body_name + "'");
          }
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
          net.join(s.body, ground);
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
            " (free-floating): give it a hold, a point hold, springs or a "
            "contact pair, or share nodes with a held body");
      }
    } // namespace

    MeshFileScene::MeshFileScene(const parameters::AllParameters &prm)
      : file(prm.scene.mesh_file.file)
      , length_unit(prm.scene.mesh_file.length_unit)
    {
      const auto      &mf = prm.scene.mesh_file;
      Triangulation<3> coarse;
      sets             = io::read_mesh_file(file, length_unit, coarse);
      const auto cells = coarse_cells(coarse);

      // Bodies: material id = position in the list.
      const auto body_items =
        parse_list("Bodies",
                   mf.bodies,
                   {"set",  "E",    "nu",     "rho",      "type",
                    "face", "axis", "centre", "manifold", "law",
                    "E1",   "E2",   "E3",     "nu12",     "nu13",
                    "nu23", "G12",  "G13",    "G23",      "Et",
                    "nut",  "Gt",   "frame",  "axis1",    "axis2"});
      if (body_items.empty())
        throw std::runtime_error(prefix + "Bodies: " + description() +
                                 " needs at least one body");
      std::vector<std::string> disc_faces(body_items.size());
      const std::vector<int>   owner = read_bodies(body_items,
                                                 sets,
                                                 cells,
                                                 description(),
                                                 bodies,
                                                 body_sets,
                                                 cylindrical,
                                                 disc_faces);
      check_overlap(coarse, cells, owner, bodies, description());

      // Face sets get boundary ids 1, 2, ... in the order the scene uses
      // them (0: free); a face may carry one id only.
      std::map<io::CellFace, std::string> face_owner;
      const auto face_id = [&](const Item &item, const std::string &name) {
        const auto it = face_ids.find(name);
        if (it != face_ids.end())
          return it->second;
        const auto &faces = named(
          item, [&]() -> const auto & { return sets.faces(name); });
        if (faces.empty())
          throw std::runtime_error(item.where() + ": face set '" + name +
                                   "' is empty");
        for (const io::CellFace &cf : faces)
          {
            const auto [at, fresh] = face_owner.emplace(cf, name);
            if (!fresh && at->second != name)
              throw std::runtime_error(item.where() + ": face sets '" + name +
                                       "' and '" + at->second +
                                       "' share faces; a face can play one "
                                       "part only");
          }
        const types::boundary_id id = face_ids.size() + 1;
        face_ids.emplace(name, id);
        return id;
      };

      for (unsigned int b = 0; b < bodies.size(); ++b)
        if (bodies[b].disc)
          {
            Body &disc        = bodies[b];
            disc.naming_face  = face_id(body_items[b], disc_faces[b]);
            disc.inner_radius = 1e300;
            for (const unsigned int c : sets.cells(body_sets[b]))
              for (const auto v : cells[c]->vertex_indices())
                {
                  const Tensor<1, 3> d = cells[c]->vertex(v) - disc.centre;
                  const double r    = (d - (d * disc.axis) * disc.axis).norm();
                  disc.inner_radius = std::min(disc.inner_radius, r);
                  disc.outer_radius = std::max(disc.outer_radius, r);
                }
          }
      const Body *disc = this->disc();

      // Contact pairs.
      const double sense =
        prm.interface.rotation_sense == "counterclockwise" ? 1. : -1.;
      for (const Item &item : parse_list("Contact pairs",
                                         mf.contact_pairs,
                                         {"slave", "master", "sliding"}))
        {
          ContactPair pair;
          pair.name   = item.name;
          pair.slave  = face_id(item, item.text("slave"));
          pair.master = face_id(item, item.text("master"));
          if (pair.slave == pair.master)
            throw std::runtime_error(item.where() +
                                     ": slave and master are one face set");
          const auto &slave  = sets.faces(item.text("slave"));
          const auto &master = sets.faces(item.text("master"));
          plane_frame(item, slave, cells, pair);
          check_master(
            item, pair, slave, master, cells, prm.preload.search_distance);
          set_sliding(item, disc, sense, pair);
          contact_pairs.push_back(pair);
        }
      // a disc's theta = 0: towards the first pair
      for (Body &b : bodies)
        if (b.disc)
          {
            Tensor<1, 3> r;
            if (!contact_pairs.empty())
              r = contact_pairs.front().centre - b.centre;
            else
              r[std::abs(b.axis[0]) < 0.9 ? 0 : 1] = 1.;
            r -= (r * b.axis) * b.axis;
            b.reference = r / r.norm();
          }

      for (const Item &item :
           parse_list("Holds", mf.holds, {"set", "components"}))
        {
          Hold hold;
          hold.name               = item.name;
          hold.id                 = face_id(item, item.text("set"));
          const std::string comps = item.text("components", "xyz");
          hold.components         = {{false, false, false}};
          for (const char c : comps)
            if (c != ' ')
              hold.components[component_of(item, "components", c)] = true;
          holds.push_back(hold);
        }
      for (const Item &item :
           parse_list("Point holds", mf.point_holds, {"point", "component"}))
        {
          const std::string c = trim(item.text("component"));
          point_holds.push_back(
            {item.name,
             Point<3>(item.vector("point")),
             component_of(item, "component", c.size() == 1 ? c[0] : '?')});
        }
      for (const Item &item :
           parse_list("Loads", mf.loads, {"set", "direction"}))
        loads.push_back({item.name,
                         face_id(item, item.text("set")),
                         item.unit("direction", "")});
      for (const Item &item : parse_list("Probes", mf.probes, {"point"}))
        probes.push_back({item.name, Point<3>(item.vector("point"))});
      for (const Item &item :
           parse_list("Masses", mf.masses, {"mass", "point", "set"}))
        {
          LumpedMass m;
          m.name = item.name;
          m.mass = item.number("mass");
          if (!(m.mass > 0.))
            throw std::runtime_error(item.where() + ": need mass > 0 [kg]");
          if (item.has("point") == item.has("set"))
            throw std::runtime_error(item.where() +
                                     ": give either point= or set=");
          m.on_faces = item.has("set");
          if (m.on_faces)
            m.faces = face_id(item, item.text("set"));
          else
            m.point = Point<3>(item.vector("point"));
          masses.push_back(m);
        }

      // Springs: each station on a boundary face of its body.
      for (const Item &item :
           parse_list("Springs",
                      mf.springs,
                      {"body", "direction", "points", "nodes", "radius"}))
        {
          SpringSet s;
          s.name                      = item.name;
          const std::string body_name = item.text("body");
          const auto        it =
            std::find_if(bodies.begin(), bodies.end(), [&](const Body &b) {
              return b.name == body_name;
            });
          if (it == bodies.end())
            throw std::runtime_error(item.where() + ": no body '" + body_name +
                                     "' in " + prefix + "Bodies");
          s.body      = it->id;
          s.direction = item.unit("direction", "");
          s.stiffness = prm.springs.stiffness;
          s.radius    = item.number("radius", prm.springs.attachment_radius);
          if (!(s.radius >= 0.))
            throw std::runtime_error(item.where() + ": radius must be >= 0");
          if (item.has("points") == item.has("nodes"))
            throw std::runtime_error(item.where() +
                                     ": give either points= or nodes=");
          if (item.has("points"))
            for (const std::string &p :
                 Utilities::split_string_list(item.text("points"), '|'))
              s.stations.emplace_back(item.vector(p, "points"));
          else
            s.stations = named(
              item, [&]() -> const auto & {
                return sets.nodes(item.text("nodes"));
              });
          place_stations(
            item, body_name, sets.cells(body_sets[s.body]), cells, s);
          springs.push_back(s);
        }

      check_grounded(*this, face_ids, sets, cells, owner, description());
    }

    void
    MeshFileScene::apply_ids(Triangulation<3> &tria) const
    {
      for (unsigned int b = 0; b < bodies.size(); ++b)
        sets.assign_material(body_sets[b], bodies[b].id, tria);
      for (const auto &[name, id] : face_ids)
        sets.assign_boundary(name, id, tria);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        if (cylindrical[b])
          {
            const types::manifold_id id = 1 + b;
            for (const auto &cell : tria.active_cell_iterators())
              if (cell->material_id() == bodies[b].id)
                cell->set_all_manifold_ids(id);
            tria.set_manifold(id,
                              CylindricalManifold<3>(bodies[b].axis,
                                                     bodies[b].centre));
          }
    }

    void
    MeshFileScene::make_mesh(Triangulation<3> &tria) const
    {
      io::read_mesh_file(file, length_unit, tria);
      apply_ids(tria);
    }

    std::string
    MeshFileScene::description() const
    {
      return "mesh file '" + file + "'";
    }

    io::NamedSets
    MeshFileScene::named_sets(const Triangulation<3> &) const
    {
      return sets;
    }
  } // namespace scene
} // namespace squeal
