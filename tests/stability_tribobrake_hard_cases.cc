// Numerical stability of the TriboBrake CEA on hard cases (coarse mesh,
// degree 1). For each case the full solver's eigenpairs must have relative
// residuals below 1e-6 on the full model, and a reduced model built at the
// case's own structural parameters (one and two levels of friction
// enrichment) must reproduce every full eigenvalue of the band (0.1 % in
// frequency, 2 % of |Re| + 1 1/s in growth rate: no mode missed by either).
// Cases: very high friction (mu = 1, 2), very soft and very stiff pads
// (E_pad = 1e8, 1e12 Pa), a very stiff and a very soft interface (1e14,
// 1e9 N/m^3). Without the interface enrichment K^-1 K_n Phi of the basis
// (Rayleigh damping beta K_s is not proportional to K_s + K_n) mu = 2,
// E_pad = 1e8 and k_n = 1e14 failed here with 18 %, 5 % and 3 %. The
// conditioning of each case (interface against structural stiffness) and the
// errors go to hard_cases_report.txt in the test's directory.
// Also: a near-free support (springs 1e-6 N/m, band from 1 Hz) has no
// unstable eigenvalue below 100 Hz; and the (n,m+) / (n,m-) members of the
// doublets split by the pad are never swapped by the tracker over an E_pad
// sweep (wherever a mode has a successor of MAC > 0.5 and another mode lies
// within 2 % in frequency of the tracked one, the tracked link has the larger
// MAC).

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/reduced_model.h>
#include <squeal/eigen/tracking.h>
#include <squeal/physics/structural_model.h>

#include "test_tools.h"

#include <fstream>

using namespace dealii;
using namespace squeal;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using test_tools::check;
  ConditionalOStream quiet(std::cout, false);
  // the measured conditioning and errors, for the record (not compared)
  std::ofstream      report("hard_cases_report.txt");
  ConditionalOStream err(report,
                         Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0);

  const parameters::AllParameters prm = test_tools::coarse_tribobrake();
  physics::StructuralModel        model(prm, MPI_COMM_WORLD);
  model.setup_and_assemble(quiet);
  const auto               parts = model.parts();
  const eigen::BandOptions band{900., 20000., 100., 1e-10, 60};

  const auto at = [&](const double E, const double mu, const double kn) {
    parameters::ScalarPoint p = model.scene->nominal_point();
    p.set("pad.E", E);
    p.set("pad on disc.mu", mu);
    p.set("pad on disc.k_n", kn);
    return p;
  };
  struct Case
  {
    std::string             name;
    parameters::ScalarPoint point;
  };
  const double kn = prm.interface.normal_stiffness;
  for (const Case &c : {Case{"mu = 1", at(25e9, 1., kn)},
                        Case{"mu = 2", at(25e9, 2., kn)},
                        Case{"E_pad = 1e8 Pa", at(1e8, 0.5, kn)},
                        Case{"E_pad = 1e12 Pa", at(1e12, 0.5, kn)},
                        Case{"k_n = 1e14 N/m^3", at(25e9, 0.5, 1e14)},
                        Case{"k_n = 1e9 N/m^3", at(25e9, 0.5, 1e9)}})
    {
      const auto full     = eigen::solve_full(parts, c.point, band, quiet);
      double     residual = 0, max_re = -1e300;
      for (const auto &f : full)
        {
          residual = std::max(residual, f.residual);
          max_re   = std::max(max_re, f.lambda.real());
        }
      // reduced with 1 and 2 enrichment levels: largest frequency and
      // growth-rate errors against the full solver
      std::array<double, 3> df{}, dre{};
      for (const unsigned int depth : {1u, 2u})
        {
          eigen::ReducedModel reduced;
          reduced.build(parts, {c.point}, band, 1.5, depth, quiet);
          const auto red = reduced.solve(c.point, 900., 20000.);
          for (const auto &f : full)
            {
              const eigen::ReducedEigenPair *best = nullptr;
              for (const auto &r : red)
                if (!best || std::abs(r.lambda - f.lambda) <
                               std::abs(best->lambda - f.lambda))
                  best = &r;
              if (!best)
                {
                  df[depth] = 1;
                  continue;
                }
              df[depth] =
                std::max(df[depth],
                         std::abs(best->lambda.imag() - f.lambda.imag()) /
                           f.lambda.imag());
              dre[depth] =
                std::max(dre[depth],
                         std::abs(best->lambda.real() - f.lambda.real()) /
                           (std::abs(f.lambda.real()) + 1.));
            }
        }
      // conditioning indicators
      physics::PETScMatrix Ks, Ki;
      const auto           coeff = parts.coefficients(c.point);
      auto structural = coeff.structural, interface = coeff.stiffness;
      for (unsigned int k = 0; k < parts.size(); ++k)
        interface[k] -= structural[k];
      parts.combine(structural, Ks);
      parts.combine(interface, Ki);
      err << c.name << ": " << full.size() << " modes in the band, "
          << "interface/structural stiffness (Frobenius) "
          << Ki.frobenius_norm() / Ks.frobenius_norm() << ", largest residual "
          << residual << ", largest Re " << max_re
          << " 1/s; reduced-full, depth 1: " << df[1] << " / " << dre[1]
          << ", depth 2: " << df[2] << " / " << dre[2] << std::endl;
      check(c.name + ": full solver finds modes in the band",
            std::min<double>(full.size(), 20),
            20,
            0);
      check(c.name + ": full residuals below 1e-6",
            std::max(residual, 1e-6),
            1e-6,
            0);
      for (const unsigned int depth : {1u, 2u})
        {
          const std::string d =
            " (enrichment depth " + std::to_string(depth) + ")";
          check(c.name + ": reduced frequencies within 0.1 % of full" + d,
                std::max(df[depth], 1e-3),
                1e-3,
                0);
          check(c.name + ": reduced growth rates within 2 % of |Re| + 1" + d,
                std::max(dre[depth], 2e-2),
                2e-2,
                0);
        }
    }

  // near-free support
  {
    parameters::ScalarPoint p = at(25e9, 0.5, kn);
    p.set("support springs.k", 1e-6);
    eigen::BandOptions low = band;
    low.f_min              = 1.;
    low.target_frequency   = 0.5;
    const auto   full      = eigen::solve_full(parts, p, low, quiet);
    unsigned int spurious = 0, near_zero = 0;
    for (const auto &f : full)
      if (f.lambda.imag() / (2 * M_PI) < 100.)
        {
          ++near_zero;
          spurious += f.lambda.real() > 1e-3;
        }
    err << "near-free support: " << full.size() << " modes in 1-20000 Hz, "
        << near_zero << " below 100 Hz" << std::endl;
    check("near-free support: no unstable eigenvalue below 100 Hz",
          spurious,
          0,
          0);
  }

  // doublets split by the pad, tracked over E_pad at mu = 0
  {
    eigen::ReducedModel reduced;
    reduced.build(parts,
                  {at(1e9, 0, kn), at(1e10, 0, kn), at(1e11, 0, kn)},
                  band,
                  1.5,
                  true,
                  quiet);
    std::vector<std::vector<std::complex<double>>> lambdas;
    std::vector<std::vector<Eigen::VectorXcd>>     q;
    std::vector<Eigen::MatrixXd>                   macs;
    for (unsigned int k = 0; k < 13; ++k)
      {
        const double E = 1e9 * std::pow(100., k / 12.);
        lambdas.emplace_back();
        q.emplace_back();
        for (const auto &r : reduced.solve(at(E, 0., kn), 900., 20000.))
          {
            lambdas.back().push_back(r.lambda);
            q.back().push_back(r.q);
          }
        macs.push_back(k > 0 ? test_tools::mac_matrix(q[k - 1], q[k]) :
                               Eigen::MatrixXd());
      }
    int          next        = 0;
    const auto   tracks      = eigen::track_modes(lambdas, macs, next);
    unsigned int close_links = 0, swapped = 0;
    for (unsigned int k = 1; k < tracks.size(); ++k)
      for (unsigned int i = 0; i < tracks[k - 1].size(); ++i)
        for (unsigned int j = 0; j < tracks[k].size(); ++j)
          if (tracks[k][j] == tracks[k - 1][i])
            for (unsigned int o = 0; o < tracks[k].size(); ++o)
              if (o != j &&
                  std::abs(lambdas[k][o].imag() - lambdas[k][j].imag()) <
                    0.02 * lambdas[k][j].imag() &&
                  std::max(macs[k](i, j), macs[k](i, o)) > 0.5)
                {
                  ++close_links;
                  if (macs[k](i, o) > macs[k](i, j))
                    {
                      ++swapped;
                      err << "swap at point " << k << ": " << lambdas[k - 1][i]
                          << " -> " << lambdas[k][j] << " (MAC "
                          << macs[k](i, j) << "), not " << lambdas[k][o]
                          << " (MAC " << macs[k](i, o) << ")" << std::endl;
                    }
                }
    err << "doublets: " << close_links
        << " tracked links with a mode within 2 % in frequency" << std::endl;
    check("doublets: close pairs exist in the sweep", close_links > 10, 1, 0);
    check("doublets: no member swapped by the tracker", swapped, 0, 0);
  }
  return test_tools::finish();
}
