// The slip rows of a slipping pair in the FETI-DP dual problem
// (DDC_FetiSlipRows.hpp): whatever the normal multiplier's increment and
// the slip increment, the multipliers the coupled rows give satisfy the
// linearised slip rows R + A δλ_t + a δλ_n + S δu_t = 0 exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "DDC_FetiSlipRows.hpp"

namespace {

/// The rows' multiplier increments for a normal increment dLn and slip
/// increment du (the values of the slip rows, B_t δu), with the dual
/// unknown solved from its equation sum_j g_j du_j - compliance x = c.
std::vector<double> multipliers(const ddc::SlipRowsInDual& s, ddc::LO normalRow, const std::vector<ddc::LO>& rows,
                                double dLn, const std::vector<double>& du) {
  auto at = [&](ddc::LO r) { return int(std::find(rows.begin(), rows.end(), r) - rows.begin()); };
  std::map<ddc::LO, double> x{{normalRow, dLn}};
  for (const auto& r : s.coupled)
    if (!r.equation.empty()) {
      double v = -s.rhs[at(r.row)];
      for (const auto& [j, g] : r.equation) v += g * du[at(j)];
      x[r.row] = v / r.compliance;
    }
  std::vector<double> lt(s.known);
  for (const auto& r : s.coupled)
    for (const auto& [j, a] : r.multiplier) lt[at(r.row)] += a * x.at(j);
  return lt;
}

/// max |R + A δλ_t + a δλ_n + S δu_t| over the rows, R = −b.
double linearisedResidual(const ddc::FrictionRows& fr, const std::vector<double>& b, double dLn,
                          const std::vector<double>& lt, const std::vector<double>& du) {
  const int nt = int(b.size());
  double worst = 0.0;
  for (int a = 0; a < nt; ++a) {
    double r = -b[a] + fr.lambdaNDerivative[a] * dLn;
    for (int c = 0; c < nt; ++c) r += fr.lambdaTDerivative(a, c) * lt[c] + fr.slipDerivative(a, c) * du[c];
    worst = std::max(worst, std::abs(r));
  }
  return worst;
}

ddc::FrictionPairState slipping(double mu, double ct) {
  ddc::FrictionPairState f;
  f.coefficient = mu;
  f.stiffness = ct;
  f.stick = false;
  return f;
}

/// Round-off of the 2 x 2 eigen-decomposition relative to the rows' size.
constexpr double kExact = 1e-12;

}  // namespace

TEST(FetiSlipRows, ThreeDimensionalSlipRowsHoldForAnyIncrement) {
  const auto f = slipping(0.3, 2.0);
  const double slip[2] = {0.4, -0.25}, lt[2] = {0.2, 0.5}, ln = -3.0;
  const auto fr = ddc::frictionRows(2, slip, ln, lt, f);
  const std::vector<double> b{0.07, -0.02};
  const std::vector<ddc::LO> rows{11, 12};
  const auto s = ddc::slipRowsInDual(fr, b, {0, 0}, 10, rows);
  // One unknown (across the slip) in the first row, the other row released.
  EXPECT_EQ(s.active[0] + s.active[1], 1);
  for (const auto& [dLn, du] : std::vector<std::pair<double, std::vector<double>>>{
           {0.0, {0.0, 0.0}}, {0.5, {0.01, -0.03}}, {-1.2, {-0.2, 0.15}}}) {
    const auto inc = multipliers(s, 10, rows, dLn, du);
    EXPECT_LT(linearisedResidual(fr, b, dLn, inc, du), kExact) << "dLn " << dLn;
  }
}

TEST(FetiSlipRows, TwoDimensionalSlipRowFollowsTheNormalMultiplier) {
  const auto f = slipping(0.3, 2.0);
  const double slip[1] = {-0.4}, lt[1] = {0.6}, ln = -3.0;
  const auto fr = ddc::frictionRows(1, slip, ln, lt, f);
  const std::vector<double> b{0.05};
  const auto s = ddc::slipRowsInDual(fr, b, {0}, 3, {4});
  EXPECT_EQ(s.active[0], 0) << "a 2-D slip row has no unknown of its own";
  for (double dLn : {0.0, 0.7, -2.0}) {
    const auto inc = multipliers(s, 3, {4}, dLn, {0.1});
    EXPECT_LT(linearisedResidual(fr, b, dLn, inc, {0.1}), kExact);
  }
}

TEST(FetiSlipRows, HeldRowStaysReleased) {
  const auto f = slipping(0.3, 2.0);
  const double slip[2] = {0.4, 0.0}, lt[2] = {0.2, 0.0}, ln = -3.0;
  const auto fr = ddc::frictionRows(2, slip, ln, lt, f);
  const auto s = ddc::slipRowsInDual(fr, {0.07, 0.0}, {0, 1}, 10, {11, 12});
  EXPECT_EQ(s.active[1], 0);
  EXPECT_EQ(s.known[1], 0.0);
  for (const auto& r : s.coupled) EXPECT_NE(r.row, 12) << "the held row is coupled";
  // Along the free row (the slip's direction) the row is exact.
  const auto inc = multipliers(s, 10, {11, 12}, 0.5, {0.0, 0.0});
  EXPECT_LT(linearisedResidual(fr, {0.07, 0.0}, 0.5, inc, {0.0, 0.0}), kExact);
}
