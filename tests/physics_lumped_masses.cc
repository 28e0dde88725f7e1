// Lumped masses of a mesh-file scene (Scene/Mesh file/Masses).
// A bar of length L along x (steel, 10 x 10 mm), its end x = 0 held along
// x and its sides sliding (y held on the y faces, z on the z faces): the
// motion is uniaxial strain, u_x(x), with the constrained modulus
// C11 = lambda + 2 mu. A tip mass M on the end x = L gives the modes
//   k L tan(k L) = rho A L / M,   f = k c / (2 pi),  c = sqrt(C11 / rho)
// (the roots found here by bisection).
// The bar has other modes too (sections shearing: u_x linear across the
// section, about 17 kHz); each closed-form frequency is matched to the
// nearest of the model's.
// 1. M = rho A L spread over the end face (set=X1), degree 2, 20 cells:
//    the first 3 longitudinal frequencies against the closed form, 1e-5;
// 2. the same mass as four point masses M / 4 at the end face's corners,
//    degree 1: the same longitudinal frequencies as the face mass at
//    degree 1 (the end face moves as one in these modes), 1e-9;
// 3. the kinetic energies by body (the masses counted with the body they
//    sit on) sum to u^T M u of the assembled mass for a random field,
//    1e-10, with both kinds of masses; the explicit dynamics' lumped mass
//    sums to rho V + 2 M per direction (1e-12);
// 4. bad masses get one error naming the item;
// 5. the mass as the named parameter `tip.m` (its own mass part, scaled):
//    set to 3 M at the point, the first 3 frequencies against the closed
//    form with 3 M (degree 2), 1e-5; the energy shares (3.) count the
//    masses at the point's values.

#include <deal.II/grid/grid_generator.h>

#include <squeal/eigen/qep_solver.h>
#include <squeal/io/mesh_file.h>
#include <squeal/physics/structural_model.h>
#include <squeal/transient/explicit_dynamics.h>

#include "test_tools.h"

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace squeal;
using test_tools::check;
using test_tools::error_of;

namespace
{
  const double L = 0.1, b = 0.01; // m
  const double E = 200e9, nu = 0.3, rho = 7800.;
  const double M = rho * b * b * L; // kg, the bar's own mass

  void
  write_bar(const std::string &file)
  {
    Triangulation<3> tria;
    GridGenerator::subdivided_hyper_rectangle(
      tria, {20, 1, 1}, Point<3>(), Point<3>(L, b, b), true);
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_material_id(0);
    io::NamedSets sets;
    sets.source = "the test's bar";
    sets.collect_from_ids(
      tria,
      {{0, "bar"}},
      {{0, "x0"}, {1, "x1"}, {2, "y0"}, {3, "y1"}, {4, "z0"}, {5, "z1"}});
    io::write_abaqus(tria, sets, file);
  }

  parameters::AllParameters
  bar_parameters(const std::string &masses,
                 const unsigned int degree,
                 ParameterHandler  &handler)
  {
    std::ostringstream body;
    body << "bar: set=BAR, E=" << E << ", nu=" << nu << ", rho=" << rho;
    std::ofstream("bar.prm")
      << "subsection Scene\n  set Type = mesh file\n"
         "  subsection Mesh file\n    set File = bar.inp\n"
         "    set Bodies = "
      << body.str()
      << "\n    set Holds = x0: set=X0, components=x; y0: set=Y0, "
         "components=y; y1: set=Y1, components=y; z0: set=Z0, components=z; "
         "z1: set=Z1, components=z\n"
         "    set Masses = "
      << masses
      << "\n  end\nend\n"
         "subsection Mesh\n  set Finite element degree = "
      << degree
      << "\nend\n"
         "subsection Damping\n  set Alpha = 0\n  set Beta = 0\nend\n"
         "subsection Eigensolver\n  set Minimum frequency = 1000\n"
         "  set Maximum frequency = 70000\nend\n";
    parameters::AllParameters prm;
    prm.read(handler, "bar.prm");
    return prm;
  }

  std::vector<double>
  frequencies(const std::string                                 &masses,
              const unsigned int                                 degree,
              const std::vector<std::pair<std::string, double>> &changes = {})
  {
    ParameterHandler handler;
    return test_tools::undamped_frequencies(
      bar_parameters(masses, degree, handler), 1000., 70000., changes);
  }

  // The frequency of @p f nearest @p x.
  double
  nearest(const std::vector<double> &f, const double x)
  {
    double best = 1e300;
    for (const double y : f)
      if (std::abs(y - x) < std::abs(best - x))
        best = y;
    return best;
  }

  // The roots of k L tan(k L) = r, one in each (n pi, n pi + pi / 2).
  std::vector<double>
  tip_mass_roots(const double r, const unsigned int n_roots)
  {
    std::vector<double> roots;
    for (unsigned int n = 0; n < n_roots; ++n)
      {
        double lo = n * M_PI + 1e-12, hi = n * M_PI + M_PI / 2 - 1e-12;
        for (unsigned int it = 0; it < 200; ++it)
          {
            const double mid                    = 0.5 * (lo + hi);
            (mid * std::tan(mid) < r ? lo : hi) = mid;
          }
        roots.push_back(0.5 * (lo + hi));
      }
    return roots;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  write_bar("bar.inp");
  const std::string face_mass = "tip: set=X1, mass=" + std::to_string(M);

  // 1. the closed form
  const double        lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double        mu     = E / (2 * (1 + nu));
  const double        c      = std::sqrt((lambda + 2 * mu) / rho);
  const auto          kL     = tip_mass_roots(rho * b * b * L / M, 3);
  const auto          f2     = frequencies(face_mass, 2);
  std::vector<double> f_exact;
  for (unsigned int k = 0; k < 3; ++k)
    {
      f_exact.push_back(kL[k] * c / (2 * M_PI * L));
      check("tip mass on the end face, longitudinal mode " +
              std::to_string(k + 1),
            nearest(f2, f_exact[k]),
            f_exact[k],
            1e-5);
    }

  // 2. four point masses at the corners = the face mass, degree 1
  std::ostringstream corners;
  for (unsigned int k = 0; k < 4; ++k)
    corners << (k > 0 ? "; " : "") << "corner " << k << ": mass=" << M / 4
            << ", point=" << L << ' ' << (k % 2) * b << ' ' << (k / 2) * b;
  const auto f_face   = frequencies(face_mass, 1);
  const auto f_points = frequencies(corners.str(), 1);
  for (unsigned int k = 0; k < 3; ++k)
    check("four point masses = the face mass, longitudinal mode " +
            std::to_string(k + 1),
          nearest(f_points, f_exact[k]),
          nearest(f_face, f_exact[k]),
          1e-9);

  // 3. kinetic energies by body against u^T M u, both kinds of mass
  {
    ParameterHandler                handler;
    const parameters::AllParameters prm =
      bar_parameters(face_mass + "; " + corners.str(), 2, handler);
    ConditionalOStream       quiet(std::cout, false);
    physics::StructuralModel model(prm, MPI_COMM_WORLD);
    model.setup_and_assemble(quiet);
    physics::PETScVector u(model.locally_owned_dofs, MPI_COMM_WORLD),
      zero(model.locally_owned_dofs, MPI_COMM_WORLD),
      Mu(model.locally_owned_dofs, MPI_COMM_WORLD);
    std::mt19937                           rng(3);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    for (const auto i : model.locally_owned_dofs)
      u(i) = uniform(rng);
    u.compress(VectorOperation::insert);
    model.constraints.distribute(u);
    // held DoFs at zero: the constrained rows of M are a placeholder
    for (const auto i : model.locally_owned_dofs)
      if (model.constraints.is_constrained(i))
        u(i) = 0.;
    u.compress(VectorOperation::insert);
    physics::PETScMatrix Mm;
    model.parts().mass(model.scene->nominal_point(), Mm);
    Mm.vmult(Mu, u);
    const std::vector<double> e = physics::kinetic_energy_by_body(
      model, model.scene->nominal_point(), u, zero);
    check("kinetic energy with lumped masses = u^T M u", e[0], u * Mu, 1e-10);
    // at a point that moves the masses (5.): each its own scaled part
    parameters::ScalarPoint p = model.scene->nominal_point();
    p.set("tip.m", 3 * M);
    p.set("corner 1.m", 0.5 * M);
    physics::PETScMatrix Mp;
    model.parts().mass(p, Mp);
    Mp.vmult(Mu, u);
    check("kinetic energy with tip.m = 3 M = u^T M(p) u",
          physics::kinetic_energy_by_body(model, p, u, zero)[0],
          u * Mu,
          1e-10);
    Vector<double> lumped =
      transient::lumped_mass(model.dof_handler,
                             model.mapping,
                             [](const auto &) { return rho; });
    physics::add_lumped_masses(model, lumped);
    const auto [points, component] = physics::dof_support_points(model);
    for (unsigned int d = 0; d < 3; ++d)
      {
        double sum = 0.;
        for (unsigned int i = 0; i < lumped.size(); ++i)
          if (component[i] == d)
            sum += lumped[i];
        check("lumped mass along " + std::to_string(d) + " = rho V + 2 M",
              sum,
              rho * b * b * L + 2 * M,
              1e-12);
      }
  }

  // 4. bad masses
  const auto has = [](const std::string &masses, const std::string &part) {
    const std::string message = error_of([&]() { frequencies(masses, 1); });
    const bool        ok      = message.find(part) != std::string::npos;
    check("error '" + part + "'", ok ? 0. : 1., 0., 0.);
    if (!ok)
      std::cout << "  got: " << message << std::endl;
  };
  has("w: set=X1, mass=-1", "item 'w': need mass > 0");
  has("w: mass=1", "item 'w': give either point= or set=");
  has("w: mass=1, set=NOPE", "no face set 'NOPE'");

  // 5. the named parameter tip.m
  {
    const auto kL3 = tip_mass_roots(rho * b * b * L / (3 * M), 3);
    const auto f3  = frequencies(face_mass, 2, {{"tip.m", 3 * M}});
    for (unsigned int k = 0; k < 3; ++k)
      {
        const double exact = kL3[k] * c / (2 * M_PI * L);
        check("tip.m = 3 M, longitudinal mode " + std::to_string(k + 1),
              nearest(f3, exact),
              exact,
              1e-5);
      }
  }
  return test_tools::n_failures == 0 ? 0 : 1;
}
