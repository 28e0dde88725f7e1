// The structural model's subsections: Materials, Springs, Damping and
// Interface (the linear friction coupling of the CEA).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <squeal/parameters/parameters.h>

#include "entries.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace parameters
  {
    using namespace dealii;
    using internal::check;
    using internal::positive;
    using internal::str;

    namespace
    {
      void
      declare_material(ParameterHandler  &prm,
                       const std::string &name,
                       const Material    &m,
                       const std::string &note)
      {
        prm.enter_subsection(name);
        prm.declare_entry("Young's modulus",
                          str(m.youngs_modulus),
                          positive,
                          "Young's modulus [Pa]." + note);
        prm.declare_entry("Poisson's ratio",
                          str(m.poisson_ratio),
                          Patterns::Double(-0.99, 0.49),
                          "Poisson's ratio [-].");
        prm.declare_entry("Density",
                          str(m.density),
                          positive,
                          "Mass density [kg/m^3].");
        prm.leave_subsection();
      }

      void
      parse_material(ParameterHandler  &prm,
                     const std::string &name,
                     Material          &m)
      {
        prm.enter_subsection(name);
        m.youngs_modulus = prm.get_double("Young's modulus");
        m.poisson_ratio  = prm.get_double("Poisson's ratio");
        m.density        = prm.get_double("Density");
        prm.leave_subsection();
        check(m.youngs_modulus > 0. && m.density > 0.,
              "Materials/" + name + ": Young's modulus = " +
                str(m.youngs_modulus) + " Pa and Density = " + str(m.density) +
                " kg/m^3 must both be > 0");
      }
    } // namespace

    void
    Materials::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Materials");
      declare_material(prm, "Disc", disc, "");
      declare_material(prm,
                       "Pad",
                       pad,
                       " Nominal value of the named parameter pad.E.");
      declare_material(prm,
                       "Support",
                       support,
                       " Its Density is used only when Support density "
                       "model = steel.");
      prm.declare_entry("Support density model",
                        support_density_model,
                        Patterns::Selection("updated|steel"),
                        "updated: the density calibrated so that the support "
                        "modes match the thesis (Support updated density); "
                        "steel: Support/Density.");
      prm.declare_entry("Support updated density",
                        str(support_updated_density),
                        positive,
                        "Calibrated support density [kg/m^3] (model updating, "
                        "see benchmarks/cea_tribobrake/README.md).");
      prm.leave_subsection();
    }

    void
    Materials::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Materials");
      parse_material(prm, "Disc", disc);
      parse_material(prm, "Pad", pad);
      parse_material(prm, "Support", support);
      support_density_model   = prm.get("Support density model");
      support_updated_density = prm.get_double("Support updated density");
      prm.leave_subsection();
      if (support_density_model == "updated")
        support.density = support_updated_density;
    }

    void
    Springs::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Springs");
      prm.declare_entry("Rows per side",
                        std::to_string(n_rows_per_side),
                        Patterns::Integer(0, 8),
                        "Rows of springs on each of the two support faces "
                        "normal to the sliding direction.");
      prm.declare_entry("Springs per row",
                        std::to_string(n_per_row),
                        Patterns::Integer(1, 401),
                        "Springs along each row, evenly spaced over the "
                        "support length, both ends included.");
      prm.declare_entry("Stiffness",
                        str(stiffness),
                        Patterns::Double(0.,
                                         Patterns::Double::max_double_value),
                        "Stiffness of one spring in the sliding direction "
                        "[N/m]; far ends fixed.");
      prm.declare_entry(
        "Attachment radius",
        str(attachment_radius),
        Patterns::Double(0., Patterns::Double::max_double_value),
        "Radius [m] of the disc of the support face on which each spring "
        "acts: a Winkler layer in the sliding direction with cosine-bell "
        "stiffness density (largest at the station, 0 at the radius), "
        "normalised so that each spring keeps its stiffness and integrated "
        "consistently, so that the spring model is the same on every mesh "
        "and degree (the braking simulation lumps it on the face nodes, "
        "which its explicit time stepping needs). 0: the nearest node only "
        "(the thesis' point springs; a point force on a 3D body is "
        "singular, so frequencies carried by the springs drift under "
        "refinement and the tolerance-driven mesh cannot converge). A model "
        "parameter, not a discretisation one: at E_pad = 1 GPa the pad mode "
        "near 2.1 kHz moves from 2152 Hz (1.25 mm) to 2251 Hz (2.5 mm).");
      prm.leave_subsection();
    }

    void
    Springs::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Springs");
      n_rows_per_side   = prm.get_integer("Rows per side");
      n_per_row         = prm.get_integer("Springs per row");
      stiffness         = prm.get_double("Stiffness");
      attachment_radius = prm.get_double("Attachment radius");
      prm.leave_subsection();
    }

    void
    Damping::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Damping");
      prm.declare_entry("Alpha",
                        str(alpha),
                        Patterns::Double(0.,
                                         Patterns::Double::max_double_value),
                        "Rayleigh mass coefficient alpha [1/s].");
      prm.declare_entry("Beta",
                        str(beta),
                        Patterns::Double(0.,
                                         Patterns::Double::max_double_value),
                        "Rayleigh stiffness coefficient beta [s] (multiplies "
                        "the structural stiffness, not the interface).");
      prm.declare_entry(
        "Modal damping ratios",
        "",
        Patterns::Anything(),
        "Modal damping of the complex eigenvalue analysis, added to the "
        "Rayleigh damping: `f1: zeta1; f2: zeta2; ...` with frequencies "
        "f [Hz] ascending and damping ratios zeta in [0, 1) (measured "
        "modal damping, or one `0: zeta` for a uniform ratio). Every mode "
        "phi_i (M-normalised) of the frictionless assembly (K without "
        "friction, M) up to Eigensolver/Maximum frequency x Reduced band "
        "factor gets the ratio interpolated linearly at its frequency f_i "
        "(constant beyond the ends): C += sum_i 2 zeta(f_i) omega_i "
        "M phi_i phi_i^T M. Set Alpha and Beta to 0 for modal damping "
        "alone. Empty: none. Not for the braking run, the sensitivities or "
        "Output/Export matrices.");
      prm.leave_subsection();
    }

    void
    Damping::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Damping");
      alpha = prm.get_double("Alpha");
      beta  = prm.get_double("Beta");
      modal_ratios.clear();
      for (const std::string &item :
           Utilities::split_string_list(prm.get("Modal damping ratios"), ';'))
        {
          const std::string where =
            "Damping/Modal damping ratios, item '" + item + "'";
          const auto fields = Utilities::split_string_list(item, ':');
          double     f = -1., zeta = -1.;
          bool       ok = fields.size() == 2;
          try
            {
              if (ok)
                {
                  f    = Utilities::string_to_double(fields[0]);
                  zeta = Utilities::string_to_double(fields[1]);
                }
            }
          catch (...)
            {
              ok = false;
            }
          check(ok, where + ": write it `frequency_Hz: ratio`");
          check(std::isfinite(f) && f >= 0. && zeta >= 0. && zeta < 1.,
                where + ": the frequency must be >= 0 Hz and the ratio in "
                        "[0, 1)");
          check(modal_ratios.empty() || f > modal_ratios.back().first,
                where + ": the frequencies must ascend");
          modal_ratios.emplace_back(f, zeta);
        }
      prm.leave_subsection();
    }

    Tensor<1, 3>
    Interface::sliding_tangent() const
    {
      Tensor<1, 3> t;
      if (sliding_direction == "rotation")
        t[1] = (rotation_sense == "counterclockwise" ? 1. : -1.);
      else
        {
          const auto v = Utilities::string_to_double(
            Utilities::split_string_list(sliding_direction, ','));
          // scaled first: the norm of (1e200, 0) overflows
          const double scale = std::max(std::abs(v[0]), std::abs(v[1]));
          t[0]               = v[0] / scale;
          t[1]               = v[1] / scale;
          t /= t.norm();
        }
      return t;
    }

    void
    Interface::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Interface");
      prm.declare_entry("Normal stiffness",
                        str(normal_stiffness),
                        Patterns::Double(0.,
                                         Patterns::Double::max_double_value),
                        "Normal interface stiffness per unit area [N/m^3]; "
                        "the thesis' 2.5895e8 N/m over 1e-4 m^2.");
      prm.declare_entry(
        "Tangential stiffness",
        str(tangential_stiffness),
        Patterns::Double(0., Patterns::Double::max_double_value),
        "Tangential (shear) interface stiffness per unit area [N/m^3] of the "
        "CEA's coupling: a traction k_t (u_disc - u_pad) on the in-plane "
        "relative displacement, the contact layer's elastic shear (its "
        "asperities' Mindlin stiffness), which holds the pad in the plane "
        "beside the sliding friction force mu k_n g. 0: none (thesis eq. "
        "3-1). Named parameter <pair>.k_t; not used by the static preload "
        "(full slip) nor the braking run.");
      prm.declare_entry("Friction coefficient",
                        str(friction_coefficient),
                        Patterns::Double(0., 10.),
                        "Coulomb friction coefficient [-] of every contact "
                        "pair that does not give its own (named parameter "
                        "<pair>.mu).");
      prm.declare_entry("Sliding direction",
                        sliding_direction,
                        Patterns::Anything(),
                        "`rotation` (the disc's velocity at the pad centre) "
                        "or two numbers `tx, ty`: the direction in the disc "
                        "plane in which the disc slides under the pad.");
      prm.declare_entry("Rotation sense",
                        rotation_sense,
                        Patterns::Selection("counterclockwise|clockwise"),
                        "Sense of the disc rotation about +z.");
      prm.declare_entry("Quadrature",
                        quadrature,
                        Patterns::Selection("mortar|nodal"),
                        "mortar: segment-based integration over the overlap "
                        "of pad and disc faces; nodal: one point per pad-face "
                        "node (node-pair elements on matching meshes).");
      prm.leave_subsection();
    }

    void
    Interface::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Interface");
      normal_stiffness     = prm.get_double("Normal stiffness");
      tangential_stiffness = prm.get_double("Tangential stiffness");
      friction_coefficient = prm.get_double("Friction coefficient");
      sliding_direction    = prm.get("Sliding direction");
      rotation_sense       = prm.get("Rotation sense");
      quadrature           = prm.get("Quadrature");
      prm.leave_subsection();
      if (sliding_direction != "rotation")
        {
          const auto parts =
            Utilities::split_string_list(sliding_direction, ',');
          bool   ok      = parts.size() == 2;
          double largest = 0;
          for (const auto &p : parts)
            {
              char        *end = nullptr;
              const double v   = std::strtod(p.c_str(), &end);
              ok = ok && end != p.c_str() && *end == '\0' && std::isfinite(v);
              largest = std::max(largest, std::abs(v));
            }
          check(ok && largest > 0,
                "Interface/Sliding direction must be `rotation` or two "
                "numbers `tx, ty` not both zero, not '" +
                  sliding_direction + "'");
        }
    }
  } // namespace parameters
} // namespace squeal
