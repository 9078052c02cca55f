// The FETI-DP primal nodes selected on parts of a mesh (Mesh::part(): each
// rank its subdomains' elements and their nodes) are those selected on the
// whole mesh, node by node (by id), with the same report: in 3-D with both
// vertex rules (every edge node; edge ends with the shared-face rule 2b),
// on METIS subdomains and on a chain of slabs whose faces are hinges, with
// and without the anchoring of rule 3; in 2-D; and a floating body refused
// on every rank with the whole mesh's message (doc/feti-dp.md, "Primal
// nodes"; doc/architecture.md, "What a distributed mesh has to change").
// On 1-3 ranks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <memory>
#include <string>
#include <vector>

#include "DDC_ElementFactory.hpp"
#include "DDC_Error.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_Model.hpp"
#include "DDC_Partition.hpp"
#include "DDC_Substructuring.hpp"

namespace {

using PL = Teuchos::ParameterList;

Teuchos::RCP<const Teuchos::Comm<int>> comm() { return Tpetra::getDefaultComm(); }

/// A body of nx x ny (x nz) unit-length elements named `name`, shifted
/// along x by `shiftX`.
void addBody(ddc::Mesh& mesh, const std::string& name, int dim, int nx, int ny, int nz, double shiftX = 0.0) {
  PL grid(dim == 3 ? "Box" : "Rectangle");
  grid.set("Elements X", nx);
  grid.set("Elements Y", ny);
  grid.set("Length X", double(nx));
  grid.set("Length Y", double(ny));
  grid.set("Origin X", shiftX);
  if (dim == 3) {
    grid.set("Elements Z", nz);
    grid.set("Length Z", double(nz));
    ddc::generateBox(mesh, name, ddc::CellType::Hex8, grid, "Box");
  } else {
    ddc::generateRectangle(mesh, name, ddc::CellType::Quad4, grid, "Rectangle");
  }
}

/// Every component of "Block/left" held (none if `fixed` is false; x of
/// "Block/right" is prescribed either way).
ddc::BoundaryConditions leftHeld(bool fixed, int dim) {
  ddc::BoundaryConditions bcs;
  ddc::DisplacementCondition pull;
  pull.name = "Pulled";
  pull.setName = "Block/right";
  pull.fix[1] = pull.fix[2] = false;
  pull.value[0] = 0.1;
  bcs.displacements = {pull};
  if (fixed) {
    ddc::DisplacementCondition held;
    held.name = "Held";
    held.setName = "Block/left";
    held.fix[2] = dim == 3;
    bcs.displacements.push_back(held);
  }
  return bcs;
}

/// Subdomains as slabs along x: element e in slab floor(centroid x / width).
ddc::Partition slabs(const ddc::Mesh& mesh, int count, double width) {
  ddc::Partition p;
  p.numSubdomains = count;
  for (int e = 0; e < mesh.numElements(); ++e) {
    double x = 0.0;
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) x += mesh.coord(mesh.elementNodes(e)[i])[0];
    p.elementSubdomain.push_back(std::min(count - 1, int(x / mesh.elementNumNodes(e) / width)));
  }
  return p;
}

/// The models on the whole mesh and on this rank's part of it, and the
/// selections made on them.
struct TwoSelections {
  std::shared_ptr<ddc::Mesh> whole, part;
  std::unique_ptr<ddc::Model> modelOnWhole, modelOnPart;
  std::vector<char> onWhole, onPart;
  std::vector<std::string> reportWhole, reportPart;

  void selectOnWhole(ddc::VertexRule rule, bool massive) {
    onWhole = ddc::selectPrimalNodes(*modelOnWhole, &reportWhole, rule, massive);
  }
  void selectOnPart(ddc::VertexRule rule, bool massive) {
    onPart = ddc::selectPrimalNodes(*modelOnPart, &reportPart, rule, massive);
  }
};

TwoSelections models(std::shared_ptr<ddc::Mesh> whole, const ddc::Partition& partition,
                     const ddc::BoundaryConditions& bcs) {
  TwoSelections t;
  t.whole = std::move(whole);
  ddc::RankPart own = ddc::rankPart(*t.whole, partition, comm()->getRank(), comm()->getSize());
  t.part = std::make_shared<ddc::Mesh>(std::move(own.mesh));
  PL el("Element");
  el.set("Type", std::string(t.whole->dim() == 3 ? "Hex8" : "Quad4"));
  el.sublist("Material").set("Type", std::string("Neo-Hookean"));
  std::vector<std::shared_ptr<const ddc::Element>> elements(
      size_t(t.whole->numBodies()), ddc::ElementFactory::withBuiltins().create(el, "Element"));
  t.modelOnWhole = std::make_unique<ddc::Model>(comm(), t.whole, elements, partition, bcs);
  t.modelOnPart = std::make_unique<ddc::Model>(comm(), t.part, elements, own.partition, bcs);
  return t;
}

TwoSelections select(std::shared_ptr<ddc::Mesh> whole, const ddc::Partition& partition,
                     const ddc::BoundaryConditions& bcs, ddc::VertexRule rule, bool massive = false) {
  TwoSelections t = models(std::move(whole), partition, bcs);
  t.selectOnWhole(rule, massive);
  t.selectOnPart(rule, massive);
  return t;
}

/// The same primal nodes by id, and the same report; `minPrimal` primal
/// nodes at least, so that the comparison is not between empty selections.
void expectSameSelection(const TwoSelections& t, int minPrimal) {
  ASSERT_EQ(t.onPart.size(), size_t(t.part->numNodes()));
  for (int n = 0; n < t.part->numNodes(); ++n)
    EXPECT_EQ(int(t.onPart[n]), int(t.onWhole[t.part->nodeId(n)])) << "node " << t.part->nodeId(n);
  EXPECT_EQ(t.reportPart, t.reportWhole);
  EXPECT_GE(std::count(t.onWhole.begin(), t.onWhole.end(), char(1)), minPrimal);
}

std::shared_ptr<ddc::Mesh> block(int dim) {
  auto mesh = std::make_shared<ddc::Mesh>();
  addBody(*mesh, "Block", dim, 8, 5, 4);
  return mesh;
}

TEST(PrimalSelectionOnPart, MetisSubdomainsEveryEdgeNode3d) {
  auto mesh = block(3);
  const auto t = select(mesh, ddc::partitionMetis(*mesh, 9), leftHeld(true, 3), ddc::VertexRule::EdgeNodes);
  expectSameSelection(t, 10);
}

TEST(PrimalSelectionOnPart, MetisSubdomainsEdgeEnds3d) {
  auto mesh = block(3);
  const auto t = select(mesh, ddc::partitionMetis(*mesh, 9), leftHeld(false, 3), ddc::VertexRule::EdgeEnds);
  expectSameSelection(t, 10);
}

TEST(PrimalSelectionOnPart, SlabsGetTheirHingesAndAnchorsFixed3d) {
  // Six slabs along x: their faces meet the mesh boundary in rings that
  // touch no vertex (two ends each), so rule 2b adds a third node per face;
  // without the held face the slabs need rule 3 too.
  auto mesh = block(3);
  for (bool held : {true, false}) {
    const auto t = select(mesh, slabs(*mesh, 6, 8.0 / 6), leftHeld(held, 3), ddc::VertexRule::EdgeEnds);
    expectSameSelection(t, 12);
  }
}

TEST(PrimalSelectionOnPart, MetisAndSlabSubdomains2d) {
  auto mesh = block(2);
  for (bool held : {true, false}) {
    expectSameSelection(select(mesh, ddc::partitionMetis(*mesh, 7), leftHeld(held, 2), ddc::VertexRule::EdgeNodes),
                        4);
    expectSameSelection(select(mesh, slabs(*mesh, 4, 2.0), leftHeld(held, 2), ddc::VertexRule::EdgeNodes), 3);
  }
}

/// Element e's subdomain from its centroid.
template <class F>
ddc::Partition byCentroid(const ddc::Mesh& mesh, int count, F subdomainAt) {
  ddc::Partition p;
  p.numSubdomains = count;
  for (int e = 0; e < mesh.numElements(); ++e) {
    double x[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < mesh.elementNumNodes(e); ++i)
      for (int c = 0; c < mesh.dim(); ++c) x[c] += mesh.coord(mesh.elementNodes(e)[i])[c] / mesh.elementNumNodes(e);
    p.elementSubdomain.push_back(subdomainAt(x[0], x[1], x[2]));
  }
  return p;
}

TEST(PrimalSelectionOnPart, EdgeLinkedOnlyByAnotherRanksElements3d) {
  // Around the vertical line x = 4, y = 3 three subdomains meet, A (0), B
  // (2) and C (3), C in the two quadrants y < 3 and A in one quadrant of the
  // first and third layers, B elsewhere; D (1) is the slab x < 1. The line's
  // inner nodes (z = 1, 2, 3) have one place {A, B, C} and form one class,
  // but no element of A joins z = 1 to z = 2: the rank of A, which decides
  // the class (its lowest subdomain), learns that link from the rank of B
  // and C (on 2 and 3 ranks A is on another rank than B and C).
  auto mesh = block(3);
  const auto partition = byCentroid(*mesh, 4, [](double x, double y, double z) {
    if (x < 1.0) return 1;
    if (y < 3.0) return 3;
    const int layer = int(z);
    if ((layer == 0 && x > 4.0) || (layer == 2 && x < 4.0)) return 0;
    return 2;
  });
  for (bool held : {true, false})
    expectSameSelection(select(mesh, partition, leftHeld(held, 3), ddc::VertexRule::EdgeEnds), 4);
}

TEST(PrimalSelectionOnPart, ScatteredSubdomains3d) {
  // Columns of 1 x 2 x 1 elements dealt to six subdomains at random (a
  // fixed linear congruential sequence per seed): places, edge classes and
  // the vertices that touch them in every arrangement, each decided on the
  // rank of its lowest subdomain from what the others send it.
  auto mesh = block(3);
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    const auto partition = byCentroid(*mesh, 6, [seed](double x, double y, double z) {
      unsigned h = seed * 2654435761u + unsigned(x) * 97u + unsigned(y / 2) * 131u + unsigned(z) * 17u;
      for (int i = 0; i < 3; ++i) h = h * 1103515245u + 12345u;
      return int((h >> 16) % 6);
    });
    for (auto rule : {ddc::VertexRule::EdgeEnds, ddc::VertexRule::EdgeNodes})
      expectSameSelection(select(mesh, partition, leftHeld(seed % 2 == 0, 3), rule, /*massive=*/true), 4);
  }
}

TEST(PrimalSelectionOnPart, IslandAnchorsSeenByTheSubdomainAroundThem2d) {
  // Two islands of 2 x 2 elements (subdomains 0 and 1) in a subdomain around
  // them (2), no prescribed displacement: rule 3 makes two nodes of each
  // island primal, and those four anchor the outer subdomain, which is
  // decided after them and on another rank (on 2 and 3 ranks).
  auto mesh = block(2);
  const auto partition = byCentroid(*mesh, 3, [](double x, double y, double) {
    if (y > 1.0 && y < 3.0 && x > 1.0 && x < 3.0) return 0;
    if (y > 1.0 && y < 3.0 && x > 5.0 && x < 7.0) return 1;
    return 2;
  });
  const auto t = select(mesh, partition, ddc::BoundaryConditions{}, ddc::VertexRule::EdgeNodes);
  expectSameSelection(t, 4);
  EXPECT_EQ(t.reportWhole.size(), 2u);  // the islands; the outer subdomain needs nothing
}

TEST(PrimalSelectionOnPart, FloatingBodyRefusedOnEveryRankOrReportedWithMass) {
  // A second body, its own subdomain (the last, on the last rank), with no
  // prescribed displacement and no interface: no primal node can fix it.
  auto mesh = block(3);
  addBody(*mesh, "Loose", 3, 2, 2, 2, 20.0);
  ddc::Partition partition = slabs(*mesh, 5, 2.0);  // the block in four slabs
  for (int e = 0; e < mesh->numElements(); ++e)
    if (mesh->elementBody(e) == 1) partition.elementSubdomain[e] = 4;
  TwoSelections t = models(mesh, partition, leftHeld(true, 3));
  std::string wholeMessage, partMessage;
  try {
    t.selectOnWhole(ddc::VertexRule::EdgeEnds, false);
  } catch (const ddc::InputError& e) {
    wholeMessage = e.what();
  }
  try {
    t.selectOnPart(ddc::VertexRule::EdgeEnds, false);
  } catch (const ddc::InputError& e) {
    partMessage = e.what();
  }
  EXPECT_THAT(wholeMessage, ::testing::HasSubstr("subdomain 4 (body 'Loose') is floating"));
  EXPECT_EQ(partMessage, wholeMessage);  // on every rank
  t.selectOnWhole(ddc::VertexRule::EdgeEnds, true);
  t.selectOnPart(ddc::VertexRule::EdgeEnds, true);
  expectSameSelection(t, 8);
  EXPECT_THAT(t.reportPart, ::testing::Contains(::testing::HasSubstr("subdomain 4 floats")));
}

}  // namespace

