// requireSupportedBodies() on parts of a mesh (Mesh::part(), each rank its
// subdomains' elements and their nodes): the ranks take their prescribed
// nodes together and give the whole mesh's verdict, with its message, on
// every rank: held faces, a line of nodes (collinear), two nodes, a
// missing direction, in 3-D and 2-D. On 1-3 ranks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <memory>
#include <string>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_ModelSetUp.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_Partition.hpp"
#include "DDC_TestRanks.hpp"

namespace {

using ddc::test::rank;
using ddc::test::ranks;

using PL = Teuchos::ParameterList;

MPI_Comm world() { return ddc::rawComm(Tpetra::getDefaultComm()); }

/// An 8 x 5 (x 4) block of unit elements with a node set "Block/edge": the
/// nodes on x = 0, y = 0 (a line).
ddc::Mesh block(int dim) {
  ddc::Mesh mesh;
  PL grid(dim == 3 ? "Box" : "Rectangle");
  grid.set("Elements X", 8);
  grid.set("Elements Y", 5);
  grid.set("Length X", 8.0);
  grid.set("Length Y", 5.0);
  if (dim == 3) {
    grid.set("Elements Z", 4);
    grid.set("Length Z", 4.0);
    ddc::generateBox(mesh, "Block", ddc::CellType::Hex8, grid, "Box");
  } else {
    ddc::generateRectangle(mesh, "Block", ddc::CellType::Quad4, grid, "Rectangle");
  }
  std::vector<int> edge;
  for (int n = 0; n < mesh.numNodes(); ++n)
    if (mesh.coord(n)[0] == 0.0 && mesh.coord(n)[1] == 0.0) edge.push_back(n);
  mesh.addNodeSet(0, "edge", edge);
  return mesh;
}

ddc::BoundaryConditions held(const std::string& set, bool fixZ) {
  ddc::BoundaryConditions bcs;
  ddc::DisplacementCondition d;
  d.name = "Held";
  d.setName = set;
  d.fix[2] = fixZ;
  bcs.displacements.push_back(d);
  return bcs;
}

/// The message requireSupportedBodies() gives ("" if none).
std::string verdict(const ddc::Mesh& mesh, const ddc::BoundaryConditions& bcs, MPI_Comm comm) {
  try {
    ddc::requireSupportedBodies(mesh, bcs, ddc::ContactOptions{}, /*feti=*/false, /*dynamic=*/false, comm);
  } catch (const ddc::InputError& e) {
    return e.what();
  }
  return "";
}

void expectSameVerdicts(int dim, const std::vector<std::pair<ddc::BoundaryConditions, bool>>& cases) {
  ddc::Mesh whole = block(dim);
  const ddc::Partition partition = ddc::partitionMetis(whole, 2 * ranks() + 1);
  // "Block/shared": one node that the parts of two ranks hold (on more than
  // one rank), to be counted once.
  const std::vector<int> rankOf = ddc::subdomainOwnerRank(partition.numSubdomains, ranks());
  std::vector<int> firstRank(whole.numNodes(), -1), shared;
  for (int e = 0; e < whole.numElements() && shared.empty(); ++e)
    for (int i = 0; i < whole.elementNumNodes(e); ++i) {
      const int n = whole.elementNodes(e)[i], r = rankOf[partition.elementSubdomain[e]];
      if (firstRank[n] >= 0 && firstRank[n] != r) shared = {n};
      if (firstRank[n] < 0) firstRank[n] = r;
    }
  if (shared.empty()) shared = {0};
  whole.addNodeSet(0, "shared", shared);
  const ddc::RankPart own = ddc::rankPart(whole, partition, rank(), ranks());
  for (const auto& [bcs, supported] : cases) {
    SCOPED_TRACE(bcs.displacements.front().setName);
    const std::string onWhole = verdict(whole, bcs, MPI_COMM_SELF);
    EXPECT_EQ(onWhole.empty(), supported) << onWhole;
    EXPECT_EQ(verdict(own.mesh, bcs, world()), onWhole);
  }
}

TEST(SupportedBodiesOnPart, SameVerdictAsTheWholeMesh3d) {
  expectSameVerdicts(3, {{held("Block/left", true), true},
                         {held("Block/left", false), false},  // z free
                         {held("Block/edge", true), false},   // a line
                         {held("Block/bottom left back", true), false},
                         {held("Block/bottom", true), true}});
}

TEST(SupportedBodiesOnPart, SameVerdictAsTheWholeMesh2d) {
  expectSameVerdicts(2, {{held("Block/left", false), true},
                         {held("Block/bottom left", false), false},  // one node
                         {held("Block/top", false), true},
                         {held("Block/shared", false), false}});  // one node, on two ranks' parts
}

}  // namespace
