// The complex eigenvalue analysis driver: model set-up, the sweep over two
// scalar parameters (by default pad modulus and friction coefficient) with
// the full or the reduced solver (points shared among MPI ranks), the
// check of the reduced solver against the full one, mode tracking and the
// unstable regions, and every output file. It follows the tutorial class
// shape (setup_system, solve, output_results, run) with a timer per phase.

#include <deal.II/base/utilities.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/error_estimator.h>

#include <squeal/cea/complex_eigenvalue_analysis.h>
#include <squeal/contact/preload.h>
#include <squeal/output/output_directory.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace cea
  {
    using namespace dealii;
    namespace fs = std::filesystem;

    ComplexEigenvalueAnalysis::ComplexEigenvalueAnalysis(
      const parameters::AllParameters &prm,
      const ParameterHandler &         handler,
      MPI_Comm                         comm)
      : prm(prm)
      , handler(handler)
      , comm(comm)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
      , timer(comm, pcout, TimerOutput::never, TimerOutput::wall_times)
      , model(std::make_unique<physics::StructuralModel>(prm, comm))
    {}

    namespace
    {
      // One contact refinement cycle (Mesh/Contact refinements): per active
      // cell the largest variation (max - min) of the preload's contact
      // pressure over its faces on the pad face or the disc's contact face
      // that overlap the pad's footprint, taken at the pad nodes NODES in
      // the face's (x, y) bounding box and at the face's vertices (the
      // nodal pressure interpolated bilinearly between the nodes): the
      // pressure gradient times the cell size. Refinement halves it, so the
      // cells go where the gradient is steepest (the pad's leading edge, its
      // separation front), not over the whole disc. The FRACTION of the
      // cells with such a face with the largest variation are refined (ties
      // together); the table (cycle, body, cell centre, variation, refined)
      // goes to CSV. Returns the number of refined cells.
      unsigned int
      refine_by_contact_pressure(
        physics::StructuralModel                                   &model,
        const std::vector<std::pair<dealii::Point<3>, double>>     &nodes_3d,
        const double                                                fraction,
        const unsigned int                                          cycle,
        std::ostream                                               &csv,
        ConditionalOStream                                         &pcout)
      {
        // everything in the contact pair's plane coordinates
        const scene::ContactPair &pair = contact::single_pair(*model.scene);
        std::vector<std::pair<Point<2>, double>> nodes;
        for (const auto &[x, p] : nodes_3d)
          nodes.emplace_back(pair.to_plane(x), p);
        double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
        for (const auto &[x, p] : nodes)
          {
            x_lo = std::min(x_lo, x[0]);
            x_hi = std::max(x_hi, x[0]);
            y_lo = std::min(y_lo, x[1]);
            y_hi = std::max(y_hi, x[1]);
          }
        const double eps = 1e-9;
        // the pad nodes form a tensor grid over the pad face (the preload
        // runs on the unrefined mesh): the pressure between them bilinear
        const auto unique_sorted = [&](const unsigned int d) {
          std::vector<double> v;
          for (const auto &[x, p] : nodes)
            v.push_back(x[d]);
          std::sort(v.begin(), v.end());
          v.erase(std::unique(v.begin(), v.end(),
                              [&](double a, double b) { return b - a < eps; }),
                  v.end());
          return v;
        };
        const std::vector<double> xs = unique_sorted(0), ys = unique_sorted(1);
        const auto locate = [&](const std::vector<double> &g, const double x) {
          unsigned int i =
            std::upper_bound(g.begin(), g.end(), x) - g.begin();
          i = std::min<unsigned int>(std::max(i, 1u), g.size() - 1) - 1;
          return std::pair<unsigned int, double>(
            i, std::clamp((x - g[i]) / (g[i + 1] - g[i]), 0., 1.));
        };
        std::vector<double> grid(xs.size() * ys.size(), 0.);
        std::vector<bool>   seen(grid.size(), false);
        for (const auto &[x, p] : nodes)
          {
            const unsigned int i = locate(xs, x[0] + eps).first +
                                   (x[0] > xs.back() - eps ? 1 : 0),
                               j = locate(ys, x[1] + eps).first +
                                   (x[1] > ys.back() - eps ? 1 : 0);
            grid[i * ys.size() + j] = p;
            seen[i * ys.size() + j] = true;
          }
        if (xs.size() < 2 || ys.size() < 2 ||
            std::count(seen.begin(), seen.end(), false) > 0)
          throw std::runtime_error(
            "Mesh/Contact refinements: the preload's pad nodes do not form a "
            "tensor grid over the pad face (" + std::to_string(nodes.size()) +
            " nodes, " + std::to_string(xs.size()) + " x " +
            std::to_string(ys.size()) + " coordinates)");
        const auto pressure_at = [&](const dealii::Point<2> &x) {
          const auto [i, t] = locate(xs, x[0]);
          const auto [j, u] = locate(ys, x[1]);
          const auto g      = [&](unsigned int a, unsigned int b) {
            return grid[a * ys.size() + b];
          };
          return (1 - t) * (1 - u) * g(i, j) + t * (1 - u) * g(i + 1, j) +
                 (1 - t) * u * g(i, j + 1) + t * u * g(i + 1, j + 1);
        };
        const unsigned int n_cells = model.triangulation.n_active_cells();
        Vector<float>      indicator(n_cells);
        std::vector<bool>  on_contact(n_cells, false);
        unsigned int       n_contact = 0;
        for (const auto &cell : model.triangulation.active_cell_iterators())
          {
            double variation = -1.;
            for (const auto f : cell->face_indices())
              {
                const auto face = cell->face(f);
                if (!face->at_boundary() ||
                    (face->boundary_id() != pair.slave &&
                     face->boundary_id() != pair.master))
                  continue;
                double fx_lo = 1e300, fx_hi = -1e300, fy_lo = 1e300,
                       fy_hi = -1e300;
                for (const auto v : face->vertex_indices())
                  {
                    const Point<2> x = pair.to_plane(face->vertex(v));
                    fx_lo         = std::min(fx_lo, x[0]);
                    fx_hi         = std::max(fx_hi, x[0]);
                    fy_lo         = std::min(fy_lo, x[1]);
                    fy_hi         = std::max(fy_hi, x[1]);
                  }
                // the face overlaps the pad's footprint (an area, not a line)
                if (std::min(fx_hi, x_hi) - std::max(fx_lo, x_lo) < eps ||
                    std::min(fy_hi, y_hi) - std::max(fy_lo, y_lo) < eps)
                  continue;
                double lo = 1e300, hi = -1e300;
                for (const auto v : face->vertex_indices())
                  {
                    const double p = pressure_at(pair.to_plane(face->vertex(v)));
                    lo             = std::min(lo, p);
                    hi             = std::max(hi, p);
                  }
                for (const auto &[q, p] : nodes)
                  if (q[0] > fx_lo - eps && q[0] < fx_hi + eps &&
                      q[1] > fy_lo - eps && q[1] < fy_hi + eps)
                    {
                      lo = std::min(lo, p);
                      hi = std::max(hi, p);
                    }
                variation = std::max(variation, hi - lo);
              }
            if (variation >= 0.)
              {
                indicator[cell->active_cell_index()]  = variation;
                on_contact[cell->active_cell_index()] = true;
                ++n_contact;
              }
          }
        const unsigned int n_refine =
          std::min(n_contact, unsigned(std::ceil(fraction * n_contact)));
        // the threshold the refined cells reach (ties refined together)
        std::vector<float> sorted;
        for (unsigned int c = 0; c < n_cells; ++c)
          if (on_contact[c])
            sorted.push_back(indicator[c]);
        std::sort(sorted.begin(), sorted.end(), std::greater<float>());
        const float threshold = n_refine > 0 ? sorted[n_refine - 1] : 1e30f;
        std::map<std::string, unsigned int> by_body;
        unsigned int n_refined = 0;
        for (const auto &cell : model.triangulation.active_cell_iterators())
          {
            const unsigned int c = cell->active_cell_index();
            if (!on_contact[c])
              continue;
            const bool refined = indicator[c] >= threshold && indicator[c] > 0.f;
            const std::string &body = model.scene->body(cell->material_id()).name;
            if (refined)
              {
                ++by_body[body];
                ++n_refined;
              }
            csv << cycle << ',' << body << ',' << cell->center()[0] << ',' << cell->center()[1] << ','
                << cell->center()[2] << ',' << indicator[c] << ',' << refined
                << '\n';
          }
        std::string split;
        for (const auto &[body, count] : by_body)
          split += (split.empty() ? "" : ", ") + std::to_string(count) + " " + body;
        pcout << "Contact refinement cycle " << cycle << ": " << n_refined
              << " of " << n_contact << " contact cells refined (" << split
              << "), pressure variation across a face: largest "
              << std::setprecision(3) << 1e-6 * sorted.front()
              << " MPa, refined down to " << 1e-6 * threshold << " MPa"
              << std::setprecision(6) << std::endl;
        if (n_refined > 0)
          {
            // refine exactly the cells above the threshold: zero elsewhere
            for (unsigned int c = 0; c < n_cells; ++c)
              if (!on_contact[c] || indicator[c] < threshold)
                indicator[c] = 0.f;
            model.refine(indicator, (n_refined + 0.5) / n_cells, false, pcout);
          }
        return n_refined;
      }
    } // namespace

    void
    ComplexEigenvalueAnalysis::setup_system()
    {
      TimerOutput::Scope t(timer, "setup and assembly");
      // Refuse to replace earlier results; write into a temporary directory
      // that output_results() renames at the end.
      work_dir =
        output::partial_directory(prm.output.directory, prm.output.overwrite);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          output::fresh_directory(work_dir, "modes");
          std::ofstream out(fs::path(work_dir) / "parameters.prm");
          handler.print_parameters(out, ParameterHandler::PRM);
        }
      MPI_Barrier(comm);
      // the preload's nodal contact pressure at the pad nodes [Pa]
      std::vector<std::pair<dealii::Point<3>, double>> preload_pressure;
      if (prm.scene.analysis == "preloaded cea")
        {
          // The preload at the file's nominal parameters, written into
          // preload/; the interface of the CEA then lives where the pad
          // stayed in contact (nearest pad node's status).
          parameters::AllParameters pre = prm;
          pre.output.directory          = work_dir + "/preload";
          pre.output.overwrite          = true;
          contact::PreloadAnalysis preload(pre, handler, comm);
          preload.run();
          const contact::MortarOperators &op = preload.interface();
          std::vector<std::pair<dealii::Point<3>, double>> nodes;
          for (unsigned int j = 0; j < op.n_slave(); ++j)
            {
              nodes.emplace_back(op.slave_points[j],
                                 preload.solution().status[j] != 0 ? 1. : 0.);
              preload_pressure.emplace_back(
                op.slave_points[j], preload.solution().nodal_pressure[j]);
            }
          model->interface_mask = [nodes](const dealii::Point<3> &x) {
            double best = 1e300, value = 0.;
            for (const auto &[p, v] : nodes)
              if (p.distance(x) < best)
                {
                  best  = p.distance(x);
                  value = v;
                }
            return value;
          };
        }
      model->setup_and_assemble(pcout);
      if (prm.mesh.contact_refinements > 0)
        {
          std::ostringstream csv;
          csv << "cycle,body,x,y,z,pressure_variation_Pa,refined\n";
          for (unsigned int c = 0; c < prm.mesh.contact_refinements; ++c)
            if (refine_by_contact_pressure(*model, preload_pressure,
                                           prm.mesh.contact_refinement_fraction,
                                           c, csv, pcout) == 0)
              break;
          if (Utilities::MPI::this_mpi_process(comm) == 0)
            std::ofstream(work_dir + "/contact_refinement.csv") << csv.str();
          pcout << "Mesh after the contact refinement: "
                << model->triangulation.n_active_cells() << " cells, "
                << model->n_dofs() << " DoFs" << std::endl;
        }
      adapt_mesh();
    }

    std::vector<parameters::ScalarPoint>
    ComplexEigenvalueAnalysis::basis_samples() const
    {
      const unsigned int n = prm.eigensolver.reduced_samples;
      std::vector<parameters::ScalarPoint> samples{prm.sweep_points()[0]};
      for (const auto *axis : {&prm.sweep.first, &prm.sweep.second})
        {
          if (!parameters::sweepable_parameter(axis->parameter).structural)
            continue;
          const auto [lo, hi] =
            std::minmax_element(axis->values.begin(), axis->values.end());
          const bool log = axis->log_scale();
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
          const auto &info = parameters::sweepable_parameter(axis->parameter);
          s << (axis == &prm.sweep.first ? "" : ", ") << info.symbol << " = "
            << p.get(axis->parameter);
          if (info.unit[0])
            s << ' ' << info.unit;
        }
      return s.str();
    }

    void
    ComplexEigenvalueAnalysis::solve_sweep()
    {
      const auto &es = prm.eigensolver;
      eigen::BandOptions band{es.f_min, es.f_max, es.target_frequency,
                              es.tolerance, 40};
      const bool reduced_method = es.method == "reduced";
      if (reduced_method)
        {
          TimerOutput::Scope t(timer, "reduced basis");
          pcout << "Building the reduced basis" << std::endl;
          reduced.build(model->parts(), basis_samples(), band,
                        es.reduced_band_factor,
                        es.reduced_enrichment ? es.reduced_enrichment_depth : 0,
                        pcout);
        }

      const auto         sweep    = prm.sweep_points();
      const unsigned int n_points = sweep.size();
      pcout << "Sweep: " << prm.sweep.second.values.size() << " x "
            << prm.sweep.second.parameter << ", "
            << prm.sweep.first.values.size() << " x "
            << prm.sweep.first.parameter << " = " << n_points << " points, "
            << (reduced_method ? "reduced" : "full") << " solver, band "
            << es.f_min << "-" << es.f_max << " Hz" << std::endl;
      const auto start = std::chrono::steady_clock::now();
      const auto progress = [&](const unsigned int k, const auto &values,
                                const unsigned int n_modes) {
        const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                        start)
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
          for (unsigned int p = rank; p < n_points; p += size)
            {
              const auto pairs = reduced.solve(sweep[p], es.f_min, es.f_max);
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
          Point p;
          p.values = values;
          if (points.empty() && !first_point_full.empty())
            {
              p.full = first_point_full;
              pcout << "  full solver: the last adaptive cycle's solve of "
                       "this point, reused"
                    << std::endl;
            }
          else
            p.full = eigen::solve_full(model->parts(), values, band, pcout);
          // 1.5 f_max holds about 1.7 times the modes of the band
          band.initial_nev =
            std::max<unsigned int>(40, 1.9 * p.full.size() + 10);
          for (const auto &r : p.full)
            {
              p.lambda.push_back(r.lambda);
              p.residual.push_back(r.residual);
            }
          points.push_back(std::move(p));
          progress(points.size(), values, points.back().lambda.size());
        }
    }

    void
    ComplexEigenvalueAnalysis::check_against_full()
    {
      const auto &es = prm.eigensolver;
      if (es.method != "reduced" || es.n_check_points == 0 || points.empty())
        return;
      TimerOutput::Scope t(timer, "check against full");
      // The most unstable point, then evenly spaced ones.
      std::vector<unsigned int> chosen;
      unsigned int              worst = 0;
      double                    max_re = -1e300;
      for (unsigned int p = 0; p < points.size(); ++p)
        for (const auto &l : points[p].lambda)
          if (l.real() > max_re)
            {
              max_re = l.real();
              worst  = p;
            }
      chosen.push_back(worst);
      for (unsigned int k = 0; chosen.size() < std::min<std::size_t>(es.n_check_points, points.size()); ++k)
        {
          const unsigned int p =
            (k * (points.size() - 1)) / std::max(1u, es.n_check_points - 1);
          if (std::find(chosen.begin(), chosen.end(), p) == chosen.end())
            chosen.push_back(p);
          if (k > points.size())
            break;
        }
      pcout << "Checking the reduced solver against the full solver at "
            << chosen.size() << " points" << std::endl;
      // about as many modes up to 1.5 f_max as each basis sample had
      eigen::BandOptions band{es.f_min, es.f_max, es.target_frequency,
                              es.tolerance,
                              std::max(40u, 5 * reduced.sample_mode_count() / 4 + 10)};
      double max_df = 0, max_dre = 0;
      unsigned int missed = 0;
      for (const unsigned int p : chosen)
        {
          const bool reuse = p == 0 && !first_point_full.empty();
          if (reuse)
            pcout << "  point 0: the last adaptive cycle's full solve, reused"
                  << std::endl;
          const auto full =
            reuse ? first_point_full :
                    eigen::solve_full(model->parts(), points[p].values, band,
                                      pcout);
          // Every full eigenvalue must have a reduced counterpart.
          for (const auto &f : full)
            {
              double best = 1e300;
              std::complex<double> match;
              for (const auto &r : points[p].lambda)
                if (std::abs(r - f.lambda) < best)
                  {
                    best  = std::abs(r - f.lambda);
                    match = r;
                  }
              const double df = std::abs(match.imag() - f.lambda.imag()) /
                                f.lambda.imag();
              const double dre = std::abs(match.real() - f.lambda.real()) /
                                 (std::abs(f.lambda.real()) + 1.);
              if (df > 1e-2)
                ++missed;
              max_df  = std::max(max_df, df);
              max_dre = std::max(max_dre, dre);
              std::ostringstream row;
              row << std::setprecision(12) << p << ','
                  << points[p].values.mu << ',' << points[p].values.E_pad
                  << ',' << f.lambda.real() << ','
                  << f.lambda.imag() / (2 * M_PI) << ',' << match.real()
                  << ',' << match.imag() / (2 * M_PI) << ',' << df << ','
                  << dre;
              check_rows.push_back(row.str());
            }
          if (full.size() != points[p].lambda.size())
            pcout << "  point " << p << ": full solver " << full.size()
                  << " modes in the band, reduced " << points[p].lambda.size()
                  << " (modes at the band edges may differ)" << std::endl;
        }
      pcout << "Reduced against full: largest frequency error "
            << 100 * max_df << " %, largest growth-rate error " << 100 * max_dre
            << " % of |Re| + 1 1/s";
      if (missed > 0)
        pcout << "; WARNING: " << missed
              << " full eigenvalues without a reduced one within 1 %";
      pcout << std::endl;
    }

    void
    ComplexEigenvalueAnalysis::classify()
    {
      TimerOutput::Scope t(timer, "tracking and classification");
      const double tol = prm.eigensolver.unstable_tolerance;
      int next_id = 0;
      unsigned int first = 0;
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
                      if (!a.q.empty())
                        mac(i, j) = eigen::ReducedModel::mac(a.q[i], b.q[j]);
                      else
                        {
                          const auto &x = a.full[i], &y = b.full[j];
                          const double rr = x.re * y.re + x.im * y.im,
                                       ri = x.re * y.im - x.im * y.re;
                          const double nx = x.re.norm_sqr() + x.im.norm_sqr(),
                                       ny = y.re.norm_sqr() + y.im.norm_sqr();
                          mac(i, j) = (rr * rr + ri * ri) / (nx * ny);
                        }
                }
              macs.push_back(mac);
            }
          const auto tracks = eigen::track_modes(lambdas, macs, next_id);
          for (unsigned int p = first; p <= last; ++p)
            for (unsigned int m = 0; m < points[p].lambda.size(); ++m)
              {
                const auto l = points[p].lambda[m];
                modes.push_back({p, points[p].values, m, l,
                                 points[p].residual[m], l.real() > tol,
                                 tracks[p - first][m]});
              }
          const auto r = eigen::find_unstable_regions(second(first), x, index,
                                                      lambdas, tracks, tol);
          regions.insert(regions.end(), r.begin(), r.end());
          first = last + 1;
        }

      pcout << "\nUnstable regions (Re lambda > " << tol << " 1/s):" << std::endl;
      if (regions.empty())
        pcout << "  none: every eigenvalue in the band is stable" << std::endl;
      const auto &first_info =
        parameters::sweepable_parameter(prm.sweep.first.parameter);
      const auto &second_info =
        parameters::sweepable_parameter(prm.sweep.second.parameter);
      for (const auto &r : regions)
        {
          std::ostringstream log10;
          if (prm.sweep.first.log_scale())
            log10 << std::setprecision(4) << " (log10 " << std::log10(r.first_min)
                  << " - " << std::log10(r.first_max) << ")";
          pcout << "  " << second_info.symbol << " = " << r.second << ": "
              << first_info.symbol << " " << std::setprecision(4)
              << r.first_min << " - " << r.first_max << ' ' << first_info.unit
              << log10.str()
              << ", " << std::setprecision(5) << r.f_min << " - " << r.f_max
              << " Hz, max Re lambda " << r.max_re << " 1/s, track " << r.track
              << (r.partner_track >= 0 ?
                    " locked in with track " + std::to_string(r.partner_track) :
                    std::string())
              << std::setprecision(6) << std::endl;
        }
    }

    // Where the discretisation error of the modes sits (issue 6's first
    // step): Kelly's estimator (the jump of the normal stress-like gradient
    // across faces; Kelly, Gago, Zienkiewicz & Babuska, IJNME 19, 1983) on
    // the real and imaginary parts of every mode of the first sweep point,
    // each mode scaled to unit kinetic norm (re^T M re + im^T M im = 1), the
    // squares summed with weight 2 for unstable and 1 for stable modes. The
    // cell values go to mesh_error.vtu; their share per body is printed and
    // written to mesh_error.csv.
    Vector<double>
    ComplexEigenvalueAnalysis::mode_indicator(
      const std::vector<eigen::EigenPair> &pairs,
      const parameters::ScalarPoint       &values,
      const std::vector<double>           &weights) const
    {
      const unsigned int n_cells = model->triangulation.n_active_cells();
      Vector<double>     sum(n_cells);
      physics::PETScVector ghosted(model->locally_owned_dofs,
                                   model->locally_relevant_dofs, comm);
      // the whole mass of the point: every mass part at its coefficient
      physics::PETScMatrix M;
      model->parts().mass(values, M);
      for (const auto &pair : pairs)
        {
          physics::PETScVector re = pair.re, im = pair.im, Mx(pair.re);
          M.vmult(Mx, re);
          double norm2 = re * Mx;
          M.vmult(Mx, im);
          norm2 += im * Mx;
          if (!(norm2 > 0.))
            continue;
          const double weight = (pair.lambda.real() > 0. ? 2. : 1.) / norm2;
          Vector<double> mode(n_cells);
          for (physics::PETScVector *x : {&re, &im})
            {
              model->constraints.distribute(*x);
              ghosted = *x;
              Vector<float> eta(n_cells);
              KellyErrorEstimator<3>::estimate(
                model->mapping, model->dof_handler,
                QGauss<2>(model->fe.degree + 1), {}, ghosted, eta);
              for (unsigned int c = 0; c < n_cells; ++c)
                mode[c] += weight * double(eta[c]) * double(eta[c]);
            }
          if (!weights.empty())
            {
              // where this mode's error sits (unit sum over all cells), times
              // the square of its estimated error
              Utilities::MPI::sum(mode, comm, mode);
              const double total = mode.l1_norm();
              if (total > 0.)
                mode *= std::pow(weights[&pair - pairs.data()], 2) / total;
              if (Utilities::MPI::this_mpi_process(comm) != 0)
                mode = 0.; // summed over the ranks below
            }
          sum += mode;
        }
      // each rank estimated its own cells
      Utilities::MPI::sum(sum, comm, sum);
      return sum;
    }

    // Where the discretisation error of the modes sits: Kelly's estimator
    // (the jump of the gradient across faces; Kelly, Gago, Zienkiewicz &
    // Babuska, IJNME 19, 1983) on the real and imaginary parts of every mode
    // of the first sweep point, each mode scaled to unit kinetic norm
    // (re^T M re + im^T M im = 1), the squares summed with weight 2 for
    // unstable and 1 for stable modes. The cell values go to mesh_error.vtu;
    // their share per body is printed and written to mesh_error.csv.
    void
    ComplexEigenvalueAnalysis::write_error_indicator() const
    {
      const auto &pt = points.empty() ? nullptr : &points[0];
      if (pt == nullptr || pt->lambda.empty())
        return;
      TimerOutput::Scope t(timer, "error indicator");
      std::vector<eigen::EigenPair> pairs;
      if (!pt->q.empty())
        for (unsigned int k = 0; k < pt->lambda.size(); ++k)
          {
            pairs.emplace_back();
            pairs.back().lambda = pt->lambda[k];
            reduced.expand(pt->q[k], pairs.back().re, pairs.back().im);
          }
      const Vector<double> sum =
        mode_indicator(pt->q.empty() ? pt->full : pairs, pt->values);
      const unsigned int n_cells = model->triangulation.n_active_cells();
      // per body of the scene: squared indicator and cells
      const auto &bodies = model->scene->bodies;
      std::map<types::material_id, std::pair<double, unsigned int>> by_body;
      Vector<float> indicator(n_cells), body(n_cells);
      double        total = 0.;
      for (const auto &cell : model->triangulation.active_cell_iterators())
        {
          const unsigned int c = cell->active_cell_index();
          indicator[c]         = std::sqrt(sum[c]);
          body[c]              = cell->material_id();
          by_body[cell->material_id()].first += sum[c];
          ++by_body[cell->material_id()].second;
          total += sum[c];
        }
      pcout << "Error indicator (Kelly, " << pt->lambda.size()
            << " modes of the first point; mesh_error.vtu):"
            << std::setprecision(3);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        pcout << (b == 0 ? " " : ", ") << bodies[b].name << " "
              << 100. * by_body[bodies[b].id].first / total << " %";
      pcout << " of the squared sum" << std::setprecision(6) << std::endl;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          std::ofstream csv(work_dir + "/mesh_error.csv");
          csv << "body,cells,share_of_squared_indicator\n";
          for (const scene::Body &b : bodies)
            csv << b.name << ',' << by_body[b.id].second << ','
                << by_body[b.id].first / total << '\n';
        }
      DataOut<3> data_out;
      data_out.attach_triangulation(model->triangulation);
      data_out.add_data_vector(indicator, "error_indicator");
      data_out.add_data_vector(body, "body");
      data_out.build_patches();
      data_out.write_vtu_in_parallel(work_dir + "/mesh_error.vtu", comm);
    }

    namespace
    {
      // Every mode shape of PAIRS as one complex vector of all n_dofs
      // values on every rank, hanging-node values filled in (the solver
      // leaves constrained entries at zero).
      std::vector<std::vector<std::complex<double>>>
      full_shapes(const physics::StructuralModel       &model,
                  const std::vector<eigen::EigenPair> &pairs)
      {
        std::vector<std::vector<std::complex<double>>> shapes;
        for (const auto &pr : pairs)
          {
            physics::PETScVector r = pr.re, i = pr.im;
            model.constraints.distribute(r);
            model.constraints.distribute(i);
            const Vector<double> re(r), im(i);
            std::vector<std::complex<double>> x(re.size());
            for (unsigned int k = 0; k < re.size(); ++k)
              x[k] = {re[k], im[k]};
            shapes.push_back(std::move(x));
          }
        return shapes;
      }

      double
      frequency(const std::complex<double> lambda)
      {
        return lambda.imag() / (2. * numbers::PI);
      }

      // The partner of each mode in a richer discretisation of the same
      // mesh and the relative eigenvalue difference |lambda - lambda_rich| /
      // |lambda_rich| to it (it bounds the relative frequency difference and
      // holds the growth rate to the same fraction of |lambda|, so a pair
      // that locks in on one discretisation and not on the other counts):
      // the shapes of the coarse modes carried to the rich model's support
      // points (physics::transfer_field), the complex MAC with every rich
      // mode, and among the rich modes within 80 % of the best MAC the one
      // nearest in the complex plane (the two members of a doublet share a
      // subspace, and near a lock-in the two shapes of the pair become
      // parallel: shape alone cannot tell them apart). A mode whose best
      // MAC is below 0.3 has no partner: difference 1 (100 %).
      struct Partner
      {
        int                  index = -1;
        std::complex<double> lambda;
        double               difference = 1.;
      };

      std::vector<Partner>
      partners_in(const std::vector<eigen::EigenPair>             &coarse_pairs,
                  const std::vector<std::vector<std::complex<double>>> &carried,
                  const physics::StructuralModel                  &rich,
                  const std::vector<eigen::EigenPair>             &rich_pairs)
      {
        const auto rich_shapes = full_shapes(rich, rich_pairs);
        std::vector<Partner> result(coarse_pairs.size());
        for (unsigned int k = 0; k < coarse_pairs.size(); ++k)
          {
            const auto         &a = carried[k];
            std::vector<double> mac(rich_pairs.size(), 0.);
            double              aa = 0.;
            for (const auto &v : a)
              aa += std::norm(v);
            for (unsigned int j = 0; j < rich_pairs.size(); ++j)
              {
                std::complex<double> ab = 0.;
                double               bb = 0.;
                for (unsigned int i = 0; i < a.size(); ++i)
                  {
                    ab += std::conj(rich_shapes[j][i]) * a[i];
                    bb += std::norm(rich_shapes[j][i]);
                  }
                mac[j] = aa > 0. && bb > 0. ? std::norm(ab) / (aa * bb) : 0.;
              }
            const double best =
              mac.empty() ? 0. : *std::max_element(mac.begin(), mac.end());
            if (best < 0.3)
              continue;
            for (unsigned int j = 0; j < rich_pairs.size(); ++j)
              if (mac[j] >= 0.8 * best)
                {
                  const auto  &lj = rich_pairs[j].lambda;
                  const double d  = std::abs(coarse_pairs[k].lambda - lj) / std::abs(lj);
                  if (result[k].index < 0 || d < result[k].difference)
                    result[k] = {int(j), rich_pairs[j].lambda, d};
                }
          }
        return result;
      }

      // Modes closer to each other than their discretisation errors share
      // their estimates: mode k takes the largest estimate of every
      // partnered mode j with |lambda_k - lambda_j| / |lambda_k| below
      // three times the larger of the two raw shifts |lambda - lambda_rich|
      // / |lambda_rich| (the estimates / 1.5). Two modes coupled by the
      // friction (or a doublet split by the pad) mix with weights set by
      // their separation; where a correction of that size can move one of
      // them, the richer space can change the mixing, and the error of the
      // less resolved member passes to the other. Measured on the coarse
      // TriboBrake with its springs (25 GPa, mu = 0.5,
      // end_to_end/adaptive_tolerance_springs): a mode at 4234.9 Hz moved
      // 0.5 Hz from degree 2 to 3 and 8.8 Hz at degree 4, while its
      // neighbour 63.5 Hz above moved 38 Hz at degree 3 (separation 1.7 x
      // its shift): its own estimate was 9.8 x under its true error. A
      // shared estimate only raises estimates, so it cannot make a mesh
      // pass that did not; modes without a partner (estimate 100 %) give
      // nothing, their shift being unknown.
      // Returns the number of estimates raised.
      unsigned int
      share_within_clusters(const std::vector<eigen::EigenPair> &pairs,
                            std::vector<Partner>                &estimate)
      {
        std::vector<double> own(estimate.size());
        for (unsigned int k = 0; k < estimate.size(); ++k)
          own[k] = estimate[k].difference;
        for (unsigned int k = 0; k < estimate.size(); ++k)
          for (unsigned int j = 0; j < estimate.size(); ++j)
            if (j != k && estimate[j].index >= 0 && estimate[k].index >= 0)
              {
                const double separation =
                  std::abs(pairs[k].lambda - pairs[j].lambda) /
                  std::abs(pairs[k].lambda);
                if (separation < 3. * std::max(own[k], own[j]) / 1.5)
                  estimate[k].difference =
                    std::max(estimate[k].difference, own[j]);
              }
        unsigned int n_raised = 0;
        for (unsigned int k = 0; k < estimate.size(); ++k)
          n_raised += estimate[k].difference > own[k];
        return n_raised;
      }

      // The partners of PAIRS (on MODEL's mesh) in the same mesh at the
      // degree + EXTRA: that model built (the refinement replayed), solved
      // at P in BAND by the full solver, or PROJECTED (below); its DoF count
      // goes to N_DOFS.
      std::vector<Partner>
      partners_at_degree(const parameters::AllParameters &prm,
                         const physics::StructuralModel  &model,
                         const std::vector<eigen::EigenPair> &pairs,
                         const std::vector<std::vector<std::complex<double>>> &shapes,
                         const unsigned int                 extra,
                         const parameters::ScalarPoint     &p,
                         const eigen::BandOptions          &band,
                         const bool                         projected,
                         types::global_dof_index           &n_dofs)
      {
        ConditionalOStream        quiet(std::cout, false);
        parameters::AllParameters prm_rich = prm;
        prm_rich.mesh.fe_degree += extra;
        physics::StructuralModel rich(prm_rich, model.comm);
        rich.interface_mask = model.interface_mask;
        rich.setup_and_assemble(quiet);
        rich.replay_refinement(model.refinement_history, quiet);
        n_dofs = rich.n_dofs();
        // the coarse shapes at the rich model's support points
        std::vector<std::vector<std::complex<double>>> carried;
        for (const auto &x : shapes)
          carried.push_back(physics::transfer_field(model, x, rich));
        if (!projected)
          return partners_in(pairs, carried, rich,
                             eigen::solve_full(rich.parts(), p, band, quiet));

        // Projected: the richer model's eigenvalues by Rayleigh-Ritz on
        // the span of the degree-p modes carried to it and three steps of
        // block shift-and-invert iteration from each, (A_i^-1 M)^l phi for
        // l = 1..3, A_i = K_s(p) - (2 pi f_i)^2 M with f_i the shift nearest
        // (on a log scale) to the mode: shifts at the geometric centres of
        // sub-bands at most an octave wide. The degree-p modes span
        // exactly the degree-p eigenvalues (the spaces are nested); the
        // iterations add the richer space's correction, fastest near the
        // shift. One factorisation per octave instead of the full
        // solver's shifted Krylov-Schur. The Ritz values of a subspace lie
        // short of the degree + 1 eigenvalues, so this estimate can only
        // fall below the full one (benchmarks/speed_vs_error measures by
        // how much).
        const auto  &parts = rich.parts();
        physics::PETScMatrix M;
        parts.mass(p, M);
        const double f_lo = std::max(band.f_min, 1.), f_hi = band.f_max;
        const unsigned int n_shifts =
          std::max(1, int(std::ceil(std::log2(f_hi / f_lo) - 1e-9)));
        const double ratio = std::pow(f_hi / f_lo, 1. / n_shifts);
        const IndexSet &owned = rich.locally_owned_dofs;
        std::vector<physics::PETScVector> vectors;
        for (unsigned int i = 0; i < n_shifts; ++i)
          {
            const double f_lower = f_lo * std::pow(ratio, i),
                         f_shift = f_lower * std::sqrt(ratio);
            std::vector<unsigned int> modes;
            for (unsigned int k = 0; k < pairs.size(); ++k)
              {
                const double f = std::abs(frequency(pairs[k].lambda));
                if ((f >= f_lower || i == 0) &&
                    (f < f_lower * ratio || i + 1 == n_shifts))
                  modes.push_back(k);
              }
            if (modes.empty())
              continue;
            physics::PETScMatrix A;
            parts.symmetric_stiffness(p, A);
            const double w = 2. * numbers::PI * f_shift;
            A.add(-w * w, M);
            const eigen::DirectSolver solver(A);
            for (const unsigned int k : modes)
              {
                for (const bool imaginary : {false, true})
                  {
                    physics::PETScVector v(owned, rich.comm),
                      f(owned, rich.comm), y(owned, rich.comm);
                    for (const auto j : owned)
                      if (!rich.constraints.is_constrained(j))
                        v(j) = imaginary ? carried[k][j].imag() :
                                           carried[k][j].real();
                    v.compress(VectorOperation::insert);
                    if (v.l2_norm() == 0.)
                      continue;
                    vectors.push_back(v);
                    for (unsigned int level = 0; level < 3; ++level)
                      {
                        M.vmult(f, v);
                        solver.solve(f, y);
                        y /= y.l2_norm();
                        vectors.push_back(y);
                        v = y;
                      }
                  }
              }
          }
        eigen::ReducedModel reduced;
        reduced.build_from_vectors(parts, vectors, false);
        std::vector<eigen::EigenPair> rich_pairs;
        for (const auto &r : reduced.solve(p, band.f_min, band.f_max))
          {
            eigen::EigenPair e{r.lambda, physics::PETScVector(owned, rich.comm),
                               physics::PETScVector(owned, rich.comm), -1.};
            reduced.expand(r.q, e.re, e.im);
            rich_pairs.push_back(std::move(e));
          }
        return partners_in(pairs, carried, rich, rich_pairs);
      }
    } // namespace

    // Adaptive refinement before the sweep (Mesh/Adaptive cycles, and
    // Mesh/Frequency tolerance): the first sweep point by the full solver
    // on each mesh, the relative change of each mode's frequency from the
    // previous mesh (the same mode found by its shape) printed and written
    // to adaptive_cycles.csv, then Kelly's indicator on the modes marks
    // Mesh/Refinement fraction of the cells. The change between meshes is
    // not an error estimate: near a lock-in (an exceptional point, where
    // frequencies move like the square root of a perturbation) it
    // under-stated the error 30x (benchmarks/speed_vs_error). With a
    // tolerance, each mode's error is estimated instead by the same mesh
    // at degree + 1 (a hierarchical estimate: the difference to a richer
    // space of the same mesh, which sees every body at once, unlike the
    // change between two local refinements), the cycles stop when every
    // estimate in the band is below the tolerance, and only the modes above
    // it drive the refinement.
    void
    ComplexEigenvalueAnalysis::adapt_mesh()
    {
      const auto &m            = prm.mesh;
      const bool  by_tolerance = m.frequency_tolerance > 0.;
      if (m.adaptive_cycles == 0 && !by_tolerance)
        return;
      TimerOutput::Scope t(timer, "adaptive refinement");
      const auto &es = prm.eigensolver;
      eigen::BandOptions band{es.f_min, es.f_max, es.target_frequency,
                              es.tolerance, 40};
      // the richer models solve a wider band, so that a partner that moved
      // across a band edge is still found
      eigen::BandOptions wide = band;
      wide.f_min *= 0.95;
      wide.f_max *= 1.05;
      const auto in_band = [&](const double f) {
        return f > 1.02 * es.f_min && f < 0.98 * es.f_max;
      };
      const parameters::ScalarPoint p0 = prm.sweep_points().front();
      std::vector<double> f_prev;
      std::vector<std::vector<std::complex<double>>> prev_shapes;
      std::vector<dealii::Point<3>> prev_points;
      std::vector<unsigned int> prev_component;
      std::ostringstream  table, per_mode;
      table << "cycle,cells,dofs,seconds,modes,max_relative_change,"
               "median_relative_change,frequency_of_max_change_Hz,"
               "modes_unmatched,estimate_dofs,estimate_seconds,"
               "max_estimated_error,frequency_of_max_estimate_Hz,"
               "modes_above_tolerance,degree\n";
      per_mode << "cycle,freq_Hz,re_per_s,estimated_relative_error,"
                  "estimate_partner_freq_Hz,estimate_partner_re_per_s,"
                  "check_freq_Hz,check_re_per_s,check_relative_error\n";
      ConditionalOStream quiet(std::cout, false);
      // the last h-refinement step: DoFs before and after, the largest
      // estimate before
      struct
      {
        types::global_dof_index dofs_before = 0;
        double                  estimate_before = 0.;
        types::global_dof_index dofs_after = 0;
      } h_step;
      std::vector<eigen::EigenPair>                  pairs;
      std::vector<std::vector<std::complex<double>>> shapes;
      std::vector<Partner>                           estimate;
      unsigned int                                   cycle = 0;
      bool                                           reached = false;
      for (;; ++cycle)
        {
          const auto t0    = std::chrono::steady_clock::now();
          pairs = eigen::solve_full(model->parts(), p0, band, quiet);
          const double seconds = std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - t0)
                                   .count();
          std::vector<double> f, e;
          for (const auto &pr : pairs)
            f.push_back(frequency(pr.lambda));
          // The same mode on the previous mesh: the refined mesh keeps the
          // old support points, so the old mode shapes are compared with the
          // new ones there (complex MAC); a new mode's partner is the old one
          // of largest MAC, if that exceeds 0.4 (a member of a doublet, whose
          // two shapes mix between meshes, has MAC ~0.5 with each old one;
          // its partner is then either, and the change includes the split
          // of the pair).
          shapes = full_shapes(*model, pairs);
          double       f_worst     = 0.;
          unsigned int n_unmatched = 0;
          // this mesh's support points: the new side of the comparison now,
          // the old side after the refinement
          auto [points, component] = physics::dof_support_points(*model);
          if (!f_prev.empty())
            {
              std::map<std::array<long long, 4>, unsigned int> new_index;
              const auto key = [](const dealii::Point<3> &x, const unsigned int c) {
                return std::array<long long, 4>{{std::llround(x[0] * 1e9),
                                                 std::llround(x[1] * 1e9),
                                                 std::llround(x[2] * 1e9), c}};
              };
              for (unsigned int i = 0; i < points.size(); ++i)
                new_index[key(points[i], component[i])] = i;
              std::vector<std::pair<unsigned int, unsigned int>> common;
              for (unsigned int i = 0; i < prev_points.size(); ++i)
                {
                  const auto it =
                    new_index.find(key(prev_points[i], prev_component[i]));
                  if (it != new_index.end())
                    common.emplace_back(i, it->second);
                }
              FullMatrix<double> mac(f.size(), f_prev.size());
              for (unsigned int k = 0; k < f.size(); ++k)
                for (unsigned int j = 0; j < f_prev.size(); ++j)
                  {
                    std::complex<double> ab = 0.;
                    double               aa = 0., bb = 0.;
                    for (const auto &[io, in] : common)
                      {
                        const auto &a = shapes[k][in];
                        const auto &b = prev_shapes[j][io];
                        ab += std::conj(b) * a;
                        aa += std::norm(a);
                        bb += std::norm(b);
                      }
                    mac(k, j) = aa > 0. && bb > 0. ? std::norm(ab) / (aa * bb) : 0.;
                  }
              const auto best_in_row = [&](const unsigned int k) {
                unsigned int b = 0;
                for (unsigned int j = 1; j < f_prev.size(); ++j)
                  if (mac(k, j) > mac(k, b))
                    b = j;
                return b;
              };
              for (unsigned int k = 0; k < f.size(); ++k)
                {
                  const unsigned int j = best_in_row(k);
                  if (mac(k, j) < 0.4)
                    {
                      ++n_unmatched;
                      continue;
                    }
                  if (in_band(f[k]))
                    {
                      e.push_back(std::abs(f[k] - f_prev[j]) / f[k]);
                      if (e.back() >= *std::max_element(e.begin(), e.end()))
                        f_worst = f[k];
                    }
                }
            }
          double e_max = -1., e_median = -1.;
          if (!e.empty())
            {
              std::sort(e.begin(), e.end());
              e_max    = e.back();
              e_median = e[e.size() / 2];
            }
          pcout << "Adaptive cycle " << cycle << ": "
                << model->triangulation.n_active_cells() << " cells, "
                << model->n_dofs() << " DoFs, " << f.size()
                << " modes in the band, full solve " << std::setprecision(3)
                << seconds << " s";
          if (e_max >= 0.)
            pcout << ", change from the previous mesh: largest "
                  << 100. * e_max << " % (" << f_worst << " Hz), median "
                  << 100. * e_median << " %"
                  << (n_unmatched > 0 ? ", " + std::to_string(n_unmatched) +
                                          " modes without a partner" :
                                        std::string());
          pcout << std::setprecision(6) << std::endl;
          table << cycle << ',' << model->triangulation.n_active_cells() << ','
                << model->n_dofs() << ',' << seconds << ',' << f.size() << ','
                << e_max << ',' << e_median << ',' << f_worst << ','
                << n_unmatched;

          // the error estimate: the same mesh at degree + 1
          std::vector<bool>       above(pairs.size(), false);
          types::global_dof_index rich_dofs = 0;
          double                  worst     = 0.;
          if (by_tolerance)
            {
              const auto t1 = std::chrono::steady_clock::now();
              rich_dofs = 0;
              estimate = partners_at_degree(model->prm, *model, pairs, shapes, 1, p0,
                                            wide,
                                            m.estimate_solver == "projected",
                                            rich_dofs);
              // The difference to degree + 1 is the error of degree p minus
              // that of degree p + 1; where the latter is at most a third of
              // the former (0.1-0.34 measured on the clamped disc against
              // verification A3), the error is at most 1.5 x the difference.
              for (auto &pe : estimate)
                pe.difference = std::min(1., 1.5 * pe.difference);
              const unsigned int n_shared =
                share_within_clusters(pairs, estimate);
              const double t_est = std::chrono::duration<double>(
                                     std::chrono::steady_clock::now() - t1)
                                     .count();
              worst = 0.;
              double       f_at = 0.;
              unsigned int n_above = 0;
              for (unsigned int k = 0; k < pairs.size(); ++k)
                if (in_band(f[k]))
                  {
                    if (estimate[k].difference > worst)
                      {
                        worst = estimate[k].difference;
                        f_at  = f[k];
                      }
                    above[k] = estimate[k].difference > m.frequency_tolerance;
                    n_above += above[k];
                  }
              pcout << "  estimated error (degree " << model->fe.degree + 1
                    << ", " << rich_dofs << " DoFs, "
                    << std::setprecision(3) << t_est << " s): largest "
                    << 100. * worst << " % (" << f_at << " Hz), " << n_above
                    << " modes above the tolerance "
                    << 100. * m.frequency_tolerance << " %";
              if (n_shared > 0)
                pcout << " (" << n_shared
                      << " modes take a closer neighbour's larger estimate)";
              pcout << std::setprecision(6) << std::endl;
              table << ',' << rich_dofs << ',' << t_est << ',' << worst
                    << ',' << f_at << ',' << n_above;
              reached = n_above == 0;
            }
          else
            table << ",,,,,";
          table << ',' << model->fe.degree << '\n';
          if (reached || cycle == m.adaptive_cycles)
            break;
          // h or p (Mesh/Degree adaptivity): the largest estimate's decay
          // per DoF, rho = log(e_before / e_after) / log(N_after /
          // N_before), measured on the last h step, against the one
          // degree + 1 on the same mesh is predicted to give: a third of
          // the error (the assumption behind the factor 1.5) for the
          // estimate's own DoFs, log 3 / log(N_p+1 / N_p). The first step
          // is h, to measure it. The degree goes up to 3 (its estimate
          // solves degree 4; with Check estimate to 2).
          const unsigned int degree = model->fe.degree;
          if (by_tolerance && m.degree_adaptivity &&
              degree + 2 <= (m.check_estimate ? 3u : 4u) &&
              h_step.dofs_after == model->n_dofs() && h_step.dofs_before > 0)
            {
              const double rho_h =
                std::log(h_step.estimate_before / worst) /
                std::log(double(h_step.dofs_after) / h_step.dofs_before);
              const double rho_p =
                std::log(3.) / std::log(double(rich_dofs) / model->n_dofs());
              pcout << "  h or p: the last refinement reduced the largest "
                       "estimate at rate "
                    << std::setprecision(3) << rho_h
                    << " per log DoFs, degree " << degree + 1
                    << " is predicted at " << rho_p << std::setprecision(6);
              if (rho_p > rho_h)
                {
                  pcout << ": degree " << degree + 1 << " on the same mesh"
                        << std::endl;
                  auto raised = std::make_unique<parameters::AllParameters>(
                    model->prm);
                  raised->mesh.fe_degree = degree + 1;
                  auto rebuilt =
                    std::make_unique<physics::StructuralModel>(*raised, comm);
                  rebuilt->interface_mask = model->interface_mask;
                  rebuilt->setup_and_assemble(quiet);
                  rebuilt->replay_refinement(model->refinement_history, quiet);
                  f_prev         = f;
                  prev_shapes    = std::move(shapes);
                  prev_points    = std::move(points);
                  prev_component = std::move(component);
                  model          = std::move(rebuilt); // the old model first,
                  raised_prm     = std::move(raised);  // then its parameters
                  continue;
                }
              pcout << ": h-refinement" << std::endl;
            }
          h_step = {model->n_dofs(), worst, 0};
          // the modes that drive the refinement: those above the tolerance,
          // or all without one
          // (with a tolerance each mode's indicator is scaled to its
          // estimated error, so the refinement goes where the largest
          // errors are, whichever body carries them)
          std::vector<eigen::EigenPair> driving;
          std::vector<double>           weights;
          for (unsigned int k = 0; k < pairs.size(); ++k)
            if (!by_tolerance || above[k])
              {
                driving.push_back(pairs[k]);
                if (by_tolerance)
                  weights.push_back(estimate[k].difference);
              }
          const Vector<double> sum = mode_indicator(driving, p0, weights);
          Vector<float>        indicator(sum.size());
          for (unsigned int c = 0; c < sum.size(); ++c)
            indicator[c] = std::sqrt(sum[c]);
          f_prev = f;
          prev_shapes    = std::move(shapes); // reassigned by the next solve
          prev_points    = std::move(points);
          prev_component = std::move(component);
          model->refine(indicator, m.refinement_fraction,
                       m.marking == "error", quiet);
          h_step.dofs_after = model->n_dofs();
        }
      if (by_tolerance)
        {
          if (reached)
            pcout << "Frequency tolerance " << 100. * m.frequency_tolerance
                  << " % reached after " << cycle << " refinement cycles: "
                  << model->n_dofs() << " DoFs" << std::endl;
          else
            pcout << "Warning: Mesh/Frequency tolerance "
                  << 100. * m.frequency_tolerance
                  << " % not reached after Mesh/Adaptive cycles = " << cycle
                  << " refinements (adaptive_modes.csv lists the modes above "
                     "it); the sweep runs on the last mesh, "
                  << model->n_dofs() << " DoFs" << std::endl;
        }

      // the estimate checked against degree + 2 on the final mesh
      std::vector<Partner> check;
      if (m.check_estimate)
        {
          const auto t1 = std::chrono::steady_clock::now();
          types::global_dof_index check_dofs = 0;
          check = partners_at_degree(model->prm, *model, pairs, shapes, 2, p0, wide,
                                     false, check_dofs);
          double worst_ratio = 0.;
          for (unsigned int k = 0; k < pairs.size(); ++k)
            if (in_band(frequency(pairs[k].lambda)) && check[k].difference > 0.)
              worst_ratio = std::max(worst_ratio, check[k].difference /
                                                    estimate[k].difference);
          pcout << "Check of the estimate (degree " << model->fe.degree + 2
                << ", " << check_dofs << " DoFs, " << std::setprecision(3)
                << std::chrono::duration<double>(
                     std::chrono::steady_clock::now() - t1)
                     .count()
                << " s): largest error / estimate " << worst_ratio
                << std::setprecision(6) << " (adaptive_modes.csv)" << std::endl;
        }
      if (by_tolerance)
        for (unsigned int k = 0; k < pairs.size(); ++k)
          {
            per_mode << cycle << ',' << std::setprecision(10)
                     << frequency(pairs[k].lambda) << ','
                     << pairs[k].lambda.real() << ','
                     << estimate[k].difference << ',';
            if (estimate[k].index >= 0)
              per_mode << frequency(estimate[k].lambda) << ','
                       << estimate[k].lambda.real();
            else
              per_mode << ',';
            per_mode << ',';
            if (!check.empty() && check[k].index >= 0)
              per_mode << frequency(check[k].lambda) << ','
                       << check[k].lambda.real() << ',' << check[k].difference;
            else
              per_mode << ",,";
            per_mode << '\n';
          }
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          std::ofstream(work_dir + "/adaptive_cycles.csv") << table.str();
          if (by_tolerance)
            std::ofstream(work_dir + "/adaptive_modes.csv") << per_mode.str();
        }
      // the last cycle solved the sweep's first point on the final mesh
      first_point_full = std::move(pairs);
    }

    void
    ComplexEigenvalueAnalysis::write_mode(const physics::PETScVector &re,
                                          const physics::PETScVector &im,
                                          const std::string &         name) const
    {
      physics::PETScVector ghosted_re(model->locally_owned_dofs,
                                      model->locally_relevant_dofs, comm),
        ghosted_im(model->locally_owned_dofs, model->locally_relevant_dofs, comm);
      physics::PETScVector r = re, i = im;
      model->constraints.distribute(r);
      model->constraints.distribute(i);
      ghosted_re = r;
      ghosted_im = i;

      DataOut<3> data_out;
      data_out.attach_dof_handler(model->dof_handler);
      const std::vector<DataComponentInterpretation::DataComponentInterpretation>
        vector(3, DataComponentInterpretation::component_is_part_of_vector);
      data_out.add_data_vector(ghosted_re,
                               std::vector<std::string>(3, "mode_real"),
                               DataOut<3>::type_dof_data, vector);
      data_out.add_data_vector(ghosted_im,
                               std::vector<std::string>(3, "mode_imag"),
                               DataOut<3>::type_dof_data, vector);
      Vector<float> material(model->triangulation.n_active_cells());
      for (const auto &cell : model->triangulation.active_cell_iterators())
        material[cell->active_cell_index()] = cell->material_id();
      data_out.add_data_vector(material, "body");
      data_out.build_patches(model->mapping, model->fe.degree,
                             DataOut<3>::curved_inner_cells);
      data_out.write_vtu_with_pvtu_record(work_dir + "/modes/", name, 0, comm,
                                          0, 0);
    }

    namespace
    {
      // The name of a disc mode from the axial displacement of the disc's
      // top face: (s, n) with n the dominant angular harmonic on the outer
      // rim and s the sign changes along the radius through the rim's
      // largest amplitude; "+" when the pad (at theta = 0) sits on an
      // antinode, "-" on a node; "in-plane" when the axial motion is small
      // against the in-plane motion.
      std::string
      disc_mode_name(const physics::StructuralModel &model,
                     const scene::Body &             disc,
                     const physics::PETScVector &    re,
                     const physics::PETScVector &    im)
      {
        // (r, theta, u_axial_re, u_axial_im, |u_inplane|^2) at the owned
        // vertices of the disc's naming face, in the disc's frame
        std::vector<std::array<double, 5>> local;
        for (const auto &cell : model.dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() && cell->material_id() == disc.id)
            for (const auto f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() == disc.naming_face)
                for (const auto v : cell->face(f)->vertex_indices())
                  {
                    const Point<3> x = cell->face(f)->vertex(v);
                    std::array<types::global_dof_index, 3> d;
                    bool                                   owned = true;
                    for (unsigned int c = 0; c < 3; ++c)
                      {
                        d[c]  = cell->face(f)->vertex_dof_index(v, c);
                        owned = owned && model.locally_owned_dofs.is_element(d[c]);
                      }
                    if (!owned)
                      continue;
                    Tensor<1, 3> u_re, u_im;
                    for (unsigned int c = 0; c < 3; ++c)
                      {
                        u_re[c] = re(d[c]);
                        u_im[c] = im(d[c]);
                      }
                    const double a_re = u_re * disc.axis, a_im = u_im * disc.axis;
                    const double inplane =
                      (u_re - a_re * disc.axis).norm_square() +
                      (u_im - a_im * disc.axis).norm_square();
                    const auto [r, theta] = disc.polar(x);
                    local.push_back({{r, theta, a_re, a_im, inplane}});
                  }
        std::vector<std::array<double, 5>> all;
        for (const auto &part : Utilities::MPI::all_gather(model.comm, local))
          all.insert(all.end(), part.begin(), part.end());
        double axial = 0, inplane = 0;
        for (const auto &a : all)
          {
            axial += a[2] * a[2] + a[3] * a[3];
            inplane += a[4];
          }
        if (all.empty())
          return "";
        if (axial < 0.25 * inplane)
          return "in-plane";
        // rim: the vertices at the outer radius
        const double tol = 1e-6 * disc.outer_radius;
        std::vector<std::array<double, 5>> rim;
        for (const auto &a : all)
          if (std::abs(a[0] - disc.outer_radius) < tol)
            rim.push_back(a);
        unsigned int best_n = 0;
        double       best   = -1;
        for (unsigned int n = 0; n <= rim.size() / 4; ++n)
          {
            std::complex<double> cp = 0, cm = 0;
            for (const auto &a : rim)
              {
                const std::complex<double> w(a[2], a[3]);
                cp += w * std::exp(std::complex<double>(0, -double(n) * a[1]));
                cm += w * std::exp(std::complex<double>(0, double(n) * a[1]));
              }
            const double power = std::norm(cp) + (n > 0 ? std::norm(cm) : 0.);
            if (power > best * (1 + 1e-9))
              {
                best   = power;
                best_n = n;
              }
          }
        // the rim point of largest amplitude and its phase
        const auto peak = *std::max_element(
          rim.begin(), rim.end(), [](const auto &a, const auto &b) {
            return std::hypot(a[2], a[3]) < std::hypot(b[2], b[3]);
          });
        const std::complex<double> phase =
          std::conj(std::complex<double>(peak[2], peak[3])) /
          std::abs(std::complex<double>(peak[2], peak[3]));
        // nodal circles: sign changes along the radius at the peak's angle
        std::vector<std::pair<double, double>> line;
        for (const auto &a : all)
          if (std::abs(std::remainder(a[1] - peak[1], 2 * M_PI)) < 1e-6)
            line.emplace_back(a[0], (std::complex<double>(a[2], a[3]) * phase).real());
        std::sort(line.begin(), line.end());
        const double amax = std::abs(peak[2]) + std::abs(peak[3]);
        unsigned int circles = 0;
        double       last    = 0;
        for (const auto &[r, w] : line)
          if (std::abs(w) > 1e-3 * amax)
            {
              if (last != 0 && (w > 0) != (last > 0))
                ++circles;
              last = w;
            }
        std::string name = "(" + std::to_string(circles) + "," +
                           std::to_string(best_n);
        if (best_n > 0)
          {
            // amplitude at the pad (theta = 0) against a quarter wave away
            const auto amplitude = [&](const double theta) {
              double a = 0, d = 1e300;
              for (const auto &x : rim)
                {
                  const double dt = std::abs(std::remainder(x[1] - theta, 2 * M_PI));
                  if (dt < d)
                    {
                      d = dt;
                      a = std::hypot(x[2], x[3]);
                    }
                }
              return a;
            };
            name += amplitude(0.) >= amplitude(M_PI / (2 * best_n)) ? "+" : "-";
          }
        return name + ")";
      }
    } // namespace

    void
    ComplexEigenvalueAnalysis::output_results() const
    {
      TimerOutput::Scope t(timer, "output");
      const bool root = Utilities::MPI::this_mpi_process(comm) == 0;
      if (root)
        {
          std::ofstream csv(work_dir + "/eigenvalues.csv");
          // The contract's columns, then any swept parameter beyond mu and
          // the pad modulus.
          std::vector<std::string> extra;
          for (const auto *axis : {&prm.sweep.first, &prm.sweep.second})
            if (axis->parameter != "pad modulus" &&
                axis->parameter != "friction coefficient")
              extra.push_back(axis->parameter);
          csv << "point,mu,E_pad_Pa,mode,re_per_s,freq_Hz,zeta,unstable,track";
          for (const auto &e : extra)
            csv << ',' << parameters::column_name(e);
          csv << '\n' << std::setprecision(12);
          std::ofstream res(work_dir + "/eigenvalue_residuals.csv");
          res << "point,mode,relative_residual\n" << std::setprecision(6);
          for (const auto &m : modes)
            {
              csv << m.point << ',' << m.values.mu << ',' << m.values.E_pad
                  << ',' << m.mode << ',' << m.lambda.real() << ','
                  << m.lambda.imag() / (2 * M_PI) << ','
                  << -m.lambda.real() / std::abs(m.lambda) << ','
                  << (m.unstable ? 1 : 0) << ',' << m.track;
              for (const auto &e : extra)
                csv << ',' << m.values.get(e);
              csv << '\n';
              res << m.point << ',' << m.mode << ',' << m.residual << '\n';
            }
          std::ofstream axes(work_dir + "/sweep_axes.csv");
          axes << "axis,parameter,column,log\n";
          for (const auto *axis : {&prm.sweep.first, &prm.sweep.second})
            axes << (axis == &prm.sweep.first ? "first," : "second,")
                 << axis->parameter << ','
                 << parameters::column_name(axis->parameter) << ','
                 << (axis->log_scale() ? 1 : 0) << '\n';
          std::ofstream reg(work_dir + "/unstable_regions.csv");
          // mu,E_pad_min_Pa,E_pad_max_Pa,... for the default sweep
          const auto &f = prm.sweep.first.parameter;
          reg << parameters::column_name(prm.sweep.second.parameter) << ','
              << parameters::column_name(f, "_min") << ','
              << parameters::column_name(f, "_max")
              << ",freq_min_Hz,freq_max_Hz,max_re_per_s,track\n"
              << std::setprecision(12);
          for (const auto &r : regions)
            reg << r.second << ',' << r.first_min << ',' << r.first_max << ','
                << r.f_min
                << ',' << r.f_max << ',' << r.max_re << ',' << r.track << '\n';
          if (!check_rows.empty())
            {
              std::ofstream chk(work_dir + "/check_full.csv");
              chk << "point,mu,E_pad_Pa,full_re_per_s,full_freq_Hz,"
                     "reduced_re_per_s,reduced_freq_Hz,freq_rel_error,"
                     "re_error_per_abs_re_plus_1\n";
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
            const bool unstable_peak = std::any_of(
              regions.begin(), regions.end(), [&](const auto &r) {
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
      participation << ",name\n"
                    << std::setprecision(8);

      std::vector<std::pair<double, std::string>> records;
      for (const auto &[p, k] : chosen)
        {
          const auto &pt = points[p];
          physics::PETScVector re, im;
          if (!pt.q.empty())
            reduced.expand(pt.q[k], re, im);
          else if (!pt.full.empty())
            {
              re = pt.full[k].re;
              im = pt.full[k].im;
            }
          else
            continue;
          {
            // kinetic-energy shares with the whole mass of the point (every
            // body at its density)
            const std::vector<double> e =
              physics::kinetic_energy_by_body(*model, pt.values, re, im);
            const auto &bodies = model->scene->bodies;
            const auto  share  = [&](const scene::Body &b) {
              return b.id < e.size() ? e[b.id] : 0.;
            };
            double total = 0.;
            for (const scene::Body &b : bodies)
              total += share(b);
            participation << p << ',' << k << ','
                          << pt.lambda[k].imag() / (2 * M_PI) << ','
                          << pt.lambda[k].real();
            for (const scene::Body &b : bodies)
              participation << ',' << share(b) / total;
            // a disc carrying more than half the energy names the mode
            // (s,n+-); otherwise the body carrying most besides the disc
            const scene::Body *disc = model->scene->disc();
            std::string        mode_name;
            if (disc != nullptr && share(*disc) > 0.5 * total)
              mode_name = disc_mode_name(*model, *disc, re, im);
            else
              {
                double most = -1.;
                for (const scene::Body &b : bodies)
                  if (&b != disc && share(b) > most)
                    {
                      most      = share(b);
                      mode_name = b.name;
                    }
              }
            participation << ",\"" << mode_name << "\"\n";
          }
          std::ostringstream name;
          name << "mode_p" << p << "_m" << k << "_" << std::fixed
               << std::setprecision(1) << pt.lambda[k].imag() / (2 * M_PI)
               << "Hz_re" << std::setprecision(3) << pt.lambda[k].real();
          write_mode(re, im, name.str());
          records.emplace_back(records.size(), "modes/" + name.str() + ".pvtu");
        }
      write_error_indicator();
      if (root)
        {
          std::ofstream pvd(work_dir + "/modes.pvd");
          DataOutBase::write_pvd_record(pvd, records);
          std::ofstream(work_dir + "/mode_participation.csv")
            << participation.str();
        }
      MPI_Barrier(comm);
      if (root)
        output::publish_directory(work_dir, prm.output.directory);
      MPI_Barrier(comm);
      pcout << "Results written to " << prm.output.directory << "/" << std::endl;
    }

    void
    ComplexEigenvalueAnalysis::run()
    {
      pcout << "squeal: complex eigenvalue analysis ("
            << Utilities::MPI::n_mpi_processes(comm) << " MPI rank(s))"
            << std::endl;
      setup_system();
      solve_sweep();
      check_against_full();
      classify();
      output_results();
      timer.print_summary();
    }
  } // namespace cea
} // namespace squeal
