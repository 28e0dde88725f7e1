#ifndef squeal_base_memory_estimate_h
#define squeal_base_memory_estimate_h

/**
 * @file
 * The memory a run is about to need, printed before it needs it: what is
 * resident after the set-up plus an estimate of what the analysis still
 * allocates (its sparse factorisation, its eigensolver subspace). The
 * factorisation sizes are calibrated on MUMPS's own figure (INFOG(22)) for
 * the coarse passenger-car brake's shifted stiffness (91 374 DoFs, degree 2,
 * 12.9 million nonzeros; benchmarks/scale/README.md) and scaled with the
 * n^(1/3) growth of the fill per nonzero that nested dissection gives on
 * 3D meshes (George, SIAM J. Numer. Anal. 10 (1973) 345-363).
 */

#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <cstddef>
#include <ostream>
#include <string>

namespace squeal
{
  /**
   * Estimated bytes of MUMPS's factorisation of an n x n sparse matrix
   * with @p nonzeros stored entries (n = @p n_dofs): 48 bytes per nonzero
   * for an LU, 28 for a symmetric LDL^T (@p symmetric), at 91 374 rows,
   * times (n / 91 374)^(1/3) above that size (no smaller below it).
   * Throws nothing.
   */
  double
  factorisation_bytes(std::size_t                     nonzeros,
                      dealii::types::global_dof_index n_dofs,
                      bool                            symmetric);

  /**
   * Prints on @p out (if not null; rank 0's) `Memory: <now> MB in use
   * (<kB> per DoF); estimated peak <peak> MB (<kB> per DoF) with
   * <what>`, where now is the resident memory (VmRSS) summed over the
   * ranks of @p comm, and peak = now + @p extra_bytes (the caller's
   * estimate of what the analysis still allocates, summed over the ranks).
   * Per DoF of @p n_dofs. Collective.
   * @returns the estimated peak [MB].
   * @throws what deal.II's MPI sum throws if the ranks' communicator fails.
   */
  double
  report_memory_estimate(MPI_Comm                        comm,
                         std::ostream                   *out,
                         dealii::types::global_dof_index n_dofs,
                         double                          extra_bytes,
                         const std::string              &what);
} // namespace squeal

#endif
