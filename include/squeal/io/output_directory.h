#ifndef squeal_io_output_directory_h
#define squeal_io_output_directory_h

/**
 * @file
 * The output-folder contract of every squeal program: a run never destroys
 * an earlier result. It writes into DIRECTORY.partial and renames it to
 * DIRECTORY only when everything is written; an existing DIRECTORY is
 * replaced only when the user asked for it (Output/Overwrite or
 * --overwrite).
 */

#include <deal.II/base/parameter_handler.h>

#include <mpi.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace squeal
{
  namespace io
  {
    /**
     * The temporary folder DIRECTORY.partial of a run writing into
     * @p directory (nothing is created).
     * @throws std::runtime_error naming the folder if it exists and
     * @p overwrite is false.
     */
    inline std::string
    partial_directory(const std::string &directory, const bool overwrite)
    {
      if (std::filesystem::exists(directory) && !overwrite)
        throw std::runtime_error(
          "output directory '" + directory +
          "' exists; set Output/Overwrite = true or pass --overwrite to "
          "replace it");
      return directory + ".partial";
    }

    /** Empties (or creates) @p partial and its sub-folder @p sub (if any). */
    inline void
    fresh_directory(const std::string &partial, const std::string &sub = "")
    {
      std::filesystem::remove_all(partial);
      std::filesystem::create_directories(std::filesystem::path(partial) / sub);
    }

    /**
     * Starts a run's output: DIRECTORY.partial (partial_directory()) made
     * fresh by rank 0 of @p comm with the sub-folders @p subs, and the
     * resolved parameters of @p handler echoed into it as parameters.prm.
     * Collective: a failure on rank 0 (a folder that cannot be created, a
     * full disk) reaches every rank, so that none waits for it.
     * @return the partial folder's path
     * @throws std::runtime_error on every rank, naming the folder, if it
     * exists without @p overwrite or cannot be written.
     */
    std::string
    start_work_directory(const std::string              &directory,
                         bool                            overwrite,
                         const dealii::ParameterHandler &handler,
                         MPI_Comm                        comm,
                         const std::vector<std::string> &subs = {});

    /** Renames the finished @p partial to @p directory, replacing an earlier
     * one (partial_directory() has checked that this is allowed). */
    inline void
    publish_directory(const std::string &partial, const std::string &directory)
    {
      std::filesystem::remove_all(directory);
      std::filesystem::rename(partial, directory);
    }
  } // namespace io
} // namespace squeal

#endif
