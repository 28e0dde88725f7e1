// Verification B4: two identical elastic bars, one striking the other at rest
// at v0 (E = rho = 1, so c = 1; L = 1, unit cross-section, nu = 0: the
// 3D bars behave as 1D rods), 50 linear elements per bar, time step 0.9 of
// the computed stability limit, contact by forward-increment Lagrange
// multipliers on the dual mortar operators. Exact (1D wave theory): contact
// force rho c A v0 / 2 for a duration 2 L / c; the striking bar stops, the
// struck bar leaves at v0, and no energy is lost.
// Also: a time step above the limit is refused, and the limit equals the
// lumped 1D chain's 2 c / h within 1 %.

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <squeal/contact/mortar.h>
#include <squeal/transient/explicit_dynamics.h>

#include "check.h"
#include "contact_assembly.h"

#include <cmath>
#include <iostream>

int
main(int argc, char **argv)
{
  using namespace dealii;
  using namespace squeal;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int               n_el = 50;
  const double                     L = 1., v0 = 0.01, c = 1., h = L / n_el;

  Triangulation<3> a, b, tria;
  GridGenerator::subdivided_hyper_rectangle(a,
                                            {n_el, 1, 1},
                                            Point<3>(-L, 0, 0),
                                            Point<3>(0, 1, 1));
  GridGenerator::subdivided_hyper_rectangle(b,
                                            {n_el, 1, 1},
                                            Point<3>(0, 0, 0),
                                            Point<3>(L, 1, 1));
  GridGenerator::merge_triangulations(a, b, tria, 0.); // no shared vertex
  for (const auto &cell : tria.active_cell_iterators())
    {
      const bool striker = cell->center()[0] < 0;
      cell->set_material_id(striker ? 0 : 1);
      for (const auto f : cell->face_indices())
        if (cell->face(f)->at_boundary() &&
            std::abs(cell->face(f)->center()[0]) < 1e-12)
          cell->face(f)->set_boundary_id(striker ? 10 : 11);
    }
  FESystem<3>   fe(FE_Q<3>(1), 3);
  MappingQ<3>   mapping(1);
  DoFHandler<3> dofs(tria);
  dofs.distribute_dofs(fe);
  AffineConstraints<double> none;
  none.close();
  DynamicSparsityPattern dsp(dofs.n_dofs());
  DoFTools::make_sparsity_pattern(dofs, dsp);
  SparsityPattern pattern;
  pattern.copy_from(dsp);
  SparseMatrix<double> K(pattern);
  assemble_elastic_system(
    dofs,
    mapping,
    none,
    [](unsigned int) { return std::make_pair(1., 0.); },
    {},
    K);
  const Vector<double> mass =
    transient::lumped_mass(dofs, mapping, [](const auto &) { return 1.; });
  const std::vector<bool> fixed(dofs.n_dofs(), false);
  const auto              mortar =
    contact::build_mortar_operators(dofs, mapping, 10, 11, 1e-3);

  const transient::StableTimeStep limit =
    transient::stable_time_step(K, mass, fixed, 0., 0.5);
  test_tools::verbose() << "omega_max " << limit.omega_max << " (1D chain "
                        << 2 * c / h << "), dt_c " << limit.critical << "\n";
  test_tools::check("stability limit = h / c of the lumped chain (1 %)",
                    limit.critical,
                    h / c,
                    0.01);

  transient::ExplicitSettings s;
  s.time_step  = 1.01 * limit.critical;
  bool refused = false;
  try
    {
      transient::ExplicitDynamics too_large(K, mass, fixed, s, limit.critical);
    }
  catch (const std::exception &e)
    {
      refused =
        std::string(e.what()).find("stability limit") != std::string::npos;
    }
  test_tools::check("a time step above the limit is refused", refused, 1., 0.);

  s.time_step = 0.9 * limit.critical;
  transient::ExplicitDynamics bars(K, mass, fixed, s, limit.critical);
  bars.set_contact(mortar);
  Vector<double> u0(dofs.n_dofs()), vel0(dofs.n_dofs());
  // striker: every x DoF of material 0 moves at v0
  std::vector<types::global_dof_index> ids(fe.n_dofs_per_cell());
  for (const auto &cell : dofs.active_cell_iterators())
    if (cell->material_id() == 0)
      {
        cell->get_dof_indices(ids);
        for (unsigned int i = 0; i < ids.size(); ++i)
          if (fe.system_to_component_index(i).first == 0)
            vel0[ids[i]] = v0;
      }
  bars.initialise(u0, vel0);
  const Vector<double> f(dofs.n_dofs());
  const double         E0      = 0.5 * 1. * v0 * v0; // m = rho A L = 1
  double               t_first = -1, t_last = -1, impulse = 0, f_max = 0;
  double               f_sum_mid = 0;
  unsigned int         n_mid     = 0;
  const double         t_end     = 3. * L / c;
  while (bars.time() < t_end)
    {
      bars.step(f);
      const double F = bars.contact_state().normal_force;
      if (F > 0)
        {
          if (t_first < 0)
            t_first = bars.time();
          t_last = bars.time();
        }
      impulse += F * s.time_step;
      f_max = std::max(f_max, F);
      // the plateau: away from the first and last 10 % of 2 L / c
      if (bars.time() > 0.2 && bars.time() < 1.8)
        {
          f_sum_mid += F;
          ++n_mid;
        }
    }
  // momenta and velocities of each bar at the end
  double            p_striker = 0, p_struck = 0;
  std::vector<bool> seen(dofs.n_dofs(), false);
  for (const auto &cell : dofs.active_cell_iterators())
    {
      cell->get_dof_indices(ids);
      for (unsigned int i = 0; i < ids.size(); ++i)
        if (!seen[ids[i]] && fe.system_to_component_index(i).first == 0)
          {
            seen[ids[i]] = true;
            (cell->material_id() == 0 ? p_striker : p_struck) +=
              mass[ids[i]] * bars.velocity()[ids[i]];
          }
    }
  const double duration = t_last - t_first + s.time_step;
  const double F_exact  = 1. * c * 1. * v0 / 2.;
  const double energy   = bars.kinetic_energy() + bars.strain_energy();
  test_tools::verbose() << "force: plateau mean " << f_sum_mid / n_mid
                        << ", max " << f_max << ", exact " << F_exact
                        << "; impulse " << impulse << "; duration " << duration
                        << " (exact " << 2 * L / c << "); energy " << energy
                        << " of " << E0 << "; momenta " << p_striker << ", "
                        << p_struck << "\n";
  test_tools::check("contact force (plateau mean) = rho c A v0 / 2 (1 %)",
                    f_sum_mid / n_mid,
                    F_exact,
                    0.01);
  test_tools::check("impulse = m v0 (1 %)", impulse, 1. * v0, 0.01);
  test_tools::check("contact duration = 2 L / c (1.5 %)",
                    duration,
                    2 * L / c,
                    0.015);
  test_tools::check("energy conserved (0.5 %)", energy, E0, 0.005);
  test_tools::check("striker stops (1 % of m v0)", p_striker, 0., 0.01, v0);
  test_tools::check("struck bar leaves at v0 (1 %)", p_struck, v0, 0.01);
  return test_tools::finish();
}
