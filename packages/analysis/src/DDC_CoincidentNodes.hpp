// Nodes of different bodies at one position that nothing joins
// (doc/user-guide.md, "Writing an input deck": "Bodies that touch").
#pragma once

#include <mpi.h>

#include "DDC_ContactParameters.hpp"
#include "DDC_Mesh.hpp"

namespace ddc {

/// Refuse a mesh in which two bodies have nodes at the same position (within
/// 1e-9 of the mesh's bounding-box diagonal) and no contact pair joins the
/// two bodies: bodies share no nodes, so such bodies are analysed as if cut
/// apart there (two element blocks of one conforming mesh read as two bodies
/// carry no load across their interface). Found by a hash of the nodes'
/// cells (O(number of nodes)). On a whole mesh every rank searches it and
/// throws the same error; on parts of a mesh (Mesh::isPart()) each node
/// goes to the rank of its cell of a coarser grid (and of a neighbouring
/// cell when it lies within the tolerance of it), which compares the nodes
/// it receives, and the ranks' findings are summed on every rank
/// (collective over `comm`): the same error.
/// \throws InputError naming the two bodies, how many positions they share,
///         the coincident pair of lowest node ids (the lower body's first)
///         and its coordinates, and what to do
void requireJoinedCoincidentNodes(const Mesh& mesh, const ContactOptions& contact, MPI_Comm comm = MPI_COMM_SELF);

}  // namespace ddc
