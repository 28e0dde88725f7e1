// Verification B3, Cattaneo-Mindlin partial slip in plane strain: the
// cylinder of the Hertz test (R = 8, E = 200, nu = 0.3, P = 2 R p = 10 per
// unit length) on a rigid flat with Coulomb friction mu = 0.2, first pressed
// without friction, then pulled along y by Q = 2 R q = 0.93616 per unit
// length, below sliding (Q / mu P = 0.468), through a rigid plate on its top
// that keeps it from rolling (Cattaneo's solution has no rotation). Stick zone
// half-width c = b sqrt(1 - Q / (mu P)) = 0.4965; tangential traction
//   q(y) = mu p0 / b (sqrt(b^2 - y^2) - sqrt(c^2 - y^2))   for |y| < c,
//   q(y) = mu p0 / b  sqrt(b^2 - y^2)                        for c < |y| < b.
// Checks: c within one element, the traction profile within 5 % of mu p0
// (RMS over the contact zone), equilibrium along y, every stuck node
// inside the cone and every slipping one on it, and the active-set
// iterations per load step below a stated bound.

#include <squeal/contact/contact_solver.h>
#include <squeal/contact/mortar.h>

#include "check.h"
#include "contact_cylinder.h"

#include <sstream>

using namespace dealii;
using namespace squeal::contact;
using test_tools::check;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double R = 8., P = 10., Q = 0.93616, mu = 0.2, E = 200., nu = 0.3;
  const double E_star  = E / (1. - nu * nu);
  const double b       = std::sqrt(4. * P * R / (M_PI * E_star)),
               p0      = 2. * P / (M_PI * b),
               c_exact = b * std::sqrt(1. - Q / (mu * P));
  check("Cattaneo stick half-width c = 0.4965", c_exact, 0.4965, 1e-4);

  const double          h0 = 0.04;
  CylinderOnFlat        cyl(R, E, nu, 6., 6., h0, false, P, Q, true);
  const MortarOperators op =
    build_mortar_operators(cyl.dofs, cyl.mapping, 10, 11, 1.0);

  // 1. normal load, frictionless (Cattaneo's solution has no tangential
  // traction from the normal load; a rigid flat under an elastic body would
  // otherwise lock in Goodman's tractions), the top plate held along y
  CylinderOnFlat        held(R, E, nu, 6., 6., h0, false, P, Q, true, true);
  const MortarOperators op_held =
    build_mortar_operators(held.dofs, held.mapping, 10, 11, 1.0);
  const ContactSolution pressed = solve_static_contact(
    held.K, held.f_normal, held.constraints, op_held, ContactSettings());
  // 2. the plate released and pulled, Coulomb friction
  ContactSettings settings;
  settings.friction             = FrictionModel::coulomb;
  settings.friction_coefficient = mu;
  // 2. the tangential load added in 8 steps (Coulomb friction is path
  // dependent: Cattaneo's loading is monotonic), slip measured from step
  // to step
  Vector<double> f = cyl.f_normal;
  f += cyl.f_tangential;
  std::ostringstream    log;
  const ContactSolution s =
    solve_contact_load_steps(cyl.K,
                             cyl.f_normal,
                             f,
                             pressed,
                             cyl.constraints,
                             op,
                             settings,
                             8,
                             6,
                             std::getenv("SQUEAL_VERBOSE") ? &std::cerr : &log);
  test_tools::verbose() << cyl.dofs.n_dofs() << " DoFs: pressed in "
                        << pressed.history.size()
                        << " active-set iterations, pulled in 8 load steps, "
                        << s.history.size() << " iterations in all\n";

  // Along the mid-plane x = 0: the stick zone and the traction profile.
  double       c_found = 0., sq = 0., inside = 0., on_cone = 0.;
  unsigned int n_profile = 0, n_stick = 0, n_slip = 0;
  for (unsigned int j = 0; j < op.n_slave(); ++j)
    {
      const double y = op.slave_points[j][1];
      // traction along +y (the frame's tangents are +-x and +-y here)
      const Tensor<1, 3> t = s.tangential_traction[j][0] * op.tangents1[j] +
                             s.tangential_traction[j][1] * op.tangents2[j];
      if (s.status[j] == 1)
        {
          ++n_stick;
          inside = std::max(inside, t.norm() - mu * s.pressure[j]);
        }
      if (s.status[j] == 2)
        {
          ++n_slip;
          on_cone = std::max(on_cone, std::abs(t.norm() - mu * s.pressure[j]));
        }
      if (std::abs(op.slave_points[j][0]) > 1e-12 || s.status[j] == 0)
        continue;
      if (s.status[j] == 1)
        c_found = std::max(c_found, std::abs(y));
      if (std::abs(y) < b)
        {
          const double exact =
            mu * p0 / b *
            (std::sqrt(b * b - y * y) -
             (std::abs(y) < c_exact ? std::sqrt(c_exact * c_exact - y * y) :
                                      0.));
          // the body is pulled along +y: the flat's friction on it acts
          // along -y
          sq += std::pow(-t[1] - exact, 2);
          test_tools::verbose()
            << "  y " << y << ": traction " << -t[1] << ", Cattaneo " << exact
            << ", status " << s.status[j] << std::endl;
          ++n_profile;
        }
    }
  double fy_slave = 0., fy_stick = 0., fy_slip = 0.;
  for (unsigned int j = 0; j < op.n_slave(); ++j)
    {
      fy_slave += s.contact_force[op.slave_dofs[j][1]];
      const Tensor<1, 3> t = s.tangential_traction[j][0] * op.tangents1[j] +
                             s.tangential_traction[j][1] * op.tangents2[j];
      (s.status[j] == 1 ? fy_stick : fy_slip) += op.D[j] * t[1];
    }
  test_tools::verbose() << "y forces: on slave dofs " << fy_slave << ", stick "
                        << fy_stick << ", slip " << fy_slip << ", applied "
                        << Q * h0 << std::endl;
  const double rms = std::sqrt(sq / std::max(1u, n_profile)) / (mu * p0);
  const double h_c = cyl.cell_size_at(c_exact);
  test_tools::verbose() << "stick half-width " << c_found << " (c " << c_exact
                        << ", element " << h_c << "), traction RMS error "
                        << rms << " of mu p0, " << n_stick << " stick, "
                        << n_slip << " slip nodes" << std::endl;
  check("stick half-width within one element of c", c_found, c_exact, 1., h_c);
  check("tangential traction within 5 % of mu p0 (RMS)",
        std::min(rms, 0.05),
        rms,
        0.);
  // equilibrium along y: the contact forces on the cylinder (tangential and,
  // on its curved face, normal) carry Q
  check("contact force along y on the cylinder = -Q per unit length",
        -fy_slave / h0,
        Q,
        1e-8);
  check("stuck nodes inside the cone", std::max(inside, 0.), 0., 1e-9, p0);
  check("slipping nodes on the cone", on_cone, 0., 1e-9, p0);
  check("stick and slip zones both present", n_stick > 0 && n_slip > 0, 1., 0.);
  check("at most 12 active-set iterations per load step on average",
        std::min<double>(s.history.size() / 8., 12.),
        s.history.size() / 8.,
        0.);
  return test_tools::finish();
}
