// The whole parameter set: every subsection declared and parsed in turn, the
// Output subsection, and reading a file with its INCLUDEs. Each subsection is a
// struct whose defaults are the values in the header, so the defaults live in
// one place; the .cc files give them ranges and help texts with SI units, and
// check the few rules that join several parameters.

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
    void
    Output::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Output");
      prm.declare_entry("Directory",
                        directory,
                        Patterns::FileName(),
                        "Output directory; a run refuses to replace an "
                        "existing one unless Overwrite is true or --overwrite "
                        "is given.");
      prm.declare_entry("Overwrite",
                        overwrite ? "true" : "false",
                        Patterns::Bool(),
                        "Replace an existing output directory.");
      prm.declare_entry("Mode shapes",
                        mode_output,
                        Patterns::Selection("none|unstable and first|all"),
                        "Which mode shapes go to modes.pvd: every unstable "
                        "mode at its largest growth rate and all modes of "
                        "the first point, all modes of every point, or none.");
      prm.declare_entry("Export matrices",
                        "",
                        Patterns::List(Patterns::Integer(0), 0, 1000),
                        "CEA: sweep point indices (from 0, in the order of "
                        "eigenvalues.csv) whose M, C, K go to matrices/ in "
                        "the MatrixMarket format, with every matrix part, "
                        "the parts' coefficients (parts.csv) and the DoF "
                        "coordinates (dofs.csv), for an independent solve; "
                        "empty: none.");
      prm.leave_subsection();
    }

    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      directory   = prm.get("Directory");
      overwrite   = prm.get_bool("Overwrite");
      mode_output = prm.get("Mode shapes");
      export_points.clear();
      for (const auto &item :
           Utilities::split_string_list(prm.get("Export matrices")))
        export_points.push_back(Utilities::string_to_int(item));
      prm.leave_subsection();
      check(!directory.empty(), "Output/Directory must not be empty");
    }

    void
    AllParameters::declare_parameters(ParameterHandler &prm) const
    {
      scene.declare_parameters(prm);
      geometry.declare_parameters(prm);
      mesh.declare_parameters(prm);
      materials.declare_parameters(prm);
      springs.declare_parameters(prm);
      damping.declare_parameters(prm);
      interface.declare_parameters(prm);
      eigensolver.declare_parameters(prm);
      sweep.declare_parameters(prm);
      preload.declare_parameters(prm);
      transient.declare_parameters(prm);
      output.declare_parameters(prm);
    }

    void
    AllParameters::parse_parameters(ParameterHandler &prm)
    {
      scene.parse_parameters(prm);
      geometry.parse_parameters(prm);
      mesh.parse_parameters(prm);
      materials.parse_parameters(prm);
      springs.parse_parameters(prm);
      damping.parse_parameters(prm);
      interface.parse_parameters(prm);
      eigensolver.parse_parameters(prm);
      sweep.parse_parameters(prm);
      preload.parse_parameters(prm);
      transient.parse_parameters(prm);
      output.parse_parameters(prm);
      check(mesh.contact_refinements == 0 || scene.analysis == "preloaded cea",
            "Mesh/Contact refinements = " +
              std::to_string(mesh.contact_refinements) +
              " refines by the preload's contact pressure and needs "
              "Scene/Analysis = preloaded cea (it is " +
              scene.analysis +
              "); without a preload set it to 0 and refine the disc track "
              "by geometry with Mesh/Disc refinements under pad");
    }

    namespace
    {
      // The INCLUDE chain of FILE (paths as deal.II opens them: from the
      // working directory): one that comes back to a file on it would
      // recurse without end in ParameterHandler.
      void
      check_includes(const std::string &file, std::vector<std::string> &chain)
      {
        chain.push_back(file);
        std::ifstream in(file);
        std::string   line;
        for (unsigned int number = 1; std::getline(in, line); ++number)
          {
            std::istringstream words(line);
            std::string        word;
            if (!(words >> word) ||
                (word != "include" && word != "INCLUDE" && word != "Include"))
              continue;
            std::string target;
            std::getline(words >> std::ws, target);
            while (!target.empty() &&
                   std::isspace(static_cast<unsigned char>(target.back())))
              target.pop_back();
            const auto same = [&](const std::string &other) {
              std::error_code ec;
              return std::filesystem::equivalent(target, other, ec);
            };
            if (std::any_of(chain.begin(), chain.end(), same) ||
                chain.size() > 32)
              {
                std::string path;
                for (const auto &f : chain)
                  path += "'" + f + "' -> ";
                throw std::runtime_error(
                  "in parameter file '" + file + "', line " +
                  std::to_string(number) + ": INCLUDE '" + target +
                  "' comes back to a file that includes it (" + path + "'" +
                  target + "'); remove the cycle");
              }
            if (std::filesystem::is_regular_file(target))
              check_includes(target, chain);
          }
        chain.pop_back();
      }
    } // namespace

    void
    parse_file(ParameterHandler &prm, const std::string &filename)
    {
      // a pipe would block the open below: look first
      if (std::filesystem::exists(filename) &&
          !std::filesystem::is_regular_file(filename))
        throw std::runtime_error("parameter file '" + filename +
                                 "' is not a regular file (a directory, a "
                                 "pipe or a device); give a .prm file");
      if (!std::ifstream(filename))
        throw std::runtime_error("cannot open parameter file '" + filename +
                                 "'");
      {
        std::vector<std::string> chain;
        check_includes(filename, chain);
      }
      try
        {
          prm.parse_input(filename, "", false, true);
        }
      catch (const ExceptionBase &e)
        {
          // deal.II's own text names the line and the entry; keep only it,
          // folded onto one line.
          std::ostringstream info;
          e.print_info(info);
          std::istringstream words(info.str());
          std::string        folded, w;
          while (words >> w)
            folded += (folded.empty() ? "" : " ") + w;
          throw std::runtime_error("in parameter file '" + filename +
                                   "': " + folded);
        }
    }

    void
    AllParameters::read(ParameterHandler &prm, const std::string &filename)
    {
      declare_parameters(prm);
      parse_file(prm, filename);
      try
        {
          parse_parameters(prm);
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error("in parameter file '" + filename +
                                   "': " + e.what());
        }
      // A relative mesh path is the parameter file's neighbour: made
      // absolute here, and in the handler, so that the copy of the
      // parameters a run writes (and --resume reads) finds it too.
      auto &mesh = scene.mesh_file.file;
      if (!mesh.empty() && std::filesystem::path(mesh).is_relative())
        {
          mesh = std::filesystem::absolute(
                   std::filesystem::path(filename).parent_path() / mesh)
                   .lexically_normal()
                   .string();
          prm.enter_subsection("Scene");
          prm.enter_subsection("Mesh file");
          prm.set("File", mesh);
          prm.leave_subsection();
          prm.leave_subsection();
        }
    }
  } // namespace parameters
} // namespace squeal
