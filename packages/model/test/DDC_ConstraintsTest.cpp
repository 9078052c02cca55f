// Prescribed DOFs in the model (packages/model/src/DDC_Model.hpp): each rank
// keeps which condition prescribes a DOF for its own DOFs only, and the
// node and slot of its overlap DOFs only, so these tests check, on 1-3
// ranks of a Hex8 block whose "left" (x = 0) and "bottom" (y = 0) faces
// share an edge:
//  - two conditions that disagree on the shared edge are refused on every
//    rank, with the same message naming both and the node;
//  - two that agree are accepted; every rank sees every prescribed DOF
//    (isConstrained() answers for any DOF), and the owner sets its values;
//  - partitionFreeDof() gives node · 3 + component for the rank's DOFs and
//    refuses a DOF the rank does not hold.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "DDC_ElementFactory.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_Model.hpp"
#include "DDC_Partition.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using PL = Teuchos::ParameterList;
using ::testing::HasSubstr;
using ddc::test::inputErrorOf;
using ddc::test::kRoundoff;

Teuchos::RCP<const Teuchos::Comm<int>> comm() { return Tpetra::getDefaultComm(); }

std::shared_ptr<ddc::Mesh> block() {
  auto mesh = std::make_shared<ddc::Mesh>();
  PL box("Box");
  box.set("Elements X", 4);
  box.set("Elements Y", 3);
  box.set("Elements Z", 2);
  ddc::generateBox(*mesh, "Block", ddc::CellType::Hex8, box, "Box");
  return mesh;
}

/// "Fixed": every component of "Block/left" held at 0; "Lifted": y of
/// "Block/bottom" prescribed to `lift` (times the load factor).
ddc::BoundaryConditions leftFixedBottomLifted(double lift) {
  ddc::BoundaryConditions bcs;
  ddc::DisplacementCondition fixed;
  fixed.name = "Fixed";
  fixed.setName = "Block/left";
  fixed.fix[2] = true;
  ddc::DisplacementCondition lifted;
  lifted.name = "Lifted";
  lifted.setName = "Block/bottom";
  lifted.fix[0] = false;
  lifted.value[1] = lift;
  bcs.displacements = {fixed, lifted};
  return bcs;
}

std::unique_ptr<ddc::Model> makeModel(const std::shared_ptr<ddc::Mesh>& mesh, ddc::BoundaryConditions bcs) {
  PL el("Element");
  el.set("Type", std::string("Hex8"));
  el.sublist("Material").set("Type", std::string("Neo-Hookean"));
  std::vector<std::shared_ptr<const ddc::Element>> elements = {
      ddc::ElementFactory::withBuiltins().create(el, "Element")};
  return std::make_unique<ddc::Model>(comm(), mesh, elements, ddc::partitionMetis(*mesh, comm()->getSize()),
                                      std::move(bcs));
}

/// Whether every rank holds the same `text` (by its hash and length).
bool sameOnEveryRank(const std::string& text) {
  const long long h[2] = {static_cast<long long>(std::hash<std::string>()(text) >> 1),
                          static_cast<long long>(text.size())};
  long long lo[2] = {0, 0}, hi[2] = {0, 0};
  Teuchos::reduceAll(*comm(), Teuchos::REDUCE_MIN, 2, h, lo);
  Teuchos::reduceAll(*comm(), Teuchos::REDUCE_MAX, 2, h, hi);
  return lo[0] == hi[0] && lo[1] == hi[1];
}

TEST(Constraints, ConditionsThatDisagreeOnASharedNodeAreRefusedOnEveryRank) {
  const auto mesh = block();
  const std::string error = inputErrorOf([&] { makeModel(mesh, leftFixedBottomLifted(0.1)); });
  EXPECT_THAT(error, HasSubstr("boundary conditions 'Fixed' and 'Lifted' prescribe different y displacements at node "));
  EXPECT_TRUE(sameOnEveryRank(error)) << error;
}

TEST(Constraints, ConditionsThatAgreeAreAcceptedAndEveryRankSeesEveryPrescribedDof) {
  const auto mesh = block();
  const auto model = makeModel(mesh, leftFixedBottomLifted(0.0));
  const std::vector<int>& left = mesh->nodeSet("Block/left");
  const std::vector<int>& bottom = mesh->nodeSet("Block/bottom");
  for (int n : left)
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(model->isConstrained(model->dof(n, c))) << "node " << n;
  for (int n : bottom) {
    EXPECT_TRUE(model->isConstrained(model->dof(n, 1))) << "node " << n;
    const bool onLeft = std::find(left.begin(), left.end(), n) != left.end();
    EXPECT_EQ(model->isConstrained(model->dof(n, 0)), onLeft) << "node " << n;
  }
  int prescribed = 0;
  for (int n = 0; n < mesh->numNodes(); ++n)
    for (int c = 0; c < 3; ++c) prescribed += model->isConstrained(model->dof(n, c)) ? 1 : 0;
  // left: 3 components of 4 x 3 nodes; bottom: y of 5 x 3 nodes, 3 of them on left.
  EXPECT_EQ(prescribed, 3 * 12 + 15 - 3);
  // The owner of each DOF sets its value: 0 everywhere here, λ-scaled.
  auto u = model->createVector();
  u->putScalar(1.0);
  model->applyPrescribed(1.0, *u);
  auto d = u->getData();
  const auto& map = *model->ownedMap();
  for (size_t l = 0; l < map.getNodeNumElements(); ++l)
    EXPECT_NEAR(d[l], model->isConstrained(map.getGlobalElement(ddc::LO(l))) ? 0.0 : 1.0, kRoundoff);
}

TEST(Constraints, PartitionFreeIdsOfTheRanksDofsAndNoneOfOthers) {
  const auto mesh = block();
  const auto model = makeModel(mesh, leftFixedBottomLifted(0.0));
  const auto& overlap = *model->overlapMap();
  int foreign = 0;
  for (int n = 0; n < mesh->numNodes(); ++n)
    for (int c = 0; c < 3; ++c) {
      const ddc::GO g = model->dof(n, c);
      if (overlap.isNodeGlobalElement(g)) {
        EXPECT_EQ(model->partitionFreeDof(g), ddc::GO(n) * 3 + c);
      } else {
        ++foreign;
        EXPECT_THROW(model->partitionFreeDof(g), std::logic_error) << "node " << n;
      }
    }
  // On more than one rank some nodes lie in no element of this rank.
  if (comm()->getSize() > 1) EXPECT_GT(foreign, 0);
}

}  // namespace
