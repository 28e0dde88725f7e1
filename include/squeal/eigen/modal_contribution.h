#ifndef squeal_eigen_modal_contribution_h
#define squeal_eigen_modal_contribution_h

/**
 * @file
 * Modal contributions: a complex mode x of the friction-coupled problem
 * written on the real modes phi_k of the frictionless assembly
 * (K_s + K_n) phi_k = omega_k^2 M phi_k, M-orthonormal:
 *
 *   x = sum_k c_k phi_k + remainder,   c_k = phi_k^T M x / ||x||_M,
 *
 * with ||x||_M^2 = x^H M x. The share of phi_k is |c_k|^2; the shares sum
 * to the part of x's kinetic norm that the frictionless modes capture
 * (1 when they span x). An unstable mode carried mostly by two frictionless
 * modes is their mode lock-in (the complex modal contribution coefficients
 * that commercial brake-squeal codes print; modal decomposition as in
 * N.M. Kinkaid, O.M. O'Reilly, P. Papadopoulos, J. Sound Vib. 267 (2003)
 * 105-166, Sec. 5).
 */

#include <deal.II/base/conditional_ostream.h>

#include <squeal/eigen/qep_solver.h>
#include <squeal/parameters/parameters.h>
#include <squeal/physics/structural_model.h>

#include <complex>
#include <memory>
#include <vector>

namespace squeal
{
  namespace eigen
  {
    /** The real modes of the frictionless assembly at one point. */
    struct FrictionlessModes
    {
      std::vector<double>          frequency; ///< f_k [Hz], ascending
      std::vector<PETScVector>     shape;     ///< phi_k, M(p)-orthonormal (n)
      std::shared_ptr<PETScMatrix> M;         ///< M(p) [kg]
    };

    /**
     * Every mode of (K_s(p) + K_n(p), M(p)) up to @p factor times
     * band.f_max (solve_undamped(), symmetric: counted by Sylvester
     * inertia and all found). Collective.
     * @throws std::runtime_error if the eigensolve fails.
     */
    FrictionlessModes
    frictionless_modes(const physics::MatrixParts    &model,
                       const parameters::ScalarPoint &p,
                       const BandOptions             &band,
                       double                         factor,
                       dealii::ConditionalOStream    &pcout);

    /** The contributions of the frictionless modes to one complex mode. */
    struct ModalContributions
    {
      /// c_k for every mode of FrictionlessModes, in its order
      std::vector<std::complex<double>> coefficient;
      /// sum_k |c_k|^2 in [0, 1]: the part of ||x||_M^2 the modes capture
      double captured = 0.;
    };

    /**
     * The contributions c_k = phi_k^T M x / ||x||_M of @p modes to the
     * complex mode @p x (x = re + i im, any scale and phase). Collective.
     * @throws std::logic_error if x is zero.
     */
    ModalContributions
    modal_contributions(const FrictionlessModes &modes, const EigenPair &x);
  } // namespace eigen
} // namespace squeal

#endif
