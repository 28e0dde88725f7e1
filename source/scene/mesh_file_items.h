// The items of Scene/Mesh file's lists and the checks of a mesh-file scene
// against its mesh, shared by mesh_file_scene.cc and mesh_file_checks.cc
// (not part of the installed interface).

#ifndef squeal_source_scene_mesh_file_items_h
#define squeal_source_scene_mesh_file_items_h

#include <deal.II/base/utilities.h>
#include <deal.II/grid/tria.h>

#include <squeal/io/named_sets.h>
#include <squeal/scene/scene.h>

#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace squeal
{
  namespace scene
  {
    namespace internal
    {
      using namespace dealii;

      inline const std::string prefix = "Scene/Mesh file/";

      using Utilities::trim;

      // One item of a list: `name: key=value, key=value`.
      struct Item
      {
        std::string                        entry; // for messages
        std::string                        name;
        std::map<std::string, std::string> keys;

        std::string
        where() const
        {
          return prefix + entry + ", item '" + name + "'";
        }

        bool
        has(const std::string &key) const
        {
          return keys.count(key) > 0;
        }

        const std::string &
        text(const std::string &key) const
        {
          const auto it = keys.find(key);
          if (it == keys.end())
            throw std::runtime_error(where() + ": '" + key + "=' is required");
          return it->second;
        }

        std::string
        text(const std::string &key, const std::string &fallback) const
        {
          return has(key) ? keys.at(key) : fallback;
        }

        double
        number(const std::string &key) const
        {
          const std::string &v = text(key);
          try
            {
              std::size_t  used = 0;
              const double x    = std::stod(v, &used);
              if (trim(v.substr(used)).empty() && std::isfinite(x))
                return x;
            }
          catch (const std::exception &)
            {}
          throw std::runtime_error(where() + ": " + key + " = '" + v +
                                   "' is not a number");
        }

        double
        number(const std::string &key, const double fallback) const
        {
          return has(key) ? number(key) : fallback;
        }

        Tensor<1, 3>
        vector(const std::string &value, const std::string &key) const
        {
          std::istringstream in(value);
          Tensor<1, 3>       v;
          std::string        rest;
          if (!(in >> v[0] >> v[1] >> v[2]) || (in >> rest) ||
              !std::isfinite(v.norm()))
            throw std::runtime_error(where() + ": " + key + " = '" + value +
                                     "' is not three numbers 'x y z'");
          return v;
        }

        Tensor<1, 3>
        vector(const std::string &key) const
        {
          return vector(text(key), key);
        }

        Tensor<1, 3>
        unit(const std::string &key, const std::string &fallback) const
        {
          const Tensor<1, 3> v =
            vector(fallback.empty() ? text(key) : text(key, fallback), key);
          if (!(v.norm() > 0.))
            throw std::runtime_error(where() + ": " + key +
                                     " is the zero vector");
          return v / v.norm();
        }
      };

      inline std::vector<Item>
      parse_list(const std::string              &entry,
                 const std::string              &text,
                 const std::vector<std::string> &allowed)
      {
        std::vector<Item>     items;
        std::set<std::string> names;
        for (const std::string &raw : Utilities::split_string_list(text, ';'))
          {
            const std::string piece = trim(raw);
            if (piece.empty())
              continue;
            Item item;
            item.entry       = entry;
            const auto colon = piece.find(':');
            item.name        = trim(piece.substr(0, colon));
            if (colon == std::string::npos || item.name.empty())
              throw std::runtime_error(prefix + entry + ": '" + piece +
                                       "' is not 'name: key=value, key=value'");
            if (!names.insert(item.name).second)
              throw std::runtime_error(item.where() + ": the name is used "
                                                      "twice");
            for (const std::string &pair :
                 Utilities::split_string_list(piece.substr(colon + 1), ','))
              {
                if (trim(pair).empty())
                  continue;
                const auto        eq  = pair.find('=');
                const std::string key = trim(
                  pair.substr(0, eq == std::string::npos ? pair.size() : eq));
                if (eq == std::string::npos ||
                    std::find(allowed.begin(), allowed.end(), key) ==
                      allowed.end())
                  {
                    std::string list;
                    for (const auto &a : allowed)
                      list += (list.empty() ? "" : ", ") + a;
                    throw std::runtime_error(item.where() + ": '" + trim(pair) +
                                             "' is not key=value with a key "
                                             "of: " +
                                             list);
                  }
                if (!item.keys.emplace(key, trim(pair.substr(eq + 1))).second)
                  throw std::runtime_error(item.where() + ": '" + key +
                                           "' given twice");
              }
            items.push_back(item);
          }
        return items;
      }

      inline unsigned int
      component_of(const Item &item, const std::string &key, const char c)
      {
        if (c == 'x' || c == 'y' || c == 'z')
          return c - 'x';
        throw std::runtime_error(item.where() + ": " + key + " = '" +
                                 item.text(key) + "': use x, y or z");
      }

      // The level-0 cells by index.
      inline std::vector<Triangulation<3>::cell_iterator>
      coarse_cells(const Triangulation<3> &tria)
      {
        std::vector<Triangulation<3>::cell_iterator> cells;
        for (const auto &cell : tria.cell_iterators_on_level(0))
          cells.push_back(cell);
        return cells;
      }

      // Outward unit normal and area [m^2] of face f of a cell (a
      // bilinear face: the normal of its diagonals' cross product).
      inline std::pair<Tensor<1, 3>, double>
      outward_normal(const Triangulation<3>::cell_iterator &cell,
                     const unsigned int                     f)
      {
        const auto   face = cell->face(f);
        Tensor<1, 3> n    = cross_product_3d(face->vertex(3) - face->vertex(0),
                                          face->vertex(2) - face->vertex(1));
        if (n * (face->center() - cell->center()) < 0)
          n = -n;
        return {n / n.norm(), face->measure()};
      }


      // LOOKUP() (a named set of the mesh), its error prefixed with where ITEM
      // is.
      template <typename Lookup>
      const auto &
      named(const Item &item, const Lookup &lookup)
      {
        try
          {
            return lookup();
          }
        catch (const std::runtime_error &e)
          {
            throw std::runtime_error(item.where() + ": " + e.what());
          }
      }

      // Overlapping bodies: a vertex, face centre or cell centre of one body
      // inside a cell of another by more than 1 % of that cell (touching
      // bodies, such as a pad on a disc, meet on each other's faces, at
      // depth 0).
      void
      check_overlap(const Triangulation<3>                             &coarse,
                    const std::vector<Triangulation<3>::cell_iterator> &cells,
                    const std::vector<int>                             &owner,
                    const std::vector<Body>                            &bodies,
                    const std::string &description);

      // The contact plane of PAIR from its slave faces SLAVE: centre, normal
      // (into the slave body), size, in-plane axes; the faces must be plane.
      void
      plane_frame(const Item                                         &item,
                  const std::vector<io::CellFace>                    &slave,
                  const std::vector<Triangulation<3>::cell_iterator> &cells,
                  ContactPair                                        &pair);

      // The master faces MASTER under the slave faces SLAVE of PAIR: some
      // exist, they face the slave, and they lie within SEARCH_DISTANCE [m].
      void
      check_master(const Item                                         &item,
                   const ContactPair                                  &pair,
                   const std::vector<io::CellFace>                    &slave,
                   const std::vector<io::CellFace>                    &master,
                   const std::vector<Triangulation<3>::cell_iterator> &cells,
                   const double search_distance);


      // Nothing may float free: every body of SCENE connected to the ground
      // through holds, point holds, springs, contact pairs or shared
      // vertices.
      void
      check_grounded(const Scene                                     &scene,
                     const std::map<std::string, types::boundary_id> &face_ids,
                     const io::NamedSets                             &sets,
                     const std::vector<Triangulation<3>::cell_iterator> &cells,
                     const std::vector<int>                             &owner,
                     const std::string &description);
    } // namespace internal
  }   // namespace scene
} // namespace squeal

#endif
