// Element partitions of a Mesh into subdomains, and the map of subdomains to
// MPI ranks.
//
// Partitions are computed identically on every rank (METIS is deterministic
// for a fixed input and options), so no communication is needed; the mesh
// is replicated (doc/architecture.md).
#pragma once

#include <string>
#include <vector>

#include "DDC_Mesh.hpp"

namespace ddc {

/// An element partition: elementSubdomain[e] in [0, numSubdomains) for every
/// element of the mesh. Every subdomain holds at least one element.
struct Partition {
  int numSubdomains = 0;
  std::vector<int> elementSubdomain;
};

/// Partition the elements with METIS_PartMeshDual (k-way, minimum edge cut)
/// on the dual graph in which two elements are adjacent when they share an
/// edge (ncommon = 2). Only the four corner nodes of an element are passed,
/// so a Quad9 mesh is partitioned exactly like the Quad4 mesh of its corners.
/// Bodies share no nodes, so a subdomain never spans two touching bodies
/// through a shared edge, but METIS may give one subdomain elements of
/// several bodies (several components) when that balances best.
///
/// Deterministic: fixed METIS seed and options. METIS is asked for
/// contiguous subdomains when the dual graph is connected (one body in one
/// piece); with several bodies a subdomain may consist of several pieces.
/// Should METIS leave a subdomain empty (possible when numSubdomains is close
/// to the number of elements; METIS 5.1 does so often for tiny meshes), the
/// element of the largest subdomain with the fewest edge-neighbours in that
/// subdomain is moved into it, so that every subdomain is non-empty.
///
/// \param numSubdomains 1 gives all zeros without calling METIS.
/// \throws InputError if numSubdomains <= 0 or > mesh.numElements()
///         (messages name "Partition/Number of Subdomains").
/// \throws SolverError if METIS reports an error.
Partition partitionMetis(const Mesh& mesh, int numSubdomains);

/// One subdomain per body: elementSubdomain[e] = mesh.elementBody(e).
Partition partitionByBody(const Mesh& mesh);

/// Subdomains as a regular nx × ny (× nz in 3-D) grid of boxes over the
/// bounding box of the mesh nodes; an element belongs to the box holding its
/// centroid (node average). Subdomain id = ix + nx·(iy + ny·iz). On a box
/// with a matching element grid this gives equal subdomains of known H/h
/// (iteration studies).
/// \throws InputError naming "Partition/Box Grid X|Y|Z" if a count is < 1,
///         nz > 1 on a 2-D mesh, or a box holds no element.
Partition partitionBoxGrid(const Mesh& mesh, int nx, int ny, int nz = 1);

/// Subdomains read from a file: whitespace-separated integers, one per
/// element in mesh element order (bodies in input order, elements as
/// generated or read), '#' starts a comment. Subdomain ids must be 0..S-1
/// with every id used. For reproducible tests and externally made partitions.
/// 	hrows InputError naming the file and the problem (missing, too few or
///         too many entries, a negative id, an unused id).
Partition partitionFromFile(const Mesh& mesh, const std::string& fileName);

/// Owner rank of each subdomain: contiguous, balanced blocks (the first
/// numSubdomains % numRanks ranks own one subdomain more). Several
/// subdomains per rank are allowed; a rank without a subdomain is not.
/// \throws InputError if numRanks < 1 or numSubdomains < numRanks (naming
///         "Partition/Number of Subdomains").
std::vector<int> subdomainOwnerRank(int numSubdomains, int numRanks);

/// Subdomains owned by `rank` under subdomainOwnerRank(), in increasing order.
std::vector<int> subdomainsOfRank(int numSubdomains, int numRanks, int rank);

}  // namespace ddc
