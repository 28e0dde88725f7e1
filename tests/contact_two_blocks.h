// Two elastic blocks stacked on the plane z = 0 (the upper one shifted by
// `gap`: negative overlaps) with non-matching interface
// meshes: the set-up of the patch test (verification B1) and the sliding
// block (B5). Upper block (slave, boundary id 10 on z = 0) [0,1]^2 x [0,1],
// lower block (master, id 11) [0,1]^2 x [-1,0]; top face id 1 (loaded),
// bottom id 2 (u_z = 0), x = 0 id 3 (u_x = 0), y = 0 id 4 (u_y = 0).
#ifndef squeal_tests_contact_two_blocks_h
#define squeal_tests_contact_two_blocks_h

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/numerics/vector_tools.h>

#include "contact_assembly.h"

#include <functional>
#include <memory>
#include <set>

struct TwoBlocks
{
  dealii::Triangulation<3>          tria;
  dealii::FESystem<3>               fe;
  dealii::MappingQ<3>               mapping{1};
  dealii::DoFHandler<3>             dofs;
  dealii::AffineConstraints<double> constraints;
  dealii::SparsityPattern           pattern;
  dealii::SparseMatrix<double>      K, K_free; // constrained, unconstrained
  dealii::Vector<double>            f, f_free;

  /** @p upper, @p lower: cells per side of the blocks' square faces. */
  TwoBlocks(unsigned int         degree,
            unsigned int         upper,
            unsigned int         lower,
            double               E_upper,
            double               nu_upper,
            double               E_lower,
            double               nu_lower,
            dealii::Tensor<1, 3> top_traction,
            double               gap = 0.)
    : TwoBlocks(degree,
                E_upper,
                nu_upper,
                E_lower,
                nu_lower,
                top_traction,
                [&](dealii::Triangulation<3> &t) {
                  make_mesh(upper, lower, gap, t);
                })
  {}

  /** The same set-up on the mesh @p fill makes: material ids 0 (upper) and
   *  1 (lower), boundary ids as in the file comment. */
  TwoBlocks(unsigned int                                           degree,
            double                                                 E_upper,
            double                                                 nu_upper,
            double                                                 E_lower,
            double                                                 nu_lower,
            dealii::Tensor<1, 3>                                   top_traction,
            const std::function<void(dealii::Triangulation<3> &)> &fill)
    : fe(dealii::FE_Q<3>(degree), 3)
    , dofs(tria)
  {
    using namespace dealii;
    fill(tria);
    dofs.distribute_dofs(fe);
    const Functions::ZeroFunction<3> zero(3);
    VectorTools::interpolate_boundary_values(
      mapping, dofs, 2, zero, constraints, ComponentMask({false, false, true}));
    VectorTools::interpolate_boundary_values(
      mapping, dofs, 3, zero, constraints, ComponentMask({true, false, false}));
    VectorTools::interpolate_boundary_values(
      mapping, dofs, 4, zero, constraints, ComponentMask({false, true, false}));
    constraints.close();
    DynamicSparsityPattern dsp(dofs.n_dofs());
    DoFTools::make_sparsity_pattern(dofs, dsp);
    pattern.copy_from(dsp);
    K.reinit(pattern);
    K_free.reinit(pattern);
    f.reinit(dofs.n_dofs());
    f_free.reinit(dofs.n_dofs());

    assemble_elastic_system(
      dofs,
      mapping,
      constraints,
      [&](unsigned int m) {
        return m == 0 ? std::make_pair(E_upper, nu_upper) :
                        std::make_pair(E_lower, nu_lower);
      },
      {{1, top_traction, &f}},
      K,
      &K_free,
      &f_free);
  }

  /** The two blocks of @p upper and @p lower cells per side, the upper one
   *  shifted by @p gap, with the ids of the file comment. */
  static void
  make_mesh(unsigned int              upper,
            unsigned int              lower,
            double                    gap,
            dealii::Triangulation<3> &tria)
  {
    using namespace dealii;
    Triangulation<3> a, b;
    GridGenerator::subdivided_hyper_rectangle(a,
                                              {upper, upper, 2},
                                              Point<3>(0, 0, gap),
                                              Point<3>(1, 1, 1 + gap));
    GridGenerator::subdivided_hyper_rectangle(b,
                                              {lower, lower, 2},
                                              Point<3>(0, 0, -1),
                                              Point<3>(1, 1, 0));
    // tolerance 0: the blocks share no vertex, even where they touch
    GridGenerator::merge_triangulations(a, b, tria, 0.);
    for (const auto &cell : tria.active_cell_iterators())
      {
        const bool up = cell->center()[2] > gap;
        cell->set_material_id(up ? 0 : 1);
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const Point<3> c = cell->face(f)->center();
              if (std::abs(c[2] - 1 - gap) < 1e-12)
                cell->face(f)->set_boundary_id(1);
              else if (std::abs(c[2] + 1) < 1e-12)
                cell->face(f)->set_boundary_id(2);
              else if (std::abs(c[2] - (up ? gap : 0.)) < 1e-12)
                cell->face(f)->set_boundary_id(up ? 10 : 11);
              else if (std::abs(c[0]) < 1e-12)
                cell->face(f)->set_boundary_id(3);
              else if (std::abs(c[1]) < 1e-12)
                cell->face(f)->set_boundary_id(4);
              else
                cell->face(f)->set_boundary_id(5);
            }
      }
  }

  /** Sum of the reaction forces (K_free u - f_free - f_contact) over the DoFs
   * of
   *  component @p c on faces with boundary id @p id of the block with
   *  material @p material [N]. */
  double
  reaction(const dealii::Vector<double> &u,
           const dealii::Vector<double> &f_contact,
           dealii::types::boundary_id    id,
           unsigned int                  c,
           unsigned int                  material) const
  {
    dealii::Vector<double> r(u.size());
    K_free.vmult(r, u);
    r -= f_free;
    r -= f_contact;
    std::set<dealii::types::global_dof_index>    seen;
    std::vector<dealii::types::global_dof_index> face_dofs(
      fe.n_dofs_per_face());
    double sum = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->material_id() == material)
        for (const auto fn : cell->face_indices())
          if (cell->face(fn)->at_boundary() &&
              cell->face(fn)->boundary_id() == id)
            {
              cell->face(fn)->get_dof_indices(face_dofs);
              for (unsigned int k = 0; k < face_dofs.size(); ++k)
                if (fe.face_system_to_component_index(k).first == c &&
                    seen.insert(face_dofs[k]).second)
                  sum += r[face_dofs[k]];
            }
    return sum;
  }
};

#endif
