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

#include "mesh_file_items.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace scene
  {
    using namespace dealii;
    using namespace internal;

    namespace
    {
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
                  const std::string         &description,
                  std::vector<Body>         &bodies,
                  std::vector<std::string>  &body_sets,
                  std::vector<bool>         &cylindrical,
                  std::vector<std::string>  &disc_faces,
                  const parameters::Damping &damping)
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
            if (type != "other" && type != "disc")
              throw std::runtime_error(
                item.where() + ": type = '" + type +
                "': allowed are other and disc (a sweep names the body's "
                "parameters: " +
                item.name + ".E, " + item.name + ".rho)");
            body.disc        = type == "disc";
            body.own_damping = item.has("alpha") || item.has("beta");
            if (body.own_damping)
              {
                body.alpha = item.number("alpha", damping.alpha);
                body.beta  = item.number("beta", damping.beta);
                if (!(body.alpha >= 0.) || !(body.beta >= 0.))
                  throw std::runtime_error(
                    item.where() + ": need alpha >= 0 [1/s] and beta >= 0 [s]");
              }
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
      using FaceId =
        std::function<types::boundary_id(const Item &, const std::string &)>;

      // The Loads list: a traction on a face set along a direction, of the
      // analysis' force, its own force or a pressure, with its own ramp.
      std::vector<Load>
      read_loads(const std::string &list, const FaceId &face_id)
      {
        std::vector<Load> loads;
        for (const Item &item :
             parse_list("Loads",
                        list,
                        {"set", "direction", "force", "pressure", "ramp"}))
          {
            Load load{item.name,
                      face_id(item, item.text("set")),
                      item.unit("direction", "")};
            if (item.has("force") && item.has("pressure"))
              throw std::runtime_error(item.where() +
                                       ": give force= or pressure=, not both");
            if (item.has("force") || item.has("pressure"))
              {
                load.magnitude = item.has("force") ? Load::Magnitude::force :
                                                     Load::Magnitude::pressure;
                load.value =
                  item.number(item.has("force") ? "force" : "pressure");
                if (!(load.value >= 0.) || !std::isfinite(load.value))
                  throw std::runtime_error(
                    item.where() + ": force [N] and pressure [Pa] must be >= 0 "
                                   "(the direction gives the sense)");
              }
            if (item.has("ramp"))
              {
                load.ramp = item.number("ramp");
                if (!(load.ramp >= 0.) || !std::isfinite(load.ramp))
                  throw std::runtime_error(item.where() +
                                           ": ramp must be >= 0 [s]");
              }
            loads.push_back(load);
          }
        return loads;
      }

      // The Masses list: at a point or spread over a face set.
      std::vector<LumpedMass>
      read_masses(const std::string &list, const FaceId &face_id)
      {
        std::vector<LumpedMass> masses;
        for (const Item &item :
             parse_list("Masses", list, {"mass", "point", "set"}))
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

        return masses;
      }

      // The Ties list: bonded slave and master face sets.
      std::vector<Tie>
      read_ties(const std::string &list, const FaceId &face_id)
      {
        std::vector<Tie> ties;
        for (const Item &item : parse_list("Ties", list, {"slave", "master"}))
          {
            Tie tie{item.name,
                    face_id(item, item.text("slave")),
                    face_id(item, item.text("master"))};
            if (tie.slave == tie.master)
              throw std::runtime_error(item.where() +
                                       ": slave and master are one face set");
            ties.push_back(tie);
          }
        return ties;
      }

      // The Springs list: stations on a body's boundary faces (to ground)
      // or joining two bodies.
      std::vector<SpringSet>
      read_springs(const parameters::AllParameters                    &prm,
                   const io::NamedSets                                &sets,
                   const std::vector<Triangulation<3>::cell_iterator> &cells,
                   const std::vector<std::string> &body_sets,
                   const std::vector<Body>        &bodies)
      {
        const auto            &mf = prm.scene.mesh_file;
        std::vector<SpringSet> springs;
        // Springs: each station on a boundary face of its body.
        for (const Item &item : parse_list(
               "Springs",
               mf.springs,
               {"body", "direction", "points", "nodes", "radius", "k", "to"}))
          {
            SpringSet s;
            s.name                      = item.name;
            const std::string body_name = item.text("body");
            const auto        it =
              std::find_if(bodies.begin(), bodies.end(), [&](const Body &b) {
                return b.name == body_name;
              });
            if (it == bodies.end())
              throw std::runtime_error(item.where() + ": no body '" +
                                       body_name + "' in " + prefix + "Bodies");
            s.body = it->id;
            if (item.has("to"))
              {
                const std::string other = item.text("to");
                const auto        jt =
                  std::find_if(bodies.begin(),
                               bodies.end(),
                               [&](const Body &b) { return b.name == other; });
                if (jt == bodies.end() || jt == it)
                  throw std::runtime_error(item.where() + ": to = '" + other +
                                           "' must name another body of " +
                                           prefix + "Bodies");
                if (item.has("radius"))
                  throw std::runtime_error(
                    item.where() +
                    ": springs between two bodies join the nodes "
                    "nearest each station; remove radius=");
                s.to_body = true;
                s.other   = jt->id;
              }
            s.direction = item.unit("direction", "");
            s.stiffness = item.number("k", prm.springs.stiffness);
            if (!(s.stiffness >= 0.))
              throw std::runtime_error(item.where() + ": k must be >= 0 [N/m]");
            s.radius = s.to_body ?
                         0. :
                         item.number("radius", prm.springs.attachment_radius);
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
            if (!s.to_body) // two bodies' springs sit at nodes, not on faces
              place_stations(
                item, body_name, sets.cells(body_sets[s.body]), cells, s);
            springs.push_back(s);
          }

        return springs;
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
                   {"set",   "E",     "nu",   "rho",    "type",     "alpha",
                    "beta",  "face",  "axis", "centre", "manifold", "law",
                    "E1",    "E2",    "E3",   "nu12",   "nu13",     "nu23",
                    "G12",   "G13",   "G23",  "Et",     "nut",      "Gt",
                    "frame", "axis1", "axis2"});
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
                                                 disc_faces,
                                                 prm.damping);
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
      for (const Item &item :
           parse_list("Contact pairs",
                      mf.contact_pairs,
                      {"slave", "master", "sliding", "mu", "k_n", "k_t"}))
        {
          ContactPair pair;
          pair.name = item.name;
          pair.friction_coefficient =
            item.number("mu", prm.interface.friction_coefficient);
          pair.normal_stiffness =
            item.number("k_n", prm.interface.normal_stiffness);
          pair.tangential_stiffness =
            item.number("k_t", prm.interface.tangential_stiffness);
          if (!(pair.friction_coefficient >= 0. &&
                pair.friction_coefficient <= 10.) ||
              !(pair.normal_stiffness >= 0.) ||
              !(pair.tangential_stiffness >= 0.))
            throw std::runtime_error(item.where() +
                                     ": need 0 <= mu <= 10, k_n >= 0 and "
                                     "k_t >= 0 [N/m^3]");
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
      ties = read_ties(mf.ties, face_id);
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
      loads = read_loads(mf.loads, face_id);
      for (const Item &item : parse_list("Probes", mf.probes, {"point"}))
        probes.push_back({item.name, Point<3>(item.vector("point"))});
      masses  = read_masses(mf.masses, face_id);
      springs = read_springs(prm, sets, cells, body_sets, bodies);
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
