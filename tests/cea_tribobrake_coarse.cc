// The TriboBrake on a coarse mesh (degree 1), through the full and the
// reduced solvers:
// - A5: at mu = 0 and mu = 0.01 no eigenvalue in 0.9-20 kHz has a positive
//   real part, at E_pad = 1e9, 1e10, 1e11 Pa (thesis § 3.3.2);
// - reduced against full (verification A6) at (25 GPa, 0.5) and
//   (40 GPa, 0.2): every full eigenvalue of the band has a reduced one with
//   frequency within 0.1 % and growth rate within 2 % of |Re| + 1 1/s;
// - the eigenvalues of the first point are printed to 8 digits: the
//   .mpirun=2 variant must reproduce the serial ones (numdiff, 1e-8).

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/reduced_model.h>
#include <squeal/physics/structural_model.h>

#include "test_tools.h"

using namespace dealii;
using namespace squeal;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using test_tools::check;
  ConditionalOStream pcout(std::cout,
                           Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) ==
                             0);
  ConditionalOStream quiet(std::cout, false);

  const parameters::AllParameters prm = test_tools::coarse_tribobrake();
  physics::StructuralModel        model(prm, MPI_COMM_WORLD);
  model.setup_and_assemble(quiet);
  const auto parts    = model.parts();
  const auto at_point = [&](const double E, const double mu) {
    parameters::ScalarPoint p = model.scene->nominal_point();
    p.set("pad.E", E);
    p.set("pad on disc.mu", mu);
    return p;
  };
  eigen::BandOptions band{900., 20000., 100., 1e-10, 60};

  for (const double mu : {0., 0.01})
    for (const double E : {1e9, 1e10, 1e11})
      {
        double max_re = -1e300;
        for (const auto &p :
             eigen::solve_full(parts, at_point(E, mu), band, quiet))
          max_re = std::max(max_re, p.lambda.real());
        check("A5 mu = " + std::to_string(mu).substr(0, 4) + ", E_pad = " +
                std::to_string(int(E / 1e9)) + " GPa: largest Re lambda <= 0",
              std::max(max_re, 0.),
              0.,
              0.,
              1.);
      }

  eigen::ReducedModel reduced;
  reduced.build(parts,
                {at_point(1e9, 0), at_point(1e10, 0), at_point(1e11, 0)},
                band,
                1.5,
                true,
                quiet);
  bool first = true;
  for (const auto &[E, mu] : {std::pair{25e9, 0.5}, std::pair{40e9, 0.2}})
    {
      const auto full = eigen::solve_full(parts, at_point(E, mu), band, quiet);
      const auto red  = reduced.solve(at_point(E, mu), 900., 20000.);
      double     df = 0, dre = 0, residual = 0;
      for (const auto &f : full)
        {
          const eigen::ReducedEigenPair *best = nullptr;
          for (const auto &r : red)
            if (!best || std::abs(r.lambda - f.lambda) <
                           std::abs(best->lambda - f.lambda))
              best = &r;
          if (!best)
            continue;
          df       = std::max(df,
                        std::abs(best->lambda.imag() - f.lambda.imag()) /
                          f.lambda.imag());
          dre      = std::max(dre,
                         std::abs(best->lambda.real() - f.lambda.real()) /
                           (std::abs(f.lambda.real()) + 1.));
          residual = std::max(residual, f.residual);
        }
      const std::string at = " at E_pad = " + std::to_string(int(E / 1e9)) +
                             " GPa, mu = " + std::to_string(mu).substr(0, 3);
      check("full solver modes in the band" + at + " (at least 40)",
            std::min<double>(full.size(), 40),
            40,
            0);
      check("full solver residuals below 1e-6" + at,
            std::max(residual, 1e-6),
            1e-6,
            0);
      check("reduced frequency error below 0.1 %" + at,
            std::max(df, 1e-3),
            1e-3,
            0);
      check("reduced growth-rate error below 2 % of |Re| + 1" + at,
            std::max(dre, 2e-2),
            2e-2,
            0);
      if (first)
        {
          pcout << "Eigenvalues" << at << " (1/s):" << std::endl;
          for (unsigned int k = 0; k < std::min<std::size_t>(12, full.size());
               ++k)
            pcout << std::setprecision(10) << "  " << full[k].lambda.real()
                  << " " << full[k].lambda.imag() << std::endl;
          first = false;
        }
    }
  return test_tools::finish();
}
