// Element partitions of a Mesh into subdomains, and the map of subdomains to
// MPI ranks.
//
// Partitions are computed identically on every rank (METIS is deterministic
// for a fixed input and options), so no communication is needed; the mesh
// is replicated (doc/architecture.md).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "DDC_Mesh.hpp"

namespace ddc {

/// An element partition: elementSubdomain[e] in [0, numSubdomains) for every
/// element of the mesh. Every subdomain holds at least one element.
struct Partition {
  int numSubdomains = 0;
  std::vector<int> elementSubdomain;
  /// Facets whose elements lie in different subdomains (edgeCut()), for the
  /// graph partitioners (METIS, PT-Scotch); -1 where not computed.
  long long edgeCut = -1;
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

/// \throws InputError naming "Partition/Number of Subdomains" unless
///         0 < numSubdomains <= numElements.
void requirePartitionable(int numSubdomains, int numElements);

/// The corner count two elements of `mesh` must share to be adjacent in its
/// dual graph: 2 in 2-D (a side), in 3-D the corners of the smallest facet
/// of any body (3 for a triangle, 4 for a quadrilateral).
int dualGraphCommonCorners(const Mesh& mesh);

/// The dual graph of a mesh in compressed rows: row e holds the elements
/// that share a facet with element e. Used as a list of rows: size(),
/// nb[e].size(), `for (int f : nb[e])`.
class FacetGraph {
 public:
  /// The neighbours of one element.
  struct Row {
    const int* first;
    const int* last;
    const int* begin() const { return first; }
    const int* end() const { return last; }
    size_t size() const { return static_cast<size_t>(last - first); }
  };
  FacetGraph(std::vector<size_t> offset, std::vector<int> neighbours)
      : offset_(std::move(offset)), neighbours_(std::move(neighbours)) {}
  size_t size() const { return offset_.size() - 1; }
  bool empty() const { return size() == 0; }
  Row operator[](size_t e) const { return Row{neighbours_.data() + offset_[e], neighbours_.data() + offset_[e + 1]}; }

 private:
  std::vector<size_t> offset_;  ///< size() + 1
  std::vector<int> neighbours_;
};

/// The facet neighbours of each element (elements sharing a side in 2-D, a
/// face in 3-D): the dual graph of a replicated mesh, neighbours in the order
/// of the shared facets' sorted corner ids.
FacetGraph facetNeighbours(const Mesh& mesh);

/// The edge cut of a partition: the number of facets (dual-graph edges)
/// whose two elements lie in different subdomains.
long long edgeCut(const FacetGraph& neighbours, const Partition& p);

/// Give every empty subdomain one element taken from the currently largest
/// subdomain: the element with the fewest neighbours in its own subdomain
/// (lowest index on ties), so the donor stays as connected as possible.
void fillEmptySubdomains(const FacetGraph& neighbours, Partition& p);

/// Make subdomains single pieces where the mesh allows: every piece of a
/// subdomain other than its largest that touches another subdomain and has
/// at most kMaxJoinedPieceShare times the mean subdomain's elements (a
/// splinter) joins the subdomain it shares most facets with (lowest id on
/// ties). Larger pieces stay (a subdomain with a piece of each of two bodies,
/// as METIS makes them too), and so do pieces that touch no other subdomain.
/// Repeated while a piece moves, at most kMaxPieceJoinPasses times. The
/// subdomain counts stay non-zero.
void joinDetachedPieces(const FacetGraph& neighbours, Partition& p);
constexpr double kMaxJoinedPieceShare = 0.25;
constexpr int kMaxPieceJoinPasses = 8;

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
/// \throws InputError naming the file and the problem (missing, too few or
///         too many entries, a negative id, an unused id).
Partition partitionFromFile(const Mesh& mesh, const std::string& fileName);

/// Owner rank of each subdomain: contiguous, balanced blocks (the first
/// numSubdomains % numRanks ranks own one subdomain more). Several
/// subdomains per rank are allowed; a rank without a subdomain is not.
/// \throws InputError if numRanks < 1 or numSubdomains < numRanks (naming
///         "Partition/Number of Subdomains").
std::vector<int> subdomainOwnerRank(int numSubdomains, int numRanks);

/// Owner rank of each node of `mesh`: the lowest rank among the ranks
/// (subdomainOwnerRank()) of the subdomains of its elements; numRanks for a
/// node of no element. How the model owns a node's DOFs.
std::vector<int> nodeOwnerRanks(const Mesh& mesh, const Partition& partition, int numRanks);

/// Subdomains owned by `rank` under subdomainOwnerRank(), in increasing order.
std::vector<int> subdomainsOfRank(int numSubdomains, int numRanks, int rank);

/// A rank's part of a mesh and the subdomains of its elements.
struct RankPart {
  Mesh mesh;
  Partition partition;
};

/// The part of `mesh` that `rank` of `numRanks` holds under `partition`:
/// the elements of the subdomains subdomainOwnerRank() gives it and their
/// nodes (Mesh::part()), and those elements' subdomains.
RankPart rankPart(const Mesh& mesh, const Partition& partition, int rank, int numRanks);

/// rankPart() when no rank holds the whole mesh: every rank holds some
/// elements (`source`, a part, e.g. an even range of element ids) and their
/// subdomains (`sourcePartition`, one per element of `source`, the same
/// numSubdomains on every rank); each element goes to the rank of its
/// subdomain (Mesh::migrated()) with its subdomain. The result is the
/// rankPart() of the whole mesh under the whole partition. The edge cut is
/// not known here (-1). Collective on `comm`.
/// \throws std::invalid_argument if `sourcePartition` does not hold one
///         subdomain per element of `source`
RankPart migratedRankPart(MPI_Comm comm, const Mesh& source, const Partition& sourcePartition);

}  // namespace ddc
