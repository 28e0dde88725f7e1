// The contact problem of a scene (scene_contact.h): merged mortar operators
// of its pairs, the structural system with its holds, the load vector.

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <squeal/contact/scene_contact.h>

#include <cmath>
#include <set>

namespace squeal
{
  namespace contact
  {
    using namespace dealii;

    const scene::ContactPair &
    single_pair(const scene::Scene &scene)
    {
      if (scene.contact_pairs.size() != 1)
        throw std::runtime_error(
          "scene " + scene.description() +
          ": Mesh/Contact refinements "
          "handles exactly one contact pair; the scene has " +
          std::to_string(scene.contact_pairs.size()));
      return scene.contact_pairs.front();
    }

    Tensor<1, 3>
    common_sliding(const scene::Scene &scene)
    {
      if (scene.contact_pairs.empty())
        throw std::runtime_error("scene " + scene.description() +
                                 " has no contact pair");
      const Tensor<1, 3> t = scene.contact_pairs.front().sliding;
      for (const scene::ContactPair &pair : scene.contact_pairs)
        if ((pair.sliding - t).norm() > 1e-9)
          throw std::runtime_error(
            "scene " + scene.description() + ": contact pairs '" +
            scene.contact_pairs.front().name + "' and '" + pair.name +
            "' slide along different directions; the preload and the "
            "braking run take one sliding direction for all pairs");
      return t;
    }

    std::set<types::boundary_id>
    slave_ids(const scene::Scene &scene)
    {
      std::set<types::boundary_id> ids;
      for (const scene::ContactPair &pair : scene.contact_pairs)
        ids.insert(pair.slave);
      return ids;
    }

    MortarOperators
    scene_mortar(const physics::StructuralModel &model,
                 const double                    search_distance,
                 ConditionalOStream             &pcout)
    {
      std::vector<MortarOperators> ops;
      for (const scene::ContactPair &pair : model.scene->contact_pairs)
        {
          ops.push_back(build_mortar_operators(model.dof_handler,
                                               model.mapping,
                                               pair.slave,
                                               pair.master,
                                               search_distance));
          const MortarOperators &op = ops.back();
          pcout << "Contact pair '" << pair.name << "': " << op.n_slave()
                << " slave nodes, slave face " << op.slave_area * 1e6
                << " mm^2, " << 100. * op.covered_area / op.slave_area
                << " % over the master face" << std::endl;
        }
      return merge_mortar_operators(ops);
    }

    std::vector<double>
    pair_normal_stiffness(const scene::Scene            &scene,
                          const parameters::ScalarPoint &point,
                          const MortarOperators         &op)
    {
      std::vector<double> k(op.n_slave());
      for (unsigned int j = 0; j < op.n_slave(); ++j)
        k[j] = point.get(
          scene.contact_pairs.at(op.slave_pair.empty() ? 0 : op.slave_pair[j])
            .name +
          ".k_n");
      return k;
    }

    std::pair<types::global_dof_index, Point<3>>
    contact_system(const physics::StructuralModel &model,
                   SparsityPattern                &pattern,
                   SparseMatrix<double>           &stiffness,
                   AffineConstraints<double>      &constraints)
    {
      // K_s at the nominal point, as a deal.II matrix.
      const physics::MatrixParts parts = model.parts();
      physics::PETScMatrix       K;
      parts.combine(parts.coefficients(model.scene->nominal_point()).structural,
                    K);
      physics::copy_to_serial(K, pattern, stiffness);

      constraints.copy_from(model.constraints);
      // The scene's point holds: one component of the node nearest each
      // point (the TriboBrake's loading arm holds the support top's centre
      // along the radius: a sliding contact does not hold it there).
      const auto [points, component] = physics::dof_support_points(model);
      types::global_dof_index held   = numbers::invalid_dof_index;
      for (const auto d :
           physics::held_dofs(model, points, component).point_held)
        {
          held = d;
          if (held == numbers::invalid_dof_index ||
              constraints.is_constrained(held))
            continue;
          constraints.add_line(held);
          const double diag = stiffness.diag_element(held);
          for (auto e = stiffness.begin(held); e != stiffness.end(held); ++e)
            if (e->column() != held)
              {
                stiffness.set(e->column(), held, 0.);
                e->value() = 0.;
              }
          stiffness.set(held, held, diag);
        }
      constraints.close();
      return {held,
              held == numbers::invalid_dof_index ? Point<3>() : points[held]};
    }

    Point<3>
    contact_system(const physics::StructuralModel &model,
                   physics::PETScMatrix           &stiffness,
                   AffineConstraints<double>      &constraints,
                   MPI_Comm                        comm)
    {
      const physics::MatrixParts parts = model.parts();
      parts.combine(parts.coefficients(model.scene->nominal_point()).structural,
                    stiffness);
      const unsigned int n = model.n_dofs();
      // Constraints on all DoFs, identical on every rank (the model's hold
      // only the locally relevant ones): hanging nodes over the whole shared
      // mesh, the clamped faces, the radial hold.
      const auto [points, component] = physics::dof_support_points(model);
      constraints.clear();
      DoFTools::make_hanging_node_constraints(model.dof_handler, constraints);
      const physics::HeldDofs fixed =
        physics::held_dofs(model, points, component);
      for (types::global_dof_index i = 0; i < n; ++i)
        if (fixed.on_holds[i] && !constraints.is_constrained(i))
          constraints.add_line(i);
      types::global_dof_index held = 0;
      for (const auto d : fixed.point_held)
        {
          held = d;
          if (constraints.is_constrained(held))
            continue;
          constraints.add_line(held);
          // its row: the diagonal alone (its column multiplies x_held = 0)
          const auto   range = stiffness.local_range();
          const bool   mine  = held >= range.first && held < range.second;
          const double diag =
            Utilities::MPI::sum(mine ? stiffness.diag_element(held) : 0., comm);
          stiffness.clear_rows(mine ?
                                 std::vector<types::global_dof_index>{held} :
                                 std::vector<types::global_dof_index>{},
                               diag);
        }
      if (!model.scene->ties.empty())
        add_tie_constraints(model, constraints);
      constraints.close();
      return points[held];
    }

    void
    add_tie_constraints(const physics::StructuralModel &model,
                        AffineConstraints<double>      &constraints)
    {
      for (const scene::Tie &tie : model.scene->ties)
        {
          MortarOperators op;
          try
            {
              op = build_mortar_operators(model.dof_handler,
                                          model.mapping,
                                          tie.slave,
                                          tie.master,
                                          model.prm.preload.search_distance);
            }
          catch (const std::exception &e)
            {
              throw std::runtime_error("tie '" + tie.name + "': " + e.what());
            }
          for (unsigned int j = 0; j < op.n_slave(); ++j)
            {
              double sum = 0.;
              for (const auto &[l, m] : op.M[j])
                sum += m;
              if (!(sum > 0.))
                continue; // no master under it
              for (unsigned int c = 0; c < 3; ++c)
                {
                  const auto dof = op.slave_dofs[j][c];
                  if (constraints.is_constrained(dof))
                    continue;
                  constraints.add_line(dof);
                  for (const auto &[l, m] : op.M[j])
                    if (op.master_dofs[l][c] != dof && m != 0.)
                      constraints.add_entry(dof, op.master_dofs[l][c], m / sum);
                }
            }
        }
    }

    Vector<double>
    scene_load(const physics::StructuralModel  &model,
               const AffineConstraints<double> &constraints,
               const double                     force,
               const int                        only,
               double                          *total)
    {
      if (model.scene->loads.empty())
        throw std::runtime_error("scene " + model.scene->description() +
                                 ": the preload and the braking run need a "
                                 "load; the scene has none");
      Vector<double>                       load(model.n_dofs());
      const auto                          &fe = model.fe;
      const QGauss<2>                      q(fe.degree + 1);
      FEFaceValues<3>                      fv(model.mapping,
                         fe,
                         q,
                         update_values | update_JxW_values);
      Vector<double>                       cell_f(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      // Each load: a uniform traction on its faces.
      if (total)
        *total = 0.;
      for (unsigned int l = 0; l < model.scene->loads.size(); ++l)
        {
          const scene::Load &applied = model.scene->loads[l];
          if (only >= 0 && static_cast<unsigned int>(only) != l)
            continue;
          double area = 0.;
          for (const auto &cell : model.dof_handler.active_cell_iterators())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() == applied.id)
                {
                  fv.reinit(cell, f);
                  for (unsigned int k = 0; k < q.size(); ++k)
                    area += fv.JxW(k);
                }
          if (!(area > 0.))
            throw std::runtime_error("load '" + applied.name +
                                     "': its face set has no faces");
          using Magnitude = scene::Load::Magnitude;
          const double traction =
            applied.magnitude == Magnitude::pressure ? applied.value :
            applied.magnitude == Magnitude::force    ? applied.value / area :
                                                       force / area;
          if (total)
            *total += traction * area;
          for (const auto &cell : model.dof_handler.active_cell_iterators())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() == applied.id)
                {
                  fv.reinit(cell, f);
                  cell_f = 0.;
                  for (unsigned int k = 0; k < q.size(); ++k)
                    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
                      if (const double t =
                            applied
                              .direction[fe.system_to_component_index(i).first];
                          t != 0.)
                        cell_f[i] +=
                          traction * t * fv.shape_value(i, k) * fv.JxW(k);
                  cell->get_dof_indices(dofs);
                  constraints.distribute_local_to_global(cell_f, dofs, load);
                }
        }
      return load;
    }

  } // namespace contact
} // namespace squeal
