// Parallel element partitioning (doc/partitioning.md): the dual graph of a
// distributed element list, built without any rank holding the whole mesh,
// and its k-way partition by PT-Scotch (F. Pellegrini, C. Chevalier,
// "PT-Scotch: a tool for efficient parallel graph ordering", Parallel
// Computing 34 (2008) 318-331), the parallel counterpart of the serial
// METIS partition (DDC_Partition.hpp).
//
// The dual graph is built the way ParMETIS_V3_Mesh2Dual builds it: every
// (corner node, element) pair goes to the node's home rank, which sends each
// element the elements it shares the node with; two elements are adjacent
// when they share at least `ncommon` corners (a side in 2-D, a face in 3-D).
// The records a rank sends grow with its own elements, never with the mesh.
#pragma once

#include <mpi.h>

#include <algorithm>
#include <vector>

#include "DDC_Partition.hpp"

namespace ddc {

/// A graph whose vertices (elements) are spread over the ranks in contiguous
/// ranges of global ids: rank r holds [firstVertex[r], firstVertex[r+1]).
/// Adjacency of this rank's vertices in CSR form, by global id, each list
/// sorted, without self-loops.
struct DistributedGraph {
  std::vector<long long> firstVertex;  ///< size ranks + 1
  std::vector<long long> offsets;      ///< local vertex -> first entry of `neighbours`; size local + 1
  std::vector<long long> neighbours;   ///< global vertex ids

  long long numLocal() const { return static_cast<long long>(offsets.size()) - 1; }
  /// The rank whose range holds global vertex v.
  int holder(long long v) const {
    return static_cast<int>(std::upper_bound(firstVertex.begin(), firstVertex.end(), v) - firstVertex.begin()) - 1;
  }
};

/// The dual graph of this rank's elements: element l (global id
/// firstVertex[rank] + l, ranges in rank order) has the corner nodes
/// corners[cornerOffsets[l] .. cornerOffsets[l+1]) (global node ids, any
/// numbering); it is adjacent to every element, on any rank, that shares at
/// least `ncommon` of them. Collective.
/// \throws std::invalid_argument (on every rank) if ncommon < 1, offsets are
///         not a CSR offset array or a node id is negative.
DistributedGraph distributedDualGraph(MPI_Comm comm, const std::vector<long long>& cornerOffsets,
                                      const std::vector<long long>& corners, int ncommon);

/// A k-way partition of `graph` into numParts parts with PT-Scotch's
/// quality strategy and at most kPtScotchImbalance load imbalance: the part
/// of each local vertex. Deterministic for a given graph and rank count
/// (a Scotch context with its deterministic option and a fixed seed).
/// Collective; needs MPI_THREAD_MULTIPLE on more than one rank
/// (requirePtScotchThreadLevel()).
/// \throws SolverError (on every rank) if PT-Scotch reports an error.
std::vector<int> partitionGraphPtScotch(MPI_Comm comm, const DistributedGraph& graph, int numParts);

/// Load imbalance PT-Scotch may leave: the largest part holds at most
/// (1 + this) times the mean number of elements.
constexpr double kPtScotchImbalance = 0.03;

/// PT-Scotch's threads call MPI: on more than one rank it needs MPI's thread
/// level (MPI_Query_thread) to be MPI_THREAD_MULTIPLE (ddc::MpiSession).
/// \throws InputError naming 'Partition/Method' otherwise.
void requirePtScotchThreadLevel(int ranks, int threadLevel);

/// fillEmptySubdomains() of DDC_Partition.hpp on a graph spread over the
/// ranks: `parts` holds the subdomain of each local vertex of `graph`, in
/// [0, numSubdomains), and every empty subdomain receives the vertex the
/// serial rule chooses (of the largest subdomain, the one with the fewest
/// neighbours inside it, lowest global id on ties). Collective; the result
/// is the serial one on the gathered parts.
/// \throws std::invalid_argument (on every rank) if `parts` does not hold one
///         subdomain in range per local vertex.
void fillEmptySubdomains(MPI_Comm comm, const DistributedGraph& graph, int numSubdomains, std::vector<int>& parts);

/// joinDetachedPieces() of DDC_Partition.hpp on a graph spread over the
/// ranks, with its rules and tie-breaks: a piece is found by spreading the
/// lowest vertex id over the subdomain's edges and judged by the rank that
/// holds that vertex. Collective; the result is the serial one on the
/// gathered parts. \throws as fillEmptySubdomains().
void joinDetachedPieces(MPI_Comm comm, const DistributedGraph& graph, int numSubdomains, std::vector<int>& parts);

/// The edge cut of a partition of a graph spread over the ranks (edges
/// whose two vertices lie in different subdomains), on every rank.
/// Collective.
long long edgeCut(MPI_Comm comm, const DistributedGraph& graph, const std::vector<int>& parts);

/// The subdomain of each local vertex of `graph` by PT-Scotch
/// (partitionGraphPtScotch()), every subdomain made non-empty and
/// splinters joined to their neighbours as by partitionPtScotch(), with the
/// edge cut; no rank holds more than its own vertices' subdomains.
/// \param numSubdomains 1 gives all zeros without calling PT-Scotch.
/// \throws InputError if numSubdomains is not in [1, vertices], and as
///         partitionGraphPtScotch().
Partition partitionDistributedGraph(MPI_Comm comm, const DistributedGraph& graph, int numSubdomains);

/// The partition of a (replicated) mesh by PT-Scotch: each rank builds the
/// dual graph of an even, contiguous range of the elements, PT-Scotch
/// partitions it in parallel (partitionDistributedGraph(): like
/// partitionMetis(), every subdomain is made non-empty, and splinters
/// (joinDetachedPieces()) join the neighbour they share most facets with),
/// and the parts are gathered to every rank. The same on every rank and in every run on the same number
/// of ranks; another rank count gives another partition.
/// \param numSubdomains 1 gives all zeros without calling PT-Scotch.
/// \throws InputError like partitionMetis(), and on more than one rank if
///         MPI was not initialised with MPI_THREAD_MULTIPLE (ddc::MpiSession);
///         SolverError from PT-Scotch.
Partition partitionPtScotch(const Mesh& mesh, int numSubdomains, MPI_Comm comm);

/// partitionPtScotch() when no rank holds the whole mesh: each rank holds a
/// part (Mesh::isPart()) whose elements are a contiguous range of ids, the
/// ranges in rank order covering the whole mesh (generateBox() by an even
/// ElementRange), and gets the subdomains of its own elements, cleaned up
/// as partitionPtScotch() cleans them (the same subdomains, element for
/// element, when the ranges are partitionPtScotch()'s even ones).
/// Collective.
/// \throws std::invalid_argument (on every rank) if the parts are not such
///         ranges; as partitionPtScotch() otherwise.
Partition partitionRangePtScotch(const Mesh& part, int numSubdomains, MPI_Comm comm);

}  // namespace ddc
