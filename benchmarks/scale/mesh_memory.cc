// squeal-bench-mesh-memory: what each rank holds of a mesh read from a Gmsh
// file, with deal.II's three parallel triangulations, for choosing the one
// squeal's analyses run on by measurement (benchmarks/scale/README.md).
//
// usage: squeal-bench-mesh-memory MSH DEGREE KIND [REFINE]
//   MSH     a Gmsh file of hexahedra (scripts/make_brake.py writes them)
//   DEGREE  the degree of the vector-valued FE_Q on it (3 components)
//   KIND    shared | distributed | fully-distributed:
//           parallel::shared::Triangulation (every rank the whole mesh,
//           METIS partition; what squeal uses), parallel::distributed::
//           Triangulation (p4est; the file's cells are its coarse cells),
//           parallel::fullydistributed::Triangulation (each rank its cells
//           and a layer of ghosts, from a description built on one rank
//           after another: TriangulationDescription::Utilities::
//           create_description_from_triangulation_in_groups)
//   REFINE  global refinements after reading (default 0; p4est refines
//           only each rank's cells, the other two every cell; the fully
//           distributed mesh is refined before it is described)
// Prints one line per rank: kind,rank,ranks,cells_stored,cells_owned,
// dofs_owned,dofs_relevant,triangulation_MB,dof_handler_MB,rss_mesh_MB,
// rss_dofs_MB,rss_pattern_MB, where the triangulation and DoF handler
// figures are deal.II's memory_consumption(), rss_* the rank's VmRSS after
// the mesh, after distributing the DoFs and after building the sparsity
// pattern of its locally owned rows (DynamicSparsityPattern, then
// distributed to the ranks as squeal's assembly does), and then a line
// "total,<kind>,<ranks>,<VmHWM summed over the ranks in MB>".

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace dealii;

namespace
{
  double
  rss_mb()
  {
    Utilities::System::MemoryStats s;
    Utilities::System::get_memory_stats(s);
    return s.VmRSS / 1024.;
  }

  void
  read_mesh(Triangulation<3>  &tria,
            const std::string &file,
            const unsigned int refinements)
  {
    std::ifstream in(file);
    if (!in)
      throw std::runtime_error("cannot open the mesh file " + file);
    GridIn<3> grid_in(tria);
    grid_in.read_msh(in);
    tria.refine_global(refinements);
  }

  void
  run(const std::string &file,
      const unsigned int degree,
      const std::string &kind,
      const unsigned int refinements)
  {
    const MPI_Comm                    comm = MPI_COMM_WORLD;
    std::unique_ptr<Triangulation<3>> tria;
    if (kind == "shared")
      {
        tria = std::make_unique<parallel::shared::Triangulation<3>>(
          comm,
          Triangulation<3>::none,
          true,
          parallel::shared::Triangulation<3>::partition_metis);
        read_mesh(*tria, file, refinements);
      }
    else if (kind == "distributed")
      {
        tria = std::make_unique<parallel::distributed::Triangulation<3>>(comm);
        read_mesh(*tria, file, refinements);
      }
    else if (kind == "fully-distributed")
      {
        auto fully =
          std::make_unique<parallel::fullydistributed::Triangulation<3>>(comm);
        // the description of each rank's part, built from the whole mesh
        // read by one rank of each group at a time (group size 1)
        const auto description = TriangulationDescription::Utilities::
          create_description_from_triangulation_in_groups<3, 3>(
            [&file, refinements](Triangulation<3> &serial) {
              read_mesh(serial, file, refinements);
            },
            [](Triangulation<3> &serial,
               const MPI_Comm   &c,
               const unsigned int) {
              GridTools::partition_triangulation(
                Utilities::MPI::n_mpi_processes(c), serial);
            },
            comm,
            1);
        fully->create_triangulation(description);
        tria = std::move(fully);
      }
    else
      throw std::runtime_error("KIND must be shared, distributed or "
                               "fully-distributed, not '" +
                               kind + "'");
    const double rss_mesh = rss_mb();

    FESystem<3>   fe(FE_Q<3>(degree), 3);
    DoFHandler<3> dofs(*tria);
    dofs.distribute_dofs(fe);
    const IndexSet owned = dofs.locally_owned_dofs();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(dofs, relevant);
    const double rss_dofs = rss_mb();

    DynamicSparsityPattern pattern(relevant);
    DoFTools::make_sparsity_pattern(dofs, pattern);
    SparsityTools::distribute_sparsity_pattern(pattern, owned, comm, relevant);
    const double rss_pattern = rss_mb();

    unsigned int owned_cells = 0;
    for (const auto &cell : tria->active_cell_iterators())
      if (cell->is_locally_owned())
        ++owned_cells;

    const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    std::ostringstream line;
    line << kind << ',' << rank << ',' << n_ranks << ','
         << tria->n_active_cells() << ',' << owned_cells << ','
         << owned.n_elements() << ',' << relevant.n_elements() << ','
         << tria->memory_consumption() / 1048576. << ','
         << dofs.memory_consumption() / 1048576. << ',' << rss_mesh << ','
         << rss_dofs << ',' << rss_pattern << '\n';
    // rank 0 prints every rank's line, in order
    const auto lines = Utilities::MPI::gather(comm, line.str());
    Utilities::System::MemoryStats s;
    Utilities::System::get_memory_stats(s);
    const double peak = Utilities::MPI::sum(double(s.VmHWM), comm) / 1024.;
    if (rank == 0)
      {
        for (const auto &l : lines)
          std::cout << l;
        std::cout << "total," << kind << ',' << n_ranks << ',' << peak
                  << std::endl;
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
    {
      if (argc != 4 && argc != 5)
        throw std::runtime_error(
          "usage: squeal-bench-mesh-memory MSH DEGREE KIND [REFINE]");
      run(argv[1],
          std::stoi(argv[2]),
          argv[3],
          argc == 5 ? std::stoi(argv[4]) : 0);
    }
  catch (const std::exception &e)
    {
      std::cerr << "squeal-bench-mesh-memory: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}
