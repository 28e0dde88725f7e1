// The complex eigenvalue analysis driver: model set-up (with the preload and
// the mesh refinement of cea_adaptivity.cc), the sweep over two scalar
// parameters with the full or the reduced solver (points shared among MPI
// ranks), the check of the reduced solver against the full one, mode
// tracking and the unstable regions. The outputs are written by
// cea_output.cc. It follows the tutorial class shape (setup_system, solve,
// output_results, run) with a timer per phase.

#include <deal.II/base/utilities.h>
#include <deal.II/lac/petsc_vector.h>

#include <squeal/analyses/cea.h>
#include <squeal/base/errors.h>
#include <squeal/base/memory_estimate.h>
#include <squeal/contact/scene_contact.h>
#include <squeal/eigen/mac.h>
#include <squeal/io/matrix_export.h>
#include <squeal/io/output_directory.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;
    namespace fs = std::filesystem;

    ComplexEigenvalueAnalysis::ComplexEigenvalueAnalysis(
      const parameters::AllParameters &prm,
      const ParameterHandler          &handler,
      MPI_Comm                         comm)
      : prm(prm)
      , handler(handler)
      , comm(comm)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
      , timer(comm, pcout, TimerOutput::never, TimerOutput::wall_times)
      , model(std::make_unique<physics::StructuralModel>(prm, comm))
    {
      // sensitivities need every named parameter in parts of its own
      if (prm.output.sensitivities == "none")
        model->varied = varied_parameters();
      model->tie_constraints = contact::add_tie_constraints;
    }

    std::set<std::string>
    ComplexEigenvalueAnalysis::varied_parameters() const
    {
      return {prm.sweep.first.parameter, prm.sweep.second.parameter};
    }

    std::vector<parameters::ScalarPoint>
    ComplexEigenvalueAnalysis::sweep_points() const
    {
      return scene::sweep_points(*model->scene, prm.sweep);
    }


    void
    ComplexEigenvalueAnalysis::setup_system()
    {
      TimerOutput::Scope t(timer, "setup and assembly");
      // Refuse to replace earlier results; write into a temporary directory
      // that output_results() renames at the end.
      const std::size_t n_points =
        prm.sweep.first.values.size() * prm.sweep.second.values.size();
      for (const unsigned int p : prm.output.export_points)
        if (p >= n_points)
          throw std::runtime_error(
            "Output/Export matrices: sweep point " + std::to_string(p) +
            " does not exist; the sweep has points 0 to " +
            std::to_string(n_points - 1));
      std::vector<std::string> folders{"modes"};
      if (!prm.output.export_points.empty())
        folders.push_back("matrices");
      work_dir = io::start_work_directory(
        prm.output.directory, prm.output.overwrite, handler, comm, folders);
      // the preload's nodal contact pressure at the pad nodes [Pa]
      std::vector<std::pair<dealii::Point<3>, double>> preload_pressure;
      // the interface where the pad is in contact: after the preload or
      // as in a braking history (cea_contact_state.cc)
      std::function<void()> check_contact_state;
      if (prm.scene.analysis == "preloaded cea")
        check_contact_state = set_contact_state(preload_pressure);
      model->setup_and_assemble(pcout);
      if (check_contact_state)
        check_contact_state();
      refine_at_contact(preload_pressure);
      adapt_mesh();
      // the matrices of the chosen points on the final mesh
      if (!prm.output.export_points.empty())
        {
          const auto sweep = sweep_points();
          std::vector<std::pair<unsigned int, parameters::ScalarPoint>> points;
          for (const unsigned int p : prm.output.export_points)
            points.emplace_back(p, sweep[p]);
          io::export_matrices(*model, points, work_dir + "/matrices");
          pcout << "Matrices of " << points.size()
                << " sweep point(s) written to matrices/ (MatrixMarket)"
                << std::endl;
        }
      const double factor = factorisation_bytes(
        model->parts().parts[0].matrix->n_nonzero_elements(),
        model->n_dofs(),
        true);
      report_memory_estimate(
        comm,
        pcout.is_active() ? &pcout.get_stream() : nullptr,
        model->n_dofs(),
        factor,
        "an LDL^T of the stiffness; the eigensolvers' vectors come on top "
        "(estimated after their inertia counts)",
        factor);
    }

    std::vector<parameters::ScalarPoint>
    ComplexEigenvalueAnalysis::basis_samples() const
    {
      const unsigned int                   n = prm.eigensolver.reduced_samples;
      std::vector<parameters::ScalarPoint> samples{sweep_points()[0]};
      for (const auto *axis : {&prm.sweep.first, &prm.sweep.second})
        {
          if (!model->scene->parameter(axis->parameter).structural)
            continue;
          const auto [lo, hi] =
            std::minmax_element(axis->values.begin(), axis->values.end());
          const bool          log = axis->log_scale();
          std::vector<double> values;
          for (unsigned int i = 0; i < n; ++i)
            {
              const double t = n == 1 ? 0.5 : double(i) / (n - 1);
              values.push_back(log ? *lo * std::pow(*hi / *lo, t) :
                                     *lo + (*hi - *lo) * t);
              if (*hi == *lo)
                break;
            }
          std::vector<parameters::ScalarPoint> combined;
          for (const auto &s : samples)
            for (const double v : values)
              {
                combined.push_back(s);
                combined.back().set(axis->parameter, v);
              }
          samples = combined;
        }
      return samples;
    }

    std::string
    ComplexEigenvalueAnalysis::describe(const parameters::ScalarPoint &p) const
    {
      std::ostringstream s;
      s << std::setprecision(4);
      for (const auto *axis : {&prm.sweep.first, &prm.sweep.second})
        {
          s << (axis == &prm.sweep.first ? "" : ", ") << axis->parameter
            << " = " << p.get(axis->parameter);
        }
      return s.str();
    }

    void
    ComplexEigenvalueAnalysis::solve_sweep()
    {
      const auto        &es             = prm.eigensolver;
      eigen::BandOptions band           = band_options();
      const bool         reduced_method = es.method == "reduced";
      if (const auto &modal = model->parts().modal; modal.active())
        {
          pcout << "Modal damping of the frictionless modes up to "
                << modal.cutoff << " Hz (besides the Rayleigh damping):";
          for (const auto &[f, zeta] : modal.ratios)
            pcout << " " << 100. * zeta << " % at " << f << " Hz;";
          pcout << " linear between, constant beyond" << std::endl;
        }
      if (reduced_method)
        {
          TimerOutput::Scope t(timer, "reduced basis");
          pcout << "Building the reduced basis" << std::endl;
          reduced.build(model->parts(),
                        basis_samples(),
                        band,
                        es.reduced_band_factor,
                        es.reduced_enrichment ? es.reduced_enrichment_depth : 0,
                        pcout,
                        first_point_full.empty() ? nullptr :
                                                   &first_point_symmetric);
        }
      first_point_symmetric = eigen::KnownSymmetricModes(); // its memory

      const auto         sweep    = sweep_points();
      const unsigned int n_points = sweep.size();
      pcout << "Sweep: " << prm.sweep.second.values.size() << " x "
            << prm.sweep.second.parameter << ", "
            << prm.sweep.first.values.size() << " x "
            << prm.sweep.first.parameter << " = " << n_points << " points, "
            << (reduced_method ? "reduced" : "full") << " solver, band "
            << es.f_min << "-" << es.f_max << " Hz" << std::endl;
      const auto start    = std::chrono::steady_clock::now();
      const auto progress = [&](const unsigned int k,
                                const auto        &values,
                                const unsigned int n_modes) {
        const double elapsed = std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - start)
                                 .count();
        pcout << "  point " << k << " of " << n_points << " ("
              << describe(values) << "): " << n_modes << " modes, elapsed "
              << std::setprecision(3) << elapsed << " s, remaining ~"
              << elapsed * (n_points - k) / k << " s" << std::setprecision(6)
              << std::endl;
      };
      if (reduced_method)
        {
          // Sweep points are independent small dense problems: each rank
          // solves every n_ranks-th point, then all results are shared.
          TimerOutput::Scope t(timer, "reduced solve");
          const unsigned int rank = Utilities::MPI::this_mpi_process(comm),
                             size = Utilities::MPI::n_mpi_processes(comm);
          std::vector<double> packed; // p, m, then (re, im, res, q) per pair
          unsigned int        done = 0;
          std::string         failure; // this rank's first failed point
          for (unsigned int p = rank; p < n_points && failure.empty();
               p += size)
            {
              std::vector<eigen::ReducedEigenPair> pairs;
              try
                {
                  pairs = reduced.solve(sweep[p], es.f_min, es.f_max);
                }
              catch (const std::exception &e)
                {
                  failure = "the reduced solve at sweep point " +
                            std::to_string(p) + " (" + describe(sweep[p]) +
                            "): " + one_line(e);
                  break;
                }
              packed.push_back(p);
              packed.push_back(pairs.size());
              for (const auto &r : pairs)
                {
                  packed.insert(packed.end(),
                                {r.lambda.real(), r.lambda.imag(), r.residual});
                  for (const auto &z : r.q)
                    packed.insert(packed.end(), {z.real(), z.imag()});
                }
              ++done;
              const unsigned int k = std::min(n_points, done * size);
              if (k == n_points || k % 10 < size)
                progress(k, sweep[p], pairs.size());
            }
          // every rank learns of a failed point (none waits for the rest)
          for (const std::string &message :
               Utilities::MPI::all_gather(comm, failure))
            if (!message.empty())
              throw std::runtime_error(message);
          points.resize(n_points);
          const int r = reduced.size();
          for (const auto &part : Utilities::MPI::all_gather(comm, packed))
            for (std::size_t i = 0; i < part.size();)
              {
                Point &pt = points[static_cast<unsigned int>(part[i])];
                const unsigned int m = part[i + 1];
                i += 2;
                for (unsigned int j = 0; j < m; ++j, i += 3 + 2 * r)
                  {
                    pt.lambda.emplace_back(part[i], part[i + 1]);
                    pt.residual.push_back(part[i + 2]);
                    Eigen::VectorXcd q(r);
                    for (int c = 0; c < r; ++c)
                      q[c] = {part[i + 3 + 2 * c], part[i + 4 + 2 * c]};
                    pt.q.push_back(q);
                  }
              }
          for (unsigned int p = 0; p < n_points; ++p)
            points[p].values = sweep[p];
          return;
        }
      for (const auto &values : sweep)
        {
          TimerOutput::Scope t(timer, "full solve");
          Point              p;
          p.values = values;
          if (points.empty() && !first_point_full.empty())
            {
              p.full = first_point_full;
              pcout << "  full solver: the last adaptive cycle's solve of "
                       "this point, reused"
                    << std::endl;
            }
          else
            try
              {
                p.full = eigen::solve_full(
                  model->parts(), values, band, pcout, &p.report);
              }
            catch (const std::exception &e)
              {
                // collective: every rank fails here together
                throw std::runtime_error("the full solve at sweep point " +
                                         std::to_string(points.size()) + " (" +
                                         describe(values) +
                                         "): " + one_line(e));
              }
          check_residuals(points.size(), p.full);
          if (prm.output.sensitivities != "none")
            {
              // inside the full solve's timer section: the left
              // eigenvectors are a second full solve
              const auto               start = std::chrono::steady_clock::now();
              std::vector<std::string> names;
              for (const auto &parameter : model->scene->parameters())
                names.push_back(parameter.name);
              try
                {
                  const auto left = eigen::left_eigenvectors(
                    model->parts(), values, band, p.full, pcout);
                  p.sensitivity = eigen::eigenvalue_sensitivities(
                    model->parts(), values, names, p.full, left);
                  pcout << "  sensitivities: " << p.full.size() << " modes x "
                        << names.size()
                        << " parameters (left eigenvectors by a full solve of "
                           "the transposed problem), "
                        << std::chrono::duration<double>(
                             std::chrono::steady_clock::now() - start)
                             .count()
                        << " s" << std::endl;
                }
              catch (const std::exception &e)
                {
                  throw std::runtime_error("the sensitivities at sweep point " +
                                           std::to_string(points.size()) +
                                           " (" + describe(values) +
                                           "): " + one_line(e));
                }
            }
          for (const auto &r : p.full)
            {
              p.lambda.push_back(r.lambda);
              p.residual.push_back(r.residual);
            }
          points.push_back(std::move(p));
          progress(points.size(), values, points.back().lambda.size());
        }
    }

    eigen::BandOptions
    ComplexEigenvalueAnalysis::band_options(
      const unsigned int initial_nev) const
    {
      const auto        &es = prm.eigensolver;
      eigen::BandOptions band{
        es.f_min, es.f_max, es.target_frequency, es.tolerance, initial_nev};
      band.residual_tolerance = es.residual_tolerance;
      band.symmetric_solver   = es.symmetric_solver;
      band.store_products     = es.subspace_products == "stored";
      return band;
    }

    bool
    ComplexEigenvalueAnalysis::near_unstable(
      const std::complex<double> lambda) const
    {
      const auto &es = prm.eigensolver;
      return lambda.real() + es.certification_margin >
             std::max(es.unstable_tolerance,
                      es.unstable_relative_tolerance * std::abs(lambda));
    }

    void
    ComplexEigenvalueAnalysis::check_residuals(
      const unsigned int                   p,
      const std::vector<eigen::EigenPair> &pairs)
    {
      for (const auto &pair : pairs)
        if (!(pair.residual <= prm.eigensolver.residual_tolerance))
          {
            std::ostringstream what;
            what << "point " << p << ": full solver eigenpair at "
                 << pair.lambda.imag() / (2 * M_PI) << " Hz, Re lambda "
                 << pair.lambda.real() << " 1/s, relative residual "
                 << pair.residual << " above Eigensolver/Residual tolerance "
                 << prm.eigensolver.residual_tolerance;
            unverified.push_back(what.str());
          }
    }

    void
    ComplexEigenvalueAnalysis::check_against_full()
    {
      const auto &es = prm.eigensolver;
      if (es.method != "reduced" || es.n_check_points == 0 || points.empty())
        return;
      TimerOutput::Scope t(timer, "check against full");
      // The most unstable point, then the first and last unstable point of
      // every unstable region's track.
      std::vector<unsigned int> chosen;
      const auto                choose = [&](const unsigned int p) {
        if (chosen.size() < es.n_check_points &&
            std::find(chosen.begin(), chosen.end(), p) == chosen.end())
          chosen.push_back(p);
      };
      unsigned int worst  = 0;
      double       max_re = -1e300;
      for (unsigned int p = 0; p < points.size(); ++p)
        for (const auto &l : points[p].lambda)
          if (l.real() > max_re)
            {
              max_re = l.real();
              worst  = p;
            }
      choose(worst);
      for (const auto &r : regions)
        {
          choose(r.first_point);
          choose(r.last_point);
        }
      pcout << "Checking the reduced solver against the full solver at "
            << chosen.size()
            << " points (the most unstable and the edges of every unstable "
               "region)"
            << std::endl;
      const auto unstable = [&](const std::complex<double> l) {
        return eigen::is_unstable(l,
                                  es.unstable_tolerance,
                                  es.unstable_relative_tolerance);
      };
      double max_error = 0;
      for (const unsigned int p : chosen)
        {
          const bool reuse = p == 0 && !first_point_full.empty();
          if (reuse)
            pcout << "  point 0: the last adaptive cycle's full solve, reused"
                  << std::endl;
          const auto full = reuse ? first_point_full :
                                    eigen::solve_full(model->parts(),
                                                      points[p].values,
                                                      band_options(),
                                                      pcout);
          check_residuals(p, full);
          // one-to-one matching by relative eigenvalue distance
          const auto     &reduced_lambda = points[p].lambda;
          Eigen::MatrixXd cost(full.size(), reduced_lambda.size());
          for (unsigned int i = 0; i < full.size(); ++i)
            for (unsigned int j = 0; j < reduced_lambda.size(); ++j)
              cost(i, j) = std::abs(reduced_lambda[j] - full[i].lambda) /
                           std::abs(full[i].lambda);
          const auto match = eigen::optimal_assignment(cost);
          // a mode may cross a band edge between the two solvers
          const auto at_edge = [&](const std::complex<double> l) {
            const double f = l.imag() / (2 * M_PI);
            return f < es.f_min * (1 + es.check_tolerance) ||
                   f > es.f_max * (1 - es.check_tolerance);
          };
          std::vector<bool>  matched(reduced_lambda.size(), false);
          unsigned int       n_unstable_full = 0, n_unstable_reduced = 0;
          std::ostringstream failures;
          for (unsigned int i = 0; i < full.size(); ++i)
            {
              const std::complex<double> f = full[i].lambda;
              n_unstable_full += unstable(f);
              std::ostringstream row;
              row << std::setprecision(12) << p << ','
                  << points[p].values.get(prm.sweep.first.parameter) << ','
                  << points[p].values.get(prm.sweep.second.parameter) << ','
                  << f.real() << ',' << f.imag() / (2 * M_PI) << ',';
              if (match[i] < 0)
                {
                  row << ",,,,";
                  if (!at_edge(f))
                    failures << "; full mode at " << f.imag() / (2 * M_PI)
                             << " Hz has no reduced one";
                }
              else
                {
                  matched[match[i]]            = true;
                  const std::complex<double> r = reduced_lambda[match[i]];
                  const double               e = cost(i, match[i]);
                  max_error                    = std::max(max_error, e);
                  row << r.real() << ',' << r.imag() / (2 * M_PI) << ','
                      << std::abs(r.imag() - f.imag()) / f.imag() << ','
                      << std::abs(r.real() - f.real()) /
                           (std::abs(f.real()) + 1.)
                      << ',' << e;
                  if (e > es.check_tolerance)
                    failures << "; full mode at " << f.imag() / (2 * M_PI)
                             << " Hz (Re " << f.real()
                             << " 1/s) matched to reduced "
                             << r.imag() / (2 * M_PI) << " Hz (Re " << r.real()
                             << " 1/s), relative error " << e;
                }
              check_rows.push_back(row.str());
            }
          for (unsigned int j = 0; j < reduced_lambda.size(); ++j)
            {
              n_unstable_reduced += unstable(reduced_lambda[j]);
              if (!matched[j] && !at_edge(reduced_lambda[j]))
                failures << "; reduced mode at "
                         << reduced_lambda[j].imag() / (2 * M_PI)
                         << " Hz has no full one";
            }
          if (n_unstable_full != n_unstable_reduced)
            failures << "; " << n_unstable_full << " unstable modes (full), "
                     << n_unstable_reduced << " (reduced)";
          pcout << "  point " << p << " (" << describe(points[p].values)
                << "): " << full.size() << " modes (full), "
                << reduced_lambda.size() << " (reduced), " << n_unstable_full
                << " unstable (full), " << n_unstable_reduced << " (reduced)"
                << std::endl;
          if (!failures.str().empty())
            unverified.push_back(
              "point " + std::to_string(p) + " (" + describe(points[p].values) +
              "), reduced against full solver" + failures.str());
        }
      pcout << "Reduced against full: largest relative eigenvalue error "
            << max_error << " of the one-to-one matched pairs" << std::endl;
    }

    void
    ComplexEigenvalueAnalysis::certify()
    {
      const auto &es = prm.eigensolver;
      if (es.method != "reduced" || !es.certify || points.empty())
        return;
      TimerOutput::Scope t(timer, "certification");
      const auto         start = std::chrono::steady_clock::now();
      const auto         near  = [this](const std::complex<double> l) {
        return near_unstable(l);
      };
      // the points with eigenvalues to certify, those that share the
      // preconditioner's M and K_s next to each other
      const auto parts = model->parts();
      std::vector<std::pair<std::vector<double>, unsigned int>> order;
      unsigned int                                              n_pairs = 0;
      for (unsigned int p = 0; p < points.size(); ++p)
        {
          points[p].refined.assign(points[p].lambda.size(), false);
          const unsigned int n = std::count_if(points[p].lambda.begin(),
                                               points[p].lambda.end(),
                                               near);
          if (n == 0)
            continue;
          n_pairs += n;
          const auto          c   = parts.coefficients(points[p].values);
          std::vector<double> key = c.mass;
          key.insert(key.end(),
                     c.symmetric_stiffness.begin(),
                     c.symmetric_stiffness.end());
          order.emplace_back(key, p);
        }
      std::stable_sort(order.begin(),
                       order.end(),
                       [](const auto &a, const auto &b) {
                         return a.first < b.first;
                       });
      pcout << "Certifying the stability map: " << n_pairs
            << " eigenvalues within " << es.certification_margin
            << " 1/s of the stability threshold at " << order.size()
            << " points, refined on the full model to residual "
            << es.residual_tolerance << std::endl;
      const eigen::BandOptions refiner_band = band_options();
      eigen::PairRefiner       refiner(parts, refiner_band);
      double                   largest = 0., largest_move = 0.;
      unsigned int             rounds = 0;
      for (const auto &[key, p] : order)
        {
          Point                            &pt = points[p];
          std::vector<unsigned int>         index;
          std::vector<std::complex<double>> lambda;
          std::vector<Eigen::VectorXcd>     q;
          for (unsigned int m = 0; m < pt.lambda.size(); ++m)
            if (near(pt.lambda[m]))
              {
                index.push_back(m);
                lambda.push_back(pt.lambda[m]);
                q.push_back(pt.q[m]);
              }
          const auto refined =
            refiner.refine(pt.values,
                           reduced.projection(pt.values,
                                              refiner_band.store_products),
                           lambda,
                           q);
          for (unsigned int a = 0; a < index.size(); ++a)
            {
              const unsigned int m = index[a];
              const auto        &r = refined[a];
              const double       moved =
                std::abs(r.lambda - pt.lambda[m]) / std::abs(r.lambda);
              std::ostringstream what;
              what << "point " << p << " (" << describe(pt.values)
                   << "): reduced eigenvalue at "
                   << pt.lambda[m].imag() / (2 * M_PI) << " Hz, Re lambda "
                   << pt.lambda[m].real() << " 1/s, ";
              if (!(r.residual <= es.residual_tolerance))
                unverified.push_back(
                  what.str() + "refined on the full model to residual " +
                  Utilities::to_string(r.residual) +
                  " only, above Eigensolver/Residual tolerance " +
                  Utilities::to_string(es.residual_tolerance));
              else if (moved > es.check_tolerance)
                unverified.push_back(
                  what.str() + "moved by " + Utilities::to_string(moved) +
                  " of |lambda| on the full model, more than "
                  "Eigensolver/Check tolerance " +
                  Utilities::to_string(es.check_tolerance));
              largest        = std::max(largest, r.residual);
              largest_move   = std::max(largest_move, moved);
              rounds         = std::max(rounds, r.rounds);
              pt.lambda[m]   = r.lambda;
              pt.residual[m] = r.residual;
              pt.refined[m]  = true;
            }
        }
      pcout << "  certified: largest residual " << largest << " after at most "
            << rounds << " rounds, largest change of a reduced eigenvalue "
            << largest_move << " of |lambda|; " << refiner.factorisations()
            << " factorisations (" << refiner.factorisation_seconds() << " s), "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                             start)
                 .count()
            << " s" << std::endl;
    }

    void
    ComplexEigenvalueAnalysis::classify()
    {
      TimerOutput::Scope t(timer, "tracking and classification");
      const auto        &es      = prm.eigensolver;
      const double       tol     = es.unstable_tolerance;
      int                next_id = 0;
      unsigned int       first   = 0;
      while (first < points.size())
        {
          // One value of the second parameter: a run of the first.
          const auto second = [&](const unsigned int p) {
            return points[p].values.get(prm.sweep.second.parameter);
          };
          unsigned int last = first;
          while (last + 1 < points.size() && second(last + 1) == second(first))
            ++last;
          std::vector<std::vector<std::complex<double>>> lambdas;
          std::vector<Eigen::MatrixXd>                   macs;
          std::vector<double>                            x;
          std::vector<unsigned int>                      index;
          for (unsigned int p = first; p <= last; ++p)
            {
              lambdas.push_back(points[p].lambda);
              x.push_back(points[p].values.get(prm.sweep.first.parameter));
              index.push_back(p);
              Eigen::MatrixXd mac;
              if (p > first)
                {
                  const auto &a = points[p - 1], &b = points[p];
                  mac.resize(a.lambda.size(), b.lambda.size());
                  for (unsigned int i = 0; i < a.lambda.size(); ++i)
                    for (unsigned int j = 0; j < b.lambda.size(); ++j)
                      mac(i, j) = !a.q.empty() ?
                                    eigen::complex_mac(a.q[i], b.q[j]) :
                                    eigen::complex_mac(a.full[i].re,
                                                       a.full[i].im,
                                                       b.full[j].re,
                                                       b.full[j].im);
                }
              macs.push_back(mac);
            }
          const auto tracks = eigen::track_modes(
            lambdas, macs, next_id, 10., es.tracking_mac_threshold);
          for (unsigned int p = first; p <= last; ++p)
            for (unsigned int m = 0; m < points[p].lambda.size(); ++m)
              {
                const auto l = points[p].lambda[m];
                modes.push_back(
                  {p,
                   points[p].values,
                   m,
                   l,
                   points[p].residual[m],
                   eigen::is_unstable(l, tol, es.unstable_relative_tolerance),
                   tracks[p - first][m],
                   !points[p].refined.empty() && points[p].refined[m]});
              }
          const auto r =
            eigen::find_unstable_regions(second(first),
                                         x,
                                         index,
                                         lambdas,
                                         tracks,
                                         tol,
                                         es.unstable_relative_tolerance);
          regions.insert(regions.end(), r.begin(), r.end());
          first = last + 1;
        }

      pcout << "\nUnstable regions (Re lambda > " << tol << " 1/s and > "
            << es.unstable_relative_tolerance << " |lambda|):" << std::endl;
      if (regions.empty())
        pcout << "  none: every eigenvalue in the band is stable" << std::endl;
      const auto first_info =
        model->scene->parameter(prm.sweep.first.parameter);
      const auto second_info =
        model->scene->parameter(prm.sweep.second.parameter);
      for (const auto &r : regions)
        {
          std::ostringstream log10;
          if (prm.sweep.first.log_scale())
            log10 << std::setprecision(4) << " (log10 "
                  << std::log10(r.first_min) << " - " << std::log10(r.first_max)
                  << ")";
          pcout << "  " << second_info.name << " = " << r.second << ": "
                << first_info.name << " " << std::setprecision(4) << r.first_min
                << " - " << r.first_max << ' ' << first_info.unit << log10.str()
                << ", " << std::setprecision(5) << r.f_min << " - " << r.f_max
                << " Hz, max Re lambda " << r.max_re << " 1/s, track "
                << r.track
                << (r.partner_track >= 0 ? " locked in with track " +
                                             std::to_string(r.partner_track) :
                                           std::string())
                << std::setprecision(6) << std::endl;
        }
    }
    void
    ComplexEigenvalueAnalysis::run()
    {
      pcout << "squeal: complex eigenvalue analysis ("
            << Utilities::MPI::n_mpi_processes(comm) << " MPI rank(s))"
            << std::endl;
      setup_system();
      solve_sweep();
      // an empty band is a wrong band, not a stable brake
      if (std::all_of(points.begin(), points.end(), [](const Point &p) {
            return p.lambda.empty();
          }))
        throw std::runtime_error(
          "no eigenvalue in the band " +
          Utilities::to_string(prm.eigensolver.f_min) + "-" +
          Utilities::to_string(prm.eigensolver.f_max) + " Hz at any of the " +
          std::to_string(points.size()) +
          " sweep points: the model's modes lie outside it; check "
          "Eigensolver/Minimum and Maximum frequency against the materials "
          "and the mesh");
      certify();
      // no reduced point is solved from here on: the check and the
      // outputs need the basis only
      if (prm.eigensolver.method == "reduced")
        reduced.release_products();
      classify();
      check_against_full();
      decompose_unstable_modes();
      if (!unverified.empty())
        {
          // one clear error: the first three failures and their count
          std::ostringstream message;
          message << unverified.size() << " verification failure(s):";
          for (unsigned int k = 0; k < unverified.size() && k < 3; ++k)
            message << "\n  " << unverified[k];
          if (unverified.size() > 3)
            message << "\n  ... (" << unverified.size() - 3 << " more)";
          if (!prm.eigensolver.allow_unverified)
            throw std::runtime_error(
              message.str() +
              "\nNo results published; Eigensolver/Allow unverified results "
              "= true writes them into " +
              io::normalised(prm.output.directory) + ".unverified");
          pcout << "WARNING: " << message.str() << "\nResults go to "
                << output_target() << std::endl;
        }
      output_results();
      timer.print_summary();
    }
  } // namespace analyses
} // namespace squeal
