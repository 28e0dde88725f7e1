// Checkpoints of the braking run (Braking/Checkpoint interval): the samples
// appended to binary files and the integrator's state written through a
// temporary file and a rename, and the resume that reads them back.

#include <deal.II/base/mpi.h>

#include <squeal/analyses/braking.h>
#include <squeal/io/output_directory.h>

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;
    namespace fs = std::filesystem;

    namespace
    {
      const char checkpoint_tag[] = "squeal braking checkpoint 2";

      // zlib's CRC-32 of @p bytes continued from @p crc
      std::uint32_t
      crc32_of(const std::string &bytes, const std::uint32_t crc = 0)
      {
        return static_cast<std::uint32_t>(
          crc32(crc,
                reinterpret_cast<const Bytef *>(bytes.data()),
                static_cast<uInt>(bytes.size())));
      }

      // the whole of @p path ("" if it cannot be read)
      std::string
      contents(const fs::path &path)
      {
        std::ifstream in(path, std::ios::binary);
        return {std::istreambuf_iterator<char>(in),
                std::istreambuf_iterator<char>()};
      }

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

    std::uint32_t
    BrakingAnalysis::parameters_checksum() const
    {
      return crc32_of(contents(fs::path(work_dir) / "parameters.prm"));
    }

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
      // Each part runs on every rank, and a failure on one (a full disk)
      // stops all of them with its message; the gather is also the barrier
      // between the parts.
      const auto collective = [&](const auto &work) {
        std::string failure;
        try
          {
            work();
          }
        catch (const std::exception &e)
          {
            failure = e.what();
          }
        for (const std::string &message :
             Utilities::MPI::all_gather(comm, failure))
          if (!message.empty())
            throw std::runtime_error("the checkpoint at step " +
                                     std::to_string(next_step) + ": " +
                                     message);
      };
      const auto state_file = [&](const std::uint64_t step) {
        return dir / ("state." + std::to_string(step) + "." +
                      std::to_string(rank) + ".bin");
      };
      collective([&]() {
        if (rank == 0)
          {
            // every rank holds the same samples; rank 0 keeps them
            std::ostringstream f, h;
            for (std::size_t i = saved_samples; i < samples.size(); ++i)
              f.write(reinterpret_cast<const char *>(samples[i].data()),
                      sizeof(samples[i]));
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
            for (const auto &[name, bytes, crc] :
                 {std::tuple(dir / "samples.bin", f.str(), &samples_crc),
                  std::tuple(dir / "history.bin", h.str(), &history_crc)})
              {
                io::OutputFile out(name, std::ios::binary | std::ios::app);
                out.write(bytes.data(), bytes.size());
                out.close(); // throws naming the file
                *crc = crc32_of(bytes, *crc);
              }
          }
        saved_samples = samples.size();
        saved_history = history.time.size();
        // the state, then its CRC-32: a damaged byte fails the resume
        std::ostringstream f;
        put<std::uint64_t>(f, model.n_dofs());
        put<std::uint64_t>(f, n_s);
        put<std::uint64_t>(f, next_step);
        put<std::uint64_t>(f, n_snapshots);
        put<std::uint64_t>(f, n_frames);
        put<std::uint64_t>(f, saved_samples);
        put<std::uint64_t>(f, saved_history);
        put(f, samples_crc);
        put(f, history_crc);
        put(f, parameters_crc);
        put(f, wall);
        put_list(f, snapshots);
        put_list(f, frames);
        put_list(f, faces);
        dynamics->save(f);
        const std::string body = f.str();
        io::OutputFile    out(state_file(next_step), std::ios::binary);
        out.write(checkpoint_tag, sizeof(checkpoint_tag));
        out.write(body.data(), body.size());
        put(out, crc32_of(body));
        out.close();
      });
      // Every rank's state is complete: only now does `latest` point to it
      // (through a rename), and the previous states go.
      collective([&]() {
        if (rank == 0)
          {
            io::OutputFile f(dir / "latest.tmp");
            f << next_step << ' ' << Utilities::MPI::n_mpi_processes(comm)
              << '\n';
            f.close();
            fs::rename(dir / "latest.tmp", dir / "latest");
          }
      });
      if (last_checkpoint > 0)
        fs::remove(state_file(last_checkpoint));
      last_checkpoint = next_step;
    }

    std::pair<unsigned int, double>
    BrakingAnalysis::read_checkpoint()
    {
      // Collective: a check that fails on one rank (its own state file)
      // stops every rank with that rank's message.
      std::pair<unsigned int, double> step_wall;
      std::string                     failure;
      try
        {
          step_wall = read_checkpoint_files();
        }
      catch (const std::exception &e)
        {
          failure = e.what();
        }
      for (const std::string &message :
           Utilities::MPI::all_gather(comm, failure))
        if (!message.empty())
          throw std::runtime_error(message);
      return step_wall;
    }

    std::pair<unsigned int, double>
    BrakingAnalysis::read_checkpoint_files()
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
      last_checkpoint        = step;
      const std::string raw  = contents(name);
      const std::size_t head = sizeof(checkpoint_tag);
      if (raw.size() < head + sizeof(std::uint32_t) ||
          raw.compare(0, head, checkpoint_tag, head) != 0)
        throw std::runtime_error("'" + name +
                                 "' is not a checkpoint of this version of "
                                 "squeal's braking run");
      const std::string body =
        raw.substr(head, raw.size() - head - sizeof(std::uint32_t));
      std::uint32_t stored = 0;
      std::copy_n(raw.data() + raw.size() - sizeof(stored),
                  sizeof(stored),
                  reinterpret_cast<char *>(&stored));
      if (crc32_of(body) != stored)
        throw std::runtime_error(
          "the checkpoint '" + name +
          "' fails its CRC-32 check (damaged bytes); it cannot be resumed, "
          "start the run again");
      std::istringstream f(body);
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
      samples_crc          = get<std::uint32_t>(f);
      history_crc          = get<std::uint32_t>(f);
      const auto   started = get<std::uint32_t>(f);
      const double wall    = get<double>(f);
      if (f && started != parameters_crc)
        throw std::runtime_error(
          "'" + work_dir +
          "/parameters.prm' differs from the parameters the run started "
          "with (CRC-32); a resumed run must continue the same model: undo "
          "the edit, or start a new run with --overwrite");
      snapshots = get_list(f);
      frames    = get_list(f);
      faces     = get_list(f);
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
            {
              fs::resize_file(path, bytes);
              if (crc32_of(contents(path)) !=
                  (file == "samples.bin" ? samples_crc : history_crc))
                throw std::runtime_error(
                  "the checkpoint file '" + path.string() +
                  "' fails its CRC-32 check (damaged bytes); it cannot be "
                  "resumed, start the run again");
            }
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
