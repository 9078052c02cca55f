// ddc::Mesh: bodies, sets, segments and the errors of check().
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>

#include "DDC_Error.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_TestErrors.hpp"

using ddc::CellType;
using ddc::InputError;
using ddc::Mesh;
using ::testing::HasSubstr;

namespace {

using ddc::test::inputErrorOf;

/// Unit square, one Quad4, in body `name`.
void addSquare(Mesh& m, const std::string& name, double x0 = 0.0) {
  m.beginBody(name, CellType::Quad4);
  const int a = m.addNode(x0, 0), b = m.addNode(x0 + 1, 0), c = m.addNode(x0 + 1, 1), d = m.addNode(x0, 1);
  const int nodes[4] = {a, b, c, d};
  m.addElement(nodes);
}

}  // namespace

TEST(Mesh, BodiesSetsAndSegments) {
  Mesh m;
  addSquare(m, "A");
  addSquare(m, "B", 2.0);
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.numBodies(), 2);
  EXPECT_EQ(m.bodyIndex("B"), 1);
  EXPECT_EQ(m.body(1).firstNode, 4);
  EXPECT_EQ(m.elementBody(1), 1);
  EXPECT_EQ(m.elementNumNodes(0), 4);
  const auto s = m.makeSegment(1, 1);
  EXPECT_EQ(s.numNodes, 2);
  EXPECT_EQ(s.nodes[0], 5);
  EXPECT_EQ(s.nodes[1], 6);
  m.addSideSet(1, "right", {s});
  m.addNodeSet(1, "right", {7});
  EXPECT_EQ(m.sideSet("B/right").size(), 1u);
  EXPECT_EQ(m.nodeSet("B/right"), (std::vector<int>{5, 6, 7}));
  EXPECT_TRUE(m.hasNodeSet("B/right"));
  EXPECT_FALSE(m.hasSideSet("A/right"));
  EXPECT_THAT(inputErrorOf([&] { m.sideSet("A/right"); }), HasSubstr("no side set named 'A/right'"));
  EXPECT_THAT(inputErrorOf([&] { m.sideSet("A/right"); }), HasSubstr("'B/right'"));
  EXPECT_THAT(inputErrorOf([&] { m.nodeSet("C/x"); }), HasSubstr("no node set named 'C/x'"));
  EXPECT_THAT(inputErrorOf([&] { m.bodyIndex("C"); }), HasSubstr("bodies are 'A', 'B'"));
}

TEST(Mesh, Quad9Segment) {
  Mesh m;
  m.beginBody("Q", CellType::Quad9);
  const double xy[9][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0}, {2, 1}, {1, 2}, {0, 1}, {1, 1}};
  int n[9];
  for (int i = 0; i < 9; ++i) n[i] = m.addNode(xy[i][0], xy[i][1]);
  m.addElement(n);
  EXPECT_NO_THROW(m.check());
  const auto s = m.makeSegment(0, 3);
  EXPECT_EQ(s.numNodes, 3);
  EXPECT_EQ(s.nodes[0], 3);
  EXPECT_EQ(s.nodes[1], 0);
  EXPECT_EQ(s.nodes[2], 7);
}

TEST(Mesh, CheckErrors) {
  {
    Mesh m;
    addSquare(m, "A");
    m.beginBody("Empty", CellType::Quad4);
    EXPECT_THAT(inputErrorOf([&] { m.check(); }), HasSubstr("body 'Empty' has no elements"));
  }
  {
    Mesh m;
    addSquare(m, "A");
    m.addNode(5, 5);
    EXPECT_THAT(inputErrorOf([&] { m.check(); }), HasSubstr("node 4 at (5, 5) belongs to no element"));
  }
  {
    Mesh m;
    addSquare(m, "A");
    m.beginBody("B", CellType::Quad4);
    for (int i = 0; i < 3; ++i) m.addNode(i, 0);
    const int nodes[4] = {4, 5, 6, 0};  // node 0 belongs to body A
    m.addElement(nodes);
    EXPECT_THAT(inputErrorOf([&] { m.check(); }), HasSubstr("references node 0 outside the body"));
  }
  {
    Mesh m;
    addSquare(m, "A");
    EXPECT_THAT(inputErrorOf([&] { m.beginBody("A", CellType::Quad9); }), HasSubstr("two bodies are named 'A'"));
    EXPECT_THAT(inputErrorOf([&] { m.beginBody("A/B", CellType::Quad9); }), HasSubstr("contain no '/'"));
    EXPECT_THAT(inputErrorOf([&] { m.beginBody("", CellType::Quad9); }), HasSubstr("must be non-empty"));
  }
}

namespace {

/// The unit cube as one Hex8 (Gmsh corner order) in body `name`; `x` may be
/// changed before the element is added.
void addCube(Mesh& m, const std::string& name, std::vector<std::array<double, 3>> x = {}) {
  if (x.empty()) x = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.beginBody(name, CellType::Hex8);
  int n[8];
  for (int i = 0; i < 8; ++i) n[i] = m.addNode(x[i][0], x[i][1], x[i][2]);
  m.addElement(n);
}

void addTet(Mesh& m, const std::string& name, std::vector<std::array<double, 3>> x) {
  m.beginBody(name, CellType::Tet4);
  int n[4];
  for (int i = 0; i < 4; ++i) n[i] = m.addNode(x[i][0], x[i][1], x[i][2]);
  m.addElement(n);
}

}  // namespace

TEST(Mesh, CheckRefusesInvertedAndDegenerate3DElements) {
  {
    Mesh m;
    addCube(m, "A");
    addTet(m, "T", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
    EXPECT_EQ(m.dim(), 3);
    EXPECT_NO_THROW(m.check());
  }
  {
    // Bottom and top layers swapped: the cube is inside out.
    Mesh m;
    addCube(m, "A");
    addCube(m, "B", {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const std::string e = inputErrorOf([&] { m.check(); });
    EXPECT_THAT(e, HasSubstr("element 1 of body 'B' (Hex8, first node 8 at (0, 0, 1)) is inverted (det J = -0.125"));
    EXPECT_THAT(e, HasSubstr("corners 0-3 must run counter-clockwise seen from corners 4-7"));
  }
  {
    // Corner 6 folded through the opposite face: only some corners invert.
    Mesh m;
    addCube(m, "A", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {-0.5, -0.5, -0.5}, {0, 1, 1}});
    EXPECT_THAT(inputErrorOf([&] { m.check(); }), HasSubstr("element 0 of body 'A' (Hex8"));
    EXPECT_THAT(inputErrorOf([&] { m.check(); }), HasSubstr("is inverted"));
  }
  {
    // Corner 6 moved onto corner 5: zero volume at corner 5.
    Mesh m;
    addCube(m, "A", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 1}, {0, 1, 1}});
    const std::string e = inputErrorOf([&] { m.check(); });
    EXPECT_THAT(e, HasSubstr("element 0 of body 'A'"));
    EXPECT_THAT(e, HasSubstr("is degenerate (det J = 0 at corner"));
    EXPECT_THAT(e, HasSubstr("zero volume there"));
  }
  {
    Mesh m;
    addTet(m, "T", {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}});  // corners 1 and 2 swapped
    const std::string e = inputErrorOf([&] { m.check(); });
    EXPECT_THAT(e, HasSubstr("element 0 of body 'T' (Tet4, first node 0 at (0, 0, 0)) is inverted (det J = -1 of"));
    EXPECT_THAT(e, HasSubstr("corners 0, 1, 2 must run counter-clockwise seen from corner 3"));
  }
  {
    Mesh m;
    addTet(m, "T", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});  // flat
    EXPECT_THAT(inputErrorOf([&] { m.check(); }), HasSubstr("element 0 of body 'T' (Tet4, first node 0 at (0, 0, 0)) is degenerate"));
  }
}

// DDC_CHECK guards invariants in every build type (the default build is
// Release): a node added before any body is a logic error naming the check,
// not a write past the end of the body list.
TEST(Mesh, InvariantChecksStayOnInEveryBuildType) {
  Mesh m;
  try {
    m.addNode(0.0, 0.0);
    FAIL() << "addNode before beginBody did not throw";
  } catch (const std::logic_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("check '!bodies_.empty()' failed: addNode before beginBody"));
  }
}

TEST(Mesh, PartKeepsIdsBodiesAndSets) {
  // Body A: two Quad4 side by side (nodes 0-5, elements 0-1); body B: one
  // Quad4 (nodes 6-9, element 2).
  Mesh m;
  m.beginBody("A", CellType::Quad4);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) m.addNode(i, j);
  const int e0[4] = {0, 1, 4, 3}, e1[4] = {1, 2, 5, 4};
  m.addElement(e0);
  m.addElement(e1);
  m.addSideSet(0, "bottom", {m.makeSegment(0, 0), m.makeSegment(1, 0)});
  m.addNodeSet(0, "left", {0, 3});
  addSquare(m, "B", 5.0);
  EXPECT_FALSE(m.isPart());
  EXPECT_EQ(m.nodeId(7), 7);
  EXPECT_EQ(m.localNode(7), 7);
  EXPECT_EQ(m.localNode(10), -1);

  const Mesh p = m.part({1, 2});
  EXPECT_TRUE(p.isPart());
  EXPECT_EQ(p.numGlobalNodes(), 10);
  EXPECT_EQ(p.numGlobalElements(), 3);
  ASSERT_EQ(p.numNodes(), 8);  // 1, 2, 4, 5 of A and all of B
  ASSERT_EQ(p.numElements(), 2);
  const std::vector<long long> ids = {1, 2, 4, 5, 6, 7, 8, 9};
  for (int n = 0; n < p.numNodes(); ++n) {
    EXPECT_EQ(p.nodeId(n), ids[n]);
    EXPECT_EQ(p.localNode(ids[n]), n);
    EXPECT_EQ(p.coord(n), m.coord(static_cast<int>(ids[n])));
  }
  EXPECT_EQ(p.localNode(0), -1);
  EXPECT_EQ(p.elementId(0), 1);
  EXPECT_EQ(p.elementId(1), 2);
  EXPECT_EQ(p.body(0).firstNode, 0);
  EXPECT_EQ(p.body(0).numNodes, 4);
  EXPECT_EQ(p.body(1).firstNode, 4);
  EXPECT_EQ(p.body(1).numNodes, 4);
  EXPECT_EQ(p.body(0).firstElement, 0);
  EXPECT_EQ(p.body(1).firstElement, 1);
  EXPECT_EQ(p.elementBody(1), 1);
  // Connectivity in local numbers: element 1 of the whole mesh is {1, 2, 5, 4}.
  EXPECT_THAT(std::vector<int>(p.elementNodes(0), p.elementNodes(0) + 4), ::testing::ElementsAre(0, 1, 3, 2));
  EXPECT_NO_THROW(p.checkConnectivity());
  // Sets restricted to what the part holds, in local numbers.
  EXPECT_TRUE(p.nodeSet("A/left").empty());
  EXPECT_THAT(p.nodeSet("A/bottom"), ::testing::ElementsAre(0, 1));  // nodes 1 and 2
  ASSERT_EQ(p.sideSet("A/bottom").size(), 1u);
  EXPECT_EQ(p.sideSet("A/bottom")[0].element, 0);
  EXPECT_EQ(p.sideSet("A/bottom")[0].nodes[0], 0);
  EXPECT_EQ(p.sideSet("A/bottom")[0].nodes[1], 1);

  // A part of a part keeps the whole mesh's ids; a body with no element
  // chosen stays, empty.
  const Mesh q = p.part({1});
  EXPECT_EQ(q.numNodes(), 4);
  EXPECT_EQ(q.nodeId(0), 6);
  EXPECT_EQ(q.elementId(0), 2);
  EXPECT_EQ(q.numGlobalNodes(), 10);
  EXPECT_EQ(q.body(0).numElements, 0);
  EXPECT_EQ(q.body(0).numNodes, 0);
  EXPECT_EQ(q.body(1).firstNode, 0);
  EXPECT_EQ(q.body(1).firstElement, 0);

  EXPECT_THROW(m.part({2, 1}), std::invalid_argument);
  EXPECT_THROW(m.part({3}), std::invalid_argument);
}
