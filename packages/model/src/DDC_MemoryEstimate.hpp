// The memory a run needs, estimated from the mesh, the partition and the
// solver before anything large is allocated (doc/user-guide.md, "Memory").
// Analysis refuses a run whose estimate exceeds ddc::availableMemory(),
// unless Solver/Memory Check = false.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <string>

#include "DDC_Mesh.hpp"
#include "DDC_Partition.hpp"

namespace ddc {

/// Bytes on the most loaded rank, beyond what the process holds at start.
struct MemoryEstimate {
  double mesh = 0.0;    ///< the replicated mesh and its indexes (every rank)
  double matrix = 0.0;  ///< assembled matrices (global or subdomain) and vectors
  double solver = 0.0;  ///< factors / preconditioner of the chosen solver
  std::string solverWhat;  ///< e.g. "MUMPS factors of 1.2e6 DOFs"
  double total() const { return mesh + matrix + solver; }
  /// "mesh 12 MiB on every rank, matrix 300 MiB, MUMPS factors of ... 2.1 GiB"
  std::string describe() const;
};

/// \param solver the validated "Solver" list (Strategy, Linear Solver/Type)
/// \param ranks the number of MPI ranks
MemoryEstimate estimateMemory(const Mesh& mesh, const Partition& partition, int ranks,
                              const Teuchos::ParameterList& solver);

}  // namespace ddc
