// requireJoinedCoincidentNodes (doc/user-guide.md, "Writing an input deck":
// "Bodies that touch"): bodies with nodes at one position that no contact
// pair joins are refused, naming both bodies and a node; a pair between them,
// or a gap, lets them pass; 2-D and 3-D. On parts of a mesh spread over 1-3
// ranks, every rank throws the whole mesh's message.
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>
#include <mpi.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "DDC_CoincidentNodes.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestRanks.hpp"

namespace {

using ddc::test::rank;
using ddc::test::ranks;

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
  // The interface x = 1 has 3 nodes in each body: the pair of lowest ids is
  // node 2 of A (its bottom right) and node 9 of B (its bottom left).
  EXPECT_NE(msg.find("mesh: bodies 'A' and 'B' have nodes at 3 common position(s)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(node 2 of 'A' and node 9 of 'B' at (1, 0))"), std::string::npos) << msg;
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


/// This rank's part of `whole` when element e goes to rank (e * stride) %
/// ranks: parts that share many nodes.
ddc::Mesh strideParts(const ddc::Mesh& whole, int stride) {
  std::vector<int> mine;
  for (int e = 0; e < whole.numElements(); ++e)
    if ((e * stride) % ranks() == rank()) mine.push_back(e);
  return whole.part(mine);
}

/// On parts of `whole` (two strides), every rank throws the message the
/// whole mesh gives (or none).
void expectPartsGiveTheWholeMessage(const ddc::Mesh& whole, const ddc::ContactOptions& contact) {
  const std::string expected = inputErrorOf([&] { ddc::requireJoinedCoincidentNodes(whole, contact); });
  for (int stride : {1, 5}) {
    const ddc::Mesh part = strideParts(whole, stride);
    EXPECT_EQ(inputErrorOf([&] { ddc::requireJoinedCoincidentNodes(part, contact, MPI_COMM_WORLD); }), expected)
        << "stride " << stride;
  }
}

/// Two unit cubes A and B, 4 x 4 x 4 elements each, B's left face at x =
/// `offset` (of the second after A's right face at x = 1 + ...): A's right
/// face and B's left face straddle x = k c for the grid step c the search
/// spreads the nodes with on parts (1024 tolerances, the tolerance 1e-9 of
/// the bounding-box diagonal), a quarter tolerance on each side: their nodes
/// coincide but lie in neighbouring cells of that grid.
ddc::Mesh straddlingCubes() {
  double a = 1.0, b = 1.0;
  for (int it = 0; it < 200; ++it) {  // the faces depend on the diagonal, the diagonal on them
    const double tol = 1e-9 * std::sqrt((b + 1.0) * (b + 1.0) + 2.0);
    const double step = 1024.0 * tol, plane = std::round(1.0 / step) * step;
    a = plane - 0.25 * tol;
    b = plane + 0.25 * tol;
  }
  ddc::Mesh m;
  for (const auto& [name, x0, length] : {std::tuple<const char*, double, double>{"A", 0.0, a}, {"B", b, 1.0}}) {
    Teuchos::ParameterList p;
    p.set("Origin X", x0);
    p.set("Length X", length);
    p.set("Elements X", 4);
    p.set("Elements Y", 4);
    p.set("Elements Z", 4);
    ddc::generateBox(m, name, ddc::CellType::Hex8, p, "Box");
  }
  return m;
}

}  // namespace

TEST(CoincidentNodesOnParts, TheWholeMeshesMessage) {
  for (bool solid : {false, true}) {
    expectPartsGiveTheWholeMessage(sideBySide(solid, 0.0), ddc::ContactOptions());
    expectPartsGiveTheWholeMessage(sideBySide(solid, 0.0), pairBetween("B/left", "A/right"));
    expectPartsGiveTheWholeMessage(sideBySide(solid, 1e-6), ddc::ContactOptions());
  }
}

TEST(CoincidentNodesOnParts, NodesInNeighbouringCellsOfTheSpreadingGrid) {
  const ddc::Mesh m = straddlingCubes();
  const std::string msg = inputErrorOf([&] { ddc::requireJoinedCoincidentNodes(m, ddc::ContactOptions()); });
  EXPECT_NE(msg.find("mesh: bodies 'A' and 'B' have nodes at 25 common position(s)"), std::string::npos) << msg;
  expectPartsGiveTheWholeMessage(m, ddc::ContactOptions());
}
