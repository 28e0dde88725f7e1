// Verification B2 in 3D: an elastic sphere (R = 8, E = 200, nu = 0.3)
// pressed by F = 12.5 on a rigid flat: Hertz gives the contact radius
// a = (3 F R / (4 E*))^(1/3) = 0.6988 and the peak pressure
// p_max = 3 F / (2 pi a^2) = 12.222, E* = E / (1 - nu^2).
//
// The body is the lower cap of the sphere cut by a square prism of half
// width and height 4 (about 6 a), a quarter of it by symmetry (u_x = 0 on
// x = 0, u_y = 0 on y = 0), its mesh graded towards the first contact point,
// without hanging nodes. The rigid flat is a block 1e6 times stiffer.
// Checks: p_max (of the nodal pressure field, the L2 projection of the
// multipliers) within 3 %, the contact radius within one element,
// equilibrium, and the active-set iterations below a stated bound.

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/numerics/vector_tools.h>

#include <squeal/contact/contact_solver.h>
#include <squeal/contact/mortar.h>
#include <squeal/physics/structural_model.h>

#include "check.h"
#include "contact_assembly.h"

#include <cmath>
#include <sstream>

using namespace dealii;
using namespace squeal::contact;
using test_tools::check;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double                     R = 8., F = 12.5, E = 200., nu = 0.3;
  const double                     E_star = E / (1. - nu * nu);
  const double a_exact = std::cbrt(3. * F * R / (4. * E_star)),
               p0      = 3. * F / (2. * M_PI * a_exact * a_exact);

  const double        w = 4., H = 4., h0 = 0.07;
  std::vector<double> dxy, dz;
  for (double y = 0., h = h0; y < w - 1e-9; h *= 1.18)
    {
      dxy.push_back(std::min(h, w - y));
      y += dxy.back();
    }
  for (double z = 0., h = h0; z < H - 1e-9; h *= 1.35)
    {
      dz.push_back(std::min(h, H - z));
      z += dz.back();
    }
  Triangulation<3> body, flat, tria;
  GridGenerator::subdivided_hyper_rectangle(body,
                                            {dxy, dxy, dz},
                                            Point<3>(0, 0, 0),
                                            Point<3>(w, w, H));
  GridTools::transform(
    [&](const Point<3> &x) {
      const double zb = R - std::sqrt(R * R - x[0] * x[0] - x[1] * x[1]);
      return Point<3>(x[0], x[1], zb + x[2] * (H - zb) / H);
    },
    body);
  GridGenerator::subdivided_hyper_rectangle(flat,
                                            {6u, 6u, 2u},
                                            Point<3>(-0.5, -0.5, -2),
                                            Point<3>(w + 0.5, w + 0.5, 0));
  GridGenerator::merge_triangulations(body, flat, tria, 0.);
  for (const auto &cell : tria.active_cell_iterators())
    {
      const bool up = cell->center()[2] > 0;
      cell->set_material_id(up ? 0 : 1);
      for (const auto f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            const Point<3>     c  = cell->face(f)->center();
            types::boundary_id id = 6;
            if (up && std::abs(c[2] - H) < 1e-12)
              id = 1; // loaded top
            else if (up && std::abs(c[0]) < 1e-12)
              id = 3; // symmetry: u_x = 0
            else if (up && std::abs(c[1]) < 1e-12)
              id = 4; // symmetry: u_y = 0
            else if (up &&
                     (std::abs(c[0] - w) < 1e-12 || std::abs(c[1] - w) < 1e-12))
              id = 5; // free sides
            else if (up)
              id = 10; // spherical bottom: slave
            else if (std::abs(c[2]) < 1e-12)
              id = 11; // the flat: master
            else if (std::abs(c[2] + 2) < 1e-12)
              id = 2; // fixed bottom of the flat
            cell->face(f)->set_boundary_id(id);
          }
    }

  const unsigned int degree = 1;
  FESystem<3>        fe(FE_Q<3>(degree), 3);
  MappingQ<3>        mapping(1);
  DoFHandler<3>      dofs(tria);
  dofs.distribute_dofs(fe);
  AffineConstraints<double>        constraints;
  const Functions::ZeroFunction<3> zero(3);
  VectorTools::interpolate_boundary_values(
    mapping, dofs, 3, zero, constraints, ComponentMask({true, false, false}));
  VectorTools::interpolate_boundary_values(
    mapping, dofs, 4, zero, constraints, ComponentMask({false, true, false}));
  VectorTools::interpolate_boundary_values(mapping, dofs, 2, zero, constraints);
  constraints.close();
  DynamicSparsityPattern dsp(dofs.n_dofs());
  DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
  SparsityPattern sp;
  sp.copy_from(dsp);
  SparseMatrix<double> K(sp);
  Vector<double>       f(dofs.n_dofs());
  // a quarter of F over the quarter top w x w
  Tensor<1, 3> pressing;
  pressing[2] = -0.25 * F / (w * w);
  assemble_elastic_system(
    dofs,
    mapping,
    constraints,
    [&](unsigned int m) { return std::make_pair(m == 0 ? E : 1e6 * E, nu); },
    {{1, pressing, &f}},
    K);

  const MortarOperators op = build_mortar_operators(dofs, mapping, 10, 11, 1.0);
  std::ostringstream    log;
  const ContactSolution s =
    solve_static_contact(K, f, constraints, op, ContactSettings(), &log);
  test_tools::verbose() << dofs.n_dofs() << " DoFs:\n" << log.str();

  double p_max = 0., a_found = 0., vertical = 0.;
  for (unsigned int j = 0; j < op.n_slave(); ++j)
    {
      vertical += op.D[j] * s.pressure[j] * op.normals[j][2];
      p_max = std::max(p_max, s.nodal_pressure[j]);
      // the contact radius along the symmetry line y = 0
      if (s.status[j] != 0 && std::abs(op.slave_points[j][1]) < 1e-12)
        a_found = std::max(a_found, op.slave_points[j][0]);
    }
  double x = 0., h_at_a = h0;
  for (const double h : dxy)
    {
      if (x + h > a_exact)
        {
          h_at_a = h;
          break;
        }
      x += h;
    }
  test_tools::verbose() << "  p_max " << p_max << " (exact " << p0
                        << "), contact radius " << a_found << " (a " << a_exact
                        << ", element " << h_at_a << ")" << std::endl;
  check("peak pressure within 3 %", p_max, p0, 0.03);
  check("contact radius within one element", a_found, a_exact, 1., h_at_a);
  check("equilibrium: vertical contact force = F / 4",
        -vertical,
        0.25 * F,
        1e-8);
  check("active set settles within 15 iterations",
        std::min<double>(s.history.size(), 15.),
        s.history.size(),
        0.);
  return test_tools::finish();
}
