// Implicit dynamics with contact: the impact of two identical elastic bars
// (Hex8, E = ρ = 1, ν = 0, 1 x 1 x 10 each in 20 elements, speeds ±0.1 towards each other,
// touching at t = 0; Cirak & West 2005). The exact solution: a compression
// wave runs from the contact faces to the free ends and back, the contact
// force is ρ c v A = 0.1, the bars part at t = 2L/c = 20 with their
// velocities reversed and no strain left (doc/user-guide.md, "Contact in
// dynamics"). With the contact-surface mass redistributed (the default),
// checked for the conventional element under Monolithic and the decomposed
// element under Monolithic and FETI-DP (METIS, three subdomains: one bar
// cut, the contact faces in different subdomains; and one subdomain per
// bar, each floating: no prescribed displacement, no interface node), on 1,
// 2 and 3 ranks:
//  - the contact lasts 20 within 2 % (the release step brackets it);
//  - after separation each bar moves with its velocity reversed (momentum /
//    mass) within 2 %, and the total energy is within 1 % of the initial;
//  - the decomposed element makes one contact exchange per time step and
//    gives the same history under FETI-DP as under Monolithic;
//  - with the surface mass kept, the same run chatters: contact opens and
//    closes again and the energy grows (why redistribution is the default);
//  - a bar bouncing between two stiff clamped walls (three impacts, each
//    starting inside a time step) keeps its energy within 1 %; with the
//    surface mass kept it does not;
//  - bars that start overlapped are warned of at the start (the depth, the
//    deepest slave node, the pair) and after the first step (the energy it
//    gained beyond the external work); bars that start touching are not.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_AnalysisTestDecks.hpp"

namespace {

using PL = Teuchos::ParameterList;
using namespace ddc::test;

constexpr double kSpeed = 0.1;         ///< each bar's initial speed
constexpr double kContactTime = 20.0;  ///< 2 L / c
/// The issue's acceptance bounds (relative).
constexpr double kDurationTolerance = 0.02;
constexpr double kVelocityTolerance = 0.02;
constexpr double kEnergyTolerance = 0.01;
/// FETI-DP = Monolithic per step for the decomposed element (its dual
/// tolerance is 1e-10 relative).
constexpr double kFetiAgreement = 1e-6;

struct Case {
  const char* name;
  const char* formulation;
  const char* strategy;
  /// METIS (3 subdomains: one bar cut) or By Body (each bar a subdomain
  /// without an interface node: it floats, which its mass allows).
  const char* partition = "METIS";
};

PL barImpactDeck(const Case& c, double dt, double finalTime) {
  PL deck("DDContact");
  for (int b = 0; b < 2; ++b) {
    BoxSpec s;
    s.origin[0] = 10.0 * b;
    s.length[0] = 10.0;
    s.elements[0] = 20;
    s.elements[1] = s.elements[2] = 1;
    s.E = 1.0;
    s.nu = 0.0;
    addBox(deck, b == 0 ? "Left" : "Right", s).sublist("Element").sublist("Material").set("Density", 1.0);
    PL& v = deck.sublist("Dynamics").sublist("Initial Velocity").sublist(b == 0 ? "L" : "R");
    v.set("Set", std::string(b == 0 ? "Left" : "Right"));
    v.set("Velocity X", b == 0 ? kSpeed : -kSpeed);
  }
  deck.sublist("Contact").set("Formulation", std::string(c.formulation));
  PL& pair = deck.sublist("Contact").sublist("Pairs").sublist("Ends");
  pair.set("Slave", std::string("Left/right"));
  pair.set("Master", std::string("Right/left"));
  PL& dyn = deck.sublist("Dynamics");
  dyn.set("Integrator", std::string("Newmark"));
  dyn.set("Final Time", finalTime);
  dyn.set("Time Step", dt);
  deck.sublist("Solver").set("Strategy", std::string(c.strategy));
  deck.sublist("Partition").set("Method", std::string(c.partition));
  if (c.partition == std::string("METIS")) deck.sublist("Partition").set("Number of Subdomains", 3);
  deck.sublist("Output").set("Progress", false);
  deck.sublist("Output").set("VTK", false);
  return deck;
}

/// Mean x-velocity of a body: its x-momentum (M v) over its mass ρ V = 10.
double meanVelocity(const ddc::Analysis& a, const std::string& body) {
  const ddc::Model& m = a.model();
  auto Mv = m.createVector();
  m.applyMass(*a.velocity(), *Mv);
  const ddc::Body& b = m.mesh().body(m.mesh().bodyIndex(body));
  double p = 0.0;
  for (int n = b.firstNode; n < b.firstNode + b.numNodes; ++n)
    if (m.ownedMap()->isNodeGlobalElement(m.dof(n, 0))) p += Mv->getData()[m.ownedMap()->getLocalElement(m.dof(n, 0))];
  double sum = 0.0;
  Teuchos::reduceAll(*m.comm(), Teuchos::REDUCE_SUM, p, Teuchos::outArg(sum));
  return sum / 10.0;
}

class BarImpact : public testing::TestWithParam<Case> {};

TEST_P(BarImpact, LastsTwoLOverCAndReversesTheVelocities) {
  constexpr double dt = 0.25, T = 24.0;
  if (GetParam().partition == std::string("By Body") && worldComm()->getSize() > 2)
    GTEST_SKIP() << "two bodies make two subdomains, fewer than the ranks";
  PL deck = barImpactDeck(GetParam(), dt, T);
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const auto& h = a.history();
  ASSERT_EQ(h.size(), size_t(T / dt));
  // Contact from the first step to the release: one closed interval.
  ASSERT_GT(h.front().activeContacts, 0);
  size_t last = 0;
  for (size_t i = 0; i < h.size(); ++i)
    if (h[i].activeContacts > 0) last = i;
  for (size_t i = 0; i <= last; ++i) EXPECT_GT(h[i].activeContacts, 0) << "contact opened at t = " << h[i].loadFactor;
  // The release lies between the last step in contact and the next.
  const double release = h[last].loadFactor + 0.5 * dt;
  EXPECT_NEAR(release / kContactTime, 1.0, kDurationTolerance) << "last step in contact at t = " << h[last].loadFactor;
  // Mid-impact, the contact force is ρ c v A (the cross-section 1 x 1).
  const auto& mid = h[size_t(10.0 / dt) - 1];
  EXPECT_NEAR(-mid.contactForce[0] / kSpeed, 1.0, 0.05) << "contact force at t = 10: " << mid.contactForce[0];
  // After separation.
  const double vLeft = meanVelocity(a, "Left"), vRight = meanVelocity(a, "Right");
  EXPECT_NEAR(vLeft / -kSpeed, 1.0, kVelocityTolerance);
  EXPECT_NEAR(vRight / kSpeed, 1.0, kVelocityTolerance);
  const double E0 = kSpeed * kSpeed * 10.0;  // ½ m v² of each bar, m = 10
  const double E = h.back().strainEnergy + h.back().kineticEnergy;
  EXPECT_NEAR(E / E0, 1.0, kEnergyTolerance);
  if (GetParam().formulation == std::string("Decomposed Node-To-Segment"))
    for (const auto& r : h) EXPECT_EQ(r.contactExchanges, 1) << "step " << r.step;
  if (worldComm()->getRank() == 0)
    std::cout << "[bar impact] " << GetParam().name << ": release at t = " << release << ", velocities " << vLeft
              << " / " << vRight << ", energy " << E / E0 << " of the initial\n";
}

const Case kCases[] = {{"ConventionalMonolithic", "Node-To-Segment", "Monolithic"},
                       {"DecomposedMonolithic", "Decomposed Node-To-Segment", "Monolithic"},
                       {"DecomposedFetiDp", "Decomposed Node-To-Segment", "FETI-DP"},
                       {"DecomposedFetiDpFloating", "Decomposed Node-To-Segment", "FETI-DP", "By Body"}};
INSTANTIATE_TEST_SUITE_P(Formulations, BarImpact, testing::ValuesIn(kCases),
                         [](const testing::TestParamInfo<Case>& i) { return std::string(i.param.name); });

TEST(BarImpact, FetiDpEqualsMonolithicForTheDecomposedElement) {
  PL mono = barImpactDeck(kCases[1], 0.5, 12.0), feti = barImpactDeck(kCases[2], 0.5, 12.0);
  ddc::Analysis a(worldComm(), mono), b(worldComm(), feti);
  a.run("");
  b.run("");
  ASSERT_EQ(a.history().size(), b.history().size());
  for (size_t i = 0; i < a.history().size(); ++i) {
    const auto &x = a.history()[i], &y = b.history()[i];
    EXPECT_EQ(x.activeContacts, y.activeContacts);
    EXPECT_NEAR(y.strainEnergy, x.strainEnergy, kFetiAgreement * (x.strainEnergy + x.kineticEnergy));
    EXPECT_NEAR(y.kineticEnergy, x.kineticEnergy, kFetiAgreement * (x.strainEnergy + x.kineticEnergy));
    EXPECT_NEAR(y.contactForce[0], x.contactForce[0], kFetiAgreement * kSpeed);
  }
}

TEST(BarImpact, KeepingTheSurfaceMassChatters) {
  // The alternative: the same impact with the contact-surface nodes keeping
  // their mass. The trapezoidal rule then carries the velocity jump of the
  // surface nodes from step to step: contact opens and closes again, and the
  // energy grows (measured: 17 contact intervals and 5.8 times the initial
  // energy at 20 elements per bar, doc/user-guide.md).
  PL deck = barImpactDeck(kCases[1], 0.25, 24.0);
  deck.sublist("Dynamics").set("Contact Surface Mass", std::string("Kept"));
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const auto& h = a.history();
  int intervals = 0;
  for (size_t i = 0; i < h.size(); ++i)
    if (h[i].activeContacts > 0 && (i == 0 || h[i - 1].activeContacts == 0)) ++intervals;
  EXPECT_GT(intervals, 2);
  const double E0 = kSpeed * kSpeed * 10.0;
  EXPECT_GT((h.back().strainEnergy + h.back().kineticEnergy) / E0, 1.1);
}

/// A bar (as above, 20 Hex8) between two stiff walls (E = 1000, one Hex8
/// each, clamped on their far faces), gaps 0.53 on both sides, moving at
/// 0.1: impacts at t = 5.3, 35.3 and 65.3 (each inside a time step of
/// 0.25), each lasting 20.
PL bouncingBarDeck(const std::string& surfaceMass) {
  PL deck("DDContact");
  constexpr double gap = 0.53;
  const struct {
    const char* name;
    double origin, length, E;
    int elements;
  } bodies[] = {{"WallL", -1.0, 1.0, 1000.0, 1}, {"Bar", gap, 10.0, 1.0, 20}, {"WallR", 10.0 + 2 * gap, 1.0, 1000.0, 1}};
  for (const auto& b : bodies) {
    BoxSpec s;
    s.origin[0] = b.origin;
    s.length[0] = b.length;
    s.elements[0] = b.elements;
    s.elements[1] = s.elements[2] = 1;
    s.E = b.E;
    s.nu = 0.0;
    addBox(deck, b.name, s).sublist("Element").sublist("Material").set("Density", 1.0);
  }
  addDisplacement(deck, "HeldL", "WallL/left", "XYZ");
  addDisplacement(deck, "HeldR", "WallR/right", "XYZ");
  deck.sublist("Contact").set("Formulation", std::string("Decomposed Node-To-Segment"));
  PL& pairs = deck.sublist("Contact").sublist("Pairs");
  pairs.sublist("Left").set("Slave", std::string("Bar/left"));
  pairs.sublist("Left").set("Master", std::string("WallL/right"));
  pairs.sublist("Right").set("Slave", std::string("Bar/right"));
  pairs.sublist("Right").set("Master", std::string("WallR/left"));
  PL& dyn = deck.sublist("Dynamics");
  dyn.set("Integrator", std::string("Newmark"));
  dyn.set("Final Time", 90.0);
  dyn.set("Time Step", 0.25);
  dyn.set("Contact Surface Mass", surfaceMass);
  PL& v = dyn.sublist("Initial Velocity").sublist("Moving");
  v.set("Set", std::string("Bar"));
  v.set("Velocity X", kSpeed);
  deck.sublist("Solver").set("Strategy", std::string("Monolithic"));
  deck.sublist("Output").set("Progress", false);
  deck.sublist("Output").set("VTK", false);
  return deck;
}

/// Contact intervals of a run and its largest relative deviation from the
/// initial total energy E0 = ½ m v² = 0.05.
std::pair<int, double> impactsAndEnergyDrift(const std::vector<ddc::StepRecord>& h) {
  int intervals = 0;
  double drift = 0.0;
  for (size_t i = 0; i < h.size(); ++i) {
    if (h[i].activeContacts > 0 && (i == 0 || h[i - 1].activeContacts == 0)) ++intervals;
    drift = std::max(drift, std::abs((h[i].strainEnergy + h[i].kineticEnergy) / (0.5 * 10.0 * kSpeed * kSpeed) - 1.0));
  }
  return {intervals, drift};
}

TEST(BouncingBar, KeepsItsEnergyOverThreeImpacts) {
  PL deck = bouncingBarDeck("Redistributed");
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const auto [impacts, drift] = impactsAndEnergyDrift(a.history());
  EXPECT_EQ(impacts, 3);
  EXPECT_LT(drift, kEnergyTolerance);
  // The alternative, for comparison: the surface mass kept.
  PL kept = bouncingBarDeck("Kept");
  ddc::Analysis b(worldComm(), kept);
  b.run("");
  const auto [keptImpacts, keptDrift] = impactsAndEnergyDrift(b.history());
  EXPECT_GT(keptImpacts, 3);
  EXPECT_GT(keptDrift, 0.1);
  if (worldComm()->getRank() == 0)
    std::cout << "[bouncing bar] redistributed: " << impacts << " impacts, largest energy deviation " << drift
              << "; kept: " << keptImpacts << " contact intervals, " << keptDrift << "\n";
}

/// The notes (warnings) of a run.
class Notes : public ddc::StepObserver {
 public:
  void note(const ddc::StepLoop&, const std::string& line) override { lines.push_back(line); }
  std::vector<std::string> lines;
  /// The note containing `text`, or "".
  std::string with(const std::string& text) const {
    for (const auto& l : lines)
      if (l.find(text) != std::string::npos) return l;
    return "";
  }
};

TEST(BarImpact, AnInitialPenetrationIsWarnedOfWithTheEnergyItAdds) {
  for (const Case& c : {kCases[0], kCases[1]}) {
    for (const double overlap : {0.0, 0.01}) {
      SCOPED_TRACE(std::string(c.name) + ", overlap " + std::to_string(overlap));
      PL deck = barImpactDeck(c, 0.25, 0.5);
      deck.sublist("Mesh").sublist("Bodies").sublist("Right").sublist("Box").set("Origin X", 10.0 - overlap);
      ddc::Analysis a(worldComm(), deck);
      auto notes = std::make_shared<Notes>();
      a.addObserver(notes);
      a.run("");
      const std::string start = notes->with("the bodies start overlapped");
      const std::string energy = notes->with("the initial penetration");
      if (overlap == 0.0) {
        EXPECT_EQ(start, "") << "bars that touch do not penetrate";
        EXPECT_EQ(energy, "");
        continue;
      }
      EXPECT_NE(start.find("lies 0.01 behind its master surface"), std::string::npos) << start;
      EXPECT_NE(start.find("of contact pair 'Ends'"), std::string::npos) << start;
      // The energy the first step gained beyond the external work (none
      // here: nothing is prescribed), as the history shows it.
      const auto& r = a.history().front();
      const double initial = 2 * 0.5 * 10.0 * kSpeed * kSpeed;  // two bars of mass 10 at speed 0.1
      const double gained = r.kineticEnergy + r.strainEnergy - initial - r.externalWork;
      EXPECT_GT(gained, 0.0) << "pushing the bars apart adds energy";
      std::ostringstream expected;
      expected << "changed the total energy from " << initial << " to " << r.kineticEnergy + r.strainEnergy
               << " with external work " << r.externalWork << ": " << gained << " beyond it";
      EXPECT_NE(energy.find(expected.str()), std::string::npos) << energy << "\nexpected: " << expected.str();
    }
  }
}

}  // namespace
