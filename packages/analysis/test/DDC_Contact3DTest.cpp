// Node-to-surface contact in 3-D through the whole analysis (doc/contact.md,
// "Curved facets and 3-D"): the contact patch test between two stacked blocks
// of Hex8 (Quad4 contact facets) under a uniform pressure, with both
// formulations. The upper block is held by contact alone, which FETI-DP does
// not allow (a floating subdomain problem); the plane-strain consistency with
// 2-D and FETI-DP = Monolithic on the 3-D half-rings are ctests
// (test/CMakeLists.txt).
#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_Model.hpp"

namespace {

using namespace ddc::test;

/// Nested meshes (every master node on a slave node): single-pass NTS
/// transmits a uniform pressure exactly, up to round-off of the solve.
constexpr double kPatchExact = 1e-9;
/// General non-matching meshes: single-pass NTS loads the master nodes with
/// λ N_i(ξ), not consistently (doc/contact.md, "Verification"); measured
/// 7.9 % at the interior slave nodes with 3 x 3 master under 4 x 4 slave
/// facets (2-D: 4.2 %, 7 under 10 segments). A regression guard, not a target.
constexpr double kNtsPatchError3D = 1e-1;
/// The contact resultant on the slave body equals the applied load by
/// equilibrium, whatever the distribution.
constexpr double kForceBalance = 1e-7;

struct Case {
  std::string formulation;
};

std::string caseName(const testing::TestParamInfo<Case>& info) {
  std::string n = info.param.formulation;
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

/// Two stacked 1 x 0.5 x 1 blocks (y up), `nLower` x `nLower` master facets
/// under 4 x 4 slave facets, on rollers (Lower/bottom in y, the left faces in
/// x, the back faces in z), a uniform dead pressure p on Upper/top.
std::unique_ptr<ddc::Analysis> runPatch(const Case& c, int nLower, double p) {
  PL deck("DDContact");
  for (const auto& [name, y0, n] : {std::make_tuple("Lower", 0.0, nLower), std::make_tuple("Upper", 0.5, 4)}) {
    BoxSpec b;
    b.origin[1] = y0;
    b.length[1] = 0.5;
    b.elements[0] = b.elements[2] = n;
    b.elements[1] = 2;
    b.material = "Neo-Hookean";
    addBox(deck, name, b);
  }
  addDisplacement(deck, "Lower bottom", "Lower/bottom", "Y");
  for (const char* body : {"Lower", "Upper"}) {
    addDisplacement(deck, std::string(body) + " left", std::string(body) + "/left", "X");
    addDisplacement(deck, std::string(body) + " back", std::string(body) + "/back", "Z");
  }
  addTraction3(deck, "Pressure", "Upper/top", {0.0, -p, 0.0});
  PL& contact = deck.sublist("Contact");
  contact.set("Formulation", c.formulation);
  PL& pair = contact.sublist("Pairs").sublist("Interface");
  pair.set("Slave", std::string("Upper/bottom"));
  pair.set("Master", std::string("Lower/top"));
  deck.sublist("Solver").set("Strategy", std::string("Monolithic"));
  setRunOptions(deck, 2);
  auto a = std::make_unique<ddc::Analysis>(worldComm(), deck);
  a->run("");
  return a;
}

/// max over the slots whose slave node satisfies `use` of |p_k − p| / p.
template <class Use>
double pressureDeviation(const ddc::Model& m, double p, const char* tag, Use use) {
  double worst = 0.0, pmin = 1e300, pmax = -1e300;
  int n = 0;
  for (const auto& sl : m.contactSlots()) {
    if (!use(m.mesh().coord(sl.slaveNode))) continue;
    EXPECT_TRUE(sl.active) << "slave node " << sl.slaveNode;
    pmin = std::min(pmin, sl.pressure());
    pmax = std::max(pmax, sl.pressure());
    worst = std::max(worst, std::abs(sl.pressure() - p) / p);
    ++n;
  }
  if (isRoot())
    std::printf("[patch 3-D] %s: %d slave nodes, pressure in [%.10f, %.10f], applied %.1f: max |p_k - p|/p = %.2e\n",
                tag, n, pmin, pmax, p, worst);
  return worst;
}

class Contact3DPatch : public testing::TestWithParam<Case> {};

TEST_P(Contact3DPatch, NestedNonMatchingMeshesTransmitUniformPressureExactly) {
  const double p = 5.0;  // 0.5 % strain with E = 1000
  auto a = runPatch(GetParam(), 2, p);
  const ddc::Model& m = a->model();
  ASSERT_EQ(m.contactSlots().size(), 25u) << "5 x 5 slave nodes";
  const std::string tag = GetParam().formulation + ", 2x2 under 4x4, all slave nodes";
  EXPECT_LE(pressureDeviation(m, p, tag.c_str(), [](const std::array<double, 3>&) { return true; }), kPatchExact);
  // The resultant on the slave body is the applied load (area 1).
  const auto& rec = a->history().back();
  EXPECT_NEAR(rec.contactForce[1], p, kForceBalance * p);
  EXPECT_NEAR(rec.contactForce[0], 0.0, kForceBalance * p);
  EXPECT_NEAR(rec.contactForce[2], 0.0, kForceBalance * p);
}

TEST_P(Contact3DPatch, GeneralNonMatchingMeshesTransmitUniformPressure) {
  const double p = 5.0;
  auto a = runPatch(GetParam(), 3, p);
  const ddc::Model& m = a->model();
  ASSERT_EQ(m.contactSlots().size(), 25u);
  // Slave nodes on the free edges of the interface are excluded, as in 2-D.
  auto interior = [](const std::array<double, 3>& x) {
    return x[0] > 1e-12 && x[0] < 1 - 1e-12 && x[2] > 1e-12 && x[2] < 1 - 1e-12;
  };
  const std::string tag = GetParam().formulation + ", 3x3 under 4x4, interior";
  const double worst = pressureDeviation(m, p, tag.c_str(), interior);
  EXPECT_NEAR(a->history().back().contactForce[1], p, kForceBalance * p) << "resultant = p · area";
  EXPECT_LE(worst, kNtsPatchError3D) << "single-pass NTS patch-test error (see kNtsPatchError3D)";
}

INSTANTIATE_TEST_SUITE_P(Formulations, Contact3DPatch,
                         testing::Values(Case{"Node-To-Surface"}, Case{"Decomposed Node-To-Surface"}),
                         caseName);

}  // namespace
