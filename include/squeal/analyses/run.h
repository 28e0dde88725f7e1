#ifndef squeal_analyses_run_h
#define squeal_analyses_run_h

/**
 * @file
 * What the program squeal does with its command line: the options, the
 * parameters read (from a file, or from a stopped braking run's folder), the
 * scene validated or exported, and the analysis that Scene/Analysis names
 * run (CEA, preloaded CEA, preload, braking, braking grid).
 */

#include <deal.II/base/parameter_handler.h>

#include <squeal/parameters/parameters.h>

#include <mpi.h>

#include <string>
#include <vector>

namespace squeal
{
  namespace analyses
  {
    /** The program's usage line. */
    extern const char usage[];

    /** squeal's command line. */
    struct CommandLine
    {
      bool        print_parameters = false; ///< --print-parameters
      bool        validate         = false; ///< --validate
      bool        overwrite        = false; ///< --overwrite
      bool        resume           = false; ///< --resume DIRECTORY
      std::string file;        ///< FILE.prm, or the DIRECTORY of --resume
      std::string export_mesh; ///< OUT.inp of --export-mesh
    };

    /**
     * Parses the program's arguments (without the program's name).
     * @throws std::runtime_error naming the option and giving the usage on
     * an unknown option, a missing or second file, or --export-mesh without
     * its file.
     */
    CommandLine
    parse_command_line(const std::vector<std::string> &args);

    /**
     * Reads the parameters of @p cl into @p prm through @p handler: the
     * file's, or with --resume those of DIRECTORY.partial/parameters.prm
     * with Output/Directory set to DIRECTORY; --overwrite sets
     * Output/Overwrite.
     * @throws std::runtime_error on a bad file (its name and line), a resume
     * without a run in progress, or the resume of a run that is not braking.
     */
    void
    read_parameters(const CommandLine         &cl,
                    parameters::AllParameters &prm,
                    dealii::ParameterHandler  &handler);

    /**
     * --validate and --export-mesh: builds the scene, checks it against its
     * mesh and the analysis, and writes the .inp of --export-mesh or a
     * one-line summary on rank 0 (@p root).
     * @throws std::runtime_error as scene::make_scene() and
     * scene::check_for_analysis(), if OUT.inp exists without --overwrite, or
     * if the scene refines its mesh as it makes it.
     */
    void
    validate_or_export(const CommandLine               &cl,
                       const parameters::AllParameters &prm,
                       bool                             root);

    /**
     * Runs the analysis of Scene/Analysis (resuming a braking run with
     * @p resume). An exception from the analysis is caught inside the
     * analysis' scope (so its TimerOutput is not destroyed while it is in
     * flight) and rethrown after it.
     * @throws std::runtime_error with the analysis' message, or on a resumed
     * braking grid.
     */
    void
    run_analysis(const parameters::AllParameters &prm,
                 const dealii::ParameterHandler  &handler,
                 bool                             resume,
                 MPI_Comm                         comm);
  } // namespace analyses
} // namespace squeal

#endif
