// Where the discretisation error of the CEA's modes sits: Kelly's or the
// traction-jump indicator on the modes of a sweep point (mesh_error.vtu,
// mesh_error.csv), which also drives the adaptive refinement.

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
#include <squeal/eigen/tracking.h>
#include <squeal/io/output_directory.h>
#include <squeal/physics/error_indicator.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
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
      // the traction-jump indicator of SOLUTIONS with the scene's laws at
      // the point P (physics/error_indicator.h)
      void
      traction_jump_estimate(
        const physics::StructuralModel                  &model,
        const parameters::ScalarPoint                   &p,
        const std::vector<const physics::PETScVector *> &solutions,
        std::vector<Vector<float>>                      &eta)
      {
        const scene::Scene &scene = *model.scene;
        physics::traction_jump_indicator(
          model.mapping,
          model.dof_handler,
          [&](const types::material_id id, const Point<3> &x) {
            const scene::Body &body = scene.body(id);
            if (body.law.anisotropic)
              return scene.stiffness_tensor(id, x, p);
            const auto [lambda, mu] =
              physics::lame_constants(scene.youngs_modulus(id, p),
                                      body.material.poisson_ratio);
            return SymmetricTensor<4, 3>(
              lambda * outer_product(unit_symmetric_tensor<3>(),
                                     unit_symmetric_tensor<3>()) +
              2. * mu * identity_tensor<3>());
          },
          [&](const types::material_id id) {
            return scene.youngs_modulus(id, p);
          },
          solutions,
          eta);
      }
    } // namespace

    // The error indicator (Mesh/Error indicator) on the real and imaginary
    // parts of the modes PAIRS, each scaled to unit kinetic norm, squared
    // and summed per cell (see write_error_indicator()). Both estimators
    // take a batch of vectors in one pass over the faces, so the mapped face
    // values (MappingQ of the element's degree on curved cells: most of its
    // cost) are computed once per batch instead of once per vector.
    Vector<double>
    ComplexEigenvalueAnalysis::mode_indicator(
      const std::vector<eigen::EigenPair> &pairs,
      const parameters::ScalarPoint       &values,
      const std::vector<double>           &weights) const
    {
      // pairs per pass: 2 ghosted vectors each (32 vectors, 300 MB at a
      // million DoFs)
      constexpr std::size_t batch   = 16;
      const unsigned int    n_cells = model->triangulation.n_active_cells();
      Vector<double>        sum(n_cells);
      std::vector<physics::PETScVector> ghosted;
      const std::size_t n_ghosted = 2 * std::min(batch, pairs.size());
      ghosted.reserve(n_ghosted);
      for (std::size_t k = 0; k < n_ghosted; ++k)
        ghosted.emplace_back(model->locally_owned_dofs,
                             model->locally_relevant_dofs,
                             comm);
      // With weights, the modes are scaled per cluster of equal eigenvalues
      // (eigen::repeated_eigenvalues(): the two members of a disc's
      // doublet): the sum of their squared fields, each of unit
      // kinetic norm, does not depend on which basis of the doublet the
      // eigensolver returned (the trace of the indicator's quadratic form
      // on the pair's space), whereas each member's own distribution does,
      // and with it the marking, by rounding. cluster[k]: the first pair of
      // k's cluster; remaining[c]: its members not yet estimated.
      const std::vector<std::size_t> cluster =
        eigen::repeated_eigenvalues(pairs);
      std::map<std::size_t, unsigned int>   remaining;
      std::map<std::size_t, Vector<double>> cluster_field;
      std::map<std::size_t, double>         cluster_weight;
      for (const std::size_t c : cluster)
        ++remaining[c];
      // the whole mass of the point: every mass part at its coefficient
      physics::PETScMatrix M;
      model->parts().mass(values, M);
      // on its own nonzeros (no coupling between displacement components:
      // a third of the common pattern's entries) for the 2 products per
      // mode
      physics::store_nonzeros_only(M, model->locally_owned_dofs, comm);
      // The members of a cluster after its first, M-orthogonalised to the
      // ones before them (Gram-Schmidt in the Hermitian product v^H M w):
      // the eigensolver's vectors of a repeated eigenvalue are any
      // independent pair of its space, not necessarily orthogonal, and the
      // indicator summed over a non-orthogonal pair depends on which pair
      // it is. (Each is scaled to unit kinetic norm below.) One copy per
      // doublet.
      std::map<std::size_t, eigen::EigenPair> orthogonal;
      const auto                              vectors_of =
        [&](const std::size_t k) -> const eigen::EigenPair & {
        const auto it = orthogonal.find(k);
        return it == orthogonal.end() ? pairs[k] : it->second;
      };
      for (std::size_t k = 0; k < pairs.size(); ++k)
        if (cluster[k] != k)
          {
            eigen::EigenPair     v = pairs[k];
            physics::PETScVector Mu_re(v.re), Mu_im(v.im);
            for (std::size_t j = cluster[k]; j < k; ++j)
              if (cluster[j] == cluster[k])
                {
                  const eigen::EigenPair &u = vectors_of(j);
                  M.vmult(Mu_re, u.re);
                  M.vmult(Mu_im, u.im);
                  const double uu = Mu_re * u.re + Mu_im * u.im;
                  if (!(uu > 0.))
                    continue;
                  // alpha = u^H M v / u^H M u (M symmetric)
                  const double a_re = (Mu_re * v.re + Mu_im * v.im) / uu;
                  const double a_im = (Mu_re * v.im - Mu_im * v.re) / uu;
                  v.re.add(-a_re, u.re, a_im, u.im);
                  v.im.add(-a_re, u.im, -a_im, u.re);
                }
            orthogonal.emplace(k, std::move(v));
          }
      // the pairs FIRST..END are done, estimated (nonzero norm) or not:
      // each cluster they complete goes into SUM at the unit sum over all
      // cells where its error sits, times the sum of its members' squared
      // estimated errors
      const auto finish_batch = [&](const std::size_t first,
                                    const std::size_t end) {
        for (std::size_t k = first; k < end; ++k)
          {
            const std::size_t c = cluster[k];
            if (--remaining[c] > 0 || cluster_field.count(c) == 0)
              continue;
            Vector<double> &field = cluster_field[c];
            Utilities::MPI::sum(field, comm, field);
            const double total = field.l1_norm();
            if (total > 0.)
              field *= cluster_weight[c] / total;
            if (Utilities::MPI::this_mpi_process(comm) == 0)
              sum += field; // summed over the ranks below
            cluster_field.erase(c);
          }
      };
      for (std::size_t first = 0; first < pairs.size(); first += batch)
        {
          const std::size_t end = std::min(pairs.size(), first + batch);
          // the batch's pairs of nonzero norm, their weights, vectors and
          // the index of each one's first vector in SOLUTIONS
          std::vector<std::size_t>                  taken, first_vector;
          std::vector<double>                       weight;
          std::vector<const physics::PETScVector *> solutions;
          for (std::size_t k = first; k < end; ++k)
            {
              const eigen::EigenPair &pair = vectors_of(k);
              physics::PETScVector    re = pair.re, im = pair.im, Mx(pair.re);
              M.vmult(Mx, re);
              const double a = re * Mx, c = im * Mx;
              M.vmult(Mx, im);
              const double b     = im * Mx;
              const double norm2 = a + b;
              if (!(norm2 > 0.))
                continue;
              taken.push_back(k);
              first_vector.push_back(solutions.size());
              // unstable by the Eigensolver thresholds, not by the sign
              // of Re lambda: an undamped mode's is rounding noise, which
              // would double some members of a doublet and not others
              const auto &es = prm.eigensolver;
              weight.push_back(
                (eigen::is_unstable(pair.lambda,
                                    es.unstable_tolerance,
                                    es.unstable_relative_tolerance) ?
                   2. :
                   1.) /
                norm2);
              // The indicator is a sum of squares of linear functionals of
              // the field, so eta^2(re) + eta^2(im) does not change when
              // the mode is multiplied by a phase e^{-i theta}. The phase
              // that makes the real and imaginary parts M-orthogonal, the
              // real part the larger, leaves an imaginary part of norm
              // zero for a real mode (undamped and frictionless: every
              // mode of a real-modes run), which is then not estimated.
              const double theta = 0.5 * std::atan2(2. * c, a - b);
              const double cs = std::cos(theta), sn = std::sin(theta);
              // re, im <- cs re + sn im, cs im - sn re (Mx the old re)
              Mx = re;
              re *= cs;
              re.add(sn, im);
              im *= cs;
              im.add(-sn, Mx);
              const double major = 0.5 * norm2 + std::hypot(0.5 * (a - b), c);
              std::vector<physics::PETScVector *> parts{&re};
              if (norm2 - major > 1e-14 * norm2)
                parts.push_back(&im);
              for (physics::PETScVector *x : parts)
                {
                  model->constraints.distribute(*x);
                  ghosted[solutions.size()] = *x;
                  solutions.push_back(&ghosted[solutions.size()]);
                }
            }
          first_vector.push_back(solutions.size());
          if (solutions.empty())
            {
              finish_batch(first, end);
              continue;
            }
          std::vector<Vector<float>> eta(solutions.size(),
                                         Vector<float>(n_cells));
          if (prm.mesh.error_indicator == "traction jump")
            traction_jump_estimate(*model, values, solutions, eta);
          else
            {
              std::vector<Vector<float> *> eta_of;
              for (Vector<float> &e : eta)
                eta_of.push_back(&e);
              // this rank's cells only (on a shared mesh Kelly estimates
              // every cell unless given the subdomain; the sum over the
              // ranks below would count each cell once per rank)
              KellyErrorEstimator<3>::estimate(
                model->mapping,
                model->dof_handler,
                QGauss<2>(model->fe.degree + 1),
                {},
                solutions,
                eta_of,
                ComponentMask(),
                nullptr,
                numbers::invalid_unsigned_int,
                model->triangulation.locally_owned_subdomain());
            }
          for (std::size_t j = 0; j < taken.size(); ++j)
            {
              Vector<double> mode(n_cells);
              for (std::size_t v = first_vector[j]; v < first_vector[j + 1];
                   ++v)
                for (unsigned int c = 0; c < n_cells; ++c)
                  mode[c] += weight[j] * double(eta[v][c]) * double(eta[v][c]);
              if (weights.empty())
                {
                  sum += mode;
                  continue;
                }
              const std::size_t c  = cluster[taken[j]];
              auto              it = cluster_field.find(c);
              if (it == cluster_field.end())
                it = cluster_field.emplace(c, Vector<double>(n_cells)).first;
              it->second += mode;
              cluster_weight[c] += std::pow(weights[taken[j]], 2);
            }
          finish_batch(first, end);
        }
      // each rank estimated its own cells
      Utilities::MPI::sum(sum, comm, sum);
      return sum;
    }

    // Where the discretisation error of the modes sits: Kelly's estimator
    // (the jump of the gradient across faces; Kelly, Gago, Zienkiewicz &
    // Babuska, IJNME 19, 1983) or the traction jump (Mesh/Error indicator)
    // on the real and imaginary parts of every mode
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
      TimerOutput::Scope            t(timer, "error indicator");
      std::vector<eigen::EigenPair> pairs;
      if (!pt->q.empty())
        reduced.expand(pt->q, pt->lambda, pairs);
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
      pcout << "Error indicator ("
            << (prm.mesh.error_indicator == "kelly" ? "Kelly" : "traction jump")
            << ", " << pt->lambda.size()
            << " modes of the first point; mesh_error.vtu):"
            << std::setprecision(3);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        pcout << (b == 0 ? " " : ", ") << bodies[b].name << " "
              << 100. * by_body[bodies[b].id].first / total << " %";
      pcout << " of the squared sum" << std::setprecision(6) << std::endl;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          io::OutputFile csv(work_dir + "/mesh_error.csv");
          csv << "body,cells,share_of_squared_indicator\n";
          for (const scene::Body &b : bodies)
            csv << b.name << ',' << by_body[b.id].second << ','
                << by_body[b.id].first / total << '\n';
        }
      DataOut<3> data_out;
      data_out.set_flags(io::vtk_flags());
      data_out.attach_triangulation(model->triangulation);
      data_out.add_data_vector(indicator, "error_indicator");
      data_out.add_data_vector(body, "body");
      data_out.build_patches();
      io::write_vtu(data_out, work_dir + "/mesh_error.vtu", comm);
    }
  } // namespace analyses
} // namespace squeal
