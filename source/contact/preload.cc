// The static preload of the TriboBrake: the CEA's structure (mesh, FE space,
// matrix parts) at the file's nominal parameters, the normal force on the
// support's top, and the pad pressed on the disc through mortar frictional
// contact. The PETSc stiffness of the structural model is copied into a
// deal.II sparse matrix for the direct solve of the augmented contact system.

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_out_faces.h>

#include <squeal/contact/preload.h>
#include <squeal/output/face_output.h>
#include <squeal/output/output_directory.h>

#include <cmath>
#include <set>
#include <filesystem>
#include <fstream>
#include <iomanip>

namespace squeal
{
  namespace contact
  {
    using namespace dealii;
    namespace fs = std::filesystem;

    namespace
    {
      // The DoF of the point hold's component nearest its point (the
      // lowest such index among equally near ones).
      types::global_dof_index
      nearest_dof(const std::vector<Point<3>>     &points,
                  const std::vector<unsigned int> &component,
                  const scene::PointHold          &hold)
      {
        types::global_dof_index held = numbers::invalid_dof_index;
        double                  best = 1e300;
        for (types::global_dof_index d = 0; d < points.size(); ++d)
          if (component[d] == hold.component &&
              points[d].distance(hold.point) < best)
            {
              best = points[d].distance(hold.point);
              held = d;
            }
        return held;
      }
    } // namespace

    const scene::ContactPair &
    single_pair(const scene::Scene &scene)
    {
      if (scene.contact_pairs.size() != 1)
        throw std::runtime_error(
          "scene " + scene.description() + ": Mesh/Contact refinements "
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
          ops.push_back(build_mortar_operators(model.dof_handler, model.mapping,
                                               pair.slave, pair.master,
                                               search_distance));
          const MortarOperators &op = ops.back();
          pcout << "Contact pair '" << pair.name << "': " << op.n_slave()
                << " slave nodes, slave face " << op.slave_area * 1e6
                << " mm^2, " << 100. * op.covered_area / op.slave_area
                << " % over the master face" << std::endl;
        }
      return merge_mortar_operators(ops);
    }

    std::pair<types::global_dof_index, Point<3>>
    contact_system(const physics::StructuralModel &model,
                   SparsityPattern                &pattern,
                   SparseMatrix<double>           &stiffness,
                   AffineConstraints<double>      &constraints)
    {
      const auto &prm = model.prm;
      // K_s at the nominal point, as a deal.II matrix.
      const physics::MatrixParts parts = model.parts();
      physics::PETScMatrix       K;
      parts.combine(parts.coefficients(prm.nominal_point()).structural, K);
      physics::copy_to_serial(K, pattern, stiffness);

      constraints.copy_from(model.constraints);
      // The scene's point holds: one component of the node nearest each
      // point (the TriboBrake's loading arm holds the support top's centre
      // along the radius: a sliding contact does not hold it there).
      const auto [points, component] = physics::dof_support_points(model);
      types::global_dof_index held = numbers::invalid_dof_index;
      for (const scene::PointHold &hold : model.scene->point_holds)
        {
          held = nearest_dof(points, component, hold);
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
      return {held, held == numbers::invalid_dof_index ? Point<3>() :
                                                          points[held]};
    }

    Point<3>
    contact_system(const physics::StructuralModel &model,
                              physics::PETScMatrix           &stiffness,
                              AffineConstraints<double>      &constraints,
                              MPI_Comm                        comm)
    {
      const auto &prm = model.prm;
      const physics::MatrixParts parts = model.parts();
      parts.combine(parts.coefficients(prm.nominal_point()).structural,
                    stiffness);
      const unsigned int n = model.n_dofs();
      // Constraints on all DoFs, identical on every rank (the model's hold
      // only the locally relevant ones): hanging nodes over the whole shared
      // mesh, the clamped faces, the radial hold.
      const auto [points, component] = physics::dof_support_points(model);
      constraints.clear();
      DoFTools::make_hanging_node_constraints(model.dof_handler, constraints);
      for (const scene::Hold &hold : model.scene->holds)
        {
          const std::vector<bool> on = physics::dofs_on_boundary(model, hold.id);
          for (types::global_dof_index i = 0; i < n; ++i)
            if (on[i] && hold.components[component[i]] &&
                !constraints.is_constrained(i))
              constraints.add_line(i);
        }
      types::global_dof_index held = 0;
      for (const scene::PointHold &hold : model.scene->point_holds)
        {
          held = nearest_dof(points, component, hold);
          if (constraints.is_constrained(held))
            continue;
          constraints.add_line(held);
          // its row: the diagonal alone (its column multiplies x_held = 0)
          const auto range = stiffness.local_range();
          const bool mine  = held >= range.first && held < range.second;
          const double diag =
            Utilities::MPI::sum(mine ? stiffness.diag_element(held) : 0., comm);
          stiffness.clear_rows(mine ? std::vector<types::global_dof_index>{held} :
                                      std::vector<types::global_dof_index>{},
                               diag);
        }
      constraints.close();
      return points[held];
    }

    Vector<double>
    scene_load(const physics::StructuralModel  &model,
               const AffineConstraints<double> &constraints,
               const double                     force)
    {
      if (model.scene->loads.empty())
        throw std::runtime_error("scene " + model.scene->description() +
                                 ": the preload and the braking run need a "
                                 "load; the scene has none");
      Vector<double> load(model.n_dofs());
      const auto     &fe = model.fe;
      const QGauss<2> q(fe.degree + 1);
      FEFaceValues<3> fv(model.mapping, fe, q, update_values | update_JxW_values);
      Vector<double>                       cell_f(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      // Each load: a uniform traction force / area on its faces.
      for (const scene::Load &applied : model.scene->loads)
        {
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
          const double traction = force / area;
          for (const auto &cell : model.dof_handler.active_cell_iterators())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() == applied.id)
                {
                  fv.reinit(cell, f);
                  cell_f = 0.;
                  for (unsigned int k = 0; k < q.size(); ++k)
                    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
                      if (const double t = applied.direction[
                            fe.system_to_component_index(i).first];
                          t != 0.)
                        cell_f[i] += traction * t * fv.shape_value(i, k) *
                                     fv.JxW(k);
                  cell->get_dof_indices(dofs);
                  constraints.distribute_local_to_global(cell_f, dofs, load);
                }
        }
      return load;
    }

    PreloadAnalysis::PreloadAnalysis(const parameters::AllParameters &prm,
                                     const ParameterHandler          &handler,
                                     MPI_Comm                         comm)
      : prm(prm)
      , handler(handler)
      , comm(comm)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
      , timer(pcout, TimerOutput::summary, TimerOutput::wall_times)
      , model(prm, comm)
    {}

    void
    PreloadAnalysis::setup_system()
    {
      TimerOutput::Scope t(timer, "setup and assembly");
      work_dir =
        output::partial_directory(prm.output.directory, prm.output.overwrite);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          output::fresh_directory(work_dir);
          std::ofstream out(fs::path(work_dir) / "parameters.prm");
          handler.print_parameters(out, ParameterHandler::PRM);
        }
      MPI_Barrier(comm);
      model.setup_and_assemble(pcout);

      const Point<3> held =
        Utilities::MPI::n_mpi_processes(comm) == 1 ?
          contact_system(model, pattern, stiffness, constraints).second :
          contact_system(model, stiffness_mpi, constraints, comm);
      pcout << "Preload: " << model.n_dofs() << " DoFs";
      for (const scene::PointHold &hold : model.scene->point_holds)
        pcout << "; " << hold.name << ": " << "xyz"[hold.component]
              << " held at (" << held[0] << ", " << held[1] << ", " << held[2]
              << ") m";
      pcout << std::endl;
    }

    void
    PreloadAnalysis::assemble_load()
    {
      TimerOutput::Scope t(timer, "setup and assembly");
      load = scene_load(model, constraints, prm.preload.normal_force);
    }

    void
    PreloadAnalysis::solve()
    {
      TimerOutput::Scope t(timer, "contact solve");
      mortar = scene_mortar(model, prm.preload.search_distance, pcout);
      ContactSettings s;
      s.friction = prm.preload.friction == "coulomb" ?
                     FrictionModel::coulomb :
                   prm.preload.friction == "steady sliding" ?
                     FrictionModel::steady_sliding :
                     FrictionModel::frictionless;
      s.friction_coefficient = prm.interface.friction_coefficient;
      s.sliding_direction    = common_sliding(*model.scene);
      s.master_slip          = prm.preload.disc_slip * s.sliding_direction;
      std::ostream *log = Utilities::MPI::this_mpi_process(comm) == 0 ?
                            &std::cout :
                            nullptr;
      // The normal force in Load steps increments; each step starts from the
      // previous one (and, with Coulomb friction, measures slip from it),
      // cutting its increment when the active set does not settle. Every
      // step's contact state is written.
      const unsigned int n_steps = prm.preload.load_steps;
      Vector<double>     segmented; // where the segmentation was built
      const ContactStiffness K = Utilities::MPI::n_mpi_processes(comm) == 1 ?
                                   ContactStiffness(stiffness) :
                                   ContactStiffness(stiffness_mpi, comm);
      Vector<double>     previous(load.size());
      state = ContactSolution();
      for (unsigned int k = 1; k <= n_steps; ++k)
        {
          Vector<double> f(load);
          f *= double(k) / n_steps;
          if (log && n_steps > 1)
            *log << "Load step " << k << " of " << n_steps << ": "
                 << prm.preload.normal_force * k / n_steps << " N"
                 << std::endl;
          const ContactSolution start = state;
          state = solve_contact_load_steps(K, previous, f, start, constraints,
                                           mortar, s, 1, 6, log);
          // Large sliding: the step once more on the segmentation of its
          // deformed surfaces.
          if (refresh_segmentation(mortar, model.dof_handler,
                                   state.displacement, segmented,
                                   prm.preload.segmentation_refresh))
            {
              pcout << "  segmentation rebuilt on the deformed surfaces; "
                       "load step "
                    << k << " again" << std::endl;
              state = solve_contact_load_steps(K, previous, f, start,
                                               constraints, mortar, s, 1, 6,
                                               log);
            }
          previous = f;
          const std::string step = Utilities::int_to_string(k, 3);
          write_contact("contact_step_" + step + ".csv",
                        "contact_surface_" + step + ".vtu");
          steps.emplace_back(double(k) / n_steps,
                             "contact_surface_" + step + ".vtu");
        }

      // What the springs carry along the sliding direction (each rank its
      // own rows of the spring matrix, summed).
      physics::PETScVector u(model.locally_owned_dofs, comm),
        r(model.locally_owned_dofs, comm);
      for (const auto i : model.locally_owned_dofs)
        u[i] = state.displacement[i];
      u.compress(VectorOperation::insert);
      model.stiffness_springs.vmult(r, u);
      const Tensor<1, 3> slide = common_sliding(*model.scene);
      const std::vector<unsigned int> component =
        physics::dof_support_points(model).second;
      spring_reaction = 0.;
      for (const auto i : model.locally_owned_dofs)
        spring_reaction += r[i] * slide[component[i]];
      spring_reaction = Utilities::MPI::sum(spring_reaction, comm);
      // The k_ref scaling: the parts hold springs at the reference value.
      spring_reaction *=
        prm.nominal_point().spring_stiffness / model.parts().reference.spring_stiffness;

      double max_p = 0.;
      for (unsigned int j = 0; j < mortar.n_slave(); ++j)
        max_p = std::max(max_p, state.nodal_pressure[j]);
      pcout << "Preload converged: normal force " << state.normal_force
            << " N, friction force " << state.tangential_force
            << " N (the springs hold back " << spring_reaction
            << " N), contact area " << state.contact_area * 1e6 << " of "
            << mortar.slave_area * 1e6 << " mm^2, mean pressure "
            << state.normal_force / state.contact_area / 1e6
            << " MPa, peak " << max_p / 1e6 << " MPa" << std::endl;
    }

    void
    PreloadAnalysis::write_contact(const std::string &csv_name,
                                   const std::string &vtu_name) const
    {
      // Collective: the contact state is the same on every rank; rank 0
      // writes the table and the whole pad face.
      const bool         root = Utilities::MPI::this_mpi_process(comm) == 0;
      const fs::path     dir(work_dir);
      const unsigned int n_s = mortar.n_slave();
      // The tangential traction as a nodal field too (the same L2
      // projection as the pressure), along and across the sliding direction.
      const Tensor<1, 3> slide = common_sliding(*model.scene);
      Vector<double>     along(n_s), across_t(n_s);
      for (unsigned int j = 0; j < n_s; ++j)
        {
          const Tensor<1, 3> tt =
            state.tangential_traction[j][0] * mortar.tangents1[j] +
            state.tangential_traction[j][1] * mortar.tangents2[j];
          along[j]    = tt * slide;
          across_t[j] = tt * cross_product_3d(mortar.normals[j], slide);
        }
      along    = mortar.nodal_pressure(along);
      across_t = mortar.nodal_pressure(across_t);
      if (root)
      {
        std::ofstream out(dir / csv_name);
        out << "x_m,y_m,z_m,p_N_Pa,t_T1_Pa,t_T2_Pa,gap_m,status\n"
            << std::setprecision(10);
        for (unsigned int j = 0; j < n_s; ++j)
          {
            const auto &x = mortar.slave_points[j];
            out << x[0] << ',' << x[1] << ',' << x[2] << ','
                << state.nodal_pressure[j] << ',' << along[j] << ','
                << across_t[j] << ',' << state.gap[j] << ',' << state.status[j]
                << '\n';
          }
      }
      // ParaView: the pad face with p_N, t_T1, status.
      Vector<double> fields(model.n_dofs());
      for (unsigned int j = 0; j < n_s; ++j)
        {
          fields[mortar.slave_dofs[j][0]] = state.nodal_pressure[j];
          fields[mortar.slave_dofs[j][1]] = along[j];
          fields[mortar.slave_dofs[j][2]] = state.status[j];
        }
      output::BoundaryFaceOutput out(slave_ids(*model.scene));
      out.attach_dof_handler(model.dof_handler);
      out.add_data_vector(fields,
                          std::vector<std::string>{"contact_pressure_Pa",
                                                   "friction_traction_Pa",
                                                   "status"});
      if (root)
        {
          out.build_patches(model.mapping, model.fe.degree);
          std::ofstream vtu(dir / vtu_name);
          out.write_vtu(vtu);
        }
    }

    void
    PreloadAnalysis::output_results() const
    {
      TimerOutput::Scope t(timer, "output");
      // contact.csv and contact_surface.vtu: the final state; contact.pvd:
      // every load step (time = load factor)
      write_contact("contact.csv", "contact_surface.vtu");
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        {
          write_displacement();
          return;
        }
      const fs::path dir(work_dir);
      {
        std::ofstream pvd(dir / "contact.pvd");
        DataOutBase::write_pvd_record(pvd, steps);
      }
      {
        std::ofstream out(dir / "preload_summary.txt");
        out << std::setprecision(8) << "normal_force_N " << state.normal_force
            << "\nfriction_force_N " << state.tangential_force
            << "\nspring_force_N " << spring_reaction << "\ncontact_area_m2 "
            << state.contact_area << "\npad_face_area_m2 " << mortar.slave_area
            << "\nactive_set_iterations " << state.history.size()
            << "\nload_steps " << steps.size() << "\n";
      }
      write_displacement();
    }

    void
    PreloadAnalysis::write_displacement() const
    {
      // every rank its own cells (DataOut takes the locally owned ones)
      DataOut<3> out;
      out.attach_dof_handler(model.dof_handler);
      out.add_data_vector(
        state.displacement, std::vector<std::string>(3, "displacement_m"),
        DataOut<3>::type_dof_data,
        std::vector<DataComponentInterpretation::DataComponentInterpretation>(
          3, DataComponentInterpretation::component_is_part_of_vector));
      out.build_patches(model.mapping, 1);
      out.write_vtu_in_parallel(
        (fs::path(work_dir) / "displacement.vtu").string(), comm);
    }

    void
    PreloadAnalysis::run()
    {
      setup_system();
      assemble_load();
      solve();
      output_results();
      MPI_Barrier(comm);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        output::publish_directory(work_dir, prm.output.directory);
      MPI_Barrier(comm);
      pcout << "Results in " << prm.output.directory << std::endl;
    }
  } // namespace contact
} // namespace squeal
