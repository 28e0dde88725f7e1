// The affine parameter dependence behind sweeps over any pair of scalar
// parameters (physics::MatrixParts): M, K, K without friction and C
// recombined from parts assembled at one set of values must equal the
// matrices assembled directly at another set (pad modulus, friction
// coefficient, interface stiffness, spring stiffness, support density,
// Rayleigh alpha and beta all changed), to 1e-12 in the Frobenius norm.
// Independent computation: a second model assembled from scratch.

#include <squeal/physics/structural_model.h>

#include "test_tools.h"

using namespace dealii;
using namespace squeal;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);

  parameters::AllParameters a = test_tools::coarse_tribobrake(24, 3, 1, 2, 1);
  a.interface.friction_coefficient = 0.3;

  parameters::AllParameters b      = a;
  b.materials.pad.youngs_modulus   = 3.7e9;
  b.interface.friction_coefficient = 0.65;
  b.interface.normal_stiffness     = 9.1e11;
  b.springs.stiffness              = 2.3e7;
  b.materials.support.density      = 7800.;
  b.damping.alpha                  = 15.;
  b.damping.beta                   = 3e-7;

  physics::StructuralModel model_a(a, MPI_COMM_WORLD),
    model_b(b, MPI_COMM_WORLD);
  // the bodies' parameters that differ get parts of their own (the disc's
  // and the support's stiffness stay in the common part, which also sets
  // the constrained rows' diagonal); the interface, spring and damping
  // parameters always vary
  for (auto *m : {&model_a, &model_b})
    m->varied = std::set<std::string>{"pad.E", "support.rho"};
  model_a.setup_and_assemble(quiet);
  model_b.setup_and_assemble(quiet);
  const auto parts_a = model_a.parts(), parts_b = model_b.parts();
  const parameters::ScalarPoint p = model_b.scene->nominal_point();

  using Assemble =
    void (physics::MatrixParts::*)(const parameters::ScalarPoint &,
                                   physics::PETScMatrix &) const;
  for (const auto &[name, f] :
       {std::pair<std::string, Assemble>{"M", &physics::MatrixParts::mass},
        {"K", &physics::MatrixParts::stiffness},
        {"K without friction", &physics::MatrixParts::symmetric_stiffness},
        {"C", &physics::MatrixParts::damping}})
    {
      physics::PETScMatrix from_parts, direct;
      (parts_a.*f)(p, from_parts);
      (parts_b.*f)(p, direct);
      const double norm = direct.frobenius_norm();
      from_parts.add(-1., direct);
      test_tools::check(name + " recombined equals " + name +
                          " assembled at the new values (1e-12)",
                        from_parts.frobenius_norm() / norm,
                        0.,
                        1e-12,
                        1.);
    }
  return test_tools::finish();
}
