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
   * Sets how MUMPS keeps its factors for the rest of the process
   * (Linear solver/Out-of-core factorisation): @p mode `in core`, `out of
   * core` (switched on at once) or `auto` (report_memory_estimate()
   * switches it on when a run's estimated peak exceeds the memory
   * available); `in core` and `auto` switch off what an earlier run of
   * the process switched on. @p directory: where the factors' files go ("": MUMPS's
   * default, MUMPS_OOC_TMPDIR or /tmp). Out of core means MUMPS's
   * ICNTL(22) = 1 for every factorisation, set in PETSc's options database
   * for the factors without a prefix (the contact solver's, the inertia
   * counts', the block solves') and with SLEPc's `st_` (shift-and-invert).
   * @throws std::runtime_error if @p mode is none of the three, or PETSc
   * refuses the option.
   */
  void
  set_factor_storage(const std::string &mode, const std::string &directory);

  /**
   * Whether MUMPS's factorisations keep their factors out of core from now
   * on (set_factor_storage(), or report_memory_estimate() under `auto`).
   * Throws nothing.
   */
  bool
  factors_out_of_core();

  /**
   * The memory available to new allocations on the nodes of @p comm [MB]:
   * /proc/meminfo's MemAvailable of each node, counted once per node (by
   * its first rank in @p comm), summed. Collective.
   * @throws what deal.II's MPI calls throw if the communicator fails.
   */
  double
  available_memory_mb(MPI_Comm comm);

  /**
   * Prints on @p out (if not null; rank 0's) `Memory: <now> MB in use
   * (<kB> per DoF); estimated peak <peak> MB (<kB> per DoF) with
   * <what>`, where now is the resident memory (VmRSS, after returning the
   * heap's free pages to the system) summed over the ranks of @p comm, and
   * peak = now + @p extra_bytes (the caller's estimate of what the
   * analysis still allocates, summed over the ranks). Per DoF of
   * @p n_dofs. @p factor_bytes: the part of @p extra_bytes that is MUMPS's
   * factors (factorisation_bytes()). With the `auto` storage of
   * set_factor_storage(), a peak above the memory available to the run
   * (available_memory_mb() plus what it holds now) switches the factors
   * out of core; out of core, a quarter of @p factor_bytes is
   * counted (MUMPS's in-core work space: on the default passenger-car
   * brake's preload, 199 584 DoFs, the peak fell from 4501 to 2786 MB out
   * of core, the factors' estimate being 2045 MB). A peak still above the
   * available memory is reported as such (the system may stop the run).
   * Collective.
   * @returns the estimated peak [MB].
   * @throws what deal.II's MPI sum throws if the ranks' communicator fails.
   */
  double
  report_memory_estimate(MPI_Comm                        comm,
                         std::ostream                   *out,
                         dealii::types::global_dof_index n_dofs,
                         double                          extra_bytes,
                         const std::string              &what,
                         double                          factor_bytes = 0.);
} // namespace squeal

#endif
