// The model updating analysis' results (see model_updating.h): the log's
// summary and the output files, written on rank 0.

#include <deal.II/base/mpi.h>

#include <squeal/analyses/model_updating.h>
#include <squeal/io/output_directory.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;
    void
    ModelUpdatingAnalysis::write_results(const updating::Result &r) const
    {
      const bool root = Utilities::MPI::this_mpi_process(comm) == 0;
      // the log's summary
      pcout << std::setprecision(6) << "  parameter  start  fitted  std. "
            << "deviation  identifiable" << std::endl;
      for (unsigned int j = 0; j < parameters.size(); ++j)
        pcout << "  " << parameters[j].name << "  " << r.initial[j] << "  "
              << r.value[j] << "  " << r.standard_deviation[j] << "  "
              << (r.identifiable[j] ? "yes" : "NO")
              << (r.at_bound[j] ? "  (at a bound)" : "") << std::endl;
      pcout << "  measured mode  Hz  model start  model fitted  error %"
            << std::endl;
      for (unsigned int i = 0; i < targets.size(); ++i)
        {
          const double f = r.modes.frequency[r.pairing.mode[i]];
          pcout << "  " << targets[i].label << "  " << targets[i].frequency
                << "  " << r.initial_modes.frequency[r.initial_pairing.mode[i]]
                << "  " << f << "  "
                << 100 * (f - targets[i].frequency) / targets[i].frequency
                << std::endl;
        }
      if (with_damping)
        {
          pcout << "  measured mode  damping ratio  model start  model fitted"
                << std::endl;
          for (unsigned int i = 0; i < targets.size(); ++i)
            if (targets[i].damping_ratio > 0.)
              pcout << "  " << targets[i].label << "  "
                    << targets[i].damping_ratio << "  "
                    << r.initial_modes.damping_ratio[r.initial_pairing.mode[i]]
                    << "  " << r.modes.damping_ratio[r.pairing.mode[i]]
                    << std::endl;
        }
      // the files on rank 0; a failure there reaches every rank, so that
      // none waits for the others
      std::string failure;
      if (root)
        try
          {
            write_files(r);
          }
        catch (const std::exception &e)
          {
            failure =
              std::string("writing the model updating results: ") + e.what();
          }
      failure = Utilities::MPI::broadcast(comm, failure, 0);
      if (!failure.empty())
        throw std::runtime_error(failure);
    }

    void
    ModelUpdatingAnalysis::write_files(const updating::Result &r) const
    {
      const auto    &scene = *model.scene;
      const double   sigma = prm.updating.measurement_error;
      io::OutputFile par(work_dir + "/updated_parameters.csv");
      par << "parameter,unit,scale,lower,upper,initial,fitted,"
             "standard_deviation,relative_deviation,at_bound,identifiable\n"
          << std::setprecision(10);
      for (unsigned int j = 0; j < parameters.size(); ++j)
        {
          const auto &q = parameters[j];
          par << q.name << ',' << scene.parameter(q.scene_name).unit << ','
              << (q.log_scale ? "log" : "linear") << ',' << q.lower << ','
              << q.upper << ',' << r.initial[j] << ',' << r.value[j] << ','
              << r.standard_deviation[j] << ','
              << r.standard_deviation[j] / std::abs(r.value[j]) << ','
              << (r.at_bound[j] ? 1 : 0) << ',' << (r.identifiable[j] ? 1 : 0)
              << '\n';
        }

      const auto quoted = [](const std::string &s) { return "\"" + s + "\""; };
      io::OutputFile tg(work_dir + "/targets.csv");
      tg
        << "label,name,configuration,measured_Hz,weight,initial_mode,initial_Hz,"
           "initial_name,initial_error_percent,initial_mac,mode,model_Hz,"
           "model_name,error_percent,mac,residual_in_sigma"
        << (with_damping ? ",measured_damping_ratio,initial_damping_ratio,"
                           "model_damping_ratio,damping_residual_in_sigma" :
                           "")
        << '\n'
        << std::setprecision(10);
      for (unsigned int i = 0; i < targets.size(); ++i)
        {
          const auto  &t  = targets[i];
          const int    k0 = r.initial_pairing.mode[i], k = r.pairing.mode[i];
          const double f0 = r.initial_modes.frequency[k0];
          const double f  = r.modes.frequency[k];
          tg << quoted(t.label) << ',' << quoted(t.name) << ','
             << quoted(configurations[t.configuration].name) << ','
             << t.frequency << ',' << t.weight << ',' << k0 << ',' << f0 << ','
             << quoted(r.initial_modes.name[k0]) << ','
             << 100 * (f0 - t.frequency) / t.frequency << ','
             << r.initial_pairing.mac[i] << ',' << k << ',' << f << ','
             << quoted(r.modes.name[k]) << ','
             << 100 * (f - t.frequency) / t.frequency << ',' << r.pairing.mac[i]
             << ','
             << std::sqrt(t.weight) * (f - t.frequency) / (sigma * t.frequency);
          // the damping ratios (empty where none was measured)
          if (with_damping && t.damping_ratio > 0.)
            tg << ',' << t.damping_ratio << ','
               << r.initial_modes.damping_ratio[k0] << ','
               << r.modes.damping_ratio[k] << ','
               << std::sqrt(t.weight) *
                    (r.modes.damping_ratio[k] - t.damping_ratio) /
                    (prm.updating.damping_error * t.damping_ratio);
          else if (with_damping)
            tg << ",,,,";
          tg << '\n';
        }

      // the sensitivities of the paired modes at the fitted point: what
      // the Jacobian is made of, per unit of each parameter
      io::OutputFile jc(work_dir + "/sensitivities.csv");
      jc << "label,mode,quantity,value";
      for (const auto &q : parameters)
        jc << ',' << quoted("d/d " + q.name);
      jc << '\n' << std::setprecision(10);
      for (unsigned int i = 0; i < targets.size(); ++i)
        {
          const int k = r.pairing.mode[i];
          jc << quoted(targets[i].label) << ',' << k << ",frequency_Hz,"
             << r.modes.frequency[k];
          for (const double d : r.modes.derivative[k])
            jc << ',' << d;
          jc << '\n';
          if (!with_damping)
            continue;
          jc << quoted(targets[i].label) << ',' << k << ",damping_ratio,"
             << r.modes.damping_ratio[k];
          for (const double d : r.modes.damping_derivative[k])
            jc << ',' << d;
          jc << '\n';
        }

      io::OutputFile md(work_dir + "/modes.csv");
      // with measurement points, the shape there (M-normalised mode)
      md << "mode,configuration,freq_Hz,name,target"
         << (with_damping ? ",damping_ratio" : "");
      for (const auto &pt : points)
        md << ',' << quoted("shape " + pt.label);
      md << '\n' << std::setprecision(10);
      for (unsigned int k = 0; k < r.modes.frequency.size(); ++k)
        {
          std::string target;
          for (unsigned int i = 0; i < targets.size(); ++i)
            if (r.pairing.mode[i] == int(k))
              target = targets[i].label;
          md << k << ','
             << quoted(configurations[r.modes.configuration[k]].name) << ','
             << r.modes.frequency[k] << ',' << quoted(r.modes.name[k]) << ','
             << quoted(target);
          if (with_damping)
            md << ',' << r.modes.damping_ratio[k];
          for (const double v : r.modes.shape[k])
            md << ',' << v;
          md << '\n';
        }

      // a header: the leading columns, then one per parameter
      const auto header = [&](io::OutputFile &f, const char *leading) {
        f << leading;
        for (const auto &q : parameters)
          f << ',' << q.name;
        f << '\n' << std::setprecision(10);
      };
      io::OutputFile id(work_dir + "/identifiability.csv");
      header(id, "index,singular_value,relative");
      for (unsigned int k = 0; k < r.singular_value.size(); ++k)
        {
          id << k << ',' << r.singular_value[k] << ','
             << (r.singular_value[0] > 0. ?
                   r.singular_value[k] / r.singular_value[0] :
                   0.);
          for (unsigned int j = 0; j < parameters.size(); ++j)
            id << ',' << r.singular_vector(j, k);
          id << '\n';
        }

      io::OutputFile hi(work_dir + "/history.csv");
      header(hi, "trial,accepted,cost,damping");
      for (const auto &h : r.history)
        {
          hi << h.index << ',' << (h.accepted ? 1 : 0) << ',' << h.cost << ','
             << h.damping;
          for (const double v : h.value)
            hi << ',' << v;
          hi << '\n';
        }

      if (r.pairing.mac_matrix.size() > 0)
        {
          io::OutputFile mac(work_dir + "/mac.csv");
          mac << "target";
          for (unsigned int k = 0; k < r.modes.frequency.size(); ++k)
            mac << ",\"mode " << k << " ("
                << (configurations[r.modes.configuration[k]].name.empty() ?
                      std::string() :
                      configurations[r.modes.configuration[k]].name + ", ")
                << std::setprecision(6) << r.modes.frequency[k] << " Hz)\"";
          mac << '\n' << std::setprecision(6);
          for (unsigned int i = 0; i < targets.size(); ++i)
            {
              mac << quoted(targets[i].label);
              for (unsigned int k = 0; k < r.modes.frequency.size(); ++k)
                mac << ',' << r.pairing.mac_matrix(i, k);
              mac << '\n';
            }
        }

      io::OutputFile summary(work_dir + "/summary.txt");
      summary << "Model updating: " << r.stop_reason << " after "
              << r.iterations << " steps (" << n_solves
              << " eigensolves); cost 1/2 sum r^2 " << r.initial_cost << " -> "
              << r.cost << " (r in units of the measurement error " << sigma
              << ")\n";
      std::vector<std::string> unidentified;
      for (unsigned int j = 0; j < parameters.size(); ++j)
        if (!r.identifiable[j])
          unidentified.push_back(parameters[j].name);
      if (unidentified.empty())
        summary << "Every parameter is identifiable from these targets.\n";
      else
        {
          summary << "Not identifiable from these targets:";
          for (const auto &n : unidentified)
            summary << ' ' << n;
          summary << " (see identifiability.csv)\n";
        }
      if (!r.converged)
        summary << "WARNING: the iteration limit was reached before the fit "
                   "converged\n";
    }
  } // namespace analyses
} // namespace squeal
