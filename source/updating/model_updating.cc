// Model updating (see model_updating.h): pairing of measured and model modes
// by the optimal assignment, a bounded Levenberg-Marquardt iteration on the
// relative frequency residuals, and the uncertainty and identifiability of
// the fit from the singular values of its Jacobian.

#include <squeal/eigen/mac.h>
#include <squeal/eigen/tracking.h>
#include <squeal/updating/model_updating.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace updating
  {
    namespace
    {
      /// the cost of a forbidden pairing in the assignment
      constexpr double forbidden = 1e6;

      /// relative gap below which model frequencies count as repeated
      constexpr double repeated = 1e-6;

      /**
       * The MAC of the measured shape @p t with model mode @p k, or with
       * the span of its group of repeated frequencies (the modes from
       * group_start[k] with the same group_start): |P t|^2 / |t|^2, P the
       * orthogonal projector on the span.
       */
      double
      subspace_mac(const std::vector<double>       &t,
                   const ModelModes                &modes,
                   const std::vector<unsigned int> &group_start,
                   const unsigned int               k)
      {
        std::vector<unsigned int> group;
        for (unsigned int l = group_start[k];
             l < modes.frequency.size() && group_start[l] == group_start[k];
             ++l)
          group.push_back(l);
        if (group.size() == 1)
          return eigen::complex_mac(
            std::vector<std::complex<double>>(t.begin(), t.end()),
            std::vector<std::complex<double>>(modes.shape[k].begin(),
                                              modes.shape[k].end()));
        const Eigen::Map<const Eigen::VectorXd> tv(t.data(), t.size());
        Eigen::MatrixXd                         S(t.size(), group.size());
        for (unsigned int g = 0; g < group.size(); ++g)
          S.col(g) =
            Eigen::Map<const Eigen::VectorXd>(modes.shape[group[g]].data(),
                                              t.size());
        const double tt = tv.squaredNorm();
        if (!(tt > 0.) || !(S.norm() > 0.))
          return 0.;
        // the projection by an orthonormal basis of the span (column-pivoted
        // QR drops dependent shapes)
        const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(S);
        const Eigen::MatrixXd                             Q =
          Eigen::MatrixXd(qr.householderQ()).leftCols(qr.rank());
        return (Q.transpose() * tv).squaredNorm() / tt;
      }

      /** Whether the model modes carry shapes of length @p n. */
      bool
      model_has_shapes(const ModelModes &modes, const std::size_t n)
      {
        if (modes.shape.size() != modes.frequency.size())
          return false;
        for (const auto &s : modes.shape)
          if (s.size() != n)
            return false;
        return true;
      }

      /** x of a parameter value (log scale or scaled by the bounds). */
      double
      to_x(const Parameter &q, const double p)
      {
        return q.log_scale ? std::log(p) : p / (q.upper - q.lower);
      }

      /** The parameter value of x. */
      double
      to_p(const Parameter &q, const double x)
      {
        return q.log_scale ? std::exp(x) : x * (q.upper - q.lower);
      }

      /** d p / d x. */
      double
      dp_dx(const Parameter &q, const double p)
      {
        return q.log_scale ? p : q.upper - q.lower;
      }

      /** The model at one point: modes, pairing, residuals, Jacobian. */
      struct Evaluation
      {
        std::vector<double> p;
        ModelModes          modes;
        Pairing             pairing;
        Eigen::VectorXd     r;
        Eigen::MatrixXd     J;
        double              cost = 0.;
      };

      Evaluation
      evaluate(const ModalModel             &model,
               const std::vector<Parameter> &parameters,
               const Eigen::VectorXd        &x,
               const std::vector<Target>    &targets,
               const Options                &options)
      {
        Evaluation e;
        for (unsigned int j = 0; j < parameters.size(); ++j)
          e.p.push_back(to_p(parameters[j], x[j]));
        e.modes = model(e.p);
        if (e.modes.frequency.empty())
          throw std::runtime_error("model updating: the model has no mode "
                                   "in its band");
        if (e.modes.derivative.size() != e.modes.frequency.size())
          throw std::logic_error("model updating: one derivative row per "
                                 "mode expected");
        for (const auto &row : e.modes.derivative)
          if (row.size() != parameters.size())
            throw std::logic_error("model updating: one derivative per "
                                   "parameter expected");
        e.pairing                   = pair_targets(targets, e.modes, options);
        const unsigned int        m = targets.size(), n = parameters.size();
        std::vector<unsigned int> damped; // targets with a damping ratio
        for (unsigned int i = 0; i < m; ++i)
          if (targets[i].damping_ratio > 0.)
            damped.push_back(i);
        if (!damped.empty() &&
            (e.modes.damping_ratio.size() != e.modes.frequency.size() ||
             e.modes.damping_derivative.size() != e.modes.frequency.size()))
          throw std::runtime_error(
            "model updating: target '" + targets[damped[0]].label +
            "' has a damping ratio, but the model gives none (a damping "
            "ratio is fitted with Rayleigh damping)");
        e.r.resize(m + damped.size());
        e.J.resize(m + damped.size(), n);
        for (unsigned int i = 0; i < m; ++i)
          {
            const Target &t = targets[i];
            const int     k = e.pairing.mode[i];
            const double  scale =
              std::sqrt(t.weight) / (options.measurement_error * t.frequency);
            e.r[i] = scale * (e.modes.frequency[k] - t.frequency);
            for (unsigned int j = 0; j < n; ++j)
              e.J(i, j) =
                scale * e.modes.derivative[k][j] * dp_dx(parameters[j], e.p[j]);
          }
        for (unsigned int d = 0; d < damped.size(); ++d)
          {
            const Target &t = targets[damped[d]];
            const int     k = e.pairing.mode[damped[d]];
            const double  scale =
              std::sqrt(t.weight) / (options.damping_error * t.damping_ratio);
            e.r[m + d] = scale * (e.modes.damping_ratio[k] - t.damping_ratio);
            if (e.modes.damping_derivative[k].size() != n)
              throw std::logic_error("model updating: one damping derivative "
                                     "per parameter expected");
            for (unsigned int j = 0; j < n; ++j)
              e.J(m + d, j) = scale * e.modes.damping_derivative[k][j] *
                              dp_dx(parameters[j], e.p[j]);
          }
        e.cost = 0.5 * e.r.squaredNorm();
        return e;
      }

      std::string
      values_text(const std::vector<double> &p)
      {
        std::ostringstream s;
        s << std::setprecision(6);
        for (unsigned int j = 0; j < p.size(); ++j)
          s << (j > 0 ? ", " : "") << p[j];
        return s.str();
      }
    } // namespace


    bool
    names_match(const std::string &wanted, const std::string &name)
    {
      // alternatives: `(0,3+)|support y`
      if (const auto bar = wanted.find('|'); bar != std::string::npos)
        return names_match(wanted.substr(0, bar), name) ||
               names_match(wanted.substr(bar + 1), name);
      if (wanted == name)
        return true;
      // `(n,m)` against `(n,m+)` / `(n,m-)`
      return !wanted.empty() && wanted.back() == ')' &&
             wanted.find_first_of("+-") == std::string::npos &&
             name.size() == wanted.size() + 1 &&
             name.compare(0, wanted.size() - 1, wanted, 0, wanted.size() - 1) ==
               0 &&
             (name[wanted.size() - 1] == '+' ||
              name[wanted.size() - 1] == '-') &&
             name.back() == ')';
    }

    Pairing
    pair_targets(const std::vector<Target> &targets,
                 const ModelModes          &modes,
                 const Options             &options)
    {
      const unsigned int m = targets.size(), n = modes.frequency.size();
      Pairing            result;
      bool               any_shape = false;
      for (const Target &t : targets)
        if (!t.shape.empty())
          {
            any_shape = true;
            if (!model_has_shapes(modes, t.shape.size()))
              throw std::runtime_error(
                "model updating: target '" + t.label + "' has a shape of " +
                std::to_string(t.shape.size()) +
                " components but the model gives none of that length (one "
                "per measurement point)");
          }
      if (any_shape)
        result.mac_matrix = Eigen::MatrixXd::Constant(m, n, -1.);
      // repeated model frequencies (a symmetric body's doublets): any
      // combination of the group's shapes is a mode, so a measured shape is
      // compared with the group's span
      const auto configuration = [&](const unsigned int k) {
        return modes.configuration.empty() ? 0u : modes.configuration[k];
      };
      std::vector<unsigned int> group_start(n);
      for (unsigned int k = 0; k < n; ++k)
        group_start[k] =
          k > 0 && configuration(k) == configuration(k - 1) &&
              std::abs(modes.frequency[k] - modes.frequency[k - 1]) <=
                repeated * std::abs(modes.frequency[k]) ?
            group_start[k - 1] :
            k;
      Eigen::MatrixXd cost(m, n);
      for (unsigned int i = 0; i < m; ++i)
        {
          const Target &t = targets[i];
          for (unsigned int k = 0; k < n; ++k)
            {
              const double distance =
                std::abs(modes.frequency[k] - t.frequency) / t.frequency;
              double c = distance;
              if (configuration(k) != t.configuration)
                c = forbidden;
              else if (!t.shape.empty())
                {
                  const double mac =
                    subspace_mac(t.shape, modes, group_start, k);
                  result.mac_matrix(i, k) = mac;
                  // the frequency breaks ties between equal shapes (a
                  // doublet's twins)
                  c = mac >= options.mac_threshold ?
                        1. - mac + 1e-3 * std::min(distance, 1.) :
                        forbidden;
                }
              else if (!t.name.empty())
                c =
                  k < modes.name.size() && names_match(t.name, modes.name[k]) ?
                    distance :
                    forbidden;
              else if (distance > options.frequency_window)
                c = forbidden;
              cost(i, k) = c;
            }
        }
      result.mode = eigen::optimal_assignment(cost, forbidden / 2);
      result.mac.assign(m, -1.);
      for (unsigned int i = 0; i < m; ++i)
        {
          const Target &t = targets[i];
          const int     k = result.mode[i];
          if (k >= 0 && cost(i, k) < forbidden / 2)
            {
              if (!t.shape.empty())
                result.mac[i] = result.mac_matrix(i, k);
              continue;
            }
          std::ostringstream what;
          what << "model updating: target '" << t.label << "' (" << t.frequency
               << " Hz) has no model mode to pair with: ";
          if (!t.shape.empty())
            what << "its largest MAC is "
                 << (n > 0 ? result.mac_matrix.row(i).maxCoeff() : 0.)
                 << ", below the MAC threshold " << options.mac_threshold
                 << " (or the modes above it are taken by other targets)";
          else if (!t.name.empty())
            {
              what << "no free mode of the model's " << n << " is named '"
                   << t.name << "'"
                   << (t.configuration > 0 ? " in configuration " +
                                               std::to_string(t.configuration) :
                                             std::string());
              // the modes nearest in frequency, to show what the model has
              std::vector<unsigned int> near;
              for (unsigned int k = 0; k < n; ++k)
                if (configuration(k) == t.configuration)
                  near.push_back(k);
              std::sort(near.begin(), near.end(), [&](auto a, auto b) {
                return std::abs(modes.frequency[a] - t.frequency) <
                       std::abs(modes.frequency[b] - t.frequency);
              });
              near.resize(std::min<std::size_t>(near.size(), 4));
              what << "; the nearest are";
              for (const unsigned int k : near)
                what << " " << std::setprecision(5) << modes.frequency[k]
                     << " Hz '" << (k < modes.name.size() ? modes.name[k] : "")
                     << "'";
            }
          else
            what << "no free mode lies within "
                 << 100 * options.frequency_window << " % of its frequency";
          throw std::runtime_error(what.str());
        }
      return result;
    }


    Result
    update(const ModalModel             &model,
           const std::vector<Parameter> &parameters,
           const std::vector<double>    &start,
           const std::vector<Target>    &targets,
           const Options                &options,
           std::ostream                 *log)
    {
      const unsigned int n = parameters.size();
      if (n == 0)
        throw std::runtime_error("model updating: no parameter to fit");
      if (start.size() != n)
        throw std::logic_error("model updating: one start value per "
                               "parameter expected");
      if (targets.empty())
        throw std::runtime_error("model updating: no measured mode to fit");
      for (const Parameter &q : parameters)
        if (!(q.lower < q.upper) || (q.log_scale && !(q.lower > 0.)))
          {
            std::ostringstream what;
            what << "model updating: parameter " << q.name << " has bounds ["
                 << q.lower << ", " << q.upper << "]; they must satisfy lower "
                 << "< upper"
                 << (q.log_scale ? " and lower > 0 (log scale)" : "");
            throw std::runtime_error(what.str());
          }
      for (const Target &t : targets)
        if (!(t.frequency > 0.) || !(t.weight > 0.) ||
            !(t.damping_ratio >= 0. && t.damping_ratio < 1.))
          throw std::runtime_error("model updating: target '" + t.label +
                                   "' needs a frequency > 0 Hz, a weight "
                                   "> 0 and a damping ratio in [0, 1)");
      if (!(options.measurement_error > 0.) || !(options.damping_error > 0.))
        throw std::runtime_error("model updating: the measurement errors of "
                                 "frequency and damping must be > 0");

      Eigen::VectorXd x(n), lo(n), hi(n);
      for (unsigned int j = 0; j < n; ++j)
        {
          const Parameter &q = parameters[j];
          lo[j]              = to_x(q, q.lower);
          hi[j]              = to_x(q, q.upper);
          x[j]               = to_x(q, std::clamp(start[j], q.lower, q.upper));
        }

      Result r;
      for (unsigned int j = 0; j < n; ++j)
        r.initial.push_back(to_p(parameters[j], x[j]));
      Evaluation now    = evaluate(model, parameters, x, targets, options);
      r.initial_modes   = now.modes;
      r.initial_pairing = now.pairing;
      r.initial_cost    = now.cost;
      r.history.push_back({0, now.cost, 0., true, now.p});
      if (log != nullptr)
        *log << "Model updating: start cost " << now.cost << " at "
             << values_text(now.p) << std::endl;

      double damping = 1e-3;
      // the damping's growth on a rejected trial, doubled on each rejection
      // in a row (H. B. Nielsen, IMM-REP-1999-05, DTU, 1999)
      double       growth = 2.;
      unsigned int trial  = 0;
      r.stop_reason       = "iteration limit";
      while (r.iterations < options.max_iterations)
        {
          if (trial >= 3 * options.max_iterations + 10)
            {
              r.stop_reason = "trial limit (3 x Maximum iterations + 10 "
                              "evaluations)";
              break;
            }
          const Eigen::MatrixXd A = now.J.transpose() * now.J;
          const Eigen::VectorXd g = now.J.transpose() * now.r;
          // the projected gradient: components pushing out of a bound at it
          // do not count
          Eigen::VectorXd free_g = g;
          for (unsigned int j = 0; j < n; ++j)
            if ((x[j] <= lo[j] && g[j] > 0.) || (x[j] >= hi[j] && g[j] < 0.))
              free_g[j] = 0.;
          if (free_g.norm() <= 1e-14 * (1. + now.r.norm()))
            {
              r.converged   = true;
              r.stop_reason = "zero gradient";
              break;
            }
          // the step in the free parameters only: one held at a bound that
          // the gradient pushes against stays there (projected
          // Levenberg-Marquardt, an active set of bounds)
          std::vector<unsigned int> unbound;
          for (unsigned int j = 0; j < n; ++j)
            if (free_g[j] != 0. || (x[j] > lo[j] && x[j] < hi[j]))
              unbound.push_back(j);
          const unsigned int nf = unbound.size();
          Eigen::MatrixXd    Af(nf, nf);
          Eigen::VectorXd    gf(nf);
          for (unsigned int a = 0; a < nf; ++a)
            {
              gf[a] = g[unbound[a]];
              for (unsigned int b = 0; b < nf; ++b)
                Af(a, b) = A(unbound[a], unbound[b]);
            }
          Eigen::VectorXd D       = Af.diagonal();
          const double    largest = std::max(D.maxCoeff(), 1e-300);
          for (unsigned int a = 0; a < nf; ++a)
            D[a] = std::max(D[a], 1e-12 * largest);
          const Eigen::MatrixXd lhs =
            Af + damping * Eigen::MatrixXd(D.asDiagonal());
          const Eigen::VectorXd dxf     = lhs.ldlt().solve(-gf);
          Eigen::VectorXd       trial_x = x;
          for (unsigned int a = 0; a < nf; ++a)
            trial_x[unbound[a]] += dxf[a];
          trial_x                    = trial_x.cwiseMax(lo).cwiseMin(hi);
          const Eigen::VectorXd dx   = trial_x - x;
          const double          step = dx.norm();
          if (step <= options.tolerance * (1. + x.norm()))
            {
              r.converged   = true;
              r.stop_reason = "step below tolerance";
              break;
            }
          // the decrease the linearised model promises for the step: where
          // it is below the tolerance the fit stands in a valley too flat
          // to descend (a parameter the data barely determine, whose
          // direction the damping hardly shortens)
          const double predicted = -(g.dot(dx) + 0.5 * dx.dot(A * dx));
          if (predicted <= options.tolerance * now.cost)
            {
              r.converged   = true;
              r.stop_reason = "predicted cost decrease below tolerance";
              break;
            }
          ++trial;
          bool       accepted = false;
          Evaluation next;
          try
            {
              next     = evaluate(model, parameters, trial_x, targets, options);
              accepted = next.cost < now.cost;
            }
          catch (const std::runtime_error &e)
            {
              // a trial point whose modes cannot be paired is a failed step
              if (log != nullptr)
                *log << "  trial " << trial << " rejected: " << e.what()
                     << std::endl;
            }
          std::vector<double> trial_p;
          for (unsigned int j = 0; j < n; ++j)
            trial_p.push_back(to_p(parameters[j], trial_x[j]));
          r.history.push_back({trial,
                               accepted ? next.cost : now.cost,
                               damping,
                               accepted,
                               trial_p});
          if (log != nullptr)
            *log << "  trial " << trial << ": cost "
                 << (accepted ? next.cost : now.cost) << " lambda " << damping
                 << (accepted ? " accepted at " : " rejected at ")
                 << values_text(trial_p) << std::endl;
          if (accepted)
            {
              const double decrease = now.cost - next.cost;
              x                     = trial_x;
              now                   = std::move(next);
              ++r.iterations;
              damping = std::max(damping / 3., 1e-12);
              growth  = 2.;
              if (decrease <= options.tolerance * now.cost || now.cost <= 1e-30)
                {
                  r.converged   = true;
                  r.stop_reason = "cost decrease below tolerance";
                  break;
                }
            }
          else
            {
              growth *= 2.;
              damping *= growth;
              if (damping > 1e12)
                {
                  r.converged   = true;
                  r.stop_reason = "no step lowers the cost";
                  break;
                }
            }
        }

      r.value   = now.p;
      r.modes   = now.modes;
      r.pairing = now.pairing;
      r.cost    = now.cost;
      for (unsigned int j = 0; j < n; ++j)
        r.at_bound.push_back(x[j] <= lo[j] || x[j] >= hi[j]);

      // uncertainty and identifiability from J = U S V^T: Cov(x) = V S^-2
      // V^T over the singular values above the rank tolerance
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(now.J, Eigen::ComputeFullV);
      r.singular_value = Eigen::VectorXd::Zero(n);
      r.singular_value.head(svd.singularValues().size()) = svd.singularValues();
      r.singular_vector                                  = svd.matrixV();
      const double s_max =
        r.singular_value.size() > 0 ? r.singular_value[0] : 0.;
      const double      cutoff = options.rank_tolerance * s_max;
      Eigen::MatrixXd   cov    = Eigen::MatrixXd::Zero(n, n);
      std::vector<bool> in_null(n, false);
      for (unsigned int k = 0; k < n; ++k)
        {
          const Eigen::VectorXd v = r.singular_vector.col(k);
          if (r.singular_value[k] > cutoff && s_max > 0.)
            cov +=
              v * v.transpose() / (r.singular_value[k] * r.singular_value[k]);
          else
            for (unsigned int j = 0; j < n; ++j)
              if (std::abs(v[j]) > 0.1)
                in_null[j] = true;
        }
      for (unsigned int j = 0; j < n; ++j)
        {
          const double sd =
            in_null[j] ?
              std::numeric_limits<double>::infinity() :
              std::sqrt(cov(j, j)) * dp_dx(parameters[j], r.value[j]);
          r.standard_deviation.push_back(sd);
          r.identifiable.push_back(!in_null[j] &&
                                   sd <= options.largest_relative_deviation *
                                           std::abs(r.value[j]));
        }
      if (log != nullptr)
        *log << "Model updating: " << r.stop_reason << " after " << r.iterations
             << " steps, cost " << r.initial_cost << " -> " << r.cost << " at "
             << values_text(r.value) << std::endl;
      return r;
    }
  } // namespace updating
} // namespace squeal
