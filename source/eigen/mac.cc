// The complex MAC of distributed mode shapes (mac.h): the Hermitian product
// from four real dot products.

#include <squeal/eigen/mac.h>

namespace squeal
{
  namespace eigen
  {
    double
    complex_mac(const physics::PETScVector &re_a,
                const physics::PETScVector &im_a,
                const physics::PETScVector &re_b,
                const physics::PETScVector &im_b)
    {
      // b^H a = (b_r - i b_i)^T (a_r + i a_i)
      const std::complex<double> ab(re_b * re_a + im_b * im_a,
                                    re_b * im_a - im_b * re_a);
      return complex_mac(ab,
                         re_a.norm_sqr() + im_a.norm_sqr(),
                         re_b.norm_sqr() + im_b.norm_sqr());
    }
  } // namespace eigen
} // namespace squeal
