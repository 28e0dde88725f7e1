// Lookup of a mesh's named sets and their conversion to deal.II material
// and boundary ids. A missing name is the commonest mistake in a scene file,
// so the error lists the names the mesh does have.

#include <squeal/io/named_sets.h>

#include <algorithm>
#include <stdexcept>

namespace squeal
{
  namespace io
  {
    using namespace dealii;

    namespace
    {
      template <typename Map>
      const typename Map::mapped_type &
      find_set(const Map         &sets,
               const std::string &name,
               const std::string &kind,
               const std::string &source)
      {
        const auto it = sets.find(name);
        if (it != sets.end())
          return it->second;
        std::string known;
        for (const auto &[n, members] : sets)
          known += (known.empty() ? "'" : ", '") + n + "'";
        throw std::runtime_error(
          source + " has no " + kind + " set '" + name + "' (its " + kind +
          " sets: " + (known.empty() ? "none" : known) + ")");
      }

      void
      require_coarse(const Triangulation<3> &tria, const std::string &what)
      {
        if (tria.n_levels() > 1)
          throw std::runtime_error(what +
                                   ": the sets must be applied to the coarse "
                                   "mesh, before it is refined");
      }

      // The level-0 cells by index.
      std::vector<Triangulation<3>::cell_iterator>
      coarse_cells(Triangulation<3> &tria)
      {
        std::vector<Triangulation<3>::cell_iterator> coarse;
        for (const auto &cell : tria.cell_iterators_on_level(0))
          coarse.push_back(cell);
        return coarse;
      }
    } // namespace

    const std::vector<unsigned int> &
    NamedSets::cells(const std::string &name) const
    {
      return find_set(cell_sets, name, "cell", source);
    }

    const std::vector<CellFace> &
    NamedSets::faces(const std::string &name) const
    {
      return find_set(face_sets, name, "face", source);
    }

    const std::vector<Point<3>> &
    NamedSets::nodes(const std::string &name) const
    {
      return find_set(node_sets, name, "node", source);
    }

    void
    NamedSets::assign_material(const std::string       &name,
                               const types::material_id id,
                               Triangulation<3>        &tria) const
    {
      const auto &set = cells(name);
      require_coarse(tria, "cell set '" + name + "'");
      const auto coarse = coarse_cells(tria);
      for (const unsigned int c : set)
        coarse.at(c)->set_material_id(id);
    }

    void
    NamedSets::assign_boundary(const std::string       &name,
                               const types::boundary_id id,
                               Triangulation<3>        &tria) const
    {
      const auto &set = faces(name);
      require_coarse(tria, "face set '" + name + "'");
      const auto coarse = coarse_cells(tria);
      for (const auto &[c, f] : set)
        {
          const auto face = coarse.at(c)->face(f);
          if (!face->at_boundary())
            throw std::runtime_error(
              source + ": face set '" + name +
              "' holds an interior face (cell " + std::to_string(c) +
              ", face " + std::to_string(f) +
              "); boundary conditions and contact need boundary faces");
          face->set_boundary_id(id);
        }
    }

    void
    NamedSets::collect_from_ids(
      const Triangulation<3>                          &tria,
      const std::map<types::material_id, std::string> &cell_names,
      const std::map<types::boundary_id, std::string> &face_names)
    {
      for (const auto &cell : tria.cell_iterators_on_level(0))
        {
          if (const auto it = cell_names.find(cell->material_id());
              it != cell_names.end())
            cell_sets[it->second].push_back(cell->index());
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              if (const auto it = face_names.find(cell->face(f)->boundary_id());
                  it != face_names.end())
                face_sets[it->second].emplace_back(cell->index(), f);
        }
    }
  } // namespace io
} // namespace squeal
