// Matrix-free stiffness product of linear elasticity (see
// elasticity_operator.h): at each quadrature point the stress of the
// symmetric gradient, sigma = 2 mu eps + lambda tr(eps) I (isotropic) or
// C : eps (anisotropic), is tested against the symmetric gradients of the
// shape functions; the springs' few entries are added afterwards.

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/matrix_free/fe_evaluation.h>

#include <squeal/transient/elasticity_operator.h>

#include <algorithm>
#include <stdexcept>

namespace squeal
{
  namespace transient
  {
    using namespace dealii;

    ElasticityOperator::ElasticityOperator(
      const DoFHandler<3>             &dof_handler,
      const Mapping<3>                &mapping,
      const AffineConstraints<double> &constraints,
      const std::function<std::pair<double, double>(types::material_id)> &lame,
      const std::vector<SpringEntry> &spring_entries,
      const TensorOf                 &tensor)
      : degree(dof_handler.get_fe().degree)
    {
      if (degree < 1 || degree > 3)
        throw std::runtime_error(
          "the matrix-free stiffness product supports degrees 1-3 (got " +
          std::to_string(degree) + ")");
      typename MatrixFree<3, double>::AdditionalData additional;
      additional.mapping_update_flags =
        update_gradients | update_JxW_values | update_quadrature_points;
      data.reinit(
        mapping, dof_handler, constraints, QGauss<1>(degree + 1), additional);
      data.initialize_dof_vector(in);
      data.initialize_dof_vector(out);
      const unsigned int n_batches = data.n_cell_batches();
      cell_lame.resize(n_batches);
      cell_tensor.resize(n_batches);
      // the quadrature points in MatrixFree's order (the tensor product of
      // the 1D Gauss rule, x fastest: QGauss<3>'s)
      const QGauss<3>    quadrature(degree + 1);
      const unsigned int n_q = quadrature.size();
      FEValues<3>        points(mapping,
                         dof_handler.get_fe(),
                         quadrature,
                         update_quadrature_points);
      for (unsigned int b = 0; b < n_batches; ++b)
        {
          const unsigned int lanes = data.n_active_entries_per_cell_batch(b);
          bool               anisotropic = false;
          for (unsigned int v = 0; v < lanes; ++v)
            {
              const auto cell        = data.get_cell_iterator(b, v);
              const auto [l, m]      = lame(cell->material_id());
              cell_lame[b].first[v]  = l;
              cell_lame[b].second[v] = m;
              if (tensor && tensor(cell->material_id(), cell->center()))
                anisotropic = true;
            }
          // a batch with an anisotropic lane: every lane's C at every
          // quadrature point
          if (!anisotropic)
            continue;
          cell_tensor[b].resize(n_q);
          for (unsigned int v = 0; v < lanes; ++v)
            {
              const auto cell = data.get_cell_iterator(b, v);
              points.reinit(cell);
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  std::optional<SymmetricTensor<4, 3>> C =
                    tensor(cell->material_id(), points.quadrature_point(q));
                  if (!C)
                    {
                      const auto [l, m] = lame(cell->material_id());
                      C                 = 2. * m * identity_tensor<3>() +
                          l * outer_product(unit_symmetric_tensor<3>(),
                                            unit_symmetric_tensor<3>());
                    }
                  for (unsigned int i = 0; i < 3; ++i)
                    for (unsigned int j = i; j < 3; ++j)
                      for (unsigned int k = 0; k < 3; ++k)
                        for (unsigned int l = k; l < 3; ++l)
                          cell_tensor[b][q][i][j][k][l][v] = (*C)[i][j][k][l];
                }
            }
        }

      // The springs: this rank's rows, and every column of every rank.
      const MPI_Comm                       comm = in.get_mpi_communicator();
      std::vector<types::global_dof_index> columns;
      for (const SpringEntry &e : spring_entries)
        if (!constraints.is_constrained(e.row))
          columns.push_back(e.column);
      std::vector<types::global_dof_index> all_columns;
      for (const auto &rank_columns : Utilities::MPI::all_gather(comm, columns))
        all_columns.insert(all_columns.end(),
                           rank_columns.begin(),
                           rank_columns.end());
      std::sort(all_columns.begin(), all_columns.end());
      all_columns.erase(std::unique(all_columns.begin(), all_columns.end()),
                        all_columns.end());
      const auto &part = *in.get_partitioner();
      for (const auto c : all_columns)
        spring_column_local.push_back(part.in_local_range(c) ?
                                        part.global_to_local(c) :
                                        numbers::invalid_unsigned_int);
      for (const SpringEntry &e : spring_entries)
        if (!constraints.is_constrained(e.row))
          springs.push_back(
            {part.global_to_local(e.row),
             static_cast<unsigned int>(std::lower_bound(all_columns.begin(),
                                                        all_columns.end(),
                                                        e.column) -
                                       all_columns.begin()),
             e.k});
      spring_values.resize(all_columns.size());
    }

    template <int p>
    void
    ElasticityOperator::apply(VectorType &dst, const VectorType &src) const
    {
      using Worker =
        std::function<void(const MatrixFree<3, double> &,
                           VectorType &,
                           const VectorType &,
                           const std::pair<unsigned int, unsigned int> &)>;
      const Worker worker =
        [this](const MatrixFree<3, double>                 &mf,
               VectorType                                  &out,
               const VectorType                            &in,
               const std::pair<unsigned int, unsigned int> &range) {
          FEEvaluation<3, p, p + 1, 3, double> phi(mf);
          for (unsigned int b = range.first; b < range.second; ++b)
            {
              phi.reinit(b);
              phi.gather_evaluate(in, EvaluationFlags::gradients);
              if (!cell_tensor[b].empty())
                {
                  for (const unsigned int q : phi.quadrature_point_indices())
                    phi.submit_symmetric_gradient(
                      cell_tensor[b][q] * phi.get_symmetric_gradient(q), q);
                  phi.integrate_scatter(EvaluationFlags::gradients, out);
                  continue;
                }
              const auto &[lambda, mu] = cell_lame[b];
              for (const unsigned int q : phi.quadrature_point_indices())
                {
                  const auto eps   = phi.get_symmetric_gradient(q);
                  auto       sigma = 2. * mu * eps;
                  const auto tr    = trace(eps);
                  for (unsigned int d = 0; d < 3; ++d)
                    sigma[d][d] += lambda * tr;
                  phi.submit_symmetric_gradient(sigma, q);
                }
              phi.integrate_scatter(EvaluationFlags::gradients, out);
            }
        };
      data.cell_loop(worker, dst, src, true);
    }

    void
    ElasticityOperator::vmult(VectorType &dst, const VectorType &src) const
    {
      in.copy_locally_owned_data_from(src);
      apply_buffers();
      dst.copy_locally_owned_data_from(out);
    }

    void
    ElasticityOperator::apply_buffers() const
    {
      switch (degree)
        {
          case 1:
            apply<1>(out, in);
            break;
          case 2:
            apply<2>(out, in);
            break;
          default:
            apply<3>(out, in);
        }
      // the springs: the values at their columns from the owning ranks
      if (!spring_values.empty())
        {
          for (unsigned int c = 0; c < spring_values.size(); ++c)
            spring_values[c] =
              spring_column_local[c] == numbers::invalid_unsigned_int ?
                0. :
                in.local_element(spring_column_local[c]);
          if (Utilities::MPI::n_mpi_processes(in.get_mpi_communicator()) > 1)
            Utilities::MPI::sum(spring_values,
                                in.get_mpi_communicator(),
                                spring_values);
          for (const LocalSpring &e : springs)
            out.local_element(e.row) += e.k * spring_values[e.column];
        }
    }

  } // namespace transient
} // namespace squeal
