#ifndef squeal_io_matrix_export_h
#define squeal_io_matrix_export_h

/**
 * @file
 * The matrices of a model written for an independent solve: every matrix
 * part and the combined M, C, K of chosen sweep points in the MatrixMarket
 * coordinate format (NIST, "The Matrix Market Exchange Formats: Initial
 * Design", 1996), with the coordinates and components of the degrees of
 * freedom. Any dense or sparse eigensolver (LAPACK, SciPy, MATLAB, Julia)
 * reads them.
 */

#include <squeal/parameters/parameters.h>
#include <squeal/physics/structural_model.h>

#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace squeal
{
  namespace io
  {
    /** The entries of a sparse matrix read from a MatrixMarket file. */
    struct Triplets
    {
      unsigned int rows = 0, columns = 0;
      /// (row, column, value), 0-based
      std::vector<std::tuple<unsigned int, unsigned int, double>> entries;
    };

    /**
     * Writes the matrix @p A (n x n, any distribution) to @p file as a
     * MatrixMarket `coordinate real general` matrix, 1-based, 17
     * significant digits, the rows gathered on rank 0, which writes.
     * Collective. @p comment goes into `%` lines after the header.
     * @throws std::runtime_error naming the file if it cannot be written
     *   completely (on every rank).
     */
    void
    write_matrix_market(const physics::PETScMatrix &A,
                        const std::string          &file,
                        const std::string          &comment = "");

    /**
     * Reads a MatrixMarket `coordinate real general` (or `symmetric`,
     * whose lower triangle is mirrored) file.
     * @throws std::runtime_error naming the file and line of a malformed
     *   header, size line or entry, or an index out of range.
     */
    Triplets
    read_matrix_market(const std::string &file);

    /**
     * Writes into @p directory (which must exist): `part_<k>.mtx` for every
     * matrix part of @p model (physics::MatrixParts, at its reference
     * value), `parts.csv` (`part,name,kind,scale,reference` and, per
     * exported point, its mass, damping and stiffness coefficients:
     * M(p) = sum_k mass_k part_k and likewise C and K), for each
     * (index, point) of @p points `point_<index>_M.mtx`, `_C.mtx`,
     * `_K.mtx` (kg, N s/m, N/m) and `point_<index>.csv` (its named
     * parameters), and `dofs.csv` (`dof,x,y,z,component,constrained`, m;
     * constrained rows carry the spurious diagonal of
     * physics::StructuralModel::setup_and_assemble()). Collective.
     * @throws std::runtime_error naming a file that cannot be written.
     */
    void
    export_matrices(
      const physics::StructuralModel &model,
      const std::vector<std::pair<unsigned int, parameters::ScalarPoint>>
                        &points,
      const std::string &directory);
  } // namespace io
} // namespace squeal

#endif
