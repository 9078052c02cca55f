// Parallel partitioning on 1-3 ranks: the distributed dual graph equals the
// serial facet graph, PT-Scotch's partition is valid, the same on every
// rank, in one piece per subdomain and within kEdgeCutOverMetis of METIS's
// edge cut, and the distributed clean-up (empty subdomains, detached
// pieces, edge cut) gives the serial one's result.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_ParallelPartition.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestRanks.hpp"

using ddc::CellType;
using ddc::Mesh;
using ::testing::HasSubstr;

namespace {

using ddc::test::rank;
using ddc::test::ranks;

/// The parallel partitioner's edge cut may exceed METIS's by at most this
/// factor (the target for the examples, doc/partitioning.md).
constexpr double kEdgeCutOverMetis = 1.2;
/// The largest subdomain may exceed the mean element count by at most this
/// factor: PT-Scotch's kPtScotchImbalance plus the pieces joined afterwards.
constexpr double kLargestOverMean = 1.10;


Mesh box(int nx, int ny, int nz, CellType t = CellType::Hex8) {
  Mesh m;
  Teuchos::ParameterList p;
  p.set("Elements X", nx);
  p.set("Elements Y", ny);
  p.set("Elements Z", nz);
  ddc::generateBox(m, "Block", t, p, "B");
  return m;
}

/// Two rectangles side by side that share no node: a disconnected dual graph.
Mesh twoRectangles(int nx, int ny) {
  Mesh m;
  for (int b = 0; b < 2; ++b) {
    Teuchos::ParameterList p;
    p.set("Elements X", nx);
    p.set("Elements Y", ny);
    p.set("Origin X", 1.5 * b);
    ddc::generateRectangle(m, b == 0 ? "Left" : "Right", CellType::Quad4, p, "R");
  }
  return m;
}

/// This rank's share of the elements as partitionPtScotch() takes it, and
/// the serial facet graph's rows for them (global ids, sorted).
void localShare(const Mesh& m, std::vector<long long>& offsets, std::vector<long long>& corners, long long& first,
                std::vector<std::vector<long long>>& expected) {
  const int ne = m.numElements();
  const int begin = int(static_cast<long long>(ne) * rank() / ranks());
  const int end = int(static_cast<long long>(ne) * (rank() + 1) / ranks());
  const auto nb = ddc::facetNeighbours(m);
  offsets.assign(1, 0);
  corners.clear();
  expected.clear();
  first = begin;
  for (int e = begin; e < end; ++e) {
    for (int k = 0; k < ddc::referenceCell(m.elementType(e)).numCorners; ++k) corners.push_back(m.elementNodes(e)[k]);
    offsets.push_back(static_cast<long long>(corners.size()));
    std::vector<long long> row(nb[e].begin(), nb[e].end());
    std::sort(row.begin(), row.end());
    expected.push_back(row);
  }
}

void expectDualGraphIsTheFacetGraph(const Mesh& m) {
  std::vector<long long> offsets, corners;
  std::vector<std::vector<long long>> expected;
  long long first = 0;
  localShare(m, offsets, corners, first, expected);
  const auto g = ddc::distributedDualGraph(MPI_COMM_WORLD, offsets, corners, ddc::dualGraphCommonCorners(m));
  ASSERT_EQ(g.firstVertex.size(), size_t(ranks() + 1));
  EXPECT_EQ(g.firstVertex[rank()], first);
  EXPECT_EQ(g.firstVertex.back(), m.numElements());
  ASSERT_EQ(g.numLocal(), static_cast<long long>(expected.size()));
  for (long long l = 0; l < g.numLocal(); ++l) {
    const std::vector<long long> row(g.neighbours.begin() + g.offsets[l], g.neighbours.begin() + g.offsets[l + 1]);
    EXPECT_EQ(row, expected[l]) << "element " << first + l;
  }
}

/// Every rank holds the same partition: the rank-0 copy compared everywhere.
bool sameOnEveryRank(const ddc::Partition& p) {
  std::vector<int> root(p.elementSubdomain);
  MPI_Bcast(root.data(), static_cast<int>(root.size()), MPI_INT, 0, MPI_COMM_WORLD);
  int same = root == p.elementSubdomain ? 1 : 0, all = 0;
  MPI_Allreduce(&same, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return all == 1;
}

/// Pieces of each subdomain through facets (1 everywhere on a connected mesh).
std::vector<int> pieceCounts(const Mesh& m, const ddc::Partition& p) {
  const auto nb = ddc::facetNeighbours(m);
  std::vector<int> seen(m.numElements(), 0), count(p.numSubdomains, 0), stack;
  for (int e0 = 0; e0 < m.numElements(); ++e0) {
    if (seen[e0]) continue;
    ++count[p.elementSubdomain[e0]];
    seen[e0] = 1;
    stack.assign(1, e0);
    while (!stack.empty()) {
      const int e = stack.back();
      stack.pop_back();
      for (int f : nb[e])
        if (!seen[f] && p.elementSubdomain[f] == p.elementSubdomain[e]) {
          seen[f] = 1;
          stack.push_back(f);
        }
    }
  }
  return count;
}

void expectGoodPartition(const Mesh& m, int parts, int expectedPieces = 1) {
  const ddc::Partition p = ddc::partitionPtScotch(m, parts, MPI_COMM_WORLD);
  const ddc::Partition metis = ddc::partitionMetis(m, parts);
  ASSERT_EQ(p.numSubdomains, parts);
  ASSERT_EQ(p.elementSubdomain.size(), size_t(m.numElements()));
  EXPECT_TRUE(sameOnEveryRank(p));
  std::vector<int> size(parts, 0);
  for (int s : p.elementSubdomain) {
    ASSERT_GE(s, 0);
    ASSERT_LT(s, parts);
    ++size[s];
  }
  EXPECT_GT(*std::min_element(size.begin(), size.end()), 0);
  const double mean = double(m.numElements()) / parts;
  std::vector<int> metisSize(parts, 0);
  for (int s : metis.elementSubdomain) ++metisSize[s];
  EXPECT_LE(*std::max_element(size.begin(), size.end()), kLargestOverMean * mean)
      << "METIS's largest: " << *std::max_element(metisSize.begin(), metisSize.end());
  const auto pieces = pieceCounts(m, p);
  EXPECT_EQ(*std::max_element(pieces.begin(), pieces.end()), expectedPieces);
  EXPECT_EQ(p.edgeCut, ddc::edgeCut(ddc::facetNeighbours(m), p));
  EXPECT_LE(double(p.edgeCut), kEdgeCutOverMetis * double(metis.edgeCut))
      << "PT-Scotch " << p.edgeCut << " against METIS " << metis.edgeCut;
}

}  // namespace

TEST(DistributedDualGraph, HexBoxIsTheFacetGraph) { expectDualGraphIsTheFacetGraph(box(6, 4, 3)); }

TEST(DistributedDualGraph, TetBoxIsTheFacetGraph) { expectDualGraphIsTheFacetGraph(box(3, 3, 2, CellType::Tet4)); }

TEST(DistributedDualGraph, TwoBodiesSideBySide) { expectDualGraphIsTheFacetGraph(twoRectangles(5, 3)); }

TEST(DistributedDualGraph, BadInputIsRefusedOnEveryRank) {
  std::vector<long long> offsets{0, 4}, corners{0, 1, 2, 3};
  if (rank() == ranks() - 1) corners[2] = -7;  // one rank's mistake
  try {
    ddc::distributedDualGraph(MPI_COMM_WORLD, offsets, corners, 2);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("corner node id -7 is negative"));
  }
  EXPECT_THROW(ddc::distributedDualGraph(MPI_COMM_WORLD, offsets, {0, 1, 2}, 2), std::invalid_argument);
  EXPECT_THROW(ddc::distributedDualGraph(MPI_COMM_WORLD, {0, 2}, {0, 1}, 0), std::invalid_argument);
}

TEST(PartitionPtScotch, HexBox) { expectGoodPartition(box(16, 4, 4), 15); }

// Subdomains of 64 elements, as block_3d's 2048 at Refinement 8 (with a few
// elements per subdomain one element is more than kLargestOverMean allows).
TEST(PartitionPtScotch, SubdomainsOfSixtyFourElements) { expectGoodPartition(box(32, 16, 8), 64); }

TEST(PartitionPtScotch, QuadRectangles) {
  Mesh m;
  Teuchos::ParameterList p;
  p.set("Elements X", 40);
  p.set("Elements Y", 10);
  ddc::generateRectangle(m, "Block", CellType::Quad4, p, "R");
  expectGoodPartition(m, 8);
}

TEST(PartitionPtScotch, TwoBodiesEachInTheirOwnSubdomains) {
  const Mesh m = twoRectangles(8, 4);
  const ddc::Partition p = ddc::partitionPtScotch(m, 4, MPI_COMM_WORLD);
  EXPECT_TRUE(sameOnEveryRank(p));
  const auto pieces = pieceCounts(m, p);
  // A subdomain may hold a piece of each body (they touch nowhere), never
  // two pieces of one body.
  EXPECT_LE(*std::max_element(pieces.begin(), pieces.end()), 2);
  std::vector<int> used(4, 0);
  for (int s : p.elementSubdomain) used[s] = 1;
  EXPECT_EQ(std::accumulate(used.begin(), used.end(), 0), 4);
}

TEST(PartitionPtScotch, TheSamePartitionOnEveryCallInOneProcess) {
  // Scotch's shared random generator went on from one call to the next.
  const Mesh m = box(6, 3, 2, CellType::Tet4);
  const ddc::Partition first = ddc::partitionPtScotch(m, 5, MPI_COMM_WORLD);
  for (int call = 0; call < 2; ++call)
    EXPECT_EQ(ddc::partitionPtScotch(m, 5, MPI_COMM_WORLD).elementSubdomain, first.elementSubdomain);
}

TEST(PartitionPtScotch, OneSubdomainAndErrors) {
  const Mesh m = box(2, 2, 2);
  const auto one = ddc::partitionPtScotch(m, 1, MPI_COMM_WORLD);
  EXPECT_EQ(one.elementSubdomain, std::vector<int>(8, 0));
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::partitionPtScotch(m, 9, MPI_COMM_WORLD); }),
              HasSubstr("'Partition/Number of Subdomains' (9) exceeds the number of elements of the mesh (8)"));
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::partitionPtScotch(m, 0, MPI_COMM_WORLD); }),
              HasSubstr("'Partition/Number of Subdomains' must be > 0, got 0"));
}

TEST(PartitionPtScotch, NeedsThreadMultipleOnSeveralRanks) {
  EXPECT_THAT(ddc::test::inputErrorOf([] { ddc::requirePtScotchThreadLevel(2, MPI_THREAD_SERIALIZED); }),
              HasSubstr("'Partition/Method' = PT-Scotch needs MPI initialised with MPI_THREAD_MULTIPLE"));
  EXPECT_NO_THROW(ddc::requirePtScotchThreadLevel(1, MPI_THREAD_SINGLE));
  EXPECT_NO_THROW(ddc::requirePtScotchThreadLevel(4, MPI_THREAD_MULTIPLE));
}

TEST(JoinDetachedPieces, MovesASplinterAndKeepsALargePiece) {
  Mesh m;
  Teuchos::ParameterList p;
  p.set("Elements X", 12);
  p.set("Elements Y", 1);
  ddc::generateRectangle(m, "Strip", CellType::Quad4, p, "R");
  const auto nb = ddc::facetNeighbours(m);
  ddc::Partition part;
  part.numSubdomains = 2;  // mean 6 elements: a splinter has at most 1.5
  part.elementSubdomain = {0, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0};  // element 0 is a splinter of subdomain 0
  ddc::joinDetachedPieces(nb, part);
  EXPECT_EQ(part.elementSubdomain, (std::vector<int>{1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(ddc::edgeCut(nb, part), 1);
  part.elementSubdomain = {0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0};  // a piece of 3: it stays
  const auto before = part.elementSubdomain;
  ddc::joinDetachedPieces(nb, part);
  EXPECT_EQ(part.elementSubdomain, before);
  EXPECT_EQ(ddc::edgeCut(nb, part), 2);
}

namespace {

/// The distributed clean-up of `whole` (the subdomain of every element,
/// the same on every rank) on each rank's even share equals the serial
/// clean-up of the whole, and so does the edge cut.
void expectDistributedCleanUpIsTheSerialOne(const Mesh& m, const ddc::Partition& whole) {
  std::vector<long long> offsets, corners;
  std::vector<std::vector<long long>> expected;
  long long first = 0;
  localShare(m, offsets, corners, first, expected);
  const auto g = ddc::distributedDualGraph(MPI_COMM_WORLD, offsets, corners, ddc::dualGraphCommonCorners(m));
  std::vector<int> mine(whole.elementSubdomain.begin() + first,
                        whole.elementSubdomain.begin() + first + g.numLocal());
  ddc::Partition serial = whole;
  const auto nb = ddc::facetNeighbours(m);
  ddc::fillEmptySubdomains(nb, serial);
  ddc::fillEmptySubdomains(MPI_COMM_WORLD, g, whole.numSubdomains, mine);
  const std::vector<int> filled(serial.elementSubdomain.begin() + first,
                                serial.elementSubdomain.begin() + first + g.numLocal());
  EXPECT_EQ(mine, filled) << "after filling empty subdomains";
  ddc::joinDetachedPieces(nb, serial);
  ddc::joinDetachedPieces(MPI_COMM_WORLD, g, whole.numSubdomains, mine);
  const std::vector<int> joined(serial.elementSubdomain.begin() + first,
                                serial.elementSubdomain.begin() + first + g.numLocal());
  EXPECT_EQ(mine, joined) << "after joining detached pieces";
  EXPECT_EQ(ddc::edgeCut(MPI_COMM_WORLD, g, mine), ddc::edgeCut(nb, serial));
}

/// Slabs along x with a few elements (chosen by the seed, the same on
/// every rank) moved to a random subdomain: splinters of every size, and
/// subdomain `empty` (if >= 0) left without elements.
ddc::Partition slabsWithSplinters(const Mesh& m, int numSubdomains, unsigned seed, int empty) {
  ddc::Partition p;
  p.numSubdomains = numSubdomains;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, numSubdomains - 1);
  std::bernoulli_distribution flip(0.08);
  double lo = 1e300, hi = -1e300;
  for (int n = 0; n < m.numNodes(); ++n) lo = std::min(lo, m.coord(n)[0]), hi = std::max(hi, m.coord(n)[0]);
  for (int e = 0; e < m.numElements(); ++e) {
    const double x = m.coord(m.elementNodes(e)[0])[0];
    int s = std::min(numSubdomains - 1, int((x - lo) / (hi - lo) * numSubdomains));
    if (flip(rng)) s = pick(rng);
    p.elementSubdomain.push_back(s);
  }
  for (int& s : p.elementSubdomain)
    if (s == empty) s = (empty + 1) % numSubdomains;
  return p;
}

}  // namespace

TEST(DistributedCleanUp, SplintersOfAHexBox) {
  const Mesh m = box(12, 4, 3);
  for (unsigned seed : {1u, 2u, 3u}) expectDistributedCleanUpIsTheSerialOne(m, slabsWithSplinters(m, 6, seed, -1));
}

TEST(DistributedCleanUp, EmptySubdomainsAndSplintersOfTets) {
  const Mesh m = box(4, 3, 3, CellType::Tet4);
  for (unsigned seed : {4u, 5u}) expectDistributedCleanUpIsTheSerialOne(m, slabsWithSplinters(m, 5, seed, 2));
  // Three empty subdomains filled in turn, each from the largest at the time.
  ddc::Partition p = slabsWithSplinters(m, 7, 6u, -1);
  for (int& s : p.elementSubdomain) s = s % 4;
  expectDistributedCleanUpIsTheSerialOne(m, p);
}

TEST(DistributedCleanUp, TwoBodiesWithPiecesThatTouchNoOtherSubdomain) {
  const Mesh m = twoRectangles(6, 4);
  for (unsigned seed : {7u, 8u}) expectDistributedCleanUpIsTheSerialOne(m, slabsWithSplinters(m, 4, seed, -1));
  // A random partition: many pieces, moves repeated over several passes.
  ddc::Partition p;
  p.numSubdomains = 3;
  std::mt19937 rng(9u);
  for (int e = 0; e < m.numElements(); ++e) p.elementSubdomain.push_back(int(rng() % 3));
  expectDistributedCleanUpIsTheSerialOne(m, p);
}

TEST(DistributedCleanUp, PartsOfTheWrongLengthAreRefusedOnEveryRank) {
  const Mesh m = box(4, 2, 2);
  std::vector<long long> offsets, corners;
  std::vector<std::vector<long long>> expected;
  long long first = 0;
  localShare(m, offsets, corners, first, expected);
  const auto g = ddc::distributedDualGraph(MPI_COMM_WORLD, offsets, corners, 4);
  std::vector<int> parts(g.numLocal() + (rank() == 0 ? 1 : 0), 0);
  EXPECT_THROW(ddc::joinDetachedPieces(MPI_COMM_WORLD, g, 2, parts), std::invalid_argument);
  std::vector<int> outOfRange(g.numLocal(), rank() == ranks() - 1 ? 5 : 0);
  EXPECT_THROW(ddc::fillEmptySubdomains(MPI_COMM_WORLD, g, 2, outOfRange), std::invalid_argument);
}
