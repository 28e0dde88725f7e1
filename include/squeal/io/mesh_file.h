#ifndef squeal_io_mesh_file_h
#define squeal_io_mesh_file_h

/**
 * @file
 * Hexahedral meshes with named sets from files, and back.
 *
 * Read: Gmsh `.msh` (ASCII, format 2.2 and 4.1) through deal.II's
 * GridIn::read_msh, the physical groups' names from the `$PhysicalNames`
 * section (volume groups become cell sets, surface groups face sets; an
 * unnamed group is called by its number); Abaqus/CalculiX `.inp` (a flat
 * input file: `*NODE`, `*ELEMENT` of types C3D8, C3D8R, C3D8I, C3D20 and
 * C3D20R, `*ELSET`, `*NSET`, `*SURFACE` of TYPE=ELEMENT, the GENERATE forms
 * included). Quadratic elements (C3D20, C3D20R) give their corner nodes
 * to the cells and their mid-side nodes to the geometry: a curved element
 * gets a manifold of its own (the 20-node serendipity map, manifold id
 * 1000 + its coarse cell index) on its cell, faces and edges, so refinement
 * and a higher-degree MappingQ follow the element's curvature. Gmsh's
 * second-order hexahedra (20 and 27 nodes) are read through Gmsh's API,
 * curved as C3D20.
 * VTK unstructured grids `.vtu` through VTK's XML reader: hexahedra (VTK
 * types 12, 25 = 20 nodes in the C3D20 order, 29 = 27 nodes, its face and
 * centre nodes dropped) make the cells, quadrilaterals (9, 23, 28) name
 * their faces; every one-component cell or point data array names sets:
 * an array of 0/1 values is the set called like the array (hexahedra:
 * a cell set, quadrilaterals: a face set, points: a node set), any other
 * one set per non-zero value, called `<array>=<value>`. Bodies meshed
 * separately stay separate: coincident nodes of two bodies are not merged.
 *
 * Write: the coarse mesh and its sets as an Abaqus/CalculiX `.inp` (C3D8,
 * one `*ELSET` per cell set, one element-based `*SURFACE` per face set, one
 * `*NSET` per node set of mesh nodes), so that the same model can be run in
 * CalculiX or Abaqus.
 *
 * Node orders: Abaqus numbers a C3D8's nodes 1-4 counter-clockwise on the
 * bottom face and 5-8 above them; deal.II numbers a hexahedron's vertices
 * lexicographically, so deal.II vertex v is Abaqus node abaqus_node[v] + 1
 * with abaqus_node = {0, 1, 3, 2, 4, 5, 7, 6}. Faces: Abaqus S1 ... S6 are
 * deal.II faces 4, 5, 2, 1, 3, 0 (face numbering of the Abaqus Analysis
 * User's Guide, "Three-dimensional solid element library"; the CalculiX
 * CrunchiX manual, C3D8, uses the same).
 */

#include <deal.II/grid/tria.h>

#include <squeal/io/named_sets.h>

#include <string>

namespace squeal
{
  namespace io
  {
    /**
     * Reads the hexahedral mesh @p filename (`.msh`, `.inp` or `.vtu`,
     * chosen by the extension) into the empty @p tria, every coordinate multiplied by
     * @p length_unit [m per file unit: 1e-3 for a mesh in mm], and returns
     * its named sets. Material and boundary ids are left 0: the scene
     * assigns them from the sets.
     * @throws std::runtime_error with one message naming the file (and the
     * line, element or set where there is one) if the file is missing or
     * malformed, holds an element type squeal cannot use (tetrahedra,
     * wedges, shells: which one, and that hexahedra are needed), a set
     * refers to an element or node that does not exist, or a cell is
     * inverted or degenerate (its Jacobian determinant at a corner is not
     * positive).
     */
    io::NamedSets
    read_mesh_file(const std::string        &filename,
                   double                    length_unit,
                   dealii::Triangulation<3> &tria);

    /**
     * Writes the coarse mesh @p tria (not refined) and @p sets to the
     * Abaqus/CalculiX input file @p filename: `*NODE` (coordinates divided
     * by @p length_unit), `*ELEMENT, TYPE=C3D8`, `*ELSET`, `*SURFACE`,
     * `*NSET` (the mesh vertices at the set's points). Element k is the
     * coarse cell k - 1, node i the vertex i - 1. Set names are written in
     * upper case with blanks as underscores (Abaqus names are
     * case-insensitive and blank-free); reading the file back gives the same
     * mesh and sets under those names.
     * @throws std::runtime_error if @p tria is refined, a node set point is
     * not a mesh vertex, or the file cannot be written.
     */
    void
    write_abaqus(const dealii::Triangulation<3> &tria,
                 const io::NamedSets            &sets,
                 const std::string              &filename,
                 double                          length_unit = 1.);

    /**
     * The name a set gets in an Abaqus file: upper case, blanks and other
     * characters Abaqus does not allow in names replaced by underscores.
     */
    std::string
    abaqus_name(const std::string &name);
  } // namespace io
} // namespace squeal

#endif
