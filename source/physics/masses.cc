// Lumped masses of a scene (a weight on a face set, an accelerometer at a
// point) in the assembled mass and in the explicit dynamics' lumped mass,
// and the modes' kinetic energy by body (the bodies' densities and these
// masses).

#include <deal.II/base/qprojector.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <squeal/physics/structural_model.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace squeal
{
  namespace physics
  {
    using namespace dealii;

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
    StructuralModel::add_mass(const scene::LumpedMass &m, PETScMatrix &M)
    {
      const QGauss<2>                      quadrature(fe.degree + 1);
      FEFaceValues<3>                      fv(mapping,
                         fe,
                         quadrature,
                         update_values | update_JxW_values);
      const unsigned int                   n = fe.n_dofs_per_cell();
      FullMatrix<double>                   cell_m(n, n);
      std::vector<types::global_dof_index> dofs(n);
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
                                            fv.shape_value(j, q) * fv.JxW(q);
                    cell->get_dof_indices(dofs);
                    constraints.distribute_local_to_global(cell_m, dofs, M);
                  }
          M.compress(VectorOperation::add);
          return;
        }
      const auto [points, component] = dof_support_points(*this);
      const auto hanging             = [&](const types::global_dof_index d) {
        const auto *entries = constraints.get_constraint_entries(d);
        return entries != nullptr && !entries->empty();
      };
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
                if (std::find(dofs.begin(), dofs.end(), x_dof) != dofs.end())
                  {
                    found[3] = cell->material_id();
                    break;
                  }
              }
        }
      std::vector<double> all(4);
      Utilities::MPI::sum(found, comm, all);
      PointMass pm;
      pm.name = m.name;
      for (unsigned int c = 0; c < 3; ++c)
        pm.dofs[c] = static_cast<types::global_dof_index>(all[c]);
      pm.mass = m.mass;
      pm.body = static_cast<types::material_id>(all[3]);
      for (const auto d : pm.dofs)
        if (locally_owned_dofs.is_element(d))
          M.add(d, d, m.mass);
      point_masses.push_back(pm);
      M.compress(VectorOperation::add);
    }

    std::vector<double>
    kinetic_energy_by_body(const StructuralModel         &model,
                           const parameters::ScalarPoint &p,
                           const PETScVector             &re,
                           const PETScVector             &im)
    {
      return kinetic_energy_by_body(model, {&p}, {&re}, {&im})[0];
    }

    std::vector<std::vector<double>>
    kinetic_energy_by_body(
      const StructuralModel                              &model,
      const std::vector<const parameters::ScalarPoint *> &p,
      const std::vector<const PETScVector *>             &re,
      const std::vector<const PETScVector *>             &im)
    {
      if (re.size() != p.size() || im.size() != p.size())
        throw std::logic_error(
          "kinetic_energy_by_body: " + std::to_string(p.size()) + " points, " +
          std::to_string(re.size()) + " and " + std::to_string(im.size()) +
          " vectors");
      const std::size_t  m       = p.size();
      types::material_id largest = 0;
      for (const auto &cell : model.triangulation.active_cell_iterators())
        largest = std::max(largest, cell->material_id());
      largest = Utilities::MPI::max(largest, model.comm);
      std::vector<std::vector<double>> energy(m,
                                              std::vector<double>(largest + 1,
                                                                  0.));
      // each mode's real and imaginary parts with the hanging-node values
      std::vector<PETScVector> ghosted;
      ghosted.reserve(2 * m);
      for (std::size_t j = 0; j < m; ++j)
        for (const PETScVector *x : {re[j], im[j]})
          {
            PETScVector owned = *x;
            model.constraints.distribute(owned);
            ghosted.emplace_back(model.locally_owned_dofs,
                                 model.locally_relevant_dofs,
                                 model.comm);
            ghosted.back() = owned;
          }
      const QGauss<3>             quadrature(model.fe.degree + 1);
      FEValues<3>                 fe_values(model.mapping,
                            model.fe,
                            quadrature,
                            update_values | update_JxW_values);
      std::vector<Vector<double>> values(quadrature.size(), Vector<double>(3));
      for (const auto &cell : model.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            for (std::size_t j = 0; j < m; ++j)
              {
                const double rho =
                  model.scene->density(cell->material_id(), *p[j]);
                double &e = energy[j][cell->material_id()];
                for (const std::size_t v : {2 * j, 2 * j + 1})
                  {
                    fe_values.get_function_values(ghosted[v], values);
                    for (unsigned int q = 0; q < quadrature.size(); ++q)
                      e += rho * (values[q] * values[q]) * fe_values.JxW(q);
                  }
              }
          }
      // the lumped masses (at their values at p), with the body they sit on
      const QGauss<2>             face_rule(model.fe.degree + 1);
      FEFaceValues<3>             fv(model.mapping,
                         model.fe,
                         face_rule,
                         update_values | update_JxW_values);
      std::vector<Vector<double>> face_values(face_rule.size(),
                                              Vector<double>(3));
      for (const scene::LumpedMass &lumped : model.scene->masses)
        if (lumped.on_faces)
          {
            const double area = boundary_area(model, lumped.faces);
            for (const auto &cell : model.dof_handler.active_cell_iterators())
              if (cell->is_locally_owned())
                for (const unsigned int f : cell->face_indices())
                  if (cell->face(f)->at_boundary() &&
                      cell->face(f)->boundary_id() == lumped.faces)
                    {
                      fv.reinit(cell, f);
                      for (std::size_t v = 0; v < ghosted.size(); ++v)
                        {
                          fv.get_function_values(ghosted[v], face_values);
                          const double density =
                            p[v / 2]->get(lumped.name + ".m") / area;
                          double &e = energy[v / 2][cell->material_id()];
                          for (unsigned int q = 0; q < face_rule.size(); ++q)
                            e += density * (face_values[q] * face_values[q]) *
                                 fv.JxW(q);
                        }
                    }
          }
      for (const auto &pm : model.point_masses)
        for (std::size_t j = 0; j < m; ++j)
          {
            const double mass = p[j]->get(pm.name + ".m");
            for (const auto d : pm.dofs)
              if (model.locally_owned_dofs.is_element(d))
                for (const std::size_t v : {2 * j, 2 * j + 1})
                  energy[j][pm.body] += mass * ghosted[v](d) * ghosted[v](d);
          }
      for (std::vector<double> &e : energy)
        {
          std::vector<double> total(e.size());
          Utilities::MPI::sum(e, model.comm, total);
          e = std::move(total);
        }
      return energy;
    }
  } // namespace physics
} // namespace squeal
