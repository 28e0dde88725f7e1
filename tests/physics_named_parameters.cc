// Named parameters and per-body Rayleigh damping of a mesh-file scene.
// Two steel-like blocks in a row along x, one mesh (shared nodes): body a on
// [0, L], body b on [L, 2L], section b x b, held at x = 0. The field
// u = (eps x, 0, 0) is uniaxial strain, so its energies are closed forms:
//   u^T K u = C11 eps^2 V per body (C11 = lambda + 2 mu of the body),
//   u^T M u = rho eps^2 b^2 (x1^3 - x0^3) / 3 per body.
// Body a has its own damping (alpha_a, beta_a), body b the scene's.
// 1. u^T C u = sum_body alpha (u^T M_body u) + beta (u^T K_body u), closed
//    form, 1e-10, with the parts grouped for a sweep of a.E and with every
//    parameter varied (one part per body);
// 2. named parameters recombine: a.E doubled doubles a's stiffness energy,
//    a.alpha changed changes C accordingly (closed forms, 1e-10);
// 3. a point that moves a parameter the model was not built to vary, an
//    unknown name, or two items giving one name gets one error naming it.
// 4. A sliding direction whose norm overflows is still a unit vector.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/vector_tools.h>

#include <squeal/io/mesh_file.h>
#include <squeal/physics/structural_model.h>

#include "test_tools.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

using namespace dealii;
using namespace squeal;
using test_tools::check;
using test_tools::error_of;

namespace
{
  const double L = 0.05, b = 0.01, eps = 1e-4;
  const double E_a = 200e9, nu_a = 0.3, rho_a = 7800.;
  const double E_b = 70e9, nu_b = 0.33, rho_b = 2700.;
  const double alpha_a = 3., beta_a = 2e-6; // body a's own
  const double alpha_g = 5., beta_g = 1e-6; // Damping subsection

  void
  write_blocks(const std::string &file)
  {
    Triangulation<3> tria;
    GridGenerator::subdivided_hyper_rectangle(
      tria, {8, 2, 2}, Point<3>(), Point<3>(2 * L, b, b), true);
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_material_id(cell->center()[0] < L ? 0 : 1);
    io::NamedSets sets;
    sets.source = "the test's blocks";
    sets.collect_from_ids(tria,
                          {{0, "a"}, {1, "b"}},
                          {{0, "x0"}, {1, "x1"}, {2, "y0"}});
    io::write_abaqus(tria, sets, file);
  }

  parameters::AllParameters
  read(const std::string &bodies, ParameterHandler &handler)
  {
    std::ofstream("blocks.prm")
      << "subsection Scene\n  set Type = mesh file\n"
         "  subsection Mesh file\n    set File = blocks.inp\n"
         "    set Bodies = "
      << bodies
      << "\n    set Holds = x0: set=X0\n  end\nend\n"
         "subsection Mesh\n  set Finite element degree = 1\nend\n"
         "subsection Damping\n  set Alpha = "
      << alpha_g << "\n  set Beta = " << beta_g << "\nend\n";
    parameters::AllParameters prm;
    prm.read(handler, "blocks.prm");
    return prm;
  }

  std::string
  bodies(const std::string &a_extra)
  {
    std::ostringstream s;
    s << "a: set=A, E=" << E_a << ", nu=" << nu_a << ", rho=" << rho_a
      << a_extra << "; b: set=B, E=" << E_b << ", nu=" << nu_b
      << ", rho=" << rho_b;
    return s.str();
  }

  double
  c11(const double E, const double nu)
  {
    return E * (1. - nu) / ((1. + nu) * (1. - 2. * nu));
  }

  // u = (eps x, 0, 0)
  class Uniaxial : public Function<3>
  {
  public:
    Uniaxial()
      : Function<3>(3)
    {}
    double
    value(const Point<3> &x, const unsigned int c) const override
    {
      return c == 0 ? eps * x[0] : 0.;
    }
  };

  // u^T A u for the uniaxial field
  double
  energy(const physics::StructuralModel &model, const physics::PETScMatrix &A)
  {
    return test_tools::field_energy(model, A, Uniaxial());
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    write_blocks("blocks.inp");
  MPI_Barrier(MPI_COMM_WORLD);

  std::ostringstream own;
  own << ", alpha=" << alpha_a << ", beta=" << beta_a;
  ParameterHandler                handler;
  const parameters::AllParameters prm = read(bodies(own.str()), handler);

  const double V   = b * b * L;
  const double k_a = c11(E_a, nu_a) * eps * eps * V,
               k_b = c11(E_b, nu_b) * eps * eps * V;
  const double m_a = rho_a * eps * eps * b * b * L * L * L / 3.,
               m_b = rho_b * eps * eps * b * b * 7. * L * L * L / 3.;

  for (const bool all : {false, true})
    {
      physics::StructuralModel model(prm, MPI_COMM_WORLD);
      if (!all)
        model.varied = std::set<std::string>{"a.E"};
      model.setup_and_assemble(quiet);
      const std::string grouping =
        all ? " (every parameter varied)" : " (parts grouped for a.E)";
      const physics::MatrixParts    parts = model.parts();
      const parameters::ScalarPoint p0    = model.scene->nominal_point();
      physics::PETScMatrix          K, M, C;
      parts.stiffness(p0, K);
      parts.mass(p0, M);
      parts.damping(p0, C);
      check("u^T K u = C11 eps^2 V per body" + grouping,
            energy(model, K),
            k_a + k_b,
            1e-10);
      check("u^T M u = rho eps^2 b^2 x^3 / 3 per body" + grouping,
            energy(model, M),
            m_a + m_b,
            1e-10);
      check("u^T C u = alpha_a m_a + alpha m_b + beta_a k_a + beta k_b" +
              grouping,
            energy(model, C),
            alpha_a * m_a + alpha_g * m_b + beta_a * k_a + beta_g * k_b,
            1e-10);

      parameters::ScalarPoint p = p0;
      p.set("a.E", 2 * E_a);
      parts.stiffness(p, K);
      parts.damping(p, C);
      check("a.E doubled: u^T K u = 2 k_a + k_b" + grouping,
            energy(model, K),
            2 * k_a + k_b,
            1e-10);
      check("a.E doubled: u^T C u" + grouping,
            energy(model, C),
            alpha_a * m_a + alpha_g * m_b + 2 * beta_a * k_a + beta_g * k_b,
            1e-10);
      p.set("a.alpha", 7.);
      p.set("damping.beta", 4e-6);
      parts.damping(p, C);
      check("a.alpha = 7, damping.beta = 4e-6: u^T C u" + grouping,
            energy(model, C),
            7. * m_a + alpha_g * m_b + 2 * beta_a * k_a + 4e-6 * k_b,
            1e-10);

      if (!all)
        {
          parameters::ScalarPoint q = p0;
          q.set("b.rho", 1000.);
          const std::string e = error_of([&]() { parts.mass(q, M); });
          test_tools::check_message(
            "a parameter the model does not vary is refused, named",
            e,
            {"b.rho", "does not vary"});
        }
    }

  {
    const auto                    scene = scene::make_scene(prm);
    const parameters::ScalarPoint p     = scene->nominal_point();
    const std::string             e     = error_of([&]() { p.get("pad.E"); });
    test_tools::check_message(
      "an unknown name lists the scene's parameters",
      e,
      {"'pad.E'",
       "a.E|a.rho|a.alpha|a.beta|b.E|b.rho|damping.alpha|damping.beta"});
    check("body a's own damping is a named parameter",
          p.get("a.beta"),
          beta_a,
          1e-15);
  }
  {
    ParameterHandler  h;
    const std::string e = error_of([&]() {
      scene::make_scene(read("damping: set=A, E=1e9, nu=0.3, rho=1000, "
                             "alpha=1; b: set=B, E=1e9, nu=0.3, rho=1000",
                             h));
    });
    test_tools::check_message(
      "a body called damping with its own alpha: one error naming "
      "damping.alpha",
      e,
      {"two parameters are called 'damping.alpha'"});
  }
  {
    // a direction whose norm overflows stays a unit vector (friction
    // vanished with it before)
    parameters::Interface i;
    i.sliding_direction = "1e200, 0";
    const auto t        = i.sliding_tangent();
    check("Interface/Sliding direction = 1e200, 0 is the unit x axis",
          t[0] + std::abs(t[1]) + std::abs(t[2]),
          1.,
          1e-15);
  }
  return test_tools::finish();
}
