#ifndef squeal_eigen_sensitivity_h
#define squeal_eigen_sensitivity_h

/**
 * @file
 * Design sensitivities of the complex eigenvalues: d lambda / d p for every
 * eigenvalue of (lambda^2 M + lambda C + K) x = 0 and every named parameter
 * p of the model, from its right eigenvector x and its left eigenvector y
 * (y^T (lambda^2 M + lambda C + K) = 0):
 *
 *   d lambda / d p = - y^T (lambda^2 M_p + lambda C_p + K_p) x
 *                      / y^T (2 lambda M + C) x,
 *
 * with M_p = dM/dp, C_p, K_p (the first-order perturbation of a simple
 * eigenvalue of a matrix polynomial: P. Lancaster, Numer. Math. 6 (1964)
 * 377-387). The matrices are affine in each named
 * parameter (physics::MatrixParts), so the derivatives are exact and cost
 * one product per matrix part and pair. The left eigenvectors are the
 * right ones of the transposed problem, in which only the friction parts
 * K_t change (to K_t^T): the same full solver with the same count and
 * residual guarantee finds them.
 *
 * At mode lock-in (an exceptional point: the two eigenvalues and their
 * vectors coalesce) y^T (2 lambda M + C) x tends to 0 and the derivative
 * is unbounded; EigenvalueSensitivity::condition says how close a pair is.
 */

#include <deal.II/base/conditional_ostream.h>

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/qep_solver.h>
#include <squeal/parameters/parameters.h>
#include <squeal/physics/structural_model.h>

#include <complex>
#include <memory>
#include <string>
#include <vector>

namespace squeal
{
  namespace eigen
  {
    /**
     * The matrix parts of the transposed model: every part of @p model as
     * it is, but the friction parts (Kind::interface_friction) transposed,
     * so that K(p)^T is their combination (M, C and every other stiffness
     * part are symmetric). Owns the transposed copies; @p model must
     * outlive it. Collective.
     */
    class TransposedModel
    {
    public:
      /** @throws std::runtime_error if PETSc cannot transpose a part. */
      explicit TransposedModel(const physics::MatrixParts &model);

      /** The transposed model's parts (same names, kinds and scales). */
      const physics::MatrixParts &
      parts() const
      {
        return transposed;
      }

    private:
      std::vector<std::unique_ptr<PETScMatrix>> copies;
      physics::MatrixParts                      transposed;
    };

    /**
     * The left eigenvectors of the pairs @p right (found by solve_full() on
     * @p model at @p p in @p band): solve_full() on the transposed model in
     * the band widened by 0.1 % at each end, its pairs matched one to one
     * to @p right by optimal assignment on |lambda_i - lambda_j|. Returns
     * one pair per element of @p right, in its order; each returned
     * EigenPair holds y = re + i im with y^T (lambda^2 M + lambda C + K) = 0
     * and the residual of that transposed solve.
     * @throws std::runtime_error if a right eigenvalue has no left partner
     *   within 1e-7 |lambda| (the two solves must find the same spectrum),
     *   or if the transposed solve fails.
     */
    std::vector<EigenPair>
    left_eigenvectors(const physics::MatrixParts    &model,
                      const parameters::ScalarPoint &p,
                      const BandOptions             &band,
                      const std::vector<EigenPair>  &right,
                      dealii::ConditionalOStream    &pcout);

    /**
     * The derivatives d c / d p of every coefficient of @p model's
     * combinations (MatrixParts::Combination: M, C, K, K_s, K_s + K_n and
     * the springs) at @p p, one Combination per parameter of @p names, in
     * their units' inverse (a part's coefficient per unit of p). Exact: each
     * coefficient is affine in every single parameter, so a central
     * difference of MatrixParts::coefficients() with a step of the
     * parameter's size is its derivative.
     * @throws std::runtime_error if a name is not a parameter of @p p, or
     *   if the model holds it fixed (MatrixParts::fixed: build the model
     *   varying it).
     */
    std::vector<physics::MatrixParts::Combination>
    coefficient_slopes(const physics::MatrixParts     &model,
                       const parameters::ScalarPoint  &p,
                       const std::vector<std::string> &names);

    /** The derivatives of one eigenvalue. */
    struct EigenvalueSensitivity
    {
      std::complex<double> lambda; ///< the eigenvalue [1/s]
      /// d lambda / d p_j for each requested parameter p_j [1/s per unit
      /// of p_j]; d Im lambda / d p_j / (2 pi) is the frequency's [Hz per
      /// unit]
      std::vector<std::complex<double>> derivative;
      /**
       * The eigenvalue's condition ||y|| ||(2 lambda M + C) x|| /
       * |y^T (2 lambda M + C) x| >= 1 (Euclidean norms): about 1 for a
       * well separated mode, growing without bound as the pair approaches
       * coalescence (mode lock-in), where the derivatives lose meaning
       * (a simplified form of the condition number of F. Tisseur, Linear
       * Algebra Appl. 309 (2000) 339-361).
       */
      double condition = 1.;
    };

    /**
     * d lambda / d p of every pair right[i] (left eigenvector left[i]) for
     * every parameter of @p names at the point @p p (see the file's
     * description). The derivative of each part's coefficient is exact:
     * a coefficient is affine in every single parameter (a central
     * difference of MatrixParts::coefficients() with a step of the
     * parameter's size). Collective.
     * @throws std::runtime_error if a name is not a parameter of @p p, if
     *   the model holds it fixed (MatrixParts::fixed: build the model
     *   varying it), or if the sizes differ.
     */
    std::vector<EigenvalueSensitivity>
    eigenvalue_sensitivities(const physics::MatrixParts     &model,
                             const parameters::ScalarPoint  &p,
                             const std::vector<std::string> &names,
                             const std::vector<EigenPair>   &right,
                             const std::vector<EigenPair>   &left);
  } // namespace eigen
} // namespace squeal

#endif
