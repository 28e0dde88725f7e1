#ifndef squeal_base_lapack_h
#define squeal_base_lapack_h

/**
 * @file
 * The LAPACK routines squeal calls directly, declared once for the library
 * and the tests (deal.II's lapack_templates.h conflicts with Eigen's BLAS
 * declarations in the same translation unit).
 */

extern "C"
{
  /**
   * LAPACK's dgeev: the eigenvalues (wr + i wi) and optionally the left
   * and right eigenvectors of a general real n x n matrix @p a (column
   * major, leading dimension @p lda; overwritten). @p lwork = -1 asks for
   * the optimal workspace size in work[0]. @p info: 0 on success, -i if
   * argument i was illegal, > 0 if the QR algorithm failed (LAPACK Users'
   * Guide, 3rd ed., SIAM 1999).
   */
  void
  dgeev_(const char *jobvl,
         const char *jobvr,
         const int  *n,
         double     *a,
         const int  *lda,
         double     *wr,
         double     *wi,
         double     *vl,
         const int  *ldvl,
         double     *vr,
         const int  *ldvr,
         double     *work,
         const int  *lwork,
         int        *info);
}

#endif
