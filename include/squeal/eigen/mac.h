#ifndef squeal_eigen_mac_h
#define squeal_eigen_mac_h

/**
 * @file
 * The complex modal assurance criterion (MAC) of two mode shapes,
 *   MAC(a, b) = |b^H a|^2 / ((a^H a) (b^H b)),
 * in [0, 1]: 1 for shapes equal up to a complex factor, 0 for orthogonal
 * ones (Allemang & Brown, Proc. 1st IMAC, 1982, with the Hermitian product
 * of complex shapes). Every comparison of mode shapes in squeal (mode
 * tracking over a sweep, partners between meshes and degrees) uses it.
 */

#include <squeal/physics/structural_model.h>

#include <complex>
#include <vector>

namespace squeal
{
  namespace eigen
  {
    /**
     * The MAC from its three sums: @p ab = b^H a, @p aa = a^H a,
     * @p bb = b^H b; 0 when either shape is zero.
     */
    inline double
    complex_mac(const std::complex<double> ab, const double aa, const double bb)
    {
      return aa > 0. && bb > 0. ? std::norm(ab) / (aa * bb) : 0.;
    }

    /**
     * The MAC of two complex shapes of equal length given entry by entry
     * (std::vector<std::complex<double>>, Eigen::VectorXcd, ...: anything
     * with size() and operator[] giving std::complex<double>); 0 when
     * either is zero.
     */
    template <typename VectorA, typename VectorB>
    double
    complex_mac(const VectorA &a, const VectorB &b)
    {
      std::complex<double> ab = 0.;
      double               aa = 0., bb = 0.;
      for (std::size_t i = 0; i < std::size_t(a.size()); ++i)
        {
          ab += std::conj(b[i]) * a[i];
          aa += std::norm(a[i]);
          bb += std::norm(b[i]);
        }
      return complex_mac(ab, aa, bb);
    }

    /**
     * The repeated eigenvalues among @p pairs (anything indexable whose
     * entries have a std::complex<double> member lambda [1/s]): entry k of
     * the result is the index of the first pair j <= k with
     * |lambda_j - lambda_k| <= 1e-6 |lambda_k|, k itself if none. The two
     * members of a disc's doublet share an entry; the eigensolver returns
     * any independent pair of their space, so whatever compares or weighs
     * their shapes one by one must treat them as one space.
     */
    template <typename Pairs>
    std::vector<std::size_t>
    repeated_eigenvalues(const Pairs &pairs)
    {
      std::vector<std::size_t> first(pairs.size());
      for (std::size_t k = 0; k < first.size(); ++k)
        {
          first[k] = k;
          for (std::size_t j = 0; j < k; ++j)
            if (std::abs(pairs[j].lambda - pairs[k].lambda) <=
                1e-6 * std::abs(pairs[k].lambda))
              {
                first[k] = first[j];
                break;
              }
        }
      return first;
    }

    /**
     * The MAC of two complex shapes held as real and imaginary parts in
     * distributed PETSc vectors (n_dofs each). Collective over the vectors'
     * communicator.
     */
    double
    complex_mac(const physics::PETScVector &re_a,
                const physics::PETScVector &im_a,
                const physics::PETScVector &re_b,
                const physics::PETScVector &im_b);
  } // namespace eigen
} // namespace squeal

#endif
