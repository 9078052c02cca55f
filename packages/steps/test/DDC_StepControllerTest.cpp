// BisectingSteps, the step controller of the quasi-static analysis: the
// sequence of (sub)steps it proposes with and without Newton failures, the
// bisection depth per nominal step, and giving up after Max Bisections.
// AdaptiveSteps, the controller of Step Control: repeats, reductions and
// growth from an error indicator, its bounds, and the end of the run.
// Both: a state saved after an accepted step restores into a new controller
// (a restart), which then proposes what the saved one would have.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
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

TEST(BisectingSteps, StopsHalvingWhereAStepNoLongerChangesTheValue) {
  // Max Bisections = INT_MAX and every attempt fails: halving ends where
  // half the step would be below the resolution of the value, at the start
  // (0 of 1) and in the middle (1 of 2, the run failing from there on).
  for (const double finalValue : {1.0, 2.0}) {
    ddc::BisectingSteps c(finalValue, int(finalValue), std::numeric_limits<int>::max());
    if (finalValue == 2.0) c.accept(c.propose());  // to 1
    const double from = c.current();
    int attempts = 0;
    ddc::StepProposal p = c.propose();
    for (; attempts < 10000; ++attempts) {
      if (!c.reject(p)) break;
      p = c.propose();
    }
    const double resolution = ddc::stepResolution(from, finalValue);
    EXPECT_LT(attempts, 100) << "halving went on below the resolution";
    EXPECT_GE(p.size, resolution);
    EXPECT_LT(0.5 * p.size, resolution);
    EXPECT_GT(p.to, p.from) << "the last step tried still changes the value";
    EXPECT_EQ(c.current(), from);
    EXPECT_NE(c.limits("Dynamics").find("Dynamics/Max Bisections = 2147483647 not used up"), std::string::npos)
        << c.limits("Dynamics");
  }
}

TEST(BisectingSteps, OutOfRangeArgumentsAreRefused) {
  EXPECT_THROW(ddc::BisectingSteps(0.0, 1, 0), std::invalid_argument);
  EXPECT_THROW(ddc::BisectingSteps(1.0, 0, 0), std::invalid_argument);
  EXPECT_THROW(ddc::BisectingSteps(1.0, 1, -1), std::invalid_argument);
}

/// Drive an AdaptiveSteps whose indicator is `error(p, attempt)` (attempt:
/// 0 for the first solve of a step, 1, 2, ... for its repeats); returns the
/// accepted steps and, per accepted step, the verdicts before it.
struct Driven {
  std::vector<ddc::StepProposal> accepted;
  std::vector<std::vector<ddc::StepVerdict>> verdicts;
};
Driven driveAdaptive(ddc::AdaptiveSteps& c, const std::function<double(const ddc::StepProposal&, int)>& error,
                     int maxAttempts = 10000) {
  Driven d;
  std::vector<ddc::StepVerdict> before;
  int repeats = 0;
  for (int attempt = 0; !c.done() && attempt < maxAttempts; ++attempt) {
    const ddc::StepProposal p = c.propose();
    EXPECT_EQ(p.from, c.current());
    const ddc::StepVerdict v = c.judge(p, error(p, repeats));
    if (v != ddc::StepVerdict::Accept) {
      repeats = v == ddc::StepVerdict::Repeat ? repeats + 1 : 0;
      before.push_back(v);
      continue;
    }
    c.accept(p);
    d.accepted.push_back(p);
    d.verdicts.push_back(before);
    before.clear();
    repeats = 0;
  }
  return d;
}

/// The frozen-geometry error grows as the square of the step: e = k h^2.
double quadratic(const ddc::StepProposal& p, double k) { return k * p.size * p.size; }

TEST(AdaptiveSteps, WithoutErrorTheStepsGrowToTheMaximumAndEndExactly) {
  // Zero error: 0.1, 0.2, 0.4 (doubling), then 0.4 (the maximum) ... and
  // the run ends on 3.0 exactly.
  ddc::AdaptiveSteps c(3.0, 0.1, 0.01, 0.4, 1e-3, 4, 0);
  const auto d = driveAdaptive(c, [](const ddc::StepProposal&, int) { return 0.0; });
  ASSERT_GE(d.accepted.size(), 3u);
  EXPECT_EQ(d.accepted[0].size, 0.1);
  EXPECT_EQ(d.accepted[1].size, 0.2);
  EXPECT_EQ(d.accepted[2].size, 0.4);
  EXPECT_EQ(d.accepted.back().to, 3.0);
  EXPECT_EQ(c.current(), 3.0);
  EXPECT_TRUE(c.done());
  for (size_t i = 0; i < d.accepted.size(); ++i) {
    EXPECT_EQ(d.accepted[i].step, int(i) + 1);
    EXPECT_LE(d.accepted[i].size, 0.4 * (1 + ddc::AdaptiveSteps::kStretch)) << i;
  }
  EXPECT_EQ(c.numSteps(), 0);
}

TEST(AdaptiveSteps, TheStepSizeSettlesWhereTheErrorMeetsTheTolerance) {
  // e = k h^2 with k = 10: the tolerance 1e-3 allows h = 0.01. With no
  // repeats allowed, the first step (0.02, e = 4e-3) is reduced to
  // kSafety sqrt(1e-3 / 4e-3) = 0.45 of itself, and the accepted steps
  // settle at kSafety x 0.01.
  const double k = 10.0, tol = 1e-3, allowed = std::sqrt(tol / k);
  ddc::AdaptiveSteps c(1.0, 0.02, 1e-4, 0.1, tol, 4, 0);
  const auto d = driveAdaptive(c, [&](const ddc::StepProposal& p, int) { return quadratic(p, k); });
  ASSERT_GT(d.accepted.size(), 10u);
  EXPECT_EQ(d.verdicts[0], std::vector<ddc::StepVerdict>{ddc::StepVerdict::Reduce});
  EXPECT_NEAR(d.accepted[0].size, 0.45 * 0.02, 1e-15);
  int reductions = 0;
  for (size_t i = 0; i < d.accepted.size(); ++i) {
    const auto& p = d.accepted[i];
    EXPECT_LE(quadratic(p, k), tol) << "accepted step " << i << " above the tolerance";
    if (i + 2 < d.accepted.size())  // away from the end
      EXPECT_GE(p.size, 0.8 * allowed) << i;
    if (i > 0) reductions += int(d.verdicts[i].size());
  }
  EXPECT_EQ(reductions, 0) << "steps sized by a smooth indicator are not rejected";
}

TEST(AdaptiveSteps, AStepAboveTheToleranceIsRepeatedWithItsGeometryThenReduced) {
  // The repeats reduce the error by 10 each; two are allowed. Step 1: error
  // 0.05 -> 0.005 -> 0.0005 <= 1e-3 after two repeats: accepted at full size.
  // Step 2 (error 1e4 h^2): 100, 10, 1 after two repeats: reduced, and
  // from the smaller size repeated again.
  ddc::AdaptiveSteps c(0.3, 0.1, 0.001, 0.1, 1e-3, 4, 2);
  const auto d = driveAdaptive(c, [&](const ddc::StepProposal& p, int repeats) {
    const double first = p.step == 1 ? 0.05 : p.step == 2 ? quadratic(p, 1e4) : 0.0;
    return first * std::pow(0.1, repeats);
  });
  ASSERT_GE(d.accepted.size(), 2u);
  using V = ddc::StepVerdict;
  EXPECT_EQ(d.verdicts[0], (std::vector<V>{V::Repeat, V::Repeat}));
  EXPECT_EQ(d.accepted[0].size, 0.1);
  EXPECT_EQ(d.accepted[0].to, 0.1);
  // Step 2 at 0.1: 1, 0.1, 0.01: two repeats, then a reduction.
  ASSERT_GE(d.verdicts[1].size(), 3u);
  EXPECT_EQ(d.verdicts[1][0], V::Repeat);
  EXPECT_EQ(d.verdicts[1][1], V::Repeat);
  EXPECT_EQ(d.verdicts[1][2], V::Reduce);
  EXPECT_LT(d.accepted[1].size, 0.1);
  // After a step accepted with repeats the size is kept, not shrunk.
  EXPECT_EQ(d.accepted[1].size, d.accepted[2].size);
}

TEST(AdaptiveSteps, RepeatsThatDoNotReduceTheErrorStopAndTheStepIsReduced) {
  // Geometry Corrections = INT_MAX, an indicator that repeats do not reduce
  // (it sits at round-off): one repeat, then the step is reduced, with a
  // note; down to the minimum size, where it is accepted.
  ddc::AdaptiveSteps c(1.0, 0.1, 0.05, 0.1, 1e-3, 4, std::numeric_limits<int>::max());
  const ddc::StepProposal p = c.propose();
  EXPECT_EQ(c.judge(p, 0.01), ddc::StepVerdict::Repeat);
  EXPECT_EQ(c.takeNote(), "");
  EXPECT_EQ(c.judge(c.propose(), 0.01), ddc::StepVerdict::Reduce);
  const std::string note = c.takeNote();
  EXPECT_NE(note.find("geometry correction 1 did not reduce the frozen-geometry error (0.01 -> 0.01"),
            std::string::npos) << note;
  EXPECT_NE(note.find("Step Control/Geometry Corrections = 2147483647 not used up"), std::string::npos) << note;
  EXPECT_EQ(c.takeNote(), "") << "a note is passed on once";
  const auto d = driveAdaptive(c, [](const ddc::StepProposal&, int) { return 0.01; }, 1000);
  EXPECT_EQ(c.current(), 1.0) << "the run ends";
  ASSERT_FALSE(d.accepted.empty());
  EXPECT_EQ(d.accepted[0].size, 0.05);
  // A repeat that reduces the error a little is still followed by another.
  ddc::AdaptiveSteps r(1.0, 0.1, 0.05, 0.1, 1e-3, 4, std::numeric_limits<int>::max());
  EXPECT_EQ(r.judge(r.propose(), 0.01), ddc::StepVerdict::Repeat);
  EXPECT_EQ(r.judge(r.propose(), 0.009), ddc::StepVerdict::Repeat);
}

TEST(AdaptiveSteps, AtTheMinimumSizeAStepIsAcceptedWhateverItsError) {
  ddc::AdaptiveSteps c(1.0, 0.1, 0.05, 0.1, 1e-3, 4, 0);
  const auto d = driveAdaptive(c, [](const ddc::StepProposal&, int) { return 1.0; });
  ASSERT_FALSE(d.accepted.empty());
  EXPECT_EQ(d.verdicts[0], std::vector<ddc::StepVerdict>{ddc::StepVerdict::Reduce});
  EXPECT_EQ(d.accepted[0].size, 0.05);
  EXPECT_TRUE(c.atMinimum());
  EXPECT_EQ(c.current(), 1.0);
}

TEST(AdaptiveSteps, NewtonFailureHalvesTheStepUpToTheLimits) {
  // Two halvings allowed: 0.1 -> 0.05 -> 0.025; the third failure gives up.
  ddc::AdaptiveSteps c(1.0, 0.1, 0.001, 0.1, 1e-3, 2, 0);
  ddc::StepProposal p = c.propose();
  EXPECT_TRUE(c.reject(p));
  p = c.propose();
  EXPECT_EQ(p.size, 0.05);
  EXPECT_EQ(p.depth, 1);
  EXPECT_TRUE(c.reject(p));
  p = c.propose();
  EXPECT_EQ(p.size, 0.025);
  EXPECT_FALSE(c.reject(p));
  // And not below the minimum size.
  ddc::AdaptiveSteps m(1.0, 0.1, 0.06, 0.1, 1e-3, 6, 0);
  EXPECT_FALSE(m.reject(m.propose()));
}

TEST(AdaptiveSteps, ANanIndicatorIsNeverAccepted) {
  ddc::AdaptiveSteps c(1.0, 0.1, 0.01, 0.1, 1e-3, 2, 1);
  const ddc::StepProposal p = c.propose();
  EXPECT_EQ(c.judge(p, std::nan("")), ddc::StepVerdict::Repeat);
  EXPECT_EQ(c.judge(c.propose(), std::nan("")), ddc::StepVerdict::Reduce);
}

TEST(AdaptiveSteps, OutOfRangeArgumentsAreRefused) {
  EXPECT_THROW(ddc::AdaptiveSteps(0.0, 0.1, 0.01, 0.1, 1e-3, 2, 1), std::invalid_argument);
  EXPECT_THROW(ddc::AdaptiveSteps(1.0, 0.1, 0.0, 0.1, 1e-3, 2, 1), std::invalid_argument);
  EXPECT_THROW(ddc::AdaptiveSteps(1.0, 0.1, 0.2, 0.3, 1e-3, 2, 1), std::invalid_argument);  // min > initial
  EXPECT_THROW(ddc::AdaptiveSteps(1.0, 0.1, 0.01, 0.05, 1e-3, 2, 1), std::invalid_argument);  // initial > max
  EXPECT_THROW(ddc::AdaptiveSteps(1.0, 0.1, 0.01, 0.1, 0.0, 2, 1), std::invalid_argument);
  EXPECT_THROW(ddc::AdaptiveSteps(1.0, 0.1, 0.01, 0.1, 1e-3, -1, 1), std::invalid_argument);
  EXPECT_THROW(ddc::AdaptiveSteps(1.0, 0.1, 0.01, 0.1, 1e-3, 2, -1), std::invalid_argument);
}

/// The proposals of `c` to its end (accepting every step; `error` judges
/// each if the controller controls the error).
std::vector<ddc::StepProposal> rest(ddc::StepController& c, double error = 0.0) {
  std::vector<ddc::StepProposal> out;
  while (!c.done()) {
    const ddc::StepProposal p = c.propose();
    if (c.controlsError()) EXPECT_EQ(c.judge(p, error), ddc::StepVerdict::Accept);
    c.accept(p);
    out.push_back(p);
  }
  return out;
}

void expectSame(const std::vector<ddc::StepProposal>& a, const std::vector<ddc::StepProposal>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].step, b[i].step) << i;
    EXPECT_EQ(a[i].from, b[i].from) << i;
    EXPECT_EQ(a[i].to, b[i].to) << i;
    EXPECT_EQ(a[i].size, b[i].size) << i;
    EXPECT_EQ(a[i].depth, b[i].depth) << i;
  }
}

TEST(BisectingSteps, ARestoredStateProposesTheStepsTheSavedControllerWould) {
  // Stopped within a bisected nominal step: the restored controller goes on
  // with the halved size and the depth of that step.
  ddc::BisectingSteps saved(1.0, 10, 4);
  for (int k = 0; k < 3; ++k) saved.accept(saved.propose());
  ASSERT_TRUE(saved.reject(saved.propose()));
  saved.accept(saved.propose());  // the first half of step 4
  const auto state = saved.saveState();
  ddc::BisectingSteps restored(1.0, 10, 4);
  ASSERT_TRUE(restored.restoreState(state, 4));
  EXPECT_EQ(restored.current(), saved.current());
  expectSame(rest(restored), rest(saved));
}

TEST(BisectingSteps, ARestoredStateWithOtherStepsGoesOnFromItsValue) {
  ddc::BisectingSteps saved(1.0, 10, 4);
  for (int k = 0; k < 3; ++k) saved.accept(saved.propose());  // at 0.3
  ddc::BisectingSteps finer(2.0, 40, 4);  // steps of 0.05 to 2
  ASSERT_TRUE(finer.restoreState(saved.saveState(), 3));
  EXPECT_EQ(finer.current(), saved.current());
  const auto steps = rest(finer);
  ASSERT_FALSE(steps.empty());
  EXPECT_EQ(steps.front().from, saved.current());
  EXPECT_EQ(steps.front().step, 7);  // 0.3 is the end of nominal step 6 of 40 to 2
  EXPECT_EQ(steps.back().to, 2.0);
  EXPECT_EQ(steps.size(), 34u);
  // Another controller's state: from its value, at the full size.
  ddc::AdaptiveSteps adaptive(1.0, 0.1, 0.01, 0.2, 1e-3, 2, 1);
  adaptive.accept(adaptive.propose());
  ddc::BisectingSteps equal(1.0, 10, 4);
  ASSERT_TRUE(equal.restoreState(adaptive.saveState(), 1));
  EXPECT_EQ(equal.current(), adaptive.current());
  EXPECT_EQ(equal.propose().size, 0.1);
  // Not a saved state.
  EXPECT_FALSE(equal.restoreState({}, 1));
  EXPECT_FALSE(equal.restoreState({7.0, 1.0, 2.0}, 1));
}

TEST(AdaptiveSteps, ARestoredStateProposesTheStepsTheSavedControllerWould) {
  ddc::AdaptiveSteps saved(1.0, 0.05, 0.01, 0.2, 1e-3, 2, 1);
  for (int k = 0; k < 3; ++k) {
    const ddc::StepProposal p = saved.propose();
    ASSERT_EQ(saved.judge(p, 2e-4), ddc::StepVerdict::Accept);  // grows the next step
    saved.accept(p);
  }
  ddc::AdaptiveSteps restored(1.0, 0.05, 0.01, 0.2, 1e-3, 2, 1);
  ASSERT_TRUE(restored.restoreState(saved.saveState(), 3));
  EXPECT_EQ(restored.current(), saved.current());
  expectSame(rest(restored, 2e-4), rest(saved, 2e-4));
  // Tighter bounds: the saved size clamped into them.
  ddc::AdaptiveSteps tight(1.0, 0.02, 0.01, 0.02, 1e-3, 2, 1);
  ddc::AdaptiveSteps again(1.0, 0.05, 0.01, 0.2, 1e-3, 2, 1);
  for (int k = 0; k < 3; ++k) {
    const ddc::StepProposal p = again.propose();
    again.judge(p, 2e-4);
    again.accept(p);
  }
  ASSERT_TRUE(tight.restoreState(again.saveState(), 3));
  EXPECT_EQ(tight.propose().size, 0.02);
  EXPECT_EQ(tight.propose().step, 4);
}

}  // namespace
