// Small helpers shared by the tests: MPI set-up, a relative-error check
// that prints a stable line (numdiff-compared) and records failures so that
// the test also exits non-zero.
#ifndef squeal_tests_test_tools_h
#define squeal_tests_test_tools_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/numerics/vector_tools.h>

#include <squeal/eigen/full_solver.h>
#include <squeal/eigen/mac.h>
#include <squeal/eigen/qep_solver.h>
#include <squeal/eigen/reduced_model.h>
#include <squeal/parameters/parameters.h>
#include <squeal/physics/structural_model.h>

#include "check.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <string>
#include <tuple>
#include <vector>

namespace test_tools
{
  /**
   * The coarse TriboBrake of the tests: degree 1, disc 48 x 6 x 2 cells (or
   * the given counts), pad 4 x 4 x 2, support 10, updated support density.
   */
  inline squeal::parameters::AllParameters
  coarse_tribobrake(const unsigned int around    = 48,
                    const unsigned int radial    = 6,
                    const unsigned int thickness = 2,
                    const unsigned int pad_side  = 4,
                    const unsigned int pad_thick = 2)
  {
    squeal::parameters::AllParameters prm;
    prm.mesh.fe_degree                = 1;
    prm.mesh.disc_cells_circumference = around;
    prm.mesh.disc_cells_radial        = radial;
    prm.mesh.disc_cells_thickness     = thickness;
    prm.mesh.pad_cells_side           = pad_side;
    prm.mesh.pad_cells_thickness      = pad_thick;
    prm.mesh.support_cells_length     = 10;
    prm.materials.support.density     = prm.materials.support_updated_density;
    return prm;
  }

  /** MAC(i, j) between mode i of @p a and mode j of @p b (reduced coordinates). */
  inline Eigen::MatrixXd
  mac_matrix(const std::vector<Eigen::VectorXcd> &a,
             const std::vector<Eigen::VectorXcd> &b)
  {
    Eigen::MatrixXd mac(a.size(), b.size());
    for (unsigned int i = 0; i < a.size(); ++i)
      for (unsigned int j = 0; j < b.size(); ++j)
        mac(i, j) = squeal::eigen::complex_mac(a[i], b[j]);
    return mac;
  }

  /**
   * The two-degree-of-freedom model of Hoffmann et al. (2002)
   * (verification A2) as matrix parts: M = I, K = [[a, c - mu k3], [c, b]]
   * with b carried by a part scaled by the parameter "b"
   * and k3 by the friction part. a = 5e6, b = 6e6 (default), c = 1e6,
   * k3 = 4e6 N/m, m = 1 kg.
   */
  struct HoffmannTwoDof
  {
    static constexpr double    a = 5e6, b = 6e6, c = 1e6, k3 = 4e6;
    squeal::eigen::PETScMatrix M, rest, pad, friction;
    HoffmannTwoDof()
    {
      using namespace dealii;
      IndexSet owned(2);
      if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        owned.add_range(0, 2);
      DynamicSparsityPattern dsp(2, 2);
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int j = 0; j < 2; ++j)
          dsp.add(i, j);
      for (auto *A : {&M, &rest, &pad, &friction})
        A->reinit(owned, owned, dsp, MPI_COMM_WORLD);
      if (owned.n_elements() > 0)
        {
          M.set(0, 0, 1.);
          M.set(1, 1, 1.);
          rest.set(0, 0, a);
          rest.set(0, 1, c);
          rest.set(1, 0, c);
          pad.set(1, 1, 1.);
          friction.set(0, 1, -k3);
        }
      for (auto *A : {&M, &rest, &pad, &friction})
        A->compress(VectorOperation::insert);
    }
    /**
     * The parts M (damped by "alpha"), K_rest and K_pad (scaled by "b",
     * both damped by "beta") and K_t (times "mu").
     */
    squeal::physics::MatrixParts
    parts() const
    {
      using Kind = squeal::physics::MatrixParts::Kind;
      squeal::physics::MatrixParts p;
      p.parts     = {{&M, Kind::mass, "M", "", 1., "", "alpha"},
                     {&rest, Kind::stiffness, "K_rest", "", 1., "", "beta"},
                     {&pad, Kind::stiffness, "K_pad", "b", 1., "", "beta"},
                     {&friction, Kind::interface_friction, "K_t", "", 1., "mu"}};
      p.reference = point(1., 0.);
      return p;
    }
    /** The point with K_22 = @p b_value, friction mu, Rayleigh alpha, beta. */
    static squeal::parameters::ScalarPoint
    point(const double b_value,
          const double mu,
          const double alpha = 0,
          const double beta  = 0)
    {
      squeal::parameters::ScalarPoint p;
      p.add("b", b_value);
      p.add("mu", mu);
      p.add("alpha", alpha);
      p.add("beta", beta);
      return p;
    }
  };

  /**
   * Two blocks meeting at z = 0 without shared vertices (so that a contact
   * pair or a mortar interface joins them, never the mesh): the lower one
   * [0, w]^2 x [-h, 0] in n_lower x n_lower x 1 cells of material
   * @p lower, the upper one [0, w]^2 x [0, h] in n_upper x n_upper x 1
   * of material @p upper [m].
   */
  inline void
  stacked_blocks(const unsigned int               n_lower,
                 const unsigned int               n_upper,
                 const double                     w,
                 const double                     h,
                 const dealii::types::material_id lower,
                 const dealii::types::material_id upper,
                 dealii::Triangulation<3>        &tria)
  {
    using namespace dealii;
    std::vector<Point<3>>    vertices;
    std::vector<CellData<3>> cells;
    for (const auto &[n, z0, material] :
         {std::tuple{n_lower, -h, lower}, std::tuple{n_upper, 0., upper}})
      {
        Triangulation<3> block;
        GridGenerator::subdivided_hyper_rectangle(block,
                                                  {n, n, 1u},
                                                  Point<3>(0, 0, z0),
                                                  Point<3>(w, w, z0 + h));
        const unsigned int offset = vertices.size();
        vertices.insert(vertices.end(),
                        block.get_vertices().begin(),
                        block.get_vertices().end());
        for (const auto &cell : block.active_cell_iterators())
          {
            CellData<3> c;
            for (const auto v : cell->vertex_indices())
              c.vertices[v] = offset + cell->vertex_index(v);
            c.material_id = material;
            cells.push_back(c);
          }
      }
    tria.create_triangulation(vertices, cells, SubCellData());
  }

  /**
   * u^T A u for the field @p f (3 components, m) interpolated on
   * @p model's DoFs: twice the energy of @p A (a stiffness [J], a mass
   * [kg m^2] or a damping matrix) in that field.
   */
  inline double
  field_energy(const squeal::physics::StructuralModel &model,
               const squeal::physics::PETScMatrix     &A,
               const dealii::Function<3>              &f)
  {
    squeal::physics::PETScVector u(model.locally_owned_dofs, MPI_COMM_WORLD),
      Au(model.locally_owned_dofs, MPI_COMM_WORLD);
    dealii::VectorTools::interpolate(model.mapping, model.dof_handler, f, u);
    A.vmult(Au, u);
    return u * Au;
  }

  /**
   * The natural frequencies [Hz] in (f_min, f_max) of the undamped
   * structure of @p prm (bodies, springs, masses; no friction) at its
   * nominal point with the named parameters @p changes set, ascending:
   * K phi = omega^2 M phi with SLEPc.
   */
  inline std::vector<double>
  undamped_frequencies(
    const squeal::parameters::AllParameters           &prm,
    const double                                       f_min,
    const double                                       f_max,
    const std::vector<std::pair<std::string, double>> &changes = {})
  {
    using namespace squeal;
    dealii::ConditionalOStream quiet(std::cout, false);
    physics::StructuralModel   model(prm, MPI_COMM_WORLD);
    model.setup_and_assemble(quiet);
    const physics::MatrixParts parts = model.parts();
    parameters::ScalarPoint    p     = model.scene->nominal_point();
    for (const auto &[name, value] : changes)
      p.set(name, value);
    const auto           c = parts.coefficients(p);
    physics::PETScMatrix K, M;
    parts.combine(c.structural, K);
    parts.combine(c.mass, M);
    eigen::BandOptions band;
    band.f_min            = f_min;
    band.f_max            = f_max;
    band.target_frequency = 100.;
    std::vector<double> f;
    for (const auto &m : eigen::solve_undamped(M, K, band, 1., true, quiet))
      if (const double x = std::sqrt(std::real(m.omega2)) / (2 * M_PI);
          x > f_min && x < f_max) // not NaN, in the band
        f.push_back(x);
    return f;
  }
} // namespace test_tools

#endif
