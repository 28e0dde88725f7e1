// Anisotropic linear elasticity (scene/material_law.h, physics/elastic_law.h):
// - the isotropic tensor assembles the same cell stiffness as the Lame
//   form of add_cell_elasticity (a distorted degree-2 cell, 1e-12);
// - both kernels (products of scalar-basis blocks) equal the plain sum over
//   every pair of vector DoFs and quadrature point, written here, for the
//   stiffness, the consistent mass and a law that varies with the point
//   (a distorted degree-3 cell, 1e-13 of the largest entry);
// - an orthotropic unit block (friction-material-like constants, held on
//   its three symmetry planes, uniaxial stress sigma on x = 1) deforms
//   exactly as the compliance says: eps_xx = sigma / E1,
//   eps_yy = -nu12 sigma / E1, eps_zz = -nu13 sigma / E1 (1e-10, degree 1
//   represents the linear field exactly);
// - the same block with the material frame turned 90 degrees about z
//   (axis 1 along global y): eps_xx = sigma / E2, eps_yy = -nu12 sigma / E1,
//   eps_zz = -nu23 sigma / E2;
// - a transversely isotropic block loaded along its axis:
//   eps_zz = sigma / E_t, eps_xx = eps_yy = -nu_pt (E_t / E_p) sigma / E_t;
// - bad constants give one error naming them.

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/numerics/vector_tools.h>

#include <squeal/physics/elastic_law.h>
#include <squeal/physics/structural_model.h>
#include <squeal/scene/material_law.h>

#include "check.h"

using namespace dealii;
using namespace squeal;
using test_tools::check;
using test_tools::error_of;

namespace
{
  const double sigma = 1e6; // Pa

  // Displacement of the corner (1, 1, 1) of the unit block under sigma along
  // @p axis (0: x, 2: z), the block held on x = 0, y = 0, z = 0 (normal
  // component each), law @p C.
  Tensor<1, 3>
  corner_displacement(const SymmetricTensor<4, 3> &C, const unsigned int axis)
  {
    Triangulation<3> tria;
    GridGenerator::subdivided_hyper_cube(tria, 2, 0., 1., true);
    FESystem<3>   fe(FE_Q<3>(1), 3);
    MappingQ<3>   mapping(1);
    DoFHandler<3> dofs(tria);
    dofs.distribute_dofs(fe);
    AffineConstraints<double> constraints;
    for (unsigned int d = 0; d < 3; ++d)
      {
        ComponentMask mask(3, false);
        mask.set(d, true);
        VectorTools::interpolate_boundary_values(mapping,
                                                 dofs,
                                                 2 * d,
                                                 Functions::ZeroFunction<3>(3),
                                                 constraints,
                                                 mask);
      }
    constraints.close();
    DynamicSparsityPattern dsp(dofs.n_dofs());
    DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
    SparsityPattern pattern;
    pattern.copy_from(dsp);
    SparseMatrix<double>                 K(pattern);
    Vector<double>                       f(dofs.n_dofs()), u(dofs.n_dofs());
    FEValues<3>                          fv(mapping,
                   fe,
                   QGauss<3>(2),
                   update_gradients | update_JxW_values);
    FEFaceValues<3>                      ffv(mapping,
                        fe,
                        QGauss<2>(2),
                        update_values | update_JxW_values);
    const unsigned int                   n = fe.n_dofs_per_cell();
    FullMatrix<double>                   cell_k(n, n);
    Vector<double>                       cell_f(n);
    std::vector<types::global_dof_index> cell_dofs(n);
    for (const auto &cell : dofs.active_cell_iterators())
      {
        fv.reinit(cell);
        cell_k = 0;
        cell_f = 0;
        physics::add_cell_stiffness(fv, C, cell_k);
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == 2 * axis + 1)
            {
              ffv.reinit(cell, f);
              for (unsigned int q = 0; q < ffv.n_quadrature_points; ++q)
                for (unsigned int i = 0; i < n; ++i)
                  if (fe.system_to_component_index(i).first == axis)
                    cell_f(i) += sigma * ffv.shape_value(i, q) * ffv.JxW(q);
            }
        cell->get_dof_indices(cell_dofs);
        constraints.distribute_local_to_global(cell_k, cell_f, cell_dofs, K, f);
      }
    SparseDirectUMFPACK solver;
    solver.initialize(K);
    solver.vmult(u, f);
    constraints.distribute(u);
    Vector<double> value(3);
    VectorTools::point_value(mapping, dofs, u, Point<3>(1., 1., 1.), value);
    return Tensor<1, 3>({value[0], value[1], value[2]});
  }

  // largest |a - b| over the largest |b|
  double
  relative_difference(const FullMatrix<double> &a, const FullMatrix<double> &b)
  {
    double diff = 0., scale = 0.;
    for (unsigned int i = 0; i < a.m(); ++i)
      for (unsigned int j = 0; j < a.n(); ++j)
        {
          diff  = std::max(diff, std::abs(a(i, j) - b(i, j)));
          scale = std::max(scale, std::abs(b(i, j)));
        }
    return scale > 0. ? diff / scale : 1.;
  }

  // The kernels against the textbook loops: K_ij = sum_q eps_i : C_q :
  // eps_j JxW, M_ij = rho delta(c_i, c_j) sum_q N_i N_j JxW.
  void
  check_against_plain_sums()
  {
    Triangulation<3> tria;
    GridGenerator::hyper_cube(tria);
    tria.begin_active()->vertex(7) += Point<3>(0.2, -0.1, 0.3);
    tria.begin_active()->vertex(2) += Point<3>(-0.1, 0.15, 0.05);
    FESystem<3>   fe(FE_Q<3>(3), 3);
    MappingQ<3>   mapping(1);
    DoFHandler<3> dofs(tria);
    dofs.distribute_dofs(fe);
    const QGauss<3> quadrature(4);
    FEValues<3>     fv(mapping,
                   fe,
                   quadrature,
                   update_values | update_gradients | update_JxW_values);
    fv.reinit(dofs.begin_active());
    const unsigned int                n = fe.n_dofs_per_cell();
    const scene::OrthotropicConstants c{
      10e9, 6e9, 3e9, 0.25, 0.1, 0.15, 3e9, 1.5e9, 1.2e9};
    std::vector<SymmetricTensor<4, 3>> C_q(quadrature.size());
    for (unsigned int q = 0; q < C_q.size(); ++q)
      C_q[q] = (1. + 0.01 * q) * scene::orthotropic_stiffness(c);
    const double E = 210e9, nu = 0.3, rho = 7800.;
    const auto [lambda, mu]         = physics::lame_constants(E, nu);
    const SymmetricTensor<4, 3> iso = scene::isotropic_stiffness(E, nu);
    FullMatrix<double> k_iso(n, n), k_var(n, n), m(n, n), plain_iso(n, n),
      plain_var(n, n), plain_m(n, n);
    physics::add_cell_elasticity(fv, lambda, mu, rho, k_iso, m);
    physics::add_cell_stiffness(fv, C_q, k_var);
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          {
            const unsigned int ci = fe.system_to_component_index(i).first,
                               cj = fe.system_to_component_index(j).first;
            SymmetricTensor<2, 3> ei, ej;
            for (unsigned int d = 0; d < 3; ++d)
              {
                ei[ci][d] += (ci == d ? 1. : 0.5) * fv.shape_grad(i, q)[d];
                ej[cj][d] += (cj == d ? 1. : 0.5) * fv.shape_grad(j, q)[d];
              }
            plain_iso(i, j) += ei * (iso * ej) * fv.JxW(q);
            plain_var(i, j) += ei * (C_q[q] * ej) * fv.JxW(q);
            if (ci == cj)
              plain_m(i, j) +=
                rho * fv.shape_value(i, q) * fv.shape_value(j, q) * fv.JxW(q);
          }
    check("isotropic stiffness kernel = plain sum (degree 3)",
          relative_difference(k_iso, plain_iso),
          0.,
          1e-13,
          1.);
    check("consistent mass kernel = plain sum (degree 3)",
          relative_difference(m, plain_m),
          0.,
          1e-13,
          1.);
    check("pointwise law kernel = plain sum (degree 3)",
          relative_difference(k_var, plain_var),
          0.,
          1e-13,
          1.);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  check_against_plain_sums();

  // 1. isotropic tensor = Lame form
  {
    Triangulation<3> tria;
    GridGenerator::hyper_cube(tria);
    tria.begin_active()->vertex(7) += Point<3>(0.2, -0.1, 0.3);
    FESystem<3>   fe(FE_Q<3>(2), 3);
    MappingQ<3>   mapping(1);
    DoFHandler<3> dofs(tria);
    dofs.distribute_dofs(fe);
    FEValues<3> fv(mapping,
                   fe,
                   QGauss<3>(3),
                   update_values | update_gradients | update_JxW_values);
    fv.reinit(dofs.begin_active());
    const unsigned int n = fe.n_dofs_per_cell();
    FullMatrix<double> a(n, n), b(n, n), m(n, n);
    const double       E = 210e9, nu = 0.3;
    const auto [lambda, mu] = physics::lame_constants(E, nu);
    physics::add_cell_elasticity(fv, lambda, mu, 7800., a, m);
    physics::add_cell_stiffness(fv, scene::isotropic_stiffness(E, nu), b);
    double diff = 0., scale = 0.;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        {
          diff  = std::max(diff, std::abs(a(i, j) - b(i, j)));
          scale = std::max(scale, std::abs(a(i, j)));
        }
    check("isotropic tensor = Lame form (distorted degree-2 cell)",
          diff / scale,
          0.,
          1e-12,
          1.);
  }

  // 2. orthotropic block
  const scene::OrthotropicConstants c{
    10e9, 6e9, 3e9, 0.25, 0.1, 0.15, 3e9, 1.5e9, 1.2e9};
  {
    const Tensor<1, 3> u =
      corner_displacement(scene::orthotropic_stiffness(c), 0);
    check("orthotropic: eps_xx = sigma / E1", u[0], sigma / c.E1, 1e-10);
    check("orthotropic: eps_yy = -nu12 sigma / E1",
          u[1],
          -c.nu12 * sigma / c.E1,
          1e-10);
    check("orthotropic: eps_zz = -nu13 sigma / E1",
          u[2],
          -c.nu13 * sigma / c.E1,
          1e-10);
  }
  // 3. the frame turned: material axis 1 = global y, 2 = global -x, 3 = z
  {
    Tensor<2, 3> R;
    R[1][0]              = 1.;  // axis 1 -> (0, 1, 0)
    R[0][1]              = -1.; // axis 2 -> (-1, 0, 0)
    R[2][2]              = 1.;
    const Tensor<1, 3> u = corner_displacement(
      scene::rotate_stiffness(scene::orthotropic_stiffness(c), R), 0);
    check("rotated frame: eps_xx = sigma / E2", u[0], sigma / c.E2, 1e-10);
    check("rotated frame: eps_yy = -nu12 sigma / E1",
          u[1],
          -c.nu12 * sigma / c.E1,
          1e-10);
    check("rotated frame: eps_zz = -nu23 sigma / E2",
          u[2],
          -c.nu23 * sigma / c.E2,
          1e-10);
  }
  // 4. transversely isotropic, loaded along its axis
  {
    const double E_p = 8e9, nu_p = 0.2, E_t = 2e9, nu_pt = 0.3, G_t = 0.9e9;
    const Tensor<1, 3> u = corner_displacement(
      scene::transversely_isotropic_stiffness(E_p, nu_p, E_t, nu_pt, G_t), 2);
    check("transversely isotropic: eps_zz = sigma / E_t",
          u[2],
          sigma / E_t,
          1e-10);
    const double lateral = -nu_pt * (E_t / E_p) * sigma / E_t;
    check("transversely isotropic: eps_xx = -nu_tp sigma / E_t",
          u[0],
          lateral,
          1e-10);
    check("transversely isotropic: eps_yy = eps_xx", u[1], lateral, 1e-10);
  }
  // 5. bad constants
  {
    auto bad = c;
    bad.E2   = -1.;
    check("a negative modulus is named",
          error_of([&] {
            scene::orthotropic_stiffness(bad);
          }).find("E2 must be a positive modulus") != std::string::npos,
          1.,
          0.);
    bad      = c;
    bad.nu12 = 2.;
    check("indefinite Poisson ratios are refused",
          error_of([&] {
            scene::orthotropic_stiffness(bad);
          }).find("make the compliance indefinite") != std::string::npos,
          1.,
          0.);
    check("nu = 0.5 is refused for an isotropic law",
          error_of([&] {
            scene::isotropic_stiffness(1e9, 0.5);
          }).find("-1 < nu < 0.5") != std::string::npos,
          1.,
          0.);
  }
  return test_tools::finish();
}
