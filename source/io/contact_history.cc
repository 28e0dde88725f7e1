// Reading and writing the contact-stress history (HDF5, layout in
// contact_history.h) with HDF5's high-level "lite" interface.
//
// Every read checks that the dataset exists and has the expected shape before
// touching it, so that a truncated or foreign file gives one line naming the
// dataset instead of HDF5's error stack.

#include <deal.II/base/utilities.h>

#include <squeal/io/contact_history.h>

#include <hdf5.h>
#include <hdf5_hl.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace squeal
{
  namespace io
  {
    namespace
    {
      const char *const format_name = "squeal contact history 1";
      const double      pi          = 3.14159265358979323846;

      // Closes an HDF5 file when it goes out of scope.
      struct H5File
      {
        hid_t id;
        explicit H5File(hid_t id)
          : id(id)
        {}
        ~H5File()
        {
          if (id >= 0)
            H5Fclose(id);
        }
      };

      [[noreturn]] void
      fail(const std::string &file, const std::string &what)
      {
        throw std::runtime_error("contact history '" + file + "': " + what);
      }

      void
      write_matrix(hid_t                                   f,
                   const std::string                      &file,
                   const char                             *name,
                   const std::vector<std::vector<double>> &rows,
                   std::size_t                             n_cols,
                   const char                             *unit)
      {
        std::vector<double> flat;
        flat.reserve(rows.size() * n_cols);
        for (const auto &r : rows)
          flat.insert(flat.end(), r.begin(), r.end());
        const hsize_t dims[2] = {rows.size(), n_cols};
        if (H5LTmake_dataset_double(f, name, 2, dims, flat.data()) < 0 ||
            H5LTset_attribute_string(f, name, "unit", unit) < 0)
          fail(file, std::string("cannot write dataset ") + name);
      }

      std::vector<hsize_t>
      dataset_shape(hid_t              f,
                    const std::string &file,
                    const char        *name,
                    H5T_class_t       *klass = nullptr)
      {
        if (H5LTfind_dataset(f, name + 1) <= 0)
          fail(file, std::string("missing dataset ") + name);
        int rank = 0;
        if (H5LTget_dataset_ndims(f, name, &rank) < 0 || rank < 1 || rank > 2)
          fail(file,
               std::string("dataset ") + name +
                 " is not a 1- or 2-dimensional array");
        std::vector<hsize_t> dims(rank);
        H5T_class_t          cls;
        std::size_t          size;
        if (H5LTget_dataset_info(f, name, dims.data(), &cls, &size) < 0)
          fail(file, std::string("cannot read the shape of dataset ") + name);
        if (klass != nullptr)
          *klass = cls;
        return dims;
      }

      std::vector<double>
      read_doubles(hid_t                       f,
                   const std::string          &file,
                   const char                 *name,
                   const std::vector<hsize_t> &expected)
      {
        const std::vector<hsize_t> dims = dataset_shape(f, file, name);
        if (dims != expected)
          {
            std::string e, g;
            for (auto d : expected)
              e += (e.empty() ? "" : " x ") + std::to_string(d);
            for (auto d : dims)
              g += (g.empty() ? "" : " x ") + std::to_string(d);
            fail(file,
                 std::string("dataset ") + name + " has shape " + g +
                   ", expected " + e);
          }
        std::size_t n = 1;
        for (auto d : dims)
          n *= d;
        std::vector<double> data(n);
        if (H5LTread_dataset_double(f, name, data.data()) < 0)
          fail(file, std::string("cannot read dataset ") + name);
        return data;
      }

      std::vector<std::vector<double>>
      split_rows(const std::vector<double> &flat, std::size_t n_rows)
      {
        std::vector<std::vector<double>> rows(n_rows);
        const std::size_t n_cols = n_rows ? flat.size() / n_rows : 0;
        for (std::size_t i = 0; i < n_rows; ++i)
          rows[i].assign(flat.begin() + i * n_cols,
                         flat.begin() + (i + 1) * n_cols);
        return rows;
      }

      // the root attribute @p name, which must hold @p n numbers
      std::vector<double>
      read_attribute(hid_t              f,
                     const std::string &file,
                     const char        *name,
                     const hsize_t      n)
      {
        if (H5LTfind_attribute(f, name) <= 0)
          fail(file, std::string("missing root attribute ") + name);
        hsize_t     dims = 0;
        H5T_class_t cls;
        std::size_t size;
        int         rank = -1;
        if (H5LTget_attribute_ndims(f, "/", name, &rank) < 0 || rank > 1 ||
            H5LTget_attribute_info(f, "/", name, &dims, &cls, &size) < 0 ||
            (rank == 0 ? 1 : dims) != n ||
            (cls != H5T_FLOAT && cls != H5T_INTEGER))
          fail(file,
               std::string("root attribute ") + name + " must hold " +
                 (n == 1 ? "one number" : std::to_string(n) + " numbers"));
        std::vector<double> v(n);
        if (H5LTget_attribute_double(f, "/", name, v.data()) < 0)
          fail(file, std::string("cannot read root attribute ") + name);
        return v;
      }

      std::array<double, 3>
      read_vector_attribute(hid_t f, const std::string &file, const char *name)
      {
        const std::vector<double> v = read_attribute(f, file, name, 3);
        return {{v[0], v[1], v[2]}};
      }

      // the machine's physical memory [bytes]
      double
      physical_memory()
      {
        return double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
      }
    } // namespace

    void
    ContactHistory::check(const std::string &where) const
    {
      const auto bad = [&](const std::string &what) { fail(where, what); };
      if (n_nodes() == 0)
        bad("no nodes in /coordinates");
      if (n_samples() == 0)
        bad("no samples in /time");
      if (!(sampling_rate > 0.) || !std::isfinite(sampling_rate))
        bad("root attribute sampling_rate must be a positive number of Hz");
      for (const auto *d : {&sliding_direction, &radial_direction})
        {
          const double n2 =
            (*d)[0] * (*d)[0] + (*d)[1] * (*d)[1] + (*d)[2] * (*d)[2];
          if (!(std::abs(n2 - 1.) < 1e-6))
            bad(std::string("root attribute ") +
                (d == &sliding_direction ? "sliding_direction" :
                                           "radial_direction") +
                " must be a unit vector");
        }
      for (std::size_t i = 0; i < n_nodes(); ++i)
        for (double c : coordinates[i])
          if (!std::isfinite(c))
            bad("dataset /coordinates: non-finite value at node " +
                std::to_string(i));
      for (std::size_t k = 0; k < time.size(); ++k)
        if (!std::isfinite(time[k]))
          bad("dataset /time: non-finite value");
        else if (k > 0 && !(time[k] > time[k - 1]))
          bad("dataset /time must increase: sample " + std::to_string(k) +
              " (t = " + std::to_string(time[k]) + " s) is not after sample " +
              std::to_string(k - 1) + " (t = " + std::to_string(time[k - 1]) +
              " s)");
      {
        const auto &s = sliding_direction, &r = radial_direction;
        if (!(std::abs(s[0] * r[0] + s[1] * r[1] + s[2] * r[2]) < 1e-6))
          bad("root attributes sliding_direction and radial_direction must "
              "be orthogonal (the sliding is tangential, along the disc's "
              "rotation)");
      }
      const std::pair<const char *, const std::vector<std::vector<double>> *>
        fields[] = {{"/p_N", &p_N},
                    {"/t_T1", &t_T1},
                    {"/t_T2", &t_T2},
                    {"/slip_velocity", &slip_velocity}};
      for (const auto &[name, rows] : fields)
        {
          if (rows->size() != n_nodes())
            bad(std::string("dataset ") + name + " has " +
                std::to_string(rows->size()) + " rows for " +
                std::to_string(n_nodes()) + " nodes");
          for (std::size_t i = 0; i < n_nodes(); ++i)
            {
              if ((*rows)[i].size() != n_samples())
                bad(std::string("dataset ") + name + ": node " +
                    std::to_string(i) + " has " +
                    std::to_string((*rows)[i].size()) + " samples, /time " +
                    std::to_string(n_samples()));
              for (double v : (*rows)[i])
                if (!std::isfinite(v))
                  bad(std::string("dataset ") + name +
                      ": non-finite value (NaN or Inf) at node " +
                      std::to_string(i));
            }
        }
      for (std::size_t i = 0; i < n_nodes(); ++i)
        for (double v : p_N[i])
          if (v < 0.)
            bad("dataset /p_N: negative contact pressure at node " +
                std::to_string(i) + " (pressure is compressive-positive)");
      if (status.size() != n_nodes())
        bad("dataset /status has " + std::to_string(status.size()) +
            " rows for " + std::to_string(n_nodes()) + " nodes");
      if (!face.empty() && face.size() != n_nodes())
        bad("dataset /face has " + std::to_string(face.size()) +
            " entries for " + std::to_string(n_nodes()) + " nodes");
      for (std::size_t i = 0; i < face.size(); ++i)
        if (face[i] >= face_names.size())
          bad("dataset /face: value " + std::to_string(face[i]) + " at node " +
              std::to_string(i) + " but " + std::to_string(face_names.size()) +
              " names in its attribute 'names'");
      for (const std::string &name : face_names)
        if (name.empty() || name.find(';') != std::string::npos)
          bad("dataset /face: the face name '" + name +
              "' is empty or holds ';'");
      for (std::size_t i = 0; i < n_nodes(); ++i)
        {
          if (status[i].size() != n_samples())
            bad("dataset /status: node " + std::to_string(i) +
                " has the wrong number of samples");
          for (int s : status[i])
            if (s < 0 || s > 2)
              bad("dataset /status: value " + std::to_string(s) + " at node " +
                  std::to_string(i) +
                  " (allowed: 0 separated, 1 stick, 2 slip)");
        }
    }

    void
    ContactHistory::keep_face(const std::string &name)
    {
      const auto named = std::find(face_names.begin(), face_names.end(), name);
      if (named == face_names.end())
        throw std::runtime_error(
          "the contact history has no pad face '" + name + "' (" +
          (face_names.empty() ? std::string("it holds one unnamed face") :
                                "its faces: " + face_list()) +
          ")");
      const unsigned int keep = named - face_names.begin();
      std::size_t        kept = 0;
      for (std::size_t i = 0; i < n_nodes(); ++i)
        if (face[i] == keep)
          {
            if (kept == i) // no self-move: it would empty the rows
              {
                ++kept;
                continue;
              }
            coordinates[kept]   = coordinates[i];
            p_N[kept]           = std::move(p_N[i]);
            t_T1[kept]          = std::move(t_T1[i]);
            t_T2[kept]          = std::move(t_T2[i]);
            slip_velocity[kept] = std::move(slip_velocity[i]);
            status[kept]        = std::move(status[i]);
            ++kept;
          }
      for (auto *rows : {&p_N, &t_T1, &t_T2, &slip_velocity})
        rows->resize(kept);
      coordinates.resize(kept);
      status.resize(kept);
      face.assign(kept, 0);
      face_names = {name};
    }

    std::string
    ContactHistory::face_list() const
    {
      std::string list;
      for (const std::string &n : face_names)
        list += (list.empty() ? "'" : ", '") + n + "'";
      return list;
    }

    std::array<double, 2>
    ContactHistory::face_coordinates(const std::size_t node) const
    {
      const auto           &x = coordinates[node];
      std::array<double, 2> uv{{0., 0.}};
      for (unsigned int d = 0; d < 3; ++d)
        {
          uv[0] += x[d] * sliding_direction[d];
          uv[1] += x[d] * radial_direction[d];
        }
      return uv;
    }

    void
    write_contact_history(const std::string &filename, const ContactHistory &h)
    {
      h.check(filename);
      const std::string tmp = filename + ".partial";
      {
        H5File f(
          H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
        if (f.id < 0)
          fail(filename, "cannot create the file");
        std::vector<std::vector<double>> xyz(h.n_nodes());
        for (std::size_t i = 0; i < h.n_nodes(); ++i)
          xyz[i].assign(h.coordinates[i].begin(), h.coordinates[i].end());
        write_matrix(f.id, filename, "/coordinates", xyz, 3, "m");
        write_matrix(f.id, filename, "/p_N", h.p_N, h.n_samples(), "Pa");
        write_matrix(f.id, filename, "/t_T1", h.t_T1, h.n_samples(), "Pa");
        write_matrix(f.id, filename, "/t_T2", h.t_T2, h.n_samples(), "Pa");
        write_matrix(f.id,
                     filename,
                     "/slip_velocity",
                     h.slip_velocity,
                     h.n_samples(),
                     "m/s");
        const hsize_t    n_t = h.n_samples();
        std::vector<int> flat;
        for (const auto &r : h.status)
          flat.insert(flat.end(), r.begin(), r.end());
        const hsize_t dims[2] = {h.n_nodes(), h.n_samples()};
        if (H5LTmake_dataset_double(f.id, "/time", 1, &n_t, h.time.data()) <
              0 ||
            H5LTset_attribute_string(f.id, "/time", "unit", "s") < 0 ||
            H5LTmake_dataset_int(f.id, "/status", 2, dims, flat.data()) < 0 ||
            H5LTset_attribute_string(
              f.id, "/status", "unit", "0 separated, 1 stick, 2 slip") < 0 ||
            H5LTset_attribute_double(
              f.id, "/", "sampling_rate", &h.sampling_rate, 1) < 0 ||
            H5LTset_attribute_double(
              f.id, "/", "sliding_direction", h.sliding_direction.data(), 3) <
              0 ||
            H5LTset_attribute_double(
              f.id, "/", "radial_direction", h.radial_direction.data(), 3) <
              0 ||
            H5LTset_attribute_string(f.id, "/", "format", format_name) < 0)
          fail(filename, "cannot write the file");
        if (!h.face.empty())
          {
            const std::vector<int> face(h.face.begin(), h.face.end());
            const hsize_t          n = face.size();
            std::string            names;
            for (const std::string &name : h.face_names)
              names += (names.empty() ? "" : ";") + name;
            if (H5LTmake_dataset_int(f.id, "/face", 1, &n, face.data()) < 0 ||
                H5LTset_attribute_string(
                  f.id, "/face", "names", names.c_str()) < 0)
              fail(filename, "cannot write dataset /face");
          }
      }
      std::filesystem::rename(tmp, filename);
    }

    ContactHistory
    read_contact_history(const std::string &filename)
    {
      if (!std::filesystem::exists(filename))
        fail(filename, "no such file");
      // HDF5 prints its own error stack on every failed call: silence it,
      // the messages below say what went wrong.
      H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
      if (H5Fis_hdf5(filename.c_str()) <= 0)
        fail(filename, "not an HDF5 file");
      H5File f(H5Fopen(filename.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
      if (f.id < 0)
        fail(filename, "cannot open the file");

      ContactHistory             h;
      const std::vector<hsize_t> xyz_shape =
        dataset_shape(f.id, filename, "/coordinates");
      if (xyz_shape.size() != 2 || xyz_shape[1] != 3)
        fail(filename, "dataset /coordinates must be n_nodes x 3");
      const std::size_t         n_nodes = xyz_shape[0];
      const std::vector<double> xyz =
        read_doubles(f.id, filename, "/coordinates", xyz_shape);
      h.coordinates.resize(n_nodes);
      for (std::size_t i = 0; i < n_nodes; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          h.coordinates[i][d] = xyz[3 * i + d];

      const std::vector<hsize_t> t_shape =
        dataset_shape(f.id, filename, "/time");
      if (t_shape.size() != 1)
        fail(filename, "dataset /time must be a vector");
      const std::vector<hsize_t> field{n_nodes, t_shape[0]};
      {
        // five n_nodes x n_samples fields, each read flat then split
        const double need = 2. * double(n_nodes) * double(t_shape[0]) *
                            (4 * sizeof(double) + sizeof(int));
        if (need > 0.8 * physical_memory())
          {
            char text[160];
            std::snprintf(text,
                          sizeof(text),
                          " samples need %.3g GB to read; this machine has "
                          "%.3g GB",
                          need / 1e9,
                          physical_memory() / 1e9);
            fail(filename,
                 std::to_string(n_nodes) + " nodes x " +
                   std::to_string(t_shape[0]) + text +
                   " (write fewer samples: a lower sampling rate or a "
                   "shorter run)");
          }
      }
      h.time = read_doubles(f.id, filename, "/time", t_shape);
      h.p_N  = split_rows(read_doubles(f.id, filename, "/p_N", field), n_nodes);
      h.t_T1 =
        split_rows(read_doubles(f.id, filename, "/t_T1", field), n_nodes);
      h.t_T2 =
        split_rows(read_doubles(f.id, filename, "/t_T2", field), n_nodes);
      h.slip_velocity =
        split_rows(read_doubles(f.id, filename, "/slip_velocity", field),
                   n_nodes);
      H5T_class_t status_class = H5T_NO_CLASS;
      if (dataset_shape(f.id, filename, "/status", &status_class) != field)
        fail(filename, "dataset /status must be n_nodes x n_samples like /p_N");
      if (status_class != H5T_INTEGER)
        fail(filename,
             "dataset /status must hold integers (0 separated, 1 stick, 2 "
             "slip)");
      std::vector<int> status(n_nodes * t_shape[0]);
      if (H5LTread_dataset_int(f.id, "/status", status.data()) < 0)
        fail(filename, "cannot read dataset /status");
      h.status.resize(n_nodes);
      for (std::size_t i = 0; i < n_nodes; ++i)
        h.status[i].assign(status.begin() + i * t_shape[0],
                           status.begin() + (i + 1) * t_shape[0]);

      if (H5LTfind_dataset(f.id, "face") > 0)
        {
          H5T_class_t face_class = H5T_NO_CLASS;
          if (dataset_shape(f.id, filename, "/face", &face_class) !=
                std::vector<hsize_t>{n_nodes} ||
              face_class != H5T_INTEGER)
            fail(filename, "dataset /face must hold n_nodes integers");
          std::vector<int> face(n_nodes);
          if (H5LTread_dataset_int(f.id, "/face", face.data()) < 0)
            fail(filename, "cannot read dataset /face");
          for (std::size_t i = 0; i < n_nodes; ++i)
            if (face[i] < 0)
              fail(filename,
                   "dataset /face: negative value at node " +
                     std::to_string(i));
          h.face.assign(face.begin(), face.end());
          hsize_t     dims = 0;
          H5T_class_t cls;
          std::size_t size = 0;
          if (H5LTget_attribute_info(
                f.id, "/face", "names", &dims, &cls, &size) < 0 ||
              cls != H5T_STRING)
            fail(filename,
                 "dataset /face needs a string attribute 'names' (the pad "
                 "faces, separated by ';')");
          std::string names(size + 1, '\0');
          if (H5LTget_attribute_string(f.id, "/face", "names", names.data()) <
              0)
            fail(filename, "cannot read attribute 'names' of /face");
          h.face_names =
            dealii::Utilities::split_string_list(names.c_str(), ';');
        }
      h.sampling_rate =
        read_attribute(f.id, filename, "sampling_rate", 1).front();
      h.sliding_direction =
        read_vector_attribute(f.id, filename, "sliding_direction");
      h.radial_direction =
        read_vector_attribute(f.id, filename, "radial_direction");
      h.check(filename);
      return h;
    }
  } // namespace io
} // namespace squeal
