// The compliant (penalty) normal contact law of the static contact solver,
// p = k_n x penetration (ContactSettings::normal_stiffness), the law of the
// CEA's linear interface (thesis eq. 3-1) that the preload uses so that the
// CEA about the preload is linearised about a state of its own law.
// - Patch test (B1 with a compliant interface): two blocks pressed by a
//   uniform pressure p through non-matching meshes. The exact solution is
//   the hard-contact one plus a rigid approach of the upper block by p / k_n:
//   the multipliers equal p, every node's gap equals -p / k_n, and the
//   displacement differs from the hard solution by -p / k_n along z on the
//   upper block and by 0 on the lower one (1e-8); with steady sliding the
//   friction force is mu N.
// - Partial contact: the upper block's face curved (a gap 0.2 (x - 1/2)^2),
//   so that its edges stay open. The penalty solution satisfies its law
//   node by node (active: z > 0 and z = -k_n g / D; inactive: z = 0 and no
//   penetration), carries the whole load, and converges to the hard
//   solution at first order in 1 / k_n (error ratio 10 per decade of k_n,
//   within 5-20).
// - Bad input: a stiffness list of the wrong length and a negative one are
//   refused with one error each.

#include <deal.II/grid/grid_tools.h>

#include <squeal/contact/contact_solver.h>
#include <squeal/contact/mortar.h>

#include "check.h"
#include "contact_two_blocks.h"

#include <set>
#include <sstream>

using namespace dealii;
using namespace squeal::contact;
using test_tools::check;

namespace
{
  // The two blocks of contact_two_blocks.h with the upper block's vertices
  // lifted by delta (x - 1/2)^2 (its contact face curved along x); boundary
  // ids by face number (the bricks keep deal.II's standard orientation).
  void
  curved_blocks(Triangulation<3> &tria, const double delta)
  {
    Triangulation<3> a, b;
    GridGenerator::subdivided_hyper_rectangle(a,
                                              {8, 8, 2},
                                              Point<3>(0, 0, 0),
                                              Point<3>(1, 1, 1));
    GridTools::transform(
      [delta](const Point<3> &x) {
        return Point<3>(x[0], x[1], x[2] + delta * (x[0] - 0.5) * (x[0] - 0.5));
      },
      a);
    GridGenerator::subdivided_hyper_rectangle(b,
                                              {6, 6, 2},
                                              Point<3>(0, 0, -1),
                                              Point<3>(1, 1, 0));
    GridGenerator::merge_triangulations(a, b, tria, 0.);
    for (const auto &cell : tria.active_cell_iterators())
      {
        const bool up = cell->center()[2] > 0.;
        cell->set_material_id(up ? 0 : 1);
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            cell->face(f)->set_boundary_id(f == 5 ? (up ? 1 : 11) :
                                           f == 4 ? (up ? 10 : 2) :
                                           f == 0 ? 3 :
                                           f == 2 ? 4 :
                                                    5);
      }
  }

  // The z resultant of the contact pressure on the slave face [N]:
  // sum_j D_jj z_j n_j . e_z (n_j the slave's outward normal, -e_z-ish)
  double
  z_resultant(const MortarOperators &op, const ContactSolution &s)
  {
    double f = 0.;
    for (unsigned int j = 0; j < op.n_slave(); ++j)
      f -= op.D[j] * s.pressure[j] * op.normals[j][2];
    return f;
  }

  // u_a - u_b relative to |u_b| (l2)
  double
  relative_difference(const Vector<double> &a, const Vector<double> &b)
  {
    Vector<double> d(a);
    d -= b;
    return d.l2_norm() / b.l2_norm();
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double                     p = 0.625; // Pa (scaled units)

  // Patch test with a compliant interface.
  for (const unsigned int degree : {1u, 2u})
    {
      const std::string name =
        "patch, degree " + std::to_string(degree) + ", k_n = 50: ";
      const double k_n = 50.; // N/m^3: the penetration p / k_n = 0.0125 m
      TwoBlocks    b(
        degree, 3, 2, 200., 0.3, 100., 0.25, Tensor<1, 3>({0., 0., -p}));
      const MortarOperators op =
        build_mortar_operators(b.dofs, b.mapping, 10, 11, 0.1);
      ContactSettings hard, soft;
      soft.normal_stiffness.assign(op.n_slave(), k_n);
      const ContactSolution h =
        solve_static_contact(b.K, b.f, b.constraints, op, hard);
      const ContactSolution s =
        solve_static_contact(b.K, b.f, b.constraints, op, soft);
      double       z_error = 0., gap_error = 0.;
      unsigned int n_active = 0;
      for (unsigned int j = 0; j < op.n_slave(); ++j)
        {
          n_active += s.status[j] != 0;
          z_error = std::max(z_error, std::abs(s.pressure[j] - p) / p);
          gap_error =
            std::max(gap_error, std::abs(s.gap[j] + p / k_n) / (p / k_n));
        }
      check(name + "every slave node in contact", n_active, op.n_slave(), 0.);
      check(name + "multipliers = p", z_error, 0., 1e-8, 1.);
      check(name + "every gap = -p / k_n", gap_error, 0., 1e-8, 1.);
      // u_penalty - u_hard: the rigid approach -p / k_n of the upper block
      Vector<double>                       expected(b.dofs.n_dofs());
      std::vector<types::global_dof_index> dofs(b.fe.n_dofs_per_cell());
      for (const auto &cell : b.dofs.active_cell_iterators())
        if (cell->material_id() == 0)
          {
            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < dofs.size(); ++i)
              if (b.fe.system_to_component_index(i).first == 2)
                expected[dofs[i]] = -p / k_n;
          }
      Vector<double> diff(s.displacement);
      diff -= h.displacement;
      diff -= expected;
      check(name + "displacement = hard + rigid approach -p / k_n",
            diff.linfty_norm(),
            0.,
            1e-8,
            p / k_n);
      ContactSettings sliding      = soft;
      sliding.friction             = FrictionModel::steady_sliding;
      sliding.friction_coefficient = 0.5;
      sliding.sliding_direction    = Tensor<1, 3>({1., 0., 0.});
      const ContactSolution f =
        solve_static_contact(b.K, b.f, b.constraints, op, sliding);
      check(name + "steady sliding: friction force = mu N",
            f.tangential_force,
            0.5 * f.normal_force,
            1e-12);
      check(name + "steady sliding: normal force = p x area",
            f.normal_force,
            p,
            1e-10);
    }

  // Partial contact on a curved face.
  {
    TwoBlocks             b(1,
                200.,
                0.3,
                100.,
                0.25,
                Tensor<1, 3>({0., 0., -p}),
                [](Triangulation<3> &t) { curved_blocks(t, 0.2); });
    const MortarOperators op =
      build_mortar_operators(b.dofs, b.mapping, 10, 11, 0.1);
    const ContactSolution h =
      solve_static_contact(b.K, b.f, b.constraints, op, ContactSettings());
    // the applied load along z [N], on the upper block's top
    double                               load = 0.;
    std::vector<types::global_dof_index> dofs(b.fe.n_dofs_per_cell());
    std::set<types::global_dof_index>    seen;
    for (const auto &cell : b.dofs.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          if (b.fe.system_to_component_index(i).first == 2 &&
              seen.insert(dofs[i]).second)
            load -= b.f_free[dofs[i]];
      }
    check("curved, hard: contact carries the load (z resultant)",
          z_resultant(op, h),
          load,
          1e-9);
    unsigned int n_hard = 0;
    for (const int st : h.status)
      n_hard += st != 0;
    test_tools::verbose() << "curved: " << n_hard << " of " << op.n_slave()
                          << " slave nodes in hard contact" << std::endl;
    check("curved, hard: part of the face in contact",
          n_hard > 0 && n_hard < op.n_slave(),
          1.,
          0.);
    std::vector<double> errors;
    for (const double k_n : {2e3, 2e4, 2e5, 2e6})
      {
        std::ostringstream name;
        name << "curved, k_n = " << k_n << ": ";
        ContactSettings settings;
        settings.normal_stiffness.assign(op.n_slave(), k_n);
        const ContactSolution s =
          solve_static_contact(b.K, b.f, b.constraints, op, settings);
        double       z_max = 0.;
        unsigned int n_on = 0, n_off = 0;
        for (unsigned int j = 0; j < op.n_slave(); ++j)
          z_max = std::max(z_max, s.pressure[j]);
        double law = 0., open = 0.;
        for (unsigned int j = 0; j < op.n_slave(); ++j)
          if (s.status[j] != 0)
            {
              ++n_on;
              law = std::max(
                {law,
                 std::abs(s.gap[j] + s.pressure[j] / k_n) / (z_max / k_n),
                 s.pressure[j] < 0. ? 1. : 0.});
            }
          else
            {
              ++n_off;
              open = std::max({open,
                               std::abs(s.pressure[j]),
                               s.gap[j] < 0. ? -s.gap[j] : 0.});
            }
        check(name.str() + "nodes in contact and separated",
              n_on > 0 && n_off > 0,
              1.,
              0.);
        check(
          name.str() + "active: z > 0 and z = -k_n g / D", law, 0., 1e-9, 1.);
        check(
          name.str() + "separated: z = 0, no penetration", open, 0., 1e-12, 1.);
        check(name.str() + "contact carries the load (z resultant)",
              z_resultant(op, s),
              load,
              1e-9);
        errors.push_back(relative_difference(s.displacement, h.displacement));
        test_tools::verbose()
          << name.str() << n_on
          << " in contact, |u - u_hard| / |u_hard| = " << errors.back()
          << std::endl;
      }
    // first order in 1 / k_n once the active set is the hard one's
    for (unsigned int i = 2; i < errors.size(); ++i)
      check("curved: error ratio per decade of k_n " + std::to_string(i) +
              " in 5-20",
            errors[i - 1] / errors[i] >= 5. && errors[i - 1] / errors[i] <= 20.,
            1.,
            0.);
    check("curved: k_n = 2e6 within 1e-3 of the hard solution",
          errors.back() < 1e-3,
          1.,
          0.);
  }

  // Bad input.
  {
    TwoBlocks b(1, 3, 2, 200., 0.3, 100., 0.25, Tensor<1, 3>({0., 0., -p}));
    const MortarOperators op =
      build_mortar_operators(b.dofs, b.mapping, 10, 11, 0.1);
    ContactSettings short_list;
    short_list.normal_stiffness.assign(op.n_slave() - 1, 50.);
    check("a stiffness list of the wrong length is refused",
          test_tools::error_of([&] {
            solve_static_contact(b.K, b.f, b.constraints, op, short_list);
          })
              .find("stiffnesses for " + std::to_string(op.n_slave()) +
                    " slave nodes") != std::string::npos,
          1.,
          0.);
    ContactSettings negative;
    negative.normal_stiffness.assign(op.n_slave(), 50.);
    negative.normal_stiffness[3] = -1.;
    check("a negative normal stiffness is refused",
          test_tools::error_of([&] {
            solve_static_contact(b.K, b.f, b.constraints, op, negative);
          }).find("must be finite and >= 0") != std::string::npos,
          1.,
          0.);
  }
  return test_tools::finish();
}
