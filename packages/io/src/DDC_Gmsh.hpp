// Reader for Gmsh meshes (MSH 4.1, ASCII): one body per call, 2-D or 3-D
// by the body's element type.
//
// Supported (everything else is rejected with an InputError naming the file,
// the line and what was expected):
//  - "$MeshFormat" version 4.1, file-type 0 (ASCII). Versions 2.2, 4.0, ...
//    and binary files are rejected (write with Mesh.MshFileVersion = 4.1,
//    Mesh.Binary = 0).
//  - Sections $PhysicalNames, $Entities, $Nodes, $Elements. Other sections
//    ($Periodic, $NodeData, ...) are skipped; $PartitionedEntities
//    (partitioned meshes) is rejected.
//  - Nodes: any tags (renumbered compactly in increasing tag order, keeping
//    only nodes used by the body's elements); parametric node blocks. For a
//    2-D body z must be 0 (planar meshes in the xy-plane;
//    |z| <= 1e-10 * max(1, |x|, |y|)).
//
// 2-D bodies (Quad4, Quad9):
//  - elements: type 3 (4-node quadrangle) for a Quad4 body, type 10 (9-node
//    quadrangle) for a Quad9 body. Triangles, 8-node quadrangles, the other
//    order of quadrangles and any 3-D element are rejected. Clockwise
//    quadrangles (a surface with normal -z) are reordered to
//    counter-clockwise; degenerate (zero-area) ones are rejected.
//  - side sets: type 1 (2-node line) with Quad4, type 8 (3-node line) with
//    Quad9, only where they belong to a physical curve; other lines are
//    ignored. 0-D elements (type 15) are ignored (physical points are taken
//    from $Entities).
//
// 3-D bodies (Hex8, Hex20, Hex27, Tet4, Tet10):
//  - elements: type 5 (8-node hexahedron) for Hex8, 17 (20-node hexahedron)
//    for Hex20, 12 (27-node hexahedron) for Hex27, 4 (4-node tetrahedron) for
//    Tet4, 11 (10-node tetrahedron) for Tet10 -- one type per body: mixed
//    types (hexahedra and tetrahedra, or two orders) are rejected, and so
//    are prisms (types 6, 13, 18), pyramids (7, 14, 19), higher orders and
//    any other type, naming the type and the supported ones. Elements are
//    taken as Gmsh writes them (positively oriented); an inverted or
//    degenerate element (cornerJacobian(): det J of the corner map at a
//    corner or the centre) is rejected with its element tag and line, not
//    reordered.
//  - side sets: the faces of the body's cells -- type 3 (4-node quadrangle)
//    with Hex8, 16 (8-node quadrangle) with Hex20, 10 (9-node quadrangle)
//    with Hex27, 2 (3-node triangle) with Tet4, 9 (6-node triangle) with
//    Tet10 -- where they belong to a physical surface. Faces of another
//    type or dimension in a physical surface (triangles on a hexahedral
//    body, lines in a surface) are rejected; faces of no physical surface
//    are ignored.
//  - physical curves (lines of type 1 or 8) -> node sets.
//
// Sets, qualified by the body name ("<body>/<physical name>"; a physical
// group without a name in $PhysicalNames is named by its tag, e.g. "7"):
//  - side sets from the physical groups one dimension below the body
//    (curves in 2-D, surfaces in 3-D), also node sets (Mesh::addSideSet):
//    each line / face is matched to the element side / face whose corners it
//    has (as a set) and oriented by Mesh::makeSegment (outward normal), so
//    its orientation in the file does not matter; its other nodes must be
//    those of that element side / face. A line / face that is not a side of
//    any element, or lies on a side shared by two elements (inside the
//    body), is an error;
//  - physical points -> node sets; in 3-D also physical curves;
//  - physical surfaces (2-D) / volumes (3-D) -> node sets (the nodes of
//    their elements).
//  Physical groups of different dimensions with the same name define one
//  node set (the union).
//
// "Physical Surface" (2-D bodies) / "Physical Volume" (3-D bodies) selects
// the body's elements when a file holds several bodies: only elements of
// that physical group are read. Physical groups of lower dimension are then
// matched only where all their nodes belong to the selected elements
// (lines, faces and points of other bodies are skipped); a line / face whose
// nodes are all in the body but which is not a side of one of its elements
// is still an error. Without a selection every element of the body's
// dimension in the file is read and every physical group of lower
// dimension must belong to it.
//
// In ranges (readGmshBodyInRange(); doc/partitioning.md): every rank reads
// the file as it streams by and keeps its range of the body's elements, an
// even share of the node tags, and the elements of lower dimension (the
// side sets, curves and points: the size of the boundary); the node
// numbering and every set membership go through the nodes' owners. No rank
// holds the whole body, and each fault is named as the whole reader names
// it. Every rank reads the whole text, twice (once to count the body's
// elements); the file system serves the same file to all.
//
// Note: Gmsh saves only elements of physical groups once any physical group
// exists (Mesh.SaveAll = 0); define a Physical Surface / Volume for the
// body, or the file will contain no elements of the body's dimension
// (rejected with that hint).
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>
#include <mpi.h>

#include <string>

#include "DDC_Error.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_MeshGenerators.hpp"

namespace ddc {

/// Parameters of a Gmsh body.
class GmshReader {
 public:
  /// "File" (string, required), "Physical Surface" and "Physical Volume"
  /// (strings, default ""; the one of the body's dimension selects it, the
  /// other must stay empty).
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
};

/// Read one body from a Gmsh MSH 4.1 ASCII file (see the file comment for
/// what is supported) and add it to `mesh`.
/// \param params the body's mesh sublist: "File" (relative paths are
///        resolved against `baseDirectory`), optional "Physical Surface"
///        (2-D) or "Physical Volume" (3-D).
///        Validated (this level) against GmshReader::getValidParameters().
/// \param path parameter path of `params`, for messages.
/// \param baseDirectory directory of the input deck ("" = current directory).
/// \return the index of the new body.
/// \throws InputError naming the file (and line) for missing files,
///         unsupported variants or malformed content; naming `path` for
///         parameter errors.
int readGmshBody(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                 const std::string& path, const std::string& baseDirectory);

/// The file (resolved against `baseDirectory`) and the selecting physical
/// group of a Gmsh body's parameters, validated as readGmshBody() does.
struct GmshBodyFile {
  std::string file, group;
};
GmshBodyFile gmshBodyFile(Teuchos::ParameterList& params, const std::string& bodyName, CellType type,
                          const std::string& path, const std::string& baseDirectory);
/// Throws `e` again, led by the parameter path `path`/File and the body.
[[noreturn]] void throwForBody(const InputError& e, const std::string& bodyName, const std::string& path);

/// The number of elements readGmshBody() would read (the file is parsed on
/// every rank). Collective on `comm`; a fault of the file is thrown on
/// every rank with the whole reader's message.
long long gmshBodyElementCount(Teuchos::ParameterList& params, const std::string& bodyName, CellType type,
                               const std::string& path, const std::string& baseDirectory, MPI_Comm comm);

/// readGmshBody() making only the body's elements whose ids in the whole
/// mesh lie in `range` (they follow those of the bodies before it), and
/// their nodes, into the part `part` (Mesh::startPart()): the part
/// Mesh::part() would cut from the whole read, with the whole reader's
/// messages (see "In ranges" above). Collective on `comm`; the ranges of
/// the ranks must be contiguous in rank order.
int readGmshBodyInRange(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                        const std::string& path, const std::string& baseDirectory, const ElementRange& range,
                        MPI_Comm comm);

/// gmshBodyElementCount() and readGmshBodyInRange() of a file directly.
long long gmshFileElementCount(const std::string& fileName, const std::string& bodyName, CellType type,
                               const std::string& physicalGroup, MPI_Comm comm);
int readGmshFileInRange(Mesh& part, const std::string& bodyName, CellType type, const std::string& fileName,
                        const std::string& physicalGroup, const ElementRange& range, MPI_Comm comm);

/// Read a file directly (used by readGmshBody; handy for tests and tools).
/// \param fileName path as given (already resolved).
/// \param type the body's element type; its dimension says whether 2-D or
///        3-D elements are read.
/// \param physicalGroup "" for every element of the body's dimension, else
///        the name of a physical surface (2-D) or volume (3-D).
int readGmshFile(Mesh& mesh, const std::string& bodyName, CellType type, const std::string& fileName,
                 const std::string& physicalGroup = "");

}  // namespace ddc
