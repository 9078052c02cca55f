// BisectingSteps, the step controller of the quasi-static analysis: the
// sequence of (sub)steps it proposes with and without Newton failures, the
// bisection depth per nominal step, and giving up after Max Bisections.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "DDC_StepController.hpp"

namespace {

/// Sub-step ends are binary fractions of the nominal size: exact sums.
constexpr double kExact = 0.0;

/// Run the controller, failing the attempts whose index is in `failures`;
/// returns the accepted steps.
std::vector<ddc::StepProposal> drive(ddc::StepController& c, const std::vector<int>& failures, bool* gaveUp = nullptr) {
  std::vector<ddc::StepProposal> accepted;
  int attempt = 0;
  while (!c.done()) {
    const ddc::StepProposal p = c.propose();
    EXPECT_EQ(p.from, c.current());
    const bool fail = std::find(failures.begin(), failures.end(), attempt++) != failures.end();
    if (fail) {
      if (!c.reject(p)) {
        if (gaveUp) *gaveUp = true;
        return accepted;
      }
      continue;
    }
    c.accept(p);
    accepted.push_back(p);
  }
  return accepted;
}

TEST(BisectingSteps, EqualNominalStepsWithoutFailures) {
  ddc::BisectingSteps c(2.0, 4, 3);
  const auto steps = drive(c, {});
  ASSERT_EQ(steps.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(steps[i].step, i + 1);
    EXPECT_NEAR(steps[i].to, 0.5 * (i + 1), kExact);
    EXPECT_EQ(steps[i].depth, 0);
    EXPECT_TRUE(c.endsNominalStep(steps[i]));
  }
  EXPECT_EQ(c.current(), 2.0);
}

TEST(BisectingSteps, AFailedStepIsHalvedAndTheHalfSizeKeptToTheNominalEnd) {
  // Attempt 1 (step 2, 0.25 -> 0.5) fails: 0.25 -> 0.375 -> 0.5 at depth 1;
  // then step 3 starts again at full size and depth 0.
  ddc::BisectingSteps c(1.0, 4, 2);
  const auto steps = drive(c, {1});
  ASSERT_EQ(steps.size(), 5u);
  const double ends[] = {0.25, 0.375, 0.5, 0.75, 1.0};
  const int depths[] = {0, 1, 1, 0, 0};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(steps[i].to, ends[i]) << i;
    EXPECT_EQ(steps[i].depth, depths[i]) << i;
  }
  EXPECT_FALSE(c.endsNominalStep(steps[1]));
  EXPECT_TRUE(c.endsNominalStep(steps[2]));
}

TEST(BisectingSteps, TheStepSizeIsTheSameNumberForEveryStepOfOneSize) {
  // 0.7 in 70 steps: to - from varies in its last bits from step to step
  // (0.01 is no binary fraction); size does not, so an integrator's c =
  // 1/(beta h^2) stays the same bit for bit and a factorisation is kept.
  ddc::BisectingSteps c(0.7, 70, 2);
  const auto steps = drive(c, {10});
  ASSERT_EQ(steps.size(), 71u);
  bool roundOffSeen = false;
  for (const auto& p : steps) {
    EXPECT_EQ(p.size, p.depth == 0 ? 0.7 / 70 : 0.5 * (0.7 / 70)) << "step " << p.step;
    roundOffSeen = roundOffSeen || (p.to - p.from != p.size);
  }
  EXPECT_TRUE(roundOffSeen) << "the case does not show why size is needed";
  EXPECT_EQ(c.current(), 0.7);
}

TEST(BisectingSteps, GivesUpAfterMaxBisections) {
  // Every attempt of step 1 fails: the original and two halvings are tried,
  // the third failure exceeds Max Bisections = 2.
  ddc::BisectingSteps c(1.0, 2, 2);
  bool gaveUp = false;
  const auto steps = drive(c, {0, 1, 2}, &gaveUp);
  EXPECT_TRUE(gaveUp);
  EXPECT_TRUE(steps.empty());
  EXPECT_EQ(c.current(), 0.0);
}

TEST(BisectingSteps, OutOfRangeArgumentsAreRefused) {
  EXPECT_THROW(ddc::BisectingSteps(0.0, 1, 0), std::invalid_argument);
  EXPECT_THROW(ddc::BisectingSteps(1.0, 0, 0), std::invalid_argument);
  EXPECT_THROW(ddc::BisectingSteps(1.0, 1, -1), std::invalid_argument);
}

}  // namespace
