// The model updating analysis' measured data (see model_updating.h): the
// CSV files of targets and measurement points, the configurations and
// fitted parameters of the parameter file, and the measurement points
// located in the mesh (PointObservation).

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include <squeal/analyses/model_updating.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;

    namespace
    {
      /** The non-blank items of a parameter's `;`-separated list. */
      std::vector<std::string>
      list_items(const std::string &text)
      {
        std::vector<std::string> result;
        std::istringstream       items(text);
        for (std::string item; std::getline(items, item, ';');)
          if (item.find_first_not_of(" \t") != std::string::npos)
            result.push_back(item);
        return result;
      }

      /** The fields of one CSV line; a field in double quotes may hold
       * commas (a doubled quote inside is one quote). */
      std::vector<std::string>
      csv_fields(const std::string &line)
      {
        std::vector<std::string> fields(1);
        bool                     quoted = false;
        for (std::size_t i = 0; i < line.size(); ++i)
          {
            const char c = line[i];
            if (c == '"')
              {
                if (quoted && i + 1 < line.size() && line[i + 1] == '"')
                  fields.back() += '"', ++i;
                else
                  quoted = !quoted;
              }
            else if (c == ',' && !quoted)
              fields.emplace_back();
            else if (c != '\r')
              fields.back() += c;
          }
        for (auto &f : fields)
          {
            const auto first = f.find_first_not_of(" \t");
            const auto last  = f.find_last_not_of(" \t");
            f                = first == std::string::npos ? "" :
                                                            f.substr(first, last - first + 1);
          }
        return fields;
      }

      /** The data lines of a CSV file (after its header; blank lines and
       * lines starting with # skipped) with their line numbers. */
      std::vector<std::pair<unsigned int, std::vector<std::string>>>
      csv_rows(const std::string &file, const std::string &what)
      {
        std::ifstream in(file);
        if (!in)
          throw std::runtime_error("cannot open " + what + " '" + file + "'");
        std::vector<std::pair<unsigned int, std::vector<std::string>>> rows;
        std::string                                                    line;
        unsigned int number = 0;
        bool         header = true;
        while (std::getline(in, line))
          {
            ++number;
            if (line.find_first_not_of(" \t\r") == std::string::npos ||
                line[line.find_first_not_of(" \t")] == '#')
              continue;
            if (header)
              {
                header = false;
                continue;
              }
            rows.emplace_back(number, csv_fields(line));
          }
        if (rows.empty())
          throw std::runtime_error(what + " '" + file +
                                   "' holds no data line after its header");
        return rows;
      }

      /** @p text as a finite number (all of it), or nothing. */
      std::optional<double>
      to_number(const std::string &text)
      {
        std::size_t used = 0;
        double      value;
        try
          {
            value = std::stod(text, &used);
          }
        catch (const std::exception &)
          {
            return {};
          }
        if (used == 0 || used != text.size() || !std::isfinite(value))
          return {};
        return value;
      }

      /** @p field as a number, or an error naming file, line and column. */
      double
      number_of(const std::string &field,
                const std::string &file,
                const unsigned int line,
                const std::string &column)
      {
        const auto value = to_number(field);
        if (!value)
          throw std::runtime_error("'" + file + "', line " +
                                   std::to_string(line) + ": " + column +
                                   " = '" + field + "' is not a number");
        return *value;
      }
    } // namespace


    std::vector<MeasurementPoint>
    read_measurement_points(const std::string &file)
    {
      std::vector<MeasurementPoint> points;
      for (const auto &[line, f] : csv_rows(file,
                                            "Model updating/Measurement "
                                            "points file"))
        {
          if (f.size() != 7)
            throw std::runtime_error(
              "'" + file + "', line " + std::to_string(line) + ": " +
              std::to_string(f.size()) +
              " fields; a measurement point is label,x,y,z,dx,dy,dz");
          MeasurementPoint p;
          p.label                    = f[0];
          const char *const column[] = {"x", "y", "z", "dx", "dy", "dz"};
          for (unsigned int d = 0; d < 3; ++d)
            {
              p.x[d]         = number_of(f[1 + d], file, line, column[d]);
              p.direction[d] = number_of(f[4 + d], file, line, column[3 + d]);
            }
          if (!(p.direction.norm() > 0.))
            throw std::runtime_error("'" + file + "', line " +
                                     std::to_string(line) +
                                     ": the direction (dx,dy,dz) is zero");
          p.direction /= p.direction.norm();
          points.push_back(p);
        }
      return points;
    }

    std::vector<Configuration>
    parse_configurations(const std::string &text)
    {
      std::vector<Configuration> result;
      for (const std::string &item : list_items(text))
        {
          const std::string where =
            "Model updating/Configurations, item '" + item + "'";
          const auto    colon = item.find(':');
          Configuration c;
          if (colon != std::string::npos)
            c.name = csv_fields(item.substr(0, colon))[0];
          if (c.name.empty())
            throw std::runtime_error(where + ": write it `name: parameter = "
                                             "value, parameter = value`");
          for (const auto &pair : csv_fields(item.substr(colon + 1)))
            {
              const auto equal = pair.find('=');
              if (equal == std::string::npos)
                throw std::runtime_error(where + ": '" + pair +
                                         "' is not `parameter = value`");
              const std::string name  = csv_fields(pair.substr(0, equal))[0];
              const std::string value = csv_fields(pair.substr(equal + 1))[0];
              const auto        v     = to_number(value);
              if (!v)
                throw std::runtime_error(where + ": the value '" + value +
                                         "' is not a number");
              c.values.emplace_back(name, *v);
            }
          for (const auto &other : result)
            if (other.name == c.name)
              throw std::runtime_error(where + ": the name '" + c.name +
                                       "' is given twice");
          result.push_back(c);
        }
      return result;
    }

    std::vector<updating::Target>
    read_targets(const std::string                &file,
                 const unsigned int                n_points,
                 const std::vector<Configuration> &configurations)
    {
      std::ifstream in(file);
      if (!in)
        throw std::runtime_error("cannot open Model updating/Targets file '" +
                                 file + "'");
      // the header names the columns
      std::string              line;
      unsigned int             number = 0;
      std::vector<std::string> header;
      while (header.empty() && std::getline(in, line))
        {
          ++number;
          const auto first = line.find_first_not_of(" \t\r");
          if (first != std::string::npos && line[first] != '#')
            header = csv_fields(line);
        }
      const auto column = [&](const std::string &name) {
        return int(std::find(header.begin(), header.end(), name) -
                   header.begin());
      };
      const int label = column("label"), frequency = column("frequency_Hz"),
                weight = column("weight"), name = column("name"),
                configuration = column("configuration"),
                damping       = column("damping_ratio");
      const int n_columns     = header.size();
      if (label == n_columns || frequency == n_columns)
        throw std::runtime_error("Model updating/Targets file '" + file +
                                 "': the header (line " +
                                 std::to_string(number) +
                                 ") needs the columns label and frequency_Hz");
      std::vector<int> shape;
      for (int c = 0; c < n_columns; ++c)
        if (header[c].rfind("shape", 0) == 0)
          shape.push_back(c);
      if (!shape.empty() && shape.size() != n_points)
        throw std::runtime_error(
          "Model updating/Targets file '" + file +
          "': " + std::to_string(shape.size()) +
          " shape columns; give one per measurement point (" +
          std::to_string(n_points) + ") or none");

      std::vector<updating::Target> targets;
      std::set<std::string>         labels;
      while (std::getline(in, line))
        {
          ++number;
          const auto first = line.find_first_not_of(" \t\r");
          if (first == std::string::npos || line[first] == '#')
            continue;
          const std::string at =
            "'" + file + "', line " + std::to_string(number);
          auto f = csv_fields(line);
          if (int(f.size()) > n_columns)
            throw std::runtime_error(at + ": " + std::to_string(f.size()) +
                                     " fields under a header of " +
                                     std::to_string(n_columns));
          f.resize(n_columns);
          updating::Target t;
          t.label     = f[label];
          t.frequency = number_of(f[frequency], file, number, "frequency_Hz");
          if (weight < n_columns && !f[weight].empty())
            t.weight = number_of(f[weight], file, number, "weight");
          if (name < n_columns)
            t.name = f[name];
          if (damping < n_columns && !f[damping].empty())
            {
              t.damping_ratio =
                number_of(f[damping], file, number, "damping_ratio");
              if (!(t.damping_ratio > 0. && t.damping_ratio < 1.))
                throw std::runtime_error(at +
                                         ": damping_ratio must lie in (0, 1) "
                                         "(a ratio, not a percentage), or "
                                         "be empty");
            }
          if (configuration < n_columns && !f[configuration].empty())
            {
              unsigned int c = 0;
              while (c < configurations.size() &&
                     configurations[c].name != f[configuration])
                ++c;
              if (c == configurations.size())
                {
                  std::string known;
                  for (const auto &k : configurations)
                    known += (known.empty() ? "" : ", ") + k.name;
                  throw std::runtime_error(
                    at + ": configuration '" + f[configuration] +
                    "' is not one of Model updating/Configurations (" +
                    (known.empty() ? std::string("none given") : known) + ")");
                }
              t.configuration = c + 1;
            }
          unsigned int given = 0;
          for (const int c : shape)
            given += !f[c].empty();
          if (given > 0 && given < shape.size())
            throw std::runtime_error(at + ": " + std::to_string(given) +
                                     " of the " + std::to_string(shape.size()) +
                                     " shape values; give all or none");
          if (given > 0)
            for (const int c : shape)
              t.shape.push_back(number_of(f[c], file, number, header[c]));
          if (!(t.frequency > 0.) || !(t.weight > 0.))
            throw std::runtime_error(at + ": frequency_Hz and weight must be "
                                          "> 0");
          if (t.label.empty() || !labels.insert(t.label).second)
            throw std::runtime_error(at + ": the label '" + t.label +
                                     "' is empty or given twice");
          targets.push_back(std::move(t));
        }
      if (targets.empty())
        throw std::runtime_error("Model updating/Targets file '" + file +
                                 "' holds no data line after its header");
      return targets;
    }

    std::vector<updating::Parameter>
    parse_updating_parameters(const std::string &text)
    {
      std::vector<updating::Parameter> result;
      for (const std::string &item : list_items(text))
        {
          const std::string where =
            "Model updating/Parameters, item '" + item + "'";
          const auto colon = item.find(':');
          if (colon == std::string::npos)
            throw std::runtime_error(where + ": write it `name: lower, upper` "
                                             "or `name: lower, upper, linear`");
          updating::Parameter q;
          q.name        = csv_fields(item.substr(0, colon))[0];
          const auto at = q.name.find('@');
          q.scene_name  = q.name.substr(0, at);
          if (at != std::string::npos)
            {
              q.configuration = q.name.substr(at + 1);
              if (q.scene_name.empty() || q.configuration.empty())
                throw std::runtime_error(
                  where + ": write a parameter of one configuration "
                          "`<parameter>@<configuration>`");
            }
          const auto f = csv_fields(item.substr(colon + 1));
          if (f.size() < 2 || f.size() > 3 ||
              (f.size() == 3 && f[2] != "linear" && f[2] != "log"))
            throw std::runtime_error(where + ": after the name give `lower, "
                                             "upper` and optionally `linear`");
          for (unsigned int b = 0; b < 2; ++b)
            {
              const auto v = to_number(f[b]);
              if (!v)
                throw std::runtime_error(where + ": the bound '" + f[b] +
                                         "' is not a number");
              (b == 0 ? q.lower : q.upper) = *v;
            }
          q.log_scale = f.size() < 3 || f[2] == "log";
          result.push_back(q);
        }
      if (result.empty())
        throw std::runtime_error("Model updating/Parameters names no "
                                 "parameter");
      return result;
    }


    PointObservation::PointObservation(
      const physics::StructuralModel      &model,
      const std::vector<MeasurementPoint> &points)
      : rows(points.size())
      , comm(model.comm)
    {
      using Row = std::vector<std::pair<types::global_dof_index, double>>;
      // each point's row is made by the rank owning its cell (its
      // constraints know that cell's DoFs) and sent to all
      std::vector<std::pair<unsigned int, Row>> mine;
      const FiniteElement<3>                   &fe = model.fe;
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          std::pair<DoFHandler<3>::active_cell_iterator, Point<3>> found;
          bool                                                     ok = false;
          for (const double tolerance : {1e-10, 1e-3})
            {
              try
                {
                  found =
                    GridTools::find_active_cell_around_point(model.mapping,
                                                             model.dof_handler,
                                                             points[i].x,
                                                             {},
                                                             tolerance);
                  ok = found.first.state() == IteratorState::valid;
                }
              catch (...)
                {
                  ok = false;
                }
              if (ok)
                break;
            }
          if (!ok)
            {
              std::ostringstream what;
              what << "Model updating/Measurement points: point '"
                   << points[i].label << "' at (" << points[i].x
                   << ") m lies outside the mesh";
              throw std::runtime_error(what.str());
            }
          const auto &cell = found.first;
          if (!cell->is_locally_owned())
            continue;
          const Point<3> unit =
            GeometryInfo<3>::project_to_unit_cell(found.second);
          std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
          cell->get_dof_indices(dofs);
          std::map<types::global_dof_index, double> weight;
          for (unsigned int k = 0; k < dofs.size(); ++k)
            {
              const unsigned int c = fe.system_to_component_index(k).first;
              const double w = fe.shape_value(k, unit) * points[i].direction[c];
              if (w == 0.)
                continue;
              if (!model.constraints.is_constrained(dofs[k]))
                weight[dofs[k]] += w;
              else if (const auto *entries =
                         model.constraints.get_constraint_entries(dofs[k]))
                for (const auto &[dof, a] : *entries)
                  weight[dof] += w * a;
            }
          mine.emplace_back(i, Row(weight.begin(), weight.end()));
        }
      std::vector<bool> have(points.size(), false);
      for (const auto &from : Utilities::MPI::all_gather(comm, mine))
        for (const auto &[i, row] : from)
          if (!have[i])
            {
              have[i] = true;
              for (const auto &[dof, w] : row)
                if (model.locally_owned_dofs.is_element(dof))
                  rows[i].emplace_back(dof, w);
            }
    }

    std::vector<double>
    PointObservation::operator()(const physics::PETScVector &u) const
    {
      std::vector<double> values(rows.size(), 0.);
      for (unsigned int i = 0; i < rows.size(); ++i)
        for (const auto &[dof, w] : rows[i])
          values[i] += w * u[dof];
      MPI_Allreduce(
        MPI_IN_PLACE, values.data(), values.size(), MPI_DOUBLE, MPI_SUM, comm);
      return values;
    }
  } // namespace analyses
} // namespace squeal
