// Kinetic-energy shares of a mode by body (mode_participation.csv, the
// mode names) with the whole mass of the point: every body at its density,
// the support's included.
// - u_z = 1 m on the pad and the support, 0 on the disc, at a point whose
//   support density (7800 kg/m^3) differs from the assembled reference
//   (76 500 kg/m^3): the shares must be the hand-computed split
//   rho_pad V_pad : rho_support V_support (V_pad = a^3, V_support = a^2 L,
//   boxes) to 1e-12; the disc's share is 0;
// - for a field with every DoF random, the energies summed over the bodies
//   equal u^T M(p) u of the assembled, recombined mass parts to 1e-10
//   (quadrature and matrices are independent paths).
// Coarse TriboBrake, degree 1 and 2.

#include <squeal/physics/structural_model.h>

#include "test_tools.h"

#include <random>

using namespace dealii;
using namespace squeal;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);
  for (const unsigned int degree : {1u, 2u})
    {
      auto prm           = test_tools::coarse_tribobrake(24, 3, 1, 2, 1);
      prm.mesh.fe_degree = degree;
      physics::StructuralModel model(prm, MPI_COMM_WORLD);
      model.setup_and_assemble(quiet);
      parameters::ScalarPoint point = model.scene->nominal_point();
      point.set("support.rho", 7800.);
      const std::string name = "degree " + std::to_string(degree) + ": ";

      physics::PETScVector u(model.locally_owned_dofs, MPI_COMM_WORLD),
        zero(model.locally_owned_dofs, MPI_COMM_WORLD);
      std::vector<types::global_dof_index> dofs(model.fe.n_dofs_per_cell());
      for (const auto &cell : model.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() && cell->material_id() != 0)
          {
            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < dofs.size(); ++i)
              if (model.fe.system_to_component_index(i).first == 2 &&
                  model.locally_owned_dofs.is_element(dofs[i]))
                u(dofs[i]) = 1.;
          }
      u.compress(VectorOperation::insert);
      const std::vector<double> e =
        physics::kinetic_energy_by_body(model, point, u, zero);
      const auto  &g   = prm.geometry;
      const double pad = prm.materials.pad.density * std::pow(g.pad_size, 3);
      const double support = 7800. * g.pad_size * g.pad_size * g.support_length;
      const double total   = e[0] + e[1] + e[2];
      test_tools::check(name + "three bodies", e.size(), 3., 0.);
      test_tools::check(name + "disc share of a pad-and-support field",
                        e[0] / total,
                        0.,
                        1e-14,
                        1.);
      test_tools::check(name +
                          "pad share = rho_p a^3 / (rho_p a^3 + rho_s a^2 L)",
                        e[1] / total,
                        pad / (pad + support),
                        1e-12);
      test_tools::check(name + "support share at 7800 kg/m^3",
                        e[2] / total,
                        support / (pad + support),
                        1e-12);
      test_tools::check(
        name + "support energy = rho_s V_s (not the reference density)",
        e[2],
        support,
        1e-12);

      // random field, clamped and hanging values as the constraints want
      std::mt19937                           rng(7);
      std::uniform_real_distribution<double> uniform(-1., 1.);
      physics::PETScVector re(model.locally_owned_dofs, MPI_COMM_WORLD), im(re),
        Mx(re);
      for (unsigned int i = 0; i < model.n_dofs(); ++i)
        {
          const double a = uniform(rng), b = uniform(rng);
          if (model.locally_owned_dofs.is_element(i))
            {
              re(i) = a;
              im(i) = b;
            }
        }
      re.compress(VectorOperation::insert);
      im.compress(VectorOperation::insert);
      model.constraints.distribute(re);
      model.constraints.distribute(im);
      physics::PETScMatrix M;
      model.parts().mass(point, M);
      M.vmult(Mx, re);
      double matrix = re * Mx;
      M.vmult(Mx, im);
      matrix += im * Mx;
      const std::vector<double> r =
        physics::kinetic_energy_by_body(model, point, re, im);
      test_tools::check(name + "sum over bodies = re^T M(p) re + im^T M(p) im",
                        r[0] + r[1] + r[2],
                        matrix,
                        1e-10);
    }
  return test_tools::finish();
}
