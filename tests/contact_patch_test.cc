// Verification B1, the contact patch test: two elastic blocks of different
// materials pressed together through non-matching interface meshes by a
// uniform pressure p on the top face. The exact solution is a uniform
// stress state sigma_zz = -p, so the dual mortar multipliers must equal p at
// every slave node to 1e-8 relative (a node-to-segment scheme fails this),
// for degree 1 and 2 and with the finer mesh on either side. Also the
// mortar operators alone: D sums to the slave area, the rows of M to D.
// And B5 in the static solver: steady sliding with mu = 0.25, 0.5, 1 gives
// a tangential force mu N, checked against the reaction on the upper
// block's restraint (an independent sum of K u - f - f_contact over it).

#include <squeal/contact/contact_solver.h>
#include <squeal/contact/mortar.h>

#include "check.h"
#include "contact_two_blocks.h"

#include <set>
#include <sstream>

using namespace dealii;
using namespace squeal::contact;
using test_tools::check;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double                     p = 0.625; // Pa (scaled units)

  struct Case
  {
    unsigned int degree, upper, lower;
  };
  for (const Case c :
       {Case{1, 5, 3}, Case{1, 3, 4}, Case{2, 3, 2}, Case{2, 2, 3}})
    {
      std::ostringstream name;
      name << "degree " << c.degree << ", slave " << c.upper << "x" << c.upper
           << " on master " << c.lower << "x" << c.lower << ": ";
      TwoBlocks             b(c.degree,
                  c.upper,
                  c.lower,
                  200.,
                  0.3,
                  100.,
                  0.25,
                  Tensor<1, 3>({0., 0., -p}));
      const MortarOperators op =
        build_mortar_operators(b.dofs, b.mapping, 10, 11, 0.1);
      double d_sum = 0., row_error = 0.;
      for (unsigned int j = 0; j < op.n_slave(); ++j)
        {
          d_sum += op.D[j];
          double r = 0.;
          for (const auto &[l, m] : op.M[j])
            r += m;
          row_error = std::max(row_error, std::abs(r - op.D[j]) / op.D[j]);
        }
      check(name.str() + "sum of D = slave area 1 m^2", d_sum, 1., 1e-12);
      check(name.str() + "rows of M sum to D", row_error, 0., 1e-12, 1.);
      check(name.str() + "covered area 1 m^2", op.covered_area, 1., 1e-12);

      ContactSettings       settings;
      std::ostringstream    log;
      const ContactSolution s =
        solve_static_contact(b.K, b.f, b.constraints, op, settings, &log);
      double       worst    = 0.;
      unsigned int n_active = 0;
      for (unsigned int j = 0; j < op.n_slave(); ++j)
        {
          worst = std::max({worst,
                            std::abs(s.pressure[j] - p) / p,
                            std::abs(s.nodal_pressure[j] - p) / p});
          n_active += s.status[j] != 0;
        }
      test_tools::verbose()
        << name.str() << log.str() << "  largest relative error " << worst
        << std::endl;
      check(name.str() + "every slave node in contact",
            n_active,
            op.n_slave(),
            0.);
      check(name.str() + "multipliers and nodal pressures = p to 1e-8",
            worst,
            0.,
            1e-8,
            1.);
      check(name.str() + "normal force = p x area", s.normal_force, p, 1e-10);
      check(name.str() + "active set settles in 1 iteration",
            s.history.size(),
            1.,
            0.);
    }

  // B5: steady sliding of the upper block, dragged along +x by the lower
  // one; the upper block is held at x = 0 (boundary id 3), whose reaction
  // must balance the friction force mu N.
  for (const double mu : {0.25, 0.5, 1.0})
    {
      TwoBlocks b(1, 4, 3, 200., 0.3, 100., 0.25, Tensor<1, 3>({0., 0., -p}));
      const MortarOperators op =
        build_mortar_operators(b.dofs, b.mapping, 10, 11, 0.1);
      ContactSettings settings;
      settings.friction             = FrictionModel::steady_sliding;
      settings.friction_coefficient = mu;
      settings.sliding_direction    = Tensor<1, 3>({1., 0., 0.});
      const ContactSolution s =
        solve_static_contact(b.K, b.f, b.constraints, op, settings);
      const std::string name = "B5 mu = " + std::to_string(mu).substr(0, 4);
      check(name + ": normal force N = p x area", s.normal_force, p, 1e-10);
      check(name + ": friction force = mu N",
            s.tangential_force,
            mu * s.normal_force,
            1e-12);
      check(name + ": restraint reaction balances mu N",
            -b.reaction(s.displacement, s.contact_force, 3, 0, 0),
            mu * s.normal_force,
            1e-9);
      unsigned int slipping = 0;
      for (int st : s.status)
        slipping += st == 2;
      check(name + ": every node slips", slipping, op.n_slave(), 0.);
    }
  // Bad input: one clear error each.
  const auto error_of = [](auto &&run) {
    try
      {
        run();
      }
    catch (const std::exception &e)
      {
        return std::string(e.what());
      }
    return std::string();
  };
  {
    TwoBlocks b(1, 3, 2, 200., 0.3, 100., 0.25, Tensor<1, 3>({0., 0., -p}));
    const MortarOperators op =
      build_mortar_operators(b.dofs, b.mapping, 10, 11, 0.1);
    ContactSettings negative;
    negative.friction_coefficient = -0.1;
    check("mu < 0 is refused",
          error_of([&] {
            solve_static_contact(b.K, b.f, b.constraints, op, negative);
          }).find("friction coefficient must not be negative") !=
            std::string::npos,
          1.,
          0.);
    check("a slave surface with no master face in reach is refused",
          error_of([&] {
            build_mortar_operators(b.dofs, b.mapping, 10, 2, 0.1);
          }).find("no slave face") != std::string::npos,
          1.,
          0.);
    TwoBlocks pulled(1, 3, 2, 200., 0.3, 100., 0.25, Tensor<1, 3>({0., 0., p}));
    const MortarOperators op2 =
      build_mortar_operators(pulled.dofs, pulled.mapping, 10, 11, 0.1);
    check("a body pulled off (held by nothing) is reported, not solved",
          error_of([&] {
            solve_static_contact(
              pulled.K, pulled.f, pulled.constraints, op2, ContactSettings());
          }).find("is singular") != std::string::npos,
          1.,
          0.);
    TwoBlocks overlap(
      1, 3, 2, 200., 0.3, 100., 0.25, Tensor<1, 3>({0., 0., -p}), -0.05);
    check("bodies overlapping beyond the search distance are refused",
          error_of([&] {
            build_mortar_operators(overlap.dofs, overlap.mapping, 10, 11, 0.01);
          }).find("the bodies overlap by 0.05") != std::string::npos,
          1.,
          0.);
  }
  return test_tools::finish();
}
