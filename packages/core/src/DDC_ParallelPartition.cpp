#include "DDC_ParallelPartition.hpp"

#include <scotch/ptscotch.h>

#include <algorithm>
#include <climits>
#include <stdexcept>
#include <string>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {

/// One corner of one element, sent to the home rank of the node.
struct NodeElement {
  long long node, element;
  bool operator<(const NodeElement& o) const { return node != o.node ? node < o.node : element < o.element; }
};


/// "" or what is wrong with the CSR input (checked on every rank, agreed on).
std::string checkCorners(const std::vector<long long>& offsets, const std::vector<long long>& corners, int ncommon) {
  if (ncommon < 1) return "ncommon must be >= 1, got " + std::to_string(ncommon);
  if (offsets.empty() || offsets.front() != 0 || offsets.back() != static_cast<long long>(corners.size()))
    return "cornerOffsets must start at 0 and end at corners.size()";
  for (size_t l = 1; l < offsets.size(); ++l)
    if (offsets[l] < offsets[l - 1]) return "cornerOffsets must not decrease";
  for (long long n : corners)
    if (n < 0) return "corner node id " + std::to_string(n) + " is negative";
  return std::string();
}

/// Phase 2 at a node's home: the whole element list of each node goes to
/// every rank owning one of its elements (usually one rank).
std::vector<std::vector<NodeElement>> nodeListsToOwners(std::vector<NodeElement> atHome, const DistributedGraph& g,
                                                        int size) {
  std::sort(atHome.begin(), atHome.end());
  std::vector<std::vector<NodeElement>> send(size);
  std::vector<int> owners;
  for (size_t i = 0; i < atHome.size();) {
    size_t j = i;
    owners.clear();
    for (; j < atHome.size() && atHome[j].node == atHome[i].node; ++j)
      owners.push_back(g.holder(atHome[j].element));
    std::sort(owners.begin(), owners.end());
    owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
    for (int r : owners) send[r].insert(send[r].end(), atHome.begin() + i, atHome.begin() + j);
    i = j;
  }
  return send;
}

/// Phase 3 at an element's owner: element l is adjacent to every other
/// element that appears in the lists of at least `ncommon` of its corner
/// nodes (`lists`: sorted, unique (node, element) records).
void adjacencyFromNodeLists(const std::vector<NodeElement>& lists, const std::vector<long long>& cornerOffsets,
                            const std::vector<long long>& corners, long long first, int ncommon, DistributedGraph& g) {
  const long long nLocal = static_cast<long long>(cornerOffsets.size()) - 1;
  g.offsets.assign(nLocal + 1, 0);
  std::vector<long long> candidates, nodes;
  for (long long l = 0; l < nLocal; ++l) {
    const long long self = first + l;
    nodes.assign(corners.begin() + cornerOffsets[l], corners.begin() + cornerOffsets[l + 1]);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    candidates.clear();
    for (long long n : nodes)
      for (auto it = std::lower_bound(lists.begin(), lists.end(), NodeElement{n, LLONG_MIN});
           it != lists.end() && it->node == n; ++it)
        if (it->element != self) candidates.push_back(it->element);
    std::sort(candidates.begin(), candidates.end());
    for (size_t i = 0; i < candidates.size();) {
      size_t j = i;
      while (j < candidates.size() && candidates[j] == candidates[i]) ++j;
      if (static_cast<int>(j - i) >= ncommon) g.neighbours.push_back(candidates[i]);
      i = j;
    }
    g.offsets[l + 1] = static_cast<long long>(g.neighbours.size());
  }
}

}  // namespace

DistributedGraph distributedDualGraph(MPI_Comm comm, const std::vector<long long>& cornerOffsets,
                                      const std::vector<long long>& corners, int ncommon) {
  const std::string bad = firstErrorOnAnyRank(comm, checkCorners(cornerOffsets, corners, ncommon));
  if (!bad.empty()) throw std::invalid_argument("distributedDualGraph(): " + bad);
  const int rank = commRank(comm), size = commSize(comm);
  DistributedGraph g;
  const long long nLocal = static_cast<long long>(cornerOffsets.size()) - 1;
  std::vector<long long> counts(size);
  MPI_Allgather(&nLocal, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, comm);
  g.firstVertex.assign(size + 1, 0);
  for (int r = 0; r < size; ++r) g.firstVertex[r + 1] = g.firstVertex[r] + counts[r];
  const long long first = g.firstVertex[rank];

  long long maxNode = -1, globalMax = -1;
  for (long long n : corners) maxNode = std::max(maxNode, n);
  MPI_Allreduce(&maxNode, &globalMax, 1, MPI_LONG_LONG, MPI_MAX, comm);
  const long long nodeCount = globalMax + 1;
  auto home = [&](long long n) { return static_cast<int>((n * size) / std::max(nodeCount, 1LL)); };

  // Phase 1: every (node, element) to the node's home.
  std::vector<std::vector<NodeElement>> send(size);
  for (long long l = 0; l < nLocal; ++l)
    for (long long k = cornerOffsets[l]; k < cornerOffsets[l + 1]; ++k)
      send[home(corners[k])].push_back(NodeElement{corners[k], first + l});
  std::vector<NodeElement> atHome = exchangeRecords(comm, send);
  // Phase 2: each node's element list to the owners of its elements.
  std::vector<NodeElement> lists = exchangeRecords(comm, nodeListsToOwners(std::move(atHome), g, size));
  std::sort(lists.begin(), lists.end());
  lists.erase(std::unique(lists.begin(), lists.end(),
                          [](const NodeElement& a, const NodeElement& b) {
                            return a.node == b.node && a.element == b.element;
                          }),
              lists.end());

  // Phase 3: count the corners each local element shares with the others.
  adjacencyFromNodeLists(lists, cornerOffsets, corners, first, ncommon, g);
  return g;
}

std::vector<int> partitionGraphPtScotch(MPI_Comm comm, const DistributedGraph& graph, int numParts) {
  const long long nLocal = graph.numLocal();
  std::vector<int> part(static_cast<size_t>(nLocal), 0);
  if (numParts <= 1) return part;
  long long edges = static_cast<long long>(graph.neighbours.size()), maxEdges = 0;
  MPI_Allreduce(&edges, &maxEdges, 1, MPI_LONG_LONG, MPI_MAX, comm);
  if (graph.firstVertex.back() >= INT_MAX || maxEdges >= INT_MAX)
    DDC_THROW(SolverError, "PT-Scotch (32-bit SCOTCH_Num in this build) cannot partition a graph of "
                               << graph.firstVertex.back() << " vertices with up to " << maxEdges
                               << " edges on one rank");
  std::vector<SCOTCH_Num> vert(graph.offsets.begin(), graph.offsets.end());
  std::vector<SCOTCH_Num> edge(graph.neighbours.begin(), graph.neighbours.end());
  std::vector<SCOTCH_Num> result(static_cast<size_t>(nLocal) + 1, 0);  // +1: never a null buffer
  // A deterministic context with a fixed seed: the same partition in every
  // run on the same rank count (Scotch's threaded methods otherwise vary).
  SCOTCH_Context context;
  SCOTCH_Dgraph built, g;
  SCOTCH_Strat strat;
  std::string error;
  SCOTCH_contextInit(&context);
  SCOTCH_stratInit(&strat);
  if (SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMDETERMINISTIC, 1) != 0 ||
      SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMRANDOMFIXEDSEED, 1) != 0)
    error = "SCOTCH_contextOptionSetNum failed";
  // The context's own random generator from its initial seed: the shared one
  // goes on from the previous call, which gave a second partition of the same
  // graph in one process another result.
  if (error.empty() && SCOTCH_contextRandomClone(&context) != 0) error = "SCOTCH_contextRandomClone failed";
  if (error.empty()) SCOTCH_contextRandomReset(&context);
  // Collective calls: a failure on one rank fails them on all, so every
  // rank reaches the same branch.
  const bool builtOk = SCOTCH_dgraphInit(&built, comm) == 0;
  const bool boundOk = SCOTCH_dgraphInit(&g, comm) == 0;
  if (!builtOk || !boundOk) error = "SCOTCH_dgraphInit failed";
  if (error.empty() && SCOTCH_dgraphBuild(&built, 0, static_cast<SCOTCH_Num>(nLocal),
                                          static_cast<SCOTCH_Num>(nLocal), vert.data(), vert.data() + 1, nullptr,
                                          nullptr, static_cast<SCOTCH_Num>(edges), static_cast<SCOTCH_Num>(edges),
                                          edge.empty() ? nullptr : edge.data(), nullptr, nullptr) != 0)
    error = "SCOTCH_dgraphBuild failed";
  if (error.empty() && SCOTCH_contextBindDgraph(&context, &built, &g) != 0) error = "SCOTCH_contextBindDgraph failed";
  if (error.empty() &&
      SCOTCH_stratDgraphMapBuild(&strat, SCOTCH_STRATQUALITY, commSize(comm), numParts, kPtScotchImbalance) != 0)
    error = "SCOTCH_stratDgraphMapBuild failed";
  if (error.empty() && SCOTCH_dgraphPart(&g, numParts, &strat, result.data()) != 0)
    error = "SCOTCH_dgraphPart failed";
  SCOTCH_stratExit(&strat);
  if (boundOk) SCOTCH_dgraphExit(&g);
  if (builtOk) SCOTCH_dgraphExit(&built);
  SCOTCH_contextExit(&context);
  error = firstErrorOnAnyRank(comm, error);
  if (!error.empty())
    DDC_THROW(SolverError, "PT-Scotch: " << error << " partitioning " << graph.firstVertex.back()
                                         << " elements into " << numParts << " subdomains");
  for (long long l = 0; l < nLocal; ++l) part[l] = static_cast<int>(result[l]);
  return part;
}

void requirePtScotchThreadLevel(int ranks, int threadLevel) {
  DDC_INPUT_REQUIRE(ranks == 1 || threadLevel >= MPI_THREAD_MULTIPLE,
                    "'Partition/Method' = PT-Scotch needs MPI initialised with MPI_THREAD_MULTIPLE on more than one "
                    "rank (PT-Scotch's threads call MPI); ddcontact does so, a host code must call MPI_Init_thread "
                    "(ddc::MpiSession) or use Method = METIS");
}

Partition partitionDistributedGraph(MPI_Comm comm, const DistributedGraph& graph, int numSubdomains) {
  const long long ne = graph.firstVertex.back();
  requirePartitionable(numSubdomains, static_cast<int>(std::min<long long>(ne, INT_MAX)));
  Partition p;
  p.numSubdomains = numSubdomains;
  p.elementSubdomain.assign(graph.numLocal(), 0);
  if (numSubdomains == 1) {
    p.edgeCut = 0;
    return p;
  }
  int level = MPI_THREAD_SINGLE;
  MPI_Query_thread(&level);
  requirePtScotchThreadLevel(commSize(comm), level);
  p.elementSubdomain = partitionGraphPtScotch(comm, graph, numSubdomains);
  fillEmptySubdomains(comm, graph, numSubdomains, p.elementSubdomain);
  joinDetachedPieces(comm, graph, numSubdomains, p.elementSubdomain);
  p.edgeCut = edgeCut(comm, graph, p.elementSubdomain);
  return p;
}

namespace {

/// The corner nodes (ids in the whole mesh) of elements [begin, end) of
/// `mesh` as a CSR list, for distributedDualGraph().
void cornerLists(const Mesh& mesh, int begin, int end, std::vector<long long>& offsets, std::vector<long long>& corners) {
  offsets.assign(1, 0);
  corners.clear();
  for (int e = begin; e < end; ++e) {
    const int* n = mesh.elementNodes(e);
    for (int k = 0; k < referenceCell(mesh.elementType(e)).numCorners; ++k) corners.push_back(mesh.nodeId(n[k]));
    offsets.push_back(static_cast<long long>(corners.size()));
  }
}

}  // namespace

Partition partitionPtScotch(const Mesh& mesh, int numSubdomains, MPI_Comm comm) {
  const int ne = mesh.numElements();
  requirePartitionable(numSubdomains, ne);
  Partition p;
  p.numSubdomains = numSubdomains;
  p.elementSubdomain.assign(ne, 0);
  if (numSubdomains == 1) return p;
  const int rank = commRank(comm), size = commSize(comm);
  const int begin = static_cast<int>(static_cast<long long>(ne) * rank / size);
  const int end = static_cast<int>(static_cast<long long>(ne) * (rank + 1) / size);
  std::vector<long long> offsets, corners;
  cornerLists(mesh, begin, end, offsets, corners);
  const DistributedGraph graph = distributedDualGraph(comm, offsets, corners, dualGraphCommonCorners(mesh));
  const Partition mine = partitionDistributedGraph(comm, graph, numSubdomains);
  std::vector<int> counts(size), displs(size, 0);
  const int n = static_cast<int>(mine.elementSubdomain.size());
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  int dummy = 0;
  MPI_Allgatherv(n == 0 ? &dummy : mine.elementSubdomain.data(), n, MPI_INT, p.elementSubdomain.data(),
                 counts.data(), displs.data(), MPI_INT, comm);
  p.edgeCut = mine.edgeCut;
  return p;
}

Partition partitionRangePtScotch(const Mesh& part, int numSubdomains, MPI_Comm comm) {
  const int size = commSize(comm);
  // The ranges must follow one another in rank order from id 0.
  const long long first = part.numElements() ? part.elementId(0) : -1;
  const bool contiguous = part.numElements() == 0 || part.elementId(part.numElements() - 1) - first + 1 == part.numElements();
  std::vector<long long> firsts(size), counts(size);
  const long long count = part.numElements();
  MPI_Allgather(&first, 1, MPI_LONG_LONG, firsts.data(), 1, MPI_LONG_LONG, comm);
  MPI_Allgather(&count, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, comm);
  long long next = 0;
  bool inOrder = true;
  for (int r = 0; r < size; ++r) {
    if (counts[r] > 0) inOrder = inOrder && firsts[r] == next;
    next += counts[r];
  }
  if (anyRank(comm, !contiguous) || !inOrder || next != part.numGlobalElements())
    throw std::invalid_argument("partitionRangePtScotch(): the ranks' elements are not ranges of ids in rank order "
                                "that cover the whole mesh");
  const int ne = static_cast<int>(std::min<long long>(part.numGlobalElements(), INT_MAX));
  requirePartitionable(numSubdomains, ne);
  std::vector<long long> offsets, corners;
  cornerLists(part, 0, part.numElements(), offsets, corners);
  const DistributedGraph graph = distributedDualGraph(comm, offsets, corners, dualGraphCommonCorners(part));
  Partition p = partitionDistributedGraph(comm, graph, numSubdomains);
  if (numSubdomains == 1) p.edgeCut = -1;  // as partitionPtScotch()
  return p;
}

}  // namespace ddc
