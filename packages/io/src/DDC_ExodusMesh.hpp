// Reader for Exodus II meshes (Mesh/Bodies/<name>/Generator = Exodus): one
// body per element block, read with the Exodus II library (SEACAS, on
// NetCDF; Cubit, Gmsh, meshio and SEACAS tools write the format).
//
// - The block: "Element Block" names it by name or by id; empty selects the
//   file's only block. Its element type must mean the body's cell type
//   (exodusElementTypeNames(): QUAD/QUAD4 for Quad4, QUAD9, HEX/HEX8, HEX20,
//   HEX27, TETRA/TETRA4/TET4 for Tet4, TETRA10) with as many nodes; node
//   order and side numbering are Exodus II's (DDC_ExodusCells.hpp). A 2-D
//   body needs a 2-D file, or a 3-D one with z = 0.
// - Nodes: those of the block's elements, renumbered compactly in increasing
//   Exodus node number. Elements: in the block's order; an inverted or
//   degenerate element (cornerJacobian()) is an error naming it (its number
//   in the file and in the block).
// - Node sets: each node set of the file, restricted to the block's nodes,
//   becomes a node set of the body ("<body>/<set name>"; a set without a
//   name is "nodeset_<id>"); sets with none of the block's nodes are left out.
// - Side sets: each side set's sides on the block's elements become a side
//   set ("<body>/<name>" or "sideset_<id>") - and a node set - oriented
//   outward (Mesh::makeSegment); sides on other blocks are left out. A side
//   on an element number the file does not have, or a side number the
//   element type does not have, is an error naming the set.
// Every error names the file and the entity.
//
// A body is read whole (readExodusBody()), or in slabs, each rank the
// elements of a range of ids (readExodusBodyInRange()): the part of the
// whole body that Mesh::part() would cut, with the same messages, and no
// rank reading or holding the whole block, its coordinates or its sets
// (doc/architecture.md, "What a distributed mesh has to change").
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>
#include <mpi.h>

#include <string>

#include "DDC_Mesh.hpp"
#include "DDC_MeshGenerators.hpp"

namespace ddc {

/// Parameters of an Exodus II body.
class ExodusMeshReader {
 public:
  /// "File" (string, required), "Element Block" (string, default "").
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
};

/// Read one body from an Exodus II file (see the top of this file) and add
/// it to `mesh`.
/// \param params the body's "Exodus" sublist: "File" (a relative path is
///        resolved against `baseDirectory`) and "Element Block"; validated
///        against ExodusMeshReader::getValidParameters().
/// \param path the parameter path of `params`, for messages.
/// \return the index of the new body.
/// \throws InputError naming the parameter, the file and the entity.
int readExodusBody(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                   const std::string& path, const std::string& baseDirectory);

/// The number of elements of the body's element block (the header alone).
/// \throws InputError as readExodusBody() for the file and the block
long long exodusBodyElementCount(Teuchos::ParameterList& params, const std::string& bodyName, CellType type,
                                 const std::string& path, const std::string& baseDirectory);

/// readExodusBody() for the elements of the body whose ids in the whole
/// mesh lie in `range` (the body's ids follow those of the bodies before
/// it, part.numGlobalElements() of them) and their nodes, into the part
/// `part` (Mesh::startPart()), as the generators make their ranges
/// (generateBox() with an ElementRange): the part Mesh::part() would cut
/// from the whole mesh, its side sets' segments by element and side. Each
/// rank reads its elements' connectivity (ex_get_partial_conn), an even
/// share of the file's coordinates and of each set's entries; the ranks'
/// ranges must be contiguous in rank order. Collective on `comm`.
/// \throws InputError on every rank, with the message readExodusBody()
///         gives for the first fault in the file
int readExodusBodyInRange(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                          const std::string& path, const std::string& baseDirectory, const ElementRange& range,
                          MPI_Comm comm);

}  // namespace ddc
