// The tangential (shear) stiffness of a contact pair, `<pair>.k_t`, in a
// mesh-file scene: a stiff pad block a x a x h (E = 5e12 Pa) on a held
// stiff base block, the two meeting at z = 0 on non-matching meshes and
// joined only by the CEA's interface (k_n, k_t; mu = 0).
// 1. Energies of the assembled symmetric stiffness K_s + K_n + K_st at the
//    nominal point: a pad translation delta in x stores k_t A delta^2, one
//    in z k_n A delta^2 (1e-8: the rigid motion's zero energy in the
//    blocks, 1e4 times stiffer than the layer, cancels to rounding only).
// 2. The rigid pad on its elastic layer (six modes; the blocks' own modes
//    lie above 300 kHz, so rigid-body values hold to about (f / f_el)^2):
//      vertical      omega^2 = k_n A / m
//      twist         omega^2 = k_t J / I_z = k_t A / m  (J = a^4 / 6)
//      in-plane x (and y, a doublet): translation u and tilt theta about
//      the centre of mass (h / 2 above the face) from
//        K = [k_t A, -k_t A h/2; -k_t A h/2, k_t A h^2/4 + k_n a^4/12],
//        M = diag(m, m (a^2 + h^2) / 12),
//    all six within 1e-4, with k_t given on the pair's item, and again
//    with k_t from Interface/Tangential stiffness moved through the named
//    parameter `layer.k_t` of the scene (the affine part).
// 3. Without the part (k_t = 0, not varied) the model has no such part;
//    a negative k_t= is refused with one error naming the pair.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/vector_tools.h>

#include <squeal/eigen/qep_solver.h>
#include <squeal/io/mesh_file.h>
#include <squeal/physics/structural_model.h>

#include <Eigen/Dense>

#include "test_tools.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

using namespace dealii;
using namespace squeal;
using test_tools::check;
using test_tools::error_of;

namespace
{
  const double a = 0.02, h = 0.01;              // m: pad face and height
  const double E = 5e12, nu = 0.3, rho = 7800.; // stiff blocks
  const double k_n = 6e9, k_t = 3e9;            // N/m^3

  // Two blocks meeting at z = 0 without shared vertices: base [0, a]^2 x
  // [-h, 0] in 3 x 3 cells (material 0), pad [0, a]^2 x [0, h] in 2 x 2
  // (material 1); faces: base bottom 1, base top 2, pad bottom 3.
  void
  write_blocks(const std::string &file)
  {
    Triangulation<3> both;
    test_tools::stacked_blocks(3, 2, a, h, 0, 1, both);
    for (const auto &cell : both.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            const double z   = cell->face(f)->center()[2];
            const bool   pad = cell->material_id() == 1;
            cell->face(f)->set_boundary_id(std::abs(z + h) < 1e-12     ? 1 :
                                           std::abs(z) < 1e-12 && !pad ? 2 :
                                           std::abs(z) < 1e-12 && pad  ? 3 :
                                                                         0);
          }
    io::NamedSets sets;
    sets.source = "the test's blocks";
    sets.collect_from_ids(both,
                          {{0, "base"}, {1, "pad"}},
                          {{1, "base bottom"},
                           {2, "base top"},
                           {3, "pad face"}});
    io::write_abaqus(both, sets, file);
  }

  parameters::AllParameters
  read(const std::string &pair, ParameterHandler &handler)
  {
    std::ostringstream body;
    body << "E=" << E << ", nu=" << nu << ", rho=" << rho;
    std::ofstream("shear.prm")
      << "subsection Scene\n  set Type = mesh file\n"
         "  subsection Mesh file\n    set File = shear.inp\n"
         "    set Bodies = base: set=BASE, "
      << body.str() << "; pad: set=PAD, " << body.str()
      << "\n    set Holds = bottom: set=BASE_BOTTOM\n"
         "    set Contact pairs = "
      << pair
      << "\n  end\nend\n"
         "subsection Interface\n  set Tangential stiffness = "
      << 2 * k_t
      << "\nend\n"
         "subsection Mesh\n  set Finite element degree = 2\nend\n"
         "subsection Damping\n  set Alpha = 0\n  set Beta = 0\nend\n";
    parameters::AllParameters prm;
    prm.read(handler, "shear.prm");
    return prm;
  }

  // The six rigid-pad frequencies [Hz], ascending.
  std::vector<double>
  rigid_pad(const double kn, const double kt)
  {
    const double    A = a * a, m = rho * A * h;
    Eigen::Matrix2d K, M         = Eigen::Matrix2d::Zero();
    K << kt * A, -kt * A * h / 2, -kt * A * h / 2,
      kt * A * h * h / 4 + kn * a * a * a * a / 12;
    M(0, 0) = m;
    M(1, 1) = m * (a * a + h * h) / 12;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> rocking(K, M);
    std::vector<double> f{kn * A / m, kt * A / m};
    for (int i = 0; i < 2; ++i)
      f.insert(f.end(), 2, rocking.eigenvalues()[i]);
    for (double &x : f)
      x = std::sqrt(x) / (2 * numbers::PI);
    std::sort(f.begin(), f.end());
    return f;
  }

  // u^T K u for u = delta e_c on the pad's DoFs (by cell: the two blocks'
  // nodes at z = 0 share their coordinates), 0 on the base's
  double
  pad_translation_energy(const physics::StructuralModel &model,
                         const physics::PETScMatrix     &K,
                         const unsigned int              c,
                         const double                    delta)
  {
    physics::PETScVector u(model.locally_owned_dofs, MPI_COMM_WORLD),
      Ku(model.locally_owned_dofs, MPI_COMM_WORLD);
    std::vector<types::global_dof_index> dofs(model.fe.n_dofs_per_cell());
    for (const auto &cell : model.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->center()[2] > 0.)
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (model.fe.system_to_component_index(i).first == c)
              u(dofs[i]) = delta;
        }
    u.compress(VectorOperation::insert);
    K.vmult(Ku, u);
    return u * Ku;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    write_blocks("shear.inp");
  MPI_Barrier(MPI_COMM_WORLD);

  std::ostringstream item;
  item << "layer: slave=PAD_FACE, master=BASE_TOP, sliding=1 0 0, mu=0, k_n="
       << k_n;
  for (const bool on_item : {true, false})
    {
      ParameterHandler handler;
      const auto       prm =
        read(item.str() + (on_item ? ", k_t=" + std::to_string(k_t) : ""),
             handler);
      physics::StructuralModel model(prm, MPI_COMM_WORLD);
      model.setup_and_assemble(quiet);
      const physics::MatrixParts parts = model.parts();
      parameters::ScalarPoint    p     = model.scene->nominal_point();
      // from the Interface default 2 k_t, moved by the named parameter
      if (!on_item)
        p.set("layer.k_t", k_t);
      const std::string tag =
        on_item ? "k_t on the item: " : "k_t moved from 2 k_t by layer.k_t: ";
      const auto           c = parts.coefficients(p);
      physics::PETScMatrix K, M;
      parts.combine(c.symmetric_stiffness, K);
      parts.combine(c.mass, M);

      const double delta = 1e-6, A = a * a;
      check(tag + "pad moved by delta in x: k_t A delta^2",
            pad_translation_energy(model, K, 0, delta),
            k_t * A * delta * delta,
            1e-8);
      check(tag + "pad moved by delta in z: k_n A delta^2",
            pad_translation_energy(model, K, 2, delta),
            k_n * A * delta * delta,
            1e-8);

      const auto         expected = rigid_pad(k_n, k_t);
      eigen::BandOptions band;
      band.f_min            = 0.5 * expected.front();
      band.f_max            = 1.5 * expected.back();
      band.target_frequency = expected.front();
      std::vector<double> f;
      for (const auto &m : eigen::solve_undamped(M, K, band, 1., true, quiet))
        if (const double x = std::sqrt(std::real(m.omega2)) / (2 * M_PI);
            x > band.f_min && x < band.f_max)
          f.push_back(x);
      check(tag + "six interface modes in the band",
            f.size(),
            expected.size(),
            0);
      for (unsigned int i = 0; i < std::min(f.size(), expected.size()); ++i)
        {
          check(tag + "rigid-pad mode " + std::to_string(i + 1),
                f[i],
                expected[i],
                1e-4);
          test_tools::verbose()
            << "mode " << i + 1 << ": " << f[i] << " Hz, rigid pad "
            << expected[i] << " Hz" << std::endl;
        }
    }

  {
    // k_t = 0 and not varied: no tangential part at all
    ParameterHandler         handler;
    auto                     prm = read(item.str() + ", k_t=0", handler);
    physics::StructuralModel model(prm, MPI_COMM_WORLD);
    model.varied = std::set<std::string>();
    model.setup_and_assemble(quiet);
    unsigned int n_shear = 0;
    for (const auto &part : model.parts().parts)
      n_shear += part.scale == "layer.k_t";
    check("k_t = 0, not varied: no tangential part", n_shear, 0, 0);
    ParameterHandler  h;
    const std::string e =
      error_of([&]() { scene::make_scene(read(item.str() + ", k_t=-1", h)); });
    test_tools::check_message("k_t=-1: one error naming the pair",
                              e,
                              {"'layer'", "k_t >= 0"});
  }
  return test_tools::finish();
}
