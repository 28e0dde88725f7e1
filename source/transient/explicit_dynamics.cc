// Explicit dynamics with forward-increment Lagrange multiplier contact (see
// explicit_dynamics.h). The step costs one sparse product with K and a
// projected Gauss-Seidel sweep over the interface nodes; the lumped mass
// keeps every local contact problem a scalar one.

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <squeal/transient/explicit_dynamics.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <istream>
#include <map>
#include <ostream>
#include <random>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace transient
  {
    using namespace dealii;

    Vector<double>
    lumped_mass(
      const DoFHandler<3> &dof_handler,
      const Mapping<3>    &mapping,
      const std::function<double(const DoFHandler<3>::active_cell_iterator &)>
        &density)
    {
      const auto &fe = dof_handler.get_fe();
      // Gauss-Lobatto points coincide with the nodes of FE_Q (equidistant
      // for degree <= 2, Gauss-Lobatto beyond): the rule makes the mass
      // diagonal with positive weights.
      const QGaussLobatto<3>               quadrature(fe.degree + 1);
      FEValues<3>                          fe_values(mapping,
                            fe,
                            quadrature,
                            update_values | update_JxW_values);
      Vector<double>                       m(dof_handler.n_dofs());
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          const double rho = density(cell);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              double mi = 0.;
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                mi += fe_values.shape_value(i, q) *
                      fe_values.shape_value(i, q) * fe_values.JxW(q);
              m[dofs[i]] += rho * mi;
            }
        }
      return m;
    }

    namespace
    {
      // M^-1/2 K M^-1/2 on the free DoFs (zero rows and columns elsewhere).
      struct ScaledStiffness
      {
        const StiffnessProduct   &K;
        DistributedVector         scale; // 1/sqrt(m), 0 on fixed DoFs
        mutable DistributedVector tmp;
        void
        vmult(DistributedVector &dst, const DistributedVector &src) const
        {
          tmp = src;
          tmp.scale(scale);
          K(dst, tmp);
          dst.scale(scale);
        }
      };

      // A value in [-1, 1] from a point and a component: the Lanczos start
      // vector, independent of the DoF numbering.
      double
      hash(const Point<3> &x, const unsigned int c)
      {
        const double t = std::sin(12.9898e3 * x[0] + 78.233e3 * x[1] +
                                  37.719e3 * x[2] + 1.618 * c) *
                         43758.5453;
        return 2. * (t - std::floor(t)) - 1.;
      }

      StableTimeStep
      lanczos(const ScaledStiffness   &A,
              const DistributedVector &b,
              const double             beta,
              const double             beta2,
              const unsigned int       lanczos_steps)
      {
        DistributedVector x(b);
        x = 0.;
        // The Ritz values of CG's Lanczos process approach the top of the
        // spectrum from below; a few dozen steps resolve it to well under
        // the safety factor a run applies (see benchmarks/transient).
        double                      lambda_max = 0.;
        IterationNumberControl      control(lanczos_steps, 0.);
        SolverCG<DistributedVector> cg(control);
        cg.connect_eigenvalues_slot(
          [&](const std::vector<double> &ev) {
            if (!ev.empty())
              lambda_max = std::max(lambda_max, ev.back());
          },
          true);
        cg.solve(A, x, b, PreconditionIdentity());
        StableTimeStep s;
        s.lanczos_steps = control.last_step();
        s.omega_max     = std::sqrt(lambda_max);
        const double z  = beta * s.omega_max / 2.;
        s.critical =
          std::sqrt(2. / beta2) / s.omega_max * (std::sqrt(1. + z * z) - z);
        return s;
      }

      // dst = K src through serial copies (the SparseMatrix constructors).
      StiffnessProduct
      serial_product(const SparseMatrix<double> &K)
      {
        auto in  = std::make_shared<Vector<double>>(K.m());
        auto out = std::make_shared<Vector<double>>(K.m());
        return
          [&K, in, out](DistributedVector &dst, const DistributedVector &src) {
            std::copy(src.begin(), src.end(), in->begin());
            K.vmult(*out, *in);
            std::copy(out->begin(), out->end(), dst.begin());
          };
      }
    } // namespace

    StableTimeStep
    stable_time_step(const SparseMatrix<double> &K,
                     const Vector<double>       &mass,
                     const std::vector<bool>    &fixed,
                     const double                beta,
                     const double                beta2,
                     const unsigned int          lanczos_steps)
    {
      const unsigned int n = K.m();
      const auto layout    = std::make_shared<Utilities::MPI::Partitioner>(n);
      const StiffnessProduct product = serial_product(K);
      ScaledStiffness        A{product,
                        DistributedVector(layout),
                        DistributedVector(layout)};
      DistributedVector      b(layout);
      std::mt19937           random(12345); // deterministic start vector
      std::uniform_real_distribution<double> uniform(-1., 1.);
      for (unsigned int i = 0; i < n; ++i)
        {
          A.scale[i] = fixed[i] ? 0. : 1. / std::sqrt(mass[i]);
          b[i]       = fixed[i] ? 0. : uniform(random);
        }
      return lanczos(A, b, beta, beta2, lanczos_steps);
    }

    StableTimeStep
    stable_time_step(
      const StiffnessProduct                                   &K,
      const std::shared_ptr<const Utilities::MPI::Partitioner> &partitioner,
      const Vector<double>                                     &mass,
      const std::vector<bool>                                  &fixed,
      const std::vector<Point<3>>                              &points,
      const double                                              beta,
      const double                                              beta2,
      const unsigned int                                        lanczos_steps)
    {
      ScaledStiffness   A{K,
                        DistributedVector(partitioner),
                        DistributedVector(partitioner)};
      DistributedVector b(partitioner);
      for (unsigned int l = 0; l < partitioner->locally_owned_size(); ++l)
        {
          const auto i             = partitioner->local_to_global(l);
          A.scale.local_element(l) = fixed[i] ? 0. : 1. / std::sqrt(mass[i]);
          b.local_element(l)       = fixed[i] ? 0. : hash(points[i], i % 3);
        }
      return lanczos(A, b, beta, beta2, lanczos_steps);
    }

    ExplicitDynamics::ExplicitDynamics(const SparseMatrix<double> &K,
                                       const Vector<double>       &mass,
                                       const std::vector<bool>    &fixed,
                                       const ExplicitSettings     &settings,
                                       const double                dt_critical)
      : ExplicitDynamics(serial_product(K),
                         std::make_shared<Utilities::MPI::Partitioner>(K.m()),
                         mass,
                         fixed,
                         settings,
                         dt_critical)
    {}

    ExplicitDynamics::ExplicitDynamics(
      StiffnessProduct                                          product,
      const std::shared_ptr<const Utilities::MPI::Partitioner> &partitioner,
      const Vector<double>                                     &mass,
      const std::vector<bool>                                  &fixed,
      const ExplicitSettings                                   &settings,
      const double                                              dt_critical)
      : K(std::move(product))
      , layout(partitioner)
      , inverse_mass(partitioner->size())
      , fixed(fixed)
      , settings(settings)
    {
      const unsigned int n = partitioner->size();
      std::ostringstream msg;
      if (!(settings.beta2 >= 0.5 && settings.beta2 <= 1.))
        msg << "beta2 = " << settings.beta2 << " is outside [0.5, 1]";
      else if (!(settings.time_step > 0.))
        msg << "the time step must be positive (got " << settings.time_step
            << " s)";
      else if (settings.time_step > dt_critical)
        msg << "the time step " << settings.time_step
            << " s exceeds the stability limit " << dt_critical
            << " s of the explicit scheme (largest frequency of the mesh "
               "and damping); choose at most that";
      if (!msg.str().empty())
        throw std::runtime_error(msg.str());
      if (mass.size() != n || fixed.size() != n)
        throw std::runtime_error("the lumped mass and the fixed flags need "
                                 "one entry per DoF");
      reinit_vectors();
      for (unsigned int i = 0; i < n; ++i)
        inverse_mass[i] = fixed[i] ? 0. : 1. / mass[i];
      const auto first = partitioner->local_range().first;
      for (unsigned int l = 0; l < partitioner->locally_owned_size(); ++l)
        owned_free.push_back(fixed[first + l] ? 0. : 1.);
    }

    void
    ExplicitDynamics::use_buffered_product(
      const BufferedStiffnessProduct &product)
    {
      if (!product.input || !product.apply || !product.output)
        throw std::invalid_argument(
          "a buffered stiffness product needs input, apply and output");
      buffered_K = product;
    }

    void
    ExplicitDynamics::reinit_vectors()
    {
      for (auto *vec : {&u, &v, &a, &v_pred, &u_next, &work})
        vec->reinit(layout);
      u_ghosts_current = false;
    }

    void
    ExplicitDynamics::set_contact(
      const contact::MortarOperators                      &m,
      const std::function<Tensor<1, 3>(const Point<3> &)> &master_velocity)
    {
      mortar                 = &m;
      const unsigned int n_s = m.n_slave();
      {
        // every interface DoF a ghost of every rank's vectors
        IndexSet ghosts(layout->size());
        for (const auto *list : {&m.slave_dofs, &m.master_dofs})
          for (const auto &d : *list)
            for (const auto i : d)
              ghosts.add_index(i);
        ghosts.add_indices(layout->locally_owned_range());
        ghosts.compress();
        layout = std::make_shared<Utilities::MPI::Partitioner>(
          layout->locally_owned_range(),
          ghosts,
          layout->get_mpi_communicator());
        reinit_vectors();
      }
      delassus.assign(n_s, 0.);
      master_slide.assign(n_s, Tensor<1, 3>());
      multiplier.assign(n_s, Tensor<1, 3>());
      iface_local.clear();
      iface_inverse_mass.clear();
      row_start.assign(1, 0);
      row_node.clear();
      row_w.clear();
      row_cwim.clear();
      // The node's 3 x 3 Delassus block is c sum_k w_k^2 diag(1/m_k) (0 for
      // a fixed component); the local solve uses its largest entry, which
      // under-relaxes nodes with a fixed component and keeps the exact
      // local solution elsewhere (the fixed point is the same).
      const double                                    c = increment_factor();
      std::map<types::global_dof_index, unsigned int> compact_node;
      for (unsigned int j = 0; j < n_s; ++j)
        {
          if (m.D[j] > 0.)
            {
              const auto add = [&](const contact::NodeDofs &d, const double w) {
                const auto [it, is_new] =
                  compact_node.emplace(d[0], compact_node.size());
                if (is_new)
                  for (unsigned int k = 0; k < 3; ++k)
                    {
                      iface_local.push_back(layout->global_to_local(d[k]));
                      iface_inverse_mass.push_back(inverse_mass[d[k]]);
                    }
                row_node.push_back(it->second);
                row_w.push_back(w);
                // c w / m of each component, in apply()'s order of
                // multiplication
                for (unsigned int k = 0; k < 3; ++k)
                  row_cwim.push_back(c * w * inverse_mass[d[k]]);
                delassus[j] += w * w *
                               std::max({inverse_mass[d[0]],
                                         inverse_mass[d[1]],
                                         inverse_mass[d[2]]});
              };
              add(m.slave_dofs[j], -m.D[j]);
              for (const auto &[l, w] : m.M[j])
                {
                  add(m.master_dofs[l], w);
                  if (master_velocity)
                    master_slide[j] += w * master_velocity(m.master_points[l]);
                }
            }
          row_start.push_back(row_node.size());
        }
      iface_start.assign(iface_local.size(), 0.);
      iface_next.assign(iface_local.size(), 0.);
      assign_contact_groups();
      contact.pressure.reinit(n_s);
      contact.slip_velocity.reinit(n_s);
      contact.traction.assign(n_s, Tensor<1, 3>());
      contact.status.assign(n_s, 0);
    }

    void
    ExplicitDynamics::assign_contact_groups()
    {
      const unsigned int n_s     = multiplier.size();
      const unsigned int n_nodes = iface_local.size() / 3;
      const MPI_Comm     comm    = layout->get_mpi_communicator();
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
      const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
      // groups: the connected components of the compact nodes, two nodes
      // joined when one weighted gap holds both (union-find)
      std::vector<unsigned int> parent(n_nodes);
      for (unsigned int i = 0; i < n_nodes; ++i)
        parent[i] = i;
      const auto root = [&](unsigned int i) {
        while (parent[i] != i)
          i = parent[i] = parent[parent[i]];
        return i;
      };
      for (unsigned int j = 0; j < n_s; ++j)
        for (unsigned int e = row_start[j] + 1; e < row_start[j + 1]; ++e)
          {
            const unsigned int a = root(row_node[row_start[j]]),
                               b = root(row_node[e]);
            if (a != b)
              parent[std::max(a, b)] = std::min(a, b);
          }
      // each group's work (its weighted-gap entries), the groups in order
      // of their first compact node
      std::map<unsigned int, std::size_t> work;
      for (unsigned int j = 0; j < n_s; ++j)
        if (row_start[j + 1] > row_start[j])
          work[root(row_node[row_start[j]])] += row_start[j + 1] - row_start[j];
      n_groups      = work.size();
      split_contact = n_ranks > 1 && n_groups > 1;
      std::map<unsigned int, unsigned int> rank_of_group;
      {
        // largest group first to the least loaded rank (the same on every
        // rank: the interface is replicated)
        std::vector<std::pair<std::size_t, unsigned int>> by_work;
        for (const auto &[g, w] : work)
          by_work.emplace_back(w, g);
        std::stable_sort(by_work.begin(),
                         by_work.end(),
                         [](const auto &x, const auto &y) {
                           return x.first > y.first;
                         });
        std::vector<std::size_t> load(n_ranks, 0);
        for (const auto &[w, g] : by_work)
          {
            const unsigned int r =
              std::min_element(load.begin(), load.end()) - load.begin();
            rank_of_group[g] = r;
            load[r] += w;
          }
      }
      own_entry.assign(iface_local.size(), 1);
      own_slave.resize(n_s);
      for (unsigned int j = 0; j < n_s; ++j)
        own_slave[j] = row_start[j + 1] > row_start[j];
      if (!split_contact)
        return;
      for (unsigned int i = 0; i < n_nodes; ++i)
        for (unsigned int k = 0; k < 3; ++k)
          own_entry[3 * i + k] = rank_of_group[root(i)] == rank;
      for (unsigned int j = 0; j < n_s; ++j)
        own_slave[j] = row_start[j + 1] > row_start[j] &&
                       rank_of_group[root(row_node[row_start[j]])] == rank;
    }

    void
    ExplicitDynamics::initialise(const Vector<double> &u0,
                                 const Vector<double> &v0)
    {
      for (unsigned int l = 0; l < layout->locally_owned_size(); ++l)
        {
          const auto i       = layout->local_to_global(l);
          u.local_element(l) = u0[i];
          v.local_element(l) = v0[i];
        }
      v_pred           = v;
      a                = 0.;
      n_step           = 0;
      pending          = false;
      u_ghosts_current = false;
      for (auto &l : multiplier)
        l = Tensor<1, 3>();
    }

    void
    ExplicitDynamics::step(const Vector<double> &f)
    {
      const double       dt = settings.time_step;
      const unsigned int n  = layout->locally_owned_size();
      // the step's vector updates fused into passes over the owned entries
      // (each pass reads and writes the vectors once)
      if (pending)
        {
          u.swap(u_next);
          u_ghosts_current = mortar != nullptr;
          ++n_step;
        }
      {
        // v~_{n+1} = v~_n + dt a_n (after a step), then u_n + beta v~_n
        double *vp       = v_pred.begin(),
               *w        = buffered_K.apply ? buffered_K.input() : work.begin();
        const double *ua = u.begin(), *aa = a.begin();
        const double  beta = settings.beta;
        if (pending)
          for (unsigned int l = 0; l < n; ++l)
            {
              vp[l] += dt * aa[l];
              w[l] = ua[l] + beta * vp[l];
            }
        else
          for (unsigned int l = 0; l < n; ++l)
            w[l] = ua[l] + beta * vp[l];
      }
      // a*_n = M^-1 (f_n - K (u_n + beta v~_n) - alpha M v~_n)
      if (buffered_K.apply)
        buffered_K.apply();
      else
        K(a, work);
      const double c = increment_factor();
      {
        double       *aa = a.begin(), *un = u_next.begin();
        const double *kw    = buffered_K.apply ? buffered_K.output() : aa;
        const auto    first = layout->local_range().first;
        const double *ua = u.begin(), *vp = v_pred.begin(),
                     *ff   = f.begin() + first,
                     *im   = inverse_mass.begin() + first,
                     *free = owned_free.data();
        const double alpha = settings.alpha;
        // a fixed DoF: a = 0 and u_{n+1} = u_n exactly
        for (unsigned int l = 0; l < n; ++l)
          {
            aa[l] = free[l] * ((ff[l] - kw[l]) * im[l] - alpha * vp[l]);
            // u_{n+1} = u_n + dt v_n + dt^2/2 a_n,
            // v_n = v~_n + dt beta2 a_n
            un[l] = ua[l] + free[l] * dt * vp[l] + free[l] * c * aa[l];
          }
      }
      if (mortar)
        solve_contact();
      // v_n = v~_n + dt beta2 a_n, and the size of u_{n+1} (four partial
      // sums in registers: one would chain every addition to the last)
      double square_sum = 0.;
      {
        double       *vv = v.begin();
        const double *vp = v_pred.begin(), *aa = a.begin(),
                     *un = u_next.begin();
        const double h   = dt * settings.beta2;
        double       s0 = 0., s1 = 0., s2 = 0., s3 = 0.;
        unsigned int l = 0;
        for (; l + 4 <= n; l += 4)
          {
            for (unsigned int k = l; k < l + 4; ++k)
              vv[k] = vp[k] + h * aa[k];
            s0 += un[l] * un[l];
            s1 += un[l + 1] * un[l + 1];
            s2 += un[l + 2] * un[l + 2];
            s3 += un[l + 3] * un[l + 3];
          }
        for (; l < n; ++l)
          {
            vv[l] = vp[l] + h * aa[l];
            s0 += un[l] * un[l];
          }
        square_sum = (s0 + s1) + (s2 + s3);
      }
      pending = true;
      if (!std::isfinite(
            Utilities::MPI::sum(square_sum, layout->get_mpi_communicator())))
        {
          std::ostringstream msg;
          msg << "the explicit solution is not finite at t = " << time()
              << " s (step " << n_step << ", time step " << dt
              << " s): the step was checked against the model's stability "
                 "limit, so look for what else can blow up: a load, a "
                 "material, a spring or an interface stiffness far out of "
                 "scale, or contact that the step resolves badly (try "
                 "Transient/Safety factor 0.5)";
          throw std::runtime_error(msg.str());
        }
    }

    void
    ExplicitDynamics::solve_contact()
    {
      const double       dt  = settings.time_step;
      const double       c   = increment_factor();
      const double       mu  = settings.friction_coefficient;
      const unsigned int n_s = multiplier.size();
      // R_j(x) = sum_k w_k x_k: weighted motion of the master against the
      // slave node j [m^3 or m^3/s].
      // Every rank sees the interface: the owners' values into the ghosts;
      // then each rank runs the same sweeps on the same numbers, writing
      // the corrections into its owned entries and its ghost copies alike.
      if (!u_ghosts_current)
        u.update_ghost_values();
      u_next.update_ghost_values();
      // The sweeps run on compact copies of the interface entries of u_n
      // and u_{n+1} (gathered here, u_{n+1}'s scattered back after them).
      const unsigned int n_iface = iface_local.size();
      for (unsigned int e = 0; e < n_iface; ++e)
        {
          iface_start[e] = u.local_element(iface_local[e]);
          iface_next[e]  = u_next.local_element(iface_local[e]);
        }
      const auto relative = [&](const unsigned int         j,
                                const std::vector<double> &x) {
        Tensor<1, 3> r;
        for (unsigned int e = row_start[j]; e < row_start[j + 1]; ++e)
          {
            const double *xn = x.data() + 3 * row_node[e];
            for (unsigned int k = 0; k < 3; ++k)
              r[k] += row_w[e] * xn[k];
          }
        return r;
      };
      const auto active = [&](const unsigned int j) {
        return row_start[j + 1] > row_start[j];
      };
      std::vector<Tensor<1, 3>> start(n_s);
      for (unsigned int j = 0; j < n_s; ++j)
        if (active(j))
          start[j] = relative(j, iface_start);

      // Warm start: the multipliers of the previous step, applied.
      const auto apply = [&](const unsigned int j, const Tensor<1, 3> &dP) {
        for (unsigned int e = row_start[j]; e < row_start[j + 1]; ++e)
          {
            double       *xn  = iface_next.data() + 3 * row_node[e];
            const double *cwm = row_cwim.data() + 3 * e;
            for (unsigned int k = 0; k < 3; ++k)
              xn[k] += cwm[k] * dP[k];
          }
      };
      for (unsigned int j = 0; j < n_s; ++j)
        if (own_slave[j])
          apply(j, multiplier[j]);

      unsigned int it     = 0;
      double       change = 0.;
      for (; it < settings.pgs_max_iterations; ++it)
        {
          double max_change = 0., max_value = 0.;
          for (unsigned int j = 0; j < n_s; ++j)
            {
              if (!own_slave[j] || !(delassus[j] > 0.))
                continue;
              const Tensor<1, 3> &nj = mortar->normals[j];
              const Tensor<1, 3>  R  = relative(j, iface_next);
              const double        g  = mortar->gap0[j] + nj * R;
              // slip of the slave against the master over the step
              Tensor<1, 3> s = -(R - start[j]) - dt * master_slide[j];
              s -= (s * nj) * nj;
              const double cw     = c * delassus[j];
              const double z      = multiplier[j] * nj;
              Tensor<1, 3> lambda = multiplier[j] - z * nj;
              const double z_new  = std::max(0., z - g / cw);
              Tensor<1, 3> l_new  = lambda + s / cw;
              const double norm   = l_new.norm();
              if (norm > mu * z_new)
                l_new *= (norm > 0. ? mu * z_new / norm : 0.);
              const Tensor<1, 3> P  = z_new * nj + l_new;
              const Tensor<1, 3> dP = P - multiplier[j];
              apply(j, dP);
              multiplier[j] = P;
              max_change    = std::max(max_change, dP.norm());
              max_value     = std::max(max_value, P.norm());
            }
          if (split_contact)
            {
              double local[2] = {max_change, max_value}, global[2];
              Utilities::MPI::max(ArrayView<const double>(local, 2),
                                  layout->get_mpi_communicator(),
                                  ArrayView<double>(global, 2));
              max_change = global[0];
              max_value  = global[1];
            }
          change = max_value > 0. ? max_change / max_value : 0.;
          if (change <= settings.pgs_tolerance)
            break;
        }
      if (it == settings.pgs_max_iterations)
        {
          std::ostringstream msg;
          msg
            << "the contact multipliers (projected Gauss-Seidel) did not "
               "converge at t = "
            << time() << " s: relative change " << change << " after " << it
            << " iterations (tolerance " << settings.pgs_tolerance
            << "); raise Transient/Contact iterations or reduce the time step";
          throw std::runtime_error(msg.str());
        }
      if (split_contact)
        {
          // every compact entry and multiplier is this rank's or another
          // single rank's: summing with zeros elsewhere copies it exactly
          std::vector<double> &mine = iface_exchange;
          mine.assign(n_iface + 3 * n_s, 0.);
          for (unsigned int e = 0; e < n_iface; ++e)
            if (own_entry[e])
              mine[e] = iface_next[e];
          for (unsigned int j = 0; j < n_s; ++j)
            if (own_slave[j])
              for (unsigned int k = 0; k < 3; ++k)
                mine[n_iface + 3 * j + k] = multiplier[j][k];
          Utilities::MPI::sum(mine, layout->get_mpi_communicator(), mine);
          std::copy(mine.begin(), mine.begin() + n_iface, iface_next.begin());
          for (unsigned int j = 0; j < n_s; ++j)
            for (unsigned int k = 0; k < 3; ++k)
              multiplier[j][k] = mine[n_iface + 3 * j + k];
        }
      // u_{n+1} corrected on every interface entry, owned and ghost alike
      for (unsigned int e = 0; e < n_iface; ++e)
        u_next.local_element(iface_local[e]) = iface_next[e];

      // a_n = a*_n + M^-1 G^T Lambda_n, and the contact report.
      ContactStep &out = contact;
      out.force        = Tensor<1, 3>();
      out.normal_force = out.contact_area = 0.;
      out.n_stick = out.n_slip = out.n_separated = 0;
      out.pgs_iterations                         = it + 1;
      out.pgs_change                             = change;
      for (unsigned int j = 0; j < n_s; ++j)
        {
          if (!active(j))
            {
              out.status[j] = 0;
              ++out.n_separated;
              continue;
            }
          for (unsigned int e = row_start[j]; e < row_start[j + 1]; ++e)
            for (unsigned int k = 0; k < 3; ++k)
              {
                const unsigned int ce = 3 * row_node[e] + k;
                a.local_element(iface_local[ce]) +=
                  row_w[e] * iface_inverse_mass[ce] * multiplier[j][k];
              }
          const Tensor<1, 3> &nj     = mortar->normals[j];
          const double        z      = multiplier[j] * nj;
          const Tensor<1, 3>  lambda = multiplier[j] - z * nj;
          const double        D      = mortar->D[j];
          out.pressure[j]            = z;
          out.traction[j]            = -lambda; // on the slave
          out.force += -D * multiplier[j];
          out.normal_force += D * z;
          Tensor<1, 3> s =
            -(relative(j, iface_next) - start[j]) - dt * master_slide[j];
          s -= (s * nj) * nj;
          out.slip_velocity[j] = s.norm() / (D * dt);
          if (!(z > 0.))
            {
              out.status[j] = 0;
              ++out.n_separated;
            }
          else
            {
              out.contact_area += D;
              const bool slip = lambda.norm() >= mu * z * (1. - 1e-9);
              out.status[j]   = slip ? 2 : 1;
              ++(slip ? out.n_slip : out.n_stick);
            }
        }
    }

    namespace
    {
      const char checkpoint_tag[] = "squeal explicit state 1";
    }

    void
    ExplicitDynamics::save(std::ostream &out) const
    {
      out.write(checkpoint_tag, sizeof(checkpoint_tag));
      const std::uint64_t header[5] = {n_step,
                                       pending ? 1u : 0u,
                                       multiplier.size(),
                                       layout->size(),
                                       layout->locally_owned_size()};
      out.write(reinterpret_cast<const char *>(header), sizeof(header));
      out.write(reinterpret_cast<const char *>(&settings.time_step),
                sizeof(double));
      for (const auto *vec : {&u, &u_next, &v, &v_pred, &a})
        out.write(reinterpret_cast<const char *>(vec->begin()),
                  vec->locally_owned_size() * sizeof(double));
      for (const auto &l : multiplier)
        for (unsigned int k = 0; k < 3; ++k)
          out.write(reinterpret_cast<const char *>(&l[k]), sizeof(double));
      if (!out)
        throw std::runtime_error("the integrator's state could not be written");
    }

    void
    ExplicitDynamics::load(std::istream &in)
    {
      char tag[sizeof(checkpoint_tag)] = {};
      in.read(tag, sizeof(tag));
      if (!in || std::string(tag) != checkpoint_tag)
        throw std::runtime_error("not a state of squeal's explicit integrator");
      std::uint64_t header[5] = {};
      double        dt        = 0.;
      in.read(reinterpret_cast<char *>(header), sizeof(header));
      in.read(reinterpret_cast<char *>(&dt), sizeof(double));
      if (!in || header[2] != multiplier.size() || dt != settings.time_step ||
          header[3] != layout->size() ||
          header[4] != layout->locally_owned_size())
        {
          std::ostringstream msg;
          msg << "the saved integrator state does not fit this model: "
              << header[2] << " slave nodes, " << header[3] << " DoFs ("
              << header[4] << " on this rank) and time step " << dt
              << " s saved, " << multiplier.size() << ", " << layout->size()
              << " (" << layout->locally_owned_size() << ") and "
              << settings.time_step << " s here (same mesh and number of "
              << "MPI ranks needed)";
          throw std::runtime_error(msg.str());
        }
      for (auto *vec : {&u, &u_next, &v, &v_pred, &a})
        in.read(reinterpret_cast<char *>(vec->begin()),
                vec->locally_owned_size() * sizeof(double));
      for (auto &l : multiplier)
        for (unsigned int k = 0; k < 3; ++k)
          in.read(reinterpret_cast<char *>(&l[k]), sizeof(double));
      if (!in)
        throw std::runtime_error("the saved integrator state is short");
      n_step           = header[0];
      pending          = header[1] != 0;
      u_ghosts_current = false;
    }

    double
    ExplicitDynamics::kinetic_energy() const
    {
      double e = 0.;
      for (unsigned int l = 0; l < layout->locally_owned_size(); ++l)
        {
          const auto i = layout->local_to_global(l);
          if (inverse_mass[i] > 0.)
            e += v.local_element(l) * v.local_element(l) / inverse_mass[i];
        }
      return Utilities::MPI::sum(e, layout->get_mpi_communicator()) / 2.;
    }

    double
    ExplicitDynamics::strain_energy() const
    {
      K(work, u);
      return (work * u) / 2.;
    }

  } // namespace transient
} // namespace squeal
