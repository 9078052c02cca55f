// Named tolerances and bounds of the FETI-DP tests (the algebra in
// packages/feti/test, the analysis level in packages/analysis/test):
// doc/verification.md rung 3 and doc/performance.md.
#pragma once

namespace ddc::test {

/// Belos tolerance of the accuracy tests: relative dual residual
/// ||d - F lambda|| / ||d||. The displacement error is about this times the
/// condition number of the preconditioned F (O(10..100) for these
/// Dirichlet-preconditioned problems), far below kFetiVsDirect.
constexpr double kTightBelos = 1e-12;

/// FETI-DP displacements against a direct solve of the assembled matrix,
/// relative 2-norm of the difference (the acceptance value of
/// doc/verification.md, rung 3). With kTightBelos the error is ~1e-10 at
/// worst (measured ~1e-12 and below: the [feti-accuracy] / [ feti-dp  ]
/// lines); 1e-8 leaves a factor 100. A wrong B sign, a missing coarse
/// contribution, a wrong right-hand side split or a solve stopped early
/// (FetiFirstSolve.LooseBelosToleranceIsDetected) gives errors far above.
constexpr double kFetiVsDirect = 1e-8;

/// Belos tolerance of the iteration-count studies (doc/performance.md).
constexpr double kCountBelos = 1e-8;

/// Upper bound of Dirichlet-preconditioned CG iterations at H/h = 16 with
/// vertex primal DOFs (doc/verification.md, rung 3). FETI-DP theory bounds
/// the condition number by C (1 + log H/h)^2 independently of the number of
/// subdomains; the measured counts are printed by the tests.
constexpr int kMaxDirichletIterations = 30;

/// Allowed relative growth of an iteration count when the number of
/// subdomains grows 4x at fixed H/h (16 -> 64 in 2-D, 8 -> 64 in 3-D).
constexpr double kMaxGrowth = 0.20;

}  // namespace ddc::test
