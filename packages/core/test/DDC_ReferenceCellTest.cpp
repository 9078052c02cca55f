// Reference cells (packages/core/src/DDC_ReferenceCell.hpp): node positions
// in Gmsh order, edges, facets with outward orientation, VTK permutations.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <map>
#include <set>

#include "DDC_Mesh.hpp"
#include "DDC_ReferenceCell.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

using ddc::CellType;
using ddc::ReferenceCell;
using ddc::referenceCell;
using ::testing::HasSubstr;

namespace {

using ddc::test::inputErrorOf;
using ddc::test::kRoundoff;

const std::vector<CellType> kAllTypes = {CellType::Quad4, CellType::Quad9, CellType::Hex8,  CellType::Hex20,
                                         CellType::Hex27, CellType::Tet4,  CellType::Tet10, CellType::Line2,
                                         CellType::Line3, CellType::Tri3,  CellType::Tri6,  CellType::Quad8};

Eigen::Vector3d at(const ReferenceCell& c, int i) { return Eigen::Vector3d(c.nodes[i][0], c.nodes[i][1], c.nodes[i][2]); }

Eigen::Vector3d centroid(const ReferenceCell& c, const std::vector<int>& nodes, int count) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (int i = 0; i < count; ++i) m += at(c, nodes[i]) / count;
  return m;
}

class EveryCell : public ::testing::TestWithParam<CellType> {};

TEST_P(EveryCell, TableIsConsistent) {
  const ReferenceCell& c = referenceCell(GetParam());
  EXPECT_EQ(c.type, GetParam());
  EXPECT_EQ(static_cast<int>(c.nodes.size()), c.numNodes);
  EXPECT_EQ(ddc::numCellNodes(c.type), c.numNodes);
  EXPECT_EQ(ddc::cellDimension(c.type), c.dim);
  // The VTK order is a permutation of the nodes.
  std::vector<int> p = c.vtkOrder;
  std::sort(p.begin(), p.end());
  for (int i = 0; i < c.numNodes; ++i) ASSERT_EQ(p.at(i), i) << c.name;
  // Nodes are distinct.
  for (int i = 0; i < c.numNodes; ++i)
    for (int j = i + 1; j < c.numNodes; ++j) EXPECT_GT((at(c, i) - at(c, j)).norm(), 0.1) << c.name << " " << i << " " << j;
}

TEST_P(EveryCell, EdgeMiddlesAreAtEdgeMidpoints) {
  const ReferenceCell& c = referenceCell(GetParam());
  for (const auto& e : c.edges) {
    ASSERT_LT(e.start, c.numCorners);
    ASSERT_LT(e.end, c.numCorners);
    if (e.middle < 0) continue;
    EXPECT_LT((at(c, e.middle) - (at(c, e.start) + at(c, e.end)) / 2).norm(), kRoundoff)
        << c.name << " edge " << e.start << "-" << e.end;
  }
}

TEST_P(EveryCell, FacetsAreOrientedOutwardAndMatchTheirReferenceCells) {
  const ReferenceCell& c = referenceCell(GetParam());
  if (c.dim == 1) {
    EXPECT_TRUE(c.facets.empty());
    return;
  }
  const Eigen::Vector3d cc = centroid(c, [&] {
    std::vector<int> v(c.numCorners);
    for (int i = 0; i < c.numCorners; ++i) v[i] = i;
    return v;
  }(), c.numCorners);
  std::map<std::vector<int>, int> edgeUses;
  for (const auto& f : c.facets) {
    const ReferenceCell& fc = referenceCell(f.type);
    ASSERT_EQ(fc.dim, c.dim - 1) << c.name;
    ASSERT_EQ(static_cast<int>(f.nodes.size()), fc.numNodes) << c.name;
    const Eigen::Vector3d fm = centroid(c, f.nodes, fc.numCorners);
    Eigen::Vector3d n;
    if (c.dim == 2) {
      const Eigen::Vector3d t = at(c, f.nodes[1]) - at(c, f.nodes[0]);
      n = Eigen::Vector3d(t.y(), -t.x(), 0);
    } else {
      n = (at(c, f.nodes[1]) - at(c, f.nodes[0])).cross(at(c, f.nodes[fc.numCorners - 1]) - at(c, f.nodes[0]));
    }
    EXPECT_GT(n.dot(fm - cc), 0.0) << c.name << ": a facet is oriented inward";
    // Higher-order facet nodes sit where the facet's own reference cell puts
    // them: edge middles at their edges' midpoints, a centre at the centroid.
    for (const auto& fe : fc.edges) {
      if (fe.middle >= 0)
        EXPECT_LT((at(c, f.nodes[fe.middle]) - (at(c, f.nodes[fe.start]) + at(c, f.nodes[fe.end])) / 2).norm(),
                  kRoundoff)
            << c.name;
      std::vector<int> key = {f.nodes[fe.start], f.nodes[fe.end]};
      std::sort(key.begin(), key.end());
      ++edgeUses[key];
    }
    if (f.type == CellType::Quad9) EXPECT_LT((at(c, f.nodes[8]) - fm).norm(), kRoundoff) << c.name;
  }
  // A closed surface: in 3-D every cell edge belongs to exactly two faces.
  if (c.dim == 3) {
    EXPECT_EQ(edgeUses.size(), c.edges.size()) << c.name;
    for (const auto& kv : edgeUses) EXPECT_EQ(kv.second, 2) << c.name;
  }
}

INSTANTIATE_TEST_SUITE_P(ReferenceCells, EveryCell, ::testing::ValuesIn(kAllTypes),
                         [](const auto& info) { return std::string(ddc::cellTypeName(info.param)); });

// Gmsh's documented positions ("Node ordering" in the Gmsh manual): the
// nodes whose numbering is easy to get wrong.
TEST(ReferenceCell, GmshNodePositions) {
  auto pos = [](CellType t, int i) { return at(referenceCell(t), i); };
  EXPECT_EQ(pos(CellType::Hex20, 9), Eigen::Vector3d(-1, 0, -1));   // edge 0-3
  EXPECT_EQ(pos(CellType::Hex20, 10), Eigen::Vector3d(-1, -1, 0));  // edge 0-4
  EXPECT_EQ(pos(CellType::Hex20, 11), Eigen::Vector3d(1, 0, -1));   // edge 1-2
  EXPECT_EQ(pos(CellType::Hex20, 17), Eigen::Vector3d(-1, 0, 1));   // edge 4-7
  EXPECT_EQ(pos(CellType::Hex27, 20), Eigen::Vector3d(0, 0, -1));
  EXPECT_EQ(pos(CellType::Hex27, 21), Eigen::Vector3d(0, -1, 0));
  EXPECT_EQ(pos(CellType::Hex27, 22), Eigen::Vector3d(-1, 0, 0));
  EXPECT_EQ(pos(CellType::Hex27, 23), Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(pos(CellType::Hex27, 24), Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(pos(CellType::Hex27, 25), Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(pos(CellType::Hex27, 26), Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(pos(CellType::Tet10, 6), Eigen::Vector3d(0, 0.5, 0));    // edge 2-0
  EXPECT_EQ(pos(CellType::Tet10, 8), Eigen::Vector3d(0, 0.5, 0.5));  // edge 3-2
  EXPECT_EQ(pos(CellType::Tet10, 9), Eigen::Vector3d(0.5, 0, 0.5));  // edge 3-1
  EXPECT_EQ(pos(CellType::Quad9, 7), Eigen::Vector3d(-1, 0, 0));     // side 3-0
}

// The 2-D sides keep the numbering the code has always used: side s runs
// from corner s to corner (s+1) mod 4, Quad9 middle node 4 + s.
TEST(ReferenceCell, QuadrilateralSidesKeepTheirNumbering) {
  for (CellType t : {CellType::Quad4, CellType::Quad9}) {
    const auto& f = referenceCell(t).facets;
    ASSERT_EQ(f.size(), 4u);
    for (int s = 0; s < 4; ++s) {
      EXPECT_EQ(f[s].nodes[0], s);
      EXPECT_EQ(f[s].nodes[1], (s + 1) % 4);
      if (t == CellType::Quad9) EXPECT_EQ(f[s].nodes.at(2), 4 + s);
    }
  }
}

TEST(ReferenceCell, FacetTypes) {
  EXPECT_EQ(referenceCell(CellType::Hex8).facets[0].type, CellType::Quad4);
  EXPECT_EQ(referenceCell(CellType::Hex20).facets[0].type, CellType::Quad8);
  EXPECT_EQ(referenceCell(CellType::Hex27).facets[0].type, CellType::Quad9);
  EXPECT_EQ(referenceCell(CellType::Tet4).facets[0].type, CellType::Tri3);
  EXPECT_EQ(referenceCell(CellType::Tet10).facets[0].type, CellType::Tri6);
  EXPECT_EQ(referenceCell(CellType::Quad9).facets[0].type, CellType::Line3);
}

// ---- the mesh's dimension --------------------------------------------------

TEST(MeshDimension, FromTheFirstBodyAndNeverMixed) {
  ddc::Mesh m;
  EXPECT_EQ(m.dim(), 0);
  m.beginBody("Brick", CellType::Hex8);
  EXPECT_EQ(m.dim(), 3);
  EXPECT_THAT(inputErrorOf([&] { m.beginBody("Plate", CellType::Quad4); }),
              HasSubstr("body 'Plate' has 2-D cells (Quad4) but body 'Brick' has 3-D cells (Hex8)"));
  ddc::Mesh m2;
  m2.beginBody("Plate", CellType::Quad9);
  EXPECT_EQ(m2.dim(), 2);
  EXPECT_THAT(inputErrorOf([&] { m2.beginBody("Brick", CellType::Tet10); }),
              HasSubstr("body 'Brick' has 3-D cells (Tet10) but body 'Plate' has 2-D cells (Quad9)"));
  EXPECT_THAT(inputErrorOf([&] { m2.beginBody("Skin", CellType::Tri3); }),
              HasSubstr("body 'Skin': Tri3 is a facet cell type, not an element type"));
}

TEST(MeshDimension, FacetsOfAHex20) {
  ddc::Mesh m;
  m.beginBody("Brick", CellType::Hex20);
  const ReferenceCell& ref = referenceCell(CellType::Hex20);
  std::vector<int> nodes;
  for (const auto& x : ref.nodes) nodes.push_back(m.addNode(x[0] + 10, x[1], x[2]));
  const int e = m.addElement(nodes.data());
  m.check();
  EXPECT_EQ(m.elementNumFacets(e), 6);
  for (int f = 0; f < 6; ++f) {
    const ddc::Segment s = m.makeSegment(e, f);
    EXPECT_EQ(s.numNodes, 8);
    EXPECT_EQ(m.facetKey(e, f).size(), 4u);
    // Every node of the face lies on the face's plane: one coordinate is +-1.
    int onPlane = 0;
    for (int d = 0; d < 3; ++d) {
      std::set<double> v;
      for (int i = 0; i < 8; ++i) v.insert(m.coord(s.nodes[i])[d]);
      onPlane += v.size() == 1;
    }
    EXPECT_EQ(onPlane, 1) << "face " << f;
  }
}

}  // namespace

TEST(CornerJacobian, ReferenceCellsAreValidAndMirrorImagesInverted) {
  for (CellType t : {CellType::Quad4, CellType::Quad9, CellType::Hex8, CellType::Hex20, CellType::Hex27,
                     CellType::Tet4, CellType::Tet10, CellType::Tri3, CellType::Quad8}) {
    const ReferenceCell& c = referenceCell(t);
    auto j = ddc::cornerJacobian(t, c.nodes.data());
    EXPECT_EQ(j.verdict, ddc::CornerJacobian::Verdict::Valid) << c.name;
    // The reference cell maps to itself: J = I.
    EXPECT_NEAR(j.det, 1.0, kRoundoff) << c.name;
    // Mirrored in x: inverted everywhere.
    auto mirrored = c.nodes;
    for (auto& p : mirrored) p[0] = -p[0];
    j = ddc::cornerJacobian(t, mirrored.data());
    EXPECT_EQ(j.verdict, ddc::CornerJacobian::Verdict::Inverted) << c.name;
    EXPECT_NEAR(j.det, -1.0, kRoundoff) << c.name;
    EXPECT_THAT(ddc::describeCornerJacobian(t, j), HasSubstr("inverted (det J = -1")) << c.name;
    // All corners in one point: degenerate.
    std::vector<std::array<double, 3>> point(c.numCorners, {{1, 2, 3}});
    j = ddc::cornerJacobian(t, point.data());
    EXPECT_EQ(j.verdict, ddc::CornerJacobian::Verdict::Degenerate) << c.name;
  }
  // A hexahedron whose corner 0 is pushed inside past the plane of its
  // neighbours 1, 3, 4: inverted at corner 0 only, positive at the centre.
  auto x = referenceCell(CellType::Hex8).nodes;
  x[0] = {0.5, 0.5, 0.5};
  const auto j = ddc::cornerJacobian(CellType::Hex8, x.data());
  EXPECT_EQ(j.verdict, ddc::CornerJacobian::Verdict::Inverted);
  EXPECT_EQ(j.where, 0);
  EXPECT_THAT(ddc::describeCornerJacobian(CellType::Hex8, j), HasSubstr("at corner 0 of the Hex8 corner map"));
  // Size independence: a cell scaled by 1e-6 is still valid.
  auto small = referenceCell(CellType::Tet4).nodes;
  for (auto& p : small)
    for (double& v : p) v *= 1e-6;
  EXPECT_EQ(ddc::cornerJacobian(CellType::Tet4, small.data()).verdict, ddc::CornerJacobian::Verdict::Valid);
}
