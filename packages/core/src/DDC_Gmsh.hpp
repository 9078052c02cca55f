// Reader for Gmsh meshes (MSH 4.1, ASCII): one body per call.
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
//    only nodes used by the body's elements); parametric node blocks; z must
//    be 0 (planar meshes in the xy-plane; |z| <= 1e-10 * max(1, |x|, |y|)).
//  - 2-D elements: type 3 (4-node quadrangle) for a Quad4 body, type 10
//    (9-node quadrangle) for a Quad9 body. Triangles, 8-node quadrangles, the
//    other order of quadrangles and any 3-D element are rejected.
//    Clockwise quadrangles (a surface with normal -z) are reordered to
//    counter-clockwise; degenerate (zero-area) ones are rejected.
//  - 1-D elements: type 1 (2-node line) with Quad4, type 8 (3-node line)
//    with Quad9, only where they belong to a physical curve; other lines are
//    ignored. 0-D elements (type 15) are ignored (physical points are taken
//    from $Entities).
//
// Sets, qualified by the body name ("<body>/<physical name>"; a physical
// group without a name in $PhysicalNames is named by its tag, e.g. "7"):
//  - physical curves -> side sets (and node sets, Mesh::addSideSet): each
//    line is matched to the element side it lies on and oriented by
//    Mesh::makeSegment (body on the left, outward normal (dy, -dx)/|.|).
//    A line that is not a side of any element, or lies on a side shared by
//    two elements (an interior edge), is an error;
//  - physical points -> node sets;
//  - physical surfaces -> node sets (the nodes of their elements).
//  A physical curve and a physical point / surface with the same name
//  define one node set (the union).
//
// "Physical Surface" selects the body's elements when a file holds several
// bodies: only 2-D elements of that physical surface are read. Physical
// curves and points are then matched only where all their nodes belong to
// the selected elements (lines and points of other bodies are skipped); a
// line whose nodes are all in the body but which is not a side of one of its
// elements is still an error. Without "Physical Surface" every 2-D element of
// the file is read and every physical curve / point must belong to it.
//
// Note: Gmsh saves only elements of physical groups once any physical group
// exists (Mesh.SaveAll = 0); define a Physical Surface for the body, or the
// file will contain no 2-D elements (rejected with that hint).
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>
#include <string>

#include "DDC_Mesh.hpp"

namespace ddc {

/// Parameters of a Gmsh body.
class GmshReader {
 public:
  /// "File" (string, required) and "Physical Surface" (string, default "").
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
};

/// Read one body from a Gmsh MSH 4.1 ASCII file (see the file comment for
/// what is supported) and add it to `mesh`.
/// \param params the body's mesh sublist: "File" (relative paths are
///        resolved against `baseDirectory`), optional "Physical Surface".
///        Validated (this level) against GmshReader::getValidParameters().
/// \param path parameter path of `params`, for messages.
/// \param baseDirectory directory of the input deck ("" = current directory).
/// \return the index of the new body.
/// \throws InputError naming the file (and line) for missing files,
///         unsupported variants or malformed content; naming `path` for
///         parameter errors.
int readGmshBody(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                 const std::string& path, const std::string& baseDirectory);

/// Read a file directly (used by readGmshBody; handy for tests and tools).
/// \param fileName path as given (already resolved).
/// \param physicalSurface "" for all 2-D elements, else a physical surface name.
int readGmshFile(Mesh& mesh, const std::string& bodyName, CellType type, const std::string& fileName,
                 const std::string& physicalSurface = "");

}  // namespace ddc
