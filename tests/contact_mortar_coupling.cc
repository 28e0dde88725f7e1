// The friction interface of the CEA (contact/friction_coupling.h) on two
// stacked unit blocks: a "disc" block below z = 0 and a "pad" block above.
// 1. Matching meshes, degree 1, nodal quadrature: K_n and K_t equal the
//    thesis' node-pair elements (eq. 3-1, F_z = k_n (z_d - z_p),
//    F_y^pad = mu k_n (z_d - z_p), F_y^disc = -mu k_n (z_d - z_p)) with
//    k_n = k A_node, A_node the node's tributary area, when the sliding
//    direction is -y (the thesis' sign convention), to 1e-12.
// 2. Non-matching meshes (pad 2 x 2, disc 3 x 3 cells; degree 1, 2 and 3),
//    mortar quadrature: a unit normal gap gives total forces k A on each
//    side, and a gap varying as x gives pad forces whose moment
//    sum_i x_i f_i equals k int_Gamma x^2 dA = k / 3, to 1e-12 (a nodal
//    trapezoidal rule misses it; Simpson's, the nodal rule of degree 2, not).
// 3. The tangential (shear) part K_st with k_s = 0.4 k on the same
//    non-matching meshes: a unit in-plane translation of the pad stores
//    u^T K_st u = k_s A (both rules), a rotation theta about the normal
//    through the face's centre k_s theta^2 J with J = int r^2 dA = 1/6 (the
//    polar moment of the unit square; mortar rule), to 1e-12; a normal
//    translation and a rigid translation of both blocks store nothing.

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/sparsity_tools.h>

#include <squeal/physics/interface_coupling.h>
#include <squeal/scene/tribobrake_mesh.h>

#include "test_tools.h"

using namespace dealii;
using namespace squeal;

namespace
{
  // Two blocks sharing the plane z = 0 but no vertices.
  void
  make_blocks(const unsigned int n_disc,
              const unsigned int n_pad,
              Triangulation<3>  &tria)
  {
    test_tools::stacked_blocks(n_disc,
                               n_pad,
                               1.,
                               1.,
                               scene::tribobrake::material::disc,
                               scene::tribobrake::material::pad,
                               tria);
    for (const auto &cell : tria.active_cell_iterators())
      for (const auto f : cell->face_indices())
        if (cell->face(f)->at_boundary() &&
            std::abs(cell->face(f)->center()[2]) < 1e-12)
          cell->face(f)->set_boundary_id(
            cell->material_id() == scene::tribobrake::material::disc ?
              scene::tribobrake::boundary::disc_contact :
              scene::tribobrake::boundary::pad_contact);
  }

  struct Interface
  {
    Triangulation<3>                            tria;
    FESystem<3>                                 fe;
    MappingQ<3>                                 mapping;
    DoFHandler<3>                               dofs;
    AffineConstraints<double>                   constraints;
    PETScWrappers::MPI::SparseMatrix            K_n, K_t, K_st;
    std::map<types::global_dof_index, Point<3>> where;

    Interface(const unsigned int  n_disc,
              const unsigned int  n_pad,
              const unsigned int  degree,
              const std::string  &rule,
              const Tensor<1, 3> &tangent,
              const double        k)
      : fe(FE_Q<3>(degree), 3)
      , mapping(degree)
    {
      make_blocks(n_disc, n_pad, tria);
      dofs.reinit(tria);
      dofs.distribute_dofs(fe);
      constraints.close();
      scene::ContactPair pair;
      pair.name          = "pad on disc";
      pair.slave         = scene::tribobrake::boundary::pad_contact;
      pair.master        = scene::tribobrake::boundary::disc_contact;
      pair.normal        = Tensor<1, 3>({0., 0., 1.});
      pair.plane_axes[0] = Tensor<1, 3>({1., 0., 0.});
      pair.plane_axes[1] = Tensor<1, 3>({0., 1., 0.});
      pair.sliding       = tangent;
      const auto points  = physics::interface_quadrature(
        dofs, mapping, pair, rule, rule == "nodal" ? degree + 1 : degree + 2);
      DynamicSparsityPattern dsp(dofs.n_dofs());
      DoFTools::make_sparsity_pattern(dofs, dsp);
      physics::add_interface_sparsity(points, constraints, dsp);
      const IndexSet all = complete_index_set(dofs.n_dofs());
      K_n.reinit(all, all, dsp, MPI_COMM_SELF);
      K_t.reinit(all, all, dsp, MPI_COMM_SELF);
      K_st.reinit(all, all, dsp, MPI_COMM_SELF);
      physics::assemble_interface(
        points, constraints, k, 0.4 * k, pair, K_n, K_t, &K_st);
      K_n.compress(VectorOperation::add);
      K_t.compress(VectorOperation::add);
      K_st.compress(VectorOperation::add);
      DoFTools::map_dofs_to_support_points(mapping, dofs, where);
    }

    // z (component c) dof of the given body at point p, or invalid
    types::global_dof_index
    dof_at(const Point<3> &p, const unsigned int c, const bool disc) const
    {
      for (const auto &cell : dofs.active_cell_iterators())
        if ((cell->material_id() == scene::tribobrake::material::disc) == disc)
          {
            std::vector<types::global_dof_index> d(fe.n_dofs_per_cell());
            cell->get_dof_indices(d);
            for (unsigned int i = 0; i < d.size(); ++i)
              if (fe.system_to_component_index(i).first == c &&
                  where.at(d[i]).distance(p) < 1e-12)
                return d[i];
          }
      return numbers::invalid_dof_index;
    }
  };
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using test_tools::check;
  const double k = 2.5e12;

  {
    // 1. matching 2 x 2 faces, degree 1, nodal rule, sliding direction -y
    Tensor<1, 3> t;
    t[1] = -1;
    Interface I(2, 2, 1, "nodal", t, k);
    // the thesis' node-pair matrices, independently
    FullMatrix<double> expected_n(I.dofs.n_dofs(), I.dofs.n_dofs()),
      expected_t(I.dofs.n_dofs(), I.dofs.n_dofs());
    const double h = 0.5;
    for (unsigned int i = 0; i <= 2; ++i)
      for (unsigned int j = 0; j <= 2; ++j)
        {
          const Point<3> p(i * h, j * h, 0.);
          const double   n_adjacent = (i == 1 ? 2 : 1) * (j == 1 ? 2 : 1);
          const double   kn         = k * n_adjacent * h * h / 4;
          const auto     zd = I.dof_at(p, 2, true), zp = I.dof_at(p, 2, false);
          const auto     yd = I.dof_at(p, 1, true), yp = I.dof_at(p, 1, false);
          // rows: internal force of F_z^disc = k_n (z_d - z_p) etc.
          expected_n(zd, zd) += kn;
          expected_n(zd, zp) -= kn;
          expected_n(zp, zd) -= kn;
          expected_n(zp, zp) += kn;
          expected_t(yd, zd) -= kn; // F_y^disc = -mu k_n (z_d - z_p)
          expected_t(yd, zp) += kn;
          expected_t(yp, zd) += kn; // F_y^pad = mu k_n (z_d - z_p)
          expected_t(yp, zp) -= kn;
        }
    double dn = 0, dt = 0;
    for (unsigned int i = 0; i < I.dofs.n_dofs(); ++i)
      for (unsigned int j = 0; j < I.dofs.n_dofs(); ++j)
        {
          dn = std::max(dn, std::abs(I.K_n.el(i, j) - expected_n(i, j)));
          dt = std::max(dt, std::abs(I.K_t.el(i, j) - expected_t(i, j)));
        }
    check(
      "matching, nodal: K_n equals the node-pair elements", dn, 0, 1e-12, k);
    check(
      "matching, nodal: K_t equals the thesis' friction rows", dt, 0, 1e-12, k);
  }

  for (const unsigned int degree : {1u, 2u, 3u})
    for (const std::string rule : {"mortar", "nodal"})
      {
        Tensor<1, 3> t;
        t[1] = 1;
        Interface                  I(3, 2, degree, rule, t, k);
        PETScWrappers::MPI::Vector u(complete_index_set(I.dofs.n_dofs()),
                                     MPI_COMM_SELF),
          f(u);
        double total_pad = 0, total_disc = 0, moment = 0;
        // unit gap: disc z = 1
        for (const auto &[i, p] : I.where)
          if (std::abs(p[2]) < 1e-12 && I.dof_at(p, 2, true) == i)
            u(i) = 1.;
        u.compress(VectorOperation::insert);
        I.K_n.vmult(f, u);
        for (const auto &[i, p] : I.where)
          if (std::abs(p[2]) < 1e-12 && I.dof_at(p, 2, false) == i)
            total_pad += f(i);
          else if (std::abs(p[2]) < 1e-12 && I.dof_at(p, 2, true) == i)
            total_disc += f(i);
        // gap varying as x
        u = 0;
        for (const auto &[i, p] : I.where)
          if (std::abs(p[2]) < 1e-12 && I.dof_at(p, 2, true) == i)
            u(i) = p[0];
        u.compress(VectorOperation::insert);
        I.K_n.vmult(f, u);
        for (const auto &[i, p] : I.where)
          if (std::abs(p[2]) < 1e-12 && I.dof_at(p, 2, false) == i)
            moment += p[0] * f(i);
        const std::string tag =
          "non-matching, degree " + std::to_string(degree) + ", " + rule + ": ";
        check(tag + "unit gap, total pad force -k A", total_pad, -k, 1e-12);
        check(tag + "unit gap, total disc force k A", total_disc, k, 1e-12);
        if (rule == "mortar")
          check(tag + "gap x, pad moment -k/3", moment, -k / 3, 1e-12);
        else if (degree == 1) // Simpson (degree 2) is exact for x^2
          check(tag + "gap x, pad moment misses -k/3 (nodal rule is not exact)",
                std::abs(moment + k / 3) > 1e-6 * k / 3,
                1,
                0);

        // 3. the tangential part: energies u^T K_st u of rigid motions
        const double k_s    = 0.4 * k;
        const auto   energy = [&](const auto &motion) {
          u = 0;
          std::vector<types::global_dof_index> d(I.fe.n_dofs_per_cell());
          for (const auto &cell : I.dofs.active_cell_iterators())
            {
              cell->get_dof_indices(d);
              for (unsigned int i = 0; i < d.size(); ++i)
                u(d[i]) = motion(I.where.at(d[i]),
                                 I.fe.system_to_component_index(i).first,
                                 cell->material_id() ==
                                   scene::tribobrake::material::disc);
            }
          u.compress(VectorOperation::insert);
          I.K_st.vmult(f, u);
          return u * f;
        };
        check(tag + "pad translated in x by 1: u^T K_st u = k_s A",
              energy([](const Point<3> &, unsigned int c, bool disc) {
                return !disc && c == 0 ? 1. : 0.;
              }),
              k_s,
              1e-12);
        check(tag + "pad translated in y by 1: u^T K_st u = k_s A",
              energy([](const Point<3> &, unsigned int c, bool disc) {
                return !disc && c == 1 ? 1. : 0.;
              }),
              k_s,
              1e-12);
        check(tag + "pad translated in z: no shear energy",
              energy([](const Point<3> &, unsigned int c, bool disc) {
                return !disc && c == 2 ? 1. : 0.;
              }),
              0.,
              1e-12,
              k_s);
        check(tag + "both blocks translated in x: no shear energy",
              energy([](const Point<3> &, unsigned int c, bool) {
                return c == 0 ? 1. : 0.;
              }),
              0.,
              1e-12,
              k_s);
        const double theta = 1e-3;
        if (rule == "mortar")
          check(tag + "pad turned about the normal: k_s theta^2 / 6",
                energy([&](const Point<3> &p, unsigned int c, bool disc) {
                  return disc   ? 0. :
                         c == 0 ? -theta * (p[1] - 0.5) :
                         c == 1 ? theta * (p[0] - 0.5) :
                                  0.;
                }),
                k_s * theta * theta / 6,
                1e-12);
      }
  return test_tools::finish();
}
