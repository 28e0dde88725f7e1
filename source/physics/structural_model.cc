// Assembly of the structural matrices of a scene: linear elasticity per body
// (the pad separately, so that a sweep over its modulus rescales one matrix),
// the support's springs and the friction interface. All matrices share one
// sparsity pattern so that combining them is a cheap MatAXPY.

#include <deal.II/base/qprojector.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_refinement.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <squeal/physics/elastic_law.h>
#include <squeal/physics/interface_coupling.h>
#include <squeal/physics/structural_model.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace squeal
{
  namespace physics
  {
    using namespace dealii;

    StructuralModel::StructuralModel(const parameters::AllParameters &prm,
                                     MPI_Comm                         comm)
      : prm(prm)
      , comm(comm)
      , triangulation(comm)
      , fe(FE_Q<3>(prm.mesh.fe_degree), 3)
      , mapping(prm.mesh.fe_degree)
      , dof_handler(triangulation)
    {}

    void
    set_constrained_diagonal(const AffineConstraints<double> &constraints,
                             const IndexSet                  &locally_owned,
                             const double                     value,
                             PETScMatrix                     &matrix)
    {
      for (const auto i : locally_owned)
        if (constraints.is_constrained(i))
          matrix.set(i, i, value);
      matrix.compress(VectorOperation::insert);
    }

    std::vector<double>
    kinetic_energy_by_body(const StructuralModel         &model,
                           const parameters::ScalarPoint &p,
                           const PETScVector             &re,
                           const PETScVector             &im)
    {
      types::material_id largest = 0;
      for (const auto &cell : model.triangulation.active_cell_iterators())
        largest = std::max(largest, cell->material_id());
      largest = Utilities::MPI::max(largest, model.comm);
      std::vector<double>         energy(largest + 1, 0.);
      const QGauss<3>             quadrature(model.fe.degree + 1);
      FEValues<3>                 fe_values(model.mapping,
                            model.fe,
                            quadrature,
                            update_values | update_JxW_values);
      std::vector<Vector<double>> values(quadrature.size(), Vector<double>(3));
      const QGauss<2>             face_rule(model.fe.degree + 1);
      FEFaceValues<3>             fv(model.mapping,
                         model.fe,
                         face_rule,
                         update_values | update_JxW_values);
      std::vector<Vector<double>> face_values(face_rule.size(),
                                              Vector<double>(3));
      for (const PETScVector *x : {&re, &im})
        {
          PETScVector owned = *x;
          model.constraints.distribute(owned);
          PETScVector ghosted(model.locally_owned_dofs,
                              model.locally_relevant_dofs,
                              model.comm);
          ghosted = owned;
          for (const auto &cell : model.dof_handler.active_cell_iterators())
            if (cell->is_locally_owned())
              {
                fe_values.reinit(cell);
                fe_values.get_function_values(ghosted, values);
                const double rho = model.scene->density(cell->material_id(), p);
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  energy[cell->material_id()] +=
                    rho * (values[q] * values[q]) * fe_values.JxW(q);
              }
          // the lumped masses, with the body they sit on
          for (const scene::LumpedMass &m : model.scene->masses)
            if (m.on_faces)
              {
                const double density = m.mass / boundary_area(model, m.faces);
                for (const auto &cell :
                     model.dof_handler.active_cell_iterators())
                  if (cell->is_locally_owned())
                    for (const unsigned int f : cell->face_indices())
                      if (cell->face(f)->at_boundary() &&
                          cell->face(f)->boundary_id() == m.faces)
                        {
                          fv.reinit(cell, f);
                          fv.get_function_values(ghosted, face_values);
                          for (unsigned int q = 0; q < face_rule.size(); ++q)
                            energy[cell->material_id()] +=
                              density * (face_values[q] * face_values[q]) *
                              fv.JxW(q);
                        }
              }
          for (const auto &pm : model.point_masses)
            for (const auto d : pm.dofs)
              if (model.locally_owned_dofs.is_element(d))
                energy[pm.body] += pm.mass * owned(d) * owned(d);
        }
      std::vector<double> total(energy.size());
      Utilities::MPI::sum(energy, model.comm, total);
      return total;
    }

    std::pair<std::vector<Point<3>>, std::vector<unsigned int>>
    dof_support_points(const StructuralModel &model)
    {
      const auto                          &fe   = model.fe;
      const auto                          &unit = fe.get_unit_support_points();
      std::vector<Point<3>>                points(model.n_dofs());
      std::vector<unsigned int>            component(model.n_dofs());
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      for (const auto &cell : model.dof_handler.active_cell_iterators())
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              points[dofs[i]] =
                model.mapping.transform_unit_to_real_cell(cell, unit[i]);
              component[dofs[i]] = fe.system_to_component_index(i).first;
            }
        }
      return {points, component};
    }

    void
    copy_to_serial(const PETScMatrix    &K,
                   SparsityPattern      &pattern,
                   SparseMatrix<double> &target)
    {
      const unsigned int     n = K.m();
      DynamicSparsityPattern dsp(n, n);
      for (unsigned int i = 0; i < n; ++i)
        for (auto e = K.begin(i); e != K.end(i); ++e)
          dsp.add(i, e->column());
      pattern.copy_from(dsp);
      target.reinit(pattern);
      for (unsigned int i = 0; i < n; ++i)
        for (auto e = K.begin(i); e != K.end(i); ++e)
          target.set(i, e->column(), e->value());
    }

    std::vector<bool>
    dofs_on_boundary(const StructuralModel &model, const types::boundary_id id)
    {
      std::vector<bool>                    on(model.n_dofs(), false);
      std::vector<types::global_dof_index> face_dofs(
        model.fe.n_dofs_per_face());
      for (const auto &cell : model.dof_handler.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == id)
            {
              cell->face(f)->get_dof_indices(face_dofs);
              for (const auto i : face_dofs)
                on[i] = true;
            }
      return on;
    }

    double
    boundary_area(const StructuralModel &model, const types::boundary_id id)
    {
      const QGauss<2> quadrature(model.fe.degree + 1);
      FEFaceValues<3> fv(model.mapping,
                         model.fe,
                         quadrature,
                         update_JxW_values);
      double          area = 0.;
      for (const auto &cell : model.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == id)
              {
                fv.reinit(cell, f);
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  area += fv.JxW(q);
              }
      return Utilities::MPI::sum(area, model.comm);
    }

    void
    add_lumped_masses(const StructuralModel &model, Vector<double> &lumped)
    {
      const auto                          &fe = model.fe;
      const QGaussLobatto<2>               quadrature(fe.degree + 1);
      FEFaceValues<3>                      fv(model.mapping,
                         fe,
                         quadrature,
                         update_values | update_JxW_values);
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      for (const scene::LumpedMass &m : model.scene->masses)
        if (m.on_faces)
          {
            const double density = m.mass / boundary_area(model, m.faces);
            // every cell of the shared mesh: the vector is whole on each rank
            for (const auto &cell : model.dof_handler.active_cell_iterators())
              for (const unsigned int f : cell->face_indices())
                if (cell->face(f)->at_boundary() &&
                    cell->face(f)->boundary_id() == m.faces)
                  {
                    fv.reinit(cell, f);
                    cell->get_dof_indices(dofs);
                    for (unsigned int i = 0; i < dofs.size(); ++i)
                      for (unsigned int q = 0; q < quadrature.size(); ++q)
                        lumped[dofs[i]] += density * fv.shape_value(i, q) *
                                           fv.shape_value(i, q) * fv.JxW(q);
                  }
          }
      for (const auto &pm : model.point_masses)
        for (const auto d : pm.dofs)
          lumped[d] += pm.mass;
    }

    void
    StructuralModel::add_masses(ConditionalOStream &pcout)
    {
      if (scene->masses.empty())
        return;
      const QGauss<2>                      quadrature(fe.degree + 1);
      FEFaceValues<3>                      fv(mapping,
                         fe,
                         quadrature,
                         update_values | update_JxW_values);
      const unsigned int                   n = fe.n_dofs_per_cell();
      FullMatrix<double>                   cell_m(n, n);
      std::vector<types::global_dof_index> dofs(n);
      const auto [points, component] = dof_support_points(*this);
      const auto hanging             = [&](const types::global_dof_index d) {
        const auto *entries = constraints.get_constraint_entries(d);
        return entries != nullptr && !entries->empty();
      };
      double total = 0.;
      for (const scene::LumpedMass &m : scene->masses)
        {
          total += m.mass;
          if (m.on_faces)
            {
              const double density = m.mass / boundary_area(*this, m.faces);
              for (const auto &cell : dof_handler.active_cell_iterators())
                if (cell->is_locally_owned())
                  for (const unsigned int f : cell->face_indices())
                    if (cell->face(f)->at_boundary() &&
                        cell->face(f)->boundary_id() == m.faces)
                      {
                        fv.reinit(cell, f);
                        cell_m = 0;
                        for (unsigned int q = 0; q < quadrature.size(); ++q)
                          for (unsigned int i = 0; i < n; ++i)
                            for (unsigned int j = 0; j < n; ++j)
                              if (fe.system_to_component_index(i).first ==
                                  fe.system_to_component_index(j).first)
                                cell_m(i, j) += density * fv.shape_value(i, q) *
                                                fv.shape_value(j, q) *
                                                fv.JxW(q);
                        cell->get_dof_indices(dofs);
                        constraints.distribute_local_to_global(cell_m,
                                                               dofs,
                                                               mass);
                      }
              continue;
            }
          // the nearest owned, not hanging x DoF on each rank, then the
          // nearest of all (the lowest index among equally near ones)
          double                  best = 1e300;
          types::global_dof_index best_dof =
            std::numeric_limits<types::global_dof_index>::max();
          for (const auto d : locally_owned_dofs)
            if (component[d] == 0 && !hanging(d))
              {
                const double r = points[d].distance(m.point);
                if (r < best - 1e-12 || (r < best + 1e-12 && d < best_dof))
                  {
                    best     = std::min(best, r);
                    best_dof = d;
                  }
              }
          const double                  d_min = Utilities::MPI::min(best, comm);
          const types::global_dof_index x_dof = Utilities::MPI::min(
            best < d_min + 1e-12 ?
              best_dof :
              std::numeric_limits<types::global_dof_index>::max(),
            comm);
          // its node's three DoFs and body, from the rank that owns it
          std::vector<double> found(4, 0.);
          if (locally_owned_dofs.is_element(x_dof))
            {
              found[0] = x_dof;
              for (const auto d : locally_owned_dofs)
                if (component[d] != 0 &&
                    points[d].distance(points[x_dof]) <= 1e-12 * (1. + d_min))
                  found[component[d]] = d;
              for (const auto &cell : dof_handler.active_cell_iterators())
                if (cell->is_locally_owned())
                  {
                    cell->get_dof_indices(dofs);
                    if (std::find(dofs.begin(), dofs.end(), x_dof) !=
                        dofs.end())
                      {
                        found[3] = cell->material_id();
                        break;
                      }
                  }
            }
          std::vector<double> all(4);
          Utilities::MPI::sum(found, comm, all);
          PointMass pm;
          for (unsigned int c = 0; c < 3; ++c)
            pm.dofs[c] = static_cast<types::global_dof_index>(all[c]);
          pm.mass = m.mass;
          pm.body = static_cast<types::material_id>(all[3]);
          for (const auto d : pm.dofs)
            if (locally_owned_dofs.is_element(d))
              mass.add(d, d, m.mass);
          point_masses.push_back(pm);
        }
      mass.compress(VectorOperation::add);
      pcout << "Masses: " << scene->masses.size() << " lumped, " << total
            << " kg in all" << std::endl;
    }

    HeldDofs
    held_dofs(const StructuralModel           &model,
              const std::vector<Point<3>>     &points,
              const std::vector<unsigned int> &component)
    {
      const types::global_dof_index n = model.n_dofs();
      HeldDofs                      held;
      held.on_holds.assign(n, false);
      for (const scene::Hold &hold : model.scene->holds)
        {
          const std::vector<bool> on = dofs_on_boundary(model, hold.id);
          for (types::global_dof_index i = 0; i < n; ++i)
            held.on_holds[i] =
              held.on_holds[i] || (on[i] && hold.components[component[i]]);
        }
      for (const scene::PointHold &hold : model.scene->point_holds)
        {
          types::global_dof_index nearest = numbers::invalid_dof_index;
          double                  best    = 1e300;
          for (types::global_dof_index d = 0; d < points.size(); ++d)
            if (component[d] == hold.component &&
                points[d].distance(hold.point) < best)
              {
                best    = points[d].distance(hold.point);
                nearest = d;
              }
          held.point_held.push_back(nearest);
        }
      return held;
    }

    void
    StructuralModel::setup_and_assemble(ConditionalOStream &pcout)
    {
      scene = scene::make_scene(prm);
      scene->make_mesh(triangulation);
      setup_dofs_and_assemble(pcout);
    }

    void
    StructuralModel::refine(const Vector<float> &indicator,
                            const double         fraction,
                            const bool           by_error,
                            ConditionalOStream  &pcout)
    {
      if (indicator.size() != triangulation.n_active_cells())
        throw std::runtime_error(
          "a refinement indicator needs one value per active cell (" +
          std::to_string(triangulation.n_active_cells()) + "), got " +
          std::to_string(indicator.size()));
      if (by_error)
        GridRefinement::refine_and_coarsen_fixed_fraction(
          triangulation,
          indicator,
          fraction,
          0.,
          std::numeric_limits<unsigned int>::max(),
          VectorTools::L2_norm);
      else
        GridRefinement::refine_and_coarsen_fixed_number(triangulation,
                                                        indicator,
                                                        fraction,
                                                        0.);
      std::vector<bool> flags;
      triangulation.save_refine_flags(flags);
      refinement_history.push_back(flags);
      triangulation.execute_coarsening_and_refinement();
      setup_dofs_and_assemble(pcout);
    }

    void
    StructuralModel::replay_refinement(
      const std::vector<std::vector<bool>> &history,
      ConditionalOStream                   &pcout)
    {
      for (const auto &flags : history)
        {
          // deal.II stores dim bits (the refinement case) per active cell
          if (flags.size() != 3 * triangulation.n_active_cells())
            throw std::runtime_error(
              "replay_refinement: a step has " + std::to_string(flags.size()) +
              " refine-flag bits for a mesh of " +
              std::to_string(triangulation.n_active_cells()) +
              " cells (3 per cell expected)");
          triangulation.load_refine_flags(flags);
          triangulation.execute_coarsening_and_refinement();
          refinement_history.push_back(flags);
        }
      setup_dofs_and_assemble(pcout);
    }

    std::vector<std::complex<double>>
    transfer_field(const StructuralModel                   &from,
                   const std::vector<std::complex<double>> &field,
                   const StructuralModel                   &to)
    {
      if (field.size() != from.n_dofs() ||
          from.triangulation.n_active_cells() !=
            to.triangulation.n_active_cells())
        throw std::runtime_error(
          "transfer_field: the field or the meshes do not match (" +
          std::to_string(field.size()) + " values for " +
          std::to_string(from.n_dofs()) + " DoFs; " +
          std::to_string(from.triangulation.n_active_cells()) + " and " +
          std::to_string(to.triangulation.n_active_cells()) + " cells)");
      const Quadrature<3> at_to_points(to.fe.get_unit_support_points());
      FEValues<3> fe_values(from.mapping, from.fe, at_to_points, update_values);
      std::vector<types::global_dof_index> from_dofs(from.fe.n_dofs_per_cell()),
        to_dofs(to.fe.n_dofs_per_cell());
      std::vector<std::complex<double>> result(to.n_dofs());
      auto                              cell_to = to.dof_handler.begin_active();
      for (const auto &cell : from.dof_handler.active_cell_iterators())
        {
          if (cell->center().distance(cell_to->center()) > 1e-9)
            throw std::runtime_error(
              "transfer_field: the meshes differ (cell " +
              std::to_string(cell->active_cell_index()) + ")");
          fe_values.reinit(cell);
          cell->get_dof_indices(from_dofs);
          cell_to->get_dof_indices(to_dofs);
          for (unsigned int q = 0; q < to_dofs.size(); ++q)
            {
              const unsigned int   c = to.fe.system_to_component_index(q).first;
              std::complex<double> v = 0.;
              for (unsigned int j = 0; j < from_dofs.size(); ++j)
                if (from.fe.system_to_component_index(j).first == c)
                  v += field[from_dofs[j]] * fe_values.shape_value(j, q);
              result[to_dofs[q]] = v;
            }
          ++cell_to;
        }
      return result;
    }

    void
    StructuralModel::setup_dofs_and_assemble(ConditionalOStream &pcout)
    {
      dof_handler.distribute_dofs(fe);
      locally_owned_dofs = dof_handler.locally_owned_dofs();
      DoFTools::extract_locally_relevant_dofs(dof_handler,
                                              locally_relevant_dofs);

      constraints.clear();
      constraints.reinit(locally_relevant_dofs);
      DoFTools::make_hanging_node_constraints(dof_handler, constraints);
      for (const scene::Hold &hold : scene->holds)
        VectorTools::interpolate_boundary_values(
          mapping,
          dof_handler,
          hold.id,
          Functions::ZeroFunction<3>(3),
          constraints,
          ComponentMask(
            std::vector<bool>(hold.components.begin(), hold.components.end())));
      constraints.close();

      // one list per contact pair
      std::vector<std::vector<CouplingPoint>> pair_points;
      for (const scene::ContactPair &pair : scene->contact_pairs)
        pair_points.push_back(
          interface_quadrature(dof_handler,
                               mapping,
                               pair,
                               prm.interface.quadrature,
                               prm.interface.quadrature == "nodal" ?
                                 prm.mesh.fe_degree + 1 :
                                 prm.mesh.fe_degree + 2));
      for (auto &interface_points : pair_points)
        if (interface_mask)
          {
            std::vector<CouplingPoint> kept;
            for (CouplingPoint p : interface_points)
              {
                p.weight *= interface_mask(
                  mapping.transform_unit_to_real_cell(p.pad_cell, p.pad_unit));
                if (p.weight != 0.)
                  kept.push_back(p);
              }
            pcout << "Interface: " << kept.size() << " of "
                  << interface_points.size()
                  << " quadrature points in contact after the preload"
                  << std::endl;
            interface_points.swap(kept);
          }

      DynamicSparsityPattern dsp(locally_relevant_dofs);
      DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
      for (const auto &interface_points : pair_points)
        add_interface_sparsity(interface_points, constraints, dsp);
      SparsityTools::distribute_sparsity_pattern(dsp,
                                                 locally_owned_dofs,
                                                 comm,
                                                 locally_relevant_dofs);
      for (auto *m : {&mass,
                      &mass_support,
                      &stiffness_rest,
                      &stiffness_pad,
                      &stiffness_springs,
                      &interface_normal,
                      &interface_friction})
        m->reinit(locally_owned_dofs, locally_owned_dofs, dsp, comm);

      pcout << "Mesh: " << triangulation.n_active_cells() << " cells, "
            << dof_handler.n_dofs() << " DoFs (degree " << prm.mesh.fe_degree
            << "), " << constraints.n_constraints() << " constrained"
            << std::endl;

      // Reference values of the scaled parts: the file's, 1 where it is 0.
      reference = prm.nominal_point();
      for (double *v : {&reference.E_pad,
                        &reference.support_density,
                        &reference.spring_stiffness,
                        &reference.interface_stiffness})
        if (*v == 0.)
          *v = 1.;
      assemble_elasticity();
      add_masses(pcout);
      for (const scene::SpringSet &springs : scene->springs)
        add_springs(springs, pcout);
      for (unsigned int i = 0; i < pair_points.size(); ++i)
        assemble_interface(pair_points[i],
                           constraints,
                           reference.interface_stiffness,
                           scene->contact_pairs[i],
                           interface_normal,
                           interface_friction);
      interface_normal.compress(VectorOperation::add);
      interface_friction.compress(VectorOperation::add);

      // Constrained rows: K_ii = d, M_ii = d / omega_s^2, all parts else 0;
      // d from the disc and support elasticity alone, so that it does not
      // depend on any swept parameter.
      double trace = 0, n_free = 0;
      for (const auto i : locally_owned_dofs)
        if (!constraints.is_constrained(i))
          {
            trace += stiffness_rest.diag_element(i);
            n_free += 1;
          }
      constrained_diagonal = Utilities::MPI::sum(trace, comm) /
                             std::max(1., Utilities::MPI::sum(n_free, comm));
      const double omega_s = 2. * numbers::PI * 1e3 * prm.eigensolver.f_max;
      set_constrained_diagonal(constraints,
                               locally_owned_dofs,
                               constrained_diagonal,
                               stiffness_rest);
      set_constrained_diagonal(constraints,
                               locally_owned_dofs,
                               constrained_diagonal / (omega_s * omega_s),
                               mass);
      for (auto *m : {&mass_support,
                      &stiffness_pad,
                      &stiffness_springs,
                      &interface_normal,
                      &interface_friction})
        set_constrained_diagonal(constraints, locally_owned_dofs, 0., *m);
    }

    void
    add_cell_elasticity(const FEValues<3>  &fe_values,
                        const double        lambda,
                        const double        mu,
                        const double        density,
                        FullMatrix<double> &cell_k,
                        FullMatrix<double> &cell_m)
    {
      const FiniteElement<3> &fe = fe_values.get_fe();
      const unsigned int      n  = fe.n_dofs_per_cell();
      for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
        {
          const double JxW = fe_values.JxW(q);
          for (unsigned int i = 0; i < n; ++i)
            {
              const unsigned int ci = fe.system_to_component_index(i).first;
              const Tensor<1, 3> gi = fe_values.shape_grad(i, q);
              const double       vi = fe_values.shape_value(i, q);
              for (unsigned int j = 0; j < n; ++j)
                {
                  const unsigned int cj = fe.system_to_component_index(j).first;
                  const Tensor<1, 3> gj = fe_values.shape_grad(j, q);
                  double k = lambda * gi[ci] * gj[cj] + mu * gi[cj] * gj[ci];
                  if (ci == cj)
                    {
                      k += mu * (gi * gj);
                      cell_m(i, j) +=
                        density * vi * fe_values.shape_value(j, q) * JxW;
                    }
                  cell_k(i, j) += k * JxW;
                }
            }
        }
    }

    void
    StructuralModel::assemble_elasticity()
    {
      const QGauss<3>                      quadrature(fe.degree + 1);
      FEValues<3>                          fe_values(mapping,
                            fe,
                            quadrature,
                            update_values | update_gradients |
                              update_JxW_values | update_quadrature_points);
      const unsigned int                   n = fe.n_dofs_per_cell();
      FullMatrix<double>                   cell_k(n, n), cell_m(n, n);
      std::vector<SymmetricTensor<4, 3>>   C_q(quadrature.size());
      std::vector<types::global_dof_index> dofs(n);

      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const scene::Body &body       = scene->body(cell->material_id());
            const bool         is_pad     = body.modulus_swept;
            const bool         is_support = body.density_swept;
            const double       E  = scene->youngs_modulus(body.id, reference);
            const double       nu = body.material.poisson_ratio;
            const double       density = scene->density(body.id, reference);
            const auto [lambda, mu]    = lame_constants(E, nu);

            fe_values.reinit(cell);
            cell_k = 0;
            cell_m = 0;
            if (body.law.anisotropic)
              {
                // the law at each quadrature point (a cylindrical frame
                // turns with the point); the mass as for an isotropic body
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  C_q[q] =
                    scene->stiffness_tensor(body.id,
                                            fe_values.quadrature_point(q),
                                            reference);
                add_cell_stiffness(fe_values, C_q, cell_k);
                add_cell_elasticity(fe_values, 0., 0., density, cell_k, cell_m);
              }
            else
              add_cell_elasticity(
                fe_values, lambda, mu, density, cell_k, cell_m);
            cell->get_dof_indices(dofs);
            constraints.distribute_local_to_global(
              cell_k, dofs, is_pad ? stiffness_pad : stiffness_rest);
            constraints.distribute_local_to_global(
              cell_m, dofs, is_support ? mass_support : mass);
          }
      for (auto *m : {&mass, &mass_support, &stiffness_rest, &stiffness_pad})
        m->compress(VectorOperation::add);
    }

    void
    StructuralModel::add_springs(const scene::SpringSet &s,
                                 ConditionalOStream     &pcout)
    {
      const std::vector<Point<3>> &stations = s.stations;
      if (stations.empty())
        return;
      if (s.station_normals.size() != stations.size())
        throw std::runtime_error("springs '" + s.name +
                                 "': one face normal per station needed");
      // the components the springs act along (for the point springs: one)
      std::vector<unsigned int> acting;
      for (unsigned int c = 0; c < 3; ++c)
        if (s.direction[c] != 0.)
          acting.push_back(c);

      std::vector<double>               total(stations.size(), 0.);
      std::vector<unsigned int>         faces_per_spring(stations.size(), 0);
      const std::vector<SpringFaceRule> rules =
        spring_face_rules(s, total, faces_per_spring);
      {
        const std::vector<double> local = total;
        Utilities::MPI::sum(local, comm, total);
      }
      assemble_spread_springs(s, rules, total);
      const bool any_point =
        std::find(total.begin(), total.end(), 0.) != total.end();
      if (any_point && acting.size() != 1)
        throw std::runtime_error(
          "springs '" + s.name +
          "': a station has no face within the "
          "attachment radius, and a spring at one node needs a direction "
          "along a coordinate axis; give a radius that reaches the faces");
      const auto [worst, n_point] =
        any_point ? add_nearest_node_springs(s, total, acting[0]) :
                    std::pair<double, unsigned int>(0., 0u);
      const double a = s.radius;
      stiffness_springs.compress(VectorOperation::add);
      // faces per spread spring (a report, not an input)
      std::vector<unsigned int> counts(stations.size());
      Utilities::MPI::sum(faces_per_spring, comm, counts);
      unsigned int n_min = std::numeric_limits<unsigned int>::max(), n_max = 0;
      for (unsigned int i = 0; i < stations.size(); ++i)
        if (total[i] > 0.)
          {
            n_min = std::min(n_min, counts[i]);
            n_max = std::max(n_max, counts[i]);
          }
      pcout << "Springs: " << stations.size() << " x " << s.stiffness
            << " N/m along (" << s.direction << "), ";
      if (n_point == stations.size())
        pcout << "each at the nearest node";
      else
        pcout << stations.size() - n_point << " spread over radius " << 1e3 * a
              << " mm ("
              << (lumped_springs ? "lumped on the face nodes" :
                                   "consistent Winkler layer")
              << ", " << n_min << "-" << n_max << " faces each)"
              << (n_point > 0 ? ", " + std::to_string(n_point) +
                                  " at the nearest node (none inside)" :
                                "");
      if (worst > 1e-9)
        pcout << " (WARNING: a station lies " << worst
              << " m from the nearest node; choose mesh counts that put "
                 "nodes at the stations)";
      pcout << std::endl;
    }

    // One record per face the bells touch: the quadrature points some
    // bell covers, in the cell's unit coordinates, each with its (spring,
    // bell x JxW [m^2]) pairs, and the shape functions of the acting
    // components nonzero on the face.
    struct StructuralModel::SpringFaceRule
    {
      DoFHandler<3>::active_cell_iterator                       cell;
      std::vector<Point<3>>                                     unit;
      std::vector<std::vector<std::pair<unsigned int, double>>> weights;
      std::vector<unsigned int>                                 shapes;
    };

    // Each spring spread over the disc of the body's face within the
    // attachment radius of its station, with cosine-bell weights normalised
    // to the spring's stiffness: a Winkler layer of stiffness density
    // k bell(x) / int(bell) [N/m^3] along the spring's direction. Consistent
    // (default): integrated exactly enough by composite Gauss rules of
    // sub-intervals a / 6 on every face the bell touches, so the model is
    // the same on every mesh and degree and a finer space can only lower its
    // frequencies. Lumped (explicit dynamics): the Gauss-Lobatto rule on the
    // face's FE_Q support points, a diagonal that changes with the node
    // spacing.
    std::vector<StructuralModel::SpringFaceRule>
    StructuralModel::spring_face_rules(
      const scene::SpringSet    &s,
      std::vector<double>       &total,
      std::vector<unsigned int> &faces_per_spring) const
    {
      const std::vector<Point<3>> &stations = s.stations;
      const double                 a        = s.radius;
      // distance of x from station i's plane, and within that plane
      const auto off_plane = [&](const Point<3> &x, const unsigned int i) {
        return std::abs((x - stations[i]) * s.station_normals[i]);
      };
      const auto bell = [&](const Point<3> &x, const unsigned int i) {
        if (off_plane(x, i) > s.tolerance)
          return 0.;
        const Tensor<1, 3> d = x - stations[i];
        const Tensor<1, 3> v =
          d - (d * s.station_normals[i]) * s.station_normals[i];
        // |v| by hypot (no overflow; exact when a component is 0)
        const double r = std::hypot(std::hypot(v[0], v[1]), v[2]);
        return r < a ? 0.5 * (1. + std::cos(numbers::PI * r / a)) : 0.;
      };
      const unsigned int n = fe.n_dofs_per_cell();
      // a boundary face of the body on some station's plane
      const auto on_side_face = [&](const auto &cell, const unsigned int f) {
        if (!cell->is_locally_owned() || cell->material_id() != s.body ||
            !cell->face(f)->at_boundary())
          return false;
        for (unsigned int i = 0; i < stations.size(); ++i)
          if (off_plane(cell->face(f)->center(), i) < s.tolerance)
            return true;
        return false;
      };
      std::vector<SpringFaceRule> rules;
      const QGauss<1>             gauss(fe.degree + 1);
      if (a > 0)
        for (const auto &cell : dof_handler.active_cell_iterators())
          for (const auto f : cell->face_indices())
            if (on_side_face(cell, f))
              {
                const auto   face = cell->face(f);
                const double h    = face->diameter();
                bool         near = false;
                for (unsigned int i = 0; i < stations.size(); ++i)
                  near =
                    near || (off_plane(face->center(), i) < s.tolerance &&
                             face->center().distance(stations[i]) < a + h / 2);
                if (!near)
                  continue;
                // the face must be a parallelogram (weights = unit weights
                // times its area)
                const Tensor<1, 3> d = face->vertex(0) + face->vertex(3) -
                                       face->vertex(1) - face->vertex(2);
                if (!(d.norm() < 1e-9 * h))
                  throw std::runtime_error(
                    "springs '" + s.name +
                    "': a face they spread over is "
                    "not a parallelogram; set their attachment radius to 0 "
                    "(point springs) or remesh the face");
                const Quadrature<2> q2 =
                  lumped_springs ?
                    Quadrature<2>(QGaussLobatto<2>(fe.degree + 1)) :
                    Quadrature<2>(
                      QIterated<2>(gauss,
                                   std::min(200u,
                                            static_cast<unsigned int>(
                                              std::ceil(6. * h / a)))));
                const Quadrature<3> q3 =
                  QProjector<3>::project_to_face(ReferenceCells::Hexahedron,
                                                 q2,
                                                 f);
                SpringFaceRule    rule;
                std::vector<bool> touched(stations.size(), false);
                rule.cell = cell;
                for (unsigned int q = 0; q < q3.size(); ++q)
                  {
                    const Point<3> x =
                      mapping.transform_unit_to_real_cell(cell, q3.point(q));
                    std::vector<std::pair<unsigned int, double>> w;
                    for (unsigned int i = 0; i < stations.size(); ++i)
                      if (const double b = bell(x, i); b > 0.)
                        {
                          w.emplace_back(i, b * q3.weight(q) * face->measure());
                          total[i] += w.back().second;
                          touched[i] = true;
                        }
                    if (w.empty())
                      continue;
                    rule.unit.push_back(q3.point(q));
                    rule.weights.push_back(std::move(w));
                  }
                for (unsigned int i = 0; i < stations.size(); ++i)
                  faces_per_spring[i] += touched[i];
                for (unsigned int k = 0; k < n; ++k)
                  if (s.direction[fe.system_to_component_index(k).first] !=
                        0. &&
                      fe.has_support_on_face(k, f))
                    rule.shapes.push_back(k);
                rules.push_back(std::move(rule));
              }
      return rules;
    }

    void
    StructuralModel::assemble_spread_springs(
      const scene::SpringSet            &s,
      const std::vector<SpringFaceRule> &rules,
      const std::vector<double>         &total)
    {
      const unsigned int                   n = fe.n_dofs_per_cell();
      FullMatrix<double>                   cell_k(n, n);
      std::vector<types::global_dof_index> dofs(n);
      std::vector<double>                  phi;
      for (const auto &rule : rules)
        {
          cell_k = 0;
          phi.resize(rule.shapes.size());
          for (unsigned int q = 0; q < rule.unit.size(); ++q)
            {
              double c = 0.;
              for (const auto &[i, w] : rule.weights[q])
                c += reference.spring_stiffness * w / total[i];
              for (unsigned int k = 0; k < phi.size(); ++k)
                {
                  const unsigned int comp =
                    fe.system_to_component_index(rule.shapes[k]).first;
                  phi[k] =
                    s.direction[comp] * fe.shape_value_component(rule.shapes[k],
                                                                 rule.unit[q],
                                                                 comp);
                }
              for (unsigned int k = 0; k < phi.size(); ++k)
                for (unsigned int l = 0; l < phi.size(); ++l)
                  cell_k(rule.shapes[k], rule.shapes[l]) += c * phi[k] * phi[l];
            }
          if (!rule.unit.empty())
            {
              rule.cell->get_dof_indices(dofs);
              constraints.distribute_local_to_global(cell_k,
                                                     dofs,
                                                     stiffness_springs);
            }
        }
    }

    // Stations with no node inside the radius (or radius 0): the nearest
    // unconstrained support node takes the whole spring (its DoF of the
    // acting component); among nodes at the same distance the lowest DoF
    // index, the same on every rank.
    std::pair<double, unsigned int>
    StructuralModel::add_nearest_node_springs(const scene::SpringSet    &s,
                                              const std::vector<double> &total,
                                              const unsigned int component)
    {
      const std::vector<Point<3>>         &stations = s.stations;
      const unsigned int                   n        = fe.n_dofs_per_cell();
      std::vector<types::global_dof_index> dofs(n);
      const auto                          &unit = fe.get_unit_support_points();
      std::vector<double>                  best(stations.size(), 1e300);
      std::vector<types::global_dof_index> best_dof(
        stations.size(), std::numeric_limits<types::global_dof_index>::max());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial() && cell->material_id() == s.body)
          {
            cell->get_dof_indices(dofs);
            for (unsigned int k = 0; k < n; ++k)
              if (fe.system_to_component_index(k).first == component &&
                  !constraints.is_constrained(dofs[k])) // not hanging
                {
                  const Point<3> x =
                    mapping.transform_unit_to_real_cell(cell, unit[k]);
                  for (unsigned int i = 0; i < stations.size(); ++i)
                    {
                      const double d = x.distance(stations[i]);
                      if (d < best[i] - 1e-12 ||
                          (d < best[i] + 1e-12 && dofs[k] < best_dof[i]))
                        {
                          best[i]     = std::min(best[i], d);
                          best_dof[i] = dofs[k];
                        }
                    }
                }
          }
      double       worst   = 0;
      unsigned int n_point = 0;
      for (unsigned int i = 0; i < stations.size(); ++i)
        if (total[i] == 0.)
          {
            ++n_point;
            const double d = Utilities::MPI::min(best[i], comm);
            const types::global_dof_index dof = Utilities::MPI::min(
              best[i] < d + 1e-12 ?
                best_dof[i] :
                std::numeric_limits<types::global_dof_index>::max(),
              comm);
            worst = std::max(worst, d);
            if (locally_owned_dofs.is_element(dof))
              stiffness_springs.add(dof,
                                    dof,
                                    reference.spring_stiffness *
                                      s.direction[component] *
                                      s.direction[component]);
          }
      return {worst, n_point};
    }


    MatrixParts::Combination
    MatrixParts::coefficients(const parameters::ScalarPoint &p) const
    {
      const auto &r = reference;
      Combination c;
      c.mass = {{1., p.support_density / r.support_density, 0, 0, 0, 0, 0}};
      c.structural          = {{0,
                                0,
                                1.,
                                p.E_pad / r.E_pad,
                                p.spring_stiffness / r.spring_stiffness,
                                0,
                                0}};
      const double kn       = p.interface_stiffness / r.interface_stiffness;
      c.symmetric_stiffness = c.structural;
      c.symmetric_stiffness[interface_normal] = kn;
      c.stiffness                             = c.symmetric_stiffness;
      c.stiffness[interface_friction]         = kn * p.mu;
      for (unsigned int k = 0; k < n_parts; ++k)
        c.damping[k] = p.alpha * c.mass[k] + p.beta * c.structural[k];
      return c;
    }

    void
    MatrixParts::combine(const Coefficients &c, PETScMatrix &result) const
    {
      // all parts share one sparsity pattern: copy one, add the others
      result.reinit(*matrix[0]);
      result.copy_from(*matrix[0]);
      result *= c[0];
      for (unsigned int k = 1; k < n_parts; ++k)
        if (c[k] != 0.)
          result.add(c[k], *matrix[k]);
    }

    void
    MatrixParts::mass(const parameters::ScalarPoint &p, PETScMatrix &M) const
    {
      combine(coefficients(p).mass, M);
    }

    void
    MatrixParts::stiffness(const parameters::ScalarPoint &p,
                           PETScMatrix                   &K) const
    {
      combine(coefficients(p).stiffness, K);
    }

    void
    MatrixParts::symmetric_stiffness(const parameters::ScalarPoint &p,
                                     PETScMatrix                   &K) const
    {
      combine(coefficients(p).symmetric_stiffness, K);
    }

    void
    MatrixParts::damping(const parameters::ScalarPoint &p, PETScMatrix &C) const
    {
      combine(coefficients(p).damping, C);
    }
  } // namespace physics
} // namespace squeal
