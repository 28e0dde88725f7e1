// Sweep parameters: the named scalar parameters of a point, the axes of a
// sweep ("name: v1, v2, ..." or "name: a .. b, n [log]") and the Sweep
// subsection.

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
      double &
      member(ScalarPoint &p, const std::string &name)
      {
        static const std::vector<std::pair<std::string, double ScalarPoint::*>>
          members = {{"pad modulus", &ScalarPoint::E_pad},
                     {"friction coefficient", &ScalarPoint::mu},
                     {"interface stiffness", &ScalarPoint::interface_stiffness},
                     {"spring stiffness", &ScalarPoint::spring_stiffness},
                     {"support density", &ScalarPoint::support_density},
                     {"rayleigh alpha", &ScalarPoint::alpha},
                     {"rayleigh beta", &ScalarPoint::beta}};
        for (const auto &[n, m] : members)
          if (n == name)
            return p.*m;
        sweepable_parameter(name); // throws with the allowed names
        throw std::logic_error("unreachable");
      }

      std::string
      sweepable_names()
      {
        std::string names;
        for (const auto &p : sweepable_parameters())
          names += (names.empty() ? "" : "|") + std::string(p.name);
        return names;
      }
    } // namespace

    double
    ScalarPoint::get(const std::string &name) const
    {
      return member(const_cast<ScalarPoint &>(*this), name);
    }

    void
    ScalarPoint::set(const std::string &name, const double value)
    {
      member(*this, name) = value;
    }

    const std::vector<SweepableParameter> &
    sweepable_parameters()
    {
      static const std::vector<SweepableParameter> list = {
        {"pad modulus", "E_pad", "Pa", 0., true, true},
        {"friction coefficient", "mu", "", 0., false, false},
        {"interface stiffness", "k_n", "N_per_m3", 0., false, true},
        {"spring stiffness", "k_spring", "N_per_m", 0., false, true},
        {"support density", "rho_support", "kg_per_m3", 0., true, true},
        {"rayleigh alpha", "alpha", "per_s", 0., false, false},
        {"rayleigh beta", "beta", "s", 0., false, false}};
      return list;
    }

    const SweepableParameter &
    sweepable_parameter(const std::string &name)
    {
      for (const auto &p : sweepable_parameters())
        if (name == p.name)
          return p;
      throw std::runtime_error("unknown sweep parameter '" + name +
                               "'; allowed: " + sweepable_names());
    }

    std::string
    column_name(const std::string &name, const std::string &qualifier)
    {
      const auto &p = sweepable_parameter(name);
      return std::string(p.symbol) + qualifier +
             (p.unit[0] ? "_" + std::string(p.unit) : std::string());
    }

    void
    SweepAxis::parse(const std::string &entry)
    {
      const std::string forms =
        "; allowed: 'log A B N' (N log-spaced values from A to B > 0), "
        "'linear A B N' or a comma-separated list of values";
      const auto        &info = sweepable_parameter(parameter);
      std::istringstream words(values_text);
      std::string        kind;
      words >> kind;
      values.clear();
      log_spaced = kind == "log";
      if (kind == "log" || kind == "linear")
        {
          double       a, b;
          unsigned int n;
          std::string  rest;
          if (!(words >> a >> b >> n) || (words >> rest) || n == 0 ||
              n > 100000)
            throw std::runtime_error("invalid parameter: " + entry + " = '" +
                                     values_text + "'" + forms);
          if (log_spaced && (a <= 0 || b <= 0))
            throw std::runtime_error("invalid parameter: " + entry +
                                     ": a log sweep needs positive ends");
          for (unsigned int i = 0; i < n; ++i)
            {
              const double t = n == 1 ? 0. : double(i) / (n - 1);
              values.push_back(log_spaced ? a * std::pow(b / a, t) :
                                            a + (b - a) * t);
            }
        }
      else
        for (const auto &item : Utilities::split_string_list(values_text))
          {
            std::size_t used = 0;
            double      v    = 0;
            try
              {
                v = std::stod(item, &used);
              }
            catch (const std::exception &)
              {
                used = 0;
              }
            if (used == 0 || used != item.size())
              throw std::runtime_error("invalid parameter: " + entry + ": '" +
                                       item + "' is not a number" + forms);
            values.push_back(v);
          }
      if (values.empty())
        throw std::runtime_error("invalid parameter: " + entry + " is empty" +
                                 forms);
      for (const double v : values)
        check(std::isfinite(v) &&
                (info.low_open ? v > info.lowest : v >= info.lowest),
              entry + ": " + str(v) + " is out of range for the " + info.name +
                " (must be " + (info.low_open ? "> " : ">= ") +
                str(info.lowest) + ")");
    }

    bool
    SweepAxis::log_scale() const
    {
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      return !values.empty() && *lo > 0 && (log_spaced || *hi > 10 * *lo);
    }

    void
    Sweep::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Sweep");
      const std::string forms =
        " Values: 'log A B N' (N log-spaced values from A to B), "
        "'linear A B N' (N evenly spaced), or a comma-separated list.";
      prm.declare_entry("First parameter",
                        first.parameter,
                        Patterns::Selection(sweepable_names()),
                        "The parameter along which modes are tracked and "
                        "unstable regions are intervals (the x axis of the "
                        "plots). Units: pad modulus Pa, interface stiffness "
                        "N/m^3, spring stiffness N/m, support density kg/m^3, "
                        "Rayleigh alpha 1/s, Rayleigh beta s.");
      prm.declare_entry("First values",
                        first.values_text,
                        Patterns::Anything(),
                        "Values of the first parameter, SI units." + forms);
      prm.declare_entry("Second parameter",
                        second.parameter,
                        Patterns::Selection(sweepable_names()),
                        "The parameter of which each value gets its own "
                        "tracked sweep of the first (one curve family of the "
                        "plots).");
      prm.declare_entry("Second values",
                        second.values_text,
                        Patterns::Anything(),
                        "Values of the second parameter, SI units." + forms);
      prm.leave_subsection();
    }

    void
    Sweep::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Sweep");
      first.parameter    = prm.get("First parameter");
      first.values_text  = prm.get("First values");
      second.parameter   = prm.get("Second parameter");
      second.values_text = prm.get("Second values");
      prm.leave_subsection();
      check(first.parameter != second.parameter,
            "Sweep/First parameter and Sweep/Second parameter are both '" +
              first.parameter + "'; choose two different parameters");
      first.parse("Sweep/First values");
      second.parse("Sweep/Second values");
    }
  } // namespace parameters
} // namespace squeal
