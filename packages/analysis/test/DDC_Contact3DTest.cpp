// Node-to-surface contact in 3-D through the whole analysis (doc/contact.md,
// "Curved facets and 3-D"): the contact patch test between two stacked blocks
// of Hex8 (Quad4 contact facets) under a uniform pressure, with both
// formulations. The upper block is held by contact alone, which FETI-DP does
// not allow (a floating subdomain problem); the plane-strain consistency with
// 2-D and FETI-DP = Monolithic on the 3-D half-rings are ctests
// (test/suites/contact.cmake).
#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_Model.hpp"
#include "DDC_ShapeFunctions.hpp"

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
/// The same on Tri3, Tri6 and Quad9 facets, |λ_k + p w_k| as a fraction of
/// the largest consistent nodal load p max w_k (Contact3DPatchFacets), both
/// formulations: measured 6.3 % (Tri3), 4.7 % (Tri6), 1.5 % (Quad9). A
/// regression guard, not a target.
constexpr double kNtsPatchErrorFacets = 1e-1;
/// The contact resultant on the slave body equals the applied load by
/// equilibrium, whatever the distribution.
constexpr double kForceBalance = 1e-7;

struct Case {
  std::string formulation;
  /// Element type of both blocks (their contact facets: Hex8 Quad4, Tet4
  /// Tri3, Tet10 Tri6, Hex20 Quad8, Hex27 Quad9).
  std::string element = "Hex8";
};

std::string caseName(const testing::TestParamInfo<Case>& info) {
  std::string n = info.param.formulation + (info.param.element == "Hex8" ? "" : " " + info.param.element);
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
    b.element = c.element;
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

/// Consistent nodal weights w_k = Σ_facets ∫ N_k dA of the side set `set`
/// (reference configuration): a uniform pressure p loads node k with p w_k.
std::map<int, double> consistentWeights(const ddc::Mesh& mesh, const std::string& set) {
  std::map<int, double> w;
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (const ddc::Segment& sg : mesh.sideSet(set)) {
    const ddc::CellType cell = mesh.body(mesh.elementBody(sg.element)).cellType;
    const ddc::CellType facet = ddc::referenceCell(cell).facets[sg.localSide].type;
    const auto& rule = ddc::facetQuadratureRule(facet);
    Eigen::MatrixXd x(sg.numNodes, 3);
    for (int i = 0; i < sg.numNodes; ++i)
      for (int c = 0; c < 3; ++c) x(i, c) = mesh.coord(sg.nodes[i])[c];
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      ddc::shapeFunctions(facet, rule.points[q], &N, &dN);
      const Eigen::MatrixXd a = x.transpose() * dN;  // the two tangents
      const double jac = Eigen::Vector3d(a.col(0)).cross(Eigen::Vector3d(a.col(1))).norm();
      for (int i = 0; i < sg.numNodes; ++i) w[sg.nodes[i]] += N[i] * jac * rule.weights[q];
    }
  }
  return w;
}

/// The nested patch test on the other facet types, where the slave nodes
/// are the facets' nodes (mid-side and centre nodes of quadratic facets
/// too) and every master node is a slave node. Exact single-pass transfer
/// means each multiplier is the consistent nodal load of the uniform
/// pressure, λ_k = −p w_k: checked on Tri3 (Tet4, Kuhn-split faces with
/// nodes of different valence), Tri6 (Tet10: w = 0 at the corners) and
/// Quad9 (Hex27). On Tri3 and Quad9 the HRZ tributary areas equal w_k, so
/// the reported pressure −λ/A is p; on Tri6 they do not (HRZ gives the
/// corners a positive share), so the pressure output there reads 0 at the
/// corners and 19/16 p at mid-sides (doc/contact.md). Quad8 faces (Hex20)
/// have w < 0 at the corners: single-pass NTS releases those nodes, and only
/// the normal resultant is checked.
class Contact3DPatchFacets : public testing::TestWithParam<Case> {};

TEST_P(Contact3DPatchFacets, NestedMeshesTransmitConsistentNodalLoads) {
  const double p = 5.0;
  auto a = runPatch(GetParam(), 2, p);
  const ddc::Model& m = a->model();
  const std::string& type = GetParam().element;
  const std::size_t slaveNodes = type == "Tet4" ? 25u : type == "Hex20" ? 65u : 81u;
  ASSERT_EQ(m.contactSlots().size(), slaveNodes) << type;
  EXPECT_NEAR(a->history().back().contactForce[1], p, kForceBalance * p) << "resultant = p · area";
  if (type == "Hex20") return;
  const auto w = consistentWeights(m.mesh(), "Upper/bottom");
  double wmax = 0.0, worst = 0.0;
  for (const auto& [node, wk] : w) wmax = std::max(wmax, wk);
  for (const auto& sl : m.contactSlots()) {
    const double expected = -p * w.at(sl.slaveNode);
    EXPECT_TRUE(sl.active || expected == 0.0) << "slave node " << sl.slaveNode;
    worst = std::max(worst, std::abs((sl.active ? sl.state.multiplier : 0.0) - expected) / (p * wmax));
  }
  if (isRoot())
    std::printf("[patch 3-D] %s %s, 2x2 under 4x4: max |lambda_k + p w_k| / (p max w) = %.2e\n",
                GetParam().formulation.c_str(), type.c_str(), worst);
  EXPECT_LE(worst, kPatchExact) << type;
}

/// General non-matching meshes on the other facet types: 3 x 3 master under
/// 4 x 4 slave elements, so master and slave nodes do not nest. Single-pass
/// NTS then loads the master with λ N_i(ξ) at the slave projections, which is
/// not the consistent load, and the multipliers differ from −p w_k; the
/// resultant is still p · area. Reported (doc/contact.md, "Verification")
/// and bounded as a regression guard, interior slave nodes only as in the
/// Hex8 test above. Quad8 (Hex20): the resultant only, as in the nested test.
TEST_P(Contact3DPatchFacets, GeneralNonMatchingMeshesTransmitTheResultant) {
  const double p = 5.0;
  auto a = runPatch(GetParam(), 3, p);
  const ddc::Model& m = a->model();
  const std::string& type = GetParam().element;
  EXPECT_NEAR(a->history().back().contactForce[1], p, kForceBalance * p) << "resultant = p · area";
  if (type == "Hex20") return;
  const auto w = consistentWeights(m.mesh(), "Upper/bottom");
  double wmax = 0.0, worst = 0.0;
  for (const auto& [node, wk] : w) wmax = std::max(wmax, wk);
  int n = 0;
  for (const auto& sl : m.contactSlots()) {
    const auto& x = m.mesh().coord(sl.slaveNode);
    if (!(x[0] > 1e-12 && x[0] < 1 - 1e-12 && x[2] > 1e-12 && x[2] < 1 - 1e-12)) continue;
    const double expected = -p * w.at(sl.slaveNode);
    worst = std::max(worst, std::abs((sl.active ? sl.state.multiplier : 0.0) - expected) / (p * wmax));
    ++n;
  }
  if (isRoot())
    std::printf("[patch 3-D] %s %s, 3x3 under 4x4, %d interior slave nodes: max |lambda_k + p w_k| / (p max w) = %.2e\n",
                GetParam().formulation.c_str(), type.c_str(), n, worst);
  EXPECT_LE(worst, kNtsPatchErrorFacets) << type << ": single-pass NTS patch-test error (see kNtsPatchErrorFacets)";
}

INSTANTIATE_TEST_SUITE_P(
    FacetTypes, Contact3DPatchFacets,
    testing::Values(Case{"Node-To-Surface", "Tet4"}, Case{"Decomposed Node-To-Surface", "Tet4"},
                    Case{"Node-To-Surface", "Tet10"}, Case{"Decomposed Node-To-Surface", "Tet10"},
                    Case{"Node-To-Surface", "Hex20"}, Case{"Decomposed Node-To-Surface", "Hex20"},
                    Case{"Node-To-Surface", "Hex27"}, Case{"Decomposed Node-To-Surface", "Hex27"}),
    caseName);

}  // namespace
