// The memory a run needs, estimated from the mesh, the partition, the
// contact surfaces and the solver before anything large is allocated
// (doc/user-guide.md, "Memory"). Analysis refuses a run whose estimate, with
// kMemoryEstimateMargin, exceeds what the ranks of a host share
// (ddc::memoryBudget()), unless Solver/Memory Check = false.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <mpi.h>

#include <string>
#include <vector>

#include "DDC_Mesh.hpp"
#include "DDC_Partition.hpp"

namespace ddc {

struct ContactOptions;

/// What the estimate may miss: the largest measured/estimated ratio of the
/// runs in doc/user-guide.md, "Memory" (1.20: block_3d Hex8 with MUMPS at
/// 56k DOFs on 2 ranks, and with Belos-MueLu at 182k DOFs on 16 ranks),
/// rounded up. A run is refused when its estimate times this exceeds what
/// its host offers.
constexpr double kMemoryEstimateMargin = 1.25;

/// Bytes on the most loaded rank, beyond what the process holds at start.
struct MemoryEstimate {
  /// What every rank holds whole: the mesh and the contact surfaces (on
  /// parts of a mesh, meshIsWhole false: the largest rank's part).
  double mesh = 0.0;
  bool meshIsWhole = true;
  /// METIS's graph of the whole mesh on every rank while it partitions;
  /// freed before the matrices exist, so it counts only if it is more.
  double partition = 0.0;
  double matrix = 0.0;  ///< assembled matrices (global or subdomain) and vectors
  double solver = 0.0;  ///< factors / preconditioner of the chosen solver
  std::string solverWhat;  ///< e.g. "MUMPS factors of 1.2e6 DOFs"
  /// The peak with `matrix` and `solver`: the mesh and the larger of the
  /// partition and the two.
  double atPeak(double matrixBytes, double solverBytes) const {
    return mesh + (partition > matrixBytes + solverBytes ? partition : matrixBytes + solverBytes);
  }
  double total() const { return atPeak(matrix, solver); }
  /// The same total for each rank (mesh + that rank's matrices and solver).
  std::vector<double> perRank;
  /// "mesh 12 MiB on every rank, matrix 300 MiB, MUMPS factors of ... 2.1 GiB"
  std::string describe() const;
};

/// What the estimate reads of a model: the whole mesh's bodies, what a rank
/// holds of the mesh, the subdomain sizes and each rank's nodes.
struct ModelSize {
  struct BodySize {
    CellType cellType = CellType::Quad4;
    double nodes = 0.0, elements = 0.0;  ///< in the whole mesh
  };
  int dim = 2;
  std::vector<BodySize> bodies;
  /// What the largest rank holds of the mesh: nodes, elements, element
  /// nodes, and the facets of the contact surfaces.
  double meshNodes = 0.0, meshElements = 0.0, meshElementNodes = 0.0, contactFacets = 0.0;
  /// Element corners in the partitioner's graph on the largest rank (0 for
  /// one subdomain).
  double partitionCorners = 0.0;
  std::vector<double> subdomainElements;  ///< per subdomain
  /// Per rank: its owned nodes and the nodes of its elements others own
  /// (empty unless asked for: only Belos-MueLu reads them).
  std::vector<double> ownedNodes, ghostNodes;
  /// Whether every rank holds the whole mesh (else each its part).
  bool meshIsWhole = true;
};

/// Whether the estimate for `solver` reads each rank's nodes.
bool estimateReadsRankNodes(const Teuchos::ParameterList& solver);

/// The size of a model on a whole mesh under `partition` on `ranks` ranks
/// (node owners as nodeOwnerRanks()); the rank nodes only with
/// `withRankNodes`.
ModelSize measureModel(const Mesh& mesh, const Partition& partition, int ranks, const ContactOptions& contact,
                       bool withRankNodes);

/// The same from the ranks' parts of a mesh (Mesh::isPart()): each rank's
/// elements with their subdomains, the mesh term that of the largest part,
/// the partitioner's graph that of the largest rank (PT-Scotch holds each
/// rank's share), a node owned by the lowest rank that holds it. Collective.
ModelSize measureModelOnParts(MPI_Comm comm, const Mesh& part, const Partition& partition,
                              const ContactOptions& contact, bool withRankNodes);

/// \param solver the validated "Solver" list (Strategy, Linear Solver/Type)
/// \param ranks the number of MPI ranks
MemoryEstimate estimateMemory(const ModelSize& size, int ranks, const Teuchos::ParameterList& solver);

/// estimateMemory() of measureModel().
/// \param contact the validated contact pairs (their side sets are counted)
MemoryEstimate estimateMemory(const Mesh& mesh, const Partition& partition, int ranks,
                              const Teuchos::ParameterList& solver, const ContactOptions& contact);

}  // namespace ddc
