// The scene interface's shared parts and the factory. The TriboBrake scene
// lists the rig's parts (thesis § 3.2.1) in the ids its mesher sets.

#include <deal.II/grid/tria.h>

#include <squeal/scene/material_law.h>
#include <squeal/scene/mesh_file_scene.h>
#include <squeal/scene/scene.h>
#include <squeal/scene/tribobrake_mesh.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace scene
  {
    using namespace dealii;

    Tensor<1, 3>
    ContactPair::radial() const
    {
      Tensor<1, 3> d = centre - axis_point;
      d -= (d * axis) * axis;
      return d / d.norm();
    }

    Point<2>
    ContactPair::to_plane(const Point<3> &x) const
    {
      const Tensor<1, 3> d = x - plane_origin;
      return Point<2>(d * plane_axes[0], d * plane_axes[1]);
    }

    Point<3>
    ContactPair::from_plane(const Point<2> &p) const
    {
      return plane_origin + p[0] * plane_axes[0] + p[1] * plane_axes[1];
    }

    std::pair<double, double>
    Body::polar(const Point<3> &x) const
    {
      const Tensor<1, 3> d  = x - centre;
      const Tensor<1, 3> e2 = cross_product_3d(axis, reference);
      const double       a = d * reference, b = d * e2;
      return {std::hypot(a, b), std::atan2(b, a)};
    }

    const Body &
    Scene::body(const types::material_id id) const
    {
      for (const Body &b : bodies)
        if (b.id == id)
          return b;
      std::string names;
      for (const Body &b : bodies)
        names += (names.empty() ? "" : ", ") + b.name + " (" +
                 std::to_string(b.id) + ")";
      throw std::runtime_error(
        "scene " + description() + ": no body has material id " +
        std::to_string(id) + "; its bodies are " + names);
    }

    double
    Scene::density(const types::material_id       id,
                   const parameters::ScalarPoint &p) const
    {
      return p.get(body(id).name + ".rho");
    }

    double
    Scene::youngs_modulus(const types::material_id       id,
                          const parameters::ScalarPoint &p) const
    {
      return p.get(body(id).name + ".E");
    }

    std::string
    NamedParameter::column(const std::string &qualifier) const
    {
      std::string c = name;
      std::replace(c.begin(), c.end(), ' ', '_');
      return c + qualifier + (unit.empty() ? "" : "_" + unit);
    }

    std::vector<NamedParameter>
    Scene::parameters() const
    {
      // Physical ranges: every value a scene or a sweep gives must lie in
      // them (sweep_points checks); beyond them a run loses all digits
      // (1e300 Pa) or fails deep in LAPACK.
      const double E_max     = 1e13; // [Pa] 8x diamond's modulus
      const double rho_max   = 1e5;  // [kg/m^3] 4x osmium's density
      const double alpha_max = 1e5;  // [1/s] damping ratio 8 at 1 kHz
      const double beta_max  = 1e-3; // [s] damping ratio 3 at 1 kHz
      const double k_n_max   = 1e20; // [N/m^3] 1e8 x a pad's penalty
      const double k_max     = 1e15; // [N/m] 1e5 x a steel bar's EA/L
      const double m_max     = 1e6;  // [kg] a loaded lorry
      std::vector<NamedParameter> list;
      for (const Body &b : bodies)
        {
          list.push_back({b.name + ".E",
                          "Pa",
                          b.material.youngs_modulus,
                          0.,
                          true,
                          E_max,
                          true});
          list.push_back({b.name + ".rho",
                          "kg_per_m3",
                          b.material.density,
                          0.,
                          true,
                          rho_max,
                          true});
          if (b.own_damping)
            {
              list.push_back({b.name + ".alpha",
                              "per_s",
                              b.alpha,
                              0.,
                              false,
                              alpha_max,
                              false});
              list.push_back(
                {b.name + ".beta", "s", b.beta, 0., false, beta_max, false});
            }
        }
      for (const ContactPair &c : contact_pairs)
        {
          // the Interface entry's range
          list.push_back({c.name + ".mu",
                          "",
                          c.friction_coefficient,
                          0.,
                          false,
                          10.,
                          false});
          list.push_back({c.name + ".k_n",
                          "N_per_m3",
                          c.normal_stiffness,
                          0.,
                          false,
                          k_n_max,
                          false});
          list.push_back({c.name + ".k_t",
                          "N_per_m3",
                          c.tangential_stiffness,
                          0.,
                          false,
                          k_n_max,
                          false});
        }
      if (contact_pairs.size() > 1) // links(): every pair's mu at once
        list.push_back({"contact.mu",
                        "",
                        contact_pairs[0].friction_coefficient,
                        0.,
                        false,
                        10.,
                        false});
      for (const SpringSet &s : springs)
        list.push_back(
          {s.name + ".k", "N_per_m", s.stiffness, 0., false, k_max, true});
      for (const LumpedMass &m : masses)
        list.push_back({m.name + ".m", "kg", m.mass, 0., false, m_max, true});
      list.push_back(
        {"damping.alpha", "per_s", damping_alpha, 0., false, alpha_max, false});
      list.push_back(
        {"damping.beta", "s", damping_beta, 0., false, beta_max, false});
      parameters::ScalarPoint unique; // throws on a repeated name
      for (const auto &p : list)
        unique.add(p.name, p.value);
      return list;
    }

    NamedParameter
    Scene::parameter(const std::string &name) const
    {
      const auto list = parameters();
      for (const auto &p : list)
        if (p.name == name)
          return p;
      return {name, "", nominal_point().get(name)}; // throws with the names
    }

    void
    Scene::set_nominal(const std::string &name, const double value)
    {
      parameter(name); // throws on an unknown name
      for (const auto &[link, members] : links())
        if (link == name)
          for (const std::string &member : members)
            set_nominal(member, value);
      const auto dot  = name.rfind('.');
      const auto item = name.substr(0, dot);
      const auto key  = name.substr(dot + 1);
      if (item == "damping")
        (key == "alpha" ? damping_alpha : damping_beta) = value;
      for (Body &b : bodies)
        if (b.name == item)
          {
            if (key == "E")
              {
                if (b.law.anisotropic)
                  b.law.C *= value / b.material.youngs_modulus;
                b.material.youngs_modulus = value;
              }
            else if (key == "rho")
              b.material.density = value;
            else
              (key == "alpha" ? b.alpha : b.beta) = value;
          }
      for (ContactPair &c : contact_pairs)
        if (c.name == item)
          (key == "mu"  ? c.friction_coefficient :
           key == "k_n" ? c.normal_stiffness :
                          c.tangential_stiffness) = value;
      for (SpringSet &k : springs)
        if (k.name == item)
          k.stiffness = value;
      for (LumpedMass &m : masses)
        if (m.name == item)
          m.mass = value;
    }

    parameters::ScalarPoint
    Scene::nominal_point() const
    {
      parameters::ScalarPoint p;
      const auto              linked = links();
      for (const auto &n : parameters())
        if (std::none_of(linked.begin(), linked.end(), [&](const auto &l) {
              return l.first == n.name;
            }))
          p.add(n.name, n.value);
      for (const auto &[name, members] : linked)
        p.link(name, members);
      return p;
    }

    std::vector<std::pair<std::string, std::vector<std::string>>>
    Scene::links() const
    {
      std::vector<std::pair<std::string, std::vector<std::string>>> out;
      if (contact_pairs.size() > 1)
        {
          // the preload and the braking run need the pairs' mu equal
          std::vector<std::string> members;
          for (const ContactPair &c : contact_pairs)
            members.push_back(c.name + ".mu");
          out.emplace_back("contact.mu", members);
        }
      return out;
    }

    double
    Scene::common_friction_coefficient(const parameters::ScalarPoint &p) const
    {
      if (contact_pairs.empty())
        return 0.;
      const double mu = p.get(contact_pairs[0].name + ".mu");
      for (const ContactPair &c : contact_pairs)
        if (p.get(c.name + ".mu") != mu)
          throw std::runtime_error(
            "the preload and the braking run solve one Coulomb law for all "
            "contact pairs: '" +
            contact_pairs[0].name + "' has mu = " + std::to_string(mu) + ", '" +
            c.name + "' mu = " + std::to_string(p.get(c.name + ".mu")) +
            "; give them the same");
      return mu;
    }

    namespace
    {
      // "" if @p v lies in @p info's range, else the range as
      // "(must be > 0 and <= 1e+13 Pa)"
      std::string
      outside(const NamedParameter &info, const double v)
      {
        if ((info.low_open ? v > info.lowest : v >= info.lowest) &&
            v <= info.highest)
          return "";
        std::ostringstream m;
        m << "(must be " << (info.low_open ? "> " : ">= ") << info.lowest
          << " and <= " << info.highest << (info.unit.empty() ? "" : " ")
          << info.unit << ")";
        return m.str();
      }
    } // namespace

    void
    check_parameter_ranges(const Scene &scene)
    {
      for (const NamedParameter &info : scene.parameters())
        if (const std::string range = outside(info, info.value); !range.empty())
          {
            std::ostringstream m;
            m << info.name << " = " << info.value << " " << info.unit
              << " (from Materials, Damping, Interface, Springs or the mesh "
                 "file's items) is out of range "
              << range;
            throw std::runtime_error(m.str());
          }
    }

    void
    check_parameter_value(const Scene       &scene,
                          const std::string &name,
                          const double       value,
                          const std::string &entry)
    {
      const NamedParameter info = scene.parameter(name);
      if (const std::string range = outside(info, value); !range.empty())
        {
          std::ostringstream m;
          m << entry << ": " << value << " is out of range for " << info.name
            << " " << range;
          throw std::runtime_error(m.str());
        }
    }

    std::vector<parameters::ScalarPoint>
    sweep_points(const Scene &scene, const parameters::Sweep &sweep)
    {
      const parameters::ScalarPoint nominal = scene.nominal_point();
      for (const auto *axis : {&sweep.first, &sweep.second})
        {
          const std::string entry =
            axis == &sweep.first ? "Sweep/First" : "Sweep/Second";
          if (!nominal.has(axis->parameter))
            throw std::runtime_error(
              entry + " parameter = '" + axis->parameter +
              "' is not a parameter of scene " + scene.description() +
              "; its parameters are " + nominal.names());
          const NamedParameter info = scene.parameter(axis->parameter);
          for (const double v : axis->values)
            if (const std::string range = outside(info, v); !range.empty())
              {
                std::ostringstream m;
                m << entry << " values: " << v << " is out of range for "
                  << info.name << " " << range;
                throw std::runtime_error(m.str());
              }
        }
      if (sweep.first.parameter == sweep.second.parameter)
        throw std::runtime_error(
          "Sweep/First parameter and Sweep/Second parameter are both '" +
          sweep.first.parameter + "'; choose two different parameters");
      std::vector<parameters::ScalarPoint> points;
      for (const double s : sweep.second.values)
        for (const double f : sweep.first.values)
          {
            parameters::ScalarPoint p = nominal;
            p.set(sweep.second.parameter, s);
            p.set(sweep.first.parameter, f);
            points.push_back(p);
          }
      return points;
    }

    SymmetricTensor<4, 3>
    Scene::stiffness_tensor(const types::material_id       id,
                            const Point<3>                &x,
                            const parameters::ScalarPoint &p) const
    {
      const Body &b = body(id);
      if (!b.law.anisotropic)
        throw std::runtime_error("body '" + b.name + "' is isotropic");
      return (youngs_modulus(id, p) / b.material.youngs_modulus) *
             rotate_stiffness(b.law.C, b.law.rotation(x));
    }

    Tensor<2, 3>
    ElasticLaw::rotation(const Point<3> &x) const
    {
      if (frame == Frame::cartesian)
        return axes;
      const Tensor<1, 3> d = x - origin;
      Tensor<1, 3>       r = d - (d * axis) * axis;
      if (!(r.norm() > 0.))
        throw std::runtime_error(
          "a cylindrical material frame has no radial direction on its axis");
      r /= r.norm();
      const Tensor<1, 3> t = cross_product_3d(axis, r);
      Tensor<2, 3>       R;
      for (unsigned int i = 0; i < 3; ++i)
        {
          R[i][0] = r[i];
          R[i][1] = t[i];
          R[i][2] = axis[i];
        }
      return R;
    }

    const Body *
    Scene::disc() const
    {
      for (const Body &b : bodies)
        if (b.disc)
          return &b;
      return nullptr;
    }

    namespace
    {
      /**
       * The TriboBrake (thesis § 3.2.1): disc clamped at its hub, pad on the
       * disc's top face z = 0 at (pad radius, 0), support beam above the pad
       * held by springs along the sliding direction on its two side faces
       * y = +-pad/2, loaded on its top; or its disc alone.
       */
      class TriboBrakeScene : public Scene
      {
      public:
        TriboBrakeScene(const parameters::AllParameters &prm,
                        const bool                       with_pad)
          : geometry(prm.geometry)
          , mesh(prm.mesh)
          , with_pad(with_pad)
        {
          namespace material = tribobrake::material;
          namespace boundary = tribobrake::boundary;
          const auto &g      = prm.geometry;

          Body disc;
          disc.name         = "disc";
          disc.id           = material::disc;
          disc.material     = prm.materials.disc;
          disc.disc         = true;
          disc.naming_face  = boundary::disc_contact;
          disc.centre       = Point<3>();
          disc.axis         = Tensor<1, 3>({0., 0., 1.});
          disc.reference    = Tensor<1, 3>({1., 0., 0.});
          disc.inner_radius = g.disc_inner_radius;
          disc.outer_radius = g.disc_outer_radius;
          bodies.push_back(disc);
          holds.push_back(
            {"disc hub", boundary::clamped, {{true, true, true}}});
          if (!with_pad)
            return;

          Body pad;
          pad.name     = "pad";
          pad.id       = material::pad;
          pad.material = prm.materials.pad;
          bodies.push_back(pad);
          Body support;
          support.name     = "support";
          support.id       = material::support;
          support.material = prm.materials.support;
          bodies.push_back(support);

          ContactPair pair;
          pair.name                 = "pad on disc";
          pair.slave                = boundary::pad_contact;
          pair.master               = boundary::disc_contact;
          pair.centre               = Point<3>(g.pad_radius, 0., 0.);
          pair.normal               = Tensor<1, 3>({0., 0., 1.});
          pair.plane_axes[0]        = Tensor<1, 3>({1., 0., 0.});
          pair.plane_axes[1]        = Tensor<1, 3>({0., 1., 0.});
          pair.plane_origin         = Point<3>();
          pair.sliding              = prm.interface.sliding_tangent();
          pair.axis                 = Tensor<1, 3>({0., 0., 1.});
          pair.axis_point           = Point<3>();
          pair.size                 = g.pad_size;
          pair.friction_coefficient = prm.interface.friction_coefficient;
          pair.normal_stiffness     = prm.interface.normal_stiffness;
          pair.tangential_stiffness = prm.interface.tangential_stiffness;
          contact_pairs.push_back(pair);

          // the loading arm holds the support top's centre along the radius
          const Point<3> top(g.pad_radius, 0., g.pad_size + g.support_length);
          point_holds.push_back({"loading arm", top, 0});
          loads.push_back({"support top",
                           boundary::support_top,
                           Tensor<1, 3>({0., 0., -1.})});
          probes.push_back({"pad centre", pair.centre});

          // Spring stations: on the two support faces y = +-pad_size/2,
          // rows at x = the centres of n_rows equal strips of the face
          // width, and along the support at evenly spaced heights, both
          // ends included.
          const auto &s = prm.springs;
          if (s.n_rows_per_side == 0)
            return;
          SpringSet springs_set;
          springs_set.name      = "support springs";
          springs_set.body      = material::support;
          springs_set.direction = Tensor<1, 3>({0., 1., 0.});
          springs_set.stiffness = s.stiffness;
          springs_set.radius    = s.attachment_radius;
          springs_set.tolerance = 1e-6 * g.pad_size;
          for (const double y : {-g.pad_size / 2, g.pad_size / 2})
            for (unsigned int r = 0; r < s.n_rows_per_side; ++r)
              for (unsigned int k = 0; k < s.n_per_row; ++k)
                {
                  springs_set.stations.emplace_back(
                    g.pad_radius - g.pad_size / 2 +
                      g.pad_size * (r + 0.5) / s.n_rows_per_side,
                    y,
                    g.pad_size + (s.n_per_row == 1 ?
                                    g.support_length / 2 :
                                    g.support_length * k / (s.n_per_row - 1)));
                  springs_set.station_normals.push_back(
                    Tensor<1, 3>({0., y > 0 ? 1. : -1., 0.}));
                }
          springs.push_back(springs_set);
        }

        void
        make_mesh(Triangulation<3> &tria) const override
        {
          tribobrake::make_tribobrake_mesh(geometry, mesh, with_pad, tria);
        }

        std::string
        description() const override
        {
          return with_pad ? "tribobrake" : "disc";
        }

        io::NamedSets
        named_sets(const Triangulation<3> &tria) const override
        {
          io::NamedSets sets = tribobrake::tribobrake_sets(tria);
          // the spring stations as a node set when they are mesh vertices
          // (they are for the default mesh counts)
          for (const SpringSet &s : springs)
            {
              unsigned int on_vertex = 0;
              for (const Point<3> &x : s.stations)
                for (const Point<3> &v : tria.get_vertices())
                  if (x.distance(v) < 1e-9 * geometry.pad_size)
                    {
                      ++on_vertex;
                      break;
                    }
              if (on_vertex == s.stations.size())
                sets.node_sets[s.name] = s.stations;
            }
          return sets;
        }

      private:
        const parameters::Geometry geometry;
        const parameters::Mesh     mesh;
        const bool                 with_pad;
      };
    } // namespace

    std::unique_ptr<Scene>
    make_scene(const parameters::AllParameters &prm)
    {
      std::unique_ptr<Scene> scene;
      if (prm.scene.type == "tribobrake" || prm.scene.type == "disc")
        scene =
          std::make_unique<TriboBrakeScene>(prm,
                                            prm.scene.type == "tribobrake");
      else if (prm.scene.type == "mesh file")
        scene = std::make_unique<MeshFileScene>(prm);
      if (scene)
        {
          scene->damping_alpha = prm.damping.alpha;
          scene->damping_beta  = prm.damping.beta;
          scene->parameters(); // names must be unique
          return scene;
        }
      throw std::runtime_error("Scene/Type = '" + prm.scene.type +
                               "': allowed are tribobrake, disc and mesh file");
    }

    void
    check_for_analysis(const Scene       &scene,
                       const std::string &analysis,
                       const bool         seeded)
    {
      if (analysis == "cea" || analysis == "model updating")
        return;
      const std::string what = "Scene/Analysis = " + analysis + " needs ";
      if (scene.contact_pairs.empty())
        throw std::runtime_error(what + "a contact pair; scene " +
                                 scene.description() + " has none");
      if (scene.loads.empty())
        throw std::runtime_error(what + "a load; scene " + scene.description() +
                                 " has none");
      if (seeded && scene.disc() == nullptr)
        throw std::runtime_error(
          "Transient/Initial perturbation > 0 seeds a disc mode; scene " +
          scene.description() + " has no body of type disc");
    }
  } // namespace scene
} // namespace squeal
