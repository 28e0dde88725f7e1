// Abaqus' numbering of a C3D8's corners and faces against deal.II's,
// shared by the .inp reader and writer (not part of the installed
// interface).

#ifndef squeal_source_io_abaqus_numbering_h
#define squeal_source_io_abaqus_numbering_h

#include <array>

namespace squeal
{
  namespace io
  {
    namespace internal
    {
      /// deal.II vertex v of a hexahedron is Abaqus corner abaqus_node[v]
      /// (0-based); the map is its own inverse.
      inline constexpr std::array<unsigned int, 8> abaqus_node{
        {0, 1, 3, 2, 4, 5, 7, 6}};
      /// Abaqus face S(k+1) of a C3D8 by its corners (0-based Abaqus nodes).
      inline constexpr std::array<std::array<unsigned int, 4>, 6> abaqus_face{
        {{{0, 1, 2, 3}},
         {{4, 7, 6, 5}},
         {{0, 4, 5, 1}},
         {{1, 5, 6, 2}},
         {{2, 6, 7, 3}},
         {{3, 7, 4, 0}}}};
      /// The Abaqus face number (1-6) of deal.II face f.
      inline constexpr std::array<unsigned int, 6> abaqus_face_of{
        {6, 4, 3, 5, 1, 2}};
    } // namespace internal
  }   // namespace io
} // namespace squeal

#endif
