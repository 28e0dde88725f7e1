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

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/parameter_handler.h>

#include <mpi.h>

#include <filesystem>
#include <fstream>
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
     * directory or one of its ancestors, or contains an input of this run
     * (parameters::register_input()): replacing it would delete the run's
     * own input;
     * or if it exists and @p overwrite is false.
     */
    std::string
    partial_directory(const std::string &directory, bool overwrite);

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

    /**
     * An output file whose failures are not lost: a std::ofstream that, when
     * it is closed or destroyed, records a failed open, write or close (a
     * full disk, a file-size limit, a vanished folder) for check_writes().
     * Every file of a run's output folder is written through one, so that a
     * run never publishes a truncated result.
     */
    class OutputFile : public std::ofstream
    {
    public:
      /** Opens @p path (truncating, or as @p mode says). */
      explicit OutputFile(const std::filesystem::path &path,
                          std::ios::openmode           mode = std::ios::out);
      /** Closes the file; a failure is recorded (destructors do not throw). */
      ~OutputFile() override;
      /**
       * Closes the file now.
       * @throws std::runtime_error naming the file if opening, writing or
       * closing it failed.
       */
      void
      close();

    private:
      std::string name;
      bool        recorded = false;
      void
      record();
    };

    /**
     * The VTK flags of every .vtu file squeal writes: zlib at its fastest
     * level (DataOutBase::VtkFlags::best_speed) instead of deal.II's
     * default best_compression, which spent most of an output's time
     * compressing for files a few per cent smaller.
     */
    inline dealii::DataOutBase::VtkFlags
    vtk_flags()
    {
      dealii::DataOutBase::VtkFlags flags;
      flags.compression_level = dealii::DataOutBase::VtkFlags::best_speed;
      return flags;
    }

    /**
     * Writes @p out as the one .vtu file @p file, collectively over
     * @p comm: on one rank through an OutputFile, on several through
     * deal.II's MPI-IO writer (DataOutInterface::write_vtu_in_parallel,
     * whose failures throw).
     */
    void
    write_vtu(const dealii::DataOutInterface<3, 3> &out,
              const std::string                    &file,
              MPI_Comm                              comm);

    /**
     * Collective over @p comm: every rank learns whether any OutputFile of
     * any rank failed since the last call (without MPI initialised, this
     * process alone).
     * @throws std::runtime_error on every rank, naming the first file that
     * could not be written and the rank, if one failed.
     */
    void
    check_writes(MPI_Comm comm);

    /**
     * Ends a run collectively over @p comm: check_writes(), then rank 0
     * removes @p scratch (a sub-folder of @p partial, if not empty) and
     * publishes @p partial as @p directory (publish_directory()).
     * @throws std::runtime_error on every rank if a write or the rename
     * failed on any (nothing is published then).
     */
    void
    finish_run(const std::string &partial,
               const std::string &directory,
               MPI_Comm           comm,
               const std::string &scratch = "");

    /** Renames the finished @p partial to @p directory, replacing an earlier
     * one (partial_directory() has checked that this is allowed). Call it
     * after check_writes(): a failed write must fail the run. */
    inline void
    publish_directory(const std::string &partial, const std::string &directory)
    {
      std::filesystem::remove_all(normalised(directory));
      std::filesystem::rename(partial, normalised(directory));
    }
  } // namespace io
} // namespace squeal

#endif
