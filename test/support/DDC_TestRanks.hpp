// This process's rank and the number of ranks of MPI_COMM_WORLD, for unit
// tests that run on several ranks.
#pragma once

#include <mpi.h>

namespace ddc::test {

inline int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

inline int ranks() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

}  // namespace ddc::test
