// The braking grid (Braking/Grid): one braking run per point of the sweep
// grid, each in its own folder, and the grid's stability map.

#include <squeal/analyses/braking.h>
#include <squeal/io/output_directory.h>
#include <squeal/scene/scene.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;
    namespace fs = std::filesystem;

    void
    run_braking_grid(const parameters::AllParameters &prm,
                     const ParameterHandler          &handler,
                     MPI_Comm                         comm)
    {
      ConditionalOStream pcout(std::cout,
                               Utilities::MPI::this_mpi_process(comm) == 0);
      const bool         root   = Utilities::MPI::this_mpi_process(comm) == 0;
      const std::string  work   = io::start_work_directory(prm.output.directory,
                                                        prm.output.overwrite,
                                                        handler,
                                                        comm);
      const auto         scene  = scene::make_scene(prm);
      const auto         points = scene::sweep_points(*scene, prm.sweep);
      const auto        &first  = prm.sweep.first.parameter,
                 &second        = prm.sweep.second.parameter;
      std::ostringstream table;
      table << std::setprecision(8) << "point,folder,"
            << scene->parameter(first).column() << ','
            << scene->parameter(second).column()
            << ",verdict,dominant_frequency_Hz,growth_rate_per_s,"
               "growth_rate_at_dominant_frequency_per_s,"
               "limit_cycle_amplitude_m_per_s,separated,"
               "leading_edge_p_min_over_mean,leading_edge_p_max_over_mean,"
               "wall_time_s\n";
      unsigned int n_failed = 0;
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          parameters::AllParameters at     = prm;
          at.transient.grid                = false;
          at.transient.checkpoint_interval = 0;
          std::ostringstream name;
          name << "point_" << std::setw(2) << std::setfill('0') << i;
          at.output.directory = (fs::path(work) / name.str()).string();
          at.output.overwrite = true;
          const double a = points[i].get(first), b = points[i].get(second);
          pcout << "\n=== Grid point " << i + 1 << " of " << points.size()
                << ": " << first << " = " << a << ", " << second << " = " << b
                << " (" << name.str() << ") ===" << std::endl;
          table << i << ',' << name.str() << ',' << a << ',' << b << ',';
          std::string    failure;
          BrakingSummary summary;
          {
            BrakingAnalysis run(at, handler, comm, {{first, a}, {second, b}});
            try
              {
                run.run();
                summary = run.summary();
              }
            catch (const std::exception &e)
              {
                failure = e.what();
              }
          }
          if (!failure.empty())
            {
              ++n_failed;
              pcout << "Grid point " << i + 1 << " failed: " << failure
                    << std::endl;
              std::string quoted = failure;
              std::replace(quoted.begin(), quoted.end(), '"', '\'');
              table << "\"failed: " << quoted << "\",,,,,,,,\n";
              continue;
            }
          table << summary.verdict << ',' << summary.dominant_frequency << ','
                << summary.growth.growth_rate << ','
                << summary.modal_growth.growth_rate << ','
                << summary.growth.final_amplitude << ','
                << (summary.separated ? 1 : 0) << ','
                << summary.leading_min_over_mean << ','
                << summary.leading_max_over_mean << ',' << summary.wall_time
                << '\n';
        }
      if (n_failed == points.size())
        throw std::runtime_error("every point of the braking grid failed "
                                 "(see the messages above); nothing written");
      if (root)
        {
          io::OutputFile out(fs::path(work) / "stability_table.csv");
          out << table.str();
        }
      pcout << "\nStability table (" << points.size() << " braking runs):\n"
            << table.str();
      io::finish_run(work, prm.output.directory, comm);
      pcout << "Results in " << prm.output.directory << std::endl;
    }
  } // namespace analyses
} // namespace squeal
