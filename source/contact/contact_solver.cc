// Static contact on dual mortar operators by the primal-dual active-set
// method (see contact_solver.h). The structure is linear, so every
// iteration is one solve of the augmented (saddle-point) system for the
// displacements and the pressures of the active nodes; the active set is
// then updated from the complementarity function, and the iteration stops
// when it no longer changes. Because the multipliers are dual, the pressure
// of a node is its own unknown (no coupling through a mass matrix), which
// keeps the active-set update node-wise.

#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_solver.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <squeal/contact/contact_solver.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace squeal
{
  namespace contact
  {
    using namespace dealii;

    namespace
    {
      // Row j of B (normal) or G (friction) as (dof, value) pairs: the
      // derivative of dir . (sum_l M_jl u_l - D_jj u_j) -- the gap for the
      // normal -- with respect to u.
      std::vector<std::pair<types::global_dof_index, double>>
      row(const MortarOperators &op, unsigned int j, const Tensor<1, 3> &dir)
      {
        std::vector<std::pair<types::global_dof_index, double>> r;
        for (unsigned int c = 0; c < 3; ++c)
          {
            if (dir[c] == 0.)
              continue;
            r.emplace_back(op.slave_dofs[j][c], -op.D[j] * dir[c]);
            for (const auto &[l, m] : op.M[j])
              r.emplace_back(op.master_dofs[l][c], m * dir[c]);
          }
        return r;
      }

      // The augmented system [K + contact columns; contact rows] x = rhs,
      // N x N, solved directly. entries: the contact blocks (row, column,
      // value), the same on every rank; void_row: multiplier rows with no
      // free DoF (identity). Throws std::runtime_error("singular") if the
      // solve fails or its residual is not small.
      Vector<double>
      solve_augmented(
        const ContactStiffness &K,
        const unsigned int      N,
        const std::vector<std::tuple<unsigned int, unsigned int, double>>
                                &entries,
        const Vector<double>    &rhs,
        const std::vector<char> &void_row)
      {
        const unsigned int n = K.size();
        Vector<double>     x(N);
        // Each rank its rows of K, the last rank also the contact rows
        // n..N-1 (PETSc wants contiguous ranges in rank order); one rank
        // (the serial K) owns all. MUMPS's LU: on the coarse passenger-car
        // brake's shifted stiffness 1.4x faster to factorise than UMFPACK,
        // 9x faster to solve and 2.3x smaller (benchmarks/scale/README.md).
        const std::pair<types::global_dof_index, types::global_dof_index>
          range =
            K.serial ? std::make_pair(0u, n) : K.distributed->local_range();
        // f(row, columns, values) for every row of K this rank holds
        const auto for_each_row = [&K, range](const auto &f) {
          std::vector<types::global_dof_index> columns;
          std::vector<double>                  values;
          const auto copy = [&](auto e, const auto end) {
            for (; e != end; ++e)
              {
                columns.push_back(e->column());
                values.push_back(e->value());
              }
          };
          for (auto i = range.first; i < range.second; ++i)
            {
              columns.clear();
              values.clear();
              if (K.serial)
                copy(K.serial->begin(i), K.serial->end(i));
              else
                copy(K.distributed->begin(i), K.distributed->end(i));
              f(i, columns, values);
            }
        };
        const unsigned int rank = Utilities::MPI::this_mpi_process(K.comm),
                           size = Utilities::MPI::n_mpi_processes(K.comm);
        IndexSet owned(N);
        owned.add_range(range.first, range.second);
        if (rank == size - 1)
          owned.add_range(n, N);
        PETScWrappers::MPI::SparseMatrix A;
        {
          // the pattern freed before MUMPS allocates (1.5 GB at a million
          // DoFs)
          DynamicSparsityPattern dsp(N, N, owned);
          for_each_row([&dsp](const types::global_dof_index i,
                              const auto                   &columns,
                              const auto &) {
            dsp.add_entries(i, columns.begin(), columns.end());
          });
          for (const auto &[r, col, v] : entries)
            if (owned.is_element(r))
              dsp.add(r, col);
          for (unsigned int i = n; i < N; ++i)
            if (owned.is_element(i))
              dsp.add(i, i);
          A.reinit(owned, owned, dsp, K.comm);
        }
        for_each_row([&A](const types::global_dof_index i,
                          const auto                   &columns,
                          const auto &values) { A.set(i, columns, values); });
        A.compress(VectorOperation::insert);
        for (const auto &[r, col, v] : entries)
          if (owned.is_element(r))
            A.add(r, col, v);
        for (unsigned int i = n; i < N; ++i)
          if (owned.is_element(i) && void_row[i])
            A.add(i, i, 1.);
        A.compress(VectorOperation::add);
        PETScWrappers::MPI::Vector b(owned, K.comm), xd(owned, K.comm),
          res(owned, K.comm);
        for (const auto i : owned)
          b[i] = rhs[i];
        b.compress(VectorOperation::insert);
        SolverControl                    control(1, 0.);
        PETScWrappers::SparseDirectMUMPS mumps(control, K.comm);
        bool                             failed = false;
        try
          {
            mumps.solve(A, xd, b);
            A.vmult(res, xd);
            res -= b;
            failed = !std::isfinite(xd.l2_norm()) ||
                     res.l2_norm() > 1e-6 * std::max(b.l2_norm(), 1e-300);
          }
        catch (const std::exception &)
          {
            failed = true;
          }
        if (Utilities::MPI::logical_or(failed, K.comm))
          throw std::runtime_error("singular");
        x = Vector<double>(xd); // gathered on every rank
        return x;
      }
    } // namespace

    ContactStiffness::ContactStiffness(const SparseMatrix<double> &K)
      : serial(&K)
      , comm(MPI_COMM_SELF)
    {}

    ContactStiffness::ContactStiffness(
      const PETScWrappers::MPI::SparseMatrix &K,
      MPI_Comm                                comm)
      : distributed(&K)
      , comm(comm)
    {}

    unsigned int
    ContactStiffness::size() const
    {
      return serial ? serial->m() : distributed->m();
    }

    std::vector<double>
    ContactStiffness::diagonal(
      const std::vector<types::global_dof_index> &dofs) const
    {
      std::vector<double> d(dofs.size(), 0.);
      if (serial)
        {
          for (unsigned int i = 0; i < dofs.size(); ++i)
            d[i] = serial->diag_element(dofs[i]);
          return d;
        }
      const auto range = distributed->local_range();
      for (unsigned int i = 0; i < dofs.size(); ++i)
        if (dofs[i] >= range.first && dofs[i] < range.second)
          d[i] = distributed->diag_element(dofs[i]);
      const std::vector<double> local = d;
      Utilities::MPI::sum(local, comm, d);
      return d;
    }

    namespace
    {
      // The active-set iteration of solve_static_contact(): the per-node
      // data fixed for the solve (tangent frames, sliding directions,
      // complementarity constants, the imposed slip), the current sets
      // (active, stick, slip directions and their linearisation), and the
      // three steps of an iteration: the linearised augmented system solved,
      // the new sets, the final contact state.
      class ActiveSet
      {
      public:
        ActiveSet(const ContactStiffness          &K,
                  const Vector<double>            &f,
                  const AffineConstraints<double> &constraints,
                  const MortarOperators           &op,
                  const ContactSettings           &settings);

        // One iteration's linearised augmented system (u, then z_n of each
        // active node, then for Coulomb its 2 tangential tractions) solved;
        // displacement, pressure and tangential traction of S updated.
        // Returns the active nodes in column order.
        std::vector<unsigned int>
        solve_linearised(unsigned int it, ContactSolution &s) const;

        // The new sets from the state S with weighted gaps G; for Coulomb
        // the slip condition's residual |t - mu z n(y)| on the slip nodes
        // (relative to mu max z) and the largest turn of a slip direction.
        ContactIteration
        update_sets(const ContactSolution &s,
                    const Vector<double>  &g,
                    double                &turn);

        // The converged state: gaps, slips, status, resultant forces.
        void
        finish(ContactSolution &s, const Vector<double> &g) const;

        // The sets of the last update_sets() become the current ones.
        void
        advance();

        bool
        coulomb() const
        {
          return model == FrictionModel::coulomb;
        }

        unsigned int
        n_stick(const std::vector<unsigned int> &A) const
        {
          unsigned int n = 0;
          if (coulomb())
            for (const unsigned int j : A)
              n += stick[j];
          return n;
        }

      private:
        // T_jk: derivative of the weighted slip tau_k . (D u_j - sum M u_l)
        std::vector<std::pair<types::global_dof_index, double>>
        slip_row(unsigned int j, unsigned int k) const
        {
          auto r = row(op, j, frame[j][k]);
          for (auto &e : r)
            e.second = -e.second;
          return r;
        }

        std::array<double, 2>
        slip_of(unsigned int j, const Vector<double> &u) const
        {
          std::array<double, 2> sl = imposed[j];
          for (unsigned int k = 0; k < 2; ++k)
            for (const auto &[d, v] : slip_row(j, k))
              sl[k] += v * (u[d] - u_prev[d]);
          return sl;
        }

        const ContactStiffness          &K;
        const Vector<double>            &f;
        const AffineConstraints<double> &constraints;
        const MortarOperators           &op;
        const unsigned int               n, n_s;
        const double                     mu;
        const FrictionModel              model;
        Vector<double>                   u_prev;

        // per node: the tangent frame, the sliding direction in it, the
        // complementarity constant c_j = K_nn / D_jj^2 (pressure per
        // weighted gap of the node's own stiffness), the imposed slip
        std::vector<std::array<Tensor<1, 3>, 2>> frame;
        std::vector<std::array<double, 2>>       slide;
        std::vector<double>                      c;
        std::vector<std::array<double, 2>>       imposed;
        // per node: the compliance e_j = D_jj / k_j [m^5/N] of a compliant
        // normal law (0: hard), g_j + e_j z_j = 0 on the active set
        std::vector<double> compliance;

        // Sets: active (in contact), stick (Coulomb only); per slip node the
        // direction n of its trial traction and a = mu z / |trial| at the
        // last iterate (the linearisation point of the slip condition).
        std::vector<char>                  active, stick;
        std::vector<std::array<double, 2>> dir;
        std::vector<double>                curl;
        // the sets found by update_sets(), taken by advance()
        std::vector<char>                  next, next_stick;
        std::vector<std::array<double, 2>> next_dir;
        std::vector<double>                next_curl;
      };

      ActiveSet::ActiveSet(const ContactStiffness          &K,
                           const Vector<double>            &f,
                           const AffineConstraints<double> &constraints,
                           const MortarOperators           &op,
                           const ContactSettings           &settings)
        : K(K)
        , f(f)
        , constraints(constraints)
        , op(op)
        , n(K.size())
        , n_s(op.n_slave())
        , mu(settings.friction_coefficient)
        , model(settings.friction_coefficient > 0. ?
                  settings.friction :
                  FrictionModel::frictionless)
        , u_prev(K.size())
        , frame(n_s)
        , slide(n_s)
        , c(n_s)
        , imposed(n_s, {{0., 0.}})
        , compliance(n_s, 0.)
        , active(n_s, 0)
        , stick(n_s, 0)
        , curl(n_s, 0.)
      {
        if (settings.previous_displacement.size() == n)
          u_prev = settings.previous_displacement;
        if (!settings.normal_stiffness.empty())
          {
            if (settings.normal_stiffness.size() != n_s)
              throw std::runtime_error(
                "contact: the normal contact law has " +
                std::to_string(settings.normal_stiffness.size()) +
                " stiffnesses for " + std::to_string(n_s) +
                " slave nodes (give one per node, or none for hard contact)");
            for (unsigned int j = 0; j < n_s; ++j)
              {
                const double k = settings.normal_stiffness[j];
                if (!std::isfinite(k) || k < 0.)
                  throw std::runtime_error(
                    "contact: the normal stiffness of slave node " +
                    std::to_string(j) + " is " + std::to_string(k) +
                    " N/m^3; it must be finite and >= 0 (0: hard contact)");
                compliance[j] = k > 0. ? op.D[j] / k : 0.;
              }
          }
        std::vector<types::global_dof_index> slave_dofs;
        for (unsigned int j = 0; j < n_s; ++j)
          for (unsigned int d = 0; d < 3; ++d)
            slave_dofs.push_back(op.slave_dofs[j][d]);
        const std::vector<double> k_diag = K.diagonal(slave_dofs);
        for (unsigned int j = 0; j < n_s; ++j)
          {
            frame[j]       = {{op.tangents1[j], op.tangents2[j]}};
            Tensor<1, 3> t = settings.sliding_direction;
            t -= (t * op.normals[j]) * op.normals[j];
            if (t.norm() > 0.)
              t /= t.norm();
            slide[j] = {{t * frame[j][0], t * frame[j][1]}};
            double k = 0.;
            for (unsigned int d = 0; d < 3; ++d)
              k += k_diag[3 * j + d] * std::abs(op.normals[j][d]);
            c[j] = k / (op.D[j] * op.D[j]);
          }
        // The master surface's imposed rigid slip (a turning disc) enters
        // each slip as -(sum_l M_jl) tau_k . delta.
        for (unsigned int j = 0; j < n_s; ++j)
          {
            double m = 0.;
            for (const auto &e : op.M[j])
              m += e.second;
            for (unsigned int k = 0; k < 2; ++k)
              imposed[j][k] = -m * (frame[j][k] * settings.master_slip);
          }
        dir = slide;
        // Closed at the start: nodes whose weighted gap is zero to rounding
        // (relative to the node's length scale sqrt(D_jj)); they start
        // stuck. A previous load step's sets, when given, are the better
        // start.
        const bool warm = settings.initial_status.size() == n_s;
        for (unsigned int j = 0; j < n_s; ++j)
          {
            active[j] =
              std::isfinite(op.gap0[j]) &&
              (warm ? settings.initial_status[j] != 0 :
                      op.gap0[j] <= 1e-10 * op.D[j] * std::sqrt(op.D[j]));
            stick[j] = model == FrictionModel::coulomb && active[j] &&
                       (!warm || settings.initial_status[j] == 1);
            // a node slipping at the previous load step keeps its traction's
            // direction for the first iteration
            if (model == FrictionModel::coulomb && warm &&
                settings.initial_traction.size() == n_s)
              {
                const auto  &t0   = settings.initial_traction[j];
                const double norm = std::hypot(t0[0], t0[1]);
                if (norm > 0.)
                  dir[j] = {{t0[0] / norm, t0[1] / norm}};
              }
          }
      }

      std::vector<unsigned int>
      ActiveSet::solve_linearised(const unsigned int it,
                                  ContactSolution   &s) const
      {
        // Unknowns: u, then z_n of each active node, then (Coulomb: 2 per
        // active node) its tangential traction.
        std::vector<unsigned int> A;
        std::vector<unsigned int> column(n_s, 0), t_column(n_s, 0);
        for (unsigned int j = 0; j < n_s; ++j)
          if (active[j])
            {
              column[j] = n + A.size();
              A.push_back(j);
            }
        unsigned int n_stick = 0;
        if (coulomb())
          for (unsigned int i = 0; i < A.size(); ++i)
            {
              t_column[A[i]] = n + A.size() + 2 * i;
              n_stick += stick[A[i]];
            }
        const unsigned int N = n + (coulomb() ? 3 : 1) * A.size();
        // (row, column, value) of the contact blocks
        std::vector<std::tuple<unsigned int, unsigned int, double>> entries;
        Vector<double> rhs(N), x(N);
        for (unsigned int i = 0; i < n; ++i)
          rhs[i] = f[i];
        const auto force_column =
          [&](unsigned int col, const auto &rows, double scale) {
            for (const auto &[d, v] : rows)
              if (!constraints.is_constrained(d))
                entries.emplace_back(d, col, -scale * v);
          };
        // A constraint row on the unconstrained DoFs, scaled by `scale`;
        // the constrained ones (Dirichlet) move to the right-hand side,
        // which gets `value`. A row with no free DoF and nothing else
        // (`alone`) is met by the boundary conditions: its multiplier is
        // void (an identity row, value 0).
        std::vector<char> void_row(N, 0);
        const auto        constraint_row = [&](unsigned int r,
                                        const auto  &rows,
                                        double       value,
                                        double       scale = 1.,
                                        bool         alone = true) {
          bool any = false;
          for (const auto &[d, v] : rows)
            if (constraints.is_constrained(d))
              value -= scale * v * constraints.get_inhomogeneity(d);
            else
              {
                entries.emplace_back(r, d, scale * v);
                any = true;
              }
          rhs[r] += (any || !alone) ? value : 0.;
          void_row[r] = !any && alone;
        };
        for (unsigned int j : A)
          {
            const auto b = row(op, j, op.normals[j]);
            // hard: g_j = 0; compliant: g_j + e_j z_j = 0
            constraint_row(column[j], b, -op.gap0[j], 1., compliance[j] == 0.);
            if (compliance[j] > 0.)
              entries.emplace_back(column[j], column[j], compliance[j]);
            // normal force B^T z
            force_column(column[j], b, 1.);
            if (model == FrictionModel::steady_sliding)
              for (unsigned int k = 0; k < 2; ++k)
                force_column(column[j], slip_row(j, k), mu * dir[j][k]);
            if (!coulomb())
              continue;
            std::array<std::vector<std::pair<types::global_dof_index, double>>,
                       2>
              T{{slip_row(j, 0), slip_row(j, 1)}};
            // s = T u - prev: the slip since the previous load step
            std::array<double, 2> prev{{-imposed[j][0], -imposed[j][1]}};
            for (unsigned int k = 0; k < 2; ++k)
              {
                for (const auto &[d, v] : T[k])
                  prev[k] += v * u_prev[d];
                force_column(t_column[j] + k, T[k], 1.);
              }
            if (stick[j])
              // no slip since the previous load step: T_j u = T_j u_prev
              for (unsigned int k = 0; k < 2; ++k)
                constraint_row(t_column[j] + k, T[k], prev[k]);
            else
              {
                // Slip: t = mu z n(y), y = t - c s the trial traction,
                // linearised at the last iterate (semi-smooth Newton,
                // Hueber, Stadler & Wohlmuth 2008, the slip branch of
                // their eq. 3.5 in the normalised form):
                //   (I - a P) t - mu n z + a c P s(u) = 0,
                // P = I - n n^T, a = mu z / |y| < 1 at the last iterate.
                const std::array<double, 2> &nn = dir[j];
                const double                 a  = curl[j];
                for (unsigned int k = 0; k < 2; ++k)
                  {
                    const unsigned int r = t_column[j] + k;
                    for (unsigned int l = 0; l < 2; ++l)
                      {
                        const double P = (k == l) - nn[k] * nn[l];
                        entries.emplace_back(r,
                                             t_column[j] + l,
                                             (k == l) - a * P);
                        if (a != 0. && P != 0.)
                          constraint_row(r,
                                         T[l],
                                         a * c[j] * P * prev[l],
                                         a * c[j] * P,
                                         false);
                      }
                    entries.emplace_back(r, column[j], -mu * nn[k]);
                  }
              }
          }
        try
          {
            x = solve_augmented(K, N, entries, rhs, void_row);
          }
        catch (const std::exception &)
          {
            throw std::runtime_error(
              "contact: the linear system of active-set iteration " +
              std::to_string(it + 1) + " (" + std::to_string(A.size()) +
              " active nodes) is singular: is every body held, by "
              "boundary conditions or by contact?");
          }
        for (unsigned int i = 0; i < n; ++i)
          s.displacement[i] = x[i];
        constraints.distribute(s.displacement);
        s.pressure = 0.;
        for (unsigned int j = 0; j < n_s; ++j)
          {
            s.tangential_traction[j] = {{0., 0.}};
            if (!active[j])
              continue;
            s.pressure[j] = x[column[j]];
            for (unsigned int k = 0; k < 2; ++k)
              s.tangential_traction[j][k] =
                coulomb() ? x[t_column[j] + k] :
                model == FrictionModel::steady_sliding ?
                            mu * s.pressure[j] * dir[j][k] :
                            0.;
          }
        return A;
      }

      ContactIteration
      ActiveSet::update_sets(const ContactSolution &s,
                             const Vector<double>  &g,
                             double                &turn)
      {
        // The new sets, and for Coulomb the slip condition's residual
        // |t - mu z n(y)| on the slip nodes (relative to mu max z): it
        // falls super-linearly once the sets stop changing.
        ContactIteration info;
        next.assign(n_s, 0);
        next_stick.assign(n_s, 0);
        next_dir = dir;
        next_curl.assign(n_s, 0.);
        double slip_residual = 0., z_max = 0.;
        turn = 0.;
        // An active node whose multiplier is negative only by rounding
        // (|z| < 1e-9 of the largest) stays active: dropping it and
        // taking it back forever was a cycle of the active set.
        double z_scale = 0.;
        for (unsigned int j = 0; j < n_s; ++j)
          z_scale = std::max(z_scale, std::abs(s.pressure[j]));
        for (unsigned int j = 0; j < n_s; ++j)
          {
            if (!std::isfinite(op.gap0[j]))
              continue;
            next[j] =
              s.pressure[j] - c[j] * (g[j] + compliance[j] * s.pressure[j]) >
              (active[j] ? -1e-9 * z_scale : 0.);
            info.changed += next[j] != active[j];
            info.active += next[j];
            z_max = std::max(z_max, s.pressure[j]);
            if (active[j])
              info.tension = std::max(info.tension, -s.pressure[j]);
            else
              info.penetration = std::max(info.penetration, -g[j] / op.D[j]);
            if (!coulomb() || !next[j])
              continue;
            // trial traction y = t - c s against the cone mu z
            const std::array<double, 2> sl = slip_of(j, s.displacement);
            const std::array<double, 2> y{
              {s.tangential_traction[j][0] - c[j] * sl[0],
               s.tangential_traction[j][1] - c[j] * sl[1]}};
            const double norm  = std::hypot(y[0], y[1]);
            const double bound = mu * std::max(s.pressure[j], 0.);
            next_stick[j]      = norm <= bound || norm == 0.;
            if (!next_stick[j])
              {
                next_dir[j]  = {{y[0] / norm, y[1] / norm}};
                next_curl[j] = bound / norm;
                if (active[j] && !stick[j] &&
                    next_dir[j][0] * dir[j][0] + next_dir[j][1] * dir[j][1] <
                      0.)
                  {
                    // The slip reversed within one iteration: it passed
                    // through zero, so the node sticks next (this breaks
                    // the two-cycle of a node flipping between opposite
                    // directions).
                    next_stick[j] = true;
                    next_dir[j]   = dir[j];
                    next_curl[j]  = 0.;
                  }
                else if (active[j] && !stick[j])
                  {
                    turn = std::max(turn,
                                    std::hypot(next_dir[j][0] - dir[j][0],
                                               next_dir[j][1] - dir[j][1]));
                    slip_residual =
                      std::max(slip_residual,
                               std::hypot(s.tangential_traction[j][0] -
                                            bound * next_dir[j][0],
                                          s.tangential_traction[j][1] -
                                            bound * next_dir[j][1]));
                  }
              }
            info.changed += next[j] == active[j] && next_stick[j] != stick[j];
            info.stick += next_stick[j];
          }
        slip_residual /= std::max(mu * z_max, 1e-300);
        info.slip_residual = slip_residual;
        return info;
      }

      void
      ActiveSet::finish(ContactSolution &s, const Vector<double> &g) const
      {
        s.gap.reinit(n_s);
        s.status.assign(n_s, 0);
        s.slip.assign(n_s, {{0., 0.}});
        Tensor<1, 3> friction;
        s.contact_force.reinit(n);
        for (unsigned int j = 0; j < n_s; ++j)
          {
            s.gap[j] = std::isfinite(op.gap0[j]) ? g[j] / op.D[j] : op.gap0[j];
            if (!active[j])
              continue;
            const auto sl = slip_of(j, s.displacement);
            s.slip[j]     = {{sl[0] / op.D[j], sl[1] / op.D[j]}};
            s.status[j]   = model == FrictionModel::frictionless ? 1 :
                            coulomb() && stick[j]                ? 1 :
                                                                   2;
            s.normal_force += op.D[j] * s.pressure[j];
            s.contact_area += op.D[j];
            for (unsigned int k = 0; k < 2; ++k)
              friction += op.D[j] * s.tangential_traction[j][k] * frame[j][k];
            // forces on both bodies: normal and tangential
            for (const auto &[d, v] : row(op, j, op.normals[j]))
              s.contact_force[d] += s.pressure[j] * v;
            for (unsigned int k = 0; k < 2; ++k)
              for (const auto &[d, v] : slip_row(j, k))
                s.contact_force[d] += s.tangential_traction[j][k] * v;
          }
        s.tangential_force = friction.norm();
        s.nodal_pressure   = op.nodal_pressure(s.pressure);
      }

      void
      ActiveSet::advance()
      {
        active = next;
        stick  = next_stick;
        dir    = next_dir;
        curl   = next_curl;
      }
    } // namespace

    ContactSolution
    solve_static_contact(const ContactStiffness          &K,
                         const Vector<double>            &f,
                         const AffineConstraints<double> &constraints,
                         const MortarOperators           &op,
                         const ContactSettings           &settings,
                         std::ostream                    *log)
    {
      if (settings.friction_coefficient < 0.)
        throw std::runtime_error(
          "contact: the friction coefficient must not be negative (got " +
          std::to_string(settings.friction_coefficient) + ")");
      ActiveSet       sets(K, f, constraints, op, settings);
      ContactSolution s;
      s.displacement.reinit(K.size());
      s.pressure.reinit(op.n_slave());
      s.tangential_traction.assign(op.n_slave(), {{0., 0.}});
      const bool coulomb = sets.coulomb();
      for (unsigned int it = 0; it < settings.max_iterations; ++it)
        {
          const std::vector<unsigned int> A = sets.solve_linearised(it, s);
          const unsigned int              n_stick = sets.n_stick(A);
          const Vector<double>            g = op.weighted_gaps(s.displacement);
          double                          turn = 0.;
          const ContactIteration          info = sets.update_sets(s, g, turn);
          const double                    slip_residual = info.slip_residual;
          s.history.push_back(info);
          if (log)
            *log << "  active-set iteration " << std::setw(2) << it + 1 << ": "
                 << A.size() << " active ("
                 << (coulomb ? std::to_string(n_stick) + " stick" :
                               std::string("-"))
                 << "), " << info.changed << " change set, largest penetration "
                 << std::setprecision(3) << info.penetration
                 << " m, largest tension " << info.tension << " Pa"
                 << (coulomb ?
                       ", slip residual " +
                         [&] {
                           std::ostringstream o;
                           o << std::setprecision(3) << slip_residual;
                           return o.str();
                         }() +
                         ", slip directions turned by " + std::to_string(turn) :
                       std::string())
                 << std::endl;
          if (info.changed == 0 && slip_residual < 1e-10)
            {
              sets.finish(s, g);
              return s;
            }
          sets.advance();
        }
      std::ostringstream sizes;
      for (const auto &h : s.history)
        sizes << (sizes.tellp() > 0 ? ", " : "") << h.active;
      throw std::runtime_error("contact: the active set did not settle in " +
                               std::to_string(settings.max_iterations) +
                               " iterations (active-set sizes " + sizes.str() +
                               "); nothing was written");
    }

    ContactSolution
    solve_contact_load_steps(const ContactStiffness          &K,
                             const Vector<double>            &f_start,
                             const Vector<double>            &f_end,
                             const ContactSolution           &start,
                             const AffineConstraints<double> &constraints,
                             const MortarOperators           &op,
                             ContactSettings                  settings,
                             const unsigned int               n_steps,
                             const unsigned int               max_cuts,
                             std::ostream                    *log)
    {
      ContactSolution               state   = start;
      const double                  nominal = 1. / std::max(1u, n_steps);
      double                        done = 0., step = nominal;
      unsigned int                  cuts = 0;
      std::vector<ContactIteration> history;
      while (done < 1. - 1e-12)
        {
          const double   target = std::min(1., done + step);
          Vector<double> f(f_start);
          f.sadd(1. - target, target, f_end);
          settings.previous_displacement = state.displacement;
          settings.initial_status        = state.status;
          settings.initial_traction      = state.tangential_traction;
          try
            {
              ContactSolution next =
                solve_static_contact(K, f, constraints, op, settings, log);
              history.insert(history.end(),
                             next.history.begin(),
                             next.history.end());
              state = std::move(next);
              done  = target;
              // after a cut, grow back towards the nominal step
              step = std::min(nominal, 2. * step);
              cuts = 0;
              if (log)
                *log << "  load factor " << done << " converged" << std::endl;
            }
          catch (const std::exception &e)
            {
              if (++cuts > max_cuts)
                throw std::runtime_error(
                  "contact: load stepping gave up at load factor " +
                  std::to_string(done) + " after " + std::to_string(max_cuts) +
                  " cuts (last step " + std::to_string(step) +
                  "); last error: " + e.what());
              step /= 2.;
              if (log)
                *log << "  step cut to " << step << " (" << e.what() << ")"
                     << std::endl;
            }
        }
      state.history = history;
      return state;
    }
  } // namespace contact
} // namespace squeal
