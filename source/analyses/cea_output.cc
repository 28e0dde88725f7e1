// The CEA's outputs: eigenvalues.csv, unstable_regions.csv,
// check_full.csv, mode_participation.csv (kinetic-energy shares per body
// and the mode names of mode_naming.h), sensitivities.csv,
// modal_contributions.csv, the mode shapes
// (modes.pvd) and the error indicator, written into the work folder and
// published at the end.

#include <deal.II/base/utilities.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/numerics/data_out.h>

#include <squeal/analyses/cea.h>
#include <squeal/analyses/mode_naming.h>
#include <squeal/io/output_directory.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;


    std::vector<std::string>
    ComplexEigenvalueAnalysis::write_modes(
      const std::vector<eigen::EigenPair> &x,
      const std::vector<std::string>      &names) const
    {
      if (x.size() != names.size())
        throw std::logic_error("write_modes: " + std::to_string(x.size()) +
                               " modes, " + std::to_string(names.size()) +
                               " names");
      const std::size_t m = x.size();
      // every mode's real and imaginary parts (hanging-node values filled
      // in, ghosted) in one DataOut: its patches map each cell once
      std::vector<physics::PETScVector> ghosted;
      ghosted.reserve(2 * m);
      DataOut<3> data_out;
      data_out.set_flags(io::vtk_flags());
      data_out.attach_dof_handler(model->dof_handler);
      const std::vector<
        DataComponentInterpretation::DataComponentInterpretation>
        vector(3, DataComponentInterpretation::component_is_part_of_vector);
      for (const eigen::EigenPair &pair : x)
        for (const physics::PETScVector *v : {&pair.re, &pair.im})
          {
            physics::PETScVector owned = *v;
            model->constraints.distribute(owned);
            ghosted.emplace_back(model->locally_owned_dofs,
                                 model->locally_relevant_dofs,
                                 comm);
            ghosted.back() = owned;
            data_out.add_data_vector(
              ghosted.back(),
              std::vector<std::string>(3, v == &pair.re ? "re" : "im"),
              DataOut<3>::type_dof_data,
              vector);
          }
      Vector<float> material(model->triangulation.n_active_cells());
      for (const auto &cell : model->triangulation.active_cell_iterators())
        material[cell->active_cell_index()] = cell->material_id();
      data_out.add_data_vector(material, "body");
      data_out.build_patches(model->mapping,
                             model->fe.degree,
                             DataOut<3>::curved_inner_cells);

      // Each mode's file from those patches: a patch's data rows are the
      // modes' six components in order (re x, y, z, im x, y, z), then the
      // body, then the mapped points' coordinates when the patch has them.
      const std::vector<std::string> data_names{"mode_real",
                                                "mode_real",
                                                "mode_real",
                                                "mode_imag",
                                                "mode_imag",
                                                "mode_imag",
                                                "body"};
      const std::vector<
        std::tuple<unsigned int,
                   unsigned int,
                   std::string,
                   DataComponentInterpretation::DataComponentInterpretation>>
                                                   ranges{{0,
                                                           2,
                                                           "mode_real",
                                                           DataComponentInterpretation::component_is_part_of_vector},
               {3,
                                                           5,
                                                           "mode_imag",
                                                           DataComponentInterpretation::component_is_part_of_vector}};
      const std::vector<DataOutBase::Patch<3, 3>> &all = data_out.get_patches();
      std::vector<DataOutBase::Patch<3, 3>>        patches(all.size());
      for (std::size_t k = 0; k < all.size(); ++k)
        {
          const auto &from = all[k];
          auto       &to   = patches[k];
          std::copy(std::begin(from.vertices),
                    std::end(from.vertices),
                    std::begin(to.vertices));
          to.neighbors            = from.neighbors;
          to.patch_index          = from.patch_index;
          to.n_subdivisions       = from.n_subdivisions;
          to.points_are_available = from.points_are_available;
          to.reference_cell       = from.reference_cell;
          to.data.reinit(7 + (from.points_are_available ? 3 : 0),
                         from.data.n_cols());
        }
      const unsigned int       rank = Utilities::MPI::this_mpi_process(comm);
      std::vector<std::string> written;
      for (std::size_t j = 0; j < m; ++j)
        {
          for (std::size_t k = 0; k < all.size(); ++k)
            {
              const auto        &from  = all[k];
              auto              &to    = patches[k];
              const unsigned int extra = from.points_are_available ? 3 : 0;
              for (unsigned int c = 0; c < from.data.n_cols(); ++c)
                {
                  for (unsigned int r = 0; r < 6; ++r)
                    to.data(r, c) = from.data(6 * j + r, c);
                  for (unsigned int r = 0; r < 1 + extra; ++r)
                    to.data(6 + r, c) = from.data(6 * m + r, c);
                }
            }
          // one piece per rank and the record on rank 0 (deal.II's
          // names), through checked files
          const std::string stem  = names[j] + "_0";
          const auto        piece = [&](const unsigned int r) {
            return stem + "." + std::to_string(r) + ".vtu";
          };
          {
            io::OutputFile vtu(work_dir + "/modes/" + piece(rank));
            DataOutBase::write_vtu(
              patches, data_names, ranges, io::vtk_flags(), vtu);
          }
          if (rank == 0)
            {
              std::vector<std::string> pieces;
              for (unsigned int r = 0;
                   r < Utilities::MPI::n_mpi_processes(comm);
                   ++r)
                pieces.push_back(piece(r));
              io::OutputFile pvtu(work_dir + "/modes/" + stem + ".pvtu");
              DataOutBase::write_pvtu_record(
                pvtu, pieces, data_names, ranges, io::vtk_flags());
            }
          written.push_back(stem + ".pvtu");
        }
      return written;
    }


    void
    ComplexEigenvalueAnalysis::output_results() const
    {
      TimerOutput::Scope t(timer, "output");
      const bool         root = Utilities::MPI::this_mpi_process(comm) == 0;
      if (root)
        {
          io::OutputFile csv(work_dir + "/eigenvalues.csv");
          // the two swept parameters, named by the scene, then the modes
          const auto &scene  = *model->scene;
          const auto  first  = scene.parameter(prm.sweep.first.parameter);
          const auto  second = scene.parameter(prm.sweep.second.parameter);
          csv << "point," << first.column() << ',' << second.column()
              << ",mode,re_per_s,freq_Hz,zeta,unstable,track\n"
              << std::setprecision(12);
          io::OutputFile res(work_dir + "/eigenvalue_residuals.csv");
          res << "point,mode,relative_residual,refined\n"
              << std::setprecision(6);
          for (const auto &m : modes)
            {
              csv << m.point << ',' << m.values.get(first.name) << ','
                  << m.values.get(second.name) << ',' << m.mode << ','
                  << m.lambda.real() << ',' << m.lambda.imag() / (2 * M_PI)
                  << ',' << -m.lambda.real() / std::abs(m.lambda) << ','
                  << (m.unstable ? 1 : 0) << ',' << m.track << '\n';
              res << m.point << ',' << m.mode << ',' << m.residual << ','
                  << (m.refined ? 1 : 0) << '\n';
            }
          io::OutputFile axes(work_dir + "/sweep_axes.csv");
          axes << "axis,parameter,column,log\n";
          for (const auto *axis : {&prm.sweep.first, &prm.sweep.second})
            axes << (axis == &prm.sweep.first ? "first," : "second,")
                 << axis->parameter << ','
                 << scene.parameter(axis->parameter).column() << ','
                 << (axis->log_scale() ? 1 : 0) << '\n';
          io::OutputFile reg(work_dir + "/unstable_regions.csv");
          // e.g. pad_on_disc.mu,pad.E_min_Pa,pad.E_max_Pa,...
          reg << second.column() << ',' << first.column("_min") << ','
              << first.column("_max")
              << ",freq_min_Hz,freq_max_Hz,max_re_per_s,track\n"
              << std::setprecision(12);
          for (const auto &r : regions)
            reg << r.second << ',' << r.first_min << ',' << r.first_max << ','
                << r.f_min << ',' << r.f_max << ',' << r.max_re << ','
                << r.track << '\n';
          if (!unverified.empty())
            {
              io::OutputFile note(work_dir + "/UNVERIFIED.txt");
              note << "These results failed verification "
                      "(Eigensolver/Allow unverified results = true):\n";
              for (const auto &u : unverified)
                note << u << '\n';
            }
          if (std::any_of(points.begin(), points.end(), [](const Point &p) {
                return p.report.symmetric_in_basis > 0;
              }))
            {
              // the full solver's counts and convergence at every point
              io::OutputFile fs(work_dir + "/full_solver.csv");
              fs
                << "point,modes,symmetric_in_band,symmetric_in_basis,"
                   "basis_size,rounds,largest_residual,seconds,peak_memory_MB\n"
                << std::setprecision(6);
              for (unsigned int p = 0; p < points.size(); ++p)
                {
                  const auto &r = points[p].report;
                  fs << p << ',' << points[p].full.size() << ','
                     << r.symmetric_in_band << ',' << r.symmetric_in_basis
                     << ',' << r.basis_size << ',' << r.rounds << ','
                     << r.largest_residual << ',' << r.seconds << ','
                     << r.peak_memory_mb << '\n';
                }
            }
          if (!check_rows.empty())
            {
              io::OutputFile chk(work_dir + "/check_full.csv");
              chk << "point," << first.column() << ',' << second.column()
                  << ",full_re_per_s,full_freq_Hz,"
                     "reduced_re_per_s,reduced_freq_Hz,freq_rel_error,"
                     "re_error_per_abs_re_plus_1,lambda_rel_error\n";
              for (const auto &r : check_rows)
                chk << r << '\n';
            }
        }

      // Mode shapes: all modes of the first point, and each unstable region
      // at its largest growth rate (or, with Output/Mode shapes = all, every
      // mode of every point).
      std::vector<std::pair<unsigned int, unsigned int>> chosen;
      const std::string what = prm.output.mode_output;
      if (what != "none")
        for (const auto &m : modes)
          {
            const bool unstable_peak =
              std::any_of(regions.begin(), regions.end(), [&](const auto &r) {
                return r.track == m.track && r.point_of_max == m.point;
              });
            if (what == "all" || m.point == 0 || unstable_peak)
              chosen.emplace_back(m.point, m.mode);
          }
      // Kinetic-energy fraction of each body in each written mode, to name
      // modes (disc, pad, support) and to calibrate the support.
      std::ostringstream participation;
      participation << "point,mode,freq_Hz,re_per_s";
      for (const scene::Body &b : model->scene->bodies)
        participation << ',' << b.name;
      participation << ",name\n" << std::setprecision(8);

      std::vector<std::pair<double, std::string>> records;
      chosen.erase(std::remove_if(chosen.begin(),
                                  chosen.end(),
                                  [&](const auto &c) {
                                    return points[c.first].q.empty() &&
                                           points[c.first].full.empty();
                                  }),
                   chosen.end());
      // 16 modes at a time: the reduced ones expanded in one product, the
      // kinetic energies in one pass over the cells, the files from one
      // set of patches
      constexpr std::size_t batch = 16;
      for (std::size_t first = 0; first < chosen.size(); first += batch)
        {
          const std::size_t end = std::min(chosen.size(), first + batch);
          std::vector<eigen::EigenPair>     x(end - first);
          std::vector<Eigen::VectorXcd>     q;
          std::vector<std::complex<double>> lambda;
          std::vector<std::size_t>          reduced_at;
          for (std::size_t j = first; j < end; ++j)
            {
              const auto &[p, k] = chosen[j];
              if (!points[p].q.empty())
                {
                  q.push_back(points[p].q[k]);
                  lambda.push_back(points[p].lambda[k]);
                  reduced_at.push_back(j - first);
                }
              else
                {
                  x[j - first].lambda = points[p].lambda[k];
                  x[j - first].re     = points[p].full[k].re;
                  x[j - first].im     = points[p].full[k].im;
                }
            }
          if (!q.empty())
            {
              std::vector<eigen::EigenPair> expanded;
              reduced.expand(q, lambda, expanded);
              for (std::size_t i = 0; i < reduced_at.size(); ++i)
                {
                  eigen::EigenPair &to = x[reduced_at[i]];
                  to.lambda            = expanded[i].lambda;
                  to.re.reinit(model->locally_owned_dofs, comm);
                  to.im.reinit(model->locally_owned_dofs, comm);
                  to.re = expanded[i].re;
                  to.im = expanded[i].im;
                }
            }
          std::vector<const parameters::ScalarPoint *> at;
          std::vector<const physics::PETScVector *>    re, im;
          for (std::size_t j = first; j < end; ++j)
            {
              at.push_back(&points[chosen[j].first].values);
              re.push_back(&x[j - first].re);
              im.push_back(&x[j - first].im);
            }
          const std::vector<std::vector<double>> energy =
            physics::kinetic_energy_by_body(*model, at, re, im);
          std::vector<std::string> names;
          for (std::size_t j = first; j < end; ++j)
            {
              const auto &[p, k]     = chosen[j];
              const auto         &pt = points[p];
              std::vector<double> shares;
              const std::string   mode_name =
                analyses::mode_name(*model,
                                    pt.values,
                                    *re[j - first],
                                    *im[j - first],
                                    &shares,
                                    false,
                                    &energy[j - first]);
              participation << p << ',' << k << ','
                            << pt.lambda[k].imag() / (2 * M_PI) << ','
                            << pt.lambda[k].real();
              for (const double share : shares)
                participation << ',' << share;
              participation << ",\"" << mode_name << "\"\n";
              std::ostringstream name;
              name << "mode_p" << p << "_m" << k << "_" << std::fixed
                   << std::setprecision(1) << pt.lambda[k].imag() / (2 * M_PI)
                   << "Hz_re" << std::setprecision(3) << pt.lambda[k].real();
              names.push_back(name.str());
            }
          // the record names the file written (deal.II appends the counter)
          for (const std::string &file : write_modes(x, names))
            records.emplace_back(records.size(), "modes/" + file);
        }
      if (prm.output.error_indicator)
        write_error_indicator();
      if (root)
        {
          io::OutputFile pvd(work_dir + "/modes.pvd");
          DataOutBase::write_pvd_record(pvd, records);
          io::OutputFile(work_dir + "/mode_participation.csv")
            << participation.str();
          if (prm.output.sensitivities != "none")
            write_sensitivities();
          if (prm.output.modal_contributions)
            {
              const auto    &scene = *model->scene;
              io::OutputFile mc(work_dir + "/modal_contributions.csv");
              mc << "point,"
                 << scene.parameter(prm.sweep.first.parameter).column() << ','
                 << scene.parameter(prm.sweep.second.parameter).column()
                 << ",mode,freq_Hz,re_per_s,captured,rank,frictionless_mode,"
                    "frictionless_freq_Hz,frictionless_name,share,"
                    "coefficient_re,coefficient_im\n";
              for (const auto &row : contribution_rows)
                mc << row << '\n';
            }
        }
      io::finish_run(work_dir, output_target(), comm);
      pcout << "Results written to " << output_target() << "/" << std::endl;
    }

    std::string
    ComplexEigenvalueAnalysis::describe_mode(
      const parameters::ScalarPoint &values,
      const physics::PETScVector    &re,
      const physics::PETScVector    &im,
      std::vector<double>           *shares) const
    {
      return mode_name(*model, values, re, im, shares);
    }

    void
    ComplexEigenvalueAnalysis::write_sensitivities() const
    {
      const auto    &scene  = *model->scene;
      const auto     first  = scene.parameter(prm.sweep.first.parameter);
      const auto     second = scene.parameter(prm.sweep.second.parameter);
      const auto    &es     = prm.eigensolver;
      io::OutputFile csv(work_dir + "/sensitivities.csv");
      // one row per mode and parameter; d* in 1/s or Hz per unit of the
      // parameter, relative_d_re_per_s = p d Re lambda / d p
      csv << "point," << first.column() << ',' << second.column()
          << ",mode,freq_Hz,re_per_s,unstable,condition,parameter,unit,value,"
             "d_re_per_s_per_unit,d_freq_Hz_per_unit,relative_d_re_per_s,"
             "value_at_re_zero\n"
          << std::setprecision(10);
      const auto parameters = scene.parameters();
      for (unsigned int p = 0; p < points.size(); ++p)
        for (unsigned int m = 0; m < points[p].sensitivity.size(); ++m)
          {
            const auto &s = points[p].sensitivity[m];
            const auto  l = s.lambda;
            if (prm.output.sensitivities == "unstable" && !near_unstable(l))
              continue;
            for (unsigned int j = 0; j < parameters.size(); ++j)
              {
                const auto  &q     = parameters[j];
                const double value = points[p].values.get(q.name);
                const double d_re  = s.derivative[j].real();
                csv << p << ',' << points[p].values.get(first.name) << ','
                    << points[p].values.get(second.name) << ',' << m << ','
                    << l.imag() / (2 * M_PI) << ',' << l.real() << ','
                    << (eigen::is_unstable(l,
                                           es.unstable_tolerance,
                                           es.unstable_relative_tolerance) ?
                          1 :
                          0)
                    << ',' << s.condition << ',' << q.name << ',' << q.unit
                    << ',' << value << ',' << d_re << ','
                    << s.derivative[j].imag() / (2 * M_PI) << ','
                    << value * d_re << ',';
                // first order: Re lambda + (v - value) d_re = 0, if the
                // value is one the parameter may take
                const double zero = value - l.real() / d_re;
                if (d_re != 0. && std::isfinite(zero) &&
                    (zero > q.lowest || (zero == q.lowest && !q.low_open)) &&
                    zero <= q.highest)
                  csv << zero;
                csv << '\n';
              }
          }
    }

    std::string
    ComplexEigenvalueAnalysis::output_target() const
    {
      return unverified.empty() ?
               prm.output.directory :
               io::normalised(prm.output.directory) + ".unverified";
    }

  } // namespace analyses
} // namespace squeal
