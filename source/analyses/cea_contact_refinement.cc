// The CEA's contact refinement (Mesh/Contact refinements): cells refined
// where the preload's contact pressure varies most.

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_refinement.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/error_estimator.h>

#include <squeal/analyses/cea.h>
#include <squeal/contact/scene_contact.h>
#include <squeal/eigen/mac.h>
#include <squeal/io/output_directory.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;

    namespace
    {
      // The preload's nodal contact pressure on a tensor grid of the pad
      // face's plane coordinates (the preload runs on the unrefined mesh),
      // bilinear between the nodes.
      struct NodalPressure
      {
        static constexpr double eps = 1e-9; ///< m, coordinate tolerance

        /// @throws std::runtime_error if @p nodes do not form a tensor grid
        explicit NodalPressure(
          const std::vector<std::pair<Point<2>, double>> &nodes)
          : xs(unique_sorted(nodes, 0))
          , ys(unique_sorted(nodes, 1))
          , grid(xs.size() * ys.size(), 0.)
        {
          std::vector<bool> seen(grid.size(), false);
          for (const auto &[x, p] : nodes)
            if (xs.size() > 1 && ys.size() > 1)
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
              "Mesh/Contact refinements: the preload's pad nodes do not form "
              "a tensor grid over the pad face (" +
              std::to_string(nodes.size()) + " nodes, " +
              std::to_string(xs.size()) + " x " + std::to_string(ys.size()) +
              " coordinates)");
        }

        /// the bilinear pressure [Pa] at @p x (clamped to the grid)
        double
        operator()(const Point<2> &x) const
        {
          const auto [i, t] = locate(xs, x[0]);
          const auto [j, u] = locate(ys, x[1]);
          const auto g      = [&](unsigned int a, unsigned int b) {
            return grid[a * ys.size() + b];
          };
          return (1 - t) * (1 - u) * g(i, j) + t * (1 - u) * g(i + 1, j) +
                 (1 - t) * u * g(i, j + 1) + t * u * g(i + 1, j + 1);
        }

        std::vector<double> xs, ys; ///< the grid's coordinates [m]
        std::vector<double> grid;   ///< pressure [Pa] at (xs[i], ys[j])

      private:
        static std::vector<double>
        unique_sorted(const std::vector<std::pair<Point<2>, double>> &nodes,
                      const unsigned int                              d)
        {
          std::vector<double> v;
          for (const auto &[x, p] : nodes)
            v.push_back(x[d]);
          std::sort(v.begin(), v.end());
          v.erase(std::unique(v.begin(),
                              v.end(),
                              [](double a, double b) { return b - a < eps; }),
                  v.end());
          return v;
        }

        // the cell of @p g holding @p x and the local coordinate in it
        static std::pair<unsigned int, double>
        locate(const std::vector<double> &g, const double x)
        {
          unsigned int i = std::upper_bound(g.begin(), g.end(), x) - g.begin();
          i = std::min<unsigned int>(std::max(i, 1u), g.size() - 1) - 1;
          return {i, std::clamp((x - g[i]) / (g[i + 1] - g[i]), 0., 1.)};
        }
      };

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
        physics::StructuralModel                               &model,
        const std::vector<std::pair<dealii::Point<3>, double>> &nodes_3d,
        const double                                            fraction,
        const unsigned int                                      cycle,
        std::ostream                                           &csv,
        ConditionalOStream                                     &pcout)
      {
        // everything in the contact pair's plane coordinates
        const scene::ContactPair &pair = contact::single_pair(*model.scene);
        std::vector<std::pair<Point<2>, double>> nodes;
        for (const auto &[x, p] : nodes_3d)
          nodes.emplace_back(pair.to_plane(x), p);
        const NodalPressure field(nodes);
        const double        eps  = NodalPressure::eps;
        const double        x_lo = field.xs.front(), x_hi = field.xs.back(),
                     y_lo = field.ys.front(), y_hi = field.ys.back();
        const auto pressure_at = [&](const Point<2> &x) { return field(x); };
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
                    fx_lo            = std::min(fx_lo, x[0]);
                    fx_hi            = std::max(fx_hi, x[0]);
                    fy_lo            = std::min(fy_lo, x[1]);
                    fy_hi            = std::max(fy_hi, x[1]);
                  }
                // the face overlaps the pad's footprint (an area, not a line)
                if (std::min(fx_hi, x_hi) - std::max(fx_lo, x_lo) < eps ||
                    std::min(fy_hi, y_hi) - std::max(fy_lo, y_lo) < eps)
                  continue;
                double lo = 1e300, hi = -1e300;
                for (const auto v : face->vertex_indices())
                  {
                    const double p =
                      pressure_at(pair.to_plane(face->vertex(v)));
                    lo = std::min(lo, p);
                    hi = std::max(hi, p);
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
        unsigned int                        n_refined = 0;
        for (const auto &cell : model.triangulation.active_cell_iterators())
          {
            const unsigned int c = cell->active_cell_index();
            if (!on_contact[c])
              continue;
            const bool refined =
              indicator[c] >= threshold && indicator[c] > 0.f;
            const std::string &body =
              model.scene->body(cell->material_id()).name;
            if (refined)
              {
                ++by_body[body];
                ++n_refined;
              }
            csv << cycle << ',' << body << ',' << cell->center()[0] << ','
                << cell->center()[1] << ',' << cell->center()[2] << ','
                << indicator[c] << ',' << refined << '\n';
          }
        std::string split;
        for (const auto &[body, count] : by_body)
          split +=
            (split.empty() ? "" : ", ") + std::to_string(count) + " " + body;
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

    // Mesh/Contact refinements: cycles of refine_by_contact_pressure() on
    // the preload's pressure, each cycle's table into contact_refinement.csv.
    void
    ComplexEigenvalueAnalysis::refine_at_contact(
      const std::vector<std::pair<dealii::Point<3>, double>> &preload_pressure)
    {
      if (prm.mesh.contact_refinements == 0)
        return;
      std::ostringstream csv;
      csv << "cycle,body,x,y,z,pressure_variation_Pa,refined\n";
      for (unsigned int c = 0; c < prm.mesh.contact_refinements; ++c)
        if (refine_by_contact_pressure(*model,
                                       preload_pressure,
                                       prm.mesh.contact_refinement_fraction,
                                       c,
                                       csv,
                                       pcout) == 0)
          break;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        io::OutputFile(work_dir + "/contact_refinement.csv") << csv.str();
      pcout << "Mesh after the contact refinement: "
            << model->triangulation.n_active_cells() << " cells, "
            << model->n_dofs() << " DoFs" << std::endl;
    }
  } // namespace analyses
} // namespace squeal
