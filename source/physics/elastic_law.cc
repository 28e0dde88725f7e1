// Cell stiffness and mass of linear elastic laws, as products of the
// scalar basis blocks.

#include <deal.II/lac/full_matrix.h>

#include <squeal/physics/elastic_law.h>
#include <squeal/physics/structural_model.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace squeal
{
  namespace physics
  {
    using namespace dealii;

    namespace
    {
      // The scalar basis of an FE_Q^3 system on the cell FE_VALUES was last
      // reinit'ed on: G[d](q, a) = d N_a / d x_d at quadrature point q, N(q,
      // a) = N_a, w(q) = JxW, and for each system DoF i its component and
      // scalar index (FESystem's numbering). The cell matrices below are
      // products of these blocks (BLAS-3 through Eigen) instead of loops
      // over every pair of vector DoFs and quadrature point.
      struct ScalarBasis
      {
        std::array<Eigen::MatrixXd, 3> G;
        Eigen::MatrixXd                N;
        Eigen::VectorXd                w;
        std::vector<unsigned int>      component, index;
      };

      ScalarBasis
      scalar_basis(const FEValues<3> &fe_values, const bool values)
      {
        const FiniteElement<3> &fe = fe_values.get_fe();
        if (fe.n_base_elements() != 1 || fe.n_components() != 3)
          throw std::logic_error(
            "cell elasticity: the element must be one scalar element "
            "repeated for the three displacement components");
        const unsigned int n_q = fe_values.n_quadrature_points,
                           n_s = fe.base_element(0).n_dofs_per_cell();
        ScalarBasis b;
        for (auto &g : b.G)
          g.resize(n_q, n_s);
        if (values)
          b.N.resize(n_q, n_s);
        b.w.resize(n_q);
        for (unsigned int q = 0; q < n_q; ++q)
          b.w[q] = fe_values.JxW(q);
        for (unsigned int a = 0; a < n_s; ++a)
          {
            const unsigned int i = fe.component_to_system_index(0, a);
            for (unsigned int q = 0; q < n_q; ++q)
              {
                const Tensor<1, 3> &g = fe_values.shape_grad(i, q);
                for (unsigned int d = 0; d < 3; ++d)
                  b.G[d](q, a) = g[d];
                if (values)
                  b.N(q, a) = fe_values.shape_value(i, q);
              }
          }
        const unsigned int n = fe.n_dofs_per_cell();
        b.component.resize(n);
        b.index.resize(n);
        for (unsigned int i = 0; i < n; ++i)
          {
            const auto ci  = fe.system_to_component_index(i);
            b.component[i] = ci.first;
            b.index[i]     = ci.second;
          }
        return b;
      }

      // cell(i, j) += blocks[c_i][c_j](a_i, a_j)
      void
      scatter(const ScalarBasis                                   &b,
              const std::array<std::array<Eigen::MatrixXd, 3>, 3> &blocks,
              FullMatrix<double>                                  &cell)
      {
        const unsigned int n = b.component.size();
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            cell(i, j) +=
              blocks[b.component[i]][b.component[j]](b.index[i], b.index[j]);
      }
    } // namespace

    void
    add_cell_stiffness(const FEValues<3>                        &fe_values,
                       const std::vector<SymmetricTensor<4, 3>> &C,
                       FullMatrix<double>                       &cell_k)
    {
      // K(c a, e b) = sum_q w_q sum_{d,f} C_cdef(q) dN_a/dx_d dN_b/dx_f
      //             = sum_d G_d^T Y_cde,  Y_cde = sum_f diag(w C_cdef) G_f
      const ScalarBasis  b   = scalar_basis(fe_values, false);
      const unsigned int n_q = b.w.size(), n_s = b.G[0].cols();
      if (C.size() != 1 && C.size() != n_q)
        throw std::logic_error("cell stiffness: one law or one per "
                               "quadrature point");
      Eigen::MatrixXd G(3 * n_q, n_s), Y(3 * n_q, n_s);
      for (unsigned int d = 0; d < 3; ++d)
        G.middleRows(d * n_q, n_q) = b.G[d];
      std::array<std::array<Eigen::MatrixXd, 3>, 3> blocks;
      Eigen::VectorXd                               weight(n_q);
      for (unsigned int c = 0; c < 3; ++c)
        for (unsigned int e = 0; e < 3; ++e)
          {
            Y.setZero();
            for (unsigned int d = 0; d < 3; ++d)
              for (unsigned int f = 0; f < 3; ++f)
                {
                  for (unsigned int q = 0; q < n_q; ++q)
                    weight[q] = b.w[q] * C[C.size() == 1 ? 0 : q][c][d][e][f];
                  Y.middleRows(d * n_q, n_q) += weight.asDiagonal() * b.G[f];
                }
            blocks[c][e].noalias() = G.transpose() * Y;
          }
      scatter(b, blocks, cell_k);
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

    void
    add_cell_elasticity(const FEValues<3>  &fe_values,
                        const double        lambda,
                        const double        mu,
                        const double        density,
                        FullMatrix<double> &cell_k,
                        FullMatrix<double> &cell_m)
    {
      // S_df = G_d^T diag(w) G_f; K(c a, e b) = lambda S_ce + mu S_ec
      // + delta_ce mu sum_d S_dd; M(c a, e b) = delta_ce rho N^T diag(w) N
      const ScalarBasis              b = scalar_basis(fe_values, true);
      std::array<Eigen::MatrixXd, 3> WG;
      std::array<std::array<Eigen::MatrixXd, 3>, 3> S, blocks;
      for (unsigned int f = 0; f < 3; ++f)
        WG[f] = b.w.asDiagonal() * b.G[f];
      for (unsigned int d = 0; d < 3; ++d)
        for (unsigned int f = 0; f < 3; ++f)
          S[d][f].noalias() = b.G[d].transpose() * WG[f];
      const Eigen::MatrixXd laplace = S[0][0] + S[1][1] + S[2][2];
      for (unsigned int c = 0; c < 3; ++c)
        for (unsigned int e = 0; e < 3; ++e)
          {
            blocks[c][e] = lambda * S[c][e] + mu * S[e][c];
            if (c == e)
              blocks[c][e] += mu * laplace;
          }
      scatter(b, blocks, cell_k);
      const Eigen::MatrixXd mass =
        density * (b.N.transpose() * b.w.asDiagonal() * b.N);
      const Eigen::MatrixXd zero =
        Eigen::MatrixXd::Zero(mass.rows(), mass.cols());
      for (unsigned int c = 0; c < 3; ++c)
        for (unsigned int e = 0; e < 3; ++e)
          blocks[c][e] = c == e ? mass : zero;
      scatter(b, blocks, cell_m);
    }
  } // namespace physics
} // namespace squeal
