// The static preload: the CEA's structure (mesh, FE space, matrix parts) at
// the file's nominal parameters, the scene's loads, and every contact pair
// pressed together through mortar frictional contact. Serially the PETSc
// stiffness of the structural model is copied into a deal.II sparse matrix
// (the contact solver's serial stiffness); under mpirun each rank keeps its
// rows. MUMPS solves the augmented contact system either way.

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_out_faces.h>

#include <squeal/analyses/preload.h>
#include <squeal/base/memory_estimate.h>
#include <squeal/contact/scene_contact.h>
#include <squeal/io/face_output.h>
#include <squeal/io/output_directory.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;
    using contact::ContactSettings;
    using contact::ContactSolution;
    using contact::ContactStiffness;
    using contact::FrictionModel;
    namespace fs = std::filesystem;

    PreloadAnalysis::PreloadAnalysis(const parameters::AllParameters &prm,
                                     const ParameterHandler          &handler,
                                     MPI_Comm                         comm)
      : prm(prm)
      , handler(handler)
      , comm(comm)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
      , timer(pcout, TimerOutput::summary, TimerOutput::wall_times)
      , model(prm, comm)
    {
      model.varied = std::set<std::string>(); // one point: nothing varies
      model.tie_constraints = contact::add_tie_constraints;
    }

    void
    PreloadAnalysis::setup_system()
    {
      TimerOutput::Scope t(timer, "setup and assembly");
      work_dir = io::start_work_directory(prm.output.directory,
                                          prm.output.overwrite,
                                          handler,
                                          comm);
      model.setup_and_assemble(pcout);

      const Point<3> held =
        Utilities::MPI::n_mpi_processes(comm) == 1 ?
          contact::contact_system(model, pattern, stiffness, constraints)
            .second :
          contact::contact_system(model, stiffness_mpi, constraints, comm);
      // the contact system holds K_s: the bodies' parts (the common pattern's
      // mass and stiffness) are no longer needed
      model.release_body_parts();
      pcout << "Preload: " << model.n_dofs() << " DoFs";
      for (const scene::PointHold &hold : model.scene->point_holds)
        pcout << "; " << hold.name << ": "
              << "xyz"[hold.component] << " held at (" << held[0] << ", "
              << held[1] << ", " << held[2] << ") m";
      pcout << std::endl;
      const std::size_t nonzeros = Utilities::MPI::n_mpi_processes(comm) == 1 ?
                                     stiffness.n_nonzero_elements() :
                                     stiffness_mpi.n_nonzero_elements();
      // the LU and, beside it, the solve's copies of the contact system (its
      // PETSc matrix, MUMPS's input and its own copy): 48 bytes per
      // nonzero of K_s (the default brake's preload: 1625 MB beside a 2045
      // MB factor, 34 million nonzeros)
      const double factor =
        factorisation_bytes(nonzeros, model.n_dofs(), false);
      report_memory_estimate(comm,
                             pcout.is_active() ? &pcout.get_stream() : nullptr,
                             model.n_dofs(),
                             factor + 48. * double(nonzeros),
                             "MUMPS's LU of the contact system and its copies",
                             factor);
    }

    void
    PreloadAnalysis::assemble_load()
    {
      TimerOutput::Scope t(timer, "setup and assembly");
      load = contact::scene_load(model, constraints, prm.preload.normal_force);
    }

    void
    PreloadAnalysis::solve()
    {
      TimerOutput::Scope t(timer, "contact solve");
      mortar = contact::scene_mortar(model, prm.preload.search_distance, pcout);
      ContactSettings s;
      s.friction = prm.preload.friction == "coulomb" ?
                     FrictionModel::coulomb :
                   prm.preload.friction == "steady sliding" ?
                     FrictionModel::steady_sliding :
                     FrictionModel::frictionless;
      s.friction_coefficient =
        model.scene->common_friction_coefficient(model.scene->nominal_point());
      s.sliding_direction = contact::common_sliding(*model.scene);
      // The penalty law: each pair's k_n, the CEA interface's stiffness.
      if (prm.preload.normal_law == "penalty")
        s.normal_stiffness =
          contact::pair_normal_stiffness(*model.scene,
                                         model.scene->nominal_point(),
                                         mortar);
      s.master_slip = prm.preload.disc_slip * s.sliding_direction;
      std::ostream *log =
        Utilities::MPI::this_mpi_process(comm) == 0 ? &std::cout : nullptr;
      // The normal force in Load steps increments; each step starts from the
      // previous one (and, with Coulomb friction, measures slip from it),
      // cutting its increment when the active set does not settle. Every
      // step's contact state is written.
      const unsigned int     n_steps = prm.preload.load_steps;
      Vector<double>         segmented; // where the segmentation was built
      const ContactStiffness K = Utilities::MPI::n_mpi_processes(comm) == 1 ?
                                   ContactStiffness(stiffness) :
                                   ContactStiffness(stiffness_mpi, comm);
      Vector<double>         previous(load.size());
      state = ContactSolution();
      for (unsigned int k = 1; k <= n_steps; ++k)
        {
          Vector<double> f(load);
          f *= double(k) / n_steps;
          if (log && n_steps > 1)
            *log << "Load step " << k << " of " << n_steps << ": "
                 << prm.preload.normal_force * k / n_steps << " N" << std::endl;
          const ContactSolution start = state;
          state                       = contact::solve_contact_load_steps(
            K, previous, f, start, constraints, mortar, s, 1, 6, log);
          // Large sliding: the step once more on the segmentation of its
          // deformed surfaces.
          if (refresh_segmentation(mortar,
                                   model.dof_handler,
                                   state.displacement,
                                   segmented,
                                   prm.preload.segmentation_refresh))
            {
              pcout << "  segmentation rebuilt on the deformed surfaces; "
                       "load step "
                    << k << " again" << std::endl;
              state = contact::solve_contact_load_steps(
                K, previous, f, start, constraints, mortar, s, 1, 6, log);
            }
          previous               = f;
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
      model.parts().spring_product(model.scene->nominal_point(), u, r);
      const Tensor<1, 3> slide = contact::common_sliding(*model.scene);
      const std::vector<unsigned int> component =
        physics::dof_support_points(model).second;
      spring_reaction = 0.;
      for (const auto i : model.locally_owned_dofs)
        spring_reaction += r[i] * slide[component[i]];
      spring_reaction = Utilities::MPI::sum(spring_reaction, comm);

      double max_p = 0.;
      for (unsigned int j = 0; j < mortar.n_slave(); ++j)
        max_p = std::max(max_p, state.nodal_pressure[j]);
      pcout << "Normal contact law: " << prm.preload.normal_law;
      if (prm.preload.normal_law == "penalty")
        pcout << " (pressure = k_n x penetration, largest penetration "
              << std::setprecision(3) << largest_penetration() << " m)";
      else
        pcout << " (no penetration)";
      pcout << std::setprecision(6) << std::endl;
      pcout << "Preload converged: normal force " << state.normal_force
            << " N, friction force " << state.tangential_force
            << " N (the springs hold back " << spring_reaction
            << " N), contact area " << state.contact_area * 1e6 << " of "
            << mortar.slave_area * 1e6 << " mm^2, mean pressure "
            << state.normal_force / state.contact_area / 1e6 << " MPa, peak "
            << max_p / 1e6 << " MPa" << std::endl;
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
      const Tensor<1, 3> slide = contact::common_sliding(*model.scene);
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
          io::OutputFile out(dir / csv_name);
          out << "x_m,y_m,z_m,p_N_Pa,t_T1_Pa,t_T2_Pa,gap_m,status\n"
              << std::setprecision(10);
          for (unsigned int j = 0; j < n_s; ++j)
            {
              const auto &x = mortar.slave_points[j];
              out << x[0] << ',' << x[1] << ',' << x[2] << ','
                  << state.nodal_pressure[j] << ',' << along[j] << ','
                  << across_t[j] << ',' << state.gap[j] << ','
                  << state.status[j] << '\n';
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
      io::BoundaryFaceOutput out(contact::slave_ids(*model.scene));
      out.attach_dof_handler(model.dof_handler);
      out.add_data_vector(fields,
                          std::vector<std::string>{"contact_pressure_Pa",
                                                   "friction_traction_Pa",
                                                   "status"});
      if (root)
        {
          out.build_patches(model.mapping, model.fe.degree);
          io::OutputFile vtu(dir / vtu_name);
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
        io::OutputFile pvd(dir / "contact.pvd");
        DataOutBase::write_pvd_record(pvd, steps);
      }
      {
        io::OutputFile out(dir / "preload_summary.txt");
        out << std::setprecision(8) << "normal_force_N " << state.normal_force
            << "\nfriction_force_N " << state.tangential_force
            << "\nspring_force_N " << spring_reaction << "\ncontact_area_m2 "
            << state.contact_area << "\npad_face_area_m2 " << mortar.slave_area
            << "\nactive_set_iterations " << state.history.size()
            << "\nload_steps " << steps.size() << "\nnormal_contact_law "
            << prm.preload.normal_law << "\nlargest_penetration_m "
            << largest_penetration() << "\n";
      }
      write_displacement();
    }

    double
    PreloadAnalysis::largest_penetration() const
    {
      double d = 0.;
      for (unsigned int j = 0; j < state.gap.size(); ++j)
        if (state.status[j] != 0)
          d = std::max(d, -state.gap[j]);
      return d;
    }

    void
    PreloadAnalysis::write_displacement() const
    {
      // every rank its own cells (DataOut takes the locally owned ones)
      DataOut<3> out;
      out.set_flags(io::vtk_flags());
      out.attach_dof_handler(model.dof_handler);
      out.add_data_vector(
        state.displacement,
        std::vector<std::string>(3, "displacement_m"),
        DataOut<3>::type_dof_data,
        std::vector<DataComponentInterpretation::DataComponentInterpretation>(
          3, DataComponentInterpretation::component_is_part_of_vector));
      out.build_patches(model.mapping, 1);
      io::write_vtu(out,
                    (fs::path(work_dir) / "displacement.vtu").string(),
                    comm);
    }

    void
    PreloadAnalysis::run()
    {
      setup_system();
      assemble_load();
      solve();
      output_results();
      io::finish_run(work_dir, prm.output.directory, comm);
      pcout << "Results in " << prm.output.directory << std::endl;
    }
  } // namespace analyses
} // namespace squeal
