// Element partitions (METIS, by body) and the subdomain -> rank map.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <set>

#include "DDC_Error.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_Partition.hpp"
#include "DDC_TestErrors.hpp"

using ddc::CellType;
using ddc::InputError;
using ddc::Mesh;
using ::testing::HasSubstr;

namespace {

using ddc::test::inputErrorOf;

Mesh rectangle(int nx, int ny, CellType t = CellType::Quad4, const std::string& name = "Block",
               Mesh m = Mesh(), double x0 = 0.0) {
  Teuchos::ParameterList p;
  p.set("Elements X", nx);
  p.set("Elements Y", ny);
  p.set("Origin X", x0);
  ddc::generateRectangle(m, name, t, p, "R");
  return m;
}

std::vector<int> partSizes(const ddc::Partition& p) {
  std::vector<int> n(p.numSubdomains, 0);
  for (int s : p.elementSubdomain) {
    EXPECT_GE(s, 0);
    EXPECT_LT(s, p.numSubdomains);
    if (s >= 0 && s < p.numSubdomains) ++n[s];
  }
  return n;
}

/// Number of connected pieces (through shared edges) of each subdomain.
std::vector<int> pieces(const Mesh& m, const ddc::Partition& p) {
  std::map<std::pair<int, int>, std::vector<int>> byEdge;
  for (int e = 0; e < m.numElements(); ++e)
    for (int s = 0; s < 4; ++s) {
      const int a = m.elementNodes(e)[s], b = m.elementNodes(e)[(s + 1) % 4];
      byEdge[{std::min(a, b), std::max(a, b)}].push_back(e);
    }
  std::vector<int> parent(m.numElements());
  for (int e = 0; e < m.numElements(); ++e) parent[e] = e;
  std::function<int(int)> find = [&](int e) { return parent[e] == e ? e : parent[e] = find(parent[e]); };
  for (const auto& kv : byEdge)
    for (size_t k = 1; k < kv.second.size(); ++k) {
      const int a = kv.second[0], b = kv.second[k];
      if (p.elementSubdomain[a] == p.elementSubdomain[b]) parent[find(a)] = find(b);
    }
  std::vector<std::set<int>> roots(p.numSubdomains);
  for (int e = 0; e < m.numElements(); ++e) roots[p.elementSubdomain[e]].insert(find(e));
  std::vector<int> n;
  for (const auto& r : roots) n.push_back(static_cast<int>(r.size()));
  return n;
}

}  // namespace

TEST(Partition, MetisFourPartsOfEightByEight) {
  const Mesh m = rectangle(8, 8);
  const auto p = ddc::partitionMetis(m, 4);
  EXPECT_EQ(p.numSubdomains, 4);
  ASSERT_EQ(p.elementSubdomain.size(), 64u);
  for (int n : partSizes(p)) EXPECT_EQ(n, 16);  // a balanced split exists and METIS finds it
  for (int n : pieces(m, p)) EXPECT_EQ(n, 1);   // contiguous
  // Deterministic.
  EXPECT_EQ(ddc::partitionMetis(m, 4).elementSubdomain, p.elementSubdomain);
}

TEST(Partition, Quad9PartitionedLikeQuad4) {
  const Mesh q4 = rectangle(6, 5), q9 = rectangle(6, 5, CellType::Quad9);
  for (int k : {2, 3, 5, 7})
    EXPECT_EQ(ddc::partitionMetis(q4, k).elementSubdomain, ddc::partitionMetis(q9, k).elementSubdomain) << k;
}

TEST(Partition, EveryPartNonEmptyUpToOneElementEach) {
  for (int nx : {1, 2, 3, 5}) {
    const Mesh m = rectangle(nx, 3);
    for (int k = 1; k <= m.numElements(); ++k) {
      const auto p = ddc::partitionMetis(m, k);
      ASSERT_EQ(static_cast<int>(p.elementSubdomain.size()), m.numElements());
      for (int n : partSizes(p)) EXPECT_GT(n, 0) << nx << "x3 mesh into " << k << " parts";
    }
  }
}

TEST(Partition, SeveralBodies) {
  Mesh m = rectangle(4, 4, CellType::Quad4, "A");
  m = rectangle(4, 4, CellType::Quad9, "B", std::move(m), 2.0);
  const auto byBody = ddc::partitionByBody(m);
  EXPECT_EQ(byBody.numSubdomains, 2);
  for (int e = 0; e < m.numElements(); ++e) EXPECT_EQ(byBody.elementSubdomain[e], e < 16 ? 0 : 1);
  const auto p = ddc::partitionMetis(m, 4);
  for (int n : partSizes(p)) EXPECT_EQ(n, 8);
}

TEST(Partition, BodyInTwoPieces) {
  // One body of four elements sharing no nodes (a disconnected dual graph):
  // METIS fails when asked for contiguous parts here; the partition must work.
  Mesh m;
  m.beginBody("Split", CellType::Quad4);
  for (double x0 : {0.0, 3.0})
    for (int j = 0; j < 2; ++j) {
      int n[4];
      const double xy[4][2] = {{x0, 1.0 * j}, {x0 + 1, 1.0 * j}, {x0 + 1, j + 1.0}, {x0, j + 1.0}};
      for (int k = 0; k < 4; ++k) n[k] = m.addNode(xy[k][0], xy[k][1]);
      m.addElement(n);
    }
  for (int k : {2, 3, 4}) {
    const auto p = ddc::partitionMetis(m, k);
    for (int n : partSizes(p)) EXPECT_GT(n, 0);
  }
}

TEST(Partition, Errors) {
  const Mesh m = rectangle(2, 2);
  EXPECT_THAT(inputErrorOf([&] { ddc::partitionMetis(m, 0); }),
              HasSubstr("'Partition/Number of Subdomains' must be > 0, got 0"));
  EXPECT_THAT(inputErrorOf([&] { ddc::partitionMetis(m, -2); }), HasSubstr("must be > 0"));
  EXPECT_THAT(inputErrorOf([&] { ddc::partitionMetis(m, 5); }),
              HasSubstr("'Partition/Number of Subdomains' (5) exceeds the number of elements of the mesh (4)"));
  const auto one = ddc::partitionMetis(m, 1);
  EXPECT_EQ(one.numSubdomains, 1);
  EXPECT_EQ(one.elementSubdomain, std::vector<int>(4, 0));
}

TEST(Partition, RankPartsHoldEachElementOnceWithItsSubdomain) {
  // Five METIS subdomains of a 6 x 4 rectangle over two ranks (0-2 on rank
  // 0, 3-4 on rank 1): each element in exactly one rank's part, with its
  // subdomain, and only subdomains of that rank.
  const Mesh m = rectangle(6, 4);
  const ddc::Partition p = ddc::partitionMetis(m, 5);
  std::vector<int> seen(m.numElements(), 0);
  for (int rank = 0; rank < 2; ++rank) {
    const ddc::RankPart own = ddc::rankPart(m, p, rank, 2);
    ASSERT_TRUE(own.mesh.isPart());
    ASSERT_EQ(own.partition.elementSubdomain.size(), size_t(own.mesh.numElements()));
    EXPECT_EQ(own.partition.numSubdomains, 5);
    for (int e = 0; e < own.mesh.numElements(); ++e) {
      const auto id = own.mesh.elementId(e);
      ++seen[id];
      EXPECT_EQ(own.partition.elementSubdomain[e], p.elementSubdomain[id]);
      EXPECT_EQ(ddc::subdomainOwnerRank(5, 2)[own.partition.elementSubdomain[e]], rank);
    }
  }
  EXPECT_EQ(seen, std::vector<int>(m.numElements(), 1));
}

TEST(Partition, SubdomainOwnerRank) {
  EXPECT_EQ(ddc::subdomainOwnerRank(4, 4), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(ddc::subdomainOwnerRank(5, 2), (std::vector<int>{0, 0, 0, 1, 1}));
  EXPECT_EQ(ddc::subdomainOwnerRank(9, 4), (std::vector<int>{0, 0, 0, 1, 1, 2, 2, 3, 3}));
  EXPECT_EQ(ddc::subdomainOwnerRank(3, 1), (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(ddc::subdomainsOfRank(9, 4, 0), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(ddc::subdomainsOfRank(9, 4, 3), (std::vector<int>{7, 8}));
  EXPECT_THAT(inputErrorOf([] { ddc::subdomainOwnerRank(2, 3); }),
              HasSubstr("'Partition/Number of Subdomains' (2) must be at least the number of MPI ranks (3)"));
  EXPECT_THAT(inputErrorOf([] { ddc::subdomainOwnerRank(2, 0); }), HasSubstr("ranks must be >= 1"));
}
