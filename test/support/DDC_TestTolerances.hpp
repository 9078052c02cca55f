// Named tolerances for tests: each says what it means, so a reader can judge
// whether a failure is a bug or a too-strict test (MFEM / Tribol style).
#pragma once

#include <algorithm>
#include <cmath>

namespace ddc::test {

/// Round-off level for quantities assembled by summing O(100) terms of size
/// O(1): results that must agree "to machine precision".
constexpr double kRoundoff = 1e-12;

/// Relative agreement required between runs that differ only in summation
/// order (1 vs 2 ranks, different partitions), as doc/verification.md requires.
constexpr double kRankIndependence = 1e-10;

/// Central finite differences with step h have truncation error O(h^2) and
/// cancellation error O(eps/h); with h = 1e-6 relative the combined error is
/// about 1e-8 to 1e-9 relative, so 1e-6 rejects any real derivative bug
/// (which shows up as O(1) relative error) without flaking on round-off.
constexpr double kFiniteDifference = 1e-6;

/// Energy identity U = 1/2 f.u for linear elasticity: U = 1/2 u^T K u
/// exactly, so U - 1/2 f.u = -1/2 u^T r with r the residual of the direct
/// solve (backward-stable: |r| ~ eps |K| |u|), i.e. about eps * cond(K)
/// relative at worst (cond(K) ~ 1e5 for the cantilever meshes of the
/// verification tests); measured <= 4e-16 in 2-D.
constexpr double kEnergyIdentity = 1e-10;

/// |a - b| relative to max(|a|, |b|, floor).
inline double relDiff(double a, double b, double floor = 1e-300) {
  return std::abs(a - b) / std::max({std::abs(a), std::abs(b), floor});
}

}  // namespace ddc::test
