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

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace squeal
{
  namespace io
  {
    /**
     * @p directory normalised: `a/./b/../c/` is `a/c` (no trailing
     * separator).
     */
    inline std::string
    normalised(const std::string &directory)
    {
      std::filesystem::path p =
        std::filesystem::path(directory).lexically_normal();
      if (p.has_parent_path() && p.filename().empty())
        p = p.parent_path();
      return p.string();
    }

    /**
     * The temporary folder DIRECTORY.partial of a run writing into
     * @p directory (normalised; nothing is created).
     * @throws std::runtime_error naming the folder if it is the working
     * directory or one of its ancestors (replacing it would delete the
     * run's own input), or if it exists and @p overwrite is false.
     */
    inline std::string
    partial_directory(const std::string &directory, const bool overwrite)
    {
      const std::string target = normalised(directory);
      namespace fs             = std::filesystem;
      const fs::path full      = fs::weakly_canonical(fs::absolute(target));
      const fs::path cwd       = fs::weakly_canonical(fs::current_path());
      const auto     mismatch =
        std::mismatch(full.begin(), full.end(), cwd.begin(), cwd.end());
      if (target.empty() || mismatch.first == full.end())
        throw std::runtime_error(
          "output directory '" + directory +
          "' is the working directory or contains it; a run replaces its "
          "output folder, so give it a folder of its own");
      if (fs::exists(target) && !overwrite)
        throw std::runtime_error(
          "output directory '" + directory +
          "' exists; set Output/Overwrite = true or pass --overwrite to "
          "replace it");
      return target + ".partial";
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
      std::filesystem::remove_all(normalised(directory));
      std::filesystem::rename(partial, normalised(directory));
    }
  } // namespace io
} // namespace squeal

#endif
