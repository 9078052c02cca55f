// GoogleTest main for DDContact unit tests under MPI: initialises MPI with
// MPI_THREAD_MULTIPLE (ddc::MpiSession, as ddcontact does) and Kokkos through
// Tpetra::ScopeGuard, prints results from rank 0 only, and
// makes the exit status the same on every rank (a failure anywhere fails all).
#include <gtest/gtest.h>
#include <mpi.h>

#include <Tpetra_Core.hpp>

#include "DDC_MpiSession.hpp"

int main(int argc, char** argv) {
  ddc::MpiSession mpi(&argc, &argv);  // MPI_THREAD_MULTIPLE (PT-Scotch), before Tpetra
  Tpetra::ScopeGuard scope(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int local = RUN_ALL_TESTS();
  int global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (rank != 0 && local != 0) std::fprintf(stderr, "rank %d: tests failed\n", rank);
  return global;
}
