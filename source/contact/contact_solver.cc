// Static contact on dual mortar operators by the primal-dual active-set
// method (see contact_solver.h). The structure is linear, so every
// iteration is one solve of the augmented (saddle-point) system for the
// displacements and the pressures of the active nodes; the active set is
// then updated from the complementarity function, and the iteration stops
// when it no longer changes. Because the multipliers are dual, the pressure
// of a node is its own unknown (no coupling through a mass matrix), which
// keeps the active-set update node-wise.

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <squeal/contact/contact_solver.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

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
    } // namespace

    ContactSolution
    solve_static_contact(const SparseMatrix<double>      &K,
                         const Vector<double>            &f,
                         const AffineConstraints<double> &constraints,
                         const MortarOperators           &op,
                         const ContactSettings           &settings,
                         std::ostream                    *log)
    {
      const unsigned int n = K.m(), n_s = op.n_slave();
      const double       mu = settings.friction_coefficient;
      if (mu < 0.)
        throw std::runtime_error(
          "contact: the friction coefficient must not be negative (got " +
          std::to_string(mu) + ")");

      // Sliding directions and the complementarity constants c_j = K_nn /
      // D_jj^2 (pressure per weighted gap of the node's own stiffness).
      std::vector<Tensor<1, 3>> tau(n_s);
      std::vector<double>       c(n_s);
      for (unsigned int j = 0; j < n_s; ++j)
        {
          Tensor<1, 3> t = settings.sliding_direction;
          t -= (t * op.normals[j]) * op.normals[j];
          tau[j] = t.norm() > 0. ? t / t.norm() : Tensor<1, 3>();
          double k = 0.;
          for (unsigned int d = 0; d < 3; ++d)
            k += K.diag_element(op.slave_dofs[j][d]) *
                 std::abs(op.normals[j][d]);
          c[j] = k / (op.D[j] * op.D[j]);
        }

      ContactSolution s;
      s.displacement.reinit(n);
      s.pressure.reinit(n_s);
      std::vector<char> active(n_s, 0);
      // Closed at the start: nodes whose weighted gap is zero to rounding
      // (relative to the node's length scale sqrt(D_jj)).
      for (unsigned int j = 0; j < n_s; ++j)
        active[j] = std::isfinite(op.gap0[j]) &&
                    op.gap0[j] <= 1e-10 * op.D[j] * std::sqrt(op.D[j]);

      for (unsigned int it = 0; it < settings.max_iterations; ++it)
        {
          std::vector<unsigned int> A;
          for (unsigned int j = 0; j < n_s; ++j)
            if (active[j])
              A.push_back(j);
          // The augmented system [K, -(B + mu G)_A^T; B_A, 0].
          const unsigned int     N = n + A.size();
          DynamicSparsityPattern dsp(N, N);
          for (unsigned int i = 0; i < n; ++i)
            for (auto e = K.begin(i); e != K.end(i); ++e)
              dsp.add(i, e->column());
          std::vector<std::vector<std::pair<types::global_dof_index, double>>>
            b_rows(A.size()), t_rows(A.size());
          for (unsigned int a = 0; a < A.size(); ++a)
            {
              b_rows[a] = row(op, A[a], op.normals[A[a]]);
              if (mu > 0.)
                t_rows[a] = row(op, A[a], tau[A[a]]);
              for (const auto &rows : {&b_rows[a], &t_rows[a]})
                for (const auto &[d, v] : *rows)
                  {
                    dsp.add(n + a, d);
                    dsp.add(d, n + a);
                  }
              dsp.add(n + a, n + a);
            }
          SparsityPattern sp;
          sp.copy_from(dsp);
          SparseMatrix<double> S(sp);
          Vector<double>       rhs(N), x(N);
          for (unsigned int i = 0; i < n; ++i)
            {
              for (auto e = K.begin(i); e != K.end(i); ++e)
                S.set(i, e->column(), e->value());
              rhs[i] = f[i];
            }
          for (unsigned int a = 0; a < A.size(); ++a)
            {
              // the gap row: B_j u = -g0_j
              for (const auto &[d, v] : b_rows[a])
                S.add(n + a, d, v);
              rhs[n + a] = -op.gap0[A[a]];
              // the contact force column, not on constrained rows (their
              // values are fixed by their own rows)
              for (const auto &[d, v] : b_rows[a])
                if (!constraints.is_constrained(d))
                  S.add(d, n + a, -v);
              // friction: the slave is dragged along tau by mu z: the
              // force is mu z (D tau on the slave, -M tau on the master),
              // i.e. -mu (G row) with G as the gap-like row along tau
              for (const auto &[d, v] : t_rows[a])
                if (!constraints.is_constrained(d))
                  S.add(d, n + a, mu * v);
            }
          SparseDirectUMFPACK direct;
          try
            {
              direct.initialize(S);
              direct.vmult(x, rhs);
              // UMFPACK may return garbage for a singular matrix instead of
              // failing: check the residual.
              Vector<double> r(N);
              S.vmult(r, x);
              r -= rhs;
              if (!std::isfinite(x.l2_norm()) ||
                  r.l2_norm() > 1e-6 * std::max(rhs.l2_norm(), 1e-300))
                throw std::runtime_error("singular");
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
          s.pressure = 0.;
          for (unsigned int a = 0; a < A.size(); ++a)
            s.pressure[A[a]] = x[n + a];
          constraints.distribute(s.displacement);

          // The new active set.
          const Vector<double> g = op.weighted_gaps(s.displacement);
          ContactIteration     info;
          std::vector<char>    next(n_s, 0);
          for (unsigned int j = 0; j < n_s; ++j)
            {
              if (!std::isfinite(op.gap0[j]))
                continue;
              next[j] = s.pressure[j] - c[j] * g[j] > 0.;
              info.changed += next[j] != active[j];
              info.active += next[j];
              if (active[j])
                info.tension = std::max(info.tension, -s.pressure[j]);
              else
                info.penetration = std::max(info.penetration, -g[j] / op.D[j]);
            }
          s.history.push_back(info);
          if (log)
            *log << "  active-set iteration " << std::setw(2) << it + 1
                 << ": " << A.size() << " active, " << info.changed
                 << " change set, largest penetration " << std::setprecision(3)
                 << info.penetration << " m, largest tension " << info.tension
                 << " Pa" << std::endl;
          if (info.changed == 0)
            {
              s.gap.reinit(n_s);
              s.status.assign(n_s, 0);
              Tensor<1, 3> friction;
              for (unsigned int j = 0; j < n_s; ++j)
                {
                  s.gap[j] = std::isfinite(op.gap0[j]) ? g[j] / op.D[j] :
                                                         op.gap0[j];
                  if (!active[j])
                    continue;
                  s.status[j] = mu > 0. ? 2 : 1;
                  s.normal_force += op.D[j] * s.pressure[j];
                  s.contact_area += op.D[j];
                  friction += op.D[j] * mu * s.pressure[j] * tau[j];
                }
              s.tangential_force = friction.norm();
              s.nodal_pressure   = op.nodal_pressure(s.pressure);
              s.contact_force.reinit(n);
              for (unsigned int a = 0; a < A.size(); ++a)
                {
                  const double z = s.pressure[A[a]];
                  for (const auto &[d, v] : b_rows[a])
                    s.contact_force[d] += z * v;
                  for (const auto &[d, v] : t_rows[a])
                    s.contact_force[d] -= mu * z * v;
                }
              return s;
            }
          active = next;
        }
      std::ostringstream sizes;
      for (const auto &h : s.history)
        sizes << (sizes.tellp() > 0 ? ", " : "") << h.active;
      throw std::runtime_error(
        "contact: the active set did not settle in " +
        std::to_string(settings.max_iterations) +
        " iterations (active-set sizes " + sizes.str() +
        "); nothing was written");
    }
  } // namespace contact
} // namespace squeal
