// Stiffness tensors of anisotropic linear elasticity: built from the
// engineering constants a user knows (moduli, Poisson ratios, shear moduli
// in a material frame) by inverting the compliance, and rotated into the
// global frame.

#include <deal.II/lac/full_matrix.h>

#include <squeal/scene/material_law.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace squeal
{
  namespace scene
  {
    using namespace dealii;

    SymmetricTensor<4, 3>
    isotropic_stiffness(const double E, const double nu)
    {
      if (!(E > 0.) || !(nu > -1. && nu < 0.5))
        throw std::runtime_error(
          "an isotropic material needs E > 0 and -1 < nu < 0.5 (got E = " +
          std::to_string(E) + " Pa, nu = " + std::to_string(nu) + ")");
      const double          lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
      const double          mu     = E / (2 * (1 + nu));
      SymmetricTensor<4, 3> C;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          C[i][i][j][j] = lambda + (i == j ? 2 * mu : 0.);
      C[1][2][1][2] = C[0][2][0][2] = C[0][1][0][1] = mu;
      return C;
    }

    SymmetricTensor<4, 3>
    orthotropic_stiffness(const OrthotropicConstants &c)
    {
      const std::pair<const char *, double> positive[] = {{"E1", c.E1},
                                                          {"E2", c.E2},
                                                          {"E3", c.E3},
                                                          {"G12", c.G12},
                                                          {"G13", c.G13},
                                                          {"G23", c.G23}};
      for (const auto &[name, value] : positive)
        if (!(value > 0.) || !std::isfinite(value))
          throw std::runtime_error(std::string("orthotropic material: ") +
                                   name +
                                   " must be a positive modulus in Pa (got " +
                                   std::to_string(value) + ")");
      FullMatrix<double> S(3, 3);
      S(0, 0) = 1. / c.E1;
      S(1, 1) = 1. / c.E2;
      S(2, 2) = 1. / c.E3;
      S(0, 1) = S(1, 0) = -c.nu12 / c.E1;
      S(0, 2) = S(2, 0) = -c.nu13 / c.E1;
      S(1, 2) = S(2, 1) = -c.nu23 / c.E2;
      // positive definite: the leading minors of S (the shear part is)
      const double m2 = S(0, 0) * S(1, 1) - S(0, 1) * S(0, 1);
      if (!(m2 > 0.) || !(S.determinant() > 0.))
        throw std::runtime_error(
          "orthotropic material: the Poisson ratios nu12 = " +
          std::to_string(c.nu12) + ", nu13 = " + std::to_string(c.nu13) +
          ", nu23 = " + std::to_string(c.nu23) +
          " make the compliance indefinite (each |nu_ij| < sqrt(E_i / E_j) "
          "and 1 - nu12 nu21 - nu23 nu32 - nu13 nu31 - 2 nu21 nu32 nu13 > 0 "
          "are needed)");
      FullMatrix<double> C3(3, 3);
      C3.invert(S);
      SymmetricTensor<4, 3> C;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          C[i][i][j][j] = C3(i, j);
      C[1][2][1][2] = c.G23;
      C[0][2][0][2] = c.G13;
      C[0][1][0][1] = c.G12;
      return C;
    }

    SymmetricTensor<4, 3>
    transversely_isotropic_stiffness(const double E_p,
                                     const double nu_p,
                                     const double E_t,
                                     const double nu_pt,
                                     const double G_t)
    {
      return orthotropic_stiffness(
        {E_p, E_p, E_t, nu_p, nu_pt, nu_pt, E_p / (2 * (1 + nu_p)), G_t, G_t});
    }

    SymmetricTensor<4, 3>
    rotate_stiffness(const SymmetricTensor<4, 3> &C, const Tensor<2, 3> &R)
    {
      // rotate the full tensor, then keep its (exactly symmetric) entries
      Tensor<4, 3> full;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = 0; l < 3; ++l)
              {
                double v = 0.;
                for (unsigned int a = 0; a < 3; ++a)
                  for (unsigned int b = 0; b < 3; ++b)
                    for (unsigned int c = 0; c < 3; ++c)
                      for (unsigned int d = 0; d < 3; ++d)
                        v +=
                          R[i][a] * R[j][b] * R[k][c] * R[l][d] * C[a][b][c][d];
                full[i][j][k][l] = v;
              }
      SymmetricTensor<4, 3> out;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = k; l < 3; ++l)
              out[i][j][k][l] = full[i][j][k][l];
      return out;
    }
  } // namespace scene
} // namespace squeal
