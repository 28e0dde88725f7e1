// An elastic cylinder (radius R) on a rigid flat in plane strain: the set-up
// of the Hertz (verification B2) and Cattaneo-Mindlin (B3) tests. The body
// is the lower part of the cylinder, a circular segment of half width w and
// height H, one cell (h0) thick in x with u_x = 0 on both faces; its mesh is
// graded towards the first contact point (y = 0, z = 0) without hanging
// nodes. With `half`, only y >= 0 with u_y = 0 on y = 0 (symmetry). The
// rigid flat is a block 1e6 times stiffer, fixed at its bottom. With
// `rigid_top`, the top moves as a rigid loading plate without rotation
// (u_y and u_z tied to one top node): a tangential load then slides rather
// than rolls the cylinder, as Cattaneo's solution assumes; with `hold_top`
// as well, the plate is also held along y (for a frictionless first step).
// Slave
// (curved bottom) boundary id 10, master (flat) 11. Loads: f_normal is a
// total force P per unit length pressing down, f_tangential a total Q per
// unit length along +y, both uniform over the top (of the modelled part).
#ifndef squeal_tests_contact_cylinder_h
#define squeal_tests_contact_cylinder_h

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/numerics/vector_tools.h>

#include "contact_assembly.h"

#include <cmath>
#include <vector>

struct CylinderOnFlat
{
  dealii::Triangulation<3>          tria;
  dealii::FESystem<3>               fe{dealii::FE_Q<3>(1), 3};
  dealii::MappingQ<3>               mapping{1};
  dealii::DoFHandler<3>             dofs;
  dealii::AffineConstraints<double> constraints;
  dealii::SparsityPattern           pattern;
  dealii::SparseMatrix<double>      K;
  dealii::Vector<double>            f_normal, f_tangential;
  std::vector<double>               dy; ///< cell sizes from y = 0 outwards
  double                            h0;

  CylinderOnFlat(double R,
                 double E,
                 double nu,
                 double w,
                 double H,
                 double h0,
                 bool   half,
                 double P,
                 double Q,
                 bool   rigid_top = false,
                 bool   hold_top  = false)
    : dofs(tria)
    , h0(h0)
  {
    using namespace dealii;
    std::vector<double> dz;
    for (double y = 0., h = h0; y < w - 1e-9; h *= 1.12)
      {
        dy.push_back(std::min(h, w - y));
        y += dy.back();
      }
    for (double z = 0., h = h0; z < H - 1e-9; h *= 1.25)
      {
        dz.push_back(std::min(h, H - z));
        z += dz.back();
      }
    std::vector<double> span(dy.rbegin(), dy.rend());
    if (half)
      span = dy;
    else
      span.insert(span.end(), dy.begin(), dy.end());
    Triangulation<3> body, flat;
    GridGenerator::subdivided_hyper_rectangle(body,
                                              {std::vector<double>{h0},
                                               span,
                                               dz},
                                              Point<3>(0, half ? 0. : -w, 0),
                                              Point<3>(h0, w, H));
    GridTools::transform(
      [&](const Point<3> &x) {
        const double zb = R - std::sqrt(R * R - x[1] * x[1]);
        return Point<3>(x[0], x[1], zb + x[2] * (H - zb) / H);
      },
      body);
    GridGenerator::subdivided_hyper_rectangle(flat,
                                              {1u, half ? 8u : 16u, 2u},
                                              Point<3>(0,
                                                       half ? -0.5 : -w - 0.5,
                                                       -2),
                                              Point<3>(h0, w + 0.5, 0));
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
              if (std::abs(c[0]) < 1e-12 || std::abs(c[0] - h0) < 1e-12)
                id = 3; // plane strain: u_x = 0
              else if (up && std::abs(c[2] - H) < 1e-12)
                id = 1; // loaded top
              else if (up && half && std::abs(c[1]) < 1e-12)
                id = 4; // symmetry: u_y = 0
              else if (up && std::abs(std::abs(c[1]) - w) < 1e-12)
                id = 5; // free sides
              else if (up)
                id = 10; // curved bottom: slave
              else if (std::abs(c[2]) < 1e-12)
                id = 11; // the flat: master
              else if (std::abs(c[2] + 2) < 1e-12)
                id = 2; // fixed bottom of the flat
              cell->face(f)->set_boundary_id(id);
            }
      }
    dofs.distribute_dofs(fe);
    const Functions::ZeroFunction<3> zero(3);
    VectorTools::interpolate_boundary_values(
      mapping, dofs, 3, zero, constraints, ComponentMask({true, false, false}));
    if (half)
      VectorTools::interpolate_boundary_values(mapping,
                                               dofs,
                                               4,
                                               zero,
                                               constraints,
                                               ComponentMask(
                                                 {false, true, false}));
    VectorTools::interpolate_boundary_values(
      mapping, dofs, 2, zero, constraints);
    if (rigid_top)
      {
        // u_y and u_z of every top node equal those of the first one
        std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
        types::global_dof_index lead[3] = {numbers::invalid_dof_index,
                                           numbers::invalid_dof_index,
                                           numbers::invalid_dof_index};
        for (const auto &cell : dofs.active_cell_iterators())
          for (const auto fn : cell->face_indices())
            if (cell->face(fn)->at_boundary() &&
                cell->face(fn)->boundary_id() == 1)
              {
                cell->face(fn)->get_dof_indices(face_dofs);
                for (unsigned int k = 0; k < face_dofs.size(); ++k)
                  {
                    const unsigned int comp =
                      fe.face_system_to_component_index(k).first;
                    if (comp == 0)
                      continue;
                    const auto d = face_dofs[k];
                    if (lead[comp] == numbers::invalid_dof_index)
                      {
                        lead[comp] = d;
                        if (hold_top && comp == 1)
                          constraints.add_line(d);
                      }
                    else if (d != lead[comp] && !constraints.is_constrained(d))
                      {
                        constraints.add_line(d);
                        constraints.add_entry(d, lead[comp], 1.);
                      }
                  }
              }
      }
    constraints.close();
    DynamicSparsityPattern dsp(dofs.n_dofs());
    DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
    pattern.copy_from(dsp);
    K.reinit(pattern);
    f_normal.reinit(dofs.n_dofs());
    f_tangential.reinit(dofs.n_dofs());

    const double top = half ? w : 2. * w; // width of the loaded top
    Tensor<1, 3> pressing, pulling;
    pressing[2] = -(half ? 0.5 * P : P) / top;
    pulling[1]  = Q / top;
    assemble_elastic_system(
      dofs,
      mapping,
      constraints,
      [&](unsigned int m) { return std::make_pair(m == 0 ? E : 1e6 * E, nu); },
      {{1, pressing, &f_normal}, {1, pulling, &f_tangential}},
      K);
  }

  /** Size of the cell that contains y > 0 in the graded direction. */
  double
  cell_size_at(double y) const
  {
    double s = 0.;
    for (const double h : dy)
      {
        if (s + h > y)
          return h;
        s += h;
      }
    return dy.back();
  }
};

#endif
