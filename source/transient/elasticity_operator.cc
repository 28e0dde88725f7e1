// Matrix-free stiffness product of linear elasticity (see
// elasticity_operator.h): at each quadrature point the stress
// sigma = 2 mu eps + lambda tr(eps) I of the symmetric gradient is tested
// against the symmetric gradients of the shape functions.

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/matrix_free/fe_evaluation.h>

#include <squeal/transient/elasticity_operator.h>

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
      const Vector<double> &spring_diagonal)
      : springs(spring_diagonal)
      , degree(dof_handler.get_fe().degree)
    {
      if (degree < 1 || degree > 3)
        throw std::runtime_error(
          "the matrix-free stiffness product supports degrees 1-3 (got " +
          std::to_string(degree) + ")");
      typename MatrixFree<3, double>::AdditionalData additional;
      additional.mapping_update_flags = update_gradients | update_JxW_values;
      data.reinit(
        mapping, dof_handler, constraints, QGauss<1>(degree + 1), additional);
      data.initialize_dof_vector(in);
      data.initialize_dof_vector(out);
      cell_lame.resize(data.n_cell_batches());
      for (unsigned int b = 0; b < data.n_cell_batches(); ++b)
        for (unsigned int v = 0; v < data.n_active_entries_per_cell_batch(b);
             ++v)
          {
            const auto [l, m] =
              lame(data.get_cell_iterator(b, v)->material_id());
            cell_lame[b].first[v]  = l;
            cell_lame[b].second[v] = m;
          }
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
      const auto &part = *out.get_partitioner();
      for (unsigned int l = 0; l < part.locally_owned_size(); ++l)
        {
          const auto i = part.local_to_global(l);
          if (springs.size() == part.size())
            out.local_element(l) += springs[i] * in.local_element(l);
          dst.local_element(l) = out.local_element(l);
        }
    }

  } // namespace transient
} // namespace squeal
