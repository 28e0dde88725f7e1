// The start of a run's output folder (output_directory.h), with rank 0's
// failure sent to every rank.

#include <deal.II/base/mpi.h>

#include <squeal/io/output_directory.h>

#include <fstream>

namespace squeal
{
  namespace io
  {
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
