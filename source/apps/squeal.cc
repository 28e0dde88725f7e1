// squeal's program: read a .prm file, echo the resolved parameters, run the
// analysis it asks for (analyses/run.h does the work). Usage:
//   squeal [--overwrite] FILE.prm      run
//   squeal --validate FILE.prm         parse, build the scene, run nothing
//   squeal --export-mesh OUT.inp FILE.prm   the scene's coarse mesh and sets
//                                      as an Abaqus/CalculiX input file
//   squeal --resume DIRECTORY          continue a stopped braking run
//   squeal --print-parameters          every parameter with default, range,
//   help

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <squeal/analyses/run.h>
#include <squeal/base/errors.h>
#include <squeal/parameters/parameters.h>

#include <petscsys.h>

#include <iostream>
#include <string>
#include <vector>

int
main(int argc, char **argv)
{
  using namespace dealii;
  using namespace squeal;
  // PETSc reads options from the command line; squeal's own must not reach it.
  int                              petsc_argc = 1;
  char                           **petsc_argv = argv;
  Utilities::MPI::MPI_InitFinalize mpi(petsc_argc, petsc_argv, 1);
  // PETSc's and SLEPc's failures reach the user as one line (deal.II's
  // exceptions, caught below), not as PETSc's printed trace
  PetscPushErrorHandler(PetscIgnoreErrorHandler, nullptr);
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  try
    {
      const analyses::CommandLine cl = analyses::parse_command_line(
        std::vector<std::string>(argv + 1, argv + argc));
      parameters::AllParameters prm;
      ParameterHandler          handler;
      if (cl.print_parameters)
        {
          prm.declare_parameters(handler);
          if (root)
            handler.print_parameters(std::cout, ParameterHandler::PRM);
          return 0;
        }
      analyses::read_parameters(cl, prm, handler);
      if (cl.validate || !cl.export_mesh.empty())
        analyses::validate_or_export(cl, prm, root);
      else
        analyses::run_analysis(prm, handler, cl.resume, MPI_COMM_WORLD);
    }
  catch (const std::bad_alloc &)
    {
      std::cerr << "squeal: error: out of memory on rank "
                << Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)
                << " (std::bad_alloc); the model, the sweep or the band needs "
                   "more than this machine has: use fewer cells, a lower "
                   "degree, fewer sweep points or a narrower band, or mpirun "
                   "on more machines"
                << std::endl;
      return 1;
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "squeal: error: " << one_line(e) << std::endl;
      return 1;
    }
  return 0;
}
