// The start of a run's output folder (output_directory.h), with rank 0's
// failure sent to every rank.

#include <deal.II/base/mpi.h>

#include <squeal/io/output_directory.h>
#include <squeal/parameters/parameters.h>

#include <algorithm>
#include <fstream>

namespace squeal
{
  namespace io
  {
    namespace
    {
      namespace fs = std::filesystem;

      fs::path
      resolved(const std::string &path)
      {
        return fs::weakly_canonical(fs::absolute(path));
      }

      // true if @p inner is @p outer or lies below it (both resolved)
      bool
      contains(const fs::path &outer, const fs::path &inner)
      {
        const auto mismatch =
          std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end());
        return mismatch.first == outer.end();
      }
    } // namespace

    namespace
    {
      // the files OutputFile could not write, since the last check_writes()
      std::vector<std::string> &
      failed_writes()
      {
        static std::vector<std::string> list;
        return list;
      }
    } // namespace

    OutputFile::OutputFile(const std::filesystem::path &path,
                           const std::ios::openmode     mode)
      : std::ofstream(path, mode)
      , name(path.string())
    {}

    OutputFile::~OutputFile()
    {
      if (is_open())
        std::ofstream::close();
      record();
    }

    void
    OutputFile::record()
    {
      if (!good() && !recorded)
        {
          failed_writes().push_back(name);
          recorded = true;
        }
    }

    void
    OutputFile::close()
    {
      if (is_open())
        std::ofstream::close();
      record();
      if (!good())
        throw std::runtime_error("could not write '" + name +
                                 "' (a full disk or a file-size limit?)");
    }

    void
    write_vtu(const dealii::DataOutInterface<3, 3> &out,
              const std::string                    &file,
              MPI_Comm                              comm)
    {
      if (dealii::Utilities::MPI::n_mpi_processes(comm) > 1)
        out.write_vtu_in_parallel(file, comm);
      else
        {
          OutputFile vtu(file);
          out.write_vtu(vtu);
        }
    }

    void
    check_writes(MPI_Comm comm)
    {
      std::string mine;
      if (!failed_writes().empty())
        mine = failed_writes().front() +
               (failed_writes().size() > 1 ?
                  " and " + std::to_string(failed_writes().size() - 1) +
                    " other file(s)" :
                  std::string());
      failed_writes().clear();
      int mpi = 0;
      MPI_Initialized(&mpi);
      const std::vector<std::string> all =
        mpi ? dealii::Utilities::MPI::all_gather(comm, mine) :
              std::vector<std::string>{mine};
      for (unsigned int rank = 0; rank < all.size(); ++rank)
        if (!all[rank].empty())
          throw std::runtime_error(
            "could not write '" + all[rank] + "' (rank " +
            std::to_string(rank) +
            "; a full disk or a file-size limit?): the results are "
            "incomplete and were not published");
    }

    void
    finish_run(const std::string &partial,
               const std::string &directory,
               MPI_Comm           comm,
               const std::string &scratch)
    {
      check_writes(comm);
      std::string failure;
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        try
          {
            if (!scratch.empty())
              std::filesystem::remove_all(std::filesystem::path(partial) /
                                          scratch);
            publish_directory(partial, directory);
          }
        catch (const std::exception &e)
          {
            failure = "could not publish '" + partial + "' as '" + directory +
                      "': " + e.what();
          }
      failure = dealii::Utilities::MPI::broadcast(comm, failure, 0);
      if (!failure.empty())
        throw std::runtime_error(failure);
    }

    std::string
    partial_directory(const std::string &directory, const bool overwrite)
    {
      const std::string target = normalised(directory);
      const fs::path    full   = resolved(target);
      if (target.empty() || contains(full, resolved(fs::current_path())))
        throw std::runtime_error(
          "output directory '" + directory +
          "' is the working directory or contains it; a run replaces its "
          "output folder, so give it a folder of its own");
      for (const std::string &file : parameters::inputs())
        if (const fs::path input = resolved(file); contains(full, input))
          throw std::runtime_error(
            "output directory '" + directory + "' contains the input '" +
            input.string() +
            "'; a run replaces its output folder, so give it a folder of its "
            "own");
      if (fs::exists(target) && !overwrite)
        throw std::runtime_error(
          "output directory '" + directory +
          "' exists; set Output/Overwrite = true or pass --overwrite to "
          "replace it");
      return target + ".partial";
    }

    std::string
    start_work_directory(const std::string              &directory,
                         const bool                      overwrite,
                         const dealii::ParameterHandler &handler,
                         MPI_Comm                        comm,
                         const std::vector<std::string> &subs)
    {
      const std::string partial = partial_directory(directory, overwrite);
      std::string       failure;
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        {
          try
            {
              // a stopped braking run's progress is not thrown away unasked
              if (std::filesystem::is_regular_file(
                    std::filesystem::path(partial) / "checkpoint" / "latest") &&
                  !overwrite)
                throw std::runtime_error(
                  "'" + partial +
                  "' holds the checkpoint of a stopped braking run; continue "
                  "it with squeal --resume " +
                  normalised(directory) +
                  ", or pass --overwrite to discard it");
              fresh_directory(partial);
              for (const std::string &sub : subs)
                std::filesystem::create_directories(
                  std::filesystem::path(partial) / sub);
              const std::string file = partial + "/parameters.prm";
              std::ofstream     out(file);
              handler.print_parameters(out, dealii::ParameterHandler::PRM);
              out.close();
              if (!out)
                throw std::runtime_error("cannot write '" + file + "'");
            }
          catch (const std::exception &e)
            {
              failure = "output directory '" + directory + "': " + e.what();
            }
        }
      failure = dealii::Utilities::MPI::broadcast(comm, failure, 0);
      if (!failure.empty())
        throw std::runtime_error(failure);
      return partial;
    }
  } // namespace io
} // namespace squeal
