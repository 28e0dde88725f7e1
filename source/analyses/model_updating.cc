// The model updating analysis (see model_updating.h): the frictionless
// assembly's modes and their exact sensitivities at each Levenberg-
// Marquardt step, on the full model or on the reduced one with full solves
// confirming it, and the run.

#include <deal.II/base/mpi.h>

#include <squeal/analyses/mode_naming.h>
#include <squeal/analyses/model_updating.h>
#include <squeal/contact/scene_contact.h>
#include <squeal/eigen/modal_contribution.h>
#include <squeal/eigen/qep_solver.h>
#include <squeal/eigen/reduced_model.h>
#include <squeal/eigen/sensitivity.h>
#include <squeal/io/output_directory.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;

    namespace
    {
      /**
       * d zeta / dp of zeta = c / (2 omega), c = phi^T C phi (phi
       * M-normalised), from c, omega^2 [1/s^2], phi^T C' phi [1/s], the
       * shape's part phi^T C d phi [1/s] and d omega^2 / dp.
       */
      double
      damping_ratio_slope(const double c,
                          const double w2,
                          const double dc,
                          const double shape,
                          const double dw2)
      {
        const double w = std::sqrt(w2);
        return (dc + 2 * shape) / (2 * w) - c / (2 * w) * dw2 / (2 * w2);
      }
    } // namespace
    ModelUpdatingAnalysis::ModelUpdatingAnalysis(
      const parameters::AllParameters &prm,
      const ParameterHandler          &handler,
      MPI_Comm                         comm)
      : prm(prm)
      , handler(handler)
      , comm(comm)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
      , timer(comm, pcout, TimerOutput::summary, TimerOutput::wall_times)
      , model(prm, comm)
    {
      parameters = parse_updating_parameters(prm.updating.parameters);
      std::set<std::string> varied, fitted;
      for (const auto &q : parameters)
        {
          varied.insert(q.scene_name);
          if (!fitted.insert(q.name).second)
            throw std::runtime_error("Model updating/Parameters: " + q.name +
                                     " is given twice");
        }
      configurations.push_back({});
      for (const auto &c : parse_configurations(prm.updating.configurations))
        {
          for (const auto &[name, value] : c.values)
            {
              if (std::any_of(parameters.begin(),
                              parameters.end(),
                              [&](const auto &q) {
                                return q.scene_name == name &&
                                       (q.configuration.empty() ||
                                        q.configuration == c.name);
                              }))
                throw std::runtime_error(
                  "Model updating/Configurations: configuration '" + c.name +
                  "' sets " + name +
                  ", which is fitted; a configuration may set only "
                  "parameters that are not");
              varied.insert(name);
            }
          configurations.push_back(c);
        }
      model.varied          = varied;
      model.tie_constraints = contact::add_tie_constraints;
    }

    parameters::ScalarPoint
    ModelUpdatingAnalysis::configuration_point(
      const unsigned int         c,
      const std::vector<double> &values,
      std::vector<std::string>  &names,
      std::vector<int>          &column) const
    {
      // the parameters that act in configuration c: a parameter of one
      // configuration replaces the common one there
      const auto acts = [&](const updating::Parameter &q) {
        if (!q.configuration.empty())
          return q.configuration == configurations[c].name;
        return std::none_of(parameters.begin(),
                            parameters.end(),
                            [&](const auto &o) {
                              return o.scene_name == q.scene_name &&
                                     !o.configuration.empty() &&
                                     o.configuration == configurations[c].name;
                            });
      };
      parameters::ScalarPoint p = model.parts().reference;
      for (const auto &[name, value] : configurations[c].values)
        p.set(name, value);
      names.clear();
      column.clear();
      for (unsigned int j = 0; j < parameters.size(); ++j)
        if (acts(parameters[j]))
          {
            p.set(parameters[j].scene_name, values[j]);
            column.push_back(names.size());
            names.push_back(parameters[j].scene_name);
          }
        else
          column.push_back(-1);
      return p;
    }

    void
    ModelUpdatingAnalysis::append_mode(updating::ModelModes          &result,
                                       const unsigned int             c,
                                       const parameters::ScalarPoint &p,
                                       const double                   f,
                                       std::vector<double>          &&d,
                                       const physics::PETScVector    &phi,
                                       const physics::PETScVector &zero) const
    {
      result.frequency.push_back(f);
      result.derivative.push_back(std::move(d));
      result.shape.push_back(observation ? (*observation)(phi) :
                                           std::vector<double>());
      result.configuration.push_back(c);
      // named in every evaluation: a few per cent of the solve's time, and
      // the names belong to exactly these modes
      result.name.push_back(mode_name(model, p, phi, zero, nullptr, true));
    }

    updating::ModelModes
    ModelUpdatingAnalysis::modes_at(const std::vector<double> &values)
    {
      TimerOutput::Scope t(timer, "eigensolve and sensitivities");
      const auto         parts = model.parts();
      const auto        &es    = prm.eigensolver;
      eigen::BandOptions band{0., f_max, es.target_frequency, es.tolerance, 40};
      band.symmetric_solver = es.symmetric_solver;
      band.store_products   = es.subspace_products == "stored";
      ConditionalOStream   quiet(std::cout, false);
      updating::ModelModes result;
      // the reduced model's basis takes the modes up to basis_factor f_max
      const double factor =
        prm.updating.method == "reduced" ? basis_factor : 1.;
      basis_candidates.clear();
      for (unsigned int c = 0; c < configurations.size(); ++c)
        if (used[c])
          {
            std::vector<std::string>      names;
            std::vector<int>              column; // parameter j -> slope, or -1
            const parameters::ScalarPoint p =
              configuration_point(c, values, names, column);
            auto modes =
              eigen::frictionless_modes(parts, p, band, factor, quiet);
            ++n_solves;
            basis_candidates.insert(basis_candidates.end(),
                                    modes.shape.begin(),
                                    modes.shape.end());

            // d omega^2 / dp_j = phi^T (K_j' - omega^2 M_j') phi from the
            // parts' quadratic forms q_k = phi^T A_k phi (0 for a parameter
            // that does not act in c)
            const auto slope = eigen::coefficient_slopes(parts, p, names);
            const auto coeff = parts.coefficients(p);
            std::vector<bool> needed(parts.size(), false);
            for (const auto &d : slope)
              for (unsigned int k = 0; k < parts.size(); ++k)
                needed[k] = needed[k] || d.mass[k] != 0. ||
                            d.symmetric_stiffness[k] != 0. ||
                            (with_damping &&
                             (d.damping[k] != 0. || coeff.damping[k] != 0.));
            if (modes.shape.empty())
              continue;
            const unsigned int   n_modes = modes.frequency.size();
            physics::PETScVector Aphi(modes.shape[0]), zero(modes.shape[0]);
            zero = 0.;
            // damping: G = Phi^T C Phi and, per mode and parameter, the
            // first-order change of the shape (below)
            Eigen::MatrixXd                   G;
            std::vector<physics::PETScVector> y; // K^-1 C phi_m
            if (with_damping)
              {
                physics::PETScMatrix C, K;
                parts.combine(coeff.damping, C);
                parts.combine(coeff.symmetric_stiffness, K);
                const eigen::DirectSolver static_solver(K, true);
                G.resize(n_modes, n_modes);
                for (unsigned int m = 0; m < n_modes; ++m)
                  {
                    C.vmult(Aphi, modes.shape[m]);
                    for (unsigned int l = 0; l <= m; ++l)
                      G(l, m) = G(m, l) = modes.shape[l] * Aphi;
                    y.emplace_back(Aphi);
                    if (modes.frequency[m] <= f_max) // a target's mode
                      static_solver.solve(Aphi, y.back());
                  }
              }
            for (unsigned int m = 0; m < n_modes; ++m)
              {
                const auto  &phi = modes.shape[m];
                const double f   = modes.frequency[m];
                const double w2  = std::pow(2 * M_PI * f, 2);
                if (f > f_max) // a basis mode only
                  continue;
                std::vector<double> q(parts.size(), 0.);
                // A_k phi for the parts a parameter's stiffness or mass acts
                // in (the shape derivative needs them whole)
                std::vector<std::optional<physics::PETScVector>> A_phi(
                  parts.size());
                for (unsigned int k = 0; k < parts.size(); ++k)
                  if (needed[k])
                    {
                      parts.matrix(k).vmult(Aphi, phi);
                      q[k] = phi * Aphi;
                      if (with_damping)
                        A_phi[k] = Aphi;
                    }
                std::vector<double> d, dzeta;
                for (const int j : column)
                  {
                    double dw2 = 0.;
                    if (j >= 0)
                      for (unsigned int k = 0; k < parts.size(); ++k)
                        if (needed[k])
                          dw2 += (slope[j].symmetric_stiffness[k] -
                                  w2 * slope[j].mass[k]) *
                                 q[k];
                    d.push_back(f > 0. ? dw2 / (8 * M_PI * M_PI * f) : 0.);
                    if (!with_damping)
                      continue;
                    // zeta_m = phi_m^T C phi_m / (2 omega_m): its derivative
                    // from C's own slope, from omega_m and from the shape,
                    // d phi_m = sum_l a_lm phi_l - (phi_m^T M' phi_m / 2)
                    // phi_m, a_lm = phi_l^T F / (omega_m^2 - omega_l^2), F =
                    // (K' - omega_m^2 M') phi_m (R.L. Fox, M.P. Kapoor, AIAA
                    // J. 6 (1968), eq. 13), over the computed modes (l of a
                    // repeated frequency left out: the shape within a
                    // doublet is arbitrary), and the modes above them in
                    // their static limit, -(K^-1 - sum_l phi_l phi_l^T /
                    // omega_l^2) F (B.P. Wang, AIAA J. 29 (1991) 1018-1020:
                    // a stiffness-proportional C makes the truncated sum
                    // converge slowly, and this correction carries the rest)
                    const double w  = std::sqrt(w2);
                    double       dc = 0., shape = 0.;
                    if (j >= 0 && w > 0.)
                      {
                        physics::PETScVector v(phi);
                        v          = 0.;
                        double m_q = 0.;
                        for (unsigned int k = 0; k < parts.size(); ++k)
                          if (needed[k])
                            {
                              dc += slope[j].damping[k] * q[k];
                              m_q += slope[j].mass[k] * q[k];
                              const double a = slope[j].symmetric_stiffness[k] -
                                               w2 * slope[j].mass[k];
                              if (a != 0.)
                                v.add(a, *A_phi[k]);
                            }
                        double computed = 0.;
                        for (unsigned int l = 0; l < n_modes; ++l)
                          {
                            const double wl2 =
                              std::pow(2 * M_PI * modes.frequency[l], 2);
                            const double lF = modes.shape[l] * v;
                            if (l != m && std::abs(w2 - wl2) > 1e-6 * w2)
                              shape += lF / (w2 - wl2) * G(m, l);
                            if (wl2 > 0.)
                              computed += G(m, l) * lF / wl2;
                          }
                        shape += computed - y[m] * v;
                        shape -= 0.5 * m_q * G(m, m);
                      }
                    dzeta.push_back(
                      w > 0. ?
                        damping_ratio_slope(G(m, m), w2, dc, shape, dw2) :
                        0.);
                  }
                if (with_damping)
                  {
                    result.damping_ratio.push_back(
                      w2 > 0. ? G(m, m) / (2 * std::sqrt(w2)) : 0.);
                    result.damping_derivative.push_back(std::move(dzeta));
                  }
                append_mode(result, c, p, f, std::move(d), phi, zero);
              }
          }
      return result;
    }

    updating::ModelModes
    ModelUpdatingAnalysis::reduced_modes_at(const std::vector<double> &values)
    {
      TimerOutput::Scope t(timer, "reduced model");
      const auto         parts = model.parts();
      const unsigned int r     = reduced->size();
      const auto combine = [&](const physics::MatrixParts::Coefficients &a) {
        Eigen::MatrixXd A = Eigen::MatrixXd::Zero(r, r);
        for (unsigned int k = 0; k < parts.size(); ++k)
          if (a[k] != 0.)
            A += a[k] * reduced->projected_part(k);
        return A;
      };
      updating::ModelModes result;
      physics::PETScVector phi, im, zero;
      for (unsigned int c = 0; c < configurations.size(); ++c)
        if (used[c])
          {
            std::vector<std::string>      names;
            std::vector<int>              column;
            const parameters::ScalarPoint p =
              configuration_point(c, values, names, column);
            const auto coeff = parts.coefficients(p);
            const auto slope = eigen::coefficient_slopes(parts, p, names);
            // the symmetric problem on the span: V^T (K_s + K_n) V q =
            // omega^2 V^T M V q, q normalised by V^T M V
            Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(
              combine(coeff.symmetric_stiffness), combine(coeff.mass));
            if (es.info() != Eigen::Success)
              throw std::runtime_error("model updating: the reduced "
                                       "eigenproblem could not be solved");
            const Eigen::MatrixXd       &Q  = es.eigenvectors();
            const Eigen::VectorXd       &W2 = es.eigenvalues();
            std::vector<Eigen::MatrixXd> dK, dM, dC;
            for (const auto &d : slope)
              {
                dK.push_back(combine(d.symmetric_stiffness));
                dM.push_back(combine(d.mass));
                if (with_damping)
                  dC.push_back(combine(d.damping));
              }
            Eigen::MatrixXd G; // Q^T C Q
            if (with_damping)
              G = Q.transpose() * combine(coeff.damping) * Q;
            for (unsigned int m = 0; m < r; ++m)
              {
                const double w2 = W2[m];
                const double f  = std::sqrt(std::max(w2, 0.)) / (2 * M_PI);
                if (!(f > 0.) || f > f_max)
                  continue;
                const Eigen::VectorXd q = Q.col(m);
                std::vector<double>   d, dzeta;
                for (const int j : column)
                  {
                    if (j < 0)
                      {
                        d.push_back(0.);
                        dzeta.push_back(0.);
                        continue;
                      }
                    // exact on the span: the reduced model's own derivatives
                    const Eigen::VectorXd F   = (dK[j] - w2 * dM[j]) * q;
                    const double          dw2 = q.dot(F);
                    d.push_back(dw2 / (8 * M_PI * M_PI * f));
                    if (!with_damping)
                      continue;
                    // as modes_at(), the expansion now complete (all r
                    // modes of the span)
                    const Eigen::VectorXd a = Q.transpose() * F;
                    double shape            = -0.5 * q.dot(dM[j] * q) * G(m, m);
                    for (unsigned int l = 0; l < r; ++l)
                      if (l != m && std::abs(w2 - W2[l]) > 1e-6 * w2)
                        shape += a[l] / (w2 - W2[l]) * G(m, l);
                    dzeta.push_back(damping_ratio_slope(
                      G(m, m), w2, q.dot(dC[j] * q), shape, dw2));
                  }
                if (with_damping)
                  {
                    result.damping_ratio.push_back(G(m, m) /
                                                   (2 * std::sqrt(w2)));
                    result.damping_derivative.push_back(std::move(dzeta));
                  }
                reduced->expand(q.cast<std::complex<double>>(), phi, im);
                if (zero.size() != phi.size())
                  {
                    zero.reinit(phi);
                    zero = 0.;
                  }
                append_mode(result, c, p, f, std::move(d), phi, zero);
              }
          }
      ++n_reduced;
      return result;
    }

    updating::Result
    ModelUpdatingAnalysis::fit_reduced(const std::vector<double> &start,
                                       const updating::Options   &options)
    {
      std::ostream *log  = pcout.is_active() ? &pcout.get_stream() : nullptr;
      const auto    full = [this](const std::vector<double> &v) {
        return modes_at(v);
      };
      const auto on_span = [this](const std::vector<double> &v) {
        return reduced_modes_at(v);
      };
      // a full solve only evaluates: no step
      updating::Options evaluate = options;
      evaluate.max_iterations    = 0;
      // the start, solved in full: its modes are the first basis
      const updating::Result first =
        updating::update(full, parameters, start, targets, evaluate);

      std::vector<physics::PETScVector> previous; // the point before's
      updating::Result                  result;
      std::vector<updating::Iteration>  history;
      std::vector<double>               at         = first.value;
      unsigned int                      iterations = 0, trials = 0;
      const unsigned int                max_rounds = 20;
      for (unsigned int round = 1;; ++round)
        {
          // the span of the full modes at this point and the one before
          std::vector<physics::PETScVector> vectors = basis_candidates;
          vectors.insert(vectors.end(), previous.begin(), previous.end());
          reduced = std::make_unique<eigen::ReducedModel>();
          reduced->build_from_vectors(model.parts(), vectors, false);
          previous = basis_candidates;
          // a trust region about the point: the span represents the model
          // near the points it was taken at, so a round moves each
          // parameter by a factor of trust_factor at most (by a quarter of
          // its range where linear)
          std::vector<updating::Parameter> region = parameters;
          for (unsigned int j = 0; j < region.size(); ++j)
            {
              auto        &q    = region[j];
              const double half = (q.upper - q.lower) / 4;
              q.lower =
                std::max(q.lower,
                         q.log_scale ? at[j] / trust_factor : at[j] - half);
              q.upper =
                std::min(q.upper,
                         q.log_scale ? at[j] * trust_factor : at[j] + half);
            }
          if (log != nullptr)
            *log << "Model updating: round " << round << " on the span of "
                 << reduced->size() << " full-model modes" << std::endl;
          const updating::Result fit =
            updating::update(on_span, region, at, targets, options, log);
          // a parameter held by the region's bound, not by its own
          bool held = false;
          for (unsigned int j = 0; j < region.size(); ++j)
            if (fit.at_bound[j])
              {
                const bool low = std::abs(fit.value[j] - region[j].lower) <
                                 std::abs(fit.value[j] - region[j].upper);
                held = held || (low ? region[j].lower > parameters[j].lower :
                                      region[j].upper < parameters[j].upper);
              }
          // the full solve at the reduced fit's point
          result =
            updating::update(full, parameters, fit.value, targets, evaluate);
          double gap = 0.;
          for (unsigned int i = 0; i < targets.size(); ++i)
            {
              const double f_full =
                result.modes.frequency[result.pairing.mode[i]];
              gap = std::max(gap,
                             std::abs(fit.modes.frequency[fit.pairing.mode[i]] -
                                      f_full) /
                               f_full);
            }
          for (const auto &step : fit.history)
            if (step.index > 0 || round == 1)
              {
                history.push_back(step);
                history.back().index = step.index == 0 ? 0 : ++trials;
              }
          iterations += fit.iterations;
          if (log != nullptr)
            *log << "Model updating: round " << round << " confirmed by a "
                 << "full solve: cost " << fit.cost << " on the span, "
                 << result.cost << " in full; largest frequency gap of a "
                 << "paired mode " << gap
                 << (held ? "; a parameter at the round's trust region" : "")
                 << std::endl;
          if (gap <= prm.updating.reduced_tolerance && !held)
            {
              result.converged   = fit.converged;
              result.stop_reason = fit.stop_reason + " (round " +
                                   std::to_string(round) +
                                   ", confirmed by a full solve)";
              break;
            }
          if (round == max_rounds)
            {
              std::ostringstream what;
              what << "Model updating/Method = reduced: after " << max_rounds
                   << " rounds the reduced fit is not confirmed (a paired "
                   << "mode differs from the full solve by " << gap
                   << ", Reduced tolerance " << prm.updating.reduced_tolerance
                   << (held ? "; a parameter is still at the round's trust "
                              "region" :
                              "")
                   << "); use Method = full or raise the tolerance";
              throw std::runtime_error(what.str());
            }
          at = fit.value;
        }
      result.initial         = first.initial;
      result.initial_modes   = first.initial_modes;
      result.initial_pairing = first.initial_pairing;
      result.initial_cost    = first.initial_cost;
      result.iterations      = iterations;
      result.history         = history;
      return result;
    }

    void
    ModelUpdatingAnalysis::run()
    {
      const auto &u = prm.updating;
      // the measured data checked before any output
      if (!u.measurement_points.empty())
        points = read_measurement_points(u.measurement_points);
      targets =
        read_targets(u.targets,
                     points.size(),
                     std::vector<Configuration>(configurations.begin() + 1,
                                                configurations.end()));
      used.assign(configurations.size(), false);
      for (const auto &t : targets)
        {
          used[t.configuration] = true;
          with_damping          = with_damping || t.damping_ratio > 0.;
        }

      {
        TimerOutput::Scope t(timer, "setup and assembly");
        work_dir = io::start_work_directory(prm.output.directory,
                                            prm.output.overwrite,
                                            handler,
                                            comm);
        model.setup_and_assemble(pcout);
        if (!points.empty())
          observation = std::make_unique<PointObservation>(model, points);
        double highest = 0.;
        for (const auto &t : targets)
          highest = std::max(highest, t.frequency);
        // damping ratios' shape derivatives take the modes above f_max in
        // their static limit: an error of order (f / f_max)^2 of that part
        f_max = u.maximum_frequency > 0. ? u.maximum_frequency :
                                           (with_damping ? 2.5 : 1.5) * highest;
        if (!(f_max > highest))
          throw std::runtime_error(
            "Model updating/Maximum frequency = " + std::to_string(f_max) +
            " Hz lies below the highest measured mode (" +
            std::to_string(highest) + " Hz); raise it or set 0");
      }
      pcout << "Model updating: " << model.n_dofs() << " DoFs, "
            << parameters.size() << " parameters, " << targets.size()
            << " measured modes"
            << (points.empty() ?
                  std::string() :
                  ", " + std::to_string(points.size()) + " measurement points")
            << ", model modes up to " << f_max << " Hz" << std::endl;

      updating::Options options;
      options.measurement_error = u.measurement_error;
      options.damping_error     = u.damping_error;
      options.max_iterations    = u.max_iterations;
      options.tolerance         = u.tolerance;
      options.mac_threshold     = u.mac_threshold;
      options.frequency_window  = u.frequency_window;
      std::vector<double> start;
      const auto          reference = model.parts().reference;
      for (const auto &q : parameters)
        start.push_back(reference.get(q.scene_name));
      // the iteration's progress on rank 0's log as it goes
      updating::Result result =
        u.method == "reduced" && u.max_iterations > 0 ?
          fit_reduced(start, options) :
          updating::update(
            [this](const std::vector<double> &v) { return modes_at(v); },
            parameters,
            start,
            targets,
            options,
            pcout.is_active() ? &pcout.get_stream() : nullptr);
      if (!result.converged && u.max_iterations > 0)
        throw std::runtime_error(
          "model updating did not converge within Model updating/Maximum "
          "iterations = " +
          std::to_string(u.max_iterations) + " steps (cost " +
          std::to_string(result.cost) +
          "); raise it, or narrow the parameters' bounds");
      {
        TimerOutput::Scope t(timer, "output");
        write_results(result);
      }
      io::finish_run(work_dir, prm.output.directory, comm);
      pcout << "Results written to " << prm.output.directory << "/ ("
            << n_solves << " eigensolves"
            << (n_reduced > 0 ? ", " + std::to_string(n_reduced) +
                                  " evaluations of the reduced model" :
                                std::string())
            << ")" << std::endl;
    }
  } // namespace analyses
} // namespace squeal
