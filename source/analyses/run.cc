// The program's command line, parameter reading (with --resume), scene
// validation and export, and the dispatch to the analysis of Scene/Analysis.

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <squeal/analyses/braking.h>
#include <squeal/analyses/cea.h>
#include <squeal/analyses/model_updating.h>
#include <squeal/analyses/preload.h>
#include <squeal/analyses/run.h>
#include <squeal/base/memory_estimate.h>
#include <squeal/io/mesh_file.h>
#include <squeal/physics/structural_model.h>
#include <squeal/scene/scene.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;
    namespace fs = std::filesystem;

    namespace
    {
      // What can be known of a run's size before any mesh is built: the
      // sweep's point count, and for the built-in scenes a lower bound of
      // the DoFs (3 p^3 per cell of the coarse disc, pad and support) and of
      // the memory (the sparse matrices alone: 3 (2p + 1)^3 entries of 12
      // bytes per row, three matrices for a CEA, one otherwise), and for a
      // braking run a lower bound of its samples and contact history.
      // @throws std::runtime_error if the sweep has more than a million
      // points or a lower bound exceeds this machine's memory.
      void
      check_run_size(const parameters::AllParameters &prm)
      {
        const double n_points = double(prm.sweep.first.values.size()) *
                                prm.sweep.second.values.size();
        if (prm.scene.analysis != "preload" && n_points > 1e6)
          throw std::runtime_error(
            "Sweep: " + std::to_string(prm.sweep.first.values.size()) + " x " +
            std::to_string(prm.sweep.second.values.size()) +
            " points is more than the 1 000 000 a run can hold; sweep "
            "coarser or in parts");
        for (const unsigned int p : prm.output.export_points)
          if (prm.scene.analysis != "preload" && p >= n_points)
            throw std::runtime_error(
              "Output/Export matrices: sweep point " + std::to_string(p) +
              " does not exist; the sweep has points 0 to " +
              std::to_string(std::size_t(n_points) - 1));
        const double memory =
          double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
        const auto &m = prm.mesh;
        if (prm.scene.analysis == "braking")
          {
            // the samples (17 numbers from t = 0) and the contact history
            // (4 numbers and a status per pad-face node from History
            // start), all kept until the end
            const auto  &tr = prm.transient;
            const double pad_nodes =
              prm.scene.type == "tribobrake" ?
                std::pow(m.pad_cells_side * m.fe_degree + 1., 2) :
                1.;
            const double history = tr.end_time * tr.sampling_rate * 17. * 8. +
                                   (tr.end_time - tr.history_start) *
                                     tr.sampling_rate * pad_nodes *
                                     (4. * 8. + 4.);
            if (history > memory)
              {
                std::ostringstream m_;
                m_.precision(3);
                m_ << "Transient: " << tr.end_time * tr.sampling_rate
                   << " samples (End time x Sampling rate) of at least "
                   << pad_nodes << " pad-face nodes need at least "
                   << history / 1e9 << " GB; this machine has " << memory / 1e9
                   << " GB (lower Transient/Sampling rate or raise History "
                      "start)";
                throw std::runtime_error(m_.str());
              }
          }
        if (prm.scene.type == "mesh file")
          return;
        const double cells =
          double(m.disc_cells_circumference) * m.disc_cells_radial *
            m.disc_cells_thickness +
          (prm.scene.type == "tribobrake" ?
             double(m.pad_cells_side) * m.pad_cells_side *
               (m.pad_cells_thickness + m.support_cells_length) :
             0.);
        const double p     = m.fe_degree;
        const double dofs  = 3. * cells * p * p * p;
        const double bytes = dofs * 3. * std::pow(2. * p + 1., 3) * 12. *
                             (prm.scene.analysis == "cea" ||
                                  prm.scene.analysis == "preloaded cea" ?
                                3. :
                                1.);
        if (bytes > memory)
          {
            std::ostringstream m_;
            m_.precision(3);
            m_ << "Mesh: " << cells << " cells of degree " << m.fe_degree
               << " give at least " << dofs << " DoFs, whose matrices alone "
               << "need at least " << bytes / 1e9 << " GB; this machine has "
               << memory / 1e9
               << " GB (use fewer cells or a lower degree, or mpirun on "
                  "more machines)";
            throw std::runtime_error(m_.str());
          }
      }
    } // namespace

    namespace
    {
      // A warning ("" if none) when the CEA band's top lies beyond what a
      // built-in scene's coarse mesh resolves: fewer than 6 nodes (6 / p
      // cells of degree p) per wavelength at Eigensolver/Maximum frequency,
      // for the disc's bending wave (Kirchhoff plate, lambda = 2 pi
      // (D / rho h)^1/4 / sqrt(omega)) over its largest in-plane cell, and
      // for the shear wave (c_s = sqrt(E / 2 (1 + nu) rho)) in the pad and
      // the support over theirs. Refinement under the pad and adaptivity
      // are not counted: the warning is about the mesh a run starts from.
      std::string
      resolution_warning(const parameters::AllParameters &prm)
      {
        if (prm.scene.type == "mesh file" ||
            (prm.scene.analysis != "cea" &&
             prm.scene.analysis != "preloaded cea"))
          return "";
        const auto  &g = prm.geometry;
        const auto  &m = prm.mesh;
        const double p = m.fe_degree, f = prm.eigensolver.f_max,
                     omega = 2. * M_PI * f;
        std::ostringstream warning;
        warning.precision(3);
        const auto judge = [&](const std::string &what,
                               const double       wavelength,
                               const double       cell) {
          const double nodes = wavelength / cell * p;
          if (nodes < 6. && warning.str().empty())
            warning << "warning: at Eigensolver/Maximum frequency " << f
                    << " Hz the " << what << " is " << wavelength * 1e3
                    << " mm long, " << nodes
                    << " nodes of the starting mesh per wavelength (6 "
                       "resolve it); refine the Mesh or raise its degree, "
                       "or let Mesh/Frequency tolerance prove it";
        };
        const auto  &d = prm.materials.disc;
        const double h = g.disc_thickness;
        const double D = d.youngs_modulus * h * h * h /
                         (12. * (1. - d.poisson_ratio * d.poisson_ratio));
        judge(
          "disc's bending wave",
          2. * M_PI * std::pow(D / (d.density * h), 0.25) / std::sqrt(omega),
          std::max(2. * M_PI * g.disc_outer_radius / m.disc_cells_circumference,
                   (g.disc_outer_radius - g.disc_inner_radius) /
                     m.disc_cells_radial));
        if (prm.scene.type == "tribobrake")
          for (const auto &[name, mat, cell] :
               {std::tuple("pad's shear wave",
                           prm.materials.pad,
                           g.pad_size / m.pad_cells_side),
                std::tuple("support's shear wave",
                           prm.materials.support,
                           g.support_length / m.support_cells_length)})
            judge(name,
                  std::sqrt(mat.youngs_modulus /
                            (2. * (1. + mat.poisson_ratio) * mat.density)) /
                    f,
                  cell);
        return warning.str();
      }
    } // namespace

    const char usage[] =
      "usage: squeal [--overwrite] FILE.prm | --validate FILE.prm | "
      "--export-mesh OUT.inp FILE.prm | --resume DIRECTORY | "
      "--print-parameters";

    CommandLine
    parse_command_line(const std::vector<std::string> &args)
    {
      CommandLine cl;
      if (args.size() == 1 && args[0] == "--print-parameters")
        {
          cl.print_parameters = true;
          return cl;
        }
      for (unsigned int i = 0; i < args.size(); ++i)
        if (const std::string &a = args[i]; a == "--validate")
          cl.validate = true;
        else if (a == "--export-mesh")
          {
            if (i + 1 == args.size() || args[i + 1].empty() ||
                args[i + 1][0] == '-')
              throw std::runtime_error("--export-mesh needs the .inp file to "
                                       "write\n" +
                                       std::string(usage));
            cl.export_mesh = args[++i];
          }
        else if (a == "--resume")
          cl.resume = true;
        else if (a == "--overwrite")
          cl.overwrite = true;
        else if (!a.empty() && a[0] == '-')
          throw std::runtime_error("unknown option '" + a + "'\n" + usage);
        else if (cl.file.empty())
          cl.file = a;
        else
          throw std::runtime_error("more than one parameter file given\n" +
                                   std::string(usage));
      if (cl.file.empty())
        throw std::runtime_error(
          std::string(cl.resume ? "no directory" : "no parameter file") +
          " given\n" + usage);
      return cl;
    }

    void
    read_parameters(const CommandLine         &cl,
                    parameters::AllParameters &prm,
                    ParameterHandler          &handler)
    {
      if (cl.resume)
        {
          // A braking run's folder: DIRECTORY.partial holds the parameters
          // it was started with and its checkpoint.
          std::string directory = fs::path(cl.file).lexically_normal().string();
          while (directory.size() > 1 && directory.back() == '/')
            directory.pop_back();
          const std::string suffix = ".partial";
          if (directory.size() > suffix.size() &&
              directory.compare(directory.size() - suffix.size(),
                                suffix.size(),
                                suffix) == 0)
            directory.resize(directory.size() - suffix.size());
          const std::string partial = directory + suffix;
          if (!fs::is_directory(partial))
            throw std::runtime_error(
              "--resume " + cl.file + ": no run in progress ('" + partial +
              "' does not exist" +
              (fs::is_directory(directory) ?
                 "; '" + directory + "' holds a finished run" :
                 "") +
              ")");
          prm.read(handler, partial + "/parameters.prm");
          if (prm.scene.analysis != "braking")
            throw std::runtime_error("--resume " + cl.file +
                                     ": only braking runs can be resumed (" +
                                     partial +
                                     "/parameters.prm has Scene/"
                                     "Analysis = " +
                                     prm.scene.analysis + ")");
          prm.output.directory = directory;
        }
      else
        prm.read(handler, cl.file);
      prm.output.overwrite = prm.output.overwrite || cl.overwrite;
    }

    namespace
    {
      // The one-line summary of a valid file.
      void
      print_summary(const CommandLine               &cl,
                    const parameters::AllParameters &prm,
                    const scene::Scene              &scene)
      {
        std::cout << cl.file << ": valid (scene " << prm.scene.type << ", "
                  << prm.scene.analysis;
        if (prm.scene.analysis == "braking")
          std::cout << ", " << prm.transient.normal_force << " N, "
                    << prm.transient.end_time << " s"
                    << (prm.transient.grid ?
                          ", a grid of " +
                            std::to_string(
                              scene::sweep_points(scene, prm.sweep).size()) +
                            " runs" :
                          std::string());
        else if (prm.scene.analysis == "model updating")
          std::cout << ", "
                    << parse_updating_parameters(prm.updating.parameters).size()
                    << " parameters fitted to " << prm.updating.targets;
        else if (prm.scene.analysis != "preload")
          std::cout << ", " << prm.sweep.second.values.size() << " x "
                    << prm.sweep.first.values.size() << " sweep points";
        else
          std::cout << ", " << prm.preload.normal_force << " N";
        std::cout << ", output to " << prm.output.directory << ")" << std::endl;
        if (const std::string w = resolution_warning(prm); !w.empty())
          std::cout << w << std::endl;
        std::cout << (prm.scene.analysis == "model updating" ?
                        "Named parameters (Model updating/Parameters):" :
                        "Named parameters (Sweep/First and Second "
                        "parameter):");
        for (const auto &p : scene.parameters())
          std::cout << "\n  " << p.name << " = " << p.value
                    << (p.unit.empty() ? "" : " " + p.unit);
        std::cout << std::endl;
      }
    } // namespace

    namespace
    {
      // The sweep's names and values against the scene (CEA, braking
      // grid), or the fitted parameters' names (model updating).
      // @throws std::runtime_error as scene::sweep_points() and
      // Scene::parameter().
      void
      check_sweep_or_updating(const scene::Scene              &scene,
                              const parameters::AllParameters &prm)
      {
        const auto &analysis = prm.scene.analysis;
        if (analysis == "model updating")
          {
            const auto known = [&](const std::string &name,
                                   const std::string &entry) {
              try
                {
                  scene.parameter(name);
                }
              catch (const std::runtime_error &e)
                {
                  throw std::runtime_error("Model updating/" + entry + ": " +
                                           std::string(e.what()));
                }
            };
            // a fit stays within its bounds, so bounds inside the scene's
            // ranges keep every evaluated model physical
            for (const auto &q :
                 parse_updating_parameters(prm.updating.parameters))
              {
                known(q.scene_name, "Parameters");
                scene::check_parameter_value(
                  scene,
                  q.scene_name,
                  q.lower,
                  "Model updating/Parameters, lower bound of " + q.name);
                scene::check_parameter_value(
                  scene,
                  q.scene_name,
                  q.upper,
                  "Model updating/Parameters, upper bound of " + q.name);
              }
            const auto configurations =
              parse_configurations(prm.updating.configurations);
            for (const auto &q :
                 parse_updating_parameters(prm.updating.parameters))
              if (!q.configuration.empty() &&
                  std::none_of(configurations.begin(),
                               configurations.end(),
                               [&](const auto &c) {
                                 return c.name == q.configuration;
                               }))
                throw std::runtime_error(
                  "Model updating/Parameters: " + q.name +
                  " names the configuration '" + q.configuration +
                  "', which is not one of Model updating/Configurations");
            for (const auto &c : configurations)
              for (const auto &v : c.values)
                {
                  known(v.first, "Configurations");
                  scene::check_parameter_value(scene,
                                               v.first,
                                               v.second,
                                               "Model updating/Configurations, "
                                               "configuration '" +
                                                 c.name + "'");
                }
          }
        else if (analysis != "preload" &&
                 (analysis != "braking" || prm.transient.grid))
          scene::sweep_points(scene, prm.sweep);
      }
    } // namespace

    void
    validate_or_export(const CommandLine               &cl,
                       const parameters::AllParameters &prm,
                       const bool                       root)
    {
      // the scene, checked against its mesh and the analysis
      const auto scene = scene::make_scene(prm);
      scene::check_for_analysis(*scene,
                                prm.scene.analysis,
                                prm.scene.analysis == "braking" &&
                                  prm.transient.initial_perturbation > 0.);
      // the scene's values and the sweep's names and values in range, the
      // run's size against the machine
      scene::check_parameter_ranges(*scene);
      check_run_size(prm);
      check_sweep_or_updating(*scene, prm);
      if (!cl.export_mesh.empty())
        {
          if (fs::exists(cl.export_mesh) && !cl.overwrite)
            throw std::runtime_error("--export-mesh: '" + cl.export_mesh +
                                     "' exists; give --overwrite to "
                                     "replace it");
          Triangulation<3> tria;
          scene->make_mesh(tria);
          if (tria.n_levels() > 1)
            throw std::runtime_error(
              "--export-mesh writes the coarse mesh; this scene refines "
              "its mesh as it makes it (Mesh/Disc refinements under pad "
              "> 0)");
          if (root)
            {
              io::write_abaqus(tria, scene->named_sets(tria), cl.export_mesh);
              std::cout << "Wrote " << cl.export_mesh << ": "
                        << tria.n_active_cells() << " cells of scene "
                        << scene->description() << std::endl;
            }
          return;
        }
      if (root)
        print_summary(cl, prm, *scene);
    }

    namespace
    {
      // Runs ANALYSIS.run() (or what RUN does with it) and returns the
      // message of a failure ("" on success) after the analysis is gone.
      template <typename Analysis, typename Run>
      std::string
      run_caught(const parameters::AllParameters &prm,
                 const ParameterHandler          &handler,
                 MPI_Comm                         comm,
                 const Run                       &run)
      {
        Analysis analysis(prm, handler, comm);
        try
          {
            run(analysis);
          }
        catch (const std::exception &e)
          {
            return e.what();
          }
        return "";
      }
    } // namespace

    namespace
    {
      // The run's peak resident memory (VmHWM) summed over the ranks and on
      // the largest one, and per DoF of its largest model.
      void
      report_peak_memory(MPI_Comm comm)
      {
        Utilities::System::MemoryStats stats;
        Utilities::System::get_memory_stats(stats);
        const double       mb    = double(stats.VmHWM) / 1024.;
        const double       total = Utilities::MPI::sum(mb, comm);
        const double       most  = Utilities::MPI::max(mb, comm);
        const double       n     = physics::largest_model_size();
        ConditionalOStream pcout(std::cout,
                                 Utilities::MPI::this_mpi_process(comm) == 0);
        pcout << std::fixed << std::setprecision(0) << "Peak memory: " << total
              << " MB";
        if (Utilities::MPI::n_mpi_processes(comm) > 1)
          pcout << " over " << Utilities::MPI::n_mpi_processes(comm)
                << " ranks (largest " << most << " MB)";
        if (n > 0.)
          pcout << ", " << std::setprecision(1) << total * 1024. / n
                << " kB per DoF (" << std::setprecision(0) << n << " DoFs)";
        pcout << std::defaultfloat << std::setprecision(6) << std::endl;
      }
    } // namespace

    void
    run_analysis(const parameters::AllParameters &prm,
                 const ParameterHandler          &handler,
                 const bool                       resume,
                 MPI_Comm                         comm)
    {
      // the scene's values and the sweep against its named parameters,
      // before any output
      {
        check_run_size(prm);
        const auto scene = scene::make_scene(prm);
        scene::check_parameter_ranges(*scene);
        check_sweep_or_updating(*scene, prm);
      }
      set_factor_storage(prm.linear_solver.out_of_core,
                         prm.linear_solver.out_of_core_directory);
      std::string failure;
      if (prm.scene.analysis == "braking" && prm.transient.grid)
        {
          if (resume)
            throw std::runtime_error(
              "a braking grid cannot be resumed (its points write no "
              "checkpoints); run it again");
          run_braking_grid(prm, handler, comm);
        }
      else if (prm.scene.analysis == "braking")
        failure = run_caught<BrakingAnalysis>(prm,
                                              handler,
                                              comm,
                                              [resume](BrakingAnalysis &a) {
                                                if (resume)
                                                  a.resume();
                                                else
                                                  a.run();
                                              });
      else if (prm.scene.analysis == "preload")
        failure = run_caught<PreloadAnalysis>(
          prm, handler, comm, [](PreloadAnalysis &a) { a.run(); });
      else if (prm.scene.analysis == "model updating")
        failure = run_caught<ModelUpdatingAnalysis>(
          prm, handler, comm, [](ModelUpdatingAnalysis &a) { a.run(); });
      else // cea, preloaded cea
        failure = run_caught<ComplexEigenvalueAnalysis>(
          prm, handler, comm, [](ComplexEigenvalueAnalysis &a) { a.run(); });
      if (!failure.empty())
        throw std::runtime_error(failure);
      report_peak_memory(comm);
    }
  } // namespace analyses
} // namespace squeal
