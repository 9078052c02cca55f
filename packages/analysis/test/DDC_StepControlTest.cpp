// Step control by the frozen-geometry error in the analysis (doc/contact.md,
// "Step control by the frozen-geometry error"): a step the controller sends
// back - repeated smaller, or first repeated with the geometry of its end
// and then smaller - leaves no trace: the run ends where a run that took the
// accepted steps directly ends (bit for bit on one rank). And the controller judged the
// indicator the history records.
#include <gtest/gtest.h>

#include <Teuchos_XMLParameterListHelpers.hpp>
#include <cmath>
#include <memory>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_StepController.hpp"

namespace {

using ddc::test::isRoot;
using ddc::test::worldComm;
using PL = Teuchos::ParameterList;

/// Two runs of the same steps on several ranks: the parallel direct
/// solver sums in an order that varies from run to run (relative to the
/// peak strain energy / the largest displacement; the indicator is
/// relative already).
constexpr double kRoundoffOfRun = 1e-10;

/// The two half-rings (examples/two_half_rings.xml) on a coarse mesh, 2 x
/// 24 Quad4 per ring, in 10 nominal steps: the decomposed element under the
/// Monolithic strategy (direct solves: runs compare to round-off).
Teuchos::RCP<PL> coarseHalfRings(double tolerance, int corrections) {
  auto deck = Teuchos::getParametersFromXmlFile(std::string(DDC_SOURCE_DIR) + "/examples/two_half_rings.xml");
  for (const char* ring : {"Lower Ring", "Upper Ring"}) {
    PL& g = deck->sublist("Mesh").sublist("Bodies").sublist(ring).sublist("Annular Sector");
    g.set("Radial Elements", 2);
    g.set("Circumferential Elements", 24);
  }
  deck->sublist("Solver").set("Strategy", std::string("Monolithic"));
  deck->sublist("Load Stepping").set("Number of Steps", 10);
  deck->sublist("Step Control").set("Error Tolerance", tolerance);
  deck->sublist("Step Control").set("Geometry Corrections", corrections);
  deck->sublist("Output").set("Progress", false);
  deck->sublist("Output").set("VTK", false);
  deck->sublist("Newton").set("Print Iterations", false);
  return deck;
}

/// Proposes the given steps (their ends) in order, never smaller; repeats
/// a step with the geometry of its end while its indicator exceeds
/// `tolerance`, up to `corrections` times, as AdaptiveSteps does, then
/// accepts it.
class ScriptedSteps final : public ddc::StepController {
 public:
  ScriptedSteps(std::vector<double> ends, double tolerance, int corrections)
      : ends_(std::move(ends)), tolerance_(tolerance), corrections_(corrections) {}
  bool done() const override { return next_ >= ends_.size(); }
  ddc::StepProposal propose() const override {
    ddc::StepProposal p;
    p.step = int(next_) + 1;
    p.from = current();
    p.to = ends_[next_];
    p.size = p.to - p.from;
    return p;
  }
  void accept(const ddc::StepProposal&) override {
    ++next_;
    repeats_ = 0;
  }
  bool controlsError() const override { return corrections_ > 0; }
  ddc::StepVerdict judge(const ddc::StepProposal&, double error) override {
    if (error > tolerance_ && repeats_ < corrections_) {
      ++repeats_;
      return ddc::StepVerdict::Repeat;
    }
    return ddc::StepVerdict::Accept;
  }
  bool reject(const ddc::StepProposal&) override { return false; }
  double current() const override { return next_ ? ends_[next_ - 1] : 0.0; }
  int numSteps() const override { return int(ends_.size()); }
  bool endsNominalStep(const ddc::StepProposal&) const override { return true; }

 private:
  std::vector<double> ends_;
  double tolerance_;
  int corrections_, repeats_ = 0;
  size_t next_ = 0;
};

struct Case {
  double tolerance;
  int corrections;
};

class StepControlNoTrace : public testing::TestWithParam<Case> {};

TEST_P(StepControlNoTrace, AStepSentBackLeavesNoTrace) {
  const Case c = GetParam();
  auto deck = coarseHalfRings(c.tolerance, c.corrections);
  ddc::Analysis adaptive(worldComm(), *deck, ddc::ElementFactory::withBuiltins(), DDC_SOURCE_DIR "/examples");
  adaptive.run("");
  const auto& h = adaptive.history();
  int rejected = 0, repeated = 0;
  std::vector<double> ends;
  for (const auto& r : h) {
    rejected += r.rejections;
    repeated += r.corrections;
    ends.push_back(r.loadFactor);
    // The controller judged the indicator the row records: accepted steps
    // meet the tolerance or are at the minimum size (the first step halved
    // Max Bisections = 6 times).
    const double minimum = std::ldexp(0.1, -6);
    EXPECT_TRUE(r.geometryError <= c.tolerance || r.stepSize <= minimum * (1 + 1e-12))
        << "step " << r.step << ": indicator " << r.geometryError << " at size " << r.stepSize;
  }
  if (isRoot())
    std::printf("[step control] tolerance %g, %d corrections allowed: %zu steps, %d reduced, %d repeated\n",
                c.tolerance, c.corrections, h.size(), rejected, repeated);
  ASSERT_GT(rejected, 0) << "the case must send steps back smaller";
  if (c.corrections > 0) ASSERT_GT(repeated, 0) << "the case must repeat steps with their end's geometry";
  EXPECT_EQ(h.back().loadFactor, 1.0);

  // The accepted steps, taken directly (no step control), each repeated as
  // often as the adaptive run repeated it before accepting it.
  auto plain = coarseHalfRings(0.0, 0);
  ddc::Analysis direct(worldComm(), *plain, ddc::ElementFactory::withBuiltins(), DDC_SOURCE_DIR "/examples");
  direct.setStepController(std::make_unique<ScriptedSteps>(ends, c.tolerance, c.corrections));
  direct.run("");
  const auto& d = direct.history();
  ASSERT_EQ(d.size(), h.size());
  // On one rank the two runs make the same operations: bit for bit. On
  // more, the parallel direct solver's summation order varies from run to
  // run: to round-off of the peak energy.
  const bool oneRank = worldComm()->getSize() == 1;
  double peak = 0.0;
  for (const auto& r : h) peak = std::max(peak, r.strainEnergy);
  const double tol = oneRank ? 0.0 : kRoundoffOfRun * peak;
  for (size_t i = 0; i < h.size(); ++i) {
    EXPECT_EQ(d[i].loadFactor, h[i].loadFactor) << i;
    EXPECT_NEAR(d[i].strainEnergy, h[i].strainEnergy, tol) << "step " << h[i].step;
    EXPECT_EQ(d[i].activeContacts, h[i].activeContacts) << "step " << h[i].step;
    EXPECT_NEAR(d[i].geometryError, h[i].geometryError, oneRank ? 0.0 : kRoundoffOfRun) << "step " << h[i].step;
    EXPECT_EQ(d[i].rejections, 0);
    // The adaptive row counts also the repeats of the larger attempts it
    // reduced; the direct run makes only those of the accepted size.
    EXPECT_LE(d[i].corrections, h[i].corrections) << "step " << h[i].step;
  }
  // The final states, displacements and multipliers, bit for bit.
  auto diff = adaptive.model().createVector();
  diff->update(1.0, adaptive.displacement(), -1.0, direct.displacement(), 0.0);
  EXPECT_LE(diff->normInf(), oneRank ? 0.0 : kRoundoffOfRun * adaptive.displacement().normInf());
}

INSTANTIATE_TEST_SUITE_P(Verdicts, StepControlNoTrace,
                         testing::Values(Case{0.005, 0},   // reduced at once
                                         Case{0.002, 1}),  // repeated, then reduced
                         [](const testing::TestParamInfo<Case>& i) {
                           return i.param.corrections ? std::string("RepeatedThenReduced") : std::string("Reduced");
                         });

}  // namespace
