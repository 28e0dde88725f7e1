// The memory a run is about to need (see the header).

#include <deal.II/base/utilities.h>

#include <squeal/base/memory_estimate.h>

#include <algorithm>
#include <cmath>
#include <iomanip>

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

  double
  report_memory_estimate(MPI_Comm                      comm,
                         std::ostream                 *out,
                         const types::global_dof_index n_dofs,
                         const double                  extra_bytes,
                         const std::string            &what)
  {
    Utilities::System::MemoryStats stats;
    Utilities::System::get_memory_stats(stats);
    const double now  = Utilities::MPI::sum(double(stats.VmRSS), comm) / 1024.;
    const double peak = now + extra_bytes / (1024. * 1024.);
    if (out)
      {
        const double per_dof = 1024. / std::max(1., double(n_dofs));
        *out << std::fixed << std::setprecision(0) << "Memory: " << now
             << " MB in use (" << std::setprecision(1) << now * per_dof
             << " kB per DoF); estimated peak " << std::setprecision(0) << peak
             << " MB (" << std::setprecision(1) << peak * per_dof
             << " kB per DoF) with " << what << std::defaultfloat
             << std::setprecision(6) << std::endl;
      }
    return peak;
  }
} // namespace squeal
