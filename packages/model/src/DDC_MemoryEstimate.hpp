// The memory a run needs, estimated from the mesh, the partition, the
// contact surfaces and the solver before anything large is allocated
// (doc/user-guide.md, "Memory"). Analysis refuses a run whose estimate, with
// kMemoryEstimateMargin, exceeds what the ranks of a host share
// (ddc::memoryBudget()), unless Solver/Memory Check = false.
#pragma once

#include <Teuchos_ParameterList.hpp>
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
  /// What every rank holds whole: the mesh and the contact surfaces.
  double mesh = 0.0;
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

/// \param solver the validated "Solver" list (Strategy, Linear Solver/Type)
/// \param ranks the number of MPI ranks
/// \param contact the validated contact pairs (their side sets are counted)
MemoryEstimate estimateMemory(const Mesh& mesh, const Partition& partition, int ranks,
                              const Teuchos::ParameterList& solver, const ContactOptions& contact);

}  // namespace ddc
