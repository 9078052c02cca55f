// requireJoinedCoincidentNodes (doc/user-guide.md, "Writing an input deck":
// "Bodies that touch"): bodies with nodes at one position that no contact
// pair joins are refused, naming both bodies and a node; a pair between them,
// or a gap, lets them pass; 2-D and 3-D.
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>
#include <string>

#include "DDC_CoincidentNodes.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_TestErrors.hpp"

namespace {

using ddc::test::inputErrorOf;

/// Two unit squares (cubes) "A" and "B" side by side along x, 2 x 2 (x 2)
/// elements each, B starting at x = 1 + gap.
ddc::Mesh sideBySide(bool solid, double gap) {
  ddc::Mesh m;
  for (const auto& [name, x0] : {std::pair<const char*, double>{"A", 0.0}, {"B", 1.0 + gap}}) {
    Teuchos::ParameterList p;
    p.set("Origin X", x0);
    p.set("Elements X", 2);
    p.set("Elements Y", 2);
    if (solid) {
      p.set("Elements Z", 2);
      ddc::generateBox(m, name, ddc::CellType::Hex8, p, "Box");
    } else {
      ddc::generateRectangle(m, name, ddc::CellType::Quad4, p, "Rectangle");
    }
  }
  return m;
}

ddc::ContactOptions pairBetween(const std::string& slave, const std::string& master) {
  ddc::ContactOptions c;
  ddc::ContactPairDefinition d;
  d.name = "Interface";
  d.slaveSet = slave;
  d.masterSet = master;
  c.pairs.push_back(d);
  return c;
}

TEST(CoincidentNodes, BodiesSharingNodesWithoutAPairAreRefused) {
  const ddc::Mesh m = sideBySide(false, 0.0);
  const std::string msg = inputErrorOf([&] { ddc::requireJoinedCoincidentNodes(m, ddc::ContactOptions()); });
  // The interface x = 1 has 3 nodes in each body.
  EXPECT_NE(msg.find("mesh: bodies 'A' and 'B' have nodes at 3 common position(s)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("of 'A' and node "), std::string::npos) << msg;
  EXPECT_NE(msg.find("mesh them as one body"), std::string::npos) << msg;
}

TEST(CoincidentNodes, ThreeDBodiesSharingAFaceAreRefused) {
  const ddc::Mesh m = sideBySide(true, 0.0);
  const std::string msg = inputErrorOf([&] { ddc::requireJoinedCoincidentNodes(m, ddc::ContactOptions()); });
  EXPECT_NE(msg.find("mesh: bodies 'A' and 'B' have nodes at 9 common position(s)"), std::string::npos) << msg;
}

TEST(CoincidentNodes, APairBetweenTheBodiesLetsThemTouch) {
  for (bool solid : {false, true}) {
    const ddc::Mesh m = sideBySide(solid, 0.0);
    EXPECT_EQ(inputErrorOf([&] { ddc::requireJoinedCoincidentNodes(m, pairBetween("B/left", "A/right")); }),
              ddc::test::kNoInputError);
  }
}

TEST(CoincidentNodes, BodiesApartPass) {
  // 1e-6 of a unit element apart: far above the coincidence tolerance
  // (1e-9 of the bounding-box diagonal).
  for (bool solid : {false, true}) {
    const ddc::Mesh m = sideBySide(solid, 1e-6);
    EXPECT_EQ(inputErrorOf([&] { ddc::requireJoinedCoincidentNodes(m, ddc::ContactOptions()); }),
              ddc::test::kNoInputError);
  }
}

}  // namespace
