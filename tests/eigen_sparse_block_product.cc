// The sparse-times-dense-block product of the eigensolvers
// (eigen::internal::multiply: Eigen's row-major product on PETSc's AIJ
// arrays, the off-process columns' rows of the block gathered by a PETSc
// star forest) against the dense product of the same matrix, computed
// independently on every rank: a banded 300 x 300 matrix with long-range
// couplings (so that under mpirun -np 2 every rank reads the other's
// rows), times blocks of 150 (more than two column blocks of 64 and a
// remainder), 1 and 0 columns. Agreement to 1e-13 of the largest entry.
// Then the parts' product (eigen::internal::PartsProduct: sums
// sum_k c_k A_k B from each part's nonzero rows) against the same sums of
// the dense parts: the matrix above with a third of its entries stored
// as zeros (a part on the common pattern), a part on its own pattern of
// 12 scattered rows with long-range couplings, and an empty part; two
// coefficient vectors, one of which skips a part, and the transposed
// product of the part that is not symmetric, and the skew part (A - A^T) B
// on its rows (PartsProduct::skew_times). The same product added
// to a block with values (multiply_add), chosen rows of it from a
// row-major block (RowProduct, as the reduced basis' projection forms
// them), and B T formed in place (multiply_in_place) against B T.

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include "../source/eigen/dense_block.h"
#include "test_tools.h"

#include <cmath>
#include <vector>

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

      // R += a A B into a block that holds values already
      const Eigen::MatrixXd R0 =
        Eigen::MatrixXd::Constant(last - first, columns, 0.75);
      Eigen::MatrixXd R = R0;
      eigen::internal::multiply_add(A,
                                    -2.5,
                                    B.middleRows(first, last - first),
                                    R);
      const double add_error =
        Utilities::MPI::max((R - (R0 - 2.5 * reference)).cwiseAbs().maxCoeff(),
                            MPI_COMM_WORLD);
      test_tools::check(name + "R - 2.5 A B against the dense product",
                        add_error,
                        0.,
                        1e-13,
                        2.5 * scale);

      // chosen rows of A B from a row-major B (every fifth local row and
      // the last, none on a rank without rows)
      const eigen::internal::RowMatrix  Br = B.middleRows(first, last - first);
      const eigen::internal::RowProduct rows_of(A, Br);
      std::vector<int>                  chosen;
      for (unsigned int i = 0; i < last - first; i += 5)
        chosen.push_back(i);
      if (chosen.back() != int(last - first) - 1)
        chosen.push_back(last - first - 1);
      const eigen::internal::RowMatrix P         = rows_of.rows(chosen);
      double                           row_error = 0.;
      for (std::size_t a = 0; a < chosen.size(); ++a)
        row_error =
          std::max(row_error,
                   (P.row(a) - reference.row(chosen[a])).cwiseAbs().maxCoeff());
      row_error = Utilities::MPI::max(row_error, MPI_COMM_WORLD);
      test_tools::check(name + "chosen rows of A B against the dense product",
                        row_error,
                        0.,
                        1e-13,
                        scale);
    }

  // B := B T in place against the product into a new block (every rank
  // its own rows: 300 x 150 times 150 x 90, blocks of 1024 rows and one)
  for (const unsigned int rows : {300u, 2500u})
    {
      Eigen::MatrixXd B(rows, 150), T(150, 90);
      for (unsigned int i = 0; i < rows; ++i)
        for (int j = 0; j < 150; ++j)
          B(i, j) = std::cos(0.21 * i - 0.13 * j);
      for (int i = 0; i < 150; ++i)
        for (int j = 0; j < 90; ++j)
          T(i, j) = std::sin(0.5 * i + 0.7 * j) / (1. + i);
      const Eigen::MatrixXd reference = B * T;
      eigen::internal::multiply_in_place(B, T);
      const std::string name =
        "B T in place, " + std::to_string(rows) + " rows: ";
      test_tools::check(name + "columns", B.cols(), 90, 0., 1.);
      test_tools::check(name + "against B T",
                        (B - reference).cwiseAbs().maxCoeff(),
                        0.,
                        1e-13,
                        reference.cwiseAbs().maxCoeff());
    }

  // the parts
  std::vector<Eigen::MatrixXd>    dense_parts(3, Eigen::MatrixXd::Zero(n, n));
  std::vector<eigen::PETScMatrix> parts(3);
  const auto in_second = [](const unsigned int i, const unsigned int j) {
    return i % 25 == 3 && (j == i || j == (i * 7 + 101) % n);
  };
  DynamicSparsityPattern own(n, n);
  for (unsigned int i = 0; i < n; ++i)
    {
      own.add(i, i); // every row keeps its diagonal
      for (unsigned int j = 0; j < n; ++j)
        if (in_second(i, j))
          own.add(i, j);
    }
  parts[0].reinit(owned, owned, dsp, MPI_COMM_WORLD);
  parts[1].reinit(owned, owned, own, MPI_COMM_WORLD);
  parts[2].reinit(owned, owned, own, MPI_COMM_WORLD);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      {
        const bool first_part = coupled(i, j) && (i + j) % 3 != 0;
        if (first_part)
          dense_parts[0](i, j) = entry(i, j);
        if (in_second(i, j))
          dense_parts[1](i, j) = 2. * entry(j, i);
        if (i >= first && i < last)
          {
            if (coupled(i, j))
              parts[0].set(i, j, dense_parts[0](i, j));
            if (in_second(i, j))
              parts[1].set(i, j, dense_parts[1](i, j));
          }
      }
  for (auto &p : parts)
    p.compress(VectorOperation::insert);
  physics::MatrixParts model;
  for (const auto &p : parts)
    model.parts.push_back({&p});
  // the second part is not symmetric: a friction part, kept transposed too
  model.parts[1].kind = physics::MatrixParts::Kind::interface_friction;
  const eigen::internal::PartsProduct product(model);
  const std::vector<double>           c1{1.5, -0.5, 3.}, c2{0., 2., 0.};
  for (const int columns : {150, 0})
    {
      Eigen::MatrixXd B(n, columns);
      for (unsigned int i = 0; i < n; ++i)
        for (int j = 0; j < columns; ++j)
          B(i, j) = std::sin(0.3 * i - 0.11 * j) + 0.02 * j;
      const auto sums =
        product.multiply({&c1, &c2}, B.middleRows(first, last - first));
      const std::string name =
        "parts, " + std::to_string(columns) + " columns: ";
      test_tools::check(name + "two sums", sums.size(), 2, 0., 1.);
      for (unsigned int s = 0; s < 2 && columns > 0; ++s)
        {
          const auto     &c = s == 0 ? c1 : c2;
          Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
          for (unsigned int k = 0; k < 3; ++k)
            A += c[k] * dense_parts[k];
          const Eigen::MatrixXd reference =
            (A * B).middleRows(first, last - first);
          const double scale =
            Utilities::MPI::max(reference.cwiseAbs().maxCoeff(),
                                MPI_COMM_WORLD);
          const double error =
            Utilities::MPI::max((sums[s] - reference).cwiseAbs().maxCoeff(),
                                MPI_COMM_WORLD);
          const std::string sum = name + "sum " + std::to_string(s + 1);
          test_tools::verbose() << sum << ": largest entry " << scale
                                << ", largest error " << error << '\n';
          test_tools::check_true(sum + " is not zero", scale > 1.);
          test_tools::check(sum + " against the dense sum of the parts",
                            error,
                            0.,
                            1e-13,
                            scale);
        }
      if (columns == 0)
        {
          test_tools::check(name + "no columns", sums[0].cols(), 0, 0., 1.);
          continue;
        }
      // the transposed product of the friction part
      const auto transposed =
        product.multiply({&c2}, B.middleRows(first, last - first), true);
      const Eigen::MatrixXd reference =
        (2. * dense_parts[1].transpose() * B).middleRows(first, last - first);
      const double scale =
        Utilities::MPI::max(reference.cwiseAbs().maxCoeff(), MPI_COMM_WORLD);
      const double error =
        Utilities::MPI::max((transposed[0] - reference).cwiseAbs().maxCoeff(),
                            MPI_COMM_WORLD);
      test_tools::check_true(name + "the transposed sum is not zero",
                             scale > 1.);
      test_tools::check(name + "2 A_2^T B against the dense transpose",
                        error,
                        0.,
                        1e-13,
                        scale);
      // the skew part (A - A^T) B of c1's sum on its rows: the friction
      // part's, the other parts being taken as symmetric (as a model
      // assembles them; this test's first part is not)
      {
        const auto skew =
          product.skew_times(c1, B.middleRows(first, last - first));
        const Eigen::MatrixXd F    = c1[1] * dense_parts[1];
        const Eigen::MatrixXd full = (F - F.transpose()) * B;
        // the local rows outside skew.rows must be zero in the dense result
        Eigen::MatrixXd mine = Eigen::MatrixXd::Zero(last - first, columns);
        for (unsigned int a = 0; a < skew.rows.size(); ++a)
          mine.row(skew.rows[a]) = skew.values.row(a);
        const Eigen::MatrixXd reference = full.middleRows(first, last - first);
        const double          skew_scale =
          Utilities::MPI::max(reference.cwiseAbs().maxCoeff(), MPI_COMM_WORLD);
        const double skew_error =
          Utilities::MPI::max((mine - reference).cwiseAbs().maxCoeff(),
                              MPI_COMM_WORLD);
        const unsigned int n_rows =
          Utilities::MPI::sum(static_cast<unsigned int>(skew.rows.size()),
                              MPI_COMM_WORLD);
        test_tools::check_true(name + "the skew part is there", skew.any);
        test_tools::check_true(name + "the skew part is not zero",
                               skew_scale > 1.);
        // the friction part's 12 rows and their columns, not every row
        test_tools::check_true(name + "the skew part's rows are few",
                               n_rows > 0 && n_rows < n / 2);
        test_tools::check(name + "(A - A^T) B against the dense sum",
                          skew_error,
                          0.,
                          1e-13,
                          skew_scale);
        const std::vector<double> symmetric{1., 0., 2.};
        test_tools::check_true(
          name + "no skew part without the friction part",
          !product.skew_times(symmetric, B.middleRows(first, last - first))
             .any);
      }
    }
  return test_tools::finish();
}
