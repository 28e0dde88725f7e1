// The cell stiffness of an anisotropic linear elastic law.

#include <deal.II/lac/full_matrix.h>

#include <squeal/physics/elastic_law.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace squeal
{
  namespace physics
  {
    using namespace dealii;

    void
    add_cell_stiffness(const FEValues<3>                        &fe_values,
                       const std::vector<SymmetricTensor<4, 3>> &C,
                       FullMatrix<double>                       &cell_k)
    {
      const FiniteElement<3>            &fe = fe_values.get_fe();
      const unsigned int                 n  = fe.n_dofs_per_cell();
      std::vector<SymmetricTensor<2, 3>> eps(n), C_eps(n);
      for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
        {
          for (unsigned int i = 0; i < n; ++i)
            {
              const unsigned int    c = fe.system_to_component_index(i).first;
              const Tensor<1, 3>    g = fe_values.shape_grad(i, q);
              SymmetricTensor<2, 3> e;
              for (unsigned int d = 0; d < 3; ++d)
                e[c][d] += (c == d ? 1. : 0.5) * g[d];
              eps[i]   = e;
              C_eps[i] = C[C.size() == 1 ? 0 : q] * e;
            }
          const double JxW = fe_values.JxW(q);
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              cell_k(i, j) += (eps[i] * C_eps[j]) * JxW;
        }
    }

    void
    add_cell_stiffness(const FEValues<3>           &fe_values,
                       const SymmetricTensor<4, 3> &C,
                       FullMatrix<double>          &cell_k)
    {
      add_cell_stiffness(fe_values,
                         std::vector<SymmetricTensor<4, 3>>{C},
                         cell_k);
    }
  } // namespace physics
} // namespace squeal
