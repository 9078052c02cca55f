#include "DDC_MemoryEstimate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <vector>

#include "DDC_ContactParameters.hpp"
#include "DDC_Memory.hpp"
#include "DDC_NodeDirectory.hpp"
#include "DDC_ReferenceCell.hpp"

namespace ddc {

namespace {

// Coefficients measured with examples/block_3d.xml (Hex8, Hex20) and
// examples/elastic_block.xml (Quad4) on 2 ranks at 8k-527k DOFs and with
// block_3d on 1-16 ranks, peak resident memory less that of an empty run
// (~70 MiB); the tables in doc/user-guide.md, "Memory", printed by
// test/benchmark/memory_estimate.sh.

/// Bytes per stored matrix entry: the owned matrix and its graph (8 B value,
/// 4 B column index; the rows other ranks own are assembled in a buffer of
/// the interface rows only). Assembling into a whole overlap copy first
/// took 21 B (measured with Belos-MueLu).
constexpr double kMatrixBytesPerEntry = 12.0;
/// Belos-FROSch: subdomain matrices beyond the matrix (measured with
/// MueLu's hierarchy when it stored its restriction: 27 B on 1 rank to 49 B
/// on 16 ranks with block_3d).
constexpr double kIterativeBytesPerEntry = 35.0;
/// Belos-MueLu: the hierarchy and the solve's vectors beyond the matrix, per
/// entry of a rank's rows, kMueLuBytesPerEntry + kMueLuBytesPerGhostShare ·
/// g with g the rank's ghost nodes over its owned nodes (the Galerkin
/// products import the ghosts' rows of P). The slope is fitted to the
/// solve's growth on the largest rank (block_3d, METIS): Refinement 8 on
/// 1 / 2 / 4 / 8 / 16 ranks, g = 0 / 0.018 / 0.070 / 0.150 / 0.243, 23.8 /
/// 27.7 / 31.6 / 40.8 / 49.3 B per entry; Refinement 17 on 8 ranks,
/// g = 0.069, 31.9 B. The base is raised from 24 to 28 B for what the run
/// holds besides (Belos's vectors, MueLu's coarse solver): with 24 B
/// block_3d at Refinement 6 on 8 ranks measured 1.23 times the estimate.
constexpr double kMueLuBytesPerEntry = 28.0;
constexpr double kMueLuBytesPerGhostShare = 105.0;
/// METIS's dual graph and work arrays, built on every rank from the whole
/// mesh, per element corner (measured 37 B: 37 MiB for 131,072 Hex8). Freed
/// when the partition is made, before the model and the solver allocate.
constexpr double kPartitionBytesPerCorner = 37.0;
/// The whole mesh on every rank, by node and by element node: the peak of
/// building it (coordinates and connectivity, their vectors' spare capacity,
/// the generator's grid, the node sets) less an empty run's, measured on 1
/// rank for block_3d at Refinement 8 / 12 / 17: 8 / 41 / 161 MiB, which
/// these give as 17 / 58 / 168 MiB; what the model keeps per node (owner,
/// first DOF) is within it.
constexpr double kMeshBytesPerNode = 64.0;
constexpr double kMeshBytesPerElement = 8.0;
constexpr double kMeshBytesPerElementNode = 8.0;
/// Per facet of a contact surface, held on every rank: its node list, the
/// slots of its slave nodes and their packed copies, search boxes and DOF
/// records (counted from those arrays, not measured: below the noise of
/// the runs of the table).
constexpr double kContactBytesPerFacet = 500.0;
/// Nested-dissection fill of a sparse factor (entries of L per entry of K):
/// 3-D  kFill3D n^(1/3) (MUMPS measured 0.34-0.62 on the bricks),
/// 2-D  kFill2D log2 n  (0.67-0.72).
constexpr double kFill3D = 0.5;
constexpr double kFill2D = 0.7;
/// FETI-DP per subdomain: two factors (K^s and the Dirichlet problem) and,
/// per entry of K^s, its copies, the jump, scaling and change-of-basis
/// operators and the Schur complements (measured 70-280 B).
constexpr double kFetiFactorCopies = 2.0;
constexpr double kFetiBytesPerEntry = 120.0;

/// Average nodes coupled to a node (matrix entries per row / dimension).
double couplingsPerNode(CellType t) {
  switch (t) {
    case CellType::Quad4: return 9;
    case CellType::Quad9: return 16;
    case CellType::Hex8: return 27;
    case CellType::Hex20: return 45;
    case CellType::Hex27: return 55;
    case CellType::Tet4: return 15;
    case CellType::Tet10: return 35;
    default: return 27;
  }
}

double fill(double n, int dim) {
  n = std::max(n, 2.0);
  return std::max(1.0, dim == 3 ? kFill3D * std::cbrt(n) : kFill2D * std::log2(n));
}

/// Element corners of the bodies of `mesh` (what a graph partitioner reads).
double elementCorners(const Mesh& mesh) {
  double corners = 0.0;
  for (int b = 0; b < mesh.numBodies(); ++b)
    corners += static_cast<double>(mesh.body(b).numElements) * referenceCell(mesh.body(b).cellType).numCorners;
  return corners;
}

double elementNodes(const Mesh& mesh) {
  double n = 0.0;
  for (int b = 0; b < mesh.numBodies(); ++b)
    n += static_cast<double>(mesh.body(b).numElements) * numCellNodes(mesh.body(b).cellType);
  return n;
}

/// The facets of the contact surfaces `mesh` holds.
double contactFacets(const Mesh& mesh, const ContactOptions& contact) {
  double facets = 0.0;
  for (const auto& pair : contact.pairs)
    for (const auto* set : {&pair.slaveSet, &pair.masterSet})
      if (mesh.hasSideSet(*set)) facets += static_cast<double>(mesh.sideSet(*set).size());
  return facets;
}

/// The whole bodies, from a whole mesh or a part.
std::vector<ModelSize::BodySize> bodySizes(const Mesh& mesh) {
  std::vector<ModelSize::BodySize> out;
  for (int b = 0; b < mesh.numBodies(); ++b)
    out.push_back({mesh.body(b).cellType, static_cast<double>(mesh.bodyGlobalNodes(b)),
                   static_cast<double>(mesh.bodyGlobalElements(b))});
  return out;
}

/// Per rank of a whole mesh: its owned nodes (nodeOwnerRanks(), as in the
/// Model) and the nodes of its elements that other ranks own (its ghosts).
void rankNodes(const Mesh& mesh, const Partition& partition, int ranks, ModelSize& size) {
  size.ownedNodes.assign(ranks, 0.0);
  size.ghostNodes.assign(ranks, 0.0);
  if (partition.elementSubdomain.size() != size_t(mesh.numElements())) return;
  const std::vector<int> rankOf = subdomainOwnerRank(partition.numSubdomains, ranks);
  const std::vector<int> owner = nodeOwnerRanks(mesh, partition, ranks);
  for (int o : owner)
    if (o < ranks) size.ownedNodes[o] += 1.0;
  std::vector<std::pair<int, int>> ghost;  // (node, rank) of a rank's element at a node it does not own
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int r = rankOf[partition.elementSubdomain[e]];
    for (int i = 0; i < mesh.elementNumNodes(e); ++i)
      if (owner[mesh.elementNodes(e)[i]] != r) ghost.emplace_back(mesh.elementNodes(e)[i], r);
  }
  std::sort(ghost.begin(), ghost.end());
  ghost.erase(std::unique(ghost.begin(), ghost.end()), ghost.end());
  for (const auto& g : ghost) size.ghostNodes[g.second] += 1.0;
}

/// Bytes of `size`'s mesh term on a rank.
double meshBytes(const ModelSize& size) {
  return kMeshBytesPerNode * size.meshNodes + kMeshBytesPerElement * size.meshElements +
         kMeshBytesPerElementNode * size.meshElementNodes + kContactBytesPerFacet * size.contactFacets;
}

}  // namespace

std::string MemoryEstimate::describe() const {
  std::ostringstream os;
  os << "mesh " << formatBytes(mesh) << (meshIsWhole ? " on every rank" : " on the largest rank's part")
     << ", matrices " << formatBytes(matrix) << ", " << solverWhat
     << " " << formatBytes(solver);
  return os.str();
}

bool estimateReadsRankNodes(const Teuchos::ParameterList& solver) {
  if (solver.get<std::string>("Strategy") == "FETI-DP" || !solver.isSublist("Linear Solver")) return false;
  const Teuchos::ParameterList& linear = solver.sublist("Linear Solver");
  return linear.isParameter("Type") && linear.get<std::string>("Type") == "Belos-MueLu";
}

ModelSize measureModel(const Mesh& mesh, const Partition& partition, int ranks, const ContactOptions& contact,
                       bool withRankNodes) {
  ModelSize size;
  size.dim = mesh.dim();
  size.bodies = bodySizes(mesh);
  size.meshNodes = mesh.numNodes();
  size.meshElements = mesh.numElements();
  size.meshElementNodes = elementNodes(mesh);
  size.contactFacets = contactFacets(mesh, contact);
  size.partitionCorners = partition.numSubdomains > 1 ? elementCorners(mesh) : 0.0;
  size.subdomainElements.assign(std::max(partition.numSubdomains, 1), 0.0);
  for (int s : partition.elementSubdomain) size.subdomainElements[s] += 1.0;
  if (withRankNodes) rankNodes(mesh, partition, std::max(ranks, 1), size);
  return size;
}

ModelSize measureModelOnParts(MPI_Comm comm, const Mesh& part, const Partition& partition,
                              const ContactOptions& contact, bool withRankNodes) {
  ModelSize size;
  size.meshIsWhole = false;
  size.dim = part.dim();
  size.bodies = bodySizes(part);
  // The largest rank's part, term by term (each is a bound of that rank's);
  // the contact surfaces whole, as every rank holds them.
  std::array<double, 4> mine{{double(part.numNodes()), double(part.numElements()), elementNodes(part),
                              partition.numSubdomains > 1 ? elementCorners(part) : 0.0}};
  MPI_Allreduce(MPI_IN_PLACE, mine.data(), 4, MPI_DOUBLE, MPI_MAX, comm);
  size.meshNodes = mine[0];
  size.meshElements = mine[1];
  size.meshElementNodes = mine[2];
  size.partitionCorners = mine[3];
  size.contactFacets = contactFacets(part, contact);
  MPI_Allreduce(MPI_IN_PLACE, &size.contactFacets, 1, MPI_DOUBLE, MPI_SUM, comm);
  size.subdomainElements.assign(std::max(partition.numSubdomains, 1), 0.0);
  for (int s : partition.elementSubdomain) size.subdomainElements[s] += 1.0;
  MPI_Allreduce(MPI_IN_PLACE, size.subdomainElements.data(), static_cast<int>(size.subdomainElements.size()),
                MPI_DOUBLE, MPI_SUM, comm);
  if (withRankNodes) {
    int rank = 0, ranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &ranks);
    const NodeDirectory directory(comm, part);
    double owned = 0.0;
    for (int holder : directory.lowestHolder()) owned += holder == rank ? 1.0 : 0.0;
    const double ghosts = part.numNodes() - owned;
    size.ownedNodes.assign(ranks, 0.0);
    size.ghostNodes.assign(ranks, 0.0);
    MPI_Allgather(&owned, 1, MPI_DOUBLE, size.ownedNodes.data(), 1, MPI_DOUBLE, comm);
    MPI_Allgather(&ghosts, 1, MPI_DOUBLE, size.ghostNodes.data(), 1, MPI_DOUBLE, comm);
  }
  return size;
}

MemoryEstimate estimateMemory(const ModelSize& size, int ranks, const Teuchos::ParameterList& solver) {
  MemoryEstimate est;
  const int dim = size.dim;
  ranks = std::max(ranks, 1);
  // Per body: DOFs and matrix entries.
  double dofs = 0.0, entries = 0.0, elements = 0.0, nodes = 0.0;
  for (const ModelSize::BodySize& body : size.bodies) {
    const double n = static_cast<double>(dim) * body.nodes;
    dofs += n;
    entries += n * dim * couplingsPerNode(body.cellType);
    elements += body.elements;
    nodes += body.nodes;
  }
  est.mesh = meshBytes(size);
  est.meshIsWhole = size.meshIsWhole;
  est.partition = kPartitionBytesPerCorner * size.partitionCorners;
  const double rowEntries = dofs > 0 ? entries / dofs : 0.0;
  const std::string strategy = solver.get<std::string>("Strategy");
  char what[160];
  if (strategy == "FETI-DP") {
    // Subdomain sizes from the partition (elements per subdomain x nodes per
    // element over the elements per node of the body type: ~ its DOFs).
    const int S = static_cast<int>(size.subdomainElements.size());
    const double dofsPerElement = elements > 0 ? dofs / elements : 0.0;
    std::vector<int> owner = subdomainOwnerRank(S, ranks);
    std::vector<double> perRank(ranks, 0.0), matrixPerRank(ranks, 0.0);
    for (int s = 0; s < S; ++s) {
      const double n = size.subdomainElements[s] * dofsPerElement;
      perRank[owner[s]] += 8.0 * kFetiFactorCopies * n * rowEntries * fill(n, dim);
      matrixPerRank[owner[s]] += kFetiBytesPerEntry * n * rowEntries;
    }
    for (int r = 0; r < ranks; ++r) est.perRank.push_back(est.atPeak(matrixPerRank[r], perRank[r]));
    const int worst = static_cast<int>(std::max_element(est.perRank.begin(), est.perRank.end()) - est.perRank.begin());
    est.solver = perRank[worst];
    est.matrix = matrixPerRank[worst];
    std::snprintf(what, sizeof what, "FETI-DP subdomain factors and operators (%d subdomains of %.3g DOFs on average)",
                  S, dofs / S);
  } else {
    const Teuchos::ParameterList* linear = solver.isSublist("Linear Solver") ? &solver.sublist("Linear Solver") : nullptr;
    const std::string type =
        linear && linear->isParameter("Type") ? linear->get<std::string>("Type") : std::string("MUMPS");
    est.matrix = kMatrixBytesPerEntry * entries / ranks;
    if (type == "Belos-MueLu") {
      // Per rank: its rows' entries, with the overhead of its ghosts.
      const double entriesPerNode = nodes > 0 ? entries / nodes : 0.0;
      double worst = -1.0;
      for (int r = 0; r < ranks && r < static_cast<int>(size.ownedNodes.size()); ++r) {
        const double e = size.ownedNodes[r] * entriesPerNode;
        const double g = size.ownedNodes[r] > 0 ? size.ghostNodes[r] / size.ownedNodes[r] : 0.0;
        const double matrix = kMatrixBytesPerEntry * e, hierarchy = (kMueLuBytesPerEntry + kMueLuBytesPerGhostShare * g) * e;
        est.perRank.push_back(est.atPeak(matrix, hierarchy));
        if (est.perRank.back() > worst) worst = est.perRank.back(), est.matrix = matrix, est.solver = hierarchy;
      }
      std::snprintf(what, sizeof what, "%s preconditioner", type.c_str());
    } else if (type == "Belos-FROSch") {
      est.solver = kIterativeBytesPerEntry * entries / ranks;
      std::snprintf(what, sizeof what, "%s preconditioner", type.c_str());
    } else if (type == "Amesos2") {
      // Gathered to rank 0 and factorised there (KLU2 fills about twice as
      // much as a nested-dissection ordering).
      est.solver = 12.0 * entries + 2.0 * 8.0 * entries * fill(dofs, dim);
      std::snprintf(what, sizeof what, "KLU2 factors of %.3g DOFs on rank 0", dofs);
      est.perRank.assign(ranks, est.atPeak(est.matrix, 0.0));
      est.perRank[0] = est.atPeak(est.matrix, est.solver);
    } else {
      est.solver = 8.0 * entries * fill(dofs, dim) / ranks;
      std::snprintf(what, sizeof what, "%s factors of %.3g DOFs", type.c_str(), dofs);
    }
  }
  if (est.perRank.empty()) est.perRank.assign(ranks, est.total());
  est.solverWhat = what;
  return est;
}

MemoryEstimate estimateMemory(const Mesh& mesh, const Partition& partition, int ranks,
                              const Teuchos::ParameterList& solver, const ContactOptions& contact) {
  return estimateMemory(measureModel(mesh, partition, ranks, contact, estimateReadsRankNodes(solver)), ranks, solver);
}

}  // namespace ddc
