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
