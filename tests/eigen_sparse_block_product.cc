// The sparse-times-dense-block product of the eigensolvers
// (eigen::internal::multiply: Eigen's row-major product on PETSc's AIJ
// arrays, the off-process columns' rows of the block gathered by a PETSc
// star forest) against the dense product of the same matrix, computed
// independently on every rank: a banded 300 x 300 matrix with long-range
// couplings (so that under mpirun -np 2 every rank reads the other's
// rows), times blocks of 150 (more than two column blocks of 64 and a
// remainder), 1 and 0 columns. Agreement to 1e-13 of the largest entry.

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include "../source/eigen/dense_block.h"
#include "test_tools.h"

#include <cmath>

using namespace dealii;
using namespace squeal;

namespace
{
  constexpr unsigned int n = 300;

  bool
  coupled(const unsigned int i, const unsigned int j)
  {
    return (i > j ? i - j : j - i) <= 3 || (7 * i + 13 * j) % 37 == 0;
  }

  double
  entry(const unsigned int i, const unsigned int j)
  {
    return std::sin(1. + i + 2. * j) + (i == j ? 4. : 0.);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int size  = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD),
                     rank  = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  const unsigned int first = rank * n / size, last = (rank + 1) * n / size;
  IndexSet           owned(n);
  owned.add_range(first, last);

  DynamicSparsityPattern dsp(n, n);
  Eigen::MatrixXd        dense = Eigen::MatrixXd::Zero(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      if (coupled(i, j))
        {
          dsp.add(i, j);
          dense(i, j) = entry(i, j);
        }
  eigen::PETScMatrix A;
  A.reinit(owned, owned, dsp, MPI_COMM_WORLD);
  for (unsigned int i = first; i < last; ++i)
    for (unsigned int j = 0; j < n; ++j)
      if (coupled(i, j))
        A.set(i, j, entry(i, j));
  A.compress(VectorOperation::insert);

  unsigned int off_process = 0;
  for (unsigned int i = first; i < last; ++i)
    for (unsigned int j = 0; j < n; ++j)
      off_process += coupled(i, j) && (j < first || j >= last);
  test_tools::verbose() << "rank " << rank << ": " << off_process
                        << " off-process couplings\n";
  test_tools::check_true("every rank has off-process couplings when np > 1",
                         size == 1 || Utilities::MPI::min(off_process,
                                                          MPI_COMM_WORLD) > 0);

  for (const int columns : {150, 1, 0})
    {
      Eigen::MatrixXd B(n, columns);
      for (unsigned int i = 0; i < n; ++i)
        for (int j = 0; j < columns; ++j)
          B(i, j) = std::cos(0.1 * i + 0.37 * j) + 0.01 * j;
      const Eigen::MatrixXd reference =
        (dense * B).middleRows(first, last - first);
      const Eigen::MatrixXd product =
        eigen::internal::multiply(A, B.middleRows(first, last - first));
      const std::string name = std::to_string(columns) + " columns: ";
      test_tools::check(name + "rows", product.rows(), last - first, 0., 1.);
      test_tools::check(name + "columns", product.cols(), columns, 0., 1.);
      if (columns == 0)
        continue;
      const double scale =
        Utilities::MPI::max(reference.cwiseAbs().maxCoeff(), MPI_COMM_WORLD);
      const double error =
        Utilities::MPI::max((product - reference).cwiseAbs().maxCoeff(),
                            MPI_COMM_WORLD);
      test_tools::verbose() << name << "largest entry " << scale
                            << ", largest error " << error << '\n';
      test_tools::check_true(name + "the product is not zero", scale > 1.);
      test_tools::check(
        name + "A B against the dense product", error, 0., 1e-13, scale);
    }
  return test_tools::finish();
}
