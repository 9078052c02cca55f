// MPI for a DDContact program: initialised with MPI_THREAD_MULTIPLE, since
// PT-Scotch (Partition/Method = PT-Scotch, doc/partitioning.md) runs threads
// that call MPI; Debian's PT-Scotch crashes or hangs on three or more ranks
// otherwise.
#pragma once

#include <mpi.h>

namespace ddc {

/// Construct before Tpetra::ScopeGuard, which then leaves MPI to it: calls
/// MPI_Init_thread(MPI_THREAD_MULTIPLE) unless MPI is already initialised,
/// and MPI_Finalize at destruction if it initialised MPI.
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv) {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (initialised) return;
    int provided = 0;
    MPI_Init_thread(argc, argv, MPI_THREAD_MULTIPLE, &provided);
    owner_ = true;
  }
  ~MpiSession() {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (owner_ && !finalised) MPI_Finalize();
  }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

 private:
  bool owner_ = false;
};

/// MPI's thread support level (MPI_Query_thread) is MPI_THREAD_MULTIPLE.
inline bool mpiThreadMultiple() {
  int level = MPI_THREAD_SINGLE;
  MPI_Query_thread(&level);
  return level >= MPI_THREAD_MULTIPLE;
}

}  // namespace ddc
