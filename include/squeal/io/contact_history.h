#ifndef squeal_io_contact_history_h
#define squeal_io_contact_history_h

/**
 * @file
 * The contact-stress history of the pad face: what the transient braking
 * simulation records at every slave (pad) node and the tribology module
 * reads. Stored as HDF5 (`contact_history.h5`), node-major so that one node's
 * history is contiguous:
 *
 * | dataset | shape | type | unit attribute |
 * |---|---|---|---|
 * | `/coordinates` | n_nodes x 3 | double | m |
 * | `/time` | n_samples | double | s |
 * | `/p_N` | n_nodes x n_samples | double | Pa (contact pressure, >= 0) |
 * | `/t_T1` | n_nodes x n_samples | double | Pa (traction along the sliding direction) |
 * | `/t_T2` | n_nodes x n_samples | double | Pa (traction along the radial direction) |
 * | `/slip_velocity` | n_nodes x n_samples | double | m/s |
 * | `/status` | n_nodes x n_samples | int | 0 separated, 1 stick, 2 slip |
 * | `/face` (optional) | n_nodes | int | index of the node's pad face |
 *
 * `/face` has a string attribute `names`: the pad faces (the scene's contact
 * pairs, e.g. `inner pad;outer pad`), separated by `;`. A file without it
 * holds one unnamed face.
 * Root attributes: `sampling_rate` (double, Hz), `sliding_direction` and
 * `radial_direction` (3 doubles each, unit vectors: the pad-face frame of the
 * maps), `format` (string, "squeal contact history 1"). Every dataset carries
 * a string attribute `unit`.
 */

#include <array>
#include <string>
#include <vector>

namespace squeal
{
  namespace io
  {
    /** A contact history in memory; the layout of the file above. */
    struct ContactHistory
    {
      std::vector<std::array<double, 3>> coordinates;        ///< [node], m
      std::vector<double>                time;               ///< [sample], s
      double                             sampling_rate = 0.; ///< Hz
      std::array<double, 3> sliding_direction{{0., 1., 0.}}; ///< unit vector
      std::array<double, 3> radial_direction{{1., 0., 0.}};  ///< unit vector
      std::vector<std::vector<double>> p_N;           ///< [node][sample], Pa
      std::vector<std::vector<double>> t_T1;          ///< [node][sample], Pa
      std::vector<std::vector<double>> t_T2;          ///< [node][sample], Pa
      std::vector<std::vector<double>> slip_velocity; ///< [node][sample], m/s
      std::vector<std::vector<int>>    status;        ///< [node][sample]
      /// [node]: index into face_names of the node's pad face; empty: one
      /// unnamed face
      std::vector<unsigned int> face;
      /// names of the pad faces (the scene's contact pairs), none of them
      /// empty or containing ';'
      std::vector<std::string> face_names;

      /** Number of slave (pad-face) nodes. */
      std::size_t
      n_nodes() const
      {
        return coordinates.size();
      }
      /** Number of samples per node. */
      std::size_t
      n_samples() const
      {
        return time.size();
      }

      /**
       * Checks shapes, finiteness, p_N >= 0, status in {0, 1, 2}, a positive
       * sampling rate and unit frame vectors.
       * @throws std::runtime_error naming the first offending dataset
       * (and node), prefixed by @p where (a file name).
       */
      void
      check(const std::string &where) const;

      /**
       * Keeps only the nodes of the pad face named @p name (their rows of
       * every dataset, in order); afterwards the history holds that one
       * face.
       * @throws std::runtime_error if there is no face of that name, naming
       * the faces there are.
       */
      void
      keep_face(const std::string &name);

      /** The face names quoted and separated by commas ("'inner pad',
       * 'outer pad'"), for messages; empty for one unnamed face. */
      std::string
      face_list() const;

      /** Pad-face coordinates of a node: (position . sliding, position .
       * radial) [m]: the x and y axes of every map. */
      std::array<double, 2>
      face_coordinates(std::size_t node) const;
    };

    /**
     * Writes @p history to @p filename (HDF5, the layout above), through a
     * temporary name renamed at the end.
     * @throws std::runtime_error if the history fails check() or the file
     * cannot be written.
     */
    void
    write_contact_history(const std::string    &filename,
                          const ContactHistory &history);

    /**
     * Reads and checks a contact history.
     * @throws std::runtime_error naming the file and the dataset or
     * attribute that is missing, of the wrong shape, or invalid (NaN,
     * negative pressure, unknown status).
     */
    ContactHistory
    read_contact_history(const std::string &filename);
  } // namespace io
} // namespace squeal

#endif
