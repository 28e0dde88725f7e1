// squeal-bench-linear-solvers: the shifted stiffness A = K + s M of one
// exported CEA point (Output/Export matrices) solved by the direct and the
// algebraic-multigrid solvers of PETSc, for choosing the solver of the
// set-up's large solves by measurement (benchmarks/scale/README.md).
//
// usage: squeal-bench-linear-solvers DIR POINT SOLVER [SHIFT_HZ [RHS [TOL]]]
//   DIR       a run's matrices/ folder; POINT the exported sweep point
//   SOLVER    mumps-lu | mumps-ldlt | mumps-lu-blr | umfpack |
//             amg-gamg | amg-hypre | amg-ml (conjugate gradients, or
//             GMRES(100) when A is not symmetric, with algebraic multigrid)
//   SHIFT_HZ  s = (2 pi SHIFT_HZ)^2, the full solver's shift (default 1000)
//   RHS       right-hand sides solved one after the other (default 8)
//   TOL       the Krylov solver's relative residual (default 1e-10);
//   mumps-lu-blr: the
//             block low-rank dropping threshold CNTL(7) (default 1e-8)
// The right-hand sides are A x for pseudo-random x (entries in [-1, 1],
// a fixed generator), so the error of each solve is known. PETSc options
// (PETSC_OPTIONS) are read after these settings and override them.
// Prints one line: solver,ranks,n,nonzeros,setup_s,solve_s_per_rhs,
// iterations_per_rhs,largest_relative_error,memory_before_MB,peak_MB,
// factor_MB (VmRSS after reading the matrix and VmHWM at the end, summed
// over the ranks; MUMPS's own figure of the memory its factorisation used,
// INFOG(22) summed over the ranks, 0 for the other solvers).

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <squeal/io/matrix_export.h>

#include <petscksp.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

using namespace dealii;

namespace
{
  double
  seconds_since(const std::chrono::steady_clock::time_point t)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t)
      .count();
  }

  double
  memory_mb(const bool peak, MPI_Comm comm)
  {
    Utilities::System::MemoryStats s;
    Utilities::System::get_memory_stats(s);
    return Utilities::MPI::sum(double(peak ? s.VmHWM : s.VmRSS), comm) / 1024.;
  }

  void
  check(const PetscErrorCode e, const char *what)
  {
    if (e != 0)
      throw std::runtime_error(std::string("PETSc: ") + what + " failed");
  }

  // the solution entries: a fixed linear congruential sequence in [-1, 1]
  std::vector<double>
  exact_solution(const unsigned int n, const unsigned int k)
  {
    std::vector<double> x(n);
    std::uint64_t       state = 12345u + 7919u * k;
    for (double &v : x)
      {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        v     = double(state >> 11) / double(1ull << 53) * 2. - 1.;
      }
    return x;
  }

  // (x, y, z, component) of every DoF from dofs.csv
  std::vector<std::array<double, 4>>
  read_dofs(const std::string &file, const unsigned int n)
  {
    std::ifstream in(file);
    if (!in)
      throw std::runtime_error(file + ": cannot be opened");
    std::vector<std::array<double, 4>> dofs(n);
    std::string                        line;
    std::getline(in, line);
    for (unsigned int i = 0; i < n; ++i)
      {
        if (!std::getline(in, line))
          throw std::runtime_error(file + ": fewer than " + std::to_string(n) +
                                   " DoFs");
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream s(line);
        unsigned int       dof;
        s >> dof >> dofs[i][0] >> dofs[i][1] >> dofs[i][2] >> dofs[i][3];
        if (!s || dof != i)
          throw std::runtime_error(file + ", line " + std::to_string(i + 2) +
                                   ": expected 'dof,x,y,z,component,...'");
      }
    return dofs;
  }

  // The six rigid-body modes (three translations, three rotations about
  // the centroid) on the DoFs, orthonormalised: the near null space of
  // elasticity that smoothed-aggregation multigrid interpolates.
  MatNullSpace
  rigid_body_modes(const Mat A, const std::vector<std::array<double, 4>> &dofs)
  {
    std::array<double, 3> c{};
    for (const auto &d : dofs)
      for (unsigned int k = 0; k < 3; ++k)
        c[k] += d[k] / dofs.size();
    Vec      modes[6];
    PetscInt lo, hi;
    check(MatGetOwnershipRange(A, &lo, &hi), "MatGetOwnershipRange");
    for (unsigned int m = 0; m < 6; ++m)
      {
        check(MatCreateVecs(A, &modes[m], nullptr), "MatCreateVecs");
        for (PetscInt i = lo; i < hi; ++i)
          {
            const auto        &d = dofs[i];
            const unsigned int q = unsigned(d[3]);
            const double x = d[0] - c[0], y = d[1] - c[1], z = d[2] - c[2];
            // rotation about axis m - 3: (omega x r)_q
            const double rot[3][3] = {{0., -z, y}, {z, 0., -x}, {-y, x, 0.}};
            const double v         = m < 3 ? (q == m ? 1. : 0.) : rot[m - 3][q];
            check(VecSetValue(modes[m], i, v, INSERT_VALUES), "VecSetValue");
          }
        check(VecAssemblyBegin(modes[m]), "VecAssembly");
        check(VecAssemblyEnd(modes[m]), "VecAssembly");
        for (unsigned int l = 0; l < m; ++l) // Gram-Schmidt, twice
          for (unsigned int pass = 0; pass < 2; ++pass)
            {
              PetscScalar dot;
              check(VecDot(modes[m], modes[l], &dot), "VecDot");
              check(VecAXPY(modes[m], -dot, modes[l]), "VecAXPY");
            }
        check(VecNormalize(modes[m], nullptr), "VecNormalize");
      }
    MatNullSpace space;
    check(MatNullSpaceCreate(
            PetscObjectComm((PetscObject)A), PETSC_FALSE, 6, modes, &space),
          "MatNullSpaceCreate");
    for (Vec &v : modes)
      VecDestroy(&v);
    return space;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  MPI_Comm                         comm = MPI_COMM_WORLD;
  try
    {
      if (argc < 4)
        throw std::runtime_error(
          "usage: squeal-bench-linear-solvers DIR POINT SOLVER "
          "[SHIFT_HZ [RHS [TOL]]]");
      const std::string dir = argv[1], point = argv[2], solver = argv[3];
      const double      shift_hz = argc > 4 ? std::stod(argv[4]) : 1000.;
      const unsigned    n_rhs    = argc > 5 ? std::stoul(argv[5]) : 8;
      const double      tol      = argc > 6 ? std::stod(argv[6]) :
                                              (solver == "mumps-lu-blr" ? 1e-8 : 1e-10);
      const std::vector<std::string> known{"mumps-lu",
                                           "mumps-ldlt",
                                           "mumps-lu-blr",
                                           "umfpack",
                                           "amg-gamg",
                                           "amg-hypre",
                                           "amg-ml"};
      if (std::find(known.begin(), known.end(), solver) == known.end())
        throw std::runtime_error("unknown solver '" + solver +
                                 "'; allowed: mumps-lu, mumps-ldlt, "
                                 "mumps-lu-blr, umfpack, amg-gamg, amg-hypre, "
                                 "amg-ml");
      const double s = std::pow(2. * M_PI * shift_hz, 2);

      // A = K + s M as triplets (every rank reads the files)
      const std::string    stem = dir + "/point_" + point;
      squeal::io::Triplets A = squeal::io::read_matrix_market(stem + "_K.mtx");
      {
        const auto M = squeal::io::read_matrix_market(stem + "_M.mtx");
        for (const auto &[i, j, v] : M.entries)
          A.entries.emplace_back(i, j, s * v);
      }
      const unsigned int n     = A.rows;
      const auto         dofs  = read_dofs(dir + "/dofs.csv", n);
      const unsigned int ranks = Utilities::MPI::n_mpi_processes(comm);
      if (solver == "umfpack" && ranks > 1)
        throw std::runtime_error("umfpack runs on one rank");

      double      setup = 0., solve = 0., error = 0., iterations = 0.;
      std::size_t nonzeros = 0;
      double      before   = 0.;
      double      factor   = 0.;
      if (solver == "umfpack")
        {
          DynamicSparsityPattern dsp(n, n);
          for (const auto &[i, j, v] : A.entries)
            dsp.add(i, j);
          SparsityPattern sp;
          sp.copy_from(dsp);
          SparseMatrix<double> S(sp);
          for (const auto &[i, j, v] : A.entries)
            S.add(i, j, v);
          nonzeros = S.n_nonzero_elements();
          A.entries.clear();
          A.entries.shrink_to_fit();
          before                = memory_mb(false, comm);
          const auto          t = std::chrono::steady_clock::now();
          SparseDirectUMFPACK direct;
          direct.initialize(S);
          setup = seconds_since(t);
          for (unsigned int k = 0; k < n_rhs; ++k)
            {
              const auto     xs = exact_solution(n, k);
              Vector<double> x(xs.begin(), xs.end()), b(n);
              S.vmult(b, x);
              const auto t1 = std::chrono::steady_clock::now();
              direct.solve(b);
              solve += seconds_since(t1);
              b -= x;
              error = std::max(error, b.l2_norm() / x.l2_norm());
            }
        }
      else
        {
          // PETSc: rows split evenly, each rank its own
          PetscInt local = PETSC_DECIDE, N = n;
          check(PetscSplitOwnership(comm, &local, &N), "PetscSplitOwnership");
          PetscInt lo = 0;
          MPI_Scan(&local, &lo, 1, MPIU_INT, MPI_SUM, comm);
          lo -= local;
          const PetscInt        hi = lo + local;
          std::vector<PetscInt> d_nnz(local, 0), o_nnz(local, 0);
          {
            std::vector<std::vector<PetscInt>> cols(local);
            for (const auto &[i, j, v] : A.entries)
              if (PetscInt(i) >= lo && PetscInt(i) < hi)
                cols[i - lo].push_back(j);
            for (PetscInt r = 0; r < local; ++r)
              {
                auto &c = cols[r];
                std::sort(c.begin(), c.end());
                c.erase(std::unique(c.begin(), c.end()), c.end());
                for (const PetscInt j : c)
                  ++((j >= lo && j < hi) ? d_nnz : o_nnz)[r];
              }
          }
          Mat P;
          check(MatCreate(comm, &P), "MatCreate");
          check(MatSetSizes(P, local, local, n, n), "MatSetSizes");
          check(MatSetType(P, MATAIJ), "MatSetType");
          check(MatXAIJSetPreallocation(
                  P, 1, d_nnz.data(), o_nnz.data(), nullptr, nullptr),
                "preallocation");
          for (const auto &[i, j, v] : A.entries)
            if (PetscInt(i) >= lo && PetscInt(i) < hi)
              check(MatSetValue(P, i, j, v, ADD_VALUES), "MatSetValue");
          check(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY), "MatAssembly");
          check(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY), "MatAssembly");
          A.entries.clear();
          A.entries.shrink_to_fit();
          MatInfo info;
          check(MatGetInfo(P, MAT_GLOBAL_SUM, &info), "MatGetInfo");
          nonzeros = std::size_t(info.nz_used);

          // symmetric: |A - A^T|_F <= 1e-12 |A|_F
          bool symmetric = false;
          {
            Mat       T;
            PetscReal norm, asymmetry;
            check(MatTranspose(P, MAT_INITIAL_MATRIX, &T), "MatTranspose");
            check(MatAXPY(T, -1., P, DIFFERENT_NONZERO_PATTERN), "MatAXPY");
            check(MatNorm(T, NORM_FROBENIUS, &asymmetry), "MatNorm");
            check(MatNorm(P, NORM_FROBENIUS, &norm), "MatNorm");
            MatDestroy(&T);
            symmetric = asymmetry <= 1e-12 * norm;
          }
          if (solver == "mumps-ldlt" && !symmetric)
            throw std::runtime_error(
              "mumps-ldlt: K + s M of point " + point +
              " is not symmetric (friction); use mumps-lu");
          KSP ksp;
          PC  pc;
          check(KSPCreate(comm, &ksp), "KSPCreate");
          check(KSPSetOperators(ksp, P, P), "KSPSetOperators");
          check(KSPGetPC(ksp, &pc), "KSPGetPC");
          MatNullSpace space = nullptr;
          if (solver.rfind("mumps", 0) == 0)
            {
              check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
              check(PCSetType(pc, solver == "mumps-ldlt" ? PCCHOLESKY : PCLU),
                    "PCSetType");
              check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS),
                    "PCFactorSetMatSolverType");
              if (solver == "mumps-lu-blr")
                {
                  check(PetscOptionsSetValue(nullptr,
                                             "-mat_mumps_icntl_35",
                                             "1"),
                        "options");
                  check(PetscOptionsSetValue(nullptr,
                                             "-mat_mumps_cntl_7",
                                             std::to_string(tol).c_str()),
                        "options");
                }
            }
          else
            {
              check(KSPSetType(ksp, symmetric ? KSPCG : KSPGMRES),
                    "KSPSetType");
              if (!symmetric)
                check(KSPGMRESSetRestart(ksp, 100), "KSPGMRESSetRestart");
              check(KSPSetTolerances(ksp, tol, 0., PETSC_DEFAULT, 10000),
                    "KSPSetTolerances");
              if (solver == "amg-hypre")
                {
                  check(PCSetType(pc, PCHYPRE), "PCSetType");
                  check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
                }
              else
                {
                  check(PCSetType(pc, solver == "amg-gamg" ? PCGAMG : PCML),
                        "PCSetType");
                  space = rigid_body_modes(P, dofs);
                  check(MatSetNearNullSpace(P, space), "MatSetNearNullSpace");
                }
            }
          check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
          Vec x, b, e;
          check(MatCreateVecs(P, &x, &b), "MatCreateVecs");
          check(VecDuplicate(x, &e), "VecDuplicate");
          before       = memory_mb(false, comm);
          const auto t = std::chrono::steady_clock::now();
          check(KSPSetUp(ksp), "KSPSetUp");
          check(PCSetUp(pc), "PCSetUp (the factorisation or the hierarchy)");
          setup = seconds_since(t);
          if (solver.rfind("mumps", 0) == 0)
            {
              Mat      F;
              PetscInt used;
              check(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix");
              check(MatMumpsGetInfog(F, 22, &used), "MatMumpsGetInfog");
              factor = used;
            }
          for (unsigned int k = 0; k < n_rhs; ++k)
            {
              const auto xs = exact_solution(n, k);
              for (PetscInt i = lo; i < hi; ++i)
                check(VecSetValue(e, i, xs[i], INSERT_VALUES), "VecSetValue");
              check(VecAssemblyBegin(e), "VecAssembly");
              check(VecAssemblyEnd(e), "VecAssembly");
              check(MatMult(P, e, b), "MatMult");
              const auto t1 = std::chrono::steady_clock::now();
              check(KSPSolve(ksp, b, x), "KSPSolve");
              solve += seconds_since(t1);
              KSPConvergedReason reason;
              PetscInt           its;
              check(KSPGetConvergedReason(ksp, &reason), "reason");
              check(KSPGetIterationNumber(ksp, &its), "iterations");
              if (reason < 0)
                throw std::runtime_error(solver + ": right-hand side " +
                                         std::to_string(k) +
                                         " did not converge (PETSc reason " +
                                         std::to_string(int(reason)) + ")");
              iterations += its;
              PetscReal ne, nd;
              check(VecNorm(e, NORM_2, &ne), "VecNorm");
              check(VecAXPY(x, -1., e), "VecAXPY");
              check(VecNorm(x, NORM_2, &nd), "VecNorm");
              error = std::max(error, double(nd / ne));
            }
          VecDestroy(&x);
          VecDestroy(&b);
          VecDestroy(&e);
          KSPDestroy(&ksp);
          if (space)
            MatNullSpaceDestroy(&space);
          MatDestroy(&P);
        }
      const double peak = memory_mb(true, comm);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        std::cout << solver << ',' << ranks << ',' << n << ',' << nonzeros
                  << ',' << setup << ',' << solve / n_rhs << ','
                  << iterations / n_rhs << ',' << error << ',' << before << ','
                  << peak << ',' << factor << std::endl;
    }
  catch (const std::exception &e)
    {
      std::cerr << "squeal-bench-linear-solvers: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}
