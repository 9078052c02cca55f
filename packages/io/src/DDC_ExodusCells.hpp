// The element conventions of Exodus II (Schoof & Yarberry, "EXODUS II: A
// Finite Element Data Model", SAND92-2137; SEACAS "Element types"): the
// element type names, the node order of each type against the mesh's (Gmsh)
// order of DDC_ReferenceCell.hpp - they differ for Hex20, Hex27 and Tet10 -
// and the side numbering. Shared by the Exodus II mesh reader and the
// results writer.
#pragma once

#include <string>
#include <vector>

#include "DDC_ReferenceCell.hpp"

namespace ddc {

/// Exodus II node permutation of an element cell type: exodus[i] =
/// ours[order[i]], computed from the reference coordinates.
/// \throws std::invalid_argument for a facet cell type.
const std::vector<int>& exodusNodeOrder(CellType t);
/// Exodus II side number (1-based) of facet `f` of an element cell type
/// (its index in referenceCell(t).facets).
int exodusSideNumber(CellType t, int f);
/// The facet of an element cell type with Exodus II side number `side`
/// (1-based); -1 if the type has no such side.
int exodusFacetOfSide(CellType t, int side);
/// The Exodus II element type name DDContact writes ("QUAD4", "HEX20",
/// "TETRA", ...).
const char* exodusElementType(CellType t);
/// Every Exodus II element type name (upper case) that means this cell type
/// ("HEX" and "HEX8" for Hex8, ...); empty for a facet cell type.
std::vector<std::string> exodusElementTypeNames(CellType t);
/// The Exodus II library's message for its last error (`status`: the
/// failed call's return value, shown when the library has no message).
std::string exodusLibraryError(int status);

}  // namespace ddc
