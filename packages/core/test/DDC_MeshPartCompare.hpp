// Comparing two parts of a mesh (Mesh::part()) in core unit tests: the
// same ids, coordinates (bit for bit), connectivity, bodies and sets.
#pragma once

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <tuple>

#include "DDC_Mesh.hpp"

namespace ddc::test {

/// Node and side sets by ids: (set, node id) and (set, element id, side).
inline std::set<std::tuple<std::string, long long, int>> setsById(const Mesh& m) {
  std::set<std::tuple<std::string, long long, int>> out;
  for (const auto& name : m.nodeSetNames())
    for (int n : m.nodeSet(name)) out.insert({name, m.nodeId(n), -1});
  for (const auto& name : m.sideSetNames())
    for (const auto& s : m.sideSet(name)) out.insert({name + " (sides)", m.elementId(s.element), s.localSide});
  return out;
}

/// `got` is `want`: ids, coordinates, connectivity by id, bodies and sets.
inline void expectSameParts(const Mesh& got, const Mesh& want) {
  ASSERT_TRUE(got.isPart());
  EXPECT_EQ(got.numGlobalNodes(), want.numGlobalNodes());
  EXPECT_EQ(got.numGlobalElements(), want.numGlobalElements());
  ASSERT_EQ(got.numNodes(), want.numNodes());
  ASSERT_EQ(got.numElements(), want.numElements());
  for (int n = 0; n < got.numNodes(); ++n) {
    EXPECT_EQ(got.nodeId(n), want.nodeId(n));
    EXPECT_EQ(got.coord(n), want.coord(n)) << "node " << got.nodeId(n);
  }
  for (int e = 0; e < got.numElements(); ++e) {
    EXPECT_EQ(got.elementId(e), want.elementId(e));
    EXPECT_EQ(got.elementBody(e), want.elementBody(e));
    ASSERT_EQ(got.elementNumNodes(e), want.elementNumNodes(e));
    for (int i = 0; i < got.elementNumNodes(e); ++i)
      EXPECT_EQ(got.elementNodes(e)[i], want.elementNodes(e)[i]) << "element " << got.elementId(e);
  }
  for (int b = 0; b < got.numBodies(); ++b) {
    EXPECT_EQ(got.body(b).firstNode, want.body(b).firstNode) << got.body(b).name;
    EXPECT_EQ(got.body(b).numNodes, want.body(b).numNodes) << got.body(b).name;
    EXPECT_EQ(got.body(b).firstElement, want.body(b).firstElement) << got.body(b).name;
    EXPECT_EQ(got.body(b).numElements, want.body(b).numElements) << got.body(b).name;
  }
  EXPECT_EQ(got.nodeSetNames(), want.nodeSetNames());
  EXPECT_EQ(got.sideSetNames(), want.sideSetNames());
  EXPECT_EQ(setsById(got), setsById(want));
}

}  // namespace ddc::test
