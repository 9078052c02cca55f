// The model on a part of a mesh (Mesh::part()): each rank holds only its
// elements and their nodes, numbered locally with their ids in the whole
// mesh, and the model must be the one it builds on the whole mesh: the
// same node owners and DOF numbers (by node id), the same prescribed DOFs,
// partition-free ids, residual and tangent, the same rigid motions left
// free and the same place named for a non-finite entry; other ranks'
// elements on a part are refused. On 1-3 ranks of a Hex8 block under
// METIS's partition; and with contact between two stacked blocks, the
// same contact slots, multiplier DOFs, residual and tangent, for the
// conventional and the decomposed element (doc/architecture.md, "What a
// distributed mesh has to change").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "DDC_ElementFactory.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_Model.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_Partition.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using PL = Teuchos::ParameterList;
using ddc::GO;
using ddc::LO;
using ddc::test::kRoundoff;

Teuchos::RCP<const Teuchos::Comm<int>> comm() { return Tpetra::getDefaultComm(); }

std::shared_ptr<ddc::Mesh> block() {
  auto mesh = std::make_shared<ddc::Mesh>();
  PL box("Box");
  box.set("Elements X", 5);
  box.set("Elements Y", 3);
  box.set("Elements Z", 2);
  ddc::generateBox(*mesh, "Block", ddc::CellType::Hex8, box, "Box");
  return mesh;
}

/// "Fixed": every component of "Block/left" held; "Pulled": x of
/// "Block/right" prescribed to 0.1. Without the first, only x is held
/// anywhere: five rigid motions are free.
ddc::BoundaryConditions pulled(bool fixLeft) {
  ddc::BoundaryConditions bcs;
  ddc::DisplacementCondition fixed;
  fixed.name = "Fixed";
  fixed.setName = "Block/left";
  fixed.fix[2] = true;
  ddc::DisplacementCondition pull;
  pull.name = "Pulled";
  pull.setName = "Block/right";
  pull.fix[1] = pull.fix[2] = false;
  pull.value[0] = 0.1;
  bcs.displacements = {pull};
  if (fixLeft) bcs.displacements.push_back(fixed);
  return bcs;
}

/// The whole mesh's model and the model on this rank's part of it.
struct TwoModels {
  std::shared_ptr<ddc::Mesh> whole;
  std::shared_ptr<ddc::Mesh> part;
  std::unique_ptr<ddc::Model> onWhole, onPart;
};

TwoModels makeModels(bool fixLeft) {
  TwoModels m;
  m.whole = block();
  const ddc::Partition partition = ddc::partitionMetis(*m.whole, comm()->getSize());
  ddc::RankPart own = ddc::rankPart(*m.whole, partition, comm()->getRank(), comm()->getSize());
  m.part = std::make_shared<ddc::Mesh>(std::move(own.mesh));
  PL el("Element");
  el.set("Type", std::string("Hex8"));
  el.sublist("Material").set("Type", std::string("Neo-Hookean"));
  std::vector<std::shared_ptr<const ddc::Element>> elements = {
      ddc::ElementFactory::withBuiltins().create(el, "Element")};
  m.onWhole = std::make_unique<ddc::Model>(comm(), m.whole, elements, partition, pulled(fixLeft));
  m.onPart = std::make_unique<ddc::Model>(comm(), m.part, elements, own.partition, pulled(fixLeft));
  return m;
}

/// u = the prescribed field at λ = 1 plus a smooth field on the free DOFs.
Teuchos::RCP<ddc::Vector> state(const ddc::Model& model) {
  auto u = model.createVector();
  const auto& map = *model.ownedMap();
  auto d = u->getDataNonConst();
  for (size_t l = 0; l < map.getNodeNumElements(); ++l) d[l] = 0.01 * std::sin(0.7 * double(map.getGlobalElement(LO(l))));
  d = Teuchos::null;
  model.applyPrescribed(1.0, *u);
  return u;
}

/// The residual and tangent of `model` at state(model), λ = 1.
struct Assembled {
  Teuchos::RCP<ddc::Vector> r;
  Teuchos::RCP<ddc::CrsMatrix> k;
  ddc::AssemblyResult result;
};
Assembled assembled(const ddc::Model& model) {
  Assembled a{model.createVector(), model.createMatrix(), {}};
  ddc::AssemblyRequest request;
  request.residual = a.r.get();
  request.tangent = a.k.get();
  a.result = model.assemble(*state(model), 1.0, request);
  return a;
}

/// The overlap maps hold the same DOFs, and their partition-free ids agree.
void expectSameOverlap(const ddc::Model& whole, const ddc::Model& part) {
  const auto& overlap = *part.overlapMap();
  ASSERT_EQ(overlap.getNodeNumElements(), whole.overlapMap()->getNodeNumElements());
  for (size_t l = 0; l < overlap.getNodeNumElements(); ++l) {
    const GO g = overlap.getGlobalElement(LO(l));
    EXPECT_EQ(g, whole.overlapMap()->getGlobalElement(LO(l)));
    EXPECT_EQ(part.partitionFreeDof(g), whole.partitionFreeDof(g)) << "DOF " << g;
  }
}

/// The residuals equal entry for entry and the tangents row by row, by
/// global column, to round-off of the residual's and tangent's size;
/// `entry(row, value)` sees each entry of the whole mesh's tangent.
void expectSameResidualAndTangent(const ddc::Model& whole, const ddc::Vector& rWhole, const ddc::Vector& rPart,
                                  const ddc::CrsMatrix& kWhole, const ddc::CrsMatrix& kPart,
                                  const std::function<void(GO, double)>& entry = {}) {
  const double scale = rWhole.normInf() + kWhole.getFrobeniusNorm();
  auto dr = rWhole.getData(), pr = rPart.getData();
  for (size_t l = 0; l < dr.size(); ++l) EXPECT_NEAR(pr[l], dr[l], kRoundoff * scale) << "row " << l;
  const auto& rows = *whole.ownedMap();
  for (size_t l = 0; l < rows.getNodeNumElements(); ++l) {
    const GO g = rows.getGlobalElement(LO(l));
    const size_t n = kWhole.getNumEntriesInGlobalRow(g);
    ASSERT_EQ(kPart.getNumEntriesInGlobalRow(g), n) << "row " << g;
    std::vector<GO> ci(n), cj(n);
    std::vector<double> vi(n), vj(n);
    size_t got = 0;
    kWhole.getGlobalRowCopy(g, ci, vi, got);
    kPart.getGlobalRowCopy(g, cj, vj, got);
    std::vector<std::pair<GO, double>> a1, a2;
    for (size_t k = 0; k < n; ++k) a1.push_back({ci[k], vi[k]}), a2.push_back({cj[k], vj[k]});
    std::sort(a1.begin(), a1.end());
    std::sort(a2.begin(), a2.end());
    for (size_t k = 0; k < n; ++k) {
      EXPECT_EQ(a2[k].first, a1[k].first) << "row " << g;
      EXPECT_NEAR(a2[k].second, a1[k].second, kRoundoff * scale) << "row " << g << " column " << a1[k].first;
      if (entry) entry(g, a1[k].second);
    }
  }
}

TEST(ModelOnPart, SameOwnersDofsAndPrescribedDofs) {
  const TwoModels m = makeModels(true);
  const ddc::Model &whole = *m.onWhole, &part = *m.onPart;
  ASSERT_EQ(part.ownedMap()->getGlobalNumElements(), whole.ownedMap()->getGlobalNumElements());
  EXPECT_EQ(part.ownedMap()->getMinGlobalIndex(), whole.ownedMap()->getMinGlobalIndex());
  EXPECT_EQ(part.ownedMap()->getNodeNumElements(), whole.ownedMap()->getNodeNumElements());
  for (int n = 0; n < m.part->numNodes(); ++n)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(part.dof(n, c), whole.dof(static_cast<int>(m.part->nodeId(n)), c)) << "node " << m.part->nodeId(n);
  // Every rank sees every prescribed DOF, as on the whole mesh.
  for (GO g = 0; g < GO(whole.ownedMap()->getGlobalNumElements()); ++g)
    EXPECT_EQ(part.isConstrained(g), whole.isConstrained(g)) << "DOF " << g;
  expectSameOverlap(whole, part);
}

TEST(ModelOnPart, SameResidualAndTangent) {
  const TwoModels m = makeModels(true);
  const ddc::Model &whole = *m.onWhole, &part = *m.onPart;
  const Assembled w = assembled(whole), p = assembled(part);
  const ddc::AssemblyResult &resultWhole = w.result, &resultPart = p.result;
  EXPECT_NEAR(resultPart.strainEnergy, resultWhole.strainEnergy, kRoundoff * resultWhole.strainEnergy);
  EXPECT_EQ(resultPart.freeMotions, "");
  EXPECT_EQ(resultWhole.freeMotions, "");
  ASSERT_GT(w.r->norm2(), 0.0);
  expectSameResidualAndTangent(whole, *w.r, *p.r, *w.k, *p.k);
}

TEST(ModelOnPart, SameFreeRigidMotionsAndSameNonFinitePlace) {
  const TwoModels m = makeModels(false);
  const ddc::Model &whole = *m.onWhole, &part = *m.onPart;
  auto kWhole = whole.createMatrix(), kPart = part.createMatrix();
  ddc::AssemblyRequest a, b;
  a.tangent = kWhole.get();
  b.tangent = kPart.get();
  const std::string freeWhole = whole.assemble(*state(whole), 1.0, a).freeMotions;
  const std::string freePart = part.assemble(*state(part), 1.0, b).freeMotions;
  EXPECT_NE(freeWhole, "");
  EXPECT_EQ(freePart, freeWhole);
  // A NaN at the last DOF: its node named by its id in the whole mesh, on
  // every rank.
  auto v = whole.createVector(), w = part.createVector();
  const GO last = GO(whole.ownedMap()->getGlobalNumElements()) - 1;
  for (auto* x : {v.get(), w.get()})
    if (x->getMap()->isNodeGlobalElement(last))
      x->replaceGlobalValue(last, std::numeric_limits<double>::quiet_NaN());
  const std::string onWhole = whole.describeNonFinite(*v), onPart = part.describeNonFinite(*w);
  EXPECT_THAT(onWhole, ::testing::HasSubstr("NaN at u_z of node "));
  EXPECT_EQ(onPart.substr(0, onPart.find(", in element")), onWhole.substr(0, onWhole.find(", in element")));
}

TEST(ModelOnPart, RefusesOtherRanksElements) {
  // A part must hold this rank's elements only: every element on every
  // rank is refused where there is more than one rank.
  const TwoModels m = makeModels(true);
  if (comm()->getSize() == 1) return;
  const ddc::Partition partition = ddc::partitionMetis(*m.whole, comm()->getSize());
  PL el("Element");
  el.set("Type", std::string("Hex8"));
  el.sublist("Material").set("Type", std::string("Neo-Hookean"));
  std::vector<std::shared_ptr<const ddc::Element>> elements = {
      ddc::ElementFactory::withBuiltins().create(el, "Element")};
  std::vector<int> all(size_t(m.whole->numElements()));
  for (int e = 0; e < m.whole->numElements(); ++e) all[size_t(e)] = e;
  auto everything = std::make_shared<ddc::Mesh>(m.whole->part(all));
  std::string refusal;
  try {
    ddc::Model(comm(), everything, elements, partition, pulled(true));
  } catch (const std::logic_error& e) {
    refusal = e.what();
  }
  EXPECT_THAT(refusal, ::testing::HasSubstr("holds elements of other ranks"));
}

// ---- contact on a part ------------------------------------------------------------

/// Two stacked blocks, 1 x 0.5 x 1 each: the upper one's 3 x 3 Hex8 bottom
/// facets on the lower one's Tet4 top facets (4 x 4 cells; non-matching, so
/// slave nodes project inside, onto edges and onto corners of master
/// facets; a tetrahedron may touch the top face at an edge or a corner
/// only, so a rank may hold a master node without a master facet); the
/// lower block fixed at its bottom, the upper one pressed down 0.01 at its
/// top, held in x on its left and in z on its back face.
struct ContactModels {
  std::shared_ptr<ddc::Mesh> whole, part;
  std::unique_ptr<ddc::Model> onWhole, onPart;
};

ContactModels makeContactModels(const std::string& formulation) {
  ContactModels m;
  m.whole = std::make_shared<ddc::Mesh>();
  for (const auto& [name, y0, n, cell] : {std::make_tuple("Lower", 0.0, 4, ddc::CellType::Tet4),
                                          std::make_tuple("Upper", 0.5, 3, ddc::CellType::Hex8)}) {
    PL box("Box");
    box.set("Origin Y", y0);
    box.set("Length Y", 0.5);
    box.set("Elements X", n);
    box.set("Elements Y", 2);
    box.set("Elements Z", n);
    ddc::generateBox(*m.whole, name, cell, box, "Box");
  }
  // The lower block's elements with a top facet and the upper block on the
  // last rank, the lower block's others dealt to the ranks in turn: a rank
  // holds master nodes through tetrahedra that touch the top at an edge or
  // a corner, and may own them (their lowest holder) without a master facet.
  const int ranks = comm()->getSize();
  ddc::Partition partition;
  partition.numSubdomains = ranks;
  partition.elementSubdomain.assign(size_t(m.whole->numElements()), ranks - 1);
  std::vector<char> topFacet(size_t(m.whole->numElements()), 0);
  for (const ddc::Segment& f : m.whole->sideSet("Lower/top")) topFacet[size_t(f.element)] = 1;
  const ddc::Body& lower = m.whole->body(m.whole->bodyIndex("Lower"));
  for (int e = lower.firstElement; e < lower.firstElement + lower.numElements; ++e)
    if (!topFacet[size_t(e)]) partition.elementSubdomain[size_t(e)] = e % ranks;
  ddc::RankPart own = ddc::rankPart(*m.whole, partition, comm()->getRank(), comm()->getSize());
  m.part = std::make_shared<ddc::Mesh>(std::move(own.mesh));
  std::vector<std::shared_ptr<const ddc::Element>> elements;
  for (const char* type : {"Tet4", "Hex8"}) {
    PL el("Element");
    el.set("Type", std::string(type));
    el.sublist("Material").set("Type", std::string("Neo-Hookean"));
    elements.push_back(ddc::ElementFactory::withBuiltins().create(el, "Element"));
  }
  ddc::BoundaryConditions bcs;
  auto condition = [&](const char* name, const char* set, std::array<bool, 3> fix, double value) {
    ddc::DisplacementCondition c;
    c.name = name;
    c.setName = set;
    for (int k = 0; k < 3; ++k) c.fix[k] = fix[k];
    c.value[1] = value;
    bcs.displacements.push_back(c);
  };
  condition("Base", "Lower/bottom", {true, true, true}, 0.0);
  condition("Press", "Upper/top", {false, true, false}, -0.01);
  condition("Left", "Upper/left", {true, false, false}, 0.0);
  condition("Back", "Upper/back", {false, false, true}, 0.0);
  auto options = [&](const ddc::Mesh& mesh) {
    PL contact("Contact");
    contact.set("Formulation", formulation);
    contact.sublist("Pairs").sublist("Interface").set("Slave", std::string("Upper/bottom"));
    contact.sublist("Pairs").sublist("Interface").set("Master", std::string("Lower/top"));
    return ddc::ContactOptions::fromParameters(contact, mesh, "Contact", ddc::rawComm(*comm()));
  };
  m.onWhole = std::make_unique<ddc::Model>(comm(), m.whole, elements, partition, bcs, options(*m.whole));
  m.onPart = std::make_unique<ddc::Model>(comm(), m.part, elements, own.partition, bcs, options(*m.part));
  return m;
}

class ContactOnPart : public ::testing::TestWithParam<std::string> {};

TEST_P(ContactOnPart, SameSlotsDofsResidualAndTangent) {
  // The contact surfaces registered from the parts by their ids in the
  // whole mesh give the whole mesh's slots (pairs, projections), multiplier
  // DOFs, overlap maps, residual and tangent with every paired slot active
  // and non-zero multipliers, and the same free rigid motions (none).
  const ContactModels m = makeContactModels(GetParam());
  ddc::Model &whole = *m.onWhole, &part = *m.onPart;
  const auto& slotsWhole = whole.contactSlots();
  const auto& slotsPart = part.contactSlots();
  ASSERT_EQ(slotsPart.size(), slotsWhole.size());
  int paired = 0;
  for (size_t k = 0; k < slotsWhole.size(); ++k) {
    EXPECT_EQ(slotsPart[k].slaveNode, slotsWhole[k].slaveNode) << "slot " << k;
    EXPECT_EQ(slotsPart[k].segment, slotsWhole[k].segment) << "slot " << k;
    EXPECT_EQ(slotsPart[k].masterElement, slotsWhole[k].masterElement) << "slot " << k;
    EXPECT_NEAR(slotsPart[k].gap, slotsWhole[k].gap, kRoundoff) << "slot " << k;
    paired += slotsWhole[k].paired();
  }
  EXPECT_EQ(paired, 16);  // the 4 x 4 slave nodes of the 3 x 3 facets
  ASSERT_EQ(part.ownedMap()->getGlobalNumElements(), whole.ownedMap()->getGlobalNumElements());
  EXPECT_EQ(part.ownedMap()->getMinGlobalIndex(), whole.ownedMap()->getMinGlobalIndex());
  for (int n = 0; n < m.part->numNodes(); ++n)
    EXPECT_EQ(part.dof(n, 0), whole.dof(static_cast<int>(m.part->nodeId(n)), 0)) << "node " << m.part->nodeId(n);
  expectSameOverlap(whole, part);
  whole.activateAllPaired();
  part.activateAllPaired();
  const Assembled w = assembled(whole), p = assembled(part);
  const ddc::AssemblyResult &resultWhole = w.result, &resultPart = p.result;
  EXPECT_NEAR(resultPart.strainEnergy, resultWhole.strainEnergy, kRoundoff * resultWhole.strainEnergy);
  EXPECT_EQ(resultPart.freeMotions, resultWhole.freeMotions);
  double contactEntries = 0.0;
  expectSameResidualAndTangent(whole, *w.r, *p.r, *w.k, *p.k, [&](GO row, double value) {
    if (whole.partitionFreeDof(row) >= 3 * m.whole->numGlobalNodes()) contactEntries += std::abs(value);
  });
  // The multipliers' rows carry the contact constraints (the test is not
  // vacuous): summed over the ranks.
  double total = 0.0;
  Teuchos::reduceAll(*comm(), Teuchos::REDUCE_SUM, contactEntries, Teuchos::outArg(total));
  EXPECT_GT(total, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Formulations, ContactOnPart,
                         ::testing::Values(std::string("Node-To-Surface"), std::string("Decomposed Node-To-Surface")),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param == "Node-To-Surface" ? std::string("Conventional") : std::string("Decomposed");
                         });

}  // namespace
