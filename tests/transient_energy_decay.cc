// Verification B6 on the clamped disc (coarse, degree 1, lumped mass), no
// contact:
// 1. without damping, central differences (beta2 = 1/2) conserve the
//    modified energy H = 1/2 v'Mv + 1/2 u'Ku - dt^2/8 a'Ma exactly for a
//    linear system: its drift over 1e5 steps stays below 1e-6 relative;
// 2. with Rayleigh damping C = alpha M + beta K, a free vibration in one
//    mode decays at the rate of the complex eigenvalue of that mode,
//    -Re lambda = (alpha + beta omega^2) / 2 (= zeta omega, verification
//    A1), and oscillates at Im lambda = sqrt(omega^2 - (Re lambda)^2),
//    omega^2 the Rayleigh quotient of the mode: both within 1 %.
// The mode is the disc's lowest axisymmetric one, (0,0), found by inverse
// iteration (UMFPACK) from an axisymmetric start.

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/sparse_direct.h>

#include <squeal/physics/structural_model.h>
#include <squeal/transient/explicit_dynamics.h>

#include "check.h"
#include "test_tools.h"

#include <cmath>
#include <iostream>
#include <map>

int
main(int argc, char **argv)
{
  using namespace dealii;
  using namespace squeal;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  parameters::AllParameters prm = test_tools::coarse_tribobrake(32, 4, 2);
  prm.scene.type                = "disc";
  ConditionalOStream       quiet(std::cout, false);
  physics::StructuralModel model(prm, MPI_COMM_WORLD);
  model.setup_and_assemble(quiet);
  const physics::MatrixParts parts = model.parts();
  physics::PETScMatrix       K_petsc;
  parts.combine(parts.coefficients(model.scene->nominal_point()).structural,
                K_petsc);
  SparsityPattern      pattern;
  SparseMatrix<double> K;
  physics::copy_to_serial(K_petsc, pattern, K);
  const unsigned int n = model.n_dofs();
  std::vector<bool>  fixed(n);
  for (unsigned int i = 0; i < n; ++i)
    fixed[i] = model.constraints.is_constrained(i);
  const Vector<double> M =
    transient::lumped_mass(model.dof_handler, model.mapping, [&](const auto &) {
      return prm.materials.disc.density;
    });

  // An axisymmetric start: u_z rising with the radius.
  std::map<types::global_dof_index, Point<3>> points;
  DoFTools::map_dofs_to_support_points(model.mapping,
                                       model.dof_handler,
                                       points);
  std::vector<bool> is_z(n, false);
  for (const auto i :
       DoFTools::extract_dofs(model.dof_handler,
                              ComponentMask({false, false, true})))
    is_z[i] = true;
  Vector<double> x(n);
  for (const auto &[i, p] : points)
    if (!fixed[i] && is_z[i])
      x[i] =
        std::pow(std::hypot(p[0], p[1]) - prm.geometry.disc_inner_radius, 2);

  // Inverse iteration on K x = omega^2 M x.
  SparseDirectUMFPACK solver;
  solver.initialize(K);
  Vector<double> y(n);
  for (unsigned int it = 0; it < 12; ++it)
    {
      for (unsigned int i = 0; i < n; ++i)
        y[i] = fixed[i] ? 0. : M[i] * x[i];
      solver.vmult(x, y);
      for (unsigned int i = 0; i < n; ++i)
        if (fixed[i])
          x[i] = 0.;
      x /= x.linfty_norm();
    }
  double xMx = 0;
  for (unsigned int i = 0; i < n; ++i)
    xMx += M[i] * x[i] * x[i];
  const double omega2 = K.matrix_norm_square(x) / xMx;
  test_tools::verbose() << n << " DoFs; mode (0,0) at "
                        << std::sqrt(omega2) / (2 * numbers::PI) << " Hz\n";

  // 1. Energy, no damping.
  const auto limit = transient::stable_time_step(K, M, fixed, 0., 0.5);
  {
    transient::ExplicitSettings s;
    s.time_step = 0.9 * limit.critical;
    transient::ExplicitDynamics d(K, M, fixed, s, limit.critical);
    Vector<double>              u0(n), v0(n);
    // a mixture of many modes: the axisymmetric start plus a cos 2 theta part
    for (const auto &[i, p] : points)
      if (!fixed[i])
        u0[i] = 1e-6 * (x[i] + (is_z[i] ? 1. : 0.3) *
                                 std::cos(2 * std::atan2(p[1], p[0])) *
                                 (std::hypot(p[0], p[1]) - 0.05) / 0.07);
    d.initialise(u0, v0);
    const Vector<double> f(n);
    double               H0 = 0, drift = 0;
    const auto           modified = [&]() {
      double aMa = 0;
      for (unsigned int i = 0; i < n; ++i)
        aMa += M[i] * d.acceleration()[i] * d.acceleration()[i];
      return d.kinetic_energy() + d.strain_energy() -
             s.time_step * s.time_step / 8. * aMa;
    };
    for (unsigned int k = 0; k < 100000; ++k)
      {
        d.step(f);
        if (k == 0)
          H0 = modified();
        else if (k % 100 == 0 || k == 99999)
          drift = std::max(drift, std::abs(modified() - H0) / H0);
      }
    test_tools::verbose() << "energy: dt " << s.time_step << " s, drift "
                          << drift << " over 1e5 steps\n";
    test_tools::check(
      "modified energy drift over 1e5 steps < 1e-6", drift, 0., 1e-6, 1.);
  }

  // 2. Decay of the (0,0) mode under Rayleigh damping.
  {
    transient::ExplicitSettings s;
    s.alpha           = 50.;
    s.beta            = 1e-6;
    const auto damped = transient::stable_time_step(K, M, fixed, s.beta, 0.5);
    s.time_step       = 0.9 * damped.critical;
    transient::ExplicitDynamics d(K, M, fixed, s, damped.critical);
    Vector<double>              u0(x), v0(n);
    u0 *= 1e-6;
    d.initialise(u0, v0);
    const Vector<double> f(n);
    std::vector<double>  t_peak, q_peak;
    double               q_prev2 = 0, q_prev = 0;
    const unsigned int   n_steps = 0.1 / s.time_step;
    for (unsigned int k = 0; k < n_steps; ++k)
      {
        d.step(f);
        double q = 0;
        for (unsigned int i = 0; i < n; ++i)
          q += M[i] * x[i] * d.displacement()[i];
        q /= xMx;
        // a local maximum of q at the previous step: refine by a parabola
        if (k >= 2 && q_prev > q_prev2 && q_prev >= q && q_prev > 0)
          {
            const double den = q_prev2 - 2 * q_prev + q;
            const double sh  = den != 0 ? 0.5 * (q_prev2 - q) / den : 0.;
            t_peak.push_back((k - 1 + sh) * s.time_step);
            q_peak.push_back(q_prev - 0.25 * (q_prev2 - q) * sh);
          }
        q_prev2 = q_prev;
        q_prev  = q;
      }
    // least squares of ln q_peak against t; period from the peak times
    double             st = 0, sy = 0, stt = 0, sty = 0;
    const unsigned int m = t_peak.size();
    for (unsigned int k = 0; k < m; ++k)
      {
        st += t_peak[k];
        sy += std::log(q_peak[k]);
        stt += t_peak[k] * t_peak[k];
        sty += t_peak[k] * std::log(q_peak[k]);
      }
    const double rate    = -(m * sty - st * sy) / (m * stt - st * st);
    const double period  = (t_peak.back() - t_peak.front()) / (m - 1);
    const double sigma   = (s.alpha + s.beta * omega2) / 2.;
    const double omega_d = std::sqrt(omega2 - sigma * sigma);
    test_tools::verbose() << "decay: dt " << s.time_step << " s, " << m
                          << " peaks, rate " << rate << " 1/s (CEA " << sigma
                          << "), frequency " << 1. / period << " Hz (CEA "
                          << omega_d / (2 * numbers::PI) << ")\n";
    test_tools::check("decay rate = (alpha + beta omega^2) / 2 (1 %)",
                      rate,
                      sigma,
                      0.01);
    test_tools::check("damped frequency = Im lambda (1 %)",
                      2 * numbers::PI / period,
                      omega_d,
                      0.01);
  }
  return test_tools::finish();
}
