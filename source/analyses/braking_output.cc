// The braking run's outputs: the ParaView snapshots (structure with its von
// Mises stress, the slave faces with their contact fields), and at the end
// forces.csv, probes.csv, the spectrum, the stability verdict, the contact
// history and braking_summary.txt.

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <squeal/analyses/braking.h>
#include <squeal/contact/scene_contact.h>
#include <squeal/io/face_output.h>
#include <squeal/io/output_directory.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;
    using transient::ContactStep;
    using transient::DistributedVector;
    using transient::dominant_frequency;
    using transient::ExplicitDynamics;
    using transient::fit_growth;
    using transient::fit_modal_growth;
    using transient::GrowthFit;
    using transient::Spectrum;
    using transient::welch_psd;
    namespace fs = std::filesystem;

    namespace
    {
      // Von Mises stress [Pa] of linear elasticity, material per cell (an
      // anisotropic body's law at the point, at the nominal parameters).
      class VonMises : public DataPostprocessorScalar<3>
      {
      public:
        VonMises(const scene::Scene &scene, const parameters::ScalarPoint &p)
          : DataPostprocessorScalar<3>("von_mises_Pa",
                                       update_gradients |
                                         update_quadrature_points)
          , scene(scene)
          , nominal(p)
        {}
        void
        evaluate_vector_field(const DataPostprocessorInputs::Vector<3> &in,
                              std::vector<Vector<double>> &out) const override
        {
          const types::material_id id =
            in.template get_cell<3>()->material_id();
          const scene::Body &body = scene.body(id);
          const auto [lambda, mu] =
            physics::lame_constants(body.material.youngs_modulus,
                                    body.material.poisson_ratio);
          for (unsigned int q = 0; q < out.size(); ++q)
            {
              Tensor<2, 3> grad;
              for (unsigned int c = 0; c < 3; ++c)
                grad[c] = in.solution_gradients[q][c];
              const Tensor<2, 3> eps = 0.5 * (grad + transpose(grad));
              Tensor<2, 3>       s;
              if (body.law.anisotropic)
                s = Tensor<2, 3>(
                  scene.stiffness_tensor(id, in.evaluation_points[q], nominal) *
                  symmetrize(eps));
              else
                {
                  s = 2 * mu * eps;
                  for (unsigned int c = 0; c < 3; ++c)
                    s[c][c] += lambda * trace(eps);
                }
              const Tensor<2, 3> dev =
                s - trace(s) / 3. * unit_symmetric_tensor<3>();
              out[q][0] = std::sqrt(1.5 * scalar_product(dev, dev));
            }
        }

      private:
        const scene::Scene           &scene;
        const parameters::ScalarPoint nominal;
      };
    } // namespace


    void
    BrakingAnalysis::write_snapshot(const std::string &series,
                                    const unsigned int index)
    {
      const ExplicitDynamics &d = *dynamics;
      const std::string       name =
        series + "_" + Utilities::int_to_string(index, 4) + ".vtu";
      const std::vector<
        DataComponentInterpretation::DataComponentInterpretation>
        vec(3, DataComponentInterpretation::component_is_part_of_vector);
      {
        // each rank writes its own cells into one file (MPI I/O)
        DistributedVector u(model.locally_owned_dofs,
                            model.locally_relevant_dofs,
                            comm),
          v(u);
        u.copy_locally_owned_data_from(d.displacement());
        v.copy_locally_owned_data_from(d.velocity());
        u.update_ghost_values();
        v.update_ghost_values();
        DataOut<3> out;
        out.set_flags(io::vtk_flags());
        out.attach_dof_handler(model.dof_handler);
        out.add_data_vector(u,
                            std::vector<std::string>(3, "displacement_m"),
                            DataOut<3>::type_dof_data,
                            vec);
        out.add_data_vector(v,
                            std::vector<std::string>(3, "velocity_m_per_s"),
                            DataOut<3>::type_dof_data,
                            vec);
        const VonMises von_mises(*model.scene, model.scene->nominal_point());
        out.add_data_vector(u, von_mises);
        out.build_patches(model.mapping, 1);
        io::write_vtu(out, (fs::path(work_dir) / "vtu" / name).string(), comm);
      }
      (series == "transient" ? snapshots : frames)
        .emplace_back(d.time(), "vtu/" + name);
      if (series != "transient")
        return;
      // The pad face's contact fields.
      const ContactStep &c = d.contact_state();
      Vector<double>     tractions(model.n_dofs()), state(model.n_dofs());
      for (unsigned int j = 0; j < mortar.n_slave(); ++j)
        {
          const auto &dofs   = mortar.slave_dofs[j];
          tractions[dofs[0]] = std::max(0., c.pressure[j]);
          tractions[dofs[1]] = c.traction[j] * sliding;
          tractions[dofs[2]] = c.traction[j] * radial;
          state[dofs[0]]     = c.status[j];
          state[dofs[1]]     = c.slip_velocity[j];
        }
      io::BoundaryFaceOutput face(contact::slave_ids(*model.scene));
      face.attach_dof_handler(model.dof_handler);
      face.add_data_vector(tractions,
                           std::vector<std::string>{"contact_pressure_Pa",
                                                    "traction_sliding_Pa",
                                                    "traction_radial_Pa"});
      face.add_data_vector(state,
                           std::vector<std::string>{"status",
                                                    "slip_velocity_m_per_s",
                                                    "unused"});
      const std::string face_name = "contact_" + name;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          // the whole pad face from the replicated contact state
          face.build_patches(model.mapping, 1);
          io::OutputFile f(fs::path(work_dir) / "vtu" / face_name);
          face.write_vtu(f);
        }
      faces.emplace_back(d.time(), "vtu/" + face_name);
    }

    void
    BrakingAnalysis::output_results()
    {
      TimerOutput::Scope t(timer, "output");
      const auto        &tr = prm.transient;
      // Analysis window: Spectrum start (default: the second half).
      const double t_spec =
        tr.spectrum_start >= 0. ? tr.spectrum_start : tr.end_time / 2.;
      const auto [spectrum, velocity_spectrum] = evaluate_run(t_spec);
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      write_tables(spectrum, velocity_spectrum, t_spec);
      print_verdict(spectrum);
    }

    // The run's verdict from its samples: the probe's acceleration and
    // velocity spectra from T_SPEC on, the dominant frequency, the growth
    // fits after the ramp, separation and the leading-edge pressure range.
    // The acceleration along the sliding direction for the spectrum (as the
    // thesis showed it); the velocity for the dominant frequency and the
    // envelope: the acceleration weights the limit cycle's harmonics by k^2
    // and can make the third one look dominant.
    std::pair<Spectrum, Spectrum>
    BrakingAnalysis::evaluate_run(const double t_spec)
    {
      const double        rate = history.sampling_rate;
      std::vector<double> acc, vel, vel_after_ramp;
      double              t_after_ramp = -1.;
      for (const auto &row : samples)
        {
          const double a_t =
            row[14] * sliding[0] + row[15] * sliding[1] + row[16] * sliding[2];
          const double v_t =
            row[11] * sliding[0] + row[12] * sliding[1] + row[13] * sliding[2];
          if (row[0] >= t_spec)
            {
              acc.push_back(a_t);
              vel.push_back(v_t);
            }
          if (row[0] >= ramp_end)
            {
              if (t_after_ramp < 0.)
                t_after_ramp = row[0];
              vel_after_ramp.push_back(v_t);
            }
        }
      Spectrum spectrum, velocity_spectrum;
      if (acc.size() >= 16)
        {
          spectrum                  = welch_psd(acc, rate);
          velocity_spectrum         = welch_psd(vel, rate);
          result.dominant_frequency = dominant_frequency(vel, rate, 100.);
        }
      if (result.dominant_frequency > 0. && vel_after_ramp.size() > 0)
        {
          try
            {
              result.growth = fit_growth(vel_after_ramp,
                                         rate,
                                         t_after_ramp,
                                         1. / result.dominant_frequency);
            }
          catch (const std::exception &)
            {
              // too short after the ramp: no verdict on growth
            }
          try
            {
              result.modal_growth = fit_modal_growth(vel_after_ramp,
                                                     rate,
                                                     t_after_ramp,
                                                     result.dominant_frequency);
            }
          catch (const std::exception &)
            {
              // too short after the ramp: no verdict on growth
            }
        }
      // Separation after the ramp and the leading-edge pressure range.
      const double p_mean = total_load / mortar.slave_area;
      double       p_lo = 1e300, p_hi = 0.;
      for (unsigned int i = 0; i < history.time.size(); ++i)
        {
          if (history.time[i] < ramp_end)
            continue;
          for (unsigned int j = 0; j < mortar.n_slave(); ++j)
            if (history.status[j][i] == 0)
              result.separated = true;
          if (history.time[i] >= t_spec)
            for (const unsigned int j : leading_nodes)
              {
                p_lo = std::min(p_lo, history.p_N[j][i]);
                p_hi = std::max(p_hi, history.p_N[j][i]);
              }
        }
      if (p_hi > 0.)
        {
          result.leading_min_over_mean = p_lo / p_mean;
          result.leading_max_over_mean = p_hi / p_mean;
        }
      // Unstable: the envelope grew tenfold and stayed up (saturated into a
      // limit cycle, overshoot or not, or still growing), or its
      // fitted exponential at least doubled it over the fit (a slow growth,
      // or one from a large seed); stable: it decays, or stays within a
      // factor of 2.
      const GrowthFit &g  = result.growth;
      const double factor = std::exp(g.growth_rate * (g.fit_end - g.fit_start));
      result.verdict =
        g.growing    ? (g.limit_cycle ? "unstable: limit cycle" :
                                        "unstable: still growing at End time") :
        factor >= 2. ? "unstable: growing slowly (x" +
                         std::to_string(int(std::round(factor))) +
                         " over the fit)" :
        g.growth_rate < 0. ? "stable: vibration decays" :
                             "stable: no growth";

      return {spectrum, velocity_spectrum};
    }

    // forces.csv, probes.csv, spectrum.csv, envelope.csv,
    // contact_history.h5, summary.csv and the .pvd records (rank 0).
    void
    BrakingAnalysis::write_tables(const Spectrum &spectrum,
                                  const Spectrum &velocity_spectrum,
                                  const double    t_spec) const
    {
      const fs::path   dir(work_dir);
      const GrowthFit &g = result.growth;
      {
        io::OutputFile out(dir / "forces.csv");
        out << "time_s,normal_force_N,tangential_force_N,radial_force_N,"
               "contact_area_m2,n_stick,n_slip,n_separated\n"
            << std::setprecision(std::numeric_limits<double>::max_digits10);
        for (const auto &r : samples)
          out << r[0] << ',' << r[1] << ',' << r[2] << ',' << r[3] << ','
              << r[4] << ',' << r[5] << ',' << r[6] << ',' << r[7] << '\n';
      }
      {
        io::OutputFile out(dir / "probes.csv");
        out << "# probe: pad leading edge at (" << probe_point[0] << ", "
            << probe_point[1] << ", " << probe_point[2]
            << ") m; sliding direction (" << sliding[0] << ", " << sliding[1]
            << ", " << sliding[2] << ")\n"
            << "time_s,u_x_m,u_y_m,u_z_m,v_x_m_per_s,v_y_m_per_s,v_z_m_per_s,"
               "a_x_m_per_s2,a_y_m_per_s2,a_z_m_per_s2\n"
            << std::setprecision(std::numeric_limits<double>::max_digits10);
        for (const auto &r : samples)
          {
            out << r[0];
            for (unsigned int k = 8; k < 17; ++k)
              out << ',' << r[k];
            out << '\n';
          }
      }
      {
        io::OutputFile out(dir / "spectrum.csv");
        out
          << "# Welch PSD of the probe's acceleration and velocity along "
             "the sliding direction, t >= "
          << t_spec
          << " s\nfrequency_Hz,psd_m2_per_s4_per_Hz,psd_velocity_m2_per_s2_per_Hz\n"
          << std::setprecision(10);
        for (unsigned int k = 0; k < spectrum.psd.size(); ++k)
          out << spectrum.frequency[k] << ',' << spectrum.psd[k] << ','
              << velocity_spectrum.psd[k] << '\n';
      }
      {
        io::OutputFile out(dir / "envelope.csv");
        out << "time_s,envelope_m_per_s\n" << std::setprecision(10);
        for (unsigned int k = 0; k < g.time.size(); ++k)
          out << g.time[k] << ',' << g.envelope[k] << '\n';
      }
      io::write_contact_history((dir / "contact_history.h5").string(), history);
      {
        io::OutputFile out(dir / "summary.csv");
        out << "quantity,value\n"
            << std::setprecision(10) << "verdict," << result.verdict;
        // the scene's named parameters at this run
        for (const auto &p : model.scene->parameters())
          out << '\n' << p.column() << ',' << p.value;
        out << "\ndominant_frequency_Hz," << result.dominant_frequency
            << "\ngrowth_rate_per_s," << g.growth_rate
            << "\ngrowth_fit_start_s," << g.fit_start << "\ngrowth_fit_end_s,"
            << g.fit_end << "\ngrowth_rate_at_dominant_frequency_per_s,"
            << result.modal_growth.growth_rate << "\nmodal_fit_start_s,"
            << result.modal_growth.fit_start << "\nmodal_fit_end_s,"
            << result.modal_growth.fit_end << "\nlimit_cycle_amplitude_m_per_s,"
            << g.final_amplitude << "\nlimit_cycle," << (g.limit_cycle ? 1 : 0)
            << "\nsaturation_time_s," << g.saturation_time << "\nseparated,"
            << (result.separated ? 1 : 0) << "\nleading_edge_p_min_over_mean,"
            << result.leading_min_over_mean << "\nleading_edge_p_max_over_mean,"
            << result.leading_max_over_mean << "\nn_dofs," << result.n_dofs
            << "\ntime_step_s," << result.time_step << "\ncritical_time_step_s,"
            << result.critical_time_step << "\nn_steps," << result.n_steps
            << "\nwall_time_s," << result.wall_time << "\nsteps_per_s,"
            << result.n_steps / result.wall_time << "\n";
      }
      for (const auto &[file, list] :
           {std::make_pair("transient.pvd", &snapshots),
            std::make_pair("animation.pvd", &frames),
            std::make_pair("contact.pvd", &faces)})
        {
          io::OutputFile pvd(dir / file);
          DataOutBase::write_pvd_record(pvd, *list);
        }
    }

    void
    BrakingAnalysis::print_verdict(const Spectrum &spectrum) const
    {
      const auto      &tr = prm.transient;
      const GrowthFit &g  = result.growth;
      pcout << "Verdict: " << result.verdict << "\n  dominant frequency "
            << result.dominant_frequency << " Hz";
      for (unsigned int h = 2; h <= 3 && !spectrum.psd.empty(); ++h)
        {
          const double f_h = h * result.dominant_frequency;
          unsigned int k   = 0;
          while (k + 1 < spectrum.frequency.size() &&
                 spectrum.frequency[k] < f_h)
            ++k;
          if (k + 1 < spectrum.frequency.size())
            pcout << "; harmonic " << h << " (" << f_h << " Hz) PSD "
                  << spectrum.psd[k];
        }
      pcout << "\n  growth rate " << g.growth_rate << " 1/s (fitted "
            << g.fit_start * 1e3 << "-" << g.fit_end * 1e3
            << " ms; at the dominant frequency alone "
            << result.modal_growth.growth_rate << " 1/s, "
            << result.modal_growth.fit_start * 1e3 << "-"
            << result.modal_growth.fit_end * 1e3 << " ms), final amplitude "
            << g.final_amplitude
            << " m/s (probe velocity along the sliding direction)";
      if (g.limit_cycle)
        pcout << "\n  grew from " << g.fit_start * 1e3
              << " ms and saturated at " << g.saturation_time * 1e3
              << " ms into a limit cycle of " << g.final_amplitude << " m/s";
      pcout << "\n  pad separated after the ramp: "
            << (result.separated ? "yes" : "no") << "; leading-edge pressure "
            << result.leading_min_over_mean << " to "
            << result.leading_max_over_mean << " x the mean\n  "
            << result.n_steps << " steps in " << result.wall_time << " s ("
            << result.n_steps / result.wall_time << " steps/s, "
            << result.wall_time / (tr.end_time * 1e3) << " s per simulated ms)";
      if (result.max_contact_sweeps > 0)
        pcout << "; contact: " << result.mean_contact_sweeps
              << " projected Gauss-Seidel sweeps per step on average, at "
                 "most "
              << result.max_contact_sweeps;
      pcout << std::endl;
    }
  } // namespace analyses
} // namespace squeal
