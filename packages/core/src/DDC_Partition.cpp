#include "DDC_Partition.hpp"

#include "DDC_MpiRecords.hpp"

#include <cstdlib>

#include <cmath>

#include <sstream>

#include <fstream>

#include <metis.h>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <utility>

#include "DDC_Error.hpp"

namespace ddc {

namespace {

constexpr const char* kParam = "Partition/Number of Subdomains";
/// Fixed METIS seed: the same partition on every rank and every run.
constexpr idx_t kMetisSeed = 42;

/// Is the dual graph (elements adjacent through edges) connected?
bool isConnected(const FacetGraph& nb) {
  if (nb.empty()) return true;
  std::vector<char> seen(nb.size(), 0);
  std::vector<int> stack{0};
  seen[0] = 1;
  size_t count = 1;
  while (!stack.empty()) {
    const int e = stack.back();
    stack.pop_back();
    for (int f : nb[e])
      if (!seen[f]) {
        seen[f] = 1;
        ++count;
        stack.push_back(f);
      }
  }
  return count == nb.size();
}

}  // namespace

void requirePartitionable(int numSubdomains, int numElements) {
  DDC_INPUT_REQUIRE(numSubdomains > 0, "'" << kParam << "' must be > 0, got " << numSubdomains);
  DDC_INPUT_REQUIRE(numSubdomains <= numElements, "'" << kParam << "' (" << numSubdomains
                                                      << ") exceeds the number of elements of the mesh ("
                                                      << numElements << "); use fewer subdomains or refine the mesh");
}

int dualGraphCommonCorners(const Mesh& mesh) {
  int ncommon = mesh.dim() == 2 ? 2 : 4;
  for (int b = 0; b < mesh.numBodies(); ++b)
    for (const auto& f : referenceCell(mesh.body(b).cellType).facets)
      ncommon = std::min(ncommon, referenceCell(f.type).numCorners);
  return ncommon;
}

FacetGraph facetNeighbours(const Mesh& mesh) {
  // Every element facet as (sorted corner ids, element), sorted: the copies
  // of a facet become neighbours. Flat records, 20 bytes each, and rows in
  // one array: a map keyed by corner vectors and a vector per element cost
  // about 230 bytes per facet, 0.7 GB on a 1.26M-element box, which the
  // allocator then kept (doc/performance.md, "Memory at set-up").
  struct FacetRecord {
    std::array<int, 4> corners;  ///< ascending, -1 after the last
    int element;
  };
  const int ne = mesh.numElements();
  size_t numFacets = 0;
  for (int e = 0; e < ne; ++e) numFacets += referenceCell(mesh.elementType(e)).facets.size();
  std::vector<FacetRecord> records;
  records.reserve(numFacets);
  for (int e = 0; e < ne; ++e) {
    const auto& cell = referenceCell(mesh.elementType(e));
    const int* en = mesh.elementNodes(e);
    for (const auto& facet : cell.facets) {
      FacetRecord r{{{-1, -1, -1, -1}}, e};
      const int nc = referenceCell(facet.type).numCorners;
      DDC_CHECK(nc <= 4, "a facet with " << nc << " corners");
      for (int i = 0; i < nc; ++i) r.corners[i] = en[facet.nodes[i]];
      std::sort(r.corners.begin(), r.corners.begin() + nc);
      records.push_back(r);
    }
  }
  std::sort(records.begin(), records.end(), [](const FacetRecord& a, const FacetRecord& b) {
    return a.corners != b.corners ? a.corners < b.corners : a.element < b.element;
  });
  // Two passes over the groups of equal corners: count, then fill.
  std::vector<size_t> offset(size_t(ne) + 1, 0);
  std::vector<int> neighbours;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<size_t> next(offset.begin(), offset.end() - 1);
    for (size_t i = 0; i < records.size();) {
      size_t j = i;
      while (j < records.size() && records[j].corners == records[i].corners) ++j;
      for (size_t a = i; a < j; ++a)
        for (size_t b = i; b < j; ++b) {
          if (a == b) continue;
          if (pass == 0)
            ++offset[records[a].element + 1];
          else
            neighbours[next[records[a].element]++] = records[b].element;
        }
      i = j;
    }
    if (pass == 0) {
      std::partial_sum(offset.begin(), offset.end(), offset.begin());
      neighbours.resize(offset.back());
    }
  }
  return FacetGraph(std::move(offset), std::move(neighbours));
}

long long edgeCut(const FacetGraph& nb, const Partition& p) {
  long long cut = 0;
  for (size_t e = 0; e < nb.size(); ++e)
    for (int f : nb[e])
      if (static_cast<int>(e) < f && p.elementSubdomain[e] != p.elementSubdomain[f]) ++cut;
  return cut;
}

void fillEmptySubdomains(const FacetGraph& nb, Partition& p) {
  const int ne = static_cast<int>(p.elementSubdomain.size());
  std::vector<int> count(p.numSubdomains, 0);
  for (int s : p.elementSubdomain) ++count[s];
  for (int s = 0; s < p.numSubdomains; ++s) {
    if (count[s] != 0) continue;
    const int donor = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
    int best = -1, bestInside = 0;
    for (int e = 0; e < ne; ++e) {
      if (p.elementSubdomain[e] != donor) continue;
      int inside = 0;
      for (int f : nb[e]) inside += p.elementSubdomain[f] == donor;
      if (best < 0 || inside < bestInside) {
        best = e;
        bestInside = inside;
      }
    }
    DDC_CHECK(best >= 0 && count[donor] > 1, "no donor element for empty subdomain");
    p.elementSubdomain[best] = s;
    --count[donor];
    ++count[s];
  }
}

namespace {

/// Pieces of each subdomain: piece[e] = a label shared by the elements of
/// e's subdomain connected to e through facets of that subdomain.
std::vector<int> subdomainPieces(const FacetGraph& nb, const Partition& p,
                                 std::vector<int>& pieceSize) {
  const int ne = static_cast<int>(nb.size());
  std::vector<int> piece(ne, -1), stack;
  pieceSize.clear();
  for (int e0 = 0; e0 < ne; ++e0) {
    if (piece[e0] >= 0) continue;
    const int label = static_cast<int>(pieceSize.size());
    pieceSize.push_back(0);
    piece[e0] = label;
    stack.assign(1, e0);
    while (!stack.empty()) {
      const int e = stack.back();
      stack.pop_back();
      ++pieceSize[label];
      for (int f : nb[e])
        if (piece[f] < 0 && p.elementSubdomain[f] == p.elementSubdomain[e]) {
          piece[f] = label;
          stack.push_back(f);
        }
    }
  }
  return piece;
}

/// One pass of joinDetachedPieces(); true if a piece moved.
bool joinPiecesOnce(const FacetGraph& nb, Partition& p) {
  std::vector<int> size;
  const std::vector<int> piece = subdomainPieces(nb, p, size);
  const int ne = static_cast<int>(nb.size());
  std::vector<int> largest(p.numSubdomains, -1);  // the piece each subdomain keeps
  for (int e = 0; e < ne; ++e) {
    int& keep = largest[p.elementSubdomain[e]];
    if (keep < 0 || size[piece[e]] > size[keep]) keep = piece[e];
  }
  std::vector<std::map<int, int>> contacts(size.size());  // piece -> neighbouring subdomain -> facets
  for (int e = 0; e < ne; ++e) {
    if (piece[e] == largest[p.elementSubdomain[e]]) continue;
    for (int f : nb[e])
      if (p.elementSubdomain[f] != p.elementSubdomain[e]) ++contacts[piece[e]][p.elementSubdomain[f]];
  }
  const double splinter = kMaxJoinedPieceShare * double(ne) / std::max(p.numSubdomains, 1);
  std::vector<int> target(size.size(), -1);
  for (size_t k = 0; k < size.size(); ++k) {
    if (size[k] > splinter) continue;
    int best = 0;
    for (const auto& [s, facets] : contacts[k])  // ascending ids: the lowest wins ties
      if (facets > best) {
        best = facets;
        target[k] = s;
      }
  }
  bool moved = false;
  for (int e = 0; e < ne; ++e)
    if (target[piece[e]] >= 0) {
      p.elementSubdomain[e] = target[piece[e]];
      moved = true;
    }
  return moved;
}

}  // namespace

void joinDetachedPieces(const FacetGraph& nb, Partition& p) {
  for (int pass = 0; pass < kMaxPieceJoinPasses && joinPiecesOnce(nb, p); ++pass) {
  }
}

Partition partitionMetis(const Mesh& mesh, int numSubdomains) {
  const int ne = mesh.numElements();
  requirePartitionable(numSubdomains, ne);
  Partition p;
  p.numSubdomains = numSubdomains;
  p.elementSubdomain.assign(ne, 0);
  if (numSubdomains == 1) return p;

  // Corner nodes only, renumbered compactly (mid-edge, face and centre
  // nodes would otherwise be isolated vertices of METIS's nodal graph).
  // METIS joins two elements that share `ncommon` corners: a side (2) in
  // 2-D, a face in 3-D (3 corners of a triangle, 4 of a quadrilateral; the
  // smallest face of any body, so that every face counts).
  std::vector<idx_t> compact(mesh.numNodes(), -1);
  std::vector<idx_t> eptr(ne + 1, 0), eind;
  idx_t nn = 0, ncommon = dualGraphCommonCorners(mesh);
  for (int e = 0; e < ne; ++e) {
    const int* n = mesh.elementNodes(e);
    const int corners = referenceCell(mesh.elementType(e)).numCorners;
    for (int k = 0; k < corners; ++k) {
      if (compact[n[k]] < 0) compact[n[k]] = nn++;
      eind.push_back(compact[n[k]]);
    }
    eptr[e + 1] = static_cast<idx_t>(eind.size());
  }

  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_SEED] = kMetisSeed;
  options[METIS_OPTION_PTYPE] = METIS_PTYPE_KWAY;
  options[METIS_OPTION_OBJTYPE] = METIS_OBJTYPE_CUT;
  // Contiguous subdomains keep FETI-DP's floating subdomains single pieces.
  // METIS fails (METIS_ERROR) when asked for them on a disconnected dual
  // graph (several bodies, or a body in pieces), so ask only when connected.
  const auto nb = facetNeighbours(mesh);
  options[METIS_OPTION_CONTIG] = isConnected(nb) ? 1 : 0;

  idx_t metisNe = ne, nparts = numSubdomains, objval = 0;
  std::vector<idx_t> epart(ne), npart(nn);
  const int status = METIS_PartMeshDual(&metisNe, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon,
                                        &nparts, nullptr, options, &objval, epart.data(), npart.data());
  DDC_INPUT_REQUIRE(status != METIS_ERROR_INPUT,
                    "METIS rejected the mesh for partitioning into " << numSubdomains << " subdomains");
  if (status != METIS_OK)
    DDC_THROW(SolverError, "METIS_PartMeshDual failed (status " << status << ") partitioning "
                                                                  << ne << " elements into " << numSubdomains
                                                                  << " subdomains");
  for (int e = 0; e < ne; ++e) {
    DDC_CHECK(epart[e] >= 0 && epart[e] < numSubdomains, "METIS part out of range");
    p.elementSubdomain[e] = static_cast<int>(epart[e]);
  }
  fillEmptySubdomains(nb, p);
  p.edgeCut = edgeCut(nb, p);
  return p;
}

Partition partitionByBody(const Mesh& mesh) {
  Partition p;
  p.numSubdomains = mesh.numBodies();
  p.elementSubdomain.resize(mesh.numElements());
  for (int e = 0; e < mesh.numElements(); ++e) p.elementSubdomain[e] = mesh.elementBody(e);
  return p;
}

Partition partitionBoxGrid(const Mesh& mesh, int nx, int ny, int nz) {
  DDC_INPUT_REQUIRE(nx >= 1 && ny >= 1 && nz >= 1, "'Partition/Box Grid X', 'Box Grid Y' and 'Box Grid Z' must be "
                                                   ">= 1, got " << nx << ", " << ny << " and " << nz);
  const int dim = mesh.dim();
  DDC_INPUT_REQUIRE(dim == 3 || nz == 1,
                    "'Partition/Box Grid Z' = " << nz << " on a 2-D mesh: there is no z direction (use 1)");
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int n = 0; n < mesh.numNodes(); ++n)
    for (int c = 0; c < dim; ++c) {
      lo[c] = std::min(lo[c], mesh.coord(n)[c]);
      hi[c] = std::max(hi[c], mesh.coord(n)[c]);
    }
  const int counts[3] = {nx, ny, nz};
  Partition p;
  p.numSubdomains = nx * ny * nz;
  p.elementSubdomain.resize(mesh.numElements());
  std::vector<int> used(p.numSubdomains, 0);
  for (int e = 0; e < mesh.numElements(); ++e) {
    double c[3] = {0, 0, 0};
    const int nn = mesh.elementNumNodes(e);
    for (int i = 0; i < nn; ++i)
      for (int d = 0; d < dim; ++d) c[d] += mesh.coord(mesh.elementNodes(e)[i])[d] / nn;
    int idx[3] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) {
      const double w = hi[d] - lo[d];
      idx[d] = w > 0 ? static_cast<int>(std::floor((c[d] - lo[d]) / w * counts[d])) : 0;
      idx[d] = std::min(std::max(idx[d], 0), counts[d] - 1);
    }
    p.elementSubdomain[e] = idx[0] + nx * (idx[1] + ny * idx[2]);
    used[p.elementSubdomain[e]] = 1;
  }
  for (int s = 0; s < p.numSubdomains; ++s)
    DDC_INPUT_REQUIRE(used[s], "'Partition/Box Grid X' x 'Partition/Box Grid Y'"
                                   << (nz > 1 ? " x 'Partition/Box Grid Z'" : "") << " = " << nx << " x " << ny
                                   << (nz > 1 ? " x " + std::to_string(nz) : std::string()) << ": box " << s
                                   << " holds no element centroid");
  return p;
}

Partition partitionFromFile(const Mesh& mesh, const std::string& fileName) {
  std::ifstream in(fileName);
  DDC_INPUT_REQUIRE(in.good(), "element map file '" << fileName << "' cannot be read");
  std::vector<int> ids;
  std::string line;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ls(line);
    std::string tok;
    while (ls >> tok) {
      char* end = nullptr;
      const long v = std::strtol(tok.c_str(), &end, 10);
      DDC_INPUT_REQUIRE(end && *end == '\0' && v >= 0 && v < (1L << 30),
                        "element map file '" << fileName << "' line " << lineNo << ": '" << tok
                                             << "' is not a non-negative subdomain id");
      ids.push_back(static_cast<int>(v));
    }
  }
  DDC_INPUT_REQUIRE(static_cast<int>(ids.size()) == mesh.numElements(),
                    "element map file '" << fileName << "' has " << ids.size() << " entries; the mesh has "
                                         << mesh.numElements() << " elements (one subdomain id per element)");
  Partition p;
  p.numSubdomains = ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end()) + 1;
  std::vector<int> used(p.numSubdomains, 0);
  for (int v : ids) used[v] = 1;
  for (int s = 0; s < p.numSubdomains; ++s)
    DDC_INPUT_REQUIRE(used[s], "element map file '" << fileName << "': subdomain " << s
                                                    << " has no element (ids must be 0.." << p.numSubdomains - 1
                                                    << ", all used)");
  p.elementSubdomain = std::move(ids);
  return p;
}

std::vector<int> nodeOwnerRanks(const Mesh& mesh, const Partition& partition, int numRanks) {
  const std::vector<int> rankOf = subdomainOwnerRank(partition.numSubdomains, numRanks);
  std::vector<int> owner(mesh.numNodes(), numRanks);
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int r = rankOf[partition.elementSubdomain[e]];
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
      int& o = owner[mesh.elementNodes(e)[i]];
      o = std::min(o, r);
    }
  }
  return owner;
}

std::vector<int> subdomainOwnerRank(int numSubdomains, int numRanks) {
  DDC_INPUT_REQUIRE(numRanks >= 1, "number of MPI ranks must be >= 1, got " << numRanks);
  DDC_INPUT_REQUIRE(numSubdomains >= numRanks,
                    "'" << kParam << "' (" << numSubdomains << ") must be at least the number of MPI ranks ("
                        << numRanks << "): every rank needs a subdomain");
  std::vector<int> owner(numSubdomains);
  const int base = numSubdomains / numRanks, extra = numSubdomains % numRanks;
  int s = 0;
  for (int r = 0; r < numRanks; ++r)
    for (int k = 0; k < base + (r < extra ? 1 : 0); ++k) owner[s++] = r;
  return owner;
}

RankPart rankPart(const Mesh& mesh, const Partition& partition, int rank, int numRanks) {
  const std::vector<int> rankOf = subdomainOwnerRank(partition.numSubdomains, numRanks);
  std::vector<int> mine;
  RankPart out;
  out.partition.numSubdomains = partition.numSubdomains;
  out.partition.edgeCut = partition.edgeCut;
  for (int e = 0; e < mesh.numElements(); ++e)
    if (rankOf[partition.elementSubdomain[e]] == rank) {
      mine.push_back(e);
      out.partition.elementSubdomain.push_back(partition.elementSubdomain[e]);
    }
  out.mesh = mesh.part(mine);
  return out;
}

RankPart migratedRankPart(MPI_Comm comm, const Mesh& source, const Partition& sourcePartition) {
  if (sourcePartition.elementSubdomain.size() != size_t(source.numElements()))
    throw std::invalid_argument("migratedRankPart: " + std::to_string(sourcePartition.elementSubdomain.size()) +
                                " subdomains for " + std::to_string(source.numElements()) + " elements");
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const std::vector<int> rankOf = subdomainOwnerRank(sourcePartition.numSubdomains, ranks);
  struct Assignment {
    Mesh::GlobalId element;
    int subdomain;
  };
  std::vector<int> destination(source.numElements());
  std::vector<std::vector<Assignment>> send(ranks);
  for (int e = 0; e < source.numElements(); ++e) {
    const int s = sourcePartition.elementSubdomain[e];
    destination[e] = rankOf.at(s);
    send[destination[e]].push_back({source.elementId(e), s});
  }
  RankPart out;
  out.mesh = source.migrated(comm, destination);
  out.partition.numSubdomains = sourcePartition.numSubdomains;
  out.partition.elementSubdomain.assign(out.mesh.numElements(), -1);
  std::vector<Mesh::GlobalId> ids(out.mesh.numElements());
  for (int e = 0; e < out.mesh.numElements(); ++e) ids[e] = out.mesh.elementId(e);
  for (const Assignment& a : exchangeRecords(comm, send)) {
    const auto it = std::lower_bound(ids.begin(), ids.end(), a.element);
    DDC_CHECK(it != ids.end() && *it == a.element, "migratedRankPart: element " << a.element << " not received");
    out.partition.elementSubdomain[it - ids.begin()] = a.subdomain;
  }
  return out;
}

std::vector<int> subdomainsOfRank(int numSubdomains, int numRanks, int rank) {
  const auto owner = subdomainOwnerRank(numSubdomains, numRanks);
  std::vector<int> mine;
  for (int s = 0; s < numSubdomains; ++s)
    if (owner[s] == rank) mine.push_back(s);
  return mine;
}

}  // namespace ddc
