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

#include <filesystem>
#include <stdexcept>
#include <string>

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
