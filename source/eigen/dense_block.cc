// Dense blocks over the locally owned rows: sparse products, block solves
// and local parts of vectors (see dense_block.h; the small dense problems
// are in projected_problem.cc).

#include "dense_block.h"

#include <deal.II/base/mpi.h>

#include <petscksp.h>
#include <slepceps.h>

#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>


namespace squeal
{
  namespace eigen
  {
    namespace internal
    {
      void
      check_petsc(const int ierr, const char *who, const char *what)
      {
        if (ierr != 0)
          throw std::runtime_error(
            std::string(who) + ": PETSc/SLEPc call failed: " + what +
            " (error code " + std::to_string(ierr) + ")");
      }

      void
      use_mumps(void *ksp_handle, const bool cholesky)
      {
        const char *who = "direct solver";
        KSP         ksp = static_cast<KSP>(ksp_handle);
        PC          pc;
        check_petsc(KSPSetType(ksp, KSPPREONLY), who, "KSPSetType");
        check_petsc(KSPGetPC(ksp, &pc), who, "KSPGetPC");
        check_petsc(PCSetType(pc, cholesky ? PCCHOLESKY : PCLU),
                    who,
                    "PCSetType");
        check_petsc(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS),
                    who,
                    "PCFactorSetMatSolverType");
      }

      namespace
      {
        // How B's pattern relates to A's, from their stored entries: the
        // same number (one model's combinations all copy the first part's
        // pattern), fewer (B on its own nonzeros within A's), or more.
        MatStructure
        pattern_of(Mat A, Mat B)
        {
          MatInfo a, b;
          MatGetInfo(A, MAT_GLOBAL_SUM, &a);
          MatGetInfo(B, MAT_GLOBAL_SUM, &b);
          return a.nz_used == b.nz_used ? SAME_NONZERO_PATTERN :
                 a.nz_used > b.nz_used  ? SUBSET_NONZERO_PATTERN :
                                          DIFFERENT_NONZERO_PATTERN;
        }
      } // namespace

      void
      add_scaled(PETScMatrix &A, const double a, const PETScMatrix &B)
      {
        check_petsc(MatAXPY(A, a, B, pattern_of(A, B)),
                    "sparse matrices",
                    "MatAXPY");
      }

      void *
      shift_invert_with_mumps(void *st_handle, const bool cholesky)
      {
        ST  st = static_cast<ST>(st_handle);
        KSP ksp;
        check_petsc(STSetType(st, STSINVERT), "shift-and-invert", "STSetType");
        check_petsc(STGetKSP(st, &ksp), "shift-and-invert", "STGetKSP");
        use_mumps(ksp, cholesky);
        // A - sigma B on A's pattern when B's is the same or within it
        // (one model's combinations, or its mass on its own nonzeros)
        PetscInt n_matrices = 0;
        check_petsc(STGetNumMatrices(st, &n_matrices),
                    "shift-and-invert",
                    "STGetNumMatrices");
        if (n_matrices == 2)
          {
            Mat A, B;
            check_petsc(STGetMatrix(st, 0, &A),
                        "shift-and-invert",
                        "STGetMatrix");
            check_petsc(STGetMatrix(st, 1, &B),
                        "shift-and-invert",
                        "STGetMatrix");
            check_petsc(STSetMatStructure(st, pattern_of(A, B)),
                        "shift-and-invert",
                        "STSetMatStructure");
          }
        return ksp;
      }

      void
      sum_over_ranks(Eigen::MatrixXd &A, MPI_Comm comm)
      {
        MPI_Allreduce(
          MPI_IN_PLACE, A.data(), A.size(), MPI_DOUBLE, MPI_SUM, comm);
      }

      Eigen::VectorXd
      column_norms(const Eigen::MatrixXd &B, MPI_Comm comm)
      {
        Eigen::MatrixXd squares = B.colwise().squaredNorm();
        sum_over_ranks(squares, comm);
        return squares.row(0).transpose().cwiseSqrt();
      }

      namespace
      {
        // A PETSc dense matrix over the local rows of B (column-major,
        // shared storage; PETSc only reads it when it is an input).
        Mat
        wrap(const PETScMatrix &A, Eigen::Ref<const Eigen::MatrixXd> B)
        {
          // PETSc's leading dimension is the local row count
          if (B.cols() > 1 && B.outerStride() != B.rows())
            throw std::logic_error(
              "dense block: a block with gaps between its columns");
          Mat Bd;
          if (MatCreateDense(A.get_mpi_communicator(),
                             B.rows(),
                             PETSC_DECIDE,
                             A.m(),
                             B.cols(),
                             const_cast<double *>(B.data()),
                             &Bd) != 0)
            throw std::runtime_error("dense block: MatCreateDense failed");
          return Bd;
        }

      } // namespace

      namespace
      {
        // A PETSc SeqAIJ matrix as an Eigen row-major sparse matrix
        // (shared storage; valid while the matrix is unchanged).
        class CsrView
        {
        public:
          explicit CsrView(Mat a)
            : a(a)
          {
            PetscBool done = PETSC_FALSE;
            if (MatGetRowIJ(
                  a, 0, PETSC_FALSE, PETSC_FALSE, &rows, &ia, &ja, &done) !=
                  0 ||
                !done || MatSeqAIJGetArrayRead(a, &values) != 0)
              throw std::runtime_error(
                "dense block: the sparse matrix's CSR arrays are not "
                "available");
            MatGetSize(a, nullptr, &columns);
          }

          ~CsrView()
          {
            MatSeqAIJRestoreArrayRead(a, &values);
            PetscBool done;
            MatRestoreRowIJ(
              a, 0, PETSC_FALSE, PETSC_FALSE, &rows, &ia, &ja, &done);
          }

          CsrView(const CsrView &) = delete;
          CsrView &
          operator=(const CsrView &) = delete;

          Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>>
          map() const
          {
            return {rows, columns, ia[rows], ia, ja, values};
          }

        private:
          Mat                a;
          PetscInt           rows = 0, columns = 0;
          const PetscInt    *ia = nullptr, *ja = nullptr;
          const PetscScalar *values = nullptr;
        };

        using RowBlock = RowMatrix;

        // Gathers the rows colmap[i] of a distributed row-major block from
        // their owners: one PETSc star forest per product, one broadcast per
        // block of columns (collective: every rank of an MPIAIJ matrix).
        class GhostRows
        {
        public:
          GhostRows(Mat a, const PetscInt n_ghost, const PetscInt *colmap)
            : n_ghost(n_ghost)
          {
            PetscLayout layout;
            if (MatGetLayouts(a, nullptr, &layout) != 0 ||
                PetscSFCreate(PetscObjectComm(reinterpret_cast<PetscObject>(a)),
                              &sf) != 0 ||
                PetscSFSetGraphLayout(
                  sf, layout, n_ghost, nullptr, PETSC_COPY_VALUES, colmap) != 0)
              throw std::runtime_error(
                "dense block: the ghost-row star forest failed");
          }

          ~GhostRows()
          {
            PetscSFDestroy(&sf);
          }

          GhostRows(const GhostRows &) = delete;
          GhostRows &
          operator=(const GhostRows &) = delete;

          RowBlock
          gather(const RowBlock &local) const
          {
            RowBlock     ghosts(n_ghost, local.cols());
            MPI_Datatype unit;
            MPI_Type_contiguous(local.cols(), MPI_DOUBLE, &unit);
            MPI_Type_commit(&unit);
            const bool ok =
              PetscSFBcastBegin(
                sf, unit, local.data(), ghosts.data(), MPI_REPLACE) == 0 &&
              PetscSFBcastEnd(
                sf, unit, local.data(), ghosts.data(), MPI_REPLACE) == 0;
            MPI_Type_free(&unit);
            if (!ok)
              throw std::runtime_error(
                "dense block: gathering the ghost rows failed");
            return ghosts;
          }

        private:
          PetscInt n_ghost;
          PetscSF  sf = nullptr;
        };

        // An AIJ matrix's local blocks: the diagonal one (the matrix
        // itself for MATSEQAIJ) and, for MATMPIAIJ, the off-diagonal one
        // with the global indices (colmap) of its n_ghost columns.
        struct AijBlocks
        {
          Mat             diagonal = nullptr, off_diagonal = nullptr;
          const PetscInt *colmap  = nullptr;
          PetscInt        n_ghost = 0;
          bool            is_mpi  = false;

          explicit AijBlocks(Mat a)
            : diagonal(a)
          {
            PetscBool mpi = PETSC_FALSE, seq = PETSC_FALSE;
            PetscObjectTypeCompare(reinterpret_cast<PetscObject>(a),
                                   MATMPIAIJ,
                                   &mpi);
            PetscObjectTypeCompare(reinterpret_cast<PetscObject>(a),
                                   MATSEQAIJ,
                                   &seq);
            if (!mpi && !seq)
              throw std::runtime_error(
                "dense block: the sparse matrix is not of PETSc type AIJ");
            is_mpi = mpi;
            if (!is_mpi)
              return;
            if (MatMPIAIJGetSeqAIJ(a, &diagonal, &off_diagonal, &colmap) != 0)
              throw std::runtime_error(
                "dense block: MatMPIAIJGetSeqAIJ failed");
            MatGetSize(off_diagonal, nullptr, &n_ghost);
          }
        };
      } // namespace

      Eigen::MatrixXd
      multiply(const PETScMatrix &A, Eigen::Ref<const Eigen::MatrixXd> B)
      {
        return multiply(static_cast<Mat>(A), B);
      }

      Eigen::MatrixXd
      multiply(Mat A, Eigen::Ref<const Eigen::MatrixXd> B)
      {
        Eigen::MatrixXd result(B.rows(), B.cols());
        multiply_add(A, 0., B, result);
        return result;
      }

      void
      multiply_add(Mat                               A,
                   const double                      a,
                   Eigen::Ref<const Eigen::MatrixXd> B,
                   Eigen::Ref<Eigen::MatrixXd>       R)
      {
        // Eigen's row-major sparse times row-major dense product reads each
        // nonzero once per block of columns and the rows of B contiguously
        // (PETSc 3.18's AIJ times dense streams the matrix once per four
        // columns); the off-process part (MPIAIJ) with ghost rows of B
        // gathered by a PETSc star forest. a = 0: R := A B (R's values
        // are not read).
        const AijBlocks                  b(A);
        const CsrView                    d(b.diagonal);
        std::unique_ptr<const CsrView>   o;
        std::unique_ptr<const GhostRows> ghosts;
        if (b.is_mpi)
          {
            o      = std::make_unique<const CsrView>(b.off_diagonal);
            ghosts = std::make_unique<const GhostRows>(A, b.n_ghost, b.colmap);
          }
        // blocks of 64 columns keep the rows of B that a row of A reads in
        // cache
        constexpr Eigen::Index width = 64;
        for (Eigen::Index c = 0; c < B.cols(); c += width)
          {
            const Eigen::Index w       = std::min(width, B.cols() - c);
            const RowBlock     local   = B.middleCols(c, w);
            RowBlock           product = d.map() * local;
            if (ghosts)
              product += o->map() * ghosts->gather(local);
            if (a == 0.)
              R.middleCols(c, w) = product;
            else
              R.middleCols(c, w) += a * product;
          }
      }

      struct RowProduct::Data
      {
        AijBlocks                      blocks;
        CsrView                        diagonal;
        std::unique_ptr<const CsrView> off_diagonal;
        RowMatrix                      ghosts; // V's rows colmap[i]
        const RowMatrix               &V;

        Data(Mat A, const RowMatrix &V)
          : blocks(A)
          , diagonal(blocks.diagonal)
          , V(V)
        {
          if (!blocks.is_mpi)
            return;
          off_diagonal = std::make_unique<const CsrView>(blocks.off_diagonal);
          ghosts       = GhostRows(A, blocks.n_ghost, blocks.colmap).gather(V);
        }
      };

      RowProduct::RowProduct(const PETScMatrix &A, const RowMatrix &V)
        : data(std::make_unique<Data>(A, V))
      {}

      RowProduct::~RowProduct() = default;

      RowMatrix
      RowProduct::rows(const std::vector<int> &rows) const
      {
        const Data &d = *data;
        RowMatrix   P = RowMatrix::Zero(rows.size(), d.V.cols());
        const auto  add_row =
          [&P](const auto &A, const RowMatrix &X, const int i, const int a) {
            for (typename std::decay_t<decltype(A)>::InnerIterator it(A, i); it;
                 ++it)
              P.row(a) += it.value() * X.row(it.col());
          };
        const auto dm = d.diagonal.map();
        for (std::size_t a = 0; a < rows.size(); ++a)
          {
            add_row(dm, d.V, rows[a], a);
            if (d.off_diagonal)
              add_row(d.off_diagonal->map(), d.ghosts, rows[a], a);
          }
        return P;
      }

      void
      multiply_in_place(Eigen::MatrixXd &B, const Eigen::MatrixXd &T)
      {
        multiply_into_leading_columns(B, T);
        // the leading columns are the front of the column-major storage:
        // shrinking them keeps the values (realloc, no copy)
        B.conservativeResize(Eigen::NoChange, T.cols());
      }

      void
      multiply_into_leading_columns(Eigen::Ref<Eigen::MatrixXd> B,
                                    const Eigen::MatrixXd      &T)
      {
        if (T.rows() != B.cols() || T.cols() > B.cols())
          throw std::logic_error(
            "dense block: B T in place needs T with B's columns as rows "
            "and at most as many columns");
        // a block of rows at a time: its product, then its first T.cols()
        // entries overwritten (rows below are still to be read)
        constexpr Eigen::Index height = 1024;
        for (Eigen::Index i = 0; i < B.rows(); i += height)
          {
            const Eigen::Index    h       = std::min(height, B.rows() - i);
            const Eigen::MatrixXd product = B.middleRows(i, h) * T;
            B.block(i, 0, h, T.cols())    = product;
          }
      }

      struct PartsProduct::Data
      {
        // one part's nonzero rows: CSR over [local columns, ghost columns]
        struct Part
        {
          std::vector<int>    rows, outer, inner;
          std::vector<double> values;
        };
        std::vector<Part> parts;
        // the transposes of the parts that are not symmetric (no rows for
        // a symmetric part)
        std::vector<Part>                transposed;
        std::vector<bool>                has_transpose;
        int                              n_local = 0, n_ghost = 0;
        std::unique_ptr<const GhostRows> ghosts;

        // columns [c0, c0 + w) of B's local rows and their ghost rows after
        // them (collective)
        RowBlock
        extended(Eigen::Ref<const Eigen::MatrixXd> B,
                 const Eigen::Index                c0,
                 const Eigen::Index                w) const
        {
          RowBlock       result(n_local + n_ghost, w);
          const RowBlock local    = B.middleCols(c0, w);
          result.topRows(n_local) = local;
          if (ghosts)
            result.bottomRows(n_ghost) = ghosts->gather(local);
          return result;
        }

        // A part times an extended block: its nonzero rows
        static RowBlock
        times(const Part &p, const RowBlock &extended)
        {
          const Eigen::Map<
            const Eigen::SparseMatrix<double, Eigen::RowMajor, int>>
            A(p.rows.size(),
              extended.rows(),
              p.values.size(),
              p.outer.data(),
              p.inner.data(),
              p.values.data());
          return A * extended;
        }
      };

      PartsProduct::PartsProduct(const physics::MatrixParts &model)
        : data(std::make_unique<Data>())
      {
        Data &d = *data;
        // a friction part (the only kind that is not symmetric) is copied
        // transposed too
        const unsigned int n_parts = model.size();
        std::vector<Mat>   transposes(n_parts, nullptr);
        d.has_transpose.assign(n_parts, false);
        for (unsigned int k = 0; k < n_parts; ++k)
          if (model.parts[k].kind ==
              physics::MatrixParts::Kind::interface_friction)
            {
              check_petsc(MatTranspose(model.matrix(k),
                                       MAT_INITIAL_MATRIX,
                                       &transposes[k]),
                          "parts product",
                          "MatTranspose");
              d.has_transpose[k] = true;
            }
        // the ghost columns of every part and transpose, in one ascending
        // numbering
        std::vector<PetscInt>  ghost_columns;
        std::vector<AijBlocks> blocks, transposed_blocks;
        bool                   is_mpi     = false;
        const auto             add_ghosts = [&](const AijBlocks &b) {
          is_mpi = is_mpi || b.is_mpi;
          if (b.is_mpi)
            ghost_columns.insert(ghost_columns.end(),
                                 b.colmap,
                                 b.colmap + b.n_ghost);
        };
        for (unsigned int k = 0; k < n_parts; ++k)
          {
            add_ghosts(blocks.emplace_back(model.matrix(k)));
            if (transposes[k])
              add_ghosts(transposed_blocks.emplace_back(transposes[k]));
          }
        std::sort(ghost_columns.begin(), ghost_columns.end());
        ghost_columns.erase(std::unique(ghost_columns.begin(),
                                        ghost_columns.end()),
                            ghost_columns.end());
        {
          PetscInt rows;
          MatGetLocalSize(model.matrix(0), &rows, nullptr);
          d.n_local = rows;
        }
        d.n_ghost = ghost_columns.size();
        if (is_mpi)
          d.ghosts = std::make_unique<const GhostRows>(model.matrix(0),
                                                       d.n_ghost,
                                                       ghost_columns.data());
        // a matrix's nonzero rows in the common column numbering
        const auto copy = [&](const AijBlocks &b) {
          const CsrView                  diagonal(b.diagonal);
          std::unique_ptr<const CsrView> off;
          if (b.off_diagonal)
            off = std::make_unique<const CsrView>(b.off_diagonal);
          // the position of each of this part's ghost columns
          std::vector<int> ghost(b.n_ghost);
          for (PetscInt j = 0; j < b.n_ghost; ++j)
            ghost[j] = d.n_local + (std::lower_bound(ghost_columns.begin(),
                                                     ghost_columns.end(),
                                                     b.colmap[j]) -
                                    ghost_columns.begin());
          Data::Part part;
          part.outer.push_back(0);
          const auto dm = diagonal.map();
          for (int i = 0; i < d.n_local; ++i)
            {
              const std::size_t before = part.values.size();
              for (std::decay_t<decltype(dm)>::InnerIterator it(dm, i); it;
                   ++it)
                if (it.value() != 0.)
                  {
                    part.inner.push_back(it.col());
                    part.values.push_back(it.value());
                  }
              if (off)
                {
                  const auto om = off->map();
                  for (std::decay_t<decltype(om)>::InnerIterator it(om, i); it;
                       ++it)
                    if (it.value() != 0.)
                      {
                        part.inner.push_back(ghost[it.col()]);
                        part.values.push_back(it.value());
                      }
                }
              if (part.values.size() > before)
                {
                  part.rows.push_back(i);
                  part.outer.push_back(part.values.size());
                }
            }
          return part;
        };
        d.transposed.resize(n_parts);
        for (unsigned int k = 0, t = 0; k < n_parts; ++k)
          {
            d.parts.push_back(copy(blocks[k]));
            if (transposes[k])
              d.transposed[k] = copy(transposed_blocks[t++]);
          }
        transposed_blocks.clear();
        for (Mat &t : transposes)
          if (t)
            MatDestroy(&t);
      }

      PartsProduct::~PartsProduct() = default;

      std::vector<Eigen::MatrixXd>
      PartsProduct::multiply(
        const std::vector<const physics::MatrixParts::Coefficients *> &c,
        Eigen::Ref<const Eigen::MatrixXd>                              B,
        const bool transposed) const
      {
        const Data        &d = *data;
        const unsigned int q = c.size();
        for (const auto *a : c)
          if (a->size() != d.parts.size())
            throw std::logic_error(
              "PartsProduct::multiply: one coefficient per part");
        std::vector<Eigen::MatrixXd> result(q,
                                            Eigen::MatrixXd(B.rows(),
                                                            B.cols()));
        // blocks of 64 columns keep the rows of B that a row of a part
        // reads in cache
        constexpr Eigen::Index width = 64;
        for (Eigen::Index c0 = 0; c0 < B.cols(); c0 += width)
          {
            const Eigen::Index    w        = std::min(width, B.cols() - c0);
            const RowBlock        extended = d.extended(B, c0, w);
            std::vector<RowBlock> sums(q, RowBlock::Zero(d.n_local, w));
            for (unsigned int k = 0; k < d.parts.size(); ++k)
              {
                const Data::Part &p    = transposed && d.has_transpose[k] ?
                                           d.transposed[k] :
                                           d.parts[k];
                bool              used = false;
                for (unsigned int i = 0; i < q; ++i)
                  used = used || (*c[i])[k] != 0.;
                if (!used || p.rows.empty())
                  continue;
                const RowBlock P = Data::times(p, extended);
                for (unsigned int i = 0; i < q; ++i)
                  {
                    const double a = (*c[i])[k];
                    if (a == 0.)
                      continue;
                    for (std::size_t r = 0; r < p.rows.size(); ++r)
                      sums[i].row(p.rows[r]) += a * P.row(r);
                  }
              }
            for (unsigned int i = 0; i < q; ++i)
              result[i].middleCols(c0, w) = sums[i];
          }
        return result;
      }

      PartsProduct::Skew
      PartsProduct::skew_times(const physics::MatrixParts::Coefficients &c,
                               Eigen::Ref<const Eigen::MatrixXd> N) const
      {
        const Data &d = *data;
        if (c.size() != d.parts.size())
          throw std::logic_error(
            "PartsProduct::skew_times: one coefficient per part");
        Skew                      result;
        std::vector<int>          position(d.n_local, -1);
        std::vector<unsigned int> skew;
        for (unsigned int k = 0; k < d.parts.size(); ++k)
          if (d.has_transpose[k] && c[k] != 0.)
            {
              skew.push_back(k);
              for (const auto *p : {&d.parts[k], &d.transposed[k]})
                for (const int i : p->rows)
                  position[i] = 0;
            }
        result.any = !skew.empty();
        if (!result.any)
          return result;
        for (int i = 0; i < d.n_local; ++i)
          if (position[i] == 0)
            {
              position[i] = result.rows.size();
              result.rows.push_back(i);
            }
        result.values = Eigen::MatrixXd::Zero(result.rows.size(), N.cols());
        constexpr Eigen::Index width = 64;
        for (Eigen::Index c0 = 0; c0 < N.cols(); c0 += width)
          {
            const Eigen::Index w        = std::min(width, N.cols() - c0);
            const RowBlock     extended = d.extended(N, c0, w);
            for (const unsigned int k : skew)
              for (const bool transposed : {false, true})
                {
                  const Data::Part &p =
                    transposed ? d.transposed[k] : d.parts[k];
                  const double a = transposed ? -c[k] : c[k];
                  if (p.rows.empty())
                    continue;
                  const RowBlock P = Data::times(p, extended);
                  for (std::size_t r = 0; r < p.rows.size(); ++r)
                    result.values.block(position[p.rows[r]], c0, 1, w) +=
                      a * P.row(r);
                }
          }
        return result;
      }

      std::vector<int>
      nonzero_rows(const PETScMatrix &A)
      {
        const auto       range = A.local_range();
        std::vector<int> rows;
        for (auto i = range.first; i < range.second; ++i)
          {
            PetscInt           n;
            const PetscScalar *values;
            if (MatGetRow(A, i, &n, nullptr, &values) != 0)
              throw std::runtime_error("dense block: MatGetRow failed");
            const bool any = std::any_of(values, values + n, [](const auto v) {
              return v != 0.;
            });
            MatRestoreRow(A, i, &n, nullptr, &values);
            if (any)
              rows.push_back(i - range.first);
          }
        return rows;
      }

      void
      common_positions(const std::vector<int> &x,
                       const std::vector<int> &y,
                       std::vector<int>       &in_x,
                       std::vector<int>       &in_y)
      {
        in_x.clear();
        in_y.clear();
        for (std::size_t a = 0, b = 0; a < x.size() && b < y.size();)
          if (x[a] < y[b])
            ++a;
          else if (y[b] < x[a])
            ++b;
          else
            {
              in_x.push_back(a++);
              in_y.push_back(b++);
            }
      }

      Eigen::MatrixXd
      solve_block(void *ksp, const PETScMatrix &A, const Eigen::MatrixXd &B)
      {
        Eigen::MatrixXd X(B.rows(), B.cols());
        solve_block(ksp, A, B, X);
        return X;
      }

      void
      solve_block(void                             *ksp,
                  const PETScMatrix                &A,
                  Eigen::Ref<const Eigen::MatrixXd> B,
                  Eigen::Ref<Eigen::MatrixXd>       X)
      {
        if (X.rows() != B.rows() || X.cols() != B.cols())
          throw std::logic_error("dense block: X and B differ in size");
        if (B.cols() == 0)
          return;
        Mat Bd = wrap(A, B), Xd = wrap(A, X);
        if (KSPMatSolve(static_cast<KSP>(ksp), Bd, Xd) != 0)
          throw std::runtime_error("dense block: KSPMatSolve failed");
        MatDestroy(&Xd);
        MatDestroy(&Bd);
      }

      Eigen::VectorXd
      local_part(const PETScVector &v, const dealii::IndexSet &owned)
      {
        if (v.locally_owned_size() != owned.n_elements())
          throw std::runtime_error(
            "dense block: a vector does not own the expected rows");
        const PetscScalar *a;
        VecGetArrayRead(v, &a);
        const Eigen::VectorXd x =
          Eigen::Map<const Eigen::VectorXd>(a, owned.n_elements());
        VecRestoreArrayRead(v, &a);
        return x;
      }

      void
      set_local_part(PETScVector &v, const Eigen::VectorXd &x)
      {
        if (v.locally_owned_size() != static_cast<std::size_t>(x.size()))
          throw std::runtime_error(
            "dense block: a vector does not own the expected rows");
        PetscScalar *a;
        VecGetArray(v, &a);
        Eigen::Map<Eigen::VectorXd>(a, x.size()) = x;
        VecRestoreArray(v, &a);
      }

    } // namespace internal
  }   // namespace eigen
} // namespace squeal
