// MatrixMarket output and input of the model's matrices, with the DoF
// coordinates, for independent solves (see the header).

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/component_mask.h>

#include <squeal/io/matrix_export.h>

#include <petscmat.h>

#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace io
  {
    using namespace dealii;

    namespace
    {
      // every rank learns whether rank 0 could write @p file
      void
      finish_file(std::ofstream &out, const std::string &file, MPI_Comm comm)
      {
        bool ok = true;
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          {
            out.close();
            ok = static_cast<bool>(out);
          }
        if (Utilities::MPI::min(ok ? 1 : 0, comm) == 0)
          throw std::runtime_error("matrix export: could not write " + file +
                                   " completely (disk full or no permission)");
      }

      std::ofstream
      open_on_root(const std::string &file, MPI_Comm comm)
      {
        std::ofstream out;
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          {
            out.open(file);
            out << std::setprecision(17);
          }
        return out;
      }

      const char *
      kind_name(const physics::MatrixParts::Kind kind)
      {
        using Kind = physics::MatrixParts::Kind;
        switch (kind)
          {
            case Kind::mass:
              return "mass";
            case Kind::stiffness:
              return "stiffness";
            case Kind::interface_normal:
              return "interface_normal";
            case Kind::interface_friction:
              return "interface_friction";
          }
        return "";
      }
    } // namespace

    void
    write_matrix_market(const physics::PETScMatrix &A,
                        const std::string          &file,
                        const std::string          &comment)
    {
      const MPI_Comm      comm = A.get_mpi_communicator();
      std::vector<double> local; // row, column, value triples
      PetscInt            first, last;
      MatGetOwnershipRange(A, &first, &last);
      for (PetscInt i = first; i < last; ++i)
        {
          PetscInt           n;
          const PetscInt    *columns;
          const PetscScalar *values;
          MatGetRow(A, i, &n, &columns, &values);
          for (PetscInt k = 0; k < n; ++k)
            if (values[k] != 0.)
              local.insert(local.end(),
                           {double(i), double(columns[k]), values[k]});
          MatRestoreRow(A, i, &n, &columns, &values);
        }
      const auto    all = Utilities::MPI::gather(comm, local, 0);
      std::ofstream out = open_on_root(file, comm);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          std::size_t nonzeros = 0;
          for (const auto &part : all)
            nonzeros += part.size() / 3;
          out << "%%MatrixMarket matrix coordinate real general\n";
          std::istringstream lines(comment);
          for (std::string line; std::getline(lines, line);)
            out << "% " << line << '\n';
          out << A.m() << ' ' << A.n() << ' ' << nonzeros << '\n';
          for (const auto &part : all)
            for (std::size_t k = 0; k < part.size(); k += 3)
              out << std::size_t(part[k]) + 1 << ' '
                  << std::size_t(part[k + 1]) + 1 << ' ' << part[k + 2] << '\n';
        }
      finish_file(out, file, comm);
    }

    Triplets
    read_matrix_market(const std::string &file)
    {
      std::ifstream in(file);
      if (!in)
        throw std::runtime_error("MatrixMarket file " + file +
                                 ": cannot be opened");
      const auto fail = [&](const unsigned int line, const std::string &what) {
        throw std::runtime_error("MatrixMarket file " + file + ", line " +
                                 std::to_string(line) + ": " + what);
      };
      std::string  line;
      unsigned int number = 1;
      std::getline(in, line);
      std::istringstream header(line);
      std::string        banner, object, format, field, symmetry;
      header >> banner >> object >> format >> field >> symmetry;
      if (banner != "%%MatrixMarket" || object != "matrix" ||
          format != "coordinate" || field != "real" ||
          (symmetry != "general" && symmetry != "symmetric"))
        fail(number,
             "expected '%%MatrixMarket matrix coordinate real general' "
             "(or symmetric), found '" +
               line + "'");
      while (std::getline(in, line) && ++number && !line.empty() &&
             line[0] == '%')
        ;
      Triplets           t;
      std::size_t        nonzeros = 0;
      std::istringstream size(line);
      if (!(size >> t.rows >> t.columns >> nonzeros))
        fail(number, "expected 'rows columns nonzeros', found '" + line + "'");
      t.entries.reserve(nonzeros);
      for (std::size_t k = 0; k < nonzeros; ++k)
        {
          ++number;
          std::size_t i, j;
          double      v;
          if (!std::getline(in, line))
            fail(number,
                 "the file ends after " + std::to_string(k) + " of " +
                   std::to_string(nonzeros) + " entries");
          std::istringstream entry(line);
          if (!(entry >> i >> j >> v))
            fail(number, "expected 'row column value', found '" + line + "'");
          if (i < 1 || i > t.rows || j < 1 || j > t.columns)
            fail(number,
                 "index (" + std::to_string(i) + ", " + std::to_string(j) +
                   ") outside the " + std::to_string(t.rows) + " x " +
                   std::to_string(t.columns) + " matrix");
          t.entries.emplace_back(i - 1, j - 1, v);
          if (symmetry == "symmetric" && i != j)
            t.entries.emplace_back(j - 1, i - 1, v);
        }
      return t;
    }

    void
    export_matrices(
      const physics::StructuralModel &model,
      const std::vector<std::pair<unsigned int, parameters::ScalarPoint>>
                        &points,
      const std::string &directory)
    {
      const MPI_Comm comm  = model.comm;
      const auto     parts = model.parts();
      for (unsigned int k = 0; k < parts.size(); ++k)
        write_matrix_market(parts.matrix(k),
                            directory + "/part_" + std::to_string(k) + ".mtx",
                            "squeal matrix part " + std::to_string(k) + ": " +
                              parts.parts[k].name);
      {
        std::vector<physics::MatrixParts::Combination> c;
        for (const auto &[index, p] : points)
          c.push_back(parts.coefficients(p));
        const std::string file = directory + "/parts.csv";
        std::ofstream     out  = open_on_root(file, comm);
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          {
            out << "part,name,kind,scale,reference";
            for (const auto &[index, p] : points)
              for (const char *m : {"mass", "damping", "stiffness"})
                out << ",point_" << index << '_' << m;
            out << '\n';
            for (unsigned int k = 0; k < parts.size(); ++k)
              {
                const auto &part = parts.parts[k];
                out << k << ",\"" << part.name << "\"," << kind_name(part.kind)
                    << ',' << part.scale << ',' << part.reference;
                for (const auto &combination : c)
                  out << ',' << combination.mass[k] << ','
                      << combination.damping[k] << ','
                      << combination.stiffness[k];
                out << '\n';
              }
          }
        finish_file(out, file, comm);
      }
      for (const auto &[index, p] : points)
        {
          const std::string stem =
            directory + "/point_" + std::to_string(index);
          physics::PETScMatrix A;
          parts.mass(p, A);
          write_matrix_market(A, stem + "_M.mtx", "M [kg]");
          parts.damping(p, A);
          write_matrix_market(A, stem + "_C.mtx", "C [N s/m]");
          parts.stiffness(p, A);
          write_matrix_market(A, stem + "_K.mtx", "K [N/m]");
          std::ofstream out = open_on_root(stem + ".csv", comm);
          if (Utilities::MPI::this_mpi_process(comm) == 0)
            {
              out << "parameter,value\n";
              for (const auto &[name, value] : p.values())
                out << name << ',' << value << '\n';
            }
          finish_file(out, stem + ".csv", comm);
        }

      // the support point and component of every DoF, gathered on rank 0
      std::vector<double> local; // dof, x, y, z, component, constrained
      {
        std::map<types::global_dof_index, Point<3>> support;
        DoFTools::map_dofs_to_support_points(model.mapping,
                                             model.dof_handler,
                                             support);
        for (unsigned int d = 0; d < 3; ++d)
          {
            ComponentMask mask(3, false);
            mask.set(d, true);
            const IndexSet component =
              DoFTools::extract_dofs(model.dof_handler, mask);
            for (const auto &[dof, x] : support)
              if (model.locally_owned_dofs.is_element(dof) &&
                  component.is_element(dof))
                local.insert(local.end(),
                             {double(dof),
                              x[0],
                              x[1],
                              x[2],
                              double(d),
                              model.constraints.is_constrained(dof) ? 1. : 0.});
          }
      }
      const auto        all  = Utilities::MPI::gather(comm, local, 0);
      const std::string file = directory + "/dofs.csv";
      std::ofstream     out  = open_on_root(file, comm);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          std::map<std::size_t, std::vector<double>> rows;
          for (const auto &part : all)
            for (std::size_t k = 0; k < part.size(); k += 6)
              rows[std::size_t(part[k])] = {part[k + 1],
                                            part[k + 2],
                                            part[k + 3],
                                            part[k + 4],
                                            part[k + 5]};
          out << "dof,x,y,z,component,constrained\n";
          for (const auto &[dof, r] : rows)
            out << dof << ',' << r[0] << ',' << r[1] << ',' << r[2] << ','
                << int(r[3]) << ',' << int(r[4]) << '\n';
        }
      finish_file(out, file, comm);
    }
  } // namespace io
} // namespace squeal
