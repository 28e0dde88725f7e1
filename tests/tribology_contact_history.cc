// The HDF5 contact history: the layout written by io::write_contact_history()
// round-trips exactly; the synthetic history at its leading inner node with
// amplitude 1 and unit mean pressure is the C3 history (to rounding); the
// damage computed from the file equals the damage of the arrays; and corrupt
// or inconsistent files give one error that names the dataset.

#include <squeal/io/contact_history.h>
#include <squeal/tribology/fatigue.h>
#include <squeal/tribology/synthetic_history.h>

#include <hdf5.h>
#include <hdf5_hl.h>

#include "check.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <type_traits>
#include <vector>

using namespace squeal::tribology;
namespace io = squeal::io;
using test_tools::check;

namespace
{
  // Writes @p h, then lets @p spoil damage the file, reads it back and
  // checks that the error names @p expected.
  template <typename Spoil>
  void
  expect_error(const std::string        &name,
               const io::ContactHistory &h,
               Spoil                   &&spoil,
               const std::string        &expected)
  {
    const std::string file = "spoiled_" + name + ".h5";
    std::remove(file.c_str());
    io::write_contact_history(file, h);
    {
      const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
      spoil(f);
      H5Fclose(f);
    }
    std::string message;
    try
      {
        io::read_contact_history(file);
      }
    catch (const std::exception &e)
      {
        message = e.what();
      }
    const bool ok = message.find(expected) != std::string::npos &&
                    message.find(file) != std::string::npos;
    if (!ok)
      test_tools::verbose() << name << ": got '" << message << "'" << std::endl;
    check("corrupt file (" + name + ") names '" + expected + "'", ok, 1., 0.);
  }
  // Replaces the n_nodes x n_samples dataset @p name of @p f by @p flat
  // (double or int values).
  template <typename T>
  void
  replace_field(const hid_t f, const char *name, const std::vector<T> &flat)
  {
    H5Ldelete(f, name, H5P_DEFAULT);
    const hsize_t dims[2] = {25, 10000};
    if constexpr (std::is_same_v<T, int>)
      H5LTmake_dataset_int(f, name, 2, dims, flat.data());
    else
      H5LTmake_dataset_double(f, name, 2, dims, flat.data());
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  // Amplitude 1 at the leading inner node (node 0), p_mean = 1, mu = 0.4.
  const io::ContactHistory h =
    synthetic_squeal_history(5, 10000, 1e6, 3400., 1., 0.4, 0.01, 0.1, 0.1);
  {
    double err = 0.;
    for (std::size_t n = 0; n < 10000; ++n)
      {
        const double c3 =
          std::max(0.,
                   1. + 15. * std::sin(2. * M_PI * 3400. * n / 1e6) +
                     3. * std::sin(2. * M_PI * 10200. * n / 1e6 + 0.7));
        err = std::max(err, std::abs(h.p_N[0][n] - c3));
      }
    check(
      "synthetic history at the leading inner node is C3", err, 0., 1e-11, 1.);
  }

  io::write_contact_history("history.h5", h);
  const io::ContactHistory r = io::read_contact_history("history.h5");
  check("round trip: nodes", r.n_nodes(), h.n_nodes(), 0.);
  check("round trip: samples", r.n_samples(), h.n_samples(), 0.);
  check("round trip: sampling rate", r.sampling_rate, 1e6, 0.);
  check("round trip: coordinates", r.coordinates == h.coordinates, 1., 0.);
  check("round trip: time", r.time == h.time, 1., 0.);
  check("round trip: p_N", r.p_N == h.p_N, 1., 0.);
  check("round trip: t_T1", r.t_T1 == h.t_T1, 1., 0.);
  check("round trip: t_T2", r.t_T2 == h.t_T2, 1., 0.);
  check("round trip: slip velocity",
        r.slip_velocity == h.slip_velocity,
        1.,
        0.);
  check("round trip: status", r.status == h.status, 1., 0.);
  check("round trip: frame",
        r.sliding_direction == h.sliding_direction &&
          r.radial_direction == h.radial_direction,
        1.,
        0.);
  check("C4 D* from the file equals C3's 3.607364580e6",
        findley_damage(r.p_N[0], r.t_T1[0], FindleyParameters()).relative,
        3.607364580e6,
        1e-9);
  {
    // units are stored as attributes
    char        unit[16] = {0};
    const hid_t f        = H5Fopen("history.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
    H5LTget_attribute_string(f, "/p_N", "unit", unit);
    H5Fclose(f);
    check("p_N carries unit Pa", std::string(unit) == "Pa", 1., 0.);
  }
  // The leading edge (smallest s) oscillates most.
  check("leading edge oscillates more than trailing edge",
        *std::max_element(h.p_N.front().begin(), h.p_N.front().end()) >
          2. * *std::max_element(h.p_N.back().begin(), h.p_N.back().end()),
        1.,
        0.);

  // Corrupt files.
  expect_error(
    "missing dataset",
    h,
    [](hid_t f) { H5Ldelete(f, "/t_T2", H5P_DEFAULT); },
    "missing dataset /t_T2");
  expect_error(
    "wrong shape",
    h,
    [](hid_t f) {
      H5Ldelete(f, "/slip_velocity", H5P_DEFAULT);
      const hsize_t       dims[2] = {3, 7};
      std::vector<double> zeros(21, 0.);
      H5LTmake_dataset_double(f, "/slip_velocity", 2, dims, zeros.data());
    },
    "dataset /slip_velocity has shape 3 x 7, expected 25 x 10000");
  expect_error(
    "NaN",
    h,
    [&](hid_t f) {
      std::vector<double> flat;
      for (auto row : h.p_N)
        flat.insert(flat.end(), row.begin(), row.end());
      flat[3 * 10000 + 17] = std::nan("");
      replace_field(f, "/p_N", flat);
    },
    "dataset /p_N: non-finite value (NaN or Inf) at node 3");
  expect_error(
    "negative pressure",
    h,
    [&](hid_t f) {
      std::vector<double> flat;
      for (auto row : h.p_N)
        flat.insert(flat.end(), row.begin(), row.end());
      flat[5 * 10000] = -1.;
      replace_field(f, "/p_N", flat);
    },
    "negative contact pressure at node 5");
  expect_error(
    "bad status",
    h,
    [&](hid_t f) {
      std::vector<int> flat(25 * 10000, 1);
      flat[42] = 7;
      replace_field(f, "/status", flat);
    },
    "dataset /status: value 7 at node 0");
  expect_error(
    "missing attribute",
    h,
    [](hid_t f) { H5Adelete(f, "sampling_rate"); },
    "missing root attribute sampling_rate");
  expect_error(
    "sampling rate of 4000 values",
    h,
    [](hid_t f) {
      H5Adelete(f, "sampling_rate");
      const std::vector<double> rates(4000, 1e5);
      H5LTset_attribute_double(f, "/", "sampling_rate", rates.data(), 4000);
    },
    "root attribute sampling_rate must hold one number");
  expect_error(
    "float status",
    h,
    [](hid_t f) {
      replace_field(f, "/status", std::vector<double>(25 * 10000, 1.5));
    },
    "dataset /status must hold integers");
  expect_error(
    "decreasing time",
    h,
    [&](hid_t f) {
      std::vector<double> t(h.time.rbegin(), h.time.rend());
      H5Ldelete(f, "/time", H5P_DEFAULT);
      const hsize_t n = t.size();
      H5LTmake_dataset_double(f, "/time", 1, &n, t.data());
    },
    "dataset /time must increase: sample 1");
  expect_error(
    "radial sliding direction",
    h,
    [&](hid_t f) {
      H5LTset_attribute_double(
        f, "/", "sliding_direction", h.radial_direction.data(), 3);
    },
    "sliding_direction and radial_direction must be orthogonal");
  expect_error(
    "1e11 samples",
    h,
    [](hid_t f) {
      // a chunked dataset without storage: its shape alone is huge
      H5Ldelete(f, "/time", H5P_DEFAULT);
      const hsize_t n = 100000000000ull, chunk = 1024;
      const hid_t   space = H5Screate_simple(1, &n, nullptr);
      const hid_t   plist = H5Pcreate(H5P_DATASET_CREATE);
      H5Pset_chunk(plist, 1, &chunk);
      const hid_t d = H5Dcreate2(
        f, "/time", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, plist, H5P_DEFAULT);
      H5Dclose(d);
      H5Pclose(plist);
      H5Sclose(space);
    },
    "25 nodes x 100000000000 samples need 1.8e+05 GB to read");

  // Two pad faces: nodes 0-9 on 'inner pad', 10-24 on 'outer pad'.
  io::ContactHistory two = h;
  two.face_names         = {"inner pad", "outer pad"};
  two.face.assign(25, 1);
  std::fill(two.face.begin(), two.face.begin() + 10, 0);
  io::write_contact_history("two_faces.h5", two);
  {
    io::ContactHistory t = io::read_contact_history("two_faces.h5");
    check("round trip: faces",
          t.face == two.face && t.face_names == two.face_names,
          1.,
          0.);
    check("the one-face history has no /face", r.face.empty(), 1., 0.);
    io::ContactHistory inner = t;
    inner.keep_face("inner pad");
    check("keep_face('inner pad'): its rows are nodes 0-9",
          inner.n_nodes() == 10 && inner.p_N[0] == h.p_N[0] &&
            inner.t_T2[9] == h.t_T2[9] && inner.status[4] == h.status[4],
          1.,
          0.);
    t.keep_face("outer pad");
    check("keep_face('outer pad'): nodes", t.n_nodes(), 15., 0.);
    check("keep_face: its rows are nodes 10-24",
          t.coordinates.front() == h.coordinates[10] &&
            t.p_N.back() == h.p_N[24] && t.status[3] == h.status[13] &&
            t.t_T1[0] == h.t_T1[10] &&
            t.slip_velocity[14] == h.slip_velocity[24],
          1.,
          0.);
    check("keep_face: one face left",
          t.face_names.size() == 1 &&
            t.face == std::vector<unsigned int>(15, 0),
          1.,
          0.);
    std::string message;
    try
      {
        t.keep_face("inner pad");
      }
    catch (const std::exception &e)
      {
        message = e.what();
      }
    check("an absent face is refused, naming the faces there are",
          message.find("no pad face 'inner pad'") != std::string::npos &&
            message.find("'outer pad'") != std::string::npos,
          1.,
          0.);
  }
  expect_error(
    "face index beyond the names",
    two,
    [](hid_t f) {
      std::vector<int> face(25, 0);
      face[12] = 2;
      H5Ldelete(f, "/face", H5P_DEFAULT);
      const hsize_t n = 25;
      H5LTmake_dataset_int(f, "/face", 1, &n, face.data());
      H5LTset_attribute_string(f, "/face", "names", "inner pad;outer pad");
    },
    "dataset /face: value 2 at node 12");
  expect_error(
    "face without names",
    two,
    [](hid_t f) { H5Adelete_by_name(f, "/face", "names", H5P_DEFAULT); },
    "dataset /face needs a string attribute 'names'");

  {
    std::ofstream("not_hdf5.h5") << "plain text, not HDF5\n";
    std::string message;
    try
      {
        io::read_contact_history("not_hdf5.h5");
      }
    catch (const std::exception &e)
      {
        message = e.what();
      }
    check("a text file is refused as not HDF5",
          message.find("not an HDF5 file") != std::string::npos,
          1.,
          0.);
    try
      {
        io::read_contact_history("does_not_exist.h5");
      }
    catch (const std::exception &e)
      {
        message = e.what();
      }
    check("a missing file is named",
          message.find("does_not_exist.h5': no such file") != std::string::npos,
          1.,
          0.);
  }
  return test_tools::finish();
}
