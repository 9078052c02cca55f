// The slip rows of a slipping frictional pair in the FETI-DP dual problem
// (doc/feti-dp.md "Friction rows"): the exact linearisation of Coulomb's
// slip row, written as coupled rows of FetiDpSolver
// (setConstraintCoupling()).
//
// The linearised slip rows of a pair (DDC_Friction.hpp) read
//
//   R + A δλ_t + a δλ_n + S δu_t = 0,   δu_t = B_t δu (the slip rows' values),
//
// A = (I − k P⊥)/c_t, a = μ t̂/c_t, S = −k P⊥, k = μ p⁺/|z|. A and S share
// their eigenvectors v_j (t̂ and, in 3-D, the direction across it), so
// row by row along v_j, with b = −R:
//
//   σ_j = v_jᵀ S v_j ≈ 0 (along the slip):  v_j·δλ_t = (b_j − a_j δλ_n)/α_j,
//       a multiplier known up to a multiple of the normal one's: the row's
//       multiplier column is the normal row's unknown (T ≠ Gᵀ: GMRES);
//   σ_j < 0 (across the slip, 3-D):  v_jᵀ B_t δu − (α_j/−σ_j) x = b_j/σ_j,
//       a compliant constraint row in the direction v_j, x = v_j·δλ_t its
//       unknown (symmetric).
//
// A row the supports hold (slipRowHeld()) stays released; the other row
// of the pair is then taken along its own direction.
#pragma once

#include <vector>

#include "DDC_FetiDpSolver.hpp"
#include "DDC_Friction.hpp"

namespace ddc {

/// Below this k = μ p⁺/|z| the direction across the slip is taken as known
/// (its multiplier c_t b_j, the lagged value): the compliance α_j/(−σ_j)
/// = (1 − k)/(k c_t) would dominate the row, which then holds nothing.
constexpr double kCoupledSlipRowMinRatio = 1e-3;

/// What one slipping pair's tangential rows are in the dual problem.
struct SlipRowsInDual {
  /// Per tangential row α: active in the dual problem (it holds the unknown
  /// across the slip), its right-hand side c, and the known part of its
  /// multiplier increment (its force enters the subdomains' right-hand side).
  std::vector<char> active;
  std::vector<double> rhs;
  std::vector<double> known;
  /// The coupled rows (FetiDpSolver::CoupledRow; rows as given).
  std::vector<CoupledRow> coupled;
};

/// The rows of the file comment for one pair: `friction` its linearised
/// slip rows (frictionRows() with stick = false), `b` = −R of its
/// tangential rows, `held` the rows the supports hold, `normalRow` and
/// `rows` the LIDs of its normal and tangential rows in the row map of
/// FetiDpSolver (the normal row active).
SlipRowsInDual slipRowsInDual(const FrictionRows& friction, const std::vector<double>& b,
                              const std::vector<char>& held, LO normalRow, const std::vector<LO>& rows);

}  // namespace ddc
