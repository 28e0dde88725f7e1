// squeal's program: read a .prm file, echo the resolved parameters, run the
// analysis it asks for. Usage:
//   squeal [--overwrite] FILE.prm      run
//   squeal --validate FILE.prm         parse, build the scene, run nothing
//   squeal --export-mesh OUT.inp FILE.prm   the scene's coarse mesh and sets
//                                      as an Abaqus/CalculiX input file
//   squeal --resume DIRECTORY          continue a stopped braking run
//   squeal --print-parameters          every parameter with default, range, help

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <squeal/cea/complex_eigenvalue_analysis.h>
#include <squeal/contact/preload.h>
#include <squeal/io/mesh_file.h>
#include <squeal/scene/scene.h>
#include <squeal/parameters/parameters.h>
#include <squeal/transient/braking.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

int
main(int argc, char **argv)
{
  using namespace dealii;
  // PETSc reads options from the command line; squeal's own must not reach it.
  int   petsc_argc = 1;
  char **petsc_argv = argv;
  Utilities::MPI::MPI_InitFinalize mpi(petsc_argc, petsc_argv, 1);
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  const std::vector<std::string> args(argv + 1, argv + argc);
  const std::string usage =
    "usage: squeal [--overwrite] FILE.prm | --validate FILE.prm | "
    "--export-mesh OUT.inp FILE.prm | --resume DIRECTORY | "
    "--print-parameters";
  try
    {
      squeal::parameters::AllParameters prm;
      ParameterHandler                  handler;
      if (args.size() == 1 && args[0] == "--print-parameters")
        {
          prm.declare_parameters(handler);
          if (root)
            handler.print_parameters(std::cout, ParameterHandler::PRM);
          return 0;
        }
      bool        validate = false, overwrite = false, resume = false;
      std::string file, export_mesh;
      for (unsigned int i = 0; i < args.size(); ++i)
        if (const std::string &a = args[i]; a == "--validate")
          validate = true;
        else if (a == "--export-mesh")
          {
            if (i + 1 == args.size() || args[i + 1].empty() ||
                args[i + 1][0] == '-')
              throw std::runtime_error("--export-mesh needs the .inp file to "
                                       "write\n" + usage);
            export_mesh = args[++i];
          }
        else if (a == "--resume")
          resume = true;
        else if (a == "--overwrite")
          overwrite = true;
        else if (!a.empty() && a[0] == '-')
          throw std::runtime_error("unknown option '" + a + "'\n" + usage);
        else if (file.empty())
          file = a;
        else
          throw std::runtime_error("more than one parameter file given\n" + usage);
      if (file.empty())
        throw std::runtime_error(std::string(resume ? "no directory" :
                                                      "no parameter file") +
                                 " given\n" + usage);
      if (resume)
        {
          // A braking run's folder: DIRECTORY.partial holds the parameters
          // it was started with and its checkpoint.
          namespace fs = std::filesystem;
          std::string directory = fs::path(file).lexically_normal().string();
          while (directory.size() > 1 && directory.back() == '/')
            directory.pop_back();
          const std::string suffix = ".partial";
          if (directory.size() > suffix.size() &&
              directory.compare(directory.size() - suffix.size(),
                                suffix.size(), suffix) == 0)
            directory.resize(directory.size() - suffix.size());
          const std::string partial = directory + suffix;
          if (!fs::is_directory(partial))
            throw std::runtime_error(
              "--resume " + file + ": no run in progress ('" + partial +
              "' does not exist" +
              (fs::is_directory(directory) ? "; '" + directory +
                                               "' holds a finished run" :
                                             "") +
              ")");
          prm.read(handler, partial + "/parameters.prm");
          if (prm.scene.analysis != "braking")
            throw std::runtime_error("--resume " + file +
                                     ": only braking runs can be resumed (" +
                                     partial + "/parameters.prm has Scene/"
                                     "Analysis = " + prm.scene.analysis + ")");
          prm.output.directory = directory;
        }
      else
        prm.read(handler, file);
      prm.output.overwrite = prm.output.overwrite || overwrite;
      if (validate || !export_mesh.empty())
        {
          // the scene, checked against its mesh and the analysis
          const auto scene = squeal::scene::make_scene(prm);
          squeal::scene::check_for_analysis(
            *scene, prm.scene.analysis,
            prm.scene.analysis == "braking" &&
              prm.transient.initial_perturbation > 0.);
          if (!export_mesh.empty())
            {
              if (std::filesystem::exists(export_mesh) && !overwrite)
                throw std::runtime_error("--export-mesh: '" + export_mesh +
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
                squeal::io::write_abaqus(tria, scene->named_sets(tria),
                                         export_mesh);
              if (root)
                std::cout << "Wrote " << export_mesh << ": "
                          << tria.n_active_cells() << " cells of scene "
                          << scene->description() << std::endl;
              return 0;
            }
        }
      if (validate)
        {
          if (root)
            {
              std::cout << file << ": valid (scene " << prm.scene.type
                        << ", " << prm.scene.analysis;
              if (prm.scene.analysis == "braking")
                std::cout << ", " << prm.transient.normal_force << " N, "
                          << prm.transient.end_time << " s"
                          << (prm.transient.grid ?
                                ", a grid of " +
                                  std::to_string(prm.sweep_points().size()) +
                                  " runs" :
                                std::string());
              else if (prm.scene.analysis != "preload")
                std::cout << ", " << prm.sweep.second.values.size() << " x "
                          << prm.sweep.first.values.size() << " sweep points";
              else
                std::cout << ", " << prm.preload.normal_force << " N";
              std::cout << ", output to " << prm.output.directory << ")"
                        << std::endl;
            }
          return 0;
        }
      // Catch inside the analysis' scope so that its TimerOutput is not
      // destroyed while an exception is in flight.
      std::string failure;
      if (prm.scene.analysis == "braking" && prm.transient.grid)
        {
          if (resume)
            throw std::runtime_error(
              "a braking grid cannot be resumed (its points write no "
              "checkpoints); run it again");
          squeal::transient::run_braking_grid(prm, handler, MPI_COMM_WORLD);
        }
      else if (prm.scene.analysis == "braking")
        {
          squeal::transient::BrakingAnalysis analysis(prm, handler,
                                                      MPI_COMM_WORLD);
          try
            {
              if (resume)
                analysis.resume();
              else
                analysis.run();
            }
          catch (const std::exception &e)
            {
              failure = e.what();
            }
        }
      else if (prm.scene.analysis == "preload")  // else cea, preloaded cea
        {
          squeal::contact::PreloadAnalysis analysis(prm, handler,
                                                    MPI_COMM_WORLD);
          try
            {
              analysis.run();
            }
          catch (const std::exception &e)
            {
              failure = e.what();
            }
        }
      else
        {
          squeal::cea::ComplexEigenvalueAnalysis analysis(prm, handler,
                                                          MPI_COMM_WORLD);
          try
            {
              analysis.run();
            }
          catch (const std::exception &e)
            {
              failure = e.what();
            }
        }
      if (!failure.empty())
        throw std::runtime_error(failure);
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "squeal: error: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}
