// Checkpoints of the braking run (Braking/Checkpoint interval): the samples
// appended to binary files and the integrator's state written through a
// temporary file and a rename, and the resume that reads them back.

#include <squeal/analyses/braking.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;
    namespace fs = std::filesystem;

    namespace
    {
      const char checkpoint_tag[] = "squeal braking checkpoint 1";

      template <typename T>
      void
      put(std::ostream &out, const T &x)
      {
        out.write(reinterpret_cast<const char *>(&x), sizeof(T));
      }

      template <typename T>
      T
      get(std::istream &in)
      {
        T x{};
        in.read(reinterpret_cast<char *>(&x), sizeof(T));
        return x;
      }

      void
      put_list(std::ostream                                      &out,
               const std::vector<std::pair<double, std::string>> &list)
      {
        put<std::uint64_t>(out, list.size());
        for (const auto &[t, name] : list)
          {
            put(out, t);
            put<std::uint64_t>(out, name.size());
            out.write(name.data(), name.size());
          }
      }

      std::vector<std::pair<double, std::string>>
      get_list(std::istream &in)
      {
        std::vector<std::pair<double, std::string>> list(
          std::min<std::uint64_t>(get<std::uint64_t>(in), 1u << 20));
        for (auto &[t, name] : list)
          {
            t = get<double>(in);
            name.resize(std::min<std::uint64_t>(get<std::uint64_t>(in), 4096));
            in.read(name.data(), name.size());
          }
        return list;
      }
    } // namespace

    // A checkpoint: the samples and history samples taken since the last
    // one are appended to checkpoint/samples.bin and history.bin, then the
    // state (step, counters, snapshot lists, the integrator) goes to
    // state.bin through a temporary file and a rename, so a kill at any
    // moment leaves the previous complete checkpoint (the appended files are
    // cut back to its counts on resume).
    void
    BrakingAnalysis::write_checkpoint(const unsigned int next_step,
                                      const double       wall)
    {
      const fs::path     dir  = fs::path(work_dir) / "checkpoint";
      const unsigned int n_s  = mortar.n_slave();
      const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
      if (rank == 0)
        {
          // every rank holds the same samples; rank 0 keeps them
          std::ofstream f(dir / "samples.bin",
                          std::ios::binary | std::ios::app);
          for (std::size_t i = saved_samples; i < samples.size(); ++i)
            f.write(reinterpret_cast<const char *>(samples[i].data()),
                    sizeof(samples[i]));
          std::ofstream h(dir / "history.bin",
                          std::ios::binary | std::ios::app);
          for (std::size_t i = saved_history; i < history.time.size(); ++i)
            {
              put(h, history.time[i]);
              for (unsigned int j = 0; j < n_s; ++j)
                {
                  put(h, history.p_N[j][i]);
                  put(h, history.t_T1[j][i]);
                  put(h, history.t_T2[j][i]);
                  put(h, history.slip_velocity[j][i]);
                  put<std::int32_t>(h, history.status[j][i]);
                }
            }
          if (!f || !h)
            throw std::runtime_error("could not append to the checkpoint "
                                     "files in '" +
                                     dir.string() + "'");
        }
      saved_samples         = samples.size();
      saved_history         = history.time.size();
      const auto state_file = [&](const std::uint64_t step) {
        return dir / ("state." + std::to_string(step) + "." +
                      std::to_string(rank) + ".bin");
      };
      {
        std::ofstream f(state_file(next_step), std::ios::binary);
        f.write(checkpoint_tag, sizeof(checkpoint_tag));
        put<std::uint64_t>(f, model.n_dofs());
        put<std::uint64_t>(f, n_s);
        put<std::uint64_t>(f, next_step);
        put<std::uint64_t>(f, n_snapshots);
        put<std::uint64_t>(f, n_frames);
        put<std::uint64_t>(f, saved_samples);
        put<std::uint64_t>(f, saved_history);
        put(f, wall);
        put_list(f, snapshots);
        put_list(f, frames);
        put_list(f, faces);
        dynamics->save(f);
        if (!f)
          throw std::runtime_error("could not write the checkpoint '" +
                                   state_file(next_step).string() + "'");
      }
      // Every rank's state is complete: only now does `latest` point to it
      // (through a rename), and the previous states go.
      MPI_Barrier(comm);
      if (rank == 0)
        {
          {
            std::ofstream f(dir / "latest.tmp");
            f << next_step << ' ' << Utilities::MPI::n_mpi_processes(comm)
              << '\n';
          }
          fs::rename(dir / "latest.tmp", dir / "latest");
        }
      MPI_Barrier(comm);
      if (last_checkpoint > 0)
        fs::remove(state_file(last_checkpoint));
      last_checkpoint = next_step;
    }

    std::pair<unsigned int, double>
    BrakingAnalysis::read_checkpoint()
    {
      const fs::path dir   = fs::path(work_dir) / "checkpoint";
      std::uint64_t  step  = 0;
      unsigned int   ranks = 0;
      {
        std::ifstream latest(dir / "latest");
        if (!(latest >> step >> ranks))
          throw std::runtime_error("the checkpoint marker '" +
                                   (dir / "latest").string() + "' is corrupt");
      }
      if (ranks != Utilities::MPI::n_mpi_processes(comm))
        throw std::runtime_error("the checkpoint in '" + dir.string() +
                                 "' was written by " + std::to_string(ranks) +
                                 " MPI rank(s); resume with mpirun -np " +
                                 std::to_string(ranks));
      const std::string name =
        (dir /
         ("state." + std::to_string(step) + "." +
          std::to_string(Utilities::MPI::this_mpi_process(comm)) + ".bin"))
          .string();
      last_checkpoint = step;
      std::ifstream f(name, std::ios::binary);
      char          tag[sizeof(checkpoint_tag)] = {};
      f.read(tag, sizeof(tag));
      if (!f || std::string(tag) != checkpoint_tag)
        throw std::runtime_error("'" + name +
                                 "' is not a checkpoint of a "
                                 "squeal braking run");
      const unsigned int n_s     = mortar.n_slave();
      const auto         n_dofs  = get<std::uint64_t>(f);
      const auto         n_nodes = get<std::uint64_t>(f);
      if (n_dofs != model.n_dofs() || n_nodes != n_s)
        throw std::runtime_error(
          "the checkpoint '" + name + "' was written by a model with " +
          std::to_string(n_dofs) + " DoFs and " + std::to_string(n_nodes) +
          " pad-face nodes; these parameters give " +
          std::to_string(model.n_dofs()) + " and " + std::to_string(n_s) +
          " (was DIRECTORY.partial/parameters.prm edited?)");
      const auto next_step = get<std::uint64_t>(f);
      n_snapshots          = get<std::uint64_t>(f);
      n_frames             = get<std::uint64_t>(f);
      saved_samples        = get<std::uint64_t>(f);
      saved_history        = get<std::uint64_t>(f);
      const double wall    = get<double>(f);
      snapshots            = get_list(f);
      frames               = get_list(f);
      faces                = get_list(f);
      if (!f)
        throw std::runtime_error("the checkpoint '" + name + "' is short");
      try
        {
          dynamics->load(f);
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error("the checkpoint '" + name +
                                   "': " + e.what());
        }

      // The samples up to the checkpoint; whatever a killed run appended
      // after it is cut off.
      const std::size_t history_record =
        sizeof(double) + n_s * (4 * sizeof(double) + sizeof(std::int32_t));
      const std::array<std::pair<std::string, std::size_t>, 2> files = {
        {{"samples.bin", saved_samples * sizeof(samples[0])},
         {"history.bin", saved_history * history_record}}};
      for (const auto &[file, bytes] : files)
        {
          const fs::path path = dir / file;
          if (!fs::exists(path) && bytes == 0)
            continue;
          if (!fs::exists(path) || fs::file_size(path) < bytes)
            throw std::runtime_error("the checkpoint file '" + path.string() +
                                     "' is shorter than its state says");
          if (Utilities::MPI::this_mpi_process(comm) == 0)
            fs::resize_file(path, bytes);
        }
      samples.resize(saved_samples);
      {
        std::ifstream in(dir / "samples.bin", std::ios::binary);
        for (auto &row : samples)
          in.read(reinterpret_cast<char *>(row.data()), sizeof(row));
      }
      history.time.resize(saved_history);
      for (unsigned int j = 0; j < n_s; ++j)
        {
          history.p_N[j].resize(saved_history);
          history.t_T1[j].resize(saved_history);
          history.t_T2[j].resize(saved_history);
          history.slip_velocity[j].resize(saved_history);
          history.status[j].resize(saved_history);
        }
      {
        std::ifstream in(dir / "history.bin", std::ios::binary);
        for (std::size_t i = 0; i < saved_history; ++i)
          {
            history.time[i] = get<double>(in);
            for (unsigned int j = 0; j < n_s; ++j)
              {
                history.p_N[j][i]           = get<double>(in);
                history.t_T1[j][i]          = get<double>(in);
                history.t_T2[j][i]          = get<double>(in);
                history.slip_velocity[j][i] = get<double>(in);
                history.status[j][i]        = get<std::int32_t>(in);
              }
          }
      }
      return {static_cast<unsigned int>(next_step), wall};
    }
  } // namespace analyses
} // namespace squeal
