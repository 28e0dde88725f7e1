// Verification B5 in the transient code: an elastic block (slave, on top)
// pressed by a ramped uniform pressure p on a lower block (master) whose
// surface slides under it at V along x (the master's rigid velocity, as the
// disc's rotation in a braking run); the upper block is held along x on its
// face x = 0. Once the load is held and the vibration has died out
// (Rayleigh alpha), every contact node slips and the friction force is
// mu N (N = p x area) for mu = 0.25, 0.5 and 1, balanced by the reaction of
// the hold, with non-matching interface meshes (4 x 4 on 3 x 3 cells).

#include <squeal/contact/mortar.h>
#include <squeal/transient/explicit_dynamics.h>

#include "check.h"
#include "contact_two_blocks.h"

#include <cmath>
#include <iostream>

int
main(int argc, char **argv)
{
  using namespace dealii;
  using namespace squeal;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double                     p = 0.05, V = 0.1;
  TwoBlocks  b(1, 4, 3, 200., 0.3, 100., 0.25, Tensor<1, 3>({0., 0., -p}));
  const auto mortar =
    contact::build_mortar_operators(b.dofs, b.mapping, 10, 11, 0.1);
  const Vector<double> mass =
    transient::lumped_mass(b.dofs, b.mapping, [](const auto &) { return 1.; });
  std::vector<bool> fixed(b.dofs.n_dofs());
  for (unsigned int i = 0; i < fixed.size(); ++i)
    fixed[i] = b.constraints.is_constrained(i);
  const auto limit = transient::stable_time_step(b.K, mass, fixed, 0., 0.5);

  for (const double mu : {0.25, 0.5, 1.})
    {
      transient::ExplicitSettings s;
      s.time_step            = 0.9 * limit.critical;
      s.alpha                = 2.;
      s.friction_coefficient = mu;
      transient::ExplicitDynamics d(b.K, mass, fixed, s, limit.critical);
      d.set_contact(mortar, [V](const Point<3> &) {
        return Tensor<1, 3>({V, 0., 0.});
      });
      Vector<double> zero(b.dofs.n_dofs()), f(b.dofs.n_dofs());
      d.initialise(zero, zero);
      const double T_ramp = 10., T_end = 40.;
      double       F_N = 0, F_T = 0, hold = 0;
      unsigned int n_avg = 0, n_slip_min = mortar.n_slave();
      for (unsigned int k = 0; k * s.time_step < T_end; ++k)
        {
          f               = b.f;
          const double tn = k * s.time_step;
          f *=
            tn >= T_ramp ? 1. : 0.5 * (1 - std::cos(numbers::PI * tn / T_ramp));
          d.step(f);
          if (d.time() > T_end - 5.)
            {
              F_N += d.contact_state().normal_force;
              F_T += d.contact_state().force[0];
              // the reaction of the hold at x = 0 of the upper block: the
              // contact forces of the multipliers enter the balance of the
              // nodes on both faces
              const auto    &c = d.contact_state();
              Vector<double> f_contact(b.dofs.n_dofs());
              for (unsigned int j = 0; j < mortar.n_slave(); ++j)
                {
                  const Tensor<1, 3> P =
                    c.pressure[j] * mortar.normals[j] - c.traction[j];
                  for (unsigned int k = 0; k < 3; ++k)
                    {
                      f_contact[mortar.slave_dofs[j][k]] -= mortar.D[j] * P[k];
                      for (const auto &[l, w] : mortar.M[j])
                        f_contact[mortar.master_dofs[l][k]] += w * P[k];
                    }
                }
              const dealii::Vector<double> u(d.displacement().begin(),
                                             d.displacement().end());
              hold += b.reaction(u, f_contact, 3, 0, 0);
              ++n_avg;
              n_slip_min = std::min(n_slip_min, d.contact_state().n_slip);
            }
        }
      F_N /= n_avg;
      F_T /= n_avg;
      hold /= n_avg;
      const std::string m = "mu = " + std::to_string(mu).substr(0, 4) + ": ";
      test_tools::verbose()
        << m << "F_N " << F_N << " (p A = " << p << "), F_T " << F_T
        << ", hold " << hold << ", slipping nodes >= " << n_slip_min << " of "
        << mortar.n_slave() << "\n";
      test_tools::check(m + "normal force = p x area (1 %)", F_N, p, 0.01);
      test_tools::check(m + "friction force = mu N (1 %)", F_T, mu * F_N, 0.01);
      test_tools::check(m + "the hold balances the friction (2 %)",
                        -hold,
                        F_T,
                        0.02);
      test_tools::check(m + "every contact node slips",
                        n_slip_min,
                        mortar.n_slave(),
                        0.);
    }
  return test_tools::finish();
}
