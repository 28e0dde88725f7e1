// The transient braking simulation (see braking.h): the preload's
// structure and contact system, a lumped mass, the explicit integrator and
// the samples it records. The outputs are written by braking_output.cc, the
// checkpoints by braking_checkpoint.cc, the grid of runs by
// braking_grid.cc.

#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>

#include <squeal/analyses/braking.h>
#include <squeal/analyses/preload.h>
#include <squeal/base/memory_estimate.h>
#include <squeal/contact/scene_contact.h>
#include <squeal/io/output_directory.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <tuple>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;
    using transient::ContactStep;
    using transient::DistributedVector;
    using transient::ElasticityOperator;
    using transient::ExplicitDynamics;
    using transient::ExplicitSettings;
    using transient::lumped_mass;
    using transient::stable_time_step;
    using transient::StiffnessProduct;
    namespace fs = std::filesystem;

    namespace
    {
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

      // the last SIGINT or SIGTERM received during a time loop (0: none)
      volatile std::sig_atomic_t stop_signal = 0;

      extern "C" void
      note_stop_signal(const int number)
      {
        stop_signal = number;
      }

      // While it lives, SIGINT and SIGTERM are noted (stop_signal) instead
      // of ending the process, so that the time loop can write a checkpoint
      // and stop; the previous handlers come back afterwards.
      class StopSignals
      {
      public:
        StopSignals()
        {
          stop_signal = 0;
          old_int     = std::signal(SIGINT, note_stop_signal);
          old_term    = std::signal(SIGTERM, note_stop_signal);
        }
        ~StopSignals()
        {
          std::signal(SIGINT, old_int);
          std::signal(SIGTERM, old_term);
        }
        StopSignals(const StopSignals &) = delete;
        StopSignals &
        operator=(const StopSignals &) = delete;

      private:
        void (*old_int)(int);
        void (*old_term)(int);
      };
    } // namespace

    BrakingAnalysis::BrakingAnalysis(
      const parameters::AllParameters                   &prm,
      const ParameterHandler                            &handler,
      MPI_Comm                                           comm,
      const std::vector<std::pair<std::string, double>> &point)
      : prm(prm)
      , handler(handler)
      , comm(comm)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
      , timer(pcout, TimerOutput::summary, TimerOutput::wall_times)
      , model(prm, comm)
    {
      model.nominal_overrides = point;
      model.varied            = std::set<std::string>(); // nothing is swept
      model.tie_constraints   = contact::add_tie_constraints;
    }

    void
    BrakingAnalysis::setup_system()
    {
      TimerOutput::Scope t(timer, "setup");
      const bool         serial = Utilities::MPI::n_mpi_processes(comm) == 1;
      // Serial run: the products may use every core (deal.II threads; the
      // program starts with one thread per MPI rank).
      if (serial)
        MultithreadInfo::set_thread_limit();
      if (!serial && prm.transient.stiffness_product == "sparse")
        throw std::runtime_error(
          "Transient/Stiffness product = sparse is serial (the assembled "
          "matrix is copied to one process); use matrix-free under mpirun");
      prepare_work_dir();
      // springs spread over a face act at its nodes, as the lumped mass
      model.lumped_springs = true;
      model.setup_and_assemble(pcout);
      if (!model.scene->ties.empty())
        throw std::runtime_error(
          "scene " + model.scene->description() + " has ties ('" +
          model.scene->ties.front().name +
          "'): the braking run's lumped mass and explicit step take holds "
          "only; mesh the bonded bodies with shared nodes");
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
      const physics::HeldDofs held =
        physics::held_dofs(model, points, component);
      fixed = held.on_holds;
      Point<3> held_point;
      for (const auto d : held.point_held)
        {
          fixed[d]   = true;
          held_point = points[d];
        }
      if (serial)
        {
          // the assembled matrix for the sparse product (the preload's
          // contact system: the same holds)
          AffineConstraints<double> contact_constraints;
          contact::contact_system(model,
                                  pattern,
                                  stiffness,
                                  contact_constraints);
        }
      // the fixed DoFs as constraints, the same on every rank: for the
      // matrix-free product and the load
      constraints.clear();
      for (unsigned int i = 0; i < n; ++i)
        if (fixed[i])
          constraints.add_line(i);
      constraints.close();

      const parameters::ScalarPoint nominal = model.scene->nominal_point();
      mass =
        lumped_mass(model.dof_handler, model.mapping, [&](const auto &cell) {
          return model.scene->density(cell->material_id(), nominal);
        });
      physics::add_lumped_masses(model, mass);

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
      mortar = contact::scene_mortar(model, prm.preload.search_distance, quiet);
      sliding          = contact::common_sliding(*model.scene);
      radial           = pair.radial();
      double pair_size = pair.size;
      for (const scene::ContactPair &other : pairs)
        pair_size = std::min(pair_size, other.size);

      const auto layout =
        std::make_shared<Utilities::MPI::Partitioner>(model.locally_owned_dofs,
                                                      comm);
      const StiffnessProduct product = make_stiffness_product(layout);
      const auto            &tr      = prm.transient;

      // Stability limit and time step.
      const scene::Scene &sc = *model.scene;
      for (const scene::Body &b : sc.bodies)
        if (b.own_damping)
          throw std::runtime_error(
            "body '" + b.name +
            "' has its own Rayleigh damping: the braking run damps every "
            "body with Damping/Alpha and Beta; remove alpha and beta from "
            "its Bodies item");
      const auto limit = stable_time_step(
        product, layout, mass, fixed, points, sc.damping_beta, tr.beta2);
      ExplicitSettings s;
      s.time_step =
        tr.time_step > 0. ? tr.time_step : tr.safety_factor * limit.critical;
      s.beta2                = tr.beta2;
      s.alpha                = sc.damping_alpha;
      s.beta                 = sc.damping_beta;
      s.friction_coefficient = sc.common_friction_coefficient(nominal);
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
      dynamics = std::make_unique<ExplicitDynamics>(
        product, layout, mass, fixed, s, limit.critical);
      if (tr.stiffness_product == "matrix-free")
        dynamics->use_buffered_product(
          {[this]() { return matrix_free->input_buffer(); },
           [this]() { matrix_free->apply_buffers(); },
           [this]() { return matrix_free->output_buffer(); }});
      const double omega = prm.interface.rotation_sense == "counterclockwise" ?
                             tr.angular_velocity :
                             -tr.angular_velocity;
      dynamics->set_contact(mortar, [omega, pair](const Point<3> &x) {
        return omega * cross_product_3d(pair.axis, x - pair.axis_point);
      });
      result.n_dofs             = n;
      result.time_step          = s.time_step;
      result.critical_time_step = limit.critical;

      setup_probe(pair, pair_size);

      const auto [n_groups, split] = dynamics->contact_groups();
      pcout << "Braking: " << n << " DoFs, " << mortar.n_slave()
            << " slave-face nodes in " << n_groups
            << (split ? " independent groups, split among the ranks" :
                        " independent group(s), solved by every rank")
            << "; point holds at (" << held_point[0] << ", " << held_point[1]
            << ", " << held_point[2] << ") m\n"
            << "Stability limit " << limit.critical << " s (largest frequency "
            << limit.omega_max / (2 * numbers::PI) << " Hz, "
            << limit.lanczos_steps << " Lanczos steps); time step "
            << s.time_step << " s, beta2 = " << tr.beta2 << "\nProbe: pad "
            << "leading edge at (" << probe_point[0] << ", " << probe_point[1]
            << ", " << probe_point[2] << ") m" << std::endl;
      // what the time loop adds: the samples (17 numbers) and the contact
      // history (4 numbers and a status per slave node), on every rank
      const double history = tr.end_time * tr.sampling_rate * 17. * 8. +
                             std::max(0., tr.end_time - tr.history_start) *
                               tr.sampling_rate * mortar.n_slave() *
                               (4. * 8. + 4.);
      report_memory_estimate(comm,
                             pcout.is_active() ? &pcout.get_stream() : nullptr,
                             n,
                             history * Utilities::MPI::n_mpi_processes(comm),
                             "the recorded samples and contact history (the "
                             "operators are in place)");
    }

    // Output/Directory.partial: fresh (parameters.prm, vtu/, checkpoint/),
    // or the stopped run's when resuming (its checkpoint must exist).
    void
    BrakingAnalysis::prepare_work_dir()
    {
      if (resuming)
        {
          work_dir = io::normalised(prm.output.directory) + ".partial";
          if (!fs::is_regular_file(fs::path(work_dir) / "checkpoint" /
                                   "latest"))
            throw std::runtime_error(
              "no checkpoint in '" + work_dir +
              "/checkpoint': a braking run writes one every Transient/"
              "Checkpoint interval steps and removes it when it ends");
        }
      else
        {
          work_dir = io::start_work_directory(prm.output.directory,
                                              prm.output.overwrite,
                                              handler,
                                              comm,
                                              {"vtu", "checkpoint"});
        }
      parameters_crc = parameters_checksum();
    }

    // The stiffness product of the time loop (Transient/Stiffness product):
    // matrix-free (elasticity per material plus the springs' diagonal, each
    // spring tying one DoF to the ground, on this rank's cells) or, serial
    // only, the assembled matrix; serial runs time both on one vector and
    // check that they agree.
    StiffnessProduct
    BrakingAnalysis::make_stiffness_product(
      const std::shared_ptr<const Utilities::MPI::Partitioner> &layout)
    {
      const bool         serial = Utilities::MPI::n_mpi_processes(comm) == 1;
      const unsigned int n      = model.n_dofs();
      const parameters::ScalarPoint nominal = model.scene->nominal_point();
      const auto                   &tr      = prm.transient;
      // Both products as the time loop calls them (the sparse one through
      // serial copies, serial runs only).
      StiffnessProduct sparse_product;
      if (serial)
        {
          auto in        = std::make_shared<Vector<double>>(n);
          auto out       = std::make_shared<Vector<double>>(n);
          sparse_product = [this, in, out](DistributedVector       &y,
                                           const DistributedVector &v) {
            std::copy(v.begin(), v.end(), in->begin());
            stiffness.vmult(*out, *in);
            std::copy(out->begin(), out->end(), y.begin());
          };
        }
      {
        // the springs' entries in this rank's rows (to the ground, between
        // two bodies, or spread over a face), the fixed rows left out
        physics::PETScMatrix ks;
        model.parts().springs(nominal, ks);
        std::vector<ElasticityOperator::SpringEntry> springs;
        for (const auto i : model.locally_owned_dofs)
          if (!fixed[i])
            for (auto e = ks.begin(i), end = ks.end(i); e != end; ++e)
              if (e->value() != 0.)
                springs.push_back({i, e->column(), e->value()});
        matrix_free = std::make_unique<ElasticityOperator>(
          model.dof_handler,
          model.mapping,
          constraints,
          [this, nominal](const types::material_id id) {
            return physics::lame_constants(
              model.scene->youngs_modulus(id, nominal),
              model.scene->body(id).material.poisson_ratio);
          },
          springs,
          [this, nominal](const types::material_id id, const Point<3> &x)
            -> std::optional<SymmetricTensor<4, 3>> {
            if (!model.scene->body(id).law.anisotropic)
              return std::nullopt;
            return model.scene->stiffness_tensor(id, x, nominal);
          });
      }
      const StiffnessProduct free_product = [this](DistributedVector       &y,
                                                   const DistributedVector &v) {
        matrix_free->vmult(y, v);
      };
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
              "matrix by " +
              as_text(difference) + " (relative)");
        }
      else
        {
          const auto cells = Utilities::MPI::min_max_avg(
            double(model.triangulation.n_locally_owned_active_cells()), comm);
          pcout << "Stiffness product: matrix-free on "
                << Utilities::MPI::n_mpi_processes(comm) << " MPI ranks ("
                << cells.min << "-" << cells.max << " cells per rank)"
                << std::endl;
        }

      return product;
    }

    // The probe: the leading-edge slave node (smallest coordinate along the
    // sliding direction: where the disc enters the contact) nearest the
    // first pair's centre along the radius; the leading-edge row for the
    // pressure range; the contact history's frame and node lists.
    void
    BrakingAnalysis::setup_probe(const scene::ContactPair &pair,
                                 const double              pair_size)
    {
      double s_min = 1e300;
      for (unsigned int j = 0; j < mortar.n_slave(); ++j)
        s_min = std::min(s_min, mortar.slave_points[j] * sliding);
      const double h      = pair_size * 1e-6;
      unsigned int best   = 0;
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
      // each node's pad face: its contact pair
      history.face_names.clear();
      for (const scene::ContactPair &p : model.scene->contact_pairs)
        history.face_names.push_back(p.name);
      history.face.assign(mortar.n_slave(), 0);
      if (!mortar.slave_pair.empty())
        history.face.assign(mortar.slave_pair.begin(), mortar.slave_pair.end());
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
    }

    void
    BrakingAnalysis::assemble_load()
    {
      TimerOutput::Scope t(timer, "setup");
      // one load vector per ramp time
      loads.clear();
      total_load      = 0.;
      ramp_end        = 0.;
      const auto &all = model.scene->loads;
      for (unsigned int l = 0; l < all.size(); ++l)
        {
          const double T =
            all[l].ramp < 0. ? prm.transient.ramp_duration : all[l].ramp;
          double     force = 0.;
          const auto f     = contact::scene_load(
            model, constraints, prm.transient.normal_force, l, &force);
          total_load += force;
          ramp_end = std::max(ramp_end, T);
          const auto same =
            std::find_if(loads.begin(), loads.end(), [T](const auto &g) {
              return g.first == T;
            });
          if (same == loads.end())
            loads.emplace_back(T, f);
          else
            same->second += f;
        }
      if (loads.empty())
        contact::scene_load(model, constraints, 0.); // throws: no load
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
                            comm,
                            ArrayView<double>(probe.data(), probe.size()));
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
    BrakingAnalysis::solve()
    {
      const auto       &tr    = prm.transient;
      ExplicitDynamics &d     = *dynamics;
      const double      dt    = result.time_step;
      const double      steps = std::ceil(tr.end_time / dt - 1e-9) + 1;
      if (!(steps < 2e9))
        throw std::runtime_error(
          "Transient/End time = " + as_text(tr.end_time) +
          " s at a time step of " + as_text(dt) + " s is " + as_text(steps) +
          " steps, more than a run can count (2e9); shorten the run or "
          "coarsen the mesh");
      const unsigned int n_steps = static_cast<unsigned int>(steps);
      const unsigned int every =
        std::max(1., std::round(1. / (tr.sampling_rate * dt)));
      history.sampling_rate = 1. / (every * dt);
      const unsigned int snap_every =
        tr.snapshot_interval > 0. ?
          std::max(1., std::round(tr.snapshot_interval / dt)) :
          0;
      const double       anim_start = tr.animation_start >= 0. ?
                                        tr.animation_start :
                                        tr.end_time - tr.animation_period;
      const unsigned int anim_every =
        tr.animation_frames > 0 ?
          std::max(1.,
                   std::round(tr.animation_period / tr.animation_frames / dt)) :
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
              "scene " +
              model.scene->description() + " has no disc");
          std::vector<bool>                    on_disc(model.n_dofs(), false);
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
      unsigned int first_step  = 0;
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
      // the loads act on a few faces: f is set on their DoFs only, each
      // load scaled by its ramp's factor at the step
      Vector<double>                       f(model.n_dofs());
      std::vector<types::global_dof_index> load_support;
      std::vector<double>                  factors(loads.size());
      for (types::global_dof_index i = 0; i < model.n_dofs(); ++i)
        if (std::any_of(loads.begin(), loads.end(), [i](const auto &g) {
              return g.second[i] != 0.;
            }))
          load_support.push_back(i);
      const auto        start       = std::chrono::steady_clock::now();
      auto              last_report = start;
      const StopSignals signals;
      const bool        parallel = Utilities::MPI::n_mpi_processes(comm) > 1;
      const auto        wall_now = [&]() {
        return wall_before + std::chrono::duration<double>(
                               std::chrono::steady_clock::now() - start)
                               .count();
      };
      double sweeps = 0.;
      for (unsigned int k = first_step; k < n_steps; ++k)
        {
          {
            TimerOutput::Scope ts(timer, "time steps");
            for (unsigned int g = 0; g < loads.size(); ++g)
              factors[g] = ramp(k * dt, loads[g].first);
            for (const auto i : load_support)
              {
                f[i] = 0.;
                for (unsigned int g = 0; g < loads.size(); ++g)
                  f[i] += factors[g] * loads[g].second[i];
              }
            d.step(f);
          }
          sweeps += d.contact_state().pgs_iterations;
          result.max_contact_sweeps =
            std::max(result.max_contact_sweeps,
                     d.contact_state().pgs_iterations);
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
          if (tr.checkpoint_interval > 0 &&
              (k + 1) % tr.checkpoint_interval == 0 && k + 1 < n_steps)
            {
              TimerOutput::Scope ts(timer, "checkpoints");
              write_checkpoint(k + 1, wall_now());
            }
          // SIGINT/SIGTERM: every rank stops after the same step, with a
          // checkpoint to resume from (the ranks agree every 64 steps)
          const int stop =
            !parallel    ? int(stop_signal) :
            k % 64 == 63 ? Utilities::MPI::max(int(stop_signal), comm) :
                           0;
          if (stop != 0 && k + 1 < n_steps)
            {
              if (last_checkpoint != k + 1)
                write_checkpoint(k + 1, wall_now());
              throw std::runtime_error(
                std::string(stop == SIGINT ? "SIGINT" : "SIGTERM") +
                " received: the run stopped at t = " + as_text(d.time()) +
                " s (step " + std::to_string(k + 1) + " of " +
                std::to_string(n_steps) +
                ") and saved its state; continue it with squeal --resume " +
                io::normalised(prm.output.directory));
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
                    << int(rate) << " steps/s, "
                    << int((n_steps - k - 1) / rate)
                    << " s left; F_N = " << d.contact_state().normal_force
                    << " N, F_T = " << d.contact_state().force * sliding
                    << " N, stick/slip/separated " << d.contact_state().n_stick
                    << "/" << d.contact_state().n_slip << "/"
                    << d.contact_state().n_separated << std::endl;
            }
        }
      result.n_steps = n_steps;
      result.mean_contact_sweeps =
        n_steps > first_step ? sweeps / (n_steps - first_step) : 0.;
      result.wall_time =
        wall_before +
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
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
      io::finish_run(work_dir, prm.output.directory, comm, "checkpoint");
      pcout << "Results in " << prm.output.directory << std::endl;
    }
  } // namespace analyses
} // namespace squeal
