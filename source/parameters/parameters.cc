// The whole parameter set: every subsection declared and parsed in turn, the
// Output subsection, and reading a file with its INCLUDEs. Each subsection is a
// struct whose defaults are the values in the header, so the defaults live in
// one place; the .cc files give them ranges and help texts with SI units, and
// check the few rules that join several parameters.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <squeal/base/errors.h>
#include <squeal/parameters/parameters.h>

#include "entries.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
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
      prm.declare_entry("Sensitivities",
                        sensitivities,
                        Patterns::Selection("none|unstable|all"),
                        "CEA with Eigensolver/Method = full: write "
                        "sensitivities.csv, d lambda / d p [1/s per unit of "
                        "p] of the modes for every named parameter p of the "
                        "scene (from the left and right eigenvectors; the "
                        "left ones cost a second full solve per point), with "
                        "the value of p that makes an unstable mode stable "
                        "to first order: unstable = the unstable modes and "
                        "those within Eigensolver/Certification margin of "
                        "the stability threshold, all = every mode in the "
                        "band, none = no file.");
      prm.declare_entry("Modal contributions",
                        modal_contributions ? "true" : "false",
                        Patterns::Bool(),
                        "CEA: write modal_contributions.csv, every unstable "
                        "region's mode at its largest growth rate written "
                        "on the real modes of the frictionless assembly "
                        "(K without friction, M) up to 1.5 times Maximum "
                        "frequency: each contributing mode's frequency, name "
                        "and share of the kinetic norm (the pair that locks "
                        "in carries most of it); one symmetric eigensolve "
                        "per point involved.");
      prm.declare_entry("Error indicator",
                        error_indicator ? "true" : "false",
                        Patterns::Bool(),
                        "CEA: write mesh_error.vtu and mesh_error.csv, "
                        "Mesh/Error indicator on the first point's modes "
                        "(where the mesh is too coarse for them, per cell "
                        "and per body); false saves its cost, a large part "
                        "of a run that solves a single point "
                        "(benchmarks/real_brake/README.md).");
      prm.leave_subsection();
    }

    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      directory           = prm.get("Directory");
      overwrite           = prm.get_bool("Overwrite");
      mode_output         = prm.get("Mode shapes");
      sensitivities       = prm.get("Sensitivities");
      modal_contributions = prm.get_bool("Modal contributions");
      error_indicator     = prm.get_bool("Error indicator");
      export_points.clear();
      for (const auto &item :
           Utilities::split_string_list(prm.get("Export matrices")))
        export_points.push_back(Utilities::string_to_int(item));
      prm.leave_subsection();
      check(!directory.empty(), "Output/Directory must not be empty");
    }

    void
    LinearSolver::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Linear solver");
      prm.declare_entry(
        "Out-of-core factorisation",
        out_of_core,
        Patterns::Selection("auto|in core|out of core"),
        "Where MUMPS keeps the factors of the sparse direct solves (the "
        "preload's contact system, the eigensolvers' shift-and-invert and "
        "inertia counts, the certification): in core (memory), out of core "
        "(ICNTL(22) = 1: written to files and read back by every solve, "
        "12 % slower and 38 % less peak memory on the default brake's "
        "preload), or auto: in core unless the run's estimated peak, "
        "printed after its set-up, exceeds the memory it holds plus what "
        "its nodes have available (MemAvailable), then out of core from "
        "there on.");
      prm.declare_entry("Out-of-core directory",
                        out_of_core_directory,
                        Patterns::Anything(),
                        "An existing directory for the factors' files out "
                        "of core (as large as the factors, whose size the "
                        "estimate after the set-up includes); empty: "
                        "MUMPS's own choice, the environment variable "
                        "MUMPS_OOC_TMPDIR or else /tmp. The files are "
                        "removed when the solver is done with them; a run "
                        "stopped by a signal leaves them.");
      prm.leave_subsection();
    }

    void
    LinearSolver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      out_of_core           = prm.get("Out-of-core factorisation");
      out_of_core_directory = prm.get("Out-of-core directory");
      prm.leave_subsection();
      check(out_of_core_directory.empty() ||
              std::filesystem::is_directory(out_of_core_directory),
            "Linear solver/Out-of-core directory = '" + out_of_core_directory +
              "' is not an existing directory");
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
      linear_solver.declare_parameters(prm);
      updating.declare_parameters(prm);
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
      linear_solver.parse_parameters(prm);
      updating.parse_parameters(prm);
      check(mesh.contact_refinements == 0 || scene.analysis == "preloaded cea",
            "Mesh/Contact refinements = " +
              std::to_string(mesh.contact_refinements) +
              " refines by the preload's contact pressure and needs "
              "Scene/Analysis = preloaded cea (it is " +
              scene.analysis +
              "); without a preload set it to 0 and refine the disc track "
              "by geometry with Mesh/Disc refinements under pad");
      check(preload.normal_law == "penalty" ||
              scene.analysis != "preloaded cea" ||
              preload.contact_state == "braking history",
            "Preload/Normal contact law = hard does not go with "
            "Scene/Analysis = preloaded cea: the CEA's interface is the "
            "tangent of the penalty law p = k_n x penetration, so the "
            "preload about which it is linearised must use that law too; "
            "set it to penalty (for the hard limit, a large Interface/Normal "
            "stiffness or k_n=)");
      check(scene.analysis != "model updating" ||
              (!updating.parameters.empty() && !updating.targets.empty()),
            "Scene/Analysis = model updating needs Model updating/Parameters "
            "(the named parameters to fit, with bounds) and Model "
            "updating/Targets (the CSV of measured modes)");
      if (!damping.modal_ratios.empty())
        {
          check(scene.analysis == "cea" || scene.analysis == "preloaded cea",
                "Damping/Modal damping ratios is a damping of the complex "
                "eigenvalue analysis (Scene/Analysis = cea or preloaded "
                "cea), not of " +
                  scene.analysis +
                  " (the braking run takes the Rayleigh damping); leave it "
                  "empty");
          check(output.sensitivities == "none",
                "Output/Sensitivities = " + output.sensitivities +
                  " does not go with Damping/Modal damping ratios: the "
                  "modal damping depends on the parameters through the "
                  "modes, which the affine sensitivities leave out; set it "
                  "to none");
          check(output.export_points.empty(),
                "Output/Export matrices does not go with Damping/Modal "
                "damping ratios: the modal damping is a dense matrix, not "
                "part of the exported C; leave one of them empty");
        }
      check(output.sensitivities == "none" || eigensolver.method == "full",
            "Output/Sensitivities = " + output.sensitivities +
              " needs Eigensolver/Method = full (it is " + eigensolver.method +
              "): the sensitivities use the full model's left and right "
              "eigenvectors; solve the points of interest with the full "
              "method, or set Output/Sensitivities = none");
    }

    namespace
    {
      // @p text without leading and trailing blanks, inner runs of blanks as
      // one space (how ParameterHandler compares names)
      std::string
      collapsed(const std::string &text)
      {
        std::istringstream words(text);
        std::string        out, w;
        while (words >> w)
          out += (out.empty() ? "" : " ") + w;
        return out;
      }

      // What a scan of a parameter file and its INCLUDEs has seen: the
      // INCLUDE chain (paths as deal.II opens them, from the working
      // directory), the open subsections and where each entry was set.
      struct FileScan
      {
        std::vector<std::string> chain;
        std::vector<std::string> sections;
        /// "A/B/entry" -> (file, "'file', line n") where it was set last
        std::map<std::string, std::pair<std::string, std::string>> set_at;
        unsigned int n_entries = 0;
      };

      // Scans @p file for what ParameterHandler does not refuse: an INCLUDE
      // that comes back to a file on the chain (it would recurse without
      // end) and an entry set twice in one file or overridden by a file it
      // includes (the last would win silently). A file's own entries may
      // override those of a file it included before them.
      void
      scan_file(const std::string &file, FileScan &scan)
      {
        scan.chain.push_back(file);
        register_input(file);
        std::ifstream in(file);
        std::string   physical;
        unsigned int  number = 0;
        while (std::getline(in, physical))
          {
            ++number;
            const unsigned int first = number;
            std::string        line  = physical;
            // continuation lines end in a backslash
            while (!line.empty() && line.back() == '\\' &&
                   std::getline(in, physical))
              {
                line.pop_back();
                line += physical;
                ++number;
              }
            line                 = collapsed(line.substr(0, line.find('#')));
            const auto  word_end = line.find(' ');
            std::string word     = line.substr(0, word_end);
            std::transform(word.begin(), word.end(), word.begin(), ::tolower);
            const std::string rest =
              word_end == std::string::npos ? "" : line.substr(word_end + 1);
            const std::string where =
              "'" + file + "', line " + std::to_string(first);
            if (word == "subsection")
              scan.sections.push_back(rest);
            else if (word == "end" && !scan.sections.empty())
              scan.sections.pop_back();
            else if (word == "set")
              {
                std::string key;
                for (const auto &section : scan.sections)
                  key += section + "/";
                key += collapsed(rest.substr(0, rest.find('=')));
                ++scan.n_entries;
                // A file may override what a file it includes sets (the
                // later value wins, as in ParameterHandler); an entry set
                // twice in one file, or set and then overridden by a file
                // it includes, is a mistake.
                const std::string here = scan.chain.back();
                const auto [it, fresh] =
                  scan.set_at.emplace(key, std::make_pair(here, where));
                if (!fresh)
                  {
                    if (std::find(scan.chain.begin(),
                                  scan.chain.end(),
                                  it->second.first) != scan.chain.end())
                      throw std::runtime_error(
                        "in parameter file " + where + ": " + key +
                        " is set a second time (first in " + it->second.second +
                        "); keep one of them");
                    it->second = {here, where};
                  }
              }
            else if (word == "include")
              {
                const std::string &target = rest;
                const auto         same   = [&](const std::string &other) {
                  std::error_code ec;
                  return std::filesystem::equivalent(target, other, ec);
                };
                if (std::any_of(scan.chain.begin(), scan.chain.end(), same) ||
                    scan.chain.size() > 32)
                  {
                    std::string path;
                    for (const auto &f : scan.chain)
                      path += "'" + f + "' -> ";
                    throw std::runtime_error(
                      "in parameter file '" + file + "', line " +
                      std::to_string(first) + ": INCLUDE '" + target +
                      "' comes back to a file that includes it (" + path + "'" +
                      target + "'); remove the cycle");
                  }
                if (std::filesystem::is_regular_file(target))
                  scan_file(target, scan);
              }
          }
        scan.chain.pop_back();
      }
    } // namespace

    namespace
    {
      std::vector<std::string> &
      input_list()
      {
        static std::vector<std::string> list;
        return list;
      }
    } // namespace

    namespace
    {
      /// "Section/entry" -> the parameter file that set it last, of the
      /// last parse_file()
      std::map<std::string, std::string> &
      setters()
      {
        static std::map<std::string, std::string> map;
        return map;
      }

      /// @p path (a file name given in an entry) made absolute against the
      /// folder of the parameter file that set the entry @p key (the top
      /// file @p top if unknown)
      std::string
      beside_setter(const std::string &path,
                    const std::string &key,
                    const std::string &top)
      {
        const auto        it   = setters().find(key);
        const std::string file = it == setters().end() ? top : it->second;
        return std::filesystem::absolute(
                 std::filesystem::path(file).parent_path() / path)
          .lexically_normal()
          .string();
      }
    } // namespace

    void
    register_input(const std::string &file)
    {
      if (!file.empty())
        input_list().push_back(file);
    }

    const std::vector<std::string> &
    inputs()
    {
      return input_list();
    }

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
      FileScan scan;
      scan_file(filename, scan);
      try
        {
          prm.parse_input(filename, "", false, true);
        }
      catch (const ExceptionBase &e)
        {
          // deal.II's own text names the line and the entry
          throw std::runtime_error("in parameter file '" + filename +
                                   "': " + one_line(e));
        }
      setters().clear();
      for (const auto &[key, where] : scan.set_at)
        setters()[key] = where.first;
      if (scan.n_entries == 0)
        throw std::runtime_error(
          "parameter file '" + filename +
          "' sets no entry; a run needs at least the analysis' own entries "
          "(squeal --print-parameters lists every entry with its default)");
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
      // A relative mesh path is the neighbour of the parameter file that
      // sets it (the file given or one it includes): made
      // absolute here, and in the handler, so that the copy of the
      // parameters a run writes (and --resume reads) finds it too.
      auto &mesh = scene.mesh_file.file;
      if (!mesh.empty() && std::filesystem::path(mesh).is_relative())
        {
          mesh = beside_setter(mesh, "Scene/Mesh file/File", filename);
          prm.enter_subsection("Scene");
          prm.enter_subsection("Mesh file");
          prm.set("File", mesh);
          prm.leave_subsection();
          prm.leave_subsection();
        }
      register_input(mesh);
      // the updating's measured data are the parameter file's neighbours
      prm.enter_subsection("Model updating");
      for (auto [entry, path] :
           {std::pair{"Targets", &updating.targets},
            std::pair{"Measurement points", &updating.measurement_points}})
        if (!path->empty())
          {
            if (std::filesystem::path(*path).is_relative())
              {
                *path = beside_setter(*path,
                                      std::string("Model updating/") + entry,
                                      filename);
                prm.set(entry, *path);
              }
            register_input(*path);
          }
      prm.leave_subsection();
    }
  } // namespace parameters
} // namespace squeal
