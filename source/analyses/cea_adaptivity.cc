// The CEA's adaptive cycles before the sweep: each mode's change between
// meshes or its hierarchical estimate at degree + 1, the choice of h or p,
// and the refinement they drive (the indicator: cea_error_indicator.cc).

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
#include <memory>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;


    namespace
    {
      // Every mode shape of PAIRS as one complex vector of all n_dofs
      // values on every rank, hanging-node values filled in (the solver
      // leaves constrained entries at zero).
      std::vector<std::vector<std::complex<double>>>
      full_shapes(const physics::StructuralModel      &model,
                  const std::vector<eigen::EigenPair> &pairs)
      {
        std::vector<std::vector<std::complex<double>>> shapes;
        for (const auto &pr : pairs)
          {
            physics::PETScVector r = pr.re, i = pr.im;
            model.constraints.distribute(r);
            model.constraints.distribute(i);
            const Vector<double>              re(r), im(i);
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
      // mode or, for the modes of one eigenvalue, with their space, and
      // among the rich modes within 80 % of the best MAC the one nearest in
      // the complex plane (the two members of a doublet share a subspace,
      // and near a lock-in the two shapes of the pair become parallel:
      // shape alone cannot tell them apart). A mode whose best MAC is below
      // 0.3 has no partner: difference 1 (100 %).
      struct Partner
      {
        int                  index = -1;
        std::complex<double> lambda;
        double               difference = 1.;
      };

      std::vector<Partner>
      partners_in(const std::vector<eigen::EigenPair> &coarse_pairs,
                  const std::vector<std::vector<std::complex<double>>> &carried,
                  const physics::StructuralModel                       &rich,
                  const std::vector<eigen::EigenPair> &rich_pairs)
      {
        auto rich_shapes = full_shapes(rich, rich_pairs);
        // the rich modes of one eigenvalue (|lambda_j - lambda_i| <= 1e-6
        // |lambda_i|: a doublet) orthonormalised (Gram-Schmidt in the
        // Hermitian product of the shapes): the eigensolver returns any
        // independent pair of a doublet's space, and a coarse mode in that
        // space can be far from both of a nearly parallel pair (MAC below
        // 0.3 with each: no partner, an estimate of 100 %, depending on
        // rounding). With an orthonormal pair its MACs with the two sum to
        // its MAC with the space, which is what a cluster is compared by.
        const std::vector<std::size_t> cluster =
          eigen::repeated_eigenvalues(rich_pairs);
        for (unsigned int j = 0; j < rich_pairs.size(); ++j)
          {
            auto &v = rich_shapes[j];
            for (unsigned int i = cluster[j]; i < j; ++i)
              if (cluster[i] == cluster[j])
                {
                  const auto          &u  = rich_shapes[i];
                  std::complex<double> uv = 0.;
                  for (std::size_t n = 0; n < v.size(); ++n)
                    uv += std::conj(u[n]) * v[n];
                  for (std::size_t n = 0; n < v.size(); ++n)
                    v[n] -= uv * u[n];
                }
            double norm2 = 0.;
            for (const auto &x : v)
              norm2 += std::norm(x);
            if (norm2 > 0.)
              for (auto &x : v)
                x /= std::sqrt(norm2);
          }
        std::vector<Partner> result(coarse_pairs.size());
        for (unsigned int k = 0; k < coarse_pairs.size(); ++k)
          {
            const auto         &a = carried[k];
            std::vector<double> mac(rich_pairs.size(), 0.);
            for (unsigned int j = 0; j < rich_pairs.size(); ++j)
              mac[j] = eigen::complex_mac(a, rich_shapes[j]);
            // each cluster's MAC: the sum over its orthonormal members
            std::vector<double> cluster_mac(rich_pairs.size(), 0.);
            for (unsigned int j = 0; j < rich_pairs.size(); ++j)
              cluster_mac[cluster[j]] += mac[j];
            const double best =
              cluster_mac.empty() ?
                0. :
                *std::max_element(cluster_mac.begin(), cluster_mac.end());
            if (best < 0.3)
              continue;
            for (unsigned int j = 0; j < rich_pairs.size(); ++j)
              if (cluster_mac[cluster[j]] >= 0.8 * best)
                {
                  const auto  &lj = rich_pairs[j].lambda;
                  const double d =
                    std::abs(coarse_pairs[k].lambda - lj) / std::abs(lj);
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

      // A model of MODEL's scene with PRM (another degree; PRM must outlive
      // it) on MODEL's refined mesh, with its interface, varied parameters
      // and ties, assembled once.
      std::unique_ptr<physics::StructuralModel>
      on_same_mesh(const physics::StructuralModel  &model,
                   const parameters::AllParameters &prm,
                   ConditionalOStream              &quiet)
      {
        auto result =
          std::make_unique<physics::StructuralModel>(prm, model.comm);
        result->interface_mask  = model.interface_mask;
        result->varied          = model.varied;
        result->tie_constraints = model.tie_constraints;
        result->setup_and_assemble(model.refinement_history, quiet);
        return result;
      }

      // The partners of PAIRS (on MODEL's mesh) in the same mesh at the
      // degree + EXTRA: that model built (on_same_mesh()), solved
      // at P in BAND by the full solver, or PROJECTED (below); its DoF count
      // goes to N_DOFS.
      std::vector<Partner>
      partners_at_degree(
        const parameters::AllParameters                      &prm,
        const physics::StructuralModel                       &model,
        const std::vector<eigen::EigenPair>                  &pairs,
        const std::vector<std::vector<std::complex<double>>> &shapes,
        const unsigned int                                    extra,
        const parameters::ScalarPoint                        &p,
        const eigen::BandOptions                             &band,
        const bool                                            projected,
        types::global_dof_index                              &n_dofs,
        std::ostream                                         &timing)
      {
        const auto                t0 = std::chrono::steady_clock::now();
        ConditionalOStream        quiet(std::cout, false);
        parameters::AllParameters prm_rich = prm;
        prm_rich.mesh.fe_degree += extra;
        const auto rich_model = on_same_mesh(model, prm_rich, quiet);
        const physics::StructuralModel &rich = *rich_model;
        n_dofs                               = rich.n_dofs();
        // the coarse shapes at the rich model's support points
        std::vector<std::vector<std::complex<double>>> carried;
        for (const auto &x : shapes)
          carried.push_back(physics::transfer_field(model, x, rich));
        timing << std::setprecision(3) << "set-up "
               << std::chrono::duration<double>(
                    std::chrono::steady_clock::now() - t0)
                    .count()
               << " s";
        if (!projected)
          return partners_in(pairs,
                             carried,
                             rich,
                             eigen::solve_full(rich.parts(), p, band, quiet));

        // Projected: the richer model's eigenvalues by Rayleigh-Ritz on
        // the span of the degree-p modes carried to it (real and imaginary
        // parts) and three block shift-and-invert iterates of each, one
        // shift per octave of the band (eigen::solve_on_iterates). The
        // degree-p modes span exactly the degree-p eigenvalues (the spaces
        // are nested); the iterates add the richer space's correction. The
        // Ritz values of a subspace lie short of the degree + 1 eigenvalues,
        // so this estimate can only fall below the full one
        // (benchmarks/speed_vs_error measures by how much).
        const IndexSet                   &owned = rich.locally_owned_dofs;
        std::vector<physics::PETScVector> start;
        std::vector<double>               start_frequency;
        for (unsigned int k = 0; k < pairs.size(); ++k)
          for (const bool imaginary : {false, true})
            {
              physics::PETScVector v(owned, rich.comm);
              for (const auto j : owned)
                if (!rich.constraints.is_constrained(j))
                  v(j) =
                    imaginary ? carried[k][j].imag() : carried[k][j].real();
              v.compress(VectorOperation::insert);
              if (v.l2_norm() == 0.)
                continue;
              start.push_back(std::move(v));
              start_frequency.push_back(std::abs(frequency(pairs[k].lambda)));
            }
        eigen::IterateReport report;
        const auto           rich_pairs = eigen::solve_on_iterates(
          rich.parts(), p, band, start, start_frequency, 3, &report);
        timing << ", " << report.factorisations << " LDL^T factorisations "
               << report.factorisation_seconds << " s, block solves "
               << report.solve_seconds << " s, projected problem on "
               << report.basis_size << " directions "
               << report.projected_seconds << " s" << std::setprecision(6);
        return partners_in(pairs, carried, rich, rich_pairs);
      }
      // The partner of each of the mode shapes SHAPES (support points
      // POINTS, components COMPONENT) among the previous mesh's shapes
      // PREV_SHAPES: the refined mesh keeps the old support points, so the
      // shapes are compared there (complex MAC); a new mode's partner is the
      // old one of largest MAC if that reaches 0.4, else -1 (a member of a
      // doublet, whose two shapes mix between meshes, has MAC ~0.5 with
      // each old one; its partner is then either).
      std::vector<int>
      previous_partners(
        const std::vector<std::vector<std::complex<double>>> &shapes,
        const std::vector<dealii::Point<3>>                  &points,
        const std::vector<unsigned int>                      &component,
        const std::vector<std::vector<std::complex<double>>> &prev_shapes,
        const std::vector<dealii::Point<3>>                  &prev_points,
        const std::vector<unsigned int>                      &prev_component)
      {
        std::map<std::array<long long, 4>, unsigned int> new_index;
        const auto key = [](const dealii::Point<3> &x, const unsigned int c) {
          return std::array<long long, 4>{{std::llround(x[0] * 1e9),
                                           std::llround(x[1] * 1e9),
                                           std::llround(x[2] * 1e9),
                                           c}};
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
        // the previous shapes at the common points
        std::vector<std::vector<std::complex<double>>> old_at(
          prev_shapes.size());
        for (unsigned int j = 0; j < prev_shapes.size(); ++j)
          for (const auto &[io, in] : common)
            old_at[j].push_back(prev_shapes[j][io]);
        std::vector<int> partner(shapes.size(), -1);
        for (unsigned int k = 0; k < shapes.size(); ++k)
          {
            std::vector<std::complex<double>> new_at;
            for (const auto &[io, in] : common)
              new_at.push_back(shapes[k][in]);
            unsigned int best     = 0;
            double       best_mac = -1.;
            for (unsigned int j = 0; j < old_at.size(); ++j)
              {
                const double mac = eigen::complex_mac(new_at, old_at[j]);
                if (j == 0 || mac > best_mac)
                  {
                    best     = j;
                    best_mac = mac;
                  }
              }
            if (!old_at.empty() && best_mac >= 0.4)
              partner[k] = best;
          }
        return partner;
      }
      // The error estimate of one adaptive cycle: each mode's partner on the
      // same mesh at degree + 1 (Mesh/Estimate solver), its relative
      // difference scaled by 1.5 and capped at 1, shared within clusters;
      // the largest in the band and the modes above Mesh/Frequency
      // tolerance.
      struct CycleEstimate
      {
        std::vector<Partner>    estimate;
        std::vector<bool>       above;
        types::global_dof_index rich_dofs = 0;
        double                  worst = 0., f_at = 0., seconds = 0.;
        std::string             timing; ///< where the seconds went
        unsigned int            n_above = 0, n_shared = 0;
      };

      CycleEstimate
      estimate_at_higher_degree(
        const physics::StructuralModel                       &model,
        const std::vector<eigen::EigenPair>                  &pairs,
        const std::vector<std::vector<std::complex<double>>> &shapes,
        const parameters::ScalarPoint                        &p0,
        const eigen::BandOptions                             &wide,
        const parameters::Mesh                               &m,
        const std::vector<double>                            &f,
        const std::function<bool(double)>                    &in_band)
      {
        CycleEstimate      ce;
        std::ostringstream timing;
        ce.above.assign(pairs.size(), false);
        const auto t1 = std::chrono::steady_clock::now();
        ce.estimate   = partners_at_degree(model.prm,
                                         model,
                                         pairs,
                                         shapes,
                                         1,
                                         p0,
                                         wide,
                                         m.estimate_solver == "projected",
                                         ce.rich_dofs,
                                         timing);
        ce.timing     = timing.str();
        // The difference to degree + 1 is the error of degree p minus that
        // of degree p + 1; where the latter is at most a third of the former
        // (0.1-0.34 measured on the clamped disc against verification A3),
        // the error is at most 1.5 x the difference.
        for (auto &pe : ce.estimate)
          pe.difference = std::min(1., 1.5 * pe.difference);
        ce.n_shared = share_within_clusters(pairs, ce.estimate);
        ce.seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t1)
            .count();
        for (unsigned int k = 0; k < pairs.size(); ++k)
          if (in_band(f[k]))
            {
              if (ce.estimate[k].difference > ce.worst)
                {
                  ce.worst = ce.estimate[k].difference;
                  ce.f_at  = f[k];
                }
              ce.above[k] = ce.estimate[k].difference > m.frequency_tolerance;
              ce.n_above += ce.above[k];
            }
        return ce;
      }

      // adaptive_modes.csv's rows: per mode of the final mesh its frequency,
      // growth rate, estimate and partner, and (Mesh/Check estimate) the
      // partner at degree + 2.
      void
      write_mode_estimates(std::ostream                        &per_mode,
                           const unsigned int                   cycle,
                           const std::vector<eigen::EigenPair> &pairs,
                           const std::vector<Partner>          &estimate,
                           const std::vector<Partner>          &check)
      {
        for (unsigned int k = 0; k < pairs.size(); ++k)
          {
            per_mode << cycle << ',' << std::setprecision(10)
                     << frequency(pairs[k].lambda) << ','
                     << pairs[k].lambda.real() << ',' << estimate[k].difference
                     << ',';
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
      }
      // The change of the modes' frequencies F (shapes SHAPES at POINTS,
      // COMPONENT) from the previous mesh's F_PREV: each mode's partner by
      // previous_partners(); the largest and the median relative change of
      // the modes in the band (IN_BAND), the frequency of the largest, the
      // modes without a partner.
      struct MeshChange
      {
        double       e_max = -1., e_median = -1., f_worst = 0.;
        unsigned int n_unmatched = 0;
      };

      MeshChange
      change_from_previous(
        const std::vector<double>                            &f,
        const std::vector<std::vector<std::complex<double>>> &shapes,
        const std::vector<dealii::Point<3>>                  &points,
        const std::vector<unsigned int>                      &component,
        const std::vector<double>                            &f_prev,
        const std::vector<std::vector<std::complex<double>>> &prev_shapes,
        const std::vector<dealii::Point<3>>                  &prev_points,
        const std::vector<unsigned int>                      &prev_component,
        const std::function<bool(double)>                    &in_band)
      {
        MeshChange             change;
        std::vector<double>    e;
        const std::vector<int> partner = previous_partners(
          shapes, points, component, prev_shapes, prev_points, prev_component);
        for (unsigned int k = 0; k < f.size(); ++k)
          {
            if (partner[k] < 0)
              {
                ++change.n_unmatched;
                continue;
              }
            const unsigned int j = partner[k];
            if (in_band(f[k]))
              {
                e.push_back(std::abs(f[k] - f_prev[j]) / f[k]);
                if (e.back() >= *std::max_element(e.begin(), e.end()))
                  change.f_worst = f[k];
              }
          }
        if (!e.empty())
          {
            std::sort(e.begin(), e.end());
            change.e_max    = e.back();
            change.e_median = e[e.size() / 2];
          }
        return change;
      }
      // Mesh/Check estimate: each mode's partner at degree + 2 on the final
      // mesh, and the largest ratio of that error to the estimate, printed.
      std::vector<Partner>
      check_estimate(
        const physics::StructuralModel                       &model,
        const std::vector<eigen::EigenPair>                  &pairs,
        const std::vector<std::vector<std::complex<double>>> &shapes,
        const parameters::ScalarPoint                        &p0,
        const eigen::BandOptions                             &wide,
        const std::vector<Partner>                           &estimate,
        const std::function<bool(double)>                    &in_band,
        ConditionalOStream                                   &pcout)
      {
        std::vector<Partner>    check;
        const auto              t1         = std::chrono::steady_clock::now();
        types::global_dof_index check_dofs = 0;
        std::ostringstream      timing;
        check              = partners_at_degree(model.prm,
                                   model,
                                   pairs,
                                   shapes,
                                   2,
                                   p0,
                                   wide,
                                   false,
                                   check_dofs,
                                   timing);
        double worst_ratio = 0.;
        for (unsigned int k = 0; k < pairs.size(); ++k)
          if (in_band(frequency(pairs[k].lambda)) && check[k].difference > 0.)
            worst_ratio =
              std::max(worst_ratio,
                       check[k].difference / estimate[k].difference);
        pcout << "Check of the estimate (degree " << model.fe.degree + 2 << ", "
              << check_dofs << " DoFs, " << std::setprecision(3)
              << std::chrono::duration<double>(
                   std::chrono::steady_clock::now() - t1)
                   .count()
              << " s): largest error / estimate " << worst_ratio
              << std::setprecision(6) << " (adaptive_modes.csv)" << std::endl;
        return check;
      }
      // Whether Mesh/Frequency TOLERANCE was REACHED after CYCLE refinement
      // cycles (N_DOFS on the final mesh), printed.
      void
      report_tolerance(ConditionalOStream           &pcout,
                       const double                  tolerance,
                       const bool                    reached,
                       const unsigned int            cycle,
                       const types::global_dof_index n_dofs)
      {
        if (reached)
          pcout << "Frequency tolerance " << 100. * tolerance
                << " % reached after " << cycle
                << " refinement cycles: " << n_dofs << " DoFs" << std::endl;
        else
          pcout << "Warning: Mesh/Frequency tolerance " << 100. * tolerance
                << " % not reached after Mesh/Adaptive cycles = " << cycle
                << " refinements (adaptive_modes.csv lists the modes above "
                   "it); the sweep runs on the last mesh, "
                << n_dofs << " DoFs" << std::endl;
      }
      // the columns of adaptive_cycles.csv and adaptive_modes.csv
      constexpr const char *cycles_header =
        "cycle,cells,dofs,seconds,modes,max_relative_change,"
        "median_relative_change,frequency_of_max_change_Hz,"
        "modes_unmatched,estimate_dofs,estimate_seconds,"
        "max_estimated_error,frequency_of_max_estimate_Hz,"
        "modes_above_tolerance,degree\n";
      constexpr const char *modes_header =
        "cycle,freq_Hz,re_per_s,estimated_relative_error,"
        "estimate_partner_freq_Hz,estimate_partner_re_per_s,"
        "check_freq_Hz,check_re_per_s,check_relative_error\n";

      // One adaptive cycle's mesh and its change from the previous one: a
      // log line and the first columns of its row of adaptive_cycles.csv.
      void
      report_cycle(ConditionalOStream             &pcout,
                   std::ostream                   &table,
                   const unsigned int              cycle,
                   const physics::StructuralModel &model,
                   const eigen::FullSolveReport   &solve,
                   const std::size_t               n_modes,
                   const MeshChange               &change)
      {
        const double seconds = solve.seconds;
        pcout << "Adaptive cycle " << cycle << ": "
              << model.triangulation.n_active_cells() << " cells, "
              << model.n_dofs() << " DoFs, " << n_modes
              << " modes in the band, full solve " << std::setprecision(3)
              << seconds << " s (" << solve.rounds
              << " refinement rounds, largest relative residual "
              << solve.largest_residual << ")";
        if (change.e_max >= 0.)
          pcout << ", change from the previous mesh: largest "
                << 100. * change.e_max << " % (" << change.f_worst
                << " Hz), median " << 100. * change.e_median << " %"
                << (change.n_unmatched > 0 ?
                      ", " + std::to_string(change.n_unmatched) +
                        " modes without a partner" :
                      std::string());
        pcout << std::setprecision(6) << std::endl;
        table << cycle << ',' << model.triangulation.n_active_cells() << ','
              << model.n_dofs() << ',' << seconds << ',' << n_modes << ','
              << change.e_max << ',' << change.e_median << ',' << change.f_worst
              << ',' << change.n_unmatched;
      }

      // The cycle's error estimate at degree @p degree: a log line and the
      // estimate's columns of adaptive_cycles.csv.
      void
      report_estimate(ConditionalOStream  &pcout,
                      std::ostream        &table,
                      const CycleEstimate &ce,
                      const unsigned int   degree,
                      const double         tolerance)
      {
        pcout << "  estimated error (degree " << degree << ", " << ce.rich_dofs
              << " DoFs, " << std::setprecision(3) << ce.seconds
              << " s: " << ce.timing << "): largest " << 100. * ce.worst
              << " % (" << ce.f_at << " Hz), " << ce.n_above
              << " modes above the tolerance " << 100. * tolerance << " %";
        if (ce.n_shared > 0)
          pcout << " (" << ce.n_shared
                << " modes take a closer neighbour's larger estimate)";
        pcout << std::setprecision(6) << std::endl;
        table << ',' << ce.rich_dofs << ',' << ce.seconds << ',' << ce.worst
              << ',' << ce.f_at << ',' << ce.n_above;
      }
    } // namespace
    // h or p (Mesh/Degree adaptivity): the largest estimate's decay per DoF,
    // rho = log(e_before / e_after) / log(N_after / N_before), measured on
    // the last h step, against the one degree + 1 on the same mesh is
    // predicted to give: a third of the error (the assumption behind the
    // factor 1.5) for the estimate's own DoFs, log 3 / log(N_p+1 / N_p). The
    // first step is h, to measure it. The degree goes up to 3 (its estimate
    // solves degree 4; with Check estimate to 2). When p wins, the model is
    // rebuilt at degree + 1 on the same mesh.
    bool
    ComplexEigenvalueAnalysis::raise_degree(
      const types::global_dof_index dofs_before,
      const double                  estimate_before,
      const double                  worst,
      const types::global_dof_index rich_dofs,
      ConditionalOStream           &quiet)
    {
      const unsigned int degree = model->fe.degree;
      if (degree + 2 > (prm.mesh.check_estimate ? 3u : 4u))
        return false;
      const double rho_h = std::log(estimate_before / worst) /
                           std::log(double(model->n_dofs()) / dofs_before);
      const double rho_p =
        std::log(3.) / std::log(double(rich_dofs) / model->n_dofs());
      pcout << "  h or p: the last refinement reduced the largest "
               "estimate at rate "
            << std::setprecision(3) << rho_h << " per log DoFs, degree "
            << degree + 1 << " is predicted at " << rho_p
            << std::setprecision(6);
      if (!(rho_p > rho_h))
        {
          pcout << ": h-refinement" << std::endl;
          return false;
        }
      pcout << ": degree " << degree + 1 << " on the same mesh" << std::endl;
      auto raised = std::make_unique<parameters::AllParameters>(model->prm);
      raised->mesh.fe_degree = degree + 1;
      auto rebuilt           = on_same_mesh(*model, *raised, quiet);
      model                  = std::move(rebuilt); // the old model first,
      raised_prm             = std::move(raised);  // then its parameters
      return true;
    }

    // One h-refinement of the adaptive cycles: the error indicator on the
    // modes PAIRS that drive it (those flagged in ABOVE, or all when it is
    // empty; each mode's squared field scaled to WEIGHTS^2 when given) marks
    // Mesh/Refinement fraction of the cells.
    void
    ComplexEigenvalueAnalysis::refine_by_modes(
      const std::vector<eigen::EigenPair> &pairs,
      const std::vector<bool>             &above,
      const std::vector<double>           &weights,
      const parameters::ScalarPoint       &p0,
      ConditionalOStream                  &quiet)
    {
      std::vector<eigen::EigenPair> driving;
      for (unsigned int k = 0; k < pairs.size(); ++k)
        if (above.empty() || above[k])
          driving.push_back(pairs[k]);
      const Vector<double> sum = mode_indicator(driving, p0, weights);
      Vector<float>        indicator(sum.size());
      for (unsigned int c = 0; c < sum.size(); ++c)
        indicator[c] = std::sqrt(sum[c]);
      model->refine(indicator,
                    prm.mesh.refinement_fraction,
                    prm.mesh.marking == "error",
                    quiet);
    }

    // Adaptive refinement before the sweep (Mesh/Adaptive cycles, and
    // Mesh/Frequency tolerance): the first sweep point by the full solver
    // on each mesh, the relative change of each mode's frequency from the
    // previous mesh (the same mode found by its shape) printed and written
    // to adaptive_cycles.csv, then the error indicator on the modes marks
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
      const auto        &es   = prm.eigensolver;
      eigen::BandOptions band = band_options();
      // the richer models solve a wider band, so that a partner that moved
      // across a band edge is still found
      eigen::BandOptions wide = band;
      wide.f_min *= 0.95;
      wide.f_max *= 1.05;
      const auto in_band = [&](const double f) {
        return f > 1.02 * es.f_min && f < 0.98 * es.f_max;
      };
      const parameters::ScalarPoint p0 = sweep_points().front();
      std::vector<double>           f_prev;
      std::vector<std::vector<std::complex<double>>> prev_shapes;
      std::vector<dealii::Point<3>>                  prev_points;
      std::vector<unsigned int>                      prev_component;
      std::ostringstream                             table, per_mode;
      table << cycles_header;
      per_mode << modes_header;
      ConditionalOStream quiet(std::cout, false);
      // the last h-refinement step: DoFs before and after, the largest
      // estimate before
      struct
      {
        types::global_dof_index dofs_before     = 0;
        double                  estimate_before = 0.;
        types::global_dof_index dofs_after      = 0;
      } h_step;
      std::vector<eigen::EigenPair>                  pairs;
      std::vector<std::vector<std::complex<double>>> shapes;
      std::vector<Partner>                           estimate;
      unsigned int                                   cycle   = 0;
      bool                                           reached = false;
      for (;; ++cycle)
        {
          // A cycle that is not the last (a fixed number of cycles) only
          // drives the indicator, for which the projection on the basis
          // is accurate enough (relative residuals 1e-9 to 1e-5, the
          // changes between meshes 1e-4 and more): no refinement rounds.
          // The last cycle's solve is the sweep's first point.
          const bool         last = by_tolerance || cycle == m.adaptive_cycles;
          eigen::BandOptions cycle_band = band;
          eigen::FullSolveReport report;
          if (!last)
            cycle_band.max_rounds = 0;
          pairs = eigen::solve_full(model->parts(),
                                    p0,
                                    cycle_band,
                                    quiet,
                                    &report,
                                    &first_point_symmetric);
          std::vector<double> f;
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
          // this mesh's support points: the new side of the comparison now,
          // the old side after the refinement
          auto [points, component] = physics::dof_support_points(*model);
          const MeshChange change  = f_prev.empty() ?
                                       MeshChange() :
                                       change_from_previous(f,
                                                           shapes,
                                                           points,
                                                           component,
                                                           f_prev,
                                                           prev_shapes,
                                                           prev_points,
                                                           prev_component,
                                                           in_band);
          report_cycle(pcout, table, cycle, *model, report, f.size(), change);

          // the error estimate: the same mesh at degree + 1
          std::vector<bool>       above(pairs.size(), false);
          types::global_dof_index rich_dofs = 0;
          double                  worst     = 0.;
          if (by_tolerance)
            {
              const CycleEstimate ce = estimate_at_higher_degree(
                *model, pairs, shapes, p0, wide, m, f, in_band);
              estimate  = ce.estimate;
              above     = ce.above;
              rich_dofs = ce.rich_dofs;
              worst     = ce.worst;
              report_estimate(
                pcout, table, ce, model->fe.degree + 1, m.frequency_tolerance);
              reached = ce.n_above == 0;
            }
          else
            table << ",,,,,";
          table << ',' << model->fe.degree << '\n';
          if (reached || cycle == m.adaptive_cycles)
            break;
          if (by_tolerance && m.degree_adaptivity &&
              h_step.dofs_after == model->n_dofs() && h_step.dofs_before > 0 &&
              raise_degree(h_step.dofs_before,
                           h_step.estimate_before,
                           worst,
                           rich_dofs,
                           quiet))
            {
              f_prev         = f;
              prev_shapes    = std::move(shapes);
              prev_points    = std::move(points);
              prev_component = std::move(component);
              continue;
            }
          h_step = {model->n_dofs(), worst, 0};
          // the modes above the tolerance drive the refinement, each scaled
          // to its estimated error (all modes, unscaled, without one)
          std::vector<double> weights;
          if (by_tolerance)
            for (unsigned int k = 0; k < pairs.size(); ++k)
              if (above[k])
                weights.push_back(estimate[k].difference);
          f_prev         = f;
          prev_shapes    = std::move(shapes); // reassigned by the next solve
          prev_points    = std::move(points);
          prev_component = std::move(component);
          refine_by_modes(pairs,
                          by_tolerance ? above : std::vector<bool>(),
                          weights,
                          p0,
                          quiet);
          h_step.dofs_after = model->n_dofs();
        }
      if (by_tolerance)
        report_tolerance(
          pcout, m.frequency_tolerance, reached, cycle, model->n_dofs());

      // the estimate checked against degree + 2 on the final mesh
      const std::vector<Partner> check =
        m.check_estimate ?
          check_estimate(
            *model, pairs, shapes, p0, wide, estimate, in_band, pcout) :
          std::vector<Partner>();
      if (by_tolerance)
        write_mode_estimates(per_mode, cycle, pairs, estimate, check);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          io::OutputFile(work_dir + "/adaptive_cycles.csv") << table.str();
          if (by_tolerance)
            io::OutputFile(work_dir + "/adaptive_modes.csv") << per_mode.str();
        }
      // the last cycle solved the sweep's first point on the final mesh
      first_point_full = std::move(pairs);
    }
  } // namespace analyses
} // namespace squeal
