// The per-element checks of the set-up, shared among the ranks
// (requireAdmissibleElements, Mesh::checkShapes; doc/user-guide.md,
// "Writing an input deck"): each rank checks an even share of the elements,
// and an inverted element in any rank's share is refused on every rank,
// naming the lowest such element, as one rank checking them all would.
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_ParameterList.hpp>
#include <memory>
#include <string>
#include <vector>

#include "DDC_ElementFactory.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_ModelSetUp.hpp"
#include "DDC_TestErrors.hpp"

namespace {

using ddc::test::inputErrorOf;

/// A unit cube of 4 x 1 x 1 Hex8 elements along x (element e spans
/// x in [e/4, (e+1)/4]), with the elements `inverted` turned inside out by
/// moving their corner at the top far end back across the element.
std::shared_ptr<ddc::Mesh> row(const std::vector<int>& inverted) {
  auto mesh = std::make_shared<ddc::Mesh>();
  Teuchos::ParameterList box;
  box.set("Elements X", 4);
  box.set("Elements Y", 1);
  box.set("Elements Z", 1);
  ddc::generateBox(*mesh, "Block", ddc::CellType::Hex8, box, "Box");
  for (int e : inverted) {
    // The element's node farthest along (1, 1, 1) is its top far corner.
    int corner = mesh->elementNodes(e)[0];
    for (int i = 0; i < 8; ++i) {
      const auto& x = mesh->coord(mesh->elementNodes(e)[i]);
      const auto& c = mesh->coord(corner);
      if (x[0] + x[1] + x[2] > c[0] + c[1] + c[2]) corner = mesh->elementNodes(e)[i];
    }
    mesh->coord(corner)[0] -= 0.4;  // past the element's near face, 0.25 away
  }
  return mesh;
}

std::vector<std::shared_ptr<const ddc::Element>> hex8() {
  Teuchos::ParameterList el("Element");
  el.set("Type", std::string("Hex8"));
  el.sublist("Material").set("Type", std::string("Linear Elastic"));
  return {ddc::ElementFactory::withBuiltins().create(el, "Element")};
}

TEST(ModelSetUp, AnInvertedElementInTheLastRanksShareIsRefusedOnEveryRank) {
  // Element 3 is in the last rank's share on 1, 2 and 3 ranks.
  const auto mesh = row({3});
  const std::string msg = inputErrorOf([&] { ddc::requireAdmissibleElements(*mesh, hex8(), MPI_COMM_WORLD); });
  EXPECT_NE(msg.find("mesh: element 3 of body 'Block' is inverted or degenerate"), std::string::npos) << msg;
}

TEST(ModelSetUp, OfTwoInvertedElementsTheLowestIsNamedOnEveryRank) {
  const auto mesh = row({0, 3});
  const std::string msg = inputErrorOf([&] { ddc::requireAdmissibleElements(*mesh, hex8(), MPI_COMM_WORLD); });
  EXPECT_NE(msg.find("mesh: element 0 of body 'Block' is inverted or degenerate"), std::string::npos) << msg;
}

TEST(ModelSetUp, AMeshWithoutInvertedElementsPassesOnEveryRank) {
  const auto mesh = row({});
  EXPECT_NO_THROW(ddc::requireAdmissibleElements(*mesh, hex8(), MPI_COMM_WORLD));
}

TEST(ModelSetUp, MeshShapeChecksCoverExactlyTheirRange) {
  // Mesh::checkShapes, the part of Mesh::check() the ranks share in
  // buildMesh(): elements [first, last) only.
  const auto mesh = row({3});
  EXPECT_NO_THROW(mesh->checkShapes(0, 3));
  const std::string msg = inputErrorOf([&] { mesh->checkShapes(2, 4); });
  EXPECT_NE(msg.find("mesh: element 3 of body 'Block' (Hex8"), std::string::npos) << msg;
  EXPECT_NE(inputErrorOf([&] { mesh->check(); }).find("element 3"), std::string::npos);
  EXPECT_NO_THROW(mesh->checkConnectivity());
}

}  // namespace
