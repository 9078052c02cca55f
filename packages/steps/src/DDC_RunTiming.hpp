// Where the time of a run went: what the Newton iterations of the step loop
// accumulate and the end-of-run report prints (max over ranks).
#pragma once

#include <array>

namespace ddc {

/// Where the time of a run went (seconds, max over ranks after a run).
struct RunTiming {
  double assembly = 0.0;     ///< element evaluation and global/subdomain assembly
  double linearSetup = 0.0;  ///< factorisations / preconditioner set-up (incl. FETI-DP coarse problem)
  double linearSolve = 0.0;  ///< triangular solves / Krylov iterations
  int linearSolves = 0;        ///< number of linear solves (Newton iterations)
  double peakMemoryMiB = 0.0;  ///< peak resident memory, max over ranks
  /// Bytes received in the contact active-set updates of Newton iterations
  /// and of step ends, each the max over ranks
  /// (ContactComponent::valueBytesReceived(); decomposed element).
  std::array<long long, 2> contactValueBytes{{0, 0}};
  /// FETI-DP breakdown (this rank): local, coarse, Dirichlet factorisation;
  /// local solves, coarse solves, preconditioner applications.
  std::array<double, 6> feti{{0, 0, 0, 0, 0, 0}};
};

}  // namespace ddc
