// Mesh::migrated(): every rank sends its elements to the ranks of their
// subdomains, with their nodes and set memberships, and each rank gets the
// part of the whole mesh it would cut out itself (Mesh::part()), from a
// whole mesh on rank 0 or from even ranges of elements on every rank, and
// scattered in even ranges from the one rank that holds it. On
// 1-3 ranks, a mesh of a Hex8 and a Hex20 body (two cell types, sets of
// both kinds), METIS's subdomains spread over the ranks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <numeric>
#include <set>
#include <stdexcept>
#include <tuple>

#include "DDC_MeshGenerators.hpp"
#include "DDC_MeshPartCompare.hpp"
#include "DDC_Partition.hpp"
#include "DDC_TestRanks.hpp"

namespace {

using ddc::test::rank;
using ddc::test::ranks;

using PL = Teuchos::ParameterList;
using ddc::Mesh;
using ddc::test::expectSameParts;


Mesh twoBodies() {
  Mesh mesh;
  PL a("Box");
  a.set("Elements X", 4);
  a.set("Elements Y", 3);
  a.set("Elements Z", 2);
  ddc::generateBox(mesh, "Lower", ddc::CellType::Hex8, a, "Box");
  PL b("Box");
  b.set("Elements X", 2);
  b.set("Elements Y", 2);
  b.set("Elements Z", 1);
  b.set("Origin Z", 2.5);
  ddc::generateBox(mesh, "Upper", ddc::CellType::Hex20, b, "Box");
  return mesh;
}

/// The rank of each element of `whole`: METIS's subdomains (twice as many
/// as ranks) in contiguous blocks.
std::vector<int> ranksOfElements(const Mesh& whole) {
  const ddc::Partition p = ddc::partitionMetis(whole, 2 * ranks());
  const std::vector<int> owner = ddc::subdomainOwnerRank(p.numSubdomains, ranks());
  std::vector<int> r(whole.numElements());
  for (int e = 0; e < whole.numElements(); ++e) r[e] = owner[p.elementSubdomain[e]];
  return r;
}

/// The elements of `whole` that go to this rank.
std::vector<int> mine(const std::vector<int>& rankOf) {
  std::vector<int> out;
  for (int e = 0; e < static_cast<int>(rankOf.size()); ++e)
    if (rankOf[e] == rank()) out.push_back(e);
  return out;
}

TEST(MeshMigrate, FromAWholeMeshOnRankZero) {
  const Mesh whole = twoBodies();
  const std::vector<int> rankOf = ranksOfElements(whole);
  // Rank 0 holds the whole mesh (as a part holding every element), the
  // others nothing.
  std::vector<int> held;
  if (rank() == 0) held.resize(whole.numElements()), std::iota(held.begin(), held.end(), 0);
  const Mesh source = whole.part(held);
  std::vector<int> destination;
  for (int e : held) destination.push_back(rankOf[e]);
  expectSameParts(source.migrated(MPI_COMM_WORLD, destination), whole.part(mine(rankOf)));
}

TEST(MeshMigrate, FromEvenRangesOfElements) {
  const Mesh whole = twoBodies();
  const std::vector<int> rankOf = ranksOfElements(whole);
  const int ne = whole.numElements();
  std::vector<int> range;
  for (int e = ne * rank() / ranks(); e < ne * (rank() + 1) / ranks(); ++e) range.push_back(e);
  const Mesh source = whole.part(range);
  std::vector<int> destination;
  for (int e : range) destination.push_back(rankOf[e]);
  const Mesh got = source.migrated(MPI_COMM_WORLD, destination);
  expectSameParts(got, whole.part(mine(rankOf)));
  // A part of a part migrates again: back to the ranges.
  std::vector<int> back;
  for (int e = 0; e < got.numElements(); ++e) {
    int r = 0;  // the rank whose range [ne r / P, ne (r + 1) / P) holds the element
    while (got.elementId(e) >= ne * (r + 1) / ranks()) ++r;
    back.push_back(r);
  }
  expectSameParts(got.migrated(MPI_COMM_WORLD, back), source);
}

TEST(MeshMigrate, ScatteredInRangesFromTheOnlyRankThatHoldsTheMesh) {
  // Rank 0 alone holds the whole mesh; every rank gets the part of its even
  // range of element ids, the bodies' and sets' names and the whole sizes
  // included, and no other rank ever held the whole mesh.
  const Mesh whole = twoBodies();
  const int ne = whole.numElements();
  std::vector<int> range;
  for (int e = ne * rank() / ranks(); e < ne * (rank() + 1) / ranks(); ++e) range.push_back(e);
  for (int root : {0, ranks() - 1}) {
    const Mesh got = Mesh::scatteredInRanges(MPI_COMM_WORLD, root, rank() == root ? &whole : nullptr);
    expectSameParts(got, whole.part(range));
    EXPECT_EQ(got.numGlobalNodes(), whole.numNodes());
    EXPECT_EQ(got.numGlobalElements(), whole.numElements());
    for (int b = 0; b < whole.numBodies(); ++b) {
      EXPECT_EQ(got.body(b).name, whole.body(b).name);
      EXPECT_EQ(got.bodyGlobalNodes(b), whole.body(b).numNodes);
      EXPECT_EQ(got.bodyGlobalElements(b), whole.body(b).numElements);
    }
    EXPECT_EQ(got.nodeSetNames(), whole.nodeSetNames());
    EXPECT_EQ(got.sideSetNames(), whole.sideSetNames());
  }
  // A root without a whole mesh: refused on every rank (no rank waits).
  EXPECT_THROW(Mesh::scatteredInRanges(MPI_COMM_WORLD, 0, nullptr), std::logic_error);
}

TEST(MeshMigrate, RefusesADestinationPerElementThatIsNot) {
  const Mesh whole = twoBodies();
  EXPECT_THROW(whole.migrated(MPI_COMM_WORLD, {0}), std::invalid_argument);
  EXPECT_THROW(whole.migrated(MPI_COMM_WORLD, std::vector<int>(whole.numElements(), ranks())), std::invalid_argument);
}

TEST(MeshMigrate, RankPartFromEvenRangesWithTheirSubdomains) {
  // Every rank holds an even range of elements and their subdomains, as a
  // generator by range and a parallel partitioner leave them; each element
  // goes to the rank of its subdomain with its subdomain: the rankPart() of
  // the whole mesh under the whole partition.
  const Mesh whole = twoBodies();
  const ddc::Partition partition = ddc::partitionMetis(whole, 2 * ranks());
  const int ne = whole.numElements();
  std::vector<int> range;
  ddc::Partition ofRange;
  ofRange.numSubdomains = partition.numSubdomains;
  for (int e = ne * rank() / ranks(); e < ne * (rank() + 1) / ranks(); ++e) {
    range.push_back(e);
    ofRange.elementSubdomain.push_back(partition.elementSubdomain[e]);
  }
  const ddc::RankPart got = ddc::migratedRankPart(MPI_COMM_WORLD, whole.part(range), ofRange);
  const ddc::RankPart want = ddc::rankPart(whole, partition, rank(), ranks());
  expectSameParts(got.mesh, want.mesh);
  EXPECT_EQ(got.partition.numSubdomains, want.partition.numSubdomains);
  EXPECT_EQ(got.partition.elementSubdomain, want.partition.elementSubdomain);
  ofRange.elementSubdomain.push_back(0);  // one subdomain too many, on every rank
  EXPECT_THROW(ddc::migratedRankPart(MPI_COMM_WORLD, whole.part(range), ofRange), std::invalid_argument);
}

}  // namespace
