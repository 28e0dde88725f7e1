// Anisotropic bodies of a mesh-file scene, through the whole structural
// model: the first modes of an orthotropic block against the closed form.
//
// A block Lx x Ly x Lz on sliding supports (each face holds its normal
// displacement only) has the modes
//   u_x = A sin(kx x) cos(ky y) cos(kz z), u_y = B cos sin cos,
//   u_z = C cos cos sin,  k = (l pi / Lx, m pi / Ly, n pi / Lz),
// for l, m, n >= 0 not all zero: rho omega^2 (A, B, C) = Gamma(k) (A, B, C)
// with the Christoffel matrix Gamma_ik = C_ijkl k_j k_l of an orthotropic law
// in the block's axes (the components whose k vanishes drop out). The
// stiffness tensor of the reference is the inverse of the 6 x 6 compliance
// computed here (Jones, Mechanics of Composite Materials, eq. 2.49), not the
// library's.
// 1. material axes along the block's: the first 12 frequencies of the
//    scene (degree 3, 4 x 3 x 2 cells) against the closed form: within
//    5e-4 (measured 0.3-2.6e-4, the discretisation error) and never below
//    it (a conforming discretisation bounds frequencies from above); an
//    isotropic or a wrongly turned law misses by percents;
// 2. material axes turned 90 degrees about z (axis1 = global y): the
//    closed form of the permuted tensor, the same checks;
// 3. cylindrical frames about far axes (1e5 block lengths away) reproduce
//    1. and 2.: axis parallel to z through (-D, 0, 0) (radial = x) and
//    through (0, -D, 0) (radial = y, tangential = -x), 1e-8;
// 4. bad laws get one error naming the item.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <squeal/eigen/qep_solver.h>
#include <squeal/io/mesh_file.h>
#include <squeal/physics/structural_model.h>

#include "test_tools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace squeal;
using test_tools::check;
using test_tools::error_of;

namespace
{
  const double Lx = 0.04, Ly = 0.03, Lz = 0.02; // m
  const double rho = 2500.;                     // kg/m^3
  // friction-material-like constants [Pa], stiffer in the pad's plane
  const double E1 = 12e9, E2 = 10e9, E3 = 4e9;
  const double nu12 = 0.25, nu13 = 0.2, nu23 = 0.18;
  const double G12 = 4e9, G13 = 1.8e9, G23 = 1.6e9;

  // The 6 x 6 Voigt stiffness (11, 22, 33, 23, 13, 12) of the constants.
  FullMatrix<double>
  voigt_stiffness()
  {
    FullMatrix<double> S(6, 6), C(6, 6);
    S(0, 0) = 1. / E1;
    S(1, 1) = 1. / E2;
    S(2, 2) = 1. / E3;
    S(0, 1) = S(1, 0) = -nu12 / E1;
    S(0, 2) = S(2, 0) = -nu13 / E1;
    S(1, 2) = S(2, 1) = -nu23 / E2;
    S(3, 3)           = 1. / G23;
    S(4, 4)           = 1. / G13;
    S(5, 5)           = 1. / G12;
    C.invert(S);
    return C;
  }

  // The first N closed-form frequencies [Hz] of the block for the Voigt
  // stiffness C in the block's axes.
  std::vector<double>
  closed_form(const FullMatrix<double> &C, const unsigned int N)
  {
    std::vector<double> f;
    for (unsigned int l = 0; l < 6; ++l)
      for (unsigned int m = 0; m < 6; ++m)
        for (unsigned int n = 0; n < 6; ++n)
          {
            if (l + m + n == 0)
              continue;
            const std::array<double, 3> k{
              {l * M_PI / Lx, m * M_PI / Ly, n * M_PI / Lz}};
            // Gamma in Voigt terms: shear index of the pair (i, j)
            const unsigned int shear[3][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}};
            FullMatrix<double> G(3, 3);
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int q = 0; q < 3; ++q)
                for (unsigned int j = 0; j < 3; ++j)
                  for (unsigned int r = 0; r < 3; ++r)
                    G(i, q) += C(shear[i][j], shear[q][r]) * k[j] * k[r];
            std::vector<unsigned int> kept;
            for (unsigned int i = 0; i < 3; ++i)
              if (k[i] != 0.)
                kept.push_back(i);
            LAPACKFullMatrix<double> g(kept.size(), kept.size());
            for (unsigned int a = 0; a < kept.size(); ++a)
              for (unsigned int b = 0; b < kept.size(); ++b)
                g(a, b) = G(kept[a], kept[b]);
            g.compute_eigenvalues();
            for (unsigned int a = 0; a < kept.size(); ++a)
              {
                const double w2 = std::real(g.eigenvalue(a)) / rho;
                f.push_back(std::sqrt(w2) / (2 * M_PI));
              }
          }
    std::sort(f.begin(), f.end());
    f.resize(N);
    return f;
  }

  // The block's mesh and face sets as an Abaqus file.
  void
  write_block(const std::string &file)
  {
    Triangulation<3> tria;
    GridGenerator::subdivided_hyper_rectangle(
      tria, {4, 3, 2}, Point<3>(), Point<3>(Lx, Ly, Lz), true);
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_material_id(0); // colorize numbers the cells too
    io::NamedSets sets;
    sets.source = "the test's block";
    sets.collect_from_ids(
      tria,
      {{0, "block"}},
      {{0, "x0"}, {1, "x1"}, {2, "y0"}, {3, "y1"}, {4, "z0"}, {5, "z1"}});
    io::write_abaqus(tria, sets, file);
  }

  // The parameters of the block scene with body keys LAW.
  parameters::AllParameters
  block_parameters(const std::string &law, ParameterHandler &handler)
  {
    std::ofstream("block.prm")
      << "subsection Scene\n  set Type = mesh file\n"
         "  subsection Mesh file\n    set File = block.inp\n"
         "    set Bodies = block: set=BLOCK, rho=2500, "
      << law
      << "\n    set Holds = x0: set=X0, components=x; x1: set=X1, "
         "components=x; y0: set=Y0, components=y; y1: set=Y1, components=y; "
         "z0: set=Z0, components=z; z1: set=Z1, components=z\n"
         "  end\nend\n"
         "subsection Mesh\n  set Finite element degree = 3\nend\n"
         "subsection Damping\n  set Alpha = 0\n"
         "  set Beta = 0\nend\n"
         "subsection Eigensolver\n  set Minimum frequency = 1000\n"
         "  set Maximum frequency = 45000\nend\n";
    parameters::AllParameters prm;
    prm.read(handler, "block.prm");
    return prm;
  }

  // The first N frequencies [Hz] of the scene's structural model.
  std::vector<double>
  model_frequencies(const std::string &law, const unsigned int N)
  {
    ParameterHandler handler;
    auto f = test_tools::undamped_frequencies(block_parameters(law, handler),
                                              1000.,
                                              45000.);
    f.resize(std::min<std::size_t>(f.size(), N));
    return f;
  }

  std::string
  orthotropic_keys()
  {
    std::ostringstream s;
    s << "law=orthotropic, E1=" << E1 << ", E2=" << E2 << ", E3=" << E3
      << ", nu12=" << nu12 << ", nu13=" << nu13 << ", nu23=" << nu23
      << ", G12=" << G12 << ", G13=" << G13 << ", G23=" << G23;
    return s.str();
  }

  void
  compare(const std::string         &name,
          const std::vector<double> &f,
          const std::vector<double> &reference,
          const double               tolerance)
  {
    check(name + ": mode count", f.size(), reference.size(), 0.);
    for (unsigned int k = 0; k < std::min(f.size(), reference.size()); ++k)
      {
        check(name + ": mode " + std::to_string(k + 1),
              f[k],
              reference[k],
              tolerance);
        // a conforming discretisation bounds the frequencies from above
        check(name + ": mode " + std::to_string(k + 1) + " not below",
              std::min(f[k] - reference[k] * (1. - 1e-10), 0.),
              0.,
              0.,
              1.);
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int               N = 12;
  write_block("block.inp");

  // 1. material axes along the block's
  const FullMatrix<double> C                 = voigt_stiffness();
  const auto               aligned_reference = closed_form(C, N);
  const auto               aligned = model_frequencies(orthotropic_keys(), N);
  compare("aligned axes", aligned, aligned_reference, 5e-4);

  // 2. material axis 1 along global y, 2 along -x: global (x, y, z) =
  // material (2, 1, 3) up to signs, which the stiffness does not see
  const unsigned int p[6] = {1, 0, 2, 4, 3, 5};
  FullMatrix<double> C_turned(6, 6);
  for (unsigned int i = 0; i < 6; ++i)
    for (unsigned int j = 0; j < 6; ++j)
      C_turned(i, j) = C(p[i], p[j]);
  const auto turned_reference = closed_form(C_turned, N);
  const auto turned =
    model_frequencies(orthotropic_keys() + ", axis1=0 1 0, axis2=-1 0 0", N);
  compare("axes turned about z", turned, turned_reference, 5e-4);

  // 3. cylindrical frames about far axes
  const double D = 1e5 * Lx;
  compare("cylindrical frame, radial = x",
          model_frequencies(orthotropic_keys() +
                              ", frame=cylindrical, axis=0 0 1, centre=" +
                              std::to_string(-D) + " 0.015 0.01",
                            N),
          aligned,
          1e-8);
  compare("cylindrical frame, radial = y",
          model_frequencies(orthotropic_keys() +
                              ", frame=cylindrical, axis=0 0 1, centre=0.02 " +
                              std::to_string(-D) + " 0.01",
                            N),
          turned,
          1e-8);

  // 4. bad laws
  const auto error = [](const std::string &law) {
    return error_of([&]() { model_frequencies(law, 1); });
  };
  const auto has = [](const std::string &message, const std::string &part) {
    const bool ok = message.find(part) != std::string::npos;
    check("error '" + part + "'", ok ? 0. : 1., 0., 0.);
    if (!ok)
      std::cout << "  got: " << message << std::endl;
  };
  has(error("law=plastic, E=1e9, nu=0.3"),
      "item 'block': law = 'plastic': allowed are isotropic, orthotropic");
  has(error("law=orthotropic, E1=1e9"), "item 'block': 'E2=' is required");
  has(error(orthotropic_keys() + ", frame=spherical"),
      "frame = 'spherical': allowed are cartesian and cylindrical");
  has(error(orthotropic_keys() + ", axis1=1 0 0, axis2=2 0 0"),
      "axis1 and axis2 are parallel");
  has(error("law=orthotropic, E1=1e9, E2=1e9, E3=1e9, nu12=0.9, nu13=0.9, "
            "nu23=0.9, G12=1e8, G13=1e8, G23=1e8"),
      "item 'block'");
  return test_tools::n_failures == 0 ? 0 : 1;
}
