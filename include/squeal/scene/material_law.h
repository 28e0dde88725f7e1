#ifndef squeal_scene_material_law_h
#define squeal_scene_material_law_h

/**
 * @file
 * The linear elastic laws of a scene's bodies as fourth-order stiffness
 * tensors C (sigma = C : eps, Pa): isotropic, transversely isotropic and
 * orthotropic, given in a material frame and rotated into the global one.
 * Friction materials are strongly anisotropic (pressed in one direction:
 * stiffer in the plane of the pad than through its thickness), which moves the
 * pad modes and with them the mode lock-ins of a brake.
 *
 * Orthotropic compliance in the material frame (Voigt order 11, 22, 33,
 * 23, 13, 12, engineering shear strains; e.g. R. M. Jones, Mechanics of
 * Composite Materials, 2nd ed., 1999, eq. 2.49):
 *   S = [[1/E1, -nu12/E1, -nu13/E1], [., 1/E2, -nu23/E2], [., ., 1/E3]]
 *       (symmetric), S44 = 1/G23, S55 = 1/G13, S66 = 1/G12,
 * nu_ij the contraction in j under a stress along i; C = S^-1.
 */

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

namespace squeal
{
  namespace scene
  {
    /** Orthotropic engineering constants in the material frame (axes
     * 1, 2, 3). Moduli in Pa, Poisson ratios dimensionless. */
    struct OrthotropicConstants
    {
      double E1;   ///< Young's modulus along axis 1 [Pa]
      double E2;   ///< along axis 2 [Pa]
      double E3;   ///< along axis 3 [Pa]
      double nu12; ///< contraction along 2 under stress along 1 [-]
      double nu13; ///< contraction along 3 under stress along 1 [-]
      double nu23; ///< contraction along 3 under stress along 2 [-]
      double G12;  ///< shear modulus in the 1-2 plane [Pa]
      double G13;  ///< shear modulus in the 1-3 plane [Pa]
      double G23;  ///< shear modulus in the 2-3 plane [Pa]
    };

    /**
     * The isotropic stiffness tensor of Young's modulus @p E [Pa] and
     * Poisson's ratio @p nu: C = lambda I x I + 2 mu I_sym.
     * @throws std::runtime_error unless E > 0 and -1 < nu < 0.5.
     */
    dealii::SymmetricTensor<4, 3>
    isotropic_stiffness(double E, double nu);

    /**
     * The orthotropic stiffness tensor of @p c in the material frame (the
     * inverse of the compliance of the file comment).
     * @throws std::runtime_error naming the constant if a modulus is not
     * positive, or if the compliance is not positive definite (the Poisson
     * ratios violate |nu_ij| < sqrt(E_i / E_j) or their joint bound).
     */
    dealii::SymmetricTensor<4, 3>
    orthotropic_stiffness(const OrthotropicConstants &c);

    /**
     * A transversely isotropic law with the material axis 3 as its axis of
     * symmetry: in-plane modulus @p E_p and Poisson ratio @p nu_p, axial
     * modulus @p E_t, @p nu_pt the contraction along the axis under
     * in-plane stress, @p G_t the transverse shear modulus (planes
     * containing the axis) [Pa]. The orthotropic law with E1 = E2 = E_p,
     * E3 = E_t, nu12 = nu_p, nu13 = nu23 = nu_pt, G12 = E_p / (2 (1 + nu_p)),
     * G13 = G23 = G_t. @throws as orthotropic_stiffness().
     */
    dealii::SymmetricTensor<4, 3>
    transversely_isotropic_stiffness(double E_p,
                                     double nu_p,
                                     double E_t,
                                     double nu_pt,
                                     double G_t);

    /**
     * C rotated into the global frame: C'_ijkl = R_ia R_jb R_kc R_ld C_abcd,
     * where the columns of @p R are the material axes 1, 2, 3 written in
     * global coordinates (R orthonormal; for a cylindrical frame, evaluate
     * at each point with the radial, tangential and axial unit vectors).
     */
    dealii::SymmetricTensor<4, 3>
    rotate_stiffness(const dealii::SymmetricTensor<4, 3> &C,
                     const dealii::Tensor<2, 3>          &R);

  } // namespace scene
} // namespace squeal

#endif
