// Contact verification (doc/verification.md rungs 2 and 5, doc/contact.md;
// Fang & Izzuddin 2022):
//   1. contact patch test: two flat blocks with non-matching meshes, a
//      uniform pressure on the upper block; the contact pressure on the
//      slave nodes is uniform and equals the applied pressure, for both
//      formulations (conventional and decomposed NTS): exactly on nested
//      meshes (5 under 10 segments), to the 1% target (doc/verification.md) on the interior
//      slave nodes of general ones (7 under 10);
//   2. force balance: a block pressed onto a rigidly supported block; the
//      resultant contact force equals the support reactions of either body;
//   3. active set: a pressed block stays in contact, a lifted block is
//      released (λ = 0 exactly, positive gap), a block lowered through an
//      initial gap is activated on penetration;
//   4. two half-rings (examples/two_half_rings.xml, 100 steps): frictionless
//      contact between hyperelastic bodies is conservative, so the strain
//      energy equals the external work; Newton converges superlinearly in
//      contact steps once the active set has settled;
//   5. Contact/Formulation = Decomposed Node-To-Segment without any pair is
//      a plain analysis (it once crashed);
//   6. the facing rule (doc/contact.md "Which slave nodes pair"): a pair of
//      the bottom and the top of one thin strip never pairs (it squashed the
//      strip), in both search paths alike;
//   7. a slave node that starts inside the master body where contact cannot
//      reach it is an input error naming the pair, the node and the depth;
//   8. duplicated and mirrored pairs are input errors naming both pairs,
//      compared by nodes and segments, not by side-set names.
//   9. inside Newton, a slave node on the free end of the master surface
//      keeps its segment against round-off displacements past the end.
//  10. contact input on every element type: pairs of Quad9 sides and of 3-D
//      faces are accepted with the automatic length scale h of their facets
//      (2-D Quad4: the mean segment length as before), overlapping 3-D pairs
//      are found by their faces, a node set is no contact surface, and the
//      Node-To-Surface formulation names are synonyms.
// Decks are in-memory Teuchos::ParameterLists (the half-rings deck is read
// from examples/). The measured numbers are printed on rank 0 for
// doc/verification.md.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_ContactParameters.hpp"
#include "DDC_ElementFactory.hpp"
#include "DDC_Error.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_Model.hpp"
#include "DDC_NodeToSegment.hpp"
#include "DDC_Partition.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using PL = Teuchos::ParameterList;
using Comm = Teuchos::RCP<const Teuchos::Comm<int>>;
using ddc::test::relDiff;
using namespace ddc::test;  // deck builders, communicators (DDC_AnalysisTestDecks.hpp)

// ---------------------------------------------------------------------------
// Named tolerances of this file (see also DDC_TestTolerances.hpp).

/// Contact patch test on nested non-matching meshes (5 master segments under
/// 10 slave segments: every master node is also a slave node position). The
/// node-to-segment transfer of the slave forces to the master nodes,
/// Σ_s λ_s N_i(ξ_s), is then the trapezoidal rule over the slave nodes of a
/// hat function whose kinks are all at slave nodes, hence exact: the
/// homogeneous state is the discrete solution and every slave pressure
/// equals the applied one up to Newton's tolerance and round-off (measured
/// <= 5e-14). A wrong normal, projection, tributary length or scatter gives
/// errors of percents.
constexpr double kPatchExact = 1e-9;

/// Contact patch test on general non-matching meshes (7 master segments
/// under 10 slave segments). The 1% target asks for every interior slave
/// pressure within 1% of the applied pressure; single-pass node-to-segment
/// contact CANNOT meet that on general non-matching meshes (Taylor &
/// Papadopoulos 1991; Zavarise & De Lorenzis 2009): the transfer above is no
/// longer exact when master nodes fall between slave nodes, so the master
/// surface is loaded non-uniformly. Measured 4.17% (NTS) and 4.18%
/// (decomposed), 9.7% for 14 under 20; the 1% target is reported as not met
/// (doc/contact.md). This bound is the measured element error with ~20%
/// margin, a regression guard: a wrong normal, projection or tributary
/// length gives tens of percent. Passing the 1% target needs a different
/// element (two-pass or the Zavarise–De Lorenzis modification).
constexpr double kNtsPatchError = 5e-2;

/// Force balance: |contact resultant − support reaction| relative to the
/// reaction. Both sums are over O(10) nodal forces; each free DOF's residual
/// is below Newton's 1e-8 · ||r_0|| (||r_0|| ~ the reaction, the consistent
/// predictor's first residual), so by Cauchy–Schwarz the sum over n ≈ 100
/// DOFs is below 1e-7 of the reaction (measured <= 5e-15, the last Newton
/// correction is quadratic). An element that drops a force component, or a
/// resultant evaluated with other normals than the ones in equilibrium, is
/// off by the normal's rotation in a step (~1e-5 .. 1e-3 here).
constexpr double kForceBalance = 1e-7;

/// Released pair: the gap of a rigidly lifted block equals the lift, up to
/// the Newton tolerance (the block carries no stress once released, so its
/// displacement is the prescribed one to round-off) — relative to the lift.
constexpr double kLiftGap = 1e-8;

/// Gap of an active pair at convergence, absolute (lengths are O(1), the
/// displacements O(0.05)). Conventional NTS enforces g_N = 0 in the current
/// configuration, to Newton's tolerance (measured ~1e-17).
constexpr double kNtsGap = 1e-10;

/// The decomposed element enforces the gap linearised on the frozen
/// projection ξ^p and normal n^p of the last converged configuration (paper
/// eq. 1); the true gap differs by (rotation of the master segment within the
/// step) x (slide of the slave along it): here ~5e-5 rad x 9e-3 ≈ 4e-7
/// (measured 4.3e-7 at the end node). A lost constraint penetrates by the
/// step's displacement, 2e-2.
constexpr double kDecomposedGap = 1e-5;

/// Activation: the final state does not depend on how the active set was
/// reached (all pairs active from the start, or activated by penetration),
/// since both converge to the solution of the same complementarity problem;
/// they differ by the Newton tolerance 1e-8 (relative residual) at most
/// (measured ~1e-15).
constexpr double kSameSolution = 1e-7;

/// Half-rings: max over steps |U − W_ext| relative to the peak strain
/// energy. Frictionless contact between hyperelastic bodies is conservative,
/// so U = W_ext in the exact solution; the discrete W_ext is a trapezoidal
/// rule in the load factor (O(Δλ²) per step) and the contact constraint is
/// enforced at the slave nodes only. Measured 0.13% with 100 steps; 1% is the
/// acceptance bound (doc/verification.md); a lost or spurious contact force shows up as several
/// percent.
constexpr double kEnergyBalance = 1e-2;

/// Newton in contact steps, once the active set has settled: with relative
/// residuals ρ_k = ||r_k|| / ||r_0||, each of the last (at most two)
/// decreasing iterations must satisfy ρ_{k+1} <= C ρ_k^p or be at the
/// round-off floor. p = 1.8 (quadratic convergence with a consistent
/// tangent, some slack for the pre-asymptotic phase) and C = 100: the
/// measured worst C is 11 (100 steps). A Newton method with an inconsistent
/// contact tangent converges linearly at the rates 0.2–0.4 seen in the
/// first iterations here, which fails ρ_{k+1} <= 100 ρ_k^1.8 for any
/// ρ_k < 1e-3.
constexpr double kSuperlinearOrder = 1.8;
constexpr double kSuperlinearConstant = 100.0;
/// Round-off floor of the relative residual: nodal forces of magnitude up
/// to ~10 ||r_0|| summed over ~1e3 DOFs, times machine epsilon, is ~1e-13
/// (measured final residuals down to 4e-14).
constexpr double kResidualFloor = 1e-12;
/// The last Newton correction of a contact step reduces the residual at
/// least 100-fold: measured >= 2458 over all contact steps; linear
/// convergence at the rates above gives 3 to 5.
constexpr double kLastContraction = 1e-2;

/// Two decks that give the same equations for the displacements (a Contact
/// sublist that adds no pair; a pair that never pairs, whose multipliers are
/// decoupled and restrained to 0): the same solution up to the round-off of
/// the linear solves. On one rank and without extra DOFs the runs are
/// bitwise equal; a 2-rank MUMPS solve is reproducible only to round-off
/// (two identical 2-rank runs differ by up to ~2e-14 relative, measured).
/// A contact force that acts at all changes the energy by orders of
/// magnitude more (the thin strip below: its elements invert).
constexpr double kSameModel = 1e-12;

// ---------------------------------------------------------------------------
// Helpers.


const char* const kNts = "Node-To-Segment";
const char* const kDecomposed = "Decomposed Node-To-Segment";

/// Two 1 x 0.5 blocks: "Lower" on [0,1] x [0,0.5] and "Upper" on
/// [0,1] x [0.5 + gap, 1 + gap], with different element counts along x so
/// the interface meshes do not match. Slave: Upper/bottom; master: Lower/top.
struct TwoBlocks {
  int nxLower = 7, nxUpper = 10, ny = 2;
  std::string material = "Neo-Hookean";
  double E = 1000.0, nu = 0.3;
  double gap = 0.0;
  std::string formulation = kNts;
  std::string initialState = "In Contact";
  int steps = 1;
};

void addBlock(PL& deck, const std::string& name, double y0, int nx, const TwoBlocks& s) {
  RectangleSpec r;
  r.originY = y0;
  r.lengthY = 0.5;
  r.nx = nx;
  r.ny = s.ny;
  r.material = s.material;
  r.E = s.E;
  r.nu = s.nu;
  addRectangle(deck, name, r);
}

/// The two blocks, the contact pair, quiet output. No supports or loads.
PL twoBlockDeck(const TwoBlocks& s) {
  PL deck("DDContact");
  addBlock(deck, "Lower", 0.0, s.nxLower, s);
  addBlock(deck, "Upper", 0.5 + s.gap, s.nxUpper, s);
  PL& c = deck.sublist("Contact");
  c.set("Formulation", s.formulation);
  c.set("Initial Contact State", s.initialState);
  PL& pair = c.sublist("Pairs").sublist("Interface");
  pair.set("Slave", std::string("Upper/bottom"));
  pair.set("Master", std::string("Lower/top"));
  setRunOptions(deck, s.steps);
  return deck;
}

/// Rollers: lower bottom fixed in y, both left sides fixed in x. The blocks
/// can expand laterally without restraint, so a uniform pressure on the top
/// gives a homogeneous state (σ_xx = 0, uniform σ_yy) in each block.
void addRollers(PL& deck) {
  addDisplacement(deck, "Lower bottom", "Lower/bottom", "Y");
  addDisplacement(deck, "Lower left", "Lower/left", "X");
  addDisplacement(deck, "Upper left", "Upper/left", "X");
}

/// Σ over the nodes of `set` of the internal force (= support reaction at
/// prescribed DOFs) at the converged state, component c; on every rank.
/// Only for sets off the contact surfaces: after run() the decomposed
/// element's frozen geometry is already the next step's, so contact
/// contributions re-assembled here would not be the converged ones.
double reaction(const ddc::Analysis& a, const std::string& set, int c) {
  const ddc::Model& m = a.model();
  auto fint = m.createVector();
  ddc::AssemblyRequest request;
  request.fint = fint.get();
  m.assemble(a.displacement(), a.history().back().loadFactor, request);
  const auto& map = *fint->getMap();
  auto f = fint->getData();
  double local = 0.0;
  for (int n : m.mesh().nodeSet(set)) {
    const auto l = map.getLocalElement(m.dof(n, c));
    if (l != Teuchos::OrdinalTraits<ddc::LO>::invalid()) local += f[l];
  }
  double sum = 0.0;
  Teuchos::reduceAll(*m.comm(), Teuchos::REDUCE_SUM, local, Teuchos::outArg(sum));
  return sum;
}

/// Slots whose slave node is not an end node of the slave surface (x = 0, 1).
std::vector<int> interiorSlots(const ddc::Model& m) {
  std::vector<int> k;
  const auto& slots = m.contactSlots();
  for (size_t i = 0; i < slots.size(); ++i) {
    const double x = m.mesh().coord(slots[i].slaveNode)[0];
    if (x > 1e-12 && x < 1.0 - 1e-12) k.push_back(static_cast<int>(i));
  }
  return k;
}

std::string formulationName(const testing::TestParamInfo<std::string>& info) {
  std::string n = info.param;
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

// ---------------------------------------------------------------------------
// 1. Contact patch test.

/// Upper block under a uniform dead pressure p on its top, both blocks on
/// rollers; the lower block has `nxLower` elements along the interface, the
/// upper (slave) block 10. Returns the analysis after `steps` load steps.
std::unique_ptr<ddc::Analysis> runPatch(const std::string& formulation, int nxLower, int steps, double p) {
  TwoBlocks s;
  s.formulation = formulation;
  s.nxLower = nxLower;
  s.steps = steps;
  PL deck = twoBlockDeck(s);
  addRollers(deck);
  PL& t = deck.sublist("Boundary Conditions").sublist("Pressure");
  t.set("Type", std::string("Traction"));
  t.set("Set", std::string("Upper/top"));
  t.set("Traction Y", -p);
  auto a = std::make_unique<ddc::Analysis>(worldComm(), deck);
  a->run("");
  return a;
}

/// max over `slots` of |p_k − p| / p, printing the pressures on rank 0.
double pressureDeviation(const ddc::Model& m, const std::vector<int>& slots, double p, const char* tag) {
  double pmin = 1e300, pmax = -1e300, worst = 0.0;
  for (int k : slots) {
    const double pk = m.contactSlots()[k].pressure();
    pmin = std::min(pmin, pk);
    pmax = std::max(pmax, pk);
    worst = std::max(worst, std::abs(pk - p) / p);
  }
  if (isRoot()) {
    std::printf("[patch] %s: pressure in [%.10f, %.10f], applied %.1f: spread (max-min)/p = %.2e, max |p_k - p|/p = "
                "%.2e; per slave node:",
                tag, pmin, pmax, p, (pmax - pmin) / p, worst);
    for (int k : slots) std::printf(" %.4f", m.contactSlots()[k].pressure());
    std::printf("\n");
  }
  return worst;
}

class ContactPatchTest : public testing::TestWithParam<std::string> {};

TEST_P(ContactPatchTest, NestedNonMatchingMeshesTransmitUniformPressureExactly) {
  const double p = 5.0;  // 0.5% strain with E = 1000
  for (int steps : {1, 2}) {
    auto a = runPatch(GetParam(), 5, steps, p);
    const ddc::Model& m = a->model();
    const auto& slots = m.contactSlots();
    ASSERT_EQ(slots.size(), 11u);
    std::vector<int> all;
    for (size_t k = 0; k < slots.size(); ++k) {
      EXPECT_TRUE(slots[k].active) << m.describeSlot(static_cast<int>(k));
      all.push_back(static_cast<int>(k));
    }
    const std::string tag = GetParam() + ", 5 under 10, " + std::to_string(steps) + " step(s), all slave nodes";
    const double worst = pressureDeviation(m, all, p, tag.c_str());
    EXPECT_LE(worst, kPatchExact);
  }
}

TEST_P(ContactPatchTest, GeneralNonMatchingMeshesTransmitUniformPressure) {
  const double p = 5.0;
  for (int steps : {1, 2}) {
    auto a = runPatch(GetParam(), 7, steps, p);
    const ddc::Model& m = a->model();
    ASSERT_EQ(m.contactSlots().size(), 11u);
    // The two end nodes of the slave surface sit on the free edges of both
    // blocks: excluded from the uniform-pressure check.
    const auto interior = interiorSlots(m);
    ASSERT_EQ(interior.size(), 9u);
    for (int k : interior) EXPECT_TRUE(m.contactSlots()[k].active) << m.describeSlot(k);
    const std::string tag = GetParam() + ", 7 under 10, " + std::to_string(steps) + " step(s), interior slave nodes";
    const double worst = pressureDeviation(m, interior, p, tag.c_str());
    // Equilibrium holds whatever the distribution: Σ p_k · (tributary) = p.
    double total = 0.0;
    for (const auto& sl : m.contactSlots()) total += sl.pressure() * sl.tributaryLength;
    EXPECT_LE(relDiff(total, p), kForceBalance);
    EXPECT_LE(worst, kNtsPatchError) << "single-pass NTS patch-test error (see kNtsPatchError)";
  }
}

INSTANTIATE_TEST_SUITE_P(Formulations, ContactPatchTest, testing::Values(kNts, kDecomposed), formulationName);

// ---------------------------------------------------------------------------
// 2. Force balance.

class ContactForceBalance : public testing::TestWithParam<std::string> {};

TEST_P(ContactForceBalance, ContactResultantEqualsSupportReactions) {
  // The lower block is fully fixed at its bottom (rigid support: a
  // non-uniform contact pressure), the upper block pressed down by 2%.
  TwoBlocks s;
  s.formulation = GetParam();
  s.steps = 2;
  PL deck = twoBlockDeck(s);
  addDisplacement(deck, "Lower bottom", "Lower/bottom", "XY");
  addDisplacement(deck, "Upper left", "Upper/left", "X");
  addDisplacement(deck, "Upper top", "Upper/top", "Y").set("Value Y", -0.02);
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const auto& rec = a.history().back();
  // The interior slave nodes at least; the upper block expands laterally
  // more than the lower one (fixed at its bottom), so its right end node may
  // slide off the master surface.
  ASSERT_GE(rec.activeContacts, 9);
  // Neither support touches a contact surface, so their reactions are
  // continuum forces only. The lower support pushes the lower block by the
  // contact force (the master feels −F_c); the top support holds the upper
  // block against it.
  const double bottomX = reaction(a, "Lower/bottom", 0);
  const double bottomY = reaction(a, "Lower/bottom", 1);
  const double topY = reaction(a, "Upper/top", 1);
  const double errY = std::max(relDiff(rec.contactForce[1], bottomY), relDiff(rec.contactForce[1], -topY));
  const double errX = std::abs(rec.contactForce[0] - bottomX) / std::abs(bottomY);
  if (isRoot())
    std::printf("[balance] %-26s %d active, contact force (%.10e, %.10e); reactions: lower bottom (%.10e, "
                "%.10e), upper top y %.10e; rel. error y %.2e, x %.2e (of the y force)\n",
                s.formulation.c_str(), rec.activeContacts, rec.contactForce[0], rec.contactForce[1], bottomX, bottomY,
                topY, errY, errX);
  EXPECT_GT(rec.contactForce[1], 0.0) << "the slave (upper) block is pushed up";
  EXPECT_LE(relDiff(bottomY, -topY), kForceBalance) << "the supports balance each other";
  EXPECT_LE(errY, kForceBalance);
  EXPECT_LE(errX, kForceBalance);
}

INSTANTIATE_TEST_SUITE_P(Formulations, ContactForceBalance, testing::Values(kNts, kDecomposed), formulationName);

// ---------------------------------------------------------------------------
// 3. Active set: pressing, lifting, activation through a gap.

class ContactActiveSet : public testing::TestWithParam<std::string> {};

TEST_P(ContactActiveSet, PressedBlockStaysInContactLiftedBlockIsReleased) {
  for (double dy : {-0.01, 0.01}) {
    TwoBlocks s;
    s.formulation = GetParam();
    PL deck = twoBlockDeck(s);
    addRollers(deck);
    addDisplacement(deck, "Upper top", "Upper/top", "Y").set("Value Y", dy);
    ddc::Analysis a(worldComm(), deck);
    a.run("");
    const ddc::Model& m = a.model();
    const auto& slots = m.contactSlots();
    const auto& rec = a.history().back();
    double lmin = 1e300, lmax = -1e300, gmin = 1e300, gmax = -1e300;
    for (size_t k = 0; k < slots.size(); ++k) {
      const auto& sl = slots[k];
      ASSERT_TRUE(sl.paired()) << m.describeSlot(k);
      lmin = std::min(lmin, sl.state.multiplier);
      lmax = std::max(lmax, sl.state.multiplier);
      gmin = std::min(gmin, sl.gap);
      gmax = std::max(gmax, sl.gap);
      if (dy < 0) {
        EXPECT_TRUE(sl.active) << m.describeSlot(k);
        EXPECT_LT(sl.state.multiplier, 0.0) << m.describeSlot(k) << ": compression has λ < 0";
      } else {
        EXPECT_FALSE(sl.active) << m.describeSlot(k);
        EXPECT_EQ(sl.state.multiplier, 0.0) << m.describeSlot(k) << ": a released multiplier is restrained to 0";
        EXPECT_LE(std::abs(sl.gap - dy) / dy, kLiftGap) << m.describeSlot(k) << ": gap " << sl.gap;
        EXPECT_EQ(sl.pressure(), 0.0);
      }
    }
    if (dy < 0) {
      EXPECT_EQ(rec.activeContacts, static_cast<int>(slots.size()));
    } else {
      EXPECT_EQ(rec.activeContacts, 0);
      EXPECT_EQ(rec.contactForce[0], 0.0);
      EXPECT_EQ(rec.contactForce[1], 0.0);
    }
    if (isRoot())
      std::printf("[active set] %-26s top dy = %+.2f: %d/%zu active, λ in [%.6e, %.6e], gap in [%.3e, %.3e], "
                  "Newton %d, residuals:",
                  s.formulation.c_str(), dy, rec.activeContacts, slots.size(), lmin, lmax, gmin, gmax,
                  rec.newtonIterations);
    if (isRoot()) {
      for (double r : rec.residualHistory) std::printf(" %.2e", r);
      std::printf("\n");
    }
  }
}

TEST_P(ContactActiveSet, BlockLoweredThroughGapIsActivatedOnPenetration) {
  // Upper block 0.02 above the lower one, lowered by 0.06 in 3 steps: the
  // first step closes the gap exactly (no contact can be active), the second
  // penetrates in its first iteration unless pairs are activated.
  auto run = [&](const std::string& initial) {
    TwoBlocks s;
    s.formulation = GetParam();
    s.gap = 0.02;
    s.steps = 3;
    s.initialState = initial;
    PL deck = twoBlockDeck(s);
    addRollers(deck);
    addDisplacement(deck, "Upper top", "Upper/top", "Y").set("Value Y", -0.06);
    auto a = std::make_unique<ddc::Analysis>(worldComm(), deck);
    a->run("");
    return a;
  };
  auto prev = run("Previous Step");
  const auto& h = prev->history();
  ASSERT_EQ(h.size(), 3u);
  const ddc::Model& m = prev->model();
  const auto& slots = m.contactSlots();
  EXPECT_EQ(h[0].activeContacts, 0) << "the first step only closes the gap";
  EXPECT_EQ(h[2].activeContacts, static_cast<int>(slots.size()));
  for (size_t k = 0; k < slots.size(); ++k) {
    EXPECT_TRUE(slots[k].active) << m.describeSlot(k);
    EXPECT_LT(slots[k].state.multiplier, 0.0) << m.describeSlot(k);
    const double tol = GetParam() == kNts ? kNtsGap : kDecomposedGap;
    EXPECT_LE(std::abs(slots[k].gap), tol) << m.describeSlot(k) << ": gap of an active pair";
  }
  auto inContact = run("In Contact");
  const double d = relDiff(h.back().contactForce[1], inContact->history().back().contactForce[1]);
  const double dU = relDiff(h.back().strainEnergy, inContact->history().back().strainEnergy);
  if (isRoot()) {
    std::printf("[activation] %-26s active per step:", GetParam().c_str());
    for (const auto& r : h) std::printf(" %d (Newton %d)", r.activeContacts, r.newtonIterations);
    std::printf("; final force %.10e vs %.10e (In Contact), rel. diff %.2e; energy rel. diff %.2e\n",
                h.back().contactForce[1], inContact->history().back().contactForce[1], d, dU);
  }
  EXPECT_LE(d, kSameSolution);
  EXPECT_LE(dU, kSameSolution);
}

INSTANTIATE_TEST_SUITE_P(Formulations, ContactActiveSet, testing::Values(kNts, kDecomposed), formulationName);

// ---------------------------------------------------------------------------
// 4. Two half-rings.

TEST(HalfRings, EnergyBalanceAndNewtonConvergence) {
  auto deck = Teuchos::getParametersFromXmlFile(std::string(DDC_SOURCE_DIR) + "/examples/two_half_rings.xml");
  // The conventional element, monolithic (the deck runs the paper's method).
  deck->sublist("Contact").set("Formulation", std::string("Node-To-Segment"));
  deck->sublist("Solver").set("Strategy", std::string("Monolithic"));
  deck->sublist("Load Stepping").set("Number of Steps", 100);
  deck->sublist("Output").set("Progress", false);
  deck->sublist("Output").set("VTK", false);
  deck->sublist("Newton").set("Print Iterations", false);
  ddc::Analysis a(worldComm(), *deck, ddc::ElementFactory::withBuiltins(), DDC_SOURCE_DIR "/examples");
  a.run("");
  const auto& h = a.history();
  double peak = 0.0, worst = 0.0;
  int worstStep = 0, contactSteps = 0;
  for (const auto& r : h) peak = std::max(peak, r.strainEnergy);
  for (const auto& r : h) {
    const double e = std::abs(r.strainEnergy - r.externalWork) / peak;
    if (e > worst) worst = e, worstStep = r.step;
    if (r.activeContacts > 0) ++contactSteps;
  }
  if (isRoot())
    std::printf("[half-rings] 100 steps: peak U = %.6e, max |U - W_ext| / peak U = %.3e (step %d); %d steps with "
                "contact\n",
                peak, worst, worstStep, contactSteps);
  EXPECT_GT(contactSteps, 50);
  EXPECT_LE(worst, kEnergyBalance);

  // Newton in contact steps: the tail of each residual sequence after the
  // last increase (an increase marks an active-set or pairing change).
  double worstC = 0.0, worstContraction = 0.0;
  int checked = 0, bisected = 0;
  const ddc::StepRecord* example = nullptr;
  for (const auto& r : h) {
    if (r.bisections > 0) ++bisected;
    if (r.activeContacts == 0) continue;
    const auto& res = r.residualHistory;
    ASSERT_GE(res.size(), 3u) << "step " << r.step;
    std::vector<double> rho;
    for (double x : res) rho.push_back(x / res.front());
    const int last = static_cast<int>(rho.size()) - 1;
    int tested = 0;
    for (int k = last; k >= 1 && tested < 2 && rho[k] < rho[k - 1]; --k, ++tested) {
      if (rho[k] > kResidualFloor) worstC = std::max(worstC, rho[k] / std::pow(rho[k - 1], kSuperlinearOrder));
      EXPECT_LE(rho[k], std::max(kSuperlinearConstant * std::pow(rho[k - 1], kSuperlinearOrder), kResidualFloor))
          << "step " << r.step << " (load factor " << r.loadFactor << "), iteration " << k
          << ": not superlinear; relative residuals end with " << rho[k - 1] << " -> " << rho[k];
    }
    EXPECT_GE(tested, 1) << "step " << r.step << ": the last Newton iteration did not reduce the residual";
    const double contraction = rho[last] / rho[last - 1];
    worstContraction = std::max(worstContraction, contraction);
    EXPECT_LE(contraction, kLastContraction) << "step " << r.step << " (load factor " << r.loadFactor << ")";
    ++checked;
    if (r.step == 50 && !example) example = &r;
  }
  if (isRoot()) {
    std::printf("[half-rings] Newton in %d contact (sub)steps: worst C in rho_k+1 <= C rho_k^%.1f = %.2f (bound %.0f), "
                "worst last contraction %.2e (bound %.0e); %d sub-steps after bisection\n",
                checked, kSuperlinearOrder, worstC, kSuperlinearConstant, worstContraction, kLastContraction, bisected);
    if (example) {
      std::printf("[half-rings] step %d (%d active pairs), ||r_k|| / ||r_0||:", example->step, example->activeContacts);
      for (double x : example->residualHistory) std::printf(" %.2e", x / example->residualHistory.front());
      std::printf("\n");
    }
  }
}

// ---------------------------------------------------------------------------
// 5. Decomposed formulation without contact pairs.

class DecomposedWithoutPairs : public testing::TestWithParam<std::string> {};

/// A 1 x 1 block (4 x 2 Quad4) fixed on the left, pulled on the right, with
/// Solver/Strategy `strategy` (FETI-DP: 4 subdomains, Belos to 1e-12), and,
/// if `contact`, a Contact sublist with the decomposed formulation and an
/// empty Pairs sublist.
PL pulledBlock(const std::string& strategy, bool contact) {
  PL deck("DDContact");
  RectangleSpec r;
  r.ny = 2;
  addRectangle(deck, "Block", r);
  addDisplacement(deck, "Fixed", "Block/left", "XY");
  addDisplacement(deck, "Pulled", "Block/right", "X").set("Value X", 0.1);
  setRunOptions(deck, 2);
  deck.sublist("Solver").set("Strategy", strategy);
  if (strategy == "FETI-DP") {
    deck.sublist("Partition").set("Number of Subdomains", 4);
    deck.sublist("Solver").sublist("FETI-DP").sublist("Belos").set("Convergence Tolerance", 1e-12);
  }
  if (contact) {
    PL& c = deck.sublist("Contact");
    c.set("Formulation", std::string(kDecomposed));
    c.sublist("Pairs");
  }
  return deck;
}

TEST_P(DecomposedWithoutPairs, RunsAsThePlainAnalysis) {
  PL withContact = pulledBlock(GetParam(), true), plain = pulledBlock(GetParam(), false);
  ddc::Analysis a(worldComm(), withContact), b(worldComm(), plain);
  a.run("");
  b.run("");
  EXPECT_FALSE(a.model().hasContact());
  EXPECT_FALSE(a.model().decomposedContact()) << "no pair: no decomposed contact, whatever the formulation";
  ASSERT_EQ(a.history().size(), b.history().size());
  for (size_t i = 0; i < a.history().size(); ++i) {
    const auto& x = a.history()[i];
    const auto& y = b.history()[i];
    EXPECT_EQ(x.activeContacts, 0);
    EXPECT_EQ(x.contactExchanges, 0);
    EXPECT_EQ(x.contactForce[0], 0.0);
    EXPECT_EQ(x.contactForce[1], 0.0);
    EXPECT_EQ(x.newtonIterations, y.newtonIterations);
    EXPECT_GT(x.strainEnergy, 0.0);
    EXPECT_LE(relDiff(x.strainEnergy, y.strainEnergy), kSameModel) << "step " << x.step;
  }
}

INSTANTIATE_TEST_SUITE_P(Strategies, DecomposedWithoutPairs, testing::Values("Monolithic", "FETI-DP"),
                         formulationName);

TEST(DecomposedWithoutPairs, ContactCallsOnAModelWithoutPairsDoNothing) {
  // A host code may drive the Model itself: the contact calls must not reach
  // for the multiplier and surface maps that only exist with pairs.
  auto mesh = std::make_shared<ddc::Mesh>();
  PL rect("Rectangle");
  rect.set("Elements X", 4);
  rect.set("Elements Y", 2);
  ddc::generateRectangle(*mesh, "Block", ddc::CellType::Quad4, rect, "Rectangle");
  PL el("Element");
  el.set("Type", std::string("Quad4"));
  el.sublist("Material").set("Type", std::string("Neo-Hookean"));
  std::vector<std::shared_ptr<const ddc::Element>> elements{
      ddc::ElementFactory::withBuiltins().create(el, "Element")};
  ddc::ContactOptions options;
  options.decomposed = true;  // and no pair
  ddc::Model m(worldComm(), mesh, elements, ddc::partitionMetis(*mesh, worldComm()->getSize()),
               ddc::BoundaryConditions{}, options);
  EXPECT_FALSE(m.hasContact());
  EXPECT_FALSE(m.decomposedContact());
  auto u = m.createVector();
  EXPECT_FALSE(m.updatePairing(*u, true, true));
  EXPECT_TRUE(m.updateActiveSet(*u).empty());
  EXPECT_TRUE(m.multiplierMap().is_null());
  EXPECT_EQ(m.ownedMap()->getGlobalNumElements(), static_cast<size_t>(2 * mesh->numNodes())) << "no multiplier DOF";
}

/// Two blocks of unit width and 2 rows of Quad4 (Neo-Hookean): "Lower" (y in
/// [0, 0.5], `nxLower` columns) under "Upper" (y in [0.5, 1], `nxUpper`
/// columns), and the contact pair "Interface" = Upper/bottom on Lower/top
/// (with a friction coefficient if `friction` > 0).
struct StackedBlocks {
  std::shared_ptr<ddc::Mesh> mesh;
  std::vector<std::shared_ptr<const ddc::Element>> elements;
  ddc::ContactOptions options;
};
StackedBlocks stackedBlocks(int nxLower, int nxUpper, double friction = 0.0) {
  auto mesh = std::make_shared<ddc::Mesh>();
  for (const auto& [name, y0, nx] :
       {std::tuple<const char*, double, int>{"Lower", 0.0, nxLower}, {"Upper", 0.5, nxUpper}}) {
    PL rect("Rectangle");
    rect.set("Origin Y", y0);
    rect.set("Length Y", 0.5);
    rect.set("Elements X", nx);
    rect.set("Elements Y", 2);
    ddc::generateRectangle(*mesh, name, ddc::CellType::Quad4, rect, "Rectangle");
  }
  PL el("Element");
  el.set("Type", std::string("Quad4"));
  el.sublist("Material").set("Type", std::string("Neo-Hookean"));
  std::vector<std::shared_ptr<const ddc::Element>> elements(
      2, ddc::ElementFactory::withBuiltins().create(el, "Element"));
  PL contact("Contact");
  PL& pair = contact.sublist("Pairs").sublist("Interface");
  pair.set("Slave", std::string("Upper/bottom"));
  pair.set("Master", std::string("Lower/top"));
  if (friction > 0.0) pair.set("Friction Coefficient", friction);
  return {mesh, elements, ddc::ContactOptions::fromParameters(contact, *mesh, "Contact")};
}

TEST(ContactPairing, SlaveOnTheFreeEndOfTheMasterKeepsItsSegmentAgainstRoundOff) {
  // Two blocks of one width: the slave end node (x = 1) sits on the free end
  // of the master surface. A displacement of round-off size past that end
  // must not unpair it inside Newton (it did, on two ranks under load, and
  // the active-set check reported a cycle with no pair changing state); a
  // real slide past the end, beyond the hysteresis, must.
  const auto [mesh, elements, options] = stackedBlocks(7, 10);
  auto factory = ddc::ElementFactory::withBuiltins();
  ddc::registerContactElements(factory);
  PL nts;
  nts.set("Type", std::string("Node-To-Segment"));
  auto ntsElement = std::dynamic_pointer_cast<const ddc::ContactElement>(factory.create(nts, "Contact/Formulation"));
  ASSERT_NE(ntsElement, nullptr);
  ddc::Model m(worldComm(), mesh, elements, ddc::partitionMetis(*mesh, worldComm()->getSize()),
               ddc::BoundaryConditions{}, options);
  auto u = m.createVector();
  m.updatePairing(*u, /*global=*/true, /*freeze=*/false);
  int end = -1;
  for (size_t k = 0; k < m.contactSlots().size(); ++k)
    if (m.mesh().coord(m.contactSlots()[k].slaveNode)[0] == 1.0) end = static_cast<int>(k);
  ASSERT_GE(end, 0);
  const int before0 = m.contactSlots()[end].master[0], before1 = m.contactSlots()[end].master[1];
  ASSERT_TRUE(m.contactSlots()[end].paired()) << m.describeSlot(end);
  auto slide = [&](double dx) {
    u->putScalar(0.0);
    const ddc::GO dof = m.dof(m.contactSlots()[end].slaveNode, 0);
    if (u->getMap()->isNodeGlobalElement(dof)) u->replaceGlobalValue(dof, dx);
    std::vector<int> repaired;
    const bool changed = m.updatePairing(*u, /*global=*/false, /*freeze=*/false, &repaired);
    EXPECT_EQ(changed, !repaired.empty());
    return changed;
  };
  constexpr double kRoundOff = 1e-14;  // a position error of a few ulp of the unit width
  EXPECT_FALSE(slide(kRoundOff)) << m.describeSlot(end);
  EXPECT_TRUE(m.contactSlots()[end].paired()) << m.describeSlot(end);
  EXPECT_EQ(m.contactSlots()[end].master[0], before0);
  EXPECT_EQ(m.contactSlots()[end].master[1], before1);
  constexpr double kPastTheEnd = 0.05;  // a third of a master segment (1/7)
  EXPECT_TRUE(slide(kPastTheEnd)) << m.describeSlot(end);
  EXPECT_FALSE(m.contactSlots()[end].paired()) << m.describeSlot(end);
}

TEST(ContactPairing, AGeometryTheContactUpdateCannotEvaluateFailsOnEveryRank) {
  // Inside Newton, an iterate far from the solution (a body sliding away in
  // gross slip) may collapse a master segment under an active frictional
  // slave node: its closest-point projection cannot converge. The active-set
  // update must raise that on every rank, as an inadmissible deformation
  // Newton fails the iteration on (and the step is bisected), not as an
  // error that escapes on the ranks that met it while the others wait.
  const auto [mesh, elements, options] = stackedBlocks(4, 4, /*friction=*/0.3);
  ddc::Model m(worldComm(), mesh, elements, ddc::partitionMetis(*mesh, worldComm()->getSize()),
               ddc::BoundaryConditions{}, options);
  auto u = m.createVector();
  m.updatePairing(*u, /*global=*/true, /*freeze=*/true);
  m.activateAllPaired();
  m.beginContactStep(*u);
  // Every slot in compression; the master segment of the slot at x = 0.5
  // collapsed onto its first node.
  int middle = -1;
  for (size_t k = 0; k < m.contactSlots().size(); ++k) {
    const ddc::ContactSlot& s = m.contactSlots()[k];
    ASSERT_TRUE(s.paired() && s.active) << m.describeSlot(int(k));
    if (m.mesh().coord(s.slaveNode)[0] == 0.5) middle = int(k);
    if (u->getMap()->isNodeGlobalElement(m.multiplierDof(int(k)))) u->replaceGlobalValue(m.multiplierDof(int(k)), -1.0);
  }
  ASSERT_GE(middle, 0);
  const ddc::ContactSlot& s = m.contactSlots()[middle];
  for (int c = 0; c < 2; ++c) {
    const ddc::GO dof = m.dof(s.master[1], c);
    const double collapse = m.mesh().coord(s.master[0])[c] - m.mesh().coord(s.master[1])[c];
    if (u->getMap()->isNodeGlobalElement(dof)) u->replaceGlobalValue(dof, collapse);
  }
  try {
    m.updateActiveSet(*u);
    ADD_FAILURE() << "no InadmissibleDeformation";
  } catch (const ddc::InadmissibleDeformation& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("closest-point projection did not converge")) << e.what();
  }
}

/// The message of the InputError that constructing an Analysis of `deck`
/// throws, or "(no InputError)".
std::string inputErrorOf(PL deck) {
  return ddc::test::inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
}

// ---------------------------------------------------------------------------
// 6. The facing rule.

/// A 4 x 0.25 strip of 12 x 1 Quad4 ("Strip"), x-fixed on the left and pinned
/// at its bottom-left corner, its right end loaded by a traction 0.1 down, and
/// the pair "Self" = Strip/bottom against Strip/top (if `selfPair`). With
/// `block`, a 1 x 0.5 block (4 x 2) on the strip's top at x in [1.5, 2.5],
/// pressed down by 0.01, x-fixed on its left, with the pair "Block" =
/// Block/bottom against Strip/top.
PL stripDeck(const std::string& formulation, bool selfPair, bool block, int steps) {
  PL deck("DDContact");
  RectangleSpec strip;
  strip.lengthX = 4.0;
  strip.lengthY = 0.25;
  strip.nx = 12;
  strip.ny = 1;
  addRectangle(deck, "Strip", strip);
  addDisplacement(deck, "Strip left", "Strip/left", "X");
  addDisplacement(deck, "Strip pin", "Strip/bottom left", "Y");
  addTraction(deck, "Tip", "Strip/right", 0.0, -0.1);
  PL& c = deck.sublist("Contact");
  c.set("Formulation", formulation);
  if (selfPair) {
    c.sublist("Pairs").sublist("Self").set("Slave", std::string("Strip/bottom"));
    c.sublist("Pairs").sublist("Self").set("Master", std::string("Strip/top"));
  }
  if (block) {
    RectangleSpec b;
    b.originX = 1.5;
    b.originY = 0.25;
    b.lengthY = 0.5;
    b.ny = 2;
    addRectangle(deck, "Block", b);
    addDisplacement(deck, "Block left", "Block/left", "X");
    addDisplacement(deck, "Block top", "Block/top", "Y").set("Value Y", -0.01);
    c.sublist("Pairs").sublist("Block").set("Slave", std::string("Block/bottom"));
    c.sublist("Pairs").sublist("Block").set("Master", std::string("Strip/top"));
  }
  setRunOptions(deck, steps);
  // FacingRuleRun compares the strip with an unpaired pair to the strip
  // alone within kSameModel: the same elimination order of their common
  // DOFs, which MUMPS' own choice (Auto) gives and METIS' nested dissection
  // (the monolithic default) does not (it reorders around the multiplier
  // rows; 3e-11 apart on this thin strip).
  deck.sublist("Solver").sublist("Linear Solver").sublist("MUMPS").set("Ordering", std::string("Auto"));
  return deck;
}

class FacingRuleRun : public testing::TestWithParam<std::string> {};

TEST_P(FacingRuleRun, ThinStripIsNotInContactWithItself) {
  // Every bottom node is within the search radius (1/3) of the top segment
  // across the strip, 0.25 behind it: without the facing rule all 13 were
  // paired and activated, the strip was squashed and Newton failed (det F < 0).
  PL withPair = stripDeck(GetParam(), true, false, 4), plain = stripDeck(GetParam(), false, false, 4);
  ddc::Analysis a(worldComm(), withPair), b(worldComm(), plain);
  a.run("");
  b.run("");
  ASSERT_EQ(a.model().contactSlots().size(), 13u);
  for (size_t k = 0; k < a.model().contactSlots().size(); ++k)
    EXPECT_FALSE(a.model().contactSlots()[k].paired()) << a.model().describeSlot(static_cast<int>(k));
  ASSERT_EQ(a.history().size(), b.history().size());
  for (size_t i = 0; i < a.history().size(); ++i) {
    const auto& x = a.history()[i];
    EXPECT_EQ(x.activeContacts, 0);
    EXPECT_EQ(x.contactForce[0], 0.0);
    EXPECT_EQ(x.contactForce[1], 0.0);
    EXPECT_LE(relDiff(x.strainEnergy, b.history()[i].strainEnergy), kSameModel) << "step " << x.step;
  }
  EXPECT_GT(a.history().back().strainEnergy, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Formulations, FacingRuleRun, testing::Values(kNts, kDecomposed), formulationName);

TEST(FacingRule, ASelfContactPairDoesNotSupportItsBody) {
  // Forces between two surfaces of one body are internal: a strip held only
  // by its self pair is unsupported (a singular matrix), reported as such.
  PL deck = stripDeck(kNts, true, false, 1);
  deck.sublist("Boundary Conditions").remove("Strip left");
  deck.sublist("Boundary Conditions").remove("Strip pin");
  const std::string msg = inputErrorOf(deck);
  EXPECT_NE(msg.find("body 'Strip' is not supported"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no contact pair joins it to another body"), std::string::npos) << msg;
}

TEST(FacingRule, BothSearchPathsPairTheSameSlaveNodes) {
  // The replicated search (conventional element) and the bounding-box
  // exchange with a search per rank (decomposed element; on 2 ranks the strip
  // is cut, so slave-surface neighbours come from the other rank) in the
  // reference configuration: the self pair never pairs, the block's slave
  // nodes all pair with the strip's top (touching, gap 0).
  PL conventional = stripDeck(kNts, true, true, 1), decomposed = stripDeck(kDecomposed, true, true, 1);
  ddc::Analysis nts(worldComm(), conventional), dec(worldComm(), decomposed);
  const auto& a = nts.model().contactSlots();
  const auto& b = dec.model().contactSlots();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), 13u + 5u);
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].paired(), a[k].pair == 1) << nts.model().describeSlot(static_cast<int>(k));
    EXPECT_EQ(a[k].paired(), b[k].paired()) << dec.model().describeSlot(static_cast<int>(k));
    EXPECT_EQ(a[k].master[0], b[k].master[0]);
    EXPECT_EQ(a[k].master[1], b[k].master[1]);
    EXPECT_EQ(a[k].gap, b[k].gap);
  }
}

// ---------------------------------------------------------------------------
// 7. Slave nodes that start inside the master body.


/// Two blocks (3 master segments of 1/3 under 4 slave segments, element
/// depth 0.25, search radius 1/3), the upper one starting `overlap` inside
/// the lower one, on rollers and pressed by 0.01.
PL overlappingBlocks(const std::string& formulation, double overlap) {
  TwoBlocks s;
  s.nxLower = 3;
  s.nxUpper = 4;
  s.formulation = formulation;
  s.gap = -overlap;
  PL deck = twoBlockDeck(s);
  addRollers(deck);
  addDisplacement(deck, "Upper top", "Upper/top", "Y").set("Value Y", -0.01);
  return deck;
}

class InitialPenetration : public testing::TestWithParam<std::string> {};

TEST_P(InitialPenetration, TooDeepForTheFacingRuleIsAnInputError) {
  // 0.2 behind Lower/top: within the radius, but not less than ½ · 0.25.
  const std::string msg = inputErrorOf(overlappingBlocks(GetParam(), 0.2));
  EXPECT_NE(msg.find("contact pair 'Contact/Pairs/Interface': slave node "), std::string::npos) << msg;
  EXPECT_NE(msg.find(" at (0.25, 0.3) of the slave side set 'Upper/bottom' starts inside the master body"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("at depth 0.2 below the master side set 'Lower/top'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not less than half the depth of that segment's element (0.125 = 0.5 x 0.25)"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("2 more slave node(s)"), std::string::npos) << msg << ": the interior slave nodes x = 0.5, 0.75";
}

TEST_P(InitialPenetration, BeyondTheSearchRadiusIsAnInputError) {
  const std::string msg = inputErrorOf(overlappingBlocks(GetParam(), 0.4));
  EXPECT_NE(msg.find(" at (0.25, 0.1) of the slave side set 'Upper/bottom' starts inside the master body"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("at depth 0.4 below"), std::string::npos) << msg;
  EXPECT_NE(msg.find("farther than the search radius (0.333333"), std::string::npos) << msg;
}

TEST_P(InitialPenetration, OnAMeshLineOfTheMasterBodyIsInside) {
  // 0.25 deep: the slave nodes lie exactly on the line between the lower
  // block's two element rows (no element's interior holds them).
  const std::string msg = inputErrorOf(overlappingBlocks(GetParam(), 0.25));
  EXPECT_NE(msg.find("at (0.25, 0.25) of the slave side set 'Upper/bottom' starts inside the master body"),
            std::string::npos)
      << msg;
}

TEST_P(InitialPenetration, ShallowOverlapIsPushedOut) {
  // 0.05 < ½ · 0.25: paired, activated, and the contact pushes the upper
  // block out (every slave node in contact, a compressive force).
  PL deck = overlappingBlocks(GetParam(), 0.05);
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const auto& rec = a.history().back();
  EXPECT_EQ(rec.activeContacts, 5);
  EXPECT_GT(rec.contactForce[1], 0.0);
}

TEST_P(InitialPenetration, SlaveSurfaceFacingAwayInsideIsAnInputError) {
  // The whole upper block starts inside the lower one (y in [-0.2, 0.3]
  // inside [0, 0.5]) and its top is the slave surface: 0.2 below Lower/top,
  // its normal +y like the master's.
  TwoBlocks s;
  s.nxLower = 3;
  s.nxUpper = 4;
  s.formulation = GetParam();
  s.gap = -0.7;
  PL deck = twoBlockDeck(s);
  deck.sublist("Contact").sublist("Pairs").sublist("Interface").set("Slave", std::string("Upper/top"));
  addRollers(deck);
  const std::string msg = inputErrorOf(deck);
  EXPECT_NE(msg.find("of the slave side set 'Upper/top' starts inside the master body"), std::string::npos) << msg;
  EXPECT_NE(msg.find("its outward normal (0, 1) does not face the outward normal (0, 1)"), std::string::npos) << msg;
}

INSTANTIATE_TEST_SUITE_P(Formulations, InitialPenetration, testing::Values(kNts, kDecomposed), formulationName);

// ---------------------------------------------------------------------------
// 8. Pairs that overlap.

/// Two blocks ("Lower" 3 x 2, "Upper" 4 x 2 Quad4 on top of it) with extra
/// side sets under other names over the same sides: "Upper/contact" =
/// Upper/bottom, "Lower/contact" = Lower/top, and "Upper/bottom half" = the
/// first two segments of Upper/bottom.
std::shared_ptr<ddc::Mesh> blocksWithRenamedSets() {
  auto m = std::make_shared<ddc::Mesh>();
  for (const auto& [name, y0, nx] : {std::tuple<const char*, double, int>{"Lower", 0.0, 3}, {"Upper", 0.5, 4}}) {
    PL r("Rectangle");
    r.set("Origin Y", y0);
    r.set("Length Y", 0.5);
    r.set("Elements X", nx);
    r.set("Elements Y", 2);
    ddc::generateRectangle(*m, name, ddc::CellType::Quad4, r, "R");
  }
  const int lower = m->bodyIndex("Lower"), upper = m->bodyIndex("Upper");
  m->addSideSet(upper, "contact", m->sideSet("Upper/bottom"));
  m->addSideSet(lower, "contact", m->sideSet("Lower/top"));
  auto half = m->sideSet("Upper/bottom");
  std::sort(half.begin(), half.end(), [&](const ddc::Segment& a, const ddc::Segment& b) {
    return m->coord(a.nodes[0])[0] + m->coord(a.nodes[1])[0] < m->coord(b.nodes[0])[0] + m->coord(b.nodes[1])[0];
  });
  half.resize(2);
  m->addSideSet(upper, "bottom half", half);
  return m;
}

/// ContactOptions::fromParameters on those blocks with the pairs
/// {name, slave, master}: the InputError's message, or "(no InputError)".
std::string pairsError(const std::vector<std::array<std::string, 3>>& pairs) {
  const auto mesh = blocksWithRenamedSets();
  PL c("Contact");
  for (const auto& p : pairs) {
    c.sublist("Pairs").sublist(p[0]).set("Slave", p[1]);
    c.sublist("Pairs").sublist(p[0]).set("Master", p[2]);
  }
  return ddc::test::inputErrorOf([&] { ddc::ContactOptions::fromParameters(c, *mesh, "Contact"); });
}

TEST(OverlappingPairs, DuplicatedPairsAreInputErrorsWhateverTheSetNames) {
  for (const auto& second : std::vector<std::array<std::string, 3>>{
           {"B", "Upper/bottom", "Lower/top"},        // the same pair twice
           {"B", "Upper/contact", "Lower/contact"},   // the same surfaces under other names
           {"B", "Upper/bottom half", "Lower/top"},   // a part of the slave surface
           {"B", "Upper/left", "Lower/top"}}) {       // only the corner node shared
    const std::string msg = pairsError({{"A", "Upper/bottom", "Lower/top"}, second});
    EXPECT_NE(msg.find("contact pairs 'Contact/Pairs/A' and 'Contact/Pairs/B' duplicate each other: slave node "),
              std::string::npos)
        << second[1] << " / " << second[2] << ": " << msg;
    EXPECT_NE(msg.find("' and '" + second[1] + "')"), std::string::npos) << msg;
  }
}

TEST(OverlappingPairs, MirroredPairsAreInputErrorsWhateverTheSetNames) {
  for (const auto& second : std::vector<std::array<std::string, 3>>{{"B", "Lower/top", "Upper/bottom"},
                                                                    {"B", "Lower/contact", "Upper/contact"},
                                                                    {"B", "Lower/top", "Upper/bottom half"}}) {
    const std::string msg = pairsError({{"A", "Upper/bottom", "Lower/top"}, second});
    EXPECT_NE(msg.find("contact pairs 'Contact/Pairs/A' and 'Contact/Pairs/B' mirror each other: the slave surface of "
                       "the first ('Upper/bottom') and the master surface of the second ('" +
                       second[2] + "') share the segment of nodes "),
              std::string::npos)
        << second[1] << " / " << second[2] << ": " << msg;
  }
}

TEST(OverlappingPairs, PairsThatShareOnlyOneSideAreAccepted) {
  // One slave surface against two master surfaces without a common segment,
  // two slave surfaces against one master without a common slave node, and
  // a chain (the second pair's slave is the first pair's master body, but
  // another side of it): all legitimate.
  EXPECT_EQ(pairsError({{"A", "Upper/bottom", "Lower/top"}, {"B", "Upper/bottom", "Lower/right"}}),
            ddc::test::kNoInputError);
  EXPECT_EQ(pairsError({{"A", "Upper/bottom", "Lower/top"}, {"B", "Upper/right", "Lower/right"}}),
            ddc::test::kNoInputError);
  EXPECT_EQ(pairsError({{"A", "Upper/bottom", "Lower/top"}, {"B", "Lower/right", "Upper/right"}}),
            ddc::test::kNoInputError);
}

// ---------------------------------------------------------------------------
// 10. Contact input on every element type.

/// Two blocks of `type`, "Lower" under "Upper", each 1.5 wide (3 elements) and
/// 1 high (2 elements), in 3-D 2 deep (2 elements): Lower/top faces are
/// 0.5 x 1.0.
std::shared_ptr<ddc::Mesh> stackedBlocks(ddc::CellType type) {
  auto m = std::make_shared<ddc::Mesh>();
  const bool is3d = ddc::cellDimension(type) == 3;
  for (const auto& [name, y0] : {std::pair<const char*, double>{"Lower", 0.0}, {"Upper", 1.0}}) {
    PL p(is3d ? "Box" : "Rectangle");
    p.set("Origin Y", y0);
    p.set("Length X", 1.5);
    p.set("Elements X", 3);
    p.set("Elements Y", 2);
    if (is3d) {
      p.set("Length Z", 2.0);
      p.set("Elements Z", 2);
      ddc::generateBox(*m, name, type, p, "Box");
    } else {
      ddc::generateRectangle(*m, name, type, p, "Rectangle");
    }
  }
  return m;
}

/// A "Contact" list with the pairs {name, slave, master}.
PL contactList(const std::vector<std::array<std::string, 3>>& pairs) {
  PL c("Contact");
  for (const auto& p : pairs) {
    c.sublist("Pairs").sublist(p[0]).set("Slave", p[1]);
    c.sublist("Pairs").sublist(p[0]).set("Master", p[2]);
  }
  return c;
}

TEST(ContactInput, FacesOf3dBodiesArePairsWithTheSquareRootOfTheFaceAreaAsLengthScale) {
  // Hexahedron faces 0.5 x 1.0; a Kuhn tetrahedron face is half of that.
  for (const auto& [type, area] : std::vector<std::pair<ddc::CellType, double>>{{ddc::CellType::Hex8, 0.5},
                                                                                {ddc::CellType::Hex20, 0.5},
                                                                                {ddc::CellType::Hex27, 0.5},
                                                                                {ddc::CellType::Tet4, 0.25},
                                                                                {ddc::CellType::Tet10, 0.25}}) {
    const auto mesh = stackedBlocks(type);
    PL c = contactList({{"Interface", "Upper/bottom", "Lower/top"}});
    c.set("Penetration Tolerance", 1e-3);
    const auto o = ddc::ContactOptions::fromParameters(c, *mesh, "Contact");
    ASSERT_EQ(o.pairs.size(), 1u);
    EXPECT_NEAR(o.searchRadius, std::sqrt(area), kRoundoff) << ddc::cellTypeName(type);
    EXPECT_NEAR(o.penetrationTolerance, 1e-3 * std::sqrt(area), kRoundoff) << ddc::cellTypeName(type);
  }
}

TEST(ContactInput, Quad9SidesArePairsWithTheChordLengthAsLengthScale) {
  const auto mesh = stackedBlocks(ddc::CellType::Quad9);
  PL c = contactList({{"Interface", "Upper/bottom", "Lower/top"}});
  const auto o = ddc::ContactOptions::fromParameters(c, *mesh, "Contact");
  EXPECT_NEAR(o.searchRadius, 0.5, kRoundoff);
  EXPECT_NEAR(o.penetrationTolerance, 1e-6 * 0.5, kRoundoff);
}

TEST(ContactInput, Quad4LengthScaleIsTheMeanMasterSegmentLengthBitForBit) {
  // A distorted master body: segments of different lengths. The arithmetic
  // of the 2-D code: the sum of hypot(dx, dy) over the segments, divided by
  // their number.
  auto mesh = std::make_shared<ddc::Mesh>();
  for (const auto& [name, y0, nx] : {std::tuple<const char*, double, int>{"Lower", 0.0, 5}, {"Upper", 1.0, 4}}) {
    PL p("Rectangle");
    p.set("Origin Y", y0);
    p.set("Elements X", nx);
    p.set("Elements Y", 3);
    p.set("Distortion", 0.3);
    ddc::generateRectangle(*mesh, name, ddc::CellType::Quad4, p, "Rectangle");
  }
  PL c = contactList({{"A", "Upper/bottom", "Lower/top"}, {"B", "Lower/right", "Upper/right"}});
  const auto o = ddc::ContactOptions::fromParameters(c, *mesh, "Contact");
  double sum = 0.0;
  int n = 0;
  for (const char* set : {"Lower/top", "Upper/right"})
    for (const ddc::Segment& s : mesh->sideSet(set)) {
      const auto& a = mesh->coord(s.nodes[0]);
      const auto& b = mesh->coord(s.nodes[1]);
      sum += std::hypot(b[0] - a[0], b[1] - a[1]);
      ++n;
    }
  EXPECT_EQ(o.searchRadius, sum / n);
  EXPECT_EQ(o.penetrationTolerance, 1e-6 * (sum / n));
}

TEST(ContactInput, OverlappingPairsOf3dFacesAreInputErrors) {
  for (ddc::CellType type : {ddc::CellType::Hex20, ddc::CellType::Tet4}) {
    const auto mesh = stackedBlocks(type);
    auto error = [&](const std::vector<std::array<std::string, 3>>& pairs) {
      PL c = contactList(pairs);
      return ddc::test::inputErrorOf([&] { ddc::ContactOptions::fromParameters(c, *mesh, "Contact"); });
    };
    const std::string duplicated =
        error({{"A", "Upper/bottom", "Lower/top"}, {"B", "Upper/left", "Lower/top"}});  // a shared edge of slaves
    EXPECT_NE(duplicated.find("contact pairs 'Contact/Pairs/A' and 'Contact/Pairs/B' duplicate each other: slave "
                              "node "),
              std::string::npos)
        << duplicated;
    EXPECT_NE(duplicated.find("share the facet of nodes "), std::string::npos) << duplicated;
    EXPECT_NE(duplicated.find("share no facet: remove the duplicated pair"), std::string::npos) << duplicated;
    const std::string mirrored = error({{"A", "Upper/bottom", "Lower/top"}, {"B", "Lower/top", "Upper/bottom"}});
    EXPECT_NE(mirrored.find("mirror each other: the slave surface of the first ('Upper/bottom') and the master "
                            "surface of the second ('Upper/bottom') share the facet of nodes "),
              std::string::npos)
        << mirrored;
    EXPECT_NE(mirrored.find("(two-pass node-to-surface)"), std::string::npos) << mirrored;
    // The sorted corner nodes of the first common face (the smallest key)
    // and the coordinates of its first corner, with z.
    std::vector<int> key;
    for (const ddc::Segment& f : mesh->sideSet("Upper/bottom")) {
      const int corners = ddc::referenceCell(ddc::referenceCell(type).facets[f.localSide].type).numCorners;
      std::vector<int> k(f.nodes.begin(), f.nodes.begin() + corners);
      std::sort(k.begin(), k.end());
      if (key.empty() || k < key) key = k;
    }
    std::ostringstream text;
    text << "facet of nodes " << key[0];
    for (std::size_t i = 1; i < key.size(); ++i) text << "-" << key[i];
    const auto& x = mesh->coord(key[0]);
    text << " at (" << x[0] << ", " << x[1] << ", " << x[2] << ")";
    EXPECT_NE(mirrored.find(text.str()), std::string::npos) << text.str() << " not in: " << mirrored;
    // Other faces of the same bodies are legitimate second pairs.
    EXPECT_EQ(error({{"A", "Upper/bottom", "Lower/top"}, {"B", "Upper/front", "Lower/front"}}),
              ddc::test::kNoInputError);
  }
}

TEST(ContactInput, ANodeSetIsNoContactSurface) {
  for (ddc::CellType type : {ddc::CellType::Quad4, ddc::CellType::Hex8}) {
    const auto mesh = stackedBlocks(type);
    const std::string corner = type == ddc::CellType::Quad4 ? "Lower/top right" : "Lower/top right front";
    for (const auto& [pair, key, set] : {std::tuple<std::array<std::string, 3>, std::string, std::string>{
                                             {"Interface", "Upper/all", "Lower/top"}, "Slave", "Upper/all"},
                                         {{"Interface", "Upper/bottom", corner}, "Master", corner}}) {
      PL c = contactList({pair});
      const std::string msg =
          ddc::test::inputErrorOf([&] { ddc::ContactOptions::fromParameters(c, *mesh, "Contact"); });
      EXPECT_NE(msg.find("contact pair 'Contact/Pairs/Interface/" + key + "': '" + set +
                         "' is a node set, not a side set; a contact surface must be a side set of " +
                         (type == ddc::CellType::Quad4 ? "element sides" : "element faces")),
                std::string::npos)
          << msg;
    }
  }
}

TEST(ContactInput, NodeToSurfaceNamesAreSynonymsOfNodeToSegment) {
  const auto mesh = stackedBlocks(ddc::CellType::Hex8);
  for (const auto& [formulation, decomposed] :
       std::vector<std::pair<std::string, bool>>{{"Node-To-Segment", false},
                                                 {"Decomposed Node-To-Segment", true},
                                                 {"Node-To-Surface", false},
                                                 {"Decomposed Node-To-Surface", true}}) {
    PL c = contactList({{"Interface", "Upper/bottom", "Lower/top"}});
    c.set("Formulation", formulation);
    EXPECT_EQ(ddc::ContactOptions::fromParameters(c, *mesh, "Contact").decomposed, decomposed) << formulation;
  }
  EXPECT_EQ(ddc::ContactOptions::getValidParameters()->get<std::string>("Formulation"), "Node-To-Segment");
}

}  // namespace
