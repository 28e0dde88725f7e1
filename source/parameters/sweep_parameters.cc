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
    using internal::str;
    const std::vector<std::string> *
    ScalarPoint::members(const std::string &name) const
    {
      for (const auto &[n, m] : links)
        if (n == name)
          return &m;
      return nullptr;
    }

    double
    ScalarPoint::get(const std::string &name) const
    {
      if (const auto *m = members(name))
        return get(m->front());
      for (const auto &[n, v] : named)
        if (n == name)
          return v;
      throw std::runtime_error("unknown parameter '" + name +
                               "'; this scene's parameters are " + names());
    }

    void
    ScalarPoint::set(const std::string &name, const double value)
    {
      if (const auto *m = members(name))
        {
          for (const std::string &member : *m)
            set(member, value);
          return;
        }
      for (auto &[n, v] : named)
        if (n == name)
          {
            v = value;
            return;
          }
      get(name); // throws with the names
    }

    void
    ScalarPoint::add(const std::string &name, const double value)
    {
      if (has(name))
        throw std::runtime_error("two parameters are called '" + name +
                                 "'; give the scene's items different names");
      named.emplace_back(name, value);
    }

    void
    ScalarPoint::link(const std::string              &name,
                      const std::vector<std::string> &group)
    {
      if (has(name))
        throw std::runtime_error("two parameters are called '" + name +
                                 "'; give the scene's items different names");
      if (group.empty())
        throw std::runtime_error("linked parameter '" + name +
                                 "' has no members");
      for (const std::string &member : group)
        get(member); // throws with the names
      links.emplace_back(name, group);
    }

    bool
    ScalarPoint::has(const std::string &name) const
    {
      if (members(name) != nullptr)
        return true;
      return std::any_of(named.begin(), named.end(), [&](const auto &nv) {
        return nv.first == name;
      });
    }

    std::string
    ScalarPoint::names() const
    {
      std::string list;
      for (const auto &nv : named)
        list += (list.empty() ? "" : "|") + nv.first;
      for (const auto &nm : links)
        list += (list.empty() ? "" : "|") + nm.first;
      return list.empty() ? "(none)" : list;
    }

    void
    SweepAxis::parse(const std::string &entry)
    {
      const std::string forms =
        "; allowed: 'log A B N' (N log-spaced values from A to B > 0), "
        "'linear A B N' or a comma-separated list of values";
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
        check(std::isfinite(v), entry + ": " + str(v) + " is not finite");
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
      prm.declare_entry(
        "First parameter",
        first.parameter,
        Patterns::Anything(),
        "The parameter along which modes are tracked and "
        "unstable regions are intervals (the x axis of the "
        "plots): a name of the scene's parameters, "
        "'<body>.E' (Young's modulus, Pa), '<body>.rho' "
        "(density, kg/m^3), '<pair>.mu' (friction "
        "coefficient; 'contact.mu' sets every pair's at "
        "once), '<pair>.k_n' (interface stiffness, "
        "N/m^3), '<pair>.k_t' (tangential interface stiffness, N/m^3), "
        "'<springs>.k' (N/m per spring), '<mass>.m' "
        "(a lumped mass, kg), 'damping.alpha' (1/s), 'damping.beta' (s), "
        "'<body>.alpha', '<body>.beta' (a body with its own "
        "Rayleigh damping). squeal --validate lists them.");
      prm.declare_entry("First values",
                        first.values_text,
                        Patterns::Anything(),
                        "Values of the first parameter, SI units." + forms);
      prm.declare_entry("Second parameter",
                        second.parameter,
                        Patterns::Anything(),
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
