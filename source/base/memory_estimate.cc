// The memory a run is about to need (see the header).

#include <deal.II/base/utilities.h>

#include <squeal/base/memory_estimate.h>

#include <petscsys.h>

#include <malloc.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <stdexcept>
#include <string>

namespace squeal
{
  using namespace dealii;

  double
  factorisation_bytes(const std::size_t             nonzeros,
                      const types::global_dof_index n_dofs,
                      const bool                    symmetric)
  {
    // MUMPS INFOG(22) on the coarse brake: LU 619 MB, LDL^T 355 MB for
    // 12.9 million nonzeros
    const double n0 = 91374.;
    return (symmetric ? 28. : 48.) * double(nonzeros) *
           std::cbrt(std::max(1., double(n_dofs) / n0));
  }

  namespace
  {
    std::string storage     = "in core"; // or "auto", "out of core"
    bool        out_of_core = false;

    // every MUMPS factor squeal creates: without a prefix, and SLEPc's
    // spectral transformation's
    constexpr std::array<const char *, 2> ooc_options{
      {"-mat_mumps_icntl_22", "-st_mat_mumps_icntl_22"}};

    void
    switch_out_of_core(const bool on)
    {
      for (const char *name : ooc_options)
        if ((on ? PetscOptionsSetValue(nullptr, name, "1") :
                  PetscOptionsClearValue(nullptr, name)) != 0)
          throw std::runtime_error(
            std::string("out-of-core factorisation: PETSc refused the "
                        "option ") +
            name);
      out_of_core = on;
    }
  } // namespace

  void
  set_factor_storage(const std::string &mode, const std::string &directory)
  {
    if (mode != "auto" && mode != "in core" && mode != "out of core")
      throw std::runtime_error("Linear solver/Out-of-core factorisation = '" +
                               mode +
                               "': allowed are auto, in core, out of core");
    storage = mode;
    if (!directory.empty())
      setenv("MUMPS_OOC_TMPDIR", directory.c_str(), 1);
    if (out_of_core || mode == "out of core")
      switch_out_of_core(mode == "out of core");
  }

  bool
  factors_out_of_core()
  {
    return out_of_core;
  }

  double
  available_memory_mb(MPI_Comm comm)
  {
    double   available = 0.;
    MPI_Comm node;
    MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    if (Utilities::MPI::this_mpi_process(node) == 0)
      {
        std::ifstream meminfo("/proc/meminfo");
        std::string   key;
        double        kb = 0.;
        while (meminfo >> key >> kb)
          {
            if (key == "MemAvailable:")
              {
                available = kb / 1024.;
                break;
              }
            meminfo.ignore(256, '\n');
          }
      }
    MPI_Comm_free(&node);
    return Utilities::MPI::sum(available, comm);
  }

  double
  report_memory_estimate(MPI_Comm                      comm,
                         std::ostream                 *out,
                         const types::global_dof_index n_dofs,
                         const double                  extra_bytes,
                         const std::string            &what,
                         const double                  factor_bytes)
  {
    // the heap's free pages back to the system: "in use" is then what the
    // run holds, not what it held at its largest so far
    malloc_trim(0);
    Utilities::System::MemoryStats stats;
    Utilities::System::get_memory_stats(stats);
    const double mb  = 1024. * 1024.;
    const double now = Utilities::MPI::sum(double(stats.VmRSS), comm) / 1024.;
    const double in_core = now + extra_bytes / mb;
    // what the run may grow into: what it holds plus what is free
    const double available = available_memory_mb(comm) + now;
    const bool   switched  = storage == "auto" && !out_of_core &&
                          factor_bytes > 0. && in_core > available;
    if (switched)
      switch_out_of_core(true);
    // out of core MUMPS holds the largest fronts: 16 % of the factors on
    // the default brake's preload (peak 4501 MB in core, 2786 MB out of
    // core, factors' estimate 2045 MB); a quarter is counted
    const double peak =
      out_of_core ? in_core - 0.75 * factor_bytes / mb : in_core;
    if (out)
      {
        const double per_dof = 1024. / std::max(1., double(n_dofs));
        *out << std::fixed << std::setprecision(0) << "Memory: " << now
             << " MB in use (" << std::setprecision(1) << now * per_dof
             << " kB per DoF); estimated peak " << std::setprecision(0) << peak
             << " MB (" << std::setprecision(1) << peak * per_dof
             << " kB per DoF) with " << what;
        if (out_of_core && factor_bytes > 0.)
          *out << std::setprecision(0) << ", MUMPS's factors out of core"
               << (switched ?
                     " (in core " + std::to_string(int(in_core)) +
                       " MB, above the " + std::to_string(int(available)) +
                       " MB available to the run)" :
                     "");
        if (peak > available)
          *out
            << std::setprecision(0) << "; more than the " << available
            << " MB available to the run: the system may stop the run (run it on "
               "more nodes under mpirun"
            << (!out_of_core && factor_bytes > 0. ?
                  ", or set Linear solver/Out-of-core factorisation = "
                  "auto" :
                  "")
            << ")";
        *out << std::defaultfloat << std::setprecision(6) << std::endl;
      }
    return peak;
  }
} // namespace squeal
