// The transient braking simulation of the TriboBrake (see braking.h): the
// preload's structure and contact system, a lumped mass, the explicit
// integrator, and the records a user reads: force and probe tables, the
// contact history for the tribology module, the spectrum, the stability
// verdict and ParaView series.

#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <squeal/contact/preload.h>
#include <squeal/output/face_output.h>
#include <squeal/output/output_directory.h>
#include <squeal/transient/braking.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <filesystem>
#include <fstream>
#include <iomanip>

namespace squeal
{
  namespace transient
  {
    using namespace dealii;
    namespace fs = std::filesystem;

    namespace
    {
      // Von Mises stress [Pa] of linear elasticity, material per cell.
      class VonMises : public DataPostprocessorScalar<3>
      {
      public:
        explicit VonMises(const scene::Scene &scene)
          : DataPostprocessorScalar<3>("von_mises_Pa", update_gradients)
          , scene(scene)
        {}
        void
        evaluate_vector_field(
          const DataPostprocessorInputs::Vector<3> &in,
          std::vector<Vector<double>> &out) const override
        {
          const parameters::Material &mat =
            scene.body(in.template get_cell<3>()->material_id()).material;
          const auto [lambda, mu] =
            physics::lame_constants(mat.youngs_modulus, mat.poisson_ratio);
          for (unsigned int q = 0; q < out.size(); ++q)
            {
              Tensor<2, 3> grad;
              for (unsigned int c = 0; c < 3; ++c)
                grad[c] = in.solution_gradients[q][c];
              const Tensor<2, 3> eps = 0.5 * (grad + transpose(grad));
              Tensor<2, 3>       s   = 2 * mu * eps;
              for (unsigned int c = 0; c < 3; ++c)
                s[c][c] += lambda * trace(eps);
              const Tensor<2, 3> dev = s - trace(s) / 3. * unit_symmetric_tensor<3>();
              out[q][0] = std::sqrt(1.5 * scalar_product(dev, dev));
            }
        }

      private:
        const scene::Scene &scene;
      };

      // Force ramp: (1 - cos(pi t / T)) / 2 up to T, then 1.
      double
      ramp(const double t, const double T)
      {
        return T <= 0. || t >= T ? 1. :
                                   0.5 * (1. - std::cos(numbers::PI * t / T));
      }

      std::string
      as_text(const double x)
      {
        std::ostringstream s;
        s << std::setprecision(10) << x;
        return s.str();
      }
    } // namespace

    BrakingAnalysis::BrakingAnalysis(const parameters::AllParameters &prm,
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
    BrakingAnalysis::setup_system()
    {
      TimerOutput::Scope t(timer, "setup");
      const bool serial = Utilities::MPI::n_mpi_processes(comm) == 1;
      const bool root   = Utilities::MPI::this_mpi_process(comm) == 0;
      // Serial run: the products may use every core (deal.II threads; the
      // program starts with one thread per MPI rank).
      if (serial)
        MultithreadInfo::set_thread_limit();
      if (!serial && prm.transient.stiffness_product == "sparse")
        throw std::runtime_error(
          "Transient/Stiffness product = sparse is serial (the assembled "
          "matrix is copied to one process); use matrix-free under mpirun");
      if (resuming)
        {
          work_dir = prm.output.directory + ".partial";
          if (!fs::is_regular_file(fs::path(work_dir) / "checkpoint" /
                                   "latest"))
            throw std::runtime_error(
              "no checkpoint in '" + work_dir +
              "/checkpoint': a braking run writes one every Transient/"
              "Checkpoint interval steps and removes it when it ends");
        }
      else
        {
          work_dir = output::partial_directory(prm.output.directory,
                                               prm.output.overwrite);
          if (root)
            {
              output::fresh_directory(work_dir, "vtu");
              fs::create_directories(fs::path(work_dir) / "checkpoint");
              std::ofstream out(fs::path(work_dir) / "parameters.prm");
              handler.print_parameters(out, ParameterHandler::PRM);
            }
          MPI_Barrier(comm);
        }
      model.lumped_springs = true; // the matrix-free product grounds each DoF
      model.setup_and_assemble(pcout);
      for (const auto &line : model.constraints.get_lines())
        if (!line.entries.empty())
          throw std::runtime_error(
            "the braking simulation needs a conforming mesh (the lumped mass "
            "of hanging nodes is not condensed): set Mesh/Disc refinements "
            "under pad = 0");
      const unsigned int n = model.n_dofs();

      // Every rank holds the whole mesh (parallel::shared::Triangulation):
      // the support points, the fixed DoFs (the clamped inner face of the
      // disc; the radial DoF of the support top's centre, the loading arm),
      // the lumped mass and the mortar operators are built over all cells,
      // the same on every rank and independent of the DoF numbering.
      std::tie(points, component) = physics::dof_support_points(model);
      fixed.assign(n, false);
      for (const scene::Hold &hold : model.scene->holds)
        {
          const std::vector<bool> on = physics::dofs_on_boundary(model, hold.id);
          for (unsigned int i = 0; i < n; ++i)
            fixed[i] = fixed[i] || (on[i] && hold.components[component[i]]);
        }
      Point<3> held_point;
      for (const scene::PointHold &hold : model.scene->point_holds)
        {
          // the component at the nearest vertex
          types::global_dof_index held = 0;
          double best = 1e300;
          for (const auto &cell : model.dof_handler.active_cell_iterators())
            for (const unsigned int v : cell->vertex_indices())
              if (cell->vertex(v).distance(hold.point) < best)
                {
                  best = cell->vertex(v).distance(hold.point);
                  held = cell->vertex_dof_index(v, hold.component);
                }
          fixed[held] = true;
          held_point  = points[held];
        }
      if (serial)
        {
          // the assembled matrix with the same fixed DoFs (the preload's
          // contact system)
          AffineConstraints<double> contact_constraints;
          const Point<3> p = contact::contact_system(
                               model, pattern, stiffness, contact_constraints)
                               .second;
          for (unsigned int i = 0; i < n; ++i)
            if (fixed[i] != contact_constraints.is_constrained(i) ||
                p.distance(held_point) > 1e-12)
              throw std::runtime_error("internal error: the braking run's "
                                       "fixed DoFs differ from the preload's");
        }
      // the fixed DoFs as constraints, the same on every rank: for the
      // matrix-free product and the load
      constraints.clear();
      for (unsigned int i = 0; i < n; ++i)
        if (fixed[i])
          constraints.add_line(i);
      constraints.close();

      const parameters::ScalarPoint nominal = prm.nominal_point();
      mass = lumped_mass(model.dof_handler, model.mapping, [&](const auto &cell) {
        return model.scene->density(cell->material_id(), nominal);
      });

      // every pair: the disc turns under all the pads at one angular
      // velocity (the first pair's axis), the same sliding direction
      const auto &pairs = model.scene->contact_pairs;
      if (pairs.empty())
        throw std::runtime_error("scene " + model.scene->description() +
                                 " has no contact pair to brake on");
      const scene::ContactPair &pair = pairs.front();
      for (const scene::ContactPair &other : pairs)
        if ((other.axis - pair.axis).norm() > 1e-9 ||
            cross_product_3d(other.axis_point - pair.axis_point, pair.axis)
                .norm() > 1e-9 * pair.size)
          throw std::runtime_error(
            "scene " + model.scene->description() + ": contact pairs '" +
            pair.name + "' and '" + other.name +
            "' turn about different axes; a braking run has one disc");
      ConditionalOStream quiet(std::cout, false);
      mortar  = contact::scene_mortar(model, prm.preload.search_distance,
                                     quiet);
      sliding = contact::common_sliding(*model.scene);
      radial  = pair.radial();
      double pair_size = pair.size;
      for (const scene::ContactPair &other : pairs)
        pair_size = std::min(pair_size, other.size);

      // The matrix-free product: elasticity per material plus the springs'
      // diagonal (each spring ties one DoF to the ground), on this rank's
      // cells.
      const auto &tr = prm.transient;
      {
        const physics::PETScMatrix &ks = model.stiffness_springs;
        const double scale = prm.nominal_point().spring_stiffness /
                             model.parts().reference.spring_stiffness;
        Vector<double> springs(n);
        for (const auto i : model.locally_owned_dofs)
          for (auto e = ks.begin(i); e != ks.end(i); ++e)
            if (e->column() == i && !fixed[i])
              springs[i] = scale * e->value();
            else if (e->value() != 0. && !fixed[i])
              throw std::runtime_error("the support's springs couple two DoFs: "
                                       "the matrix-free product needs them "
                                       "grounded");
        matrix_free     = std::make_unique<ElasticityOperator>(
          model.dof_handler, model.mapping, constraints,
          [this, nominal](const types::material_id id) {
            return physics::lame_constants(
              model.scene->youngs_modulus(id, nominal),
              model.scene->body(id).material.poisson_ratio);
          },
          springs);
      }
      const auto layout =
        std::make_shared<Utilities::MPI::Partitioner>(model.locally_owned_dofs,
                                                      comm);
      // Both products as the time loop calls them (the sparse one through
      // serial copies, serial runs only).
      const StiffnessProduct free_product = [this](DistributedVector       &y,
                                                   const DistributedVector &v) {
        matrix_free->vmult(y, v);
      };
      StiffnessProduct sparse_product;
      if (serial)
        {
          auto in  = std::make_shared<Vector<double>>(n);
          auto out = std::make_shared<Vector<double>>(n);
          sparse_product = [this, in, out](DistributedVector       &y,
                                           const DistributedVector &v) {
            std::copy(v.begin(), v.end(), in->begin());
            stiffness.vmult(*out, *in);
            std::copy(out->begin(), out->end(), y.begin());
          };
        }
      const StiffnessProduct product =
        tr.stiffness_product == "matrix-free" ? free_product : sparse_product;
      if (serial)
        {
          // Both products on one vector: time and agreement.
          DistributedVector x(layout), y_sparse(layout), y_free(layout);
          for (unsigned int i = 0; i < n; ++i)
            x[i] = fixed[i] ? 0. : std::sin(0.37 * i);
          const auto time_of = [&](const StiffnessProduct &multiply,
                                   DistributedVector      &y) {
            const auto t0 = std::chrono::steady_clock::now();
            for (unsigned int k = 0; k < 10; ++k)
              multiply(y, x);
            return std::chrono::duration<double>(
                     std::chrono::steady_clock::now() - t0)
                     .count() /
                   10.;
          };
          result.sparse_product      = time_of(sparse_product, y_sparse);
          result.matrix_free_product = time_of(free_product, y_free);
          for (unsigned int i = 0; i < n; ++i)
            if (fixed[i])
              y_sparse[i] = 0.;
          y_free -= y_sparse;
          const double difference = y_free.l2_norm() / y_sparse.l2_norm();
          pcout << "Stiffness product: sparse " << result.sparse_product * 1e3
                << " ms, matrix-free " << result.matrix_free_product * 1e3
                << " ms (relative difference " << difference << "); using "
                << tr.stiffness_product << std::endl;
          if (!(difference < 1e-10))
            throw std::runtime_error(
              "the matrix-free stiffness product differs from the assembled "
              "matrix by " + as_text(difference) + " (relative)");
        }
      else
        pcout << "Stiffness product: matrix-free on "
              << Utilities::MPI::n_mpi_processes(comm) << " MPI ranks"
              << std::endl;

      // Stability limit and time step.
      const auto limit = stable_time_step(product, layout, mass, fixed, points,
                                          prm.damping.beta, tr.beta2);
      ExplicitSettings s;
      s.time_step = tr.time_step > 0. ? tr.time_step :
                                        tr.safety_factor * limit.critical;
      s.beta2                = tr.beta2;
      s.alpha                = prm.damping.alpha;
      s.beta                 = prm.damping.beta;
      s.friction_coefficient = prm.interface.friction_coefficient;
      s.pgs_tolerance        = tr.contact_tolerance;
      s.pgs_max_iterations   = tr.contact_iterations;
      if (tr.time_step > limit.critical)
        throw std::runtime_error(
          "Transient/Time step = " + as_text(tr.time_step) +
          " s exceeds the stability limit " + as_text(limit.critical) +
          " s of this mesh (largest frequency " +
          as_text(limit.omega_max / (2 * numbers::PI)) +
          " Hz with Rayleigh beta); set it at most to the limit, or 0 for " +
          as_text(tr.safety_factor) + " x the limit");
      dynamics = std::make_unique<ExplicitDynamics>(product, layout, mass,
                                                    fixed, s, limit.critical);
      const double omega =
        prm.interface.rotation_sense == "counterclockwise" ?
          tr.angular_velocity :
          -tr.angular_velocity;
      dynamics->set_contact(mortar, [omega, pair](const Point<3> &x) {
        return omega * cross_product_3d(pair.axis, x - pair.axis_point);
      });
      result.n_dofs             = n;
      result.time_step          = s.time_step;
      result.critical_time_step = limit.critical;

      // The probe: the pad's leading-edge node (smallest coordinate along
      // the sliding direction: where the disc enters the contact) nearest
      // the pad's mid radius; the leading-edge row for the pressure range.
      double s_min = 1e300;
      for (unsigned int j = 0; j < mortar.n_slave(); ++j)
        s_min = std::min(s_min, mortar.slave_points[j] * sliding);
      const double h = pair_size * 1e-6;
      unsigned int best = 0;
      double       best_r = 1e300;
      for (unsigned int j = 0; j < mortar.n_slave(); ++j)
        if (mortar.slave_points[j] * sliding < s_min + h)
          {
            leading_nodes.push_back(j);
            const double dr =
              std::abs((mortar.slave_points[j] - pair.centre) * radial);
            if (dr < best_r)
              {
                best_r = dr;
                best   = j;
              }
          }
      probe_point = mortar.slave_points[best];
      probe_dofs  = mortar.slave_dofs[best];

      history.coordinates.clear();
      for (const auto &x : mortar.slave_points)
        history.coordinates.push_back({{x[0], x[1], x[2]}});
      for (unsigned int c = 0; c < 3; ++c)
        {
          history.sliding_direction[c] = sliding[c];
          history.radial_direction[c]  = radial[c];
        }
      const unsigned int n_s = mortar.n_slave();
      history.p_N.assign(n_s, {});
      history.t_T1.assign(n_s, {});
      history.t_T2.assign(n_s, {});
      history.slip_velocity.assign(n_s, {});
      history.status.assign(n_s, {});

      pcout << "Braking: " << n << " DoFs, " << mortar.n_slave()
            << " slave-face nodes; point holds at (" << held_point[0]
            << ", " << held_point[1] << ", " << held_point[2] << ") m\n"
            << "Stability limit " << limit.critical << " s (largest frequency "
            << limit.omega_max / (2 * numbers::PI) << " Hz, "
            << limit.lanczos_steps << " Lanczos steps); time step "
            << s.time_step << " s, beta2 = " << tr.beta2 << "\nProbe: pad "
            << "leading edge at (" << probe_point[0] << ", " << probe_point[1]
            << ", " << probe_point[2] << ") m" << std::endl;
    }

    void
    BrakingAnalysis::assemble_load()
    {
      TimerOutput::Scope t(timer, "setup");
      load = contact::scene_load(model, constraints,
                                       prm.transient.normal_force);
    }

    void
    BrakingAnalysis::record_sample()
    {
      const ExplicitDynamics &d = *dynamics;
      const ContactStep      &c = d.contact_state();
      std::array<double, 17>  row;
      row[0] = d.time();
      row[1] = c.normal_force;
      row[2] = c.force * sliding;
      row[3] = c.force * radial;
      row[4] = c.contact_area;
      row[5] = c.n_stick;
      row[6] = c.n_slip;
      row[7] = c.n_separated;
      // the probe's values from the rank that owns them
      std::array<double, 9> probe{};
      for (unsigned int k = 0; k < 3; ++k)
        if (model.locally_owned_dofs.is_element(probe_dofs[k]))
          {
            probe[k]     = d.displacement()[probe_dofs[k]];
            probe[3 + k] = d.velocity()[probe_dofs[k]];
            probe[6 + k] = d.acceleration()[probe_dofs[k]];
          }
      if (Utilities::MPI::n_mpi_processes(comm) > 1)
        Utilities::MPI::sum(ArrayView<const double>(probe.data(), probe.size()),
                            comm, ArrayView<double>(probe.data(), probe.size()));
      for (unsigned int k = 0; k < 9; ++k)
        row[8 + k] = probe[k];
      samples.push_back(row);
      if (d.time() + 1e-15 >= prm.transient.history_start)
        {
          history.time.push_back(d.time());
          for (unsigned int j = 0; j < mortar.n_slave(); ++j)
            {
              history.p_N[j].push_back(std::max(0., c.pressure[j]));
              history.t_T1[j].push_back(c.traction[j] * sliding);
              history.t_T2[j].push_back(c.traction[j] * radial);
              history.slip_velocity[j].push_back(c.slip_velocity[j]);
              history.status[j].push_back(c.status[j]);
            }
        }
    }

    void
    BrakingAnalysis::write_snapshot(const std::string &series,
                                    const unsigned int index)
    {
      const ExplicitDynamics &d    = *dynamics;
      const std::string       name = series + "_" +
                               Utilities::int_to_string(index, 4) + ".vtu";
      const std::vector<DataComponentInterpretation::DataComponentInterpretation>
        vec(3, DataComponentInterpretation::component_is_part_of_vector);
      {
        // each rank writes its own cells into one file (MPI I/O)
        DistributedVector u(model.locally_owned_dofs, model.locally_relevant_dofs,
                            comm),
          v(u);
        u.copy_locally_owned_data_from(d.displacement());
        v.copy_locally_owned_data_from(d.velocity());
        u.update_ghost_values();
        v.update_ghost_values();
        DataOut<3> out;
        out.attach_dof_handler(model.dof_handler);
        out.add_data_vector(u, std::vector<std::string>(3, "displacement_m"),
                            DataOut<3>::type_dof_data, vec);
        out.add_data_vector(v, std::vector<std::string>(3, "velocity_m_per_s"),
                            DataOut<3>::type_dof_data, vec);
        const VonMises von_mises(*model.scene);
        out.add_data_vector(u, von_mises);
        out.build_patches(model.mapping, 1);
        out.write_vtu_in_parallel((fs::path(work_dir) / "vtu" / name).string(),
                                  comm);
      }
      (series == "transient" ? snapshots : frames)
        .emplace_back(d.time(), "vtu/" + name);
      if (series != "transient")
        return;
      // The pad face's contact fields.
      const ContactStep &c = d.contact_state();
      Vector<double>     tractions(model.n_dofs()), state(model.n_dofs());
      for (unsigned int j = 0; j < mortar.n_slave(); ++j)
        {
          const auto &dofs   = mortar.slave_dofs[j];
          tractions[dofs[0]] = std::max(0., c.pressure[j]);
          tractions[dofs[1]] = c.traction[j] * sliding;
          tractions[dofs[2]] = c.traction[j] * radial;
          state[dofs[0]]     = c.status[j];
          state[dofs[1]]     = c.slip_velocity[j];
        }
      output::BoundaryFaceOutput face(contact::slave_ids(*model.scene));
      face.attach_dof_handler(model.dof_handler);
      face.add_data_vector(tractions,
                           std::vector<std::string>{"contact_pressure_Pa",
                                                    "traction_sliding_Pa",
                                                    "traction_radial_Pa"});
      face.add_data_vector(state, std::vector<std::string>{"status",
                                                           "slip_velocity_m_per_s",
                                                           "unused"});
      const std::string face_name = "contact_" + name;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          // the whole pad face from the replicated contact state
          face.build_patches(model.mapping, 1);
          std::ofstream f(fs::path(work_dir) / "vtu" / face_name);
          face.write_vtu(f);
        }
      faces.emplace_back(d.time(), "vtu/" + face_name);
    }

    namespace
    {
      const char checkpoint_tag[] = "squeal braking checkpoint 1";

      template <typename T>
      void
      put(std::ostream &out, const T &x)
      {
        out.write(reinterpret_cast<const char *>(&x), sizeof(T));
      }

      template <typename T>
      T
      get(std::istream &in)
      {
        T x{};
        in.read(reinterpret_cast<char *>(&x), sizeof(T));
        return x;
      }

      void
      put_list(std::ostream &out,
               const std::vector<std::pair<double, std::string>> &list)
      {
        put<std::uint64_t>(out, list.size());
        for (const auto &[t, name] : list)
          {
            put(out, t);
            put<std::uint64_t>(out, name.size());
            out.write(name.data(), name.size());
          }
      }

      std::vector<std::pair<double, std::string>>
      get_list(std::istream &in)
      {
        std::vector<std::pair<double, std::string>> list(
          std::min<std::uint64_t>(get<std::uint64_t>(in), 1u << 20));
        for (auto &[t, name] : list)
          {
            t = get<double>(in);
            name.resize(std::min<std::uint64_t>(get<std::uint64_t>(in), 4096));
            in.read(name.data(), name.size());
          }
        return list;
      }
    } // namespace

    // A checkpoint: the samples and history samples taken since the last
    // one are appended to checkpoint/samples.bin and history.bin, then the
    // state (step, counters, snapshot lists, the integrator) goes to
    // state.bin through a temporary file and a rename, so a kill at any
    // moment leaves the previous complete checkpoint (the appended files are
    // cut back to its counts on resume).
    void
    BrakingAnalysis::write_checkpoint(const unsigned int next_step,
                                      const double       wall)
    {
      const fs::path dir = fs::path(work_dir) / "checkpoint";
      const unsigned int n_s  = mortar.n_slave();
      const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
      if (rank == 0)
        {
          // every rank holds the same samples; rank 0 keeps them
          std::ofstream f(dir / "samples.bin", std::ios::binary | std::ios::app);
          for (std::size_t i = saved_samples; i < samples.size(); ++i)
            f.write(reinterpret_cast<const char *>(samples[i].data()),
                    sizeof(samples[i]));
          std::ofstream h(dir / "history.bin", std::ios::binary | std::ios::app);
          for (std::size_t i = saved_history; i < history.time.size(); ++i)
            {
              put(h, history.time[i]);
              for (unsigned int j = 0; j < n_s; ++j)
                {
                  put(h, history.p_N[j][i]);
                  put(h, history.t_T1[j][i]);
                  put(h, history.t_T2[j][i]);
                  put(h, history.slip_velocity[j][i]);
                  put<std::int32_t>(h, history.status[j][i]);
                }
            }
          if (!f || !h)
            throw std::runtime_error("could not append to the checkpoint "
                                     "files in '" + dir.string() + "'");
        }
      saved_samples = samples.size();
      saved_history = history.time.size();
      const auto state_file = [&](const std::uint64_t step) {
        return dir / ("state." + std::to_string(step) + "." +
                      std::to_string(rank) + ".bin");
      };
      {
        std::ofstream f(state_file(next_step), std::ios::binary);
        f.write(checkpoint_tag, sizeof(checkpoint_tag));
        put<std::uint64_t>(f, model.n_dofs());
        put<std::uint64_t>(f, n_s);
        put<std::uint64_t>(f, next_step);
        put<std::uint64_t>(f, n_snapshots);
        put<std::uint64_t>(f, n_frames);
        put<std::uint64_t>(f, saved_samples);
        put<std::uint64_t>(f, saved_history);
        put(f, wall);
        put_list(f, snapshots);
        put_list(f, frames);
        put_list(f, faces);
        dynamics->save(f);
        if (!f)
          throw std::runtime_error("could not write the checkpoint '" +
                                   state_file(next_step).string() + "'");
      }
      // Every rank's state is complete: only now does `latest` point to it
      // (through a rename), and the previous states go.
      MPI_Barrier(comm);
      if (rank == 0)
        {
          {
            std::ofstream f(dir / "latest.tmp");
            f << next_step << ' ' << Utilities::MPI::n_mpi_processes(comm)
              << '\n';
          }
          fs::rename(dir / "latest.tmp", dir / "latest");
        }
      MPI_Barrier(comm);
      if (last_checkpoint > 0)
        fs::remove(state_file(last_checkpoint));
      last_checkpoint = next_step;
    }

    std::pair<unsigned int, double>
    BrakingAnalysis::read_checkpoint()
    {
      const fs::path dir = fs::path(work_dir) / "checkpoint";
      std::uint64_t  step = 0;
      unsigned int   ranks = 0;
      {
        std::ifstream latest(dir / "latest");
        if (!(latest >> step >> ranks))
          throw std::runtime_error("the checkpoint marker '" +
                                   (dir / "latest").string() + "' is corrupt");
      }
      if (ranks != Utilities::MPI::n_mpi_processes(comm))
        throw std::runtime_error(
          "the checkpoint in '" + dir.string() + "' was written by " +
          std::to_string(ranks) + " MPI rank(s); resume with mpirun -np " +
          std::to_string(ranks));
      const std::string name =
        (dir / ("state." + std::to_string(step) + "." +
                std::to_string(Utilities::MPI::this_mpi_process(comm)) +
                ".bin"))
          .string();
      last_checkpoint = step;
      std::ifstream f(name, std::ios::binary);
      char tag[sizeof(checkpoint_tag)] = {};
      f.read(tag, sizeof(tag));
      if (!f || std::string(tag) != checkpoint_tag)
        throw std::runtime_error("'" + name + "' is not a checkpoint of a "
                                 "squeal braking run");
      const unsigned int n_s     = mortar.n_slave();
      const auto         n_dofs  = get<std::uint64_t>(f);
      const auto         n_nodes = get<std::uint64_t>(f);
      if (n_dofs != model.n_dofs() || n_nodes != n_s)
        throw std::runtime_error(
          "the checkpoint '" + name + "' was written by a model with " +
          std::to_string(n_dofs) + " DoFs and " + std::to_string(n_nodes) +
          " pad-face nodes; these parameters give " +
          std::to_string(model.n_dofs()) + " and " + std::to_string(n_s) +
          " (was DIRECTORY.partial/parameters.prm edited?)");
      const auto   next_step = get<std::uint64_t>(f);
      n_snapshots            = get<std::uint64_t>(f);
      n_frames               = get<std::uint64_t>(f);
      saved_samples          = get<std::uint64_t>(f);
      saved_history          = get<std::uint64_t>(f);
      const double wall      = get<double>(f);
      snapshots              = get_list(f);
      frames                 = get_list(f);
      faces                  = get_list(f);
      if (!f)
        throw std::runtime_error("the checkpoint '" + name + "' is short");
      try
        {
          dynamics->load(f);
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error("the checkpoint '" + name + "': " + e.what());
        }

      // The samples up to the checkpoint; whatever a killed run appended
      // after it is cut off.
      const std::size_t history_record =
        sizeof(double) + n_s * (4 * sizeof(double) + sizeof(std::int32_t));
      const std::array<std::pair<std::string, std::size_t>, 2> files = {
        {{"samples.bin", saved_samples * sizeof(samples[0])},
         {"history.bin", saved_history * history_record}}};
      for (const auto &[file, bytes] : files)
        {
          const fs::path path = dir / file;
          if (!fs::exists(path) && bytes == 0)
            continue;
          if (!fs::exists(path) || fs::file_size(path) < bytes)
            throw std::runtime_error("the checkpoint file '" + path.string() +
                                     "' is shorter than its state says");
          if (Utilities::MPI::this_mpi_process(comm) == 0)
            fs::resize_file(path, bytes);
        }
      samples.resize(saved_samples);
      {
        std::ifstream in(dir / "samples.bin", std::ios::binary);
        for (auto &row : samples)
          in.read(reinterpret_cast<char *>(row.data()), sizeof(row));
      }
      history.time.resize(saved_history);
      for (unsigned int j = 0; j < n_s; ++j)
        {
          history.p_N[j].resize(saved_history);
          history.t_T1[j].resize(saved_history);
          history.t_T2[j].resize(saved_history);
          history.slip_velocity[j].resize(saved_history);
          history.status[j].resize(saved_history);
        }
      {
        std::ifstream in(dir / "history.bin", std::ios::binary);
        for (std::size_t i = 0; i < saved_history; ++i)
          {
            history.time[i] = get<double>(in);
            for (unsigned int j = 0; j < n_s; ++j)
              {
                history.p_N[j][i]           = get<double>(in);
                history.t_T1[j][i]          = get<double>(in);
                history.t_T2[j][i]          = get<double>(in);
                history.slip_velocity[j][i] = get<double>(in);
                history.status[j][i]        = get<std::int32_t>(in);
              }
          }
      }
      return {static_cast<unsigned int>(next_step), wall};
    }

    void
    BrakingAnalysis::solve()
    {
      const auto        &tr = prm.transient;
      ExplicitDynamics  &d  = *dynamics;
      const double       dt = result.time_step;
      const unsigned int n_steps =
        static_cast<unsigned int>(std::ceil(tr.end_time / dt - 1e-9)) + 1;
      const unsigned int every = std::max(1., std::round(1. / (tr.sampling_rate * dt)));
      history.sampling_rate    = 1. / (every * dt);
      const unsigned int snap_every =
        tr.snapshot_interval > 0. ?
          std::max(1., std::round(tr.snapshot_interval / dt)) :
          0;
      const double anim_start =
        tr.animation_start >= 0. ? tr.animation_start :
                                   tr.end_time - tr.animation_period;
      const unsigned int anim_every =
        tr.animation_frames > 0 ?
          std::max(1., std::round(tr.animation_period / tr.animation_frames / dt)) :
          0;

      Vector<double> u0(model.n_dofs()), v0(model.n_dofs());
      if (tr.initial_perturbation > 0. && !resuming)
        {
          // the seed: axial velocity in the shape of a (0,3) mode of the
          // scene's disc
          const scene::Body *disc = model.scene->disc();
          if (disc == nullptr)
            throw std::runtime_error(
              "Transient/Initial perturbation > 0 seeds a disc mode, and "
              "scene " + model.scene->description() + " has no disc");
          std::vector<bool> on_disc(model.n_dofs(), false);
          std::vector<types::global_dof_index> dofs(model.fe.n_dofs_per_cell());
          for (const auto &cell : model.dof_handler.active_cell_iterators())
            if (cell->material_id() == disc->id)
              {
                cell->get_dof_indices(dofs);
                for (const auto i : dofs)
                  on_disc[i] = true;
              }
          const double r_i = disc->inner_radius, r_o = disc->outer_radius;
          for (unsigned int i = 0; i < model.n_dofs(); ++i)
            if (on_disc[i] && !fixed[i])
              {
                const auto [r, theta] = disc->polar(points[i]);
                for (unsigned int c = 0; c < 3; ++c)
                  if (c == component[i])
                    v0[i] = tr.initial_perturbation * disc->axis[c] *
                            std::cos(3. * theta) * (r - r_i) / (r_o - r_i);
              }
        }
      d.initialise(u0, v0);
      unsigned int first_step = 0;
      double       wall_before = 0.;
      if (resuming)
        std::tie(first_step, wall_before) = read_checkpoint();

      pcout << "Time loop: " << n_steps << " steps to " << tr.end_time
            << " s; samples every " << every << " steps ("
            << history.sampling_rate << " Hz)";
      if (tr.checkpoint_interval > 0)
        pcout << "; checkpoint every " << tr.checkpoint_interval << " steps";
      if (resuming)
        pcout << "; resumed at step " << first_step << " (t = " << d.time()
              << " s)";
      pcout << std::endl;
      Vector<double> f(model.n_dofs());
      const auto     start = std::chrono::steady_clock::now();
      auto           last_report = start;
      for (unsigned int k = first_step; k < n_steps; ++k)
        {
          {
            TimerOutput::Scope ts(timer, "time steps");
            f.equ(ramp(k * dt, tr.ramp_duration), load);
            d.step(f);
          }
          if (k % every == 0)
            record_sample();
          {
            TimerOutput::Scope ts(timer, "snapshots");
            if (snap_every > 0 && k % snap_every == 0)
              write_snapshot("transient", n_snapshots++);
            if (anim_every > 0 && d.time() >= anim_start - 1e-15 &&
                k % anim_every == 0 && n_frames < tr.animation_frames)
              write_snapshot("animation", n_frames++);
          }
          if (tr.checkpoint_interval > 0 && (k + 1) % tr.checkpoint_interval == 0 &&
              k + 1 < n_steps)
            {
              TimerOutput::Scope ts(timer, "checkpoints");
              write_checkpoint(k + 1,
                               wall_before +
                                 std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - start)
                                   .count());
            }
          const auto now = std::chrono::steady_clock::now();
          if (std::chrono::duration<double>(now - last_report).count() > 10. ||
              k + 1 == n_steps)
            {
              last_report = now;
              const double wall =
                std::chrono::duration<double>(now - start).count();
              const double rate = (k + 1 - first_step) / wall;
              pcout << "  t = " << std::setw(10) << d.time() * 1e3 << " ms ("
                    << std::setw(3) << int(100. * (k + 1) / n_steps) << " %), "
                    << int(rate) << " steps/s, " << int((n_steps - k - 1) / rate)
                    << " s left; F_N = " << d.contact_state().normal_force
                    << " N, F_T = " << d.contact_state().force * sliding
                    << " N, stick/slip/separated "
                    << d.contact_state().n_stick << "/"
                    << d.contact_state().n_slip << "/"
                    << d.contact_state().n_separated << std::endl;
            }
        }
      result.n_steps   = n_steps;
      result.wall_time = wall_before + std::chrono::duration<double>(
                                         std::chrono::steady_clock::now() - start)
                                         .count();
    }

    void
    BrakingAnalysis::output_results()
    {
      TimerOutput::Scope t(timer, "output");
      const auto    &tr  = prm.transient;
      const fs::path dir(work_dir);
      const double   rate = history.sampling_rate;

      // Analysis window: Spectrum start (default: the second half).
      const double t_spec =
        tr.spectrum_start >= 0. ? tr.spectrum_start : tr.end_time / 2.;
      // The acceleration along the sliding direction for the spectrum (as
      // the thesis showed it); the velocity for the dominant frequency and
      // the envelope: the acceleration weights the limit cycle's harmonics
      // by k^2 and can make the third one look dominant.
      std::vector<double> acc, vel, vel_after_ramp;
      double              t_after_ramp = -1.;
      for (const auto &row : samples)
        {
          const double a_t = row[14] * sliding[0] + row[15] * sliding[1] +
                             row[16] * sliding[2];
          const double v_t = row[11] * sliding[0] + row[12] * sliding[1] +
                             row[13] * sliding[2];
          if (row[0] >= t_spec)
            {
              acc.push_back(a_t);
              vel.push_back(v_t);
            }
          if (row[0] >= tr.ramp_duration)
            {
              if (t_after_ramp < 0.)
                t_after_ramp = row[0];
              vel_after_ramp.push_back(v_t);
            }
        }
      Spectrum spectrum, velocity_spectrum;
      if (acc.size() >= 16)
        {
          spectrum                  = welch_psd(acc, rate);
          velocity_spectrum         = welch_psd(vel, rate);
          result.dominant_frequency = dominant_frequency(vel, rate, 100.);
        }
      if (result.dominant_frequency > 0. && vel_after_ramp.size() > 0)
        {
          try
            {
              result.growth = fit_growth(vel_after_ramp, rate, t_after_ramp,
                                         1. / result.dominant_frequency);
            }
          catch (const std::exception &)
            {
              // too short after the ramp: no verdict on growth
            }
          try
            {
              result.modal_growth =
                fit_modal_growth(vel_after_ramp, rate, t_after_ramp,
                                 result.dominant_frequency);
            }
          catch (const std::exception &)
            {
              // too short after the ramp: no verdict on growth
            }
        }
      // Separation after the ramp and the leading-edge pressure range.
      const double p_mean = tr.normal_force / mortar.slave_area;
      double       p_lo = 1e300, p_hi = 0.;
      for (unsigned int i = 0; i < history.time.size(); ++i)
        {
          if (history.time[i] < tr.ramp_duration)
            continue;
          for (unsigned int j = 0; j < mortar.n_slave(); ++j)
            if (history.status[j][i] == 0)
              result.separated = true;
          if (history.time[i] >= t_spec)
            for (const unsigned int j : leading_nodes)
              {
                p_lo = std::min(p_lo, history.p_N[j][i]);
                p_hi = std::max(p_hi, history.p_N[j][i]);
              }
        }
      if (p_hi > 0.)
        {
          result.leading_min_over_mean = p_lo / p_mean;
          result.leading_max_over_mean = p_hi / p_mean;
        }
      // Unstable: the envelope grew tenfold (then saturated or not), or its
      // fitted exponential at least doubled it over the fit (a slow growth,
      // or one from a large seed); stable: it decays, or stays within a
      // factor of 2.
      const GrowthFit &g      = result.growth;
      const double     factor = std::exp(g.growth_rate * (g.fit_end - g.fit_start));
      result.verdict =
        g.growing     ? (g.limit_cycle ? "unstable: limit cycle" :
                                         "unstable: still growing at End time") :
        factor >= 2.  ? "unstable: growing slowly (x" +
                          std::to_string(int(std::round(factor))) +
                          " over the fit)" :
        g.growth_rate < 0. ? "stable: vibration decays" :
                             "stable: no growth";

      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      {
        std::ofstream out(dir / "forces.csv");
        out << "time_s,normal_force_N,tangential_force_N,radial_force_N,"
               "contact_area_m2,n_stick,n_slip,n_separated\n"
            << std::setprecision(std::numeric_limits<double>::max_digits10);
        for (const auto &r : samples)
          out << r[0] << ',' << r[1] << ',' << r[2] << ',' << r[3] << ','
              << r[4] << ',' << r[5] << ',' << r[6] << ',' << r[7] << '\n';
      }
      {
        std::ofstream out(dir / "probes.csv");
        out << "# probe: pad leading edge at (" << probe_point[0] << ", "
            << probe_point[1] << ", " << probe_point[2]
            << ") m; sliding direction (" << sliding[0] << ", " << sliding[1]
            << ", " << sliding[2] << ")\n"
            << "time_s,u_x_m,u_y_m,u_z_m,v_x_m_per_s,v_y_m_per_s,v_z_m_per_s,"
               "a_x_m_per_s2,a_y_m_per_s2,a_z_m_per_s2\n"
            << std::setprecision(std::numeric_limits<double>::max_digits10);
        for (const auto &r : samples)
          {
            out << r[0];
            for (unsigned int k = 8; k < 17; ++k)
              out << ',' << r[k];
            out << '\n';
          }
      }
      {
        std::ofstream out(dir / "spectrum.csv");
        out << "# Welch PSD of the probe's acceleration and velocity along "
               "the sliding direction, t >= "
            << t_spec
            << " s\nfrequency_Hz,psd_m2_per_s4_per_Hz,psd_velocity_m2_per_s2_per_Hz\n"
            << std::setprecision(10);
        for (unsigned int k = 0; k < spectrum.psd.size(); ++k)
          out << spectrum.frequency[k] << ',' << spectrum.psd[k] << ','
              << velocity_spectrum.psd[k] << '\n';
      }
      {
        std::ofstream out(dir / "envelope.csv");
        out << "time_s,envelope_m_per_s\n" << std::setprecision(10);
        for (unsigned int k = 0; k < g.time.size(); ++k)
          out << g.time[k] << ',' << g.envelope[k] << '\n';
      }
      tribology::write_contact_history((dir / "contact_history.h5").string(),
                                       history);
      {
        std::ofstream out(dir / "summary.csv");
        out << "quantity,value\n"
            << std::setprecision(10) << "verdict," << result.verdict
            << "\npad_modulus_Pa," << prm.materials.pad.youngs_modulus
            << "\nfriction_coefficient," << prm.interface.friction_coefficient
            << "\ndominant_frequency_Hz," << result.dominant_frequency
            << "\ngrowth_rate_per_s," << g.growth_rate
            << "\ngrowth_fit_start_s," << g.fit_start
            << "\ngrowth_fit_end_s," << g.fit_end
            << "\ngrowth_rate_at_dominant_frequency_per_s,"
            << result.modal_growth.growth_rate
            << "\nmodal_fit_start_s," << result.modal_growth.fit_start
            << "\nmodal_fit_end_s," << result.modal_growth.fit_end
            << "\nlimit_cycle_amplitude_m_per_s," << g.final_amplitude
            << "\nlimit_cycle," << (g.limit_cycle ? 1 : 0)
            << "\nseparated," << (result.separated ? 1 : 0)
            << "\nleading_edge_p_min_over_mean," << result.leading_min_over_mean
            << "\nleading_edge_p_max_over_mean," << result.leading_max_over_mean
            << "\nn_dofs," << result.n_dofs << "\ntime_step_s,"
            << result.time_step << "\ncritical_time_step_s,"
            << result.critical_time_step << "\nn_steps," << result.n_steps
            << "\nwall_time_s," << result.wall_time << "\nsteps_per_s,"
            << result.n_steps / result.wall_time << "\n";
      }
      for (const auto &[file, list] :
           {std::make_pair("transient.pvd", &snapshots),
            std::make_pair("animation.pvd", &frames),
            std::make_pair("contact.pvd", &faces)})
        {
          std::ofstream pvd(dir / file);
          DataOutBase::write_pvd_record(pvd, *list);
        }

      pcout << "Verdict: " << result.verdict << "\n  dominant frequency "
            << result.dominant_frequency << " Hz";
      for (unsigned int h = 2; h <= 3 && !spectrum.psd.empty(); ++h)
        {
          const double f_h = h * result.dominant_frequency;
          unsigned int k   = 0;
          while (k + 1 < spectrum.frequency.size() &&
                 spectrum.frequency[k] < f_h)
            ++k;
          if (k + 1 < spectrum.frequency.size())
            pcout << "; harmonic " << h << " (" << f_h << " Hz) PSD "
                  << spectrum.psd[k];
        }
      pcout << "\n  growth rate " << g.growth_rate << " 1/s (fitted "
            << g.fit_start * 1e3 << "-" << g.fit_end * 1e3
            << " ms; at the dominant frequency alone "
            << result.modal_growth.growth_rate << " 1/s, "
            << result.modal_growth.fit_start * 1e3 << "-"
            << result.modal_growth.fit_end * 1e3
            << " ms), final amplitude " << g.final_amplitude
            << " m/s (probe velocity along the sliding direction)"
            << "\n  pad separated after the ramp: "
            << (result.separated ? "yes" : "no")
            << "; leading-edge pressure " << result.leading_min_over_mean
            << " to " << result.leading_max_over_mean
            << " x the mean\n  " << result.n_steps << " steps in "
            << result.wall_time << " s (" << result.n_steps / result.wall_time
            << " steps/s, " << result.wall_time / (tr.end_time * 1e3)
            << " s per simulated ms)" << std::endl;
    }

    void
    BrakingAnalysis::run()
    {
      run(false);
    }

    void
    BrakingAnalysis::resume()
    {
      run(true);
    }

    void
    BrakingAnalysis::run(const bool resume)
    {
      resuming = resume;
      setup_system();
      assemble_load();
      solve();
      output_results();
      MPI_Barrier(comm);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          fs::remove_all(fs::path(work_dir) / "checkpoint");
          output::publish_directory(work_dir, prm.output.directory);
        }
      MPI_Barrier(comm);
      pcout << "Results in " << prm.output.directory << std::endl;
    }

    void
    run_braking_grid(const parameters::AllParameters &prm,
                     const ParameterHandler          &handler,
                     MPI_Comm                         comm)
    {
      ConditionalOStream pcout(std::cout,
                               Utilities::MPI::this_mpi_process(comm) == 0);
      const bool         root = Utilities::MPI::this_mpi_process(comm) == 0;
      const std::string  work =
        output::partial_directory(prm.output.directory, prm.output.overwrite);
      if (root)
        {
          output::fresh_directory(work);
          std::ofstream out(fs::path(work) / "parameters.prm");
          handler.print_parameters(out, ParameterHandler::PRM);
        }
      MPI_Barrier(comm);
      const auto points = prm.sweep_points();
      const auto &first = prm.sweep.first.parameter,
                 &second = prm.sweep.second.parameter;
      std::ostringstream table;
      table << std::setprecision(8) << "point,folder,"
            << parameters::column_name(first) << ','
            << parameters::column_name(second)
            << ",verdict,dominant_frequency_Hz,growth_rate_per_s,"
               "growth_rate_at_dominant_frequency_per_s,"
               "limit_cycle_amplitude_m_per_s,separated,"
               "leading_edge_p_min_over_mean,leading_edge_p_max_over_mean,"
               "wall_time_s\n";
      unsigned int n_failed = 0;
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          parameters::AllParameters at = prm;
          at.set_nominal_point(points[i]);
          at.transient.grid                = false;
          at.transient.checkpoint_interval = 0;
          std::ostringstream name;
          name << "point_" << std::setw(2) << std::setfill('0') << i;
          at.output.directory = (fs::path(work) / name.str()).string();
          at.output.overwrite = true;
          const double a = points[i].get(first), b = points[i].get(second);
          pcout << "\n=== Grid point " << i + 1 << " of " << points.size()
                << ": " << first << " = " << a << ", " << second << " = " << b
                << " (" << name.str() << ") ===" << std::endl;
          table << i << ',' << name.str() << ',' << a << ',' << b << ',';
          std::string failure;
          BrakingSummary summary;
          {
            BrakingAnalysis run(at, handler, comm);
            try
              {
                run.run();
                summary = run.summary();
              }
            catch (const std::exception &e)
              {
                failure = e.what();
              }
          }
          if (!failure.empty())
            {
              ++n_failed;
              pcout << "Grid point " << i + 1 << " failed: " << failure
                    << std::endl;
              std::string quoted = failure;
              std::replace(quoted.begin(), quoted.end(), '"', '\'');
              table << "\"failed: " << quoted << "\",,,,,,,,\n";
              continue;
            }
          table << summary.verdict << ',' << summary.dominant_frequency << ','
                << summary.growth.growth_rate << ','
                << summary.modal_growth.growth_rate << ','
                << summary.growth.final_amplitude << ','
                << (summary.separated ? 1 : 0) << ','
                << summary.leading_min_over_mean << ','
                << summary.leading_max_over_mean << ',' << summary.wall_time
                << '\n';
        }
      if (n_failed == points.size())
        throw std::runtime_error("every point of the braking grid failed "
                                 "(see the messages above); nothing written");
      if (root)
        {
          std::ofstream out(fs::path(work) / "stability_table.csv");
          out << table.str();
        }
      pcout << "\nStability table (" << points.size() << " braking runs):\n"
            << table.str();
      if (root)
        output::publish_directory(work, prm.output.directory);
      MPI_Barrier(comm);
      pcout << "Results in " << prm.output.directory << std::endl;
    }
  } // namespace transient
} // namespace squeal
