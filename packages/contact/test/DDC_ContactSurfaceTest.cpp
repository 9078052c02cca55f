// Contact surfaces from side sets (DDC_ContactSurface.hpp) on generated
// meshes of every element type: the facet type and node order, outward
// orientation, element depths (box faces, curved sides of sectors and shells),
// the Line2 case against masterSegmentsFromSideSet()/masterElementDepths(),
// and the errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "DDC_ContactSearch.hpp"
#include "DDC_ContactSurface.hpp"
#include "DDC_Error.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_ShapeFunctions.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using ddc::CellType;
using ddc::ContactSurfaceFacets;
using ddc::Mesh;
using ddc::test::inputErrorOf;
using ddc::test::kRoundoff;
using ::testing::HasSubstr;
using Vec = Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

const std::vector<std::string> kRectangleSides = {"bottom", "right", "top", "left"};
const std::vector<std::string> kBoxSides = {"bottom", "right", "top", "left", "back", "front"};

/// Generator parameters: lengths and element counts per axis (2 or 3 axes).
Teuchos::ParameterList gridParams(const char* name, const std::vector<double>& length, const std::vector<int>& n,
                                  double distortion = 0.0) {
  Teuchos::ParameterList p(name);
  const char* axis[3] = {"X", "Y", "Z"};
  for (std::size_t d = 0; d < length.size(); ++d) {
    p.set(std::string("Length ") + axis[d], length[d]);
    p.set(std::string("Elements ") + axis[d], n[d]);
  }
  p.set("Distortion", distortion);
  return p;
}

/// A 1.5 x 1.0 (x 2.0) block of 3 x 4 (x 2) elements, 0.5 x 0.25 (x 1.0) each.
Mesh block(CellType type) {
  Mesh m;
  if (ddc::cellDimension(type) == 2) {
    auto p = gridParams("Rectangle", {1.5, 1.0}, {3, 4});
    ddc::generateRectangle(m, "B", type, p, "Rectangle");
  } else {
    auto p = gridParams("Box", {1.5, 1.0, 2.0}, {3, 4, 2});
    ddc::generateBox(m, "B", type, p, "Box");
  }
  return m;
}
const Vec kBlockCentre(0.75, 0.5, 1.0);
const Vec kElementSize(0.5, 0.25, 1.0);

/// The facet type each element type's sides or faces have.
CellType facetTypeOf(CellType element) {
  switch (element) {
    case CellType::Quad4:
      return CellType::Line2;
    case CellType::Quad9:
      return CellType::Line3;
    case CellType::Hex8:
      return CellType::Quad4;
    case CellType::Hex20:
      return CellType::Quad8;
    case CellType::Hex27:
      return CellType::Quad9;
    case CellType::Tet4:
      return CellType::Tri3;
    default:
      return CellType::Tri6;
  }
}

Vec position(const Mesh& m, int node) { return Vec(m.coord(node)[0], m.coord(node)[1], m.coord(node)[2]); }

/// Outward normal direction of a facet from its corners alone (the rule of
/// DDC_ReferenceCell.hpp, independent of the code under test): 2-D
/// (dy, −dx) of start → end, 3-D (x_1 − x_0) × (x_last − x_0).
Vec cornerNormal(const Mesh& m, CellType type, const std::vector<int>& nodes) {
  const Vec x0 = position(m, nodes[0]), x1 = position(m, nodes[1]);
  if (ddc::cellDimension(type) == 1) return Vec(x1.y() - x0.y(), x0.x() - x1.x(), 0.0);
  const Vec xl = position(m, nodes[ddc::referenceCell(type).numCorners - 1]);
  return (x1 - x0).cross(xl - x0);
}

Vec cornerCentroid(const Mesh& m, CellType type, const std::vector<int>& nodes) {
  const int nc = ddc::referenceCell(type).numCorners;
  Vec c = Vec::Zero();
  for (int i = 0; i < nc; ++i) c += position(m, nodes[i]) / nc;
  return c;
}

std::vector<int> segmentNodes(const ddc::Segment& s) { return {s.nodes.begin(), s.nodes.begin() + s.numNodes}; }

// ---------------------------------------------------------------------------

TEST(ContactSurface, FacetTypeAndNodesOfEveryElementType) {
  for (CellType t : ddc::elementCellTypes()) {
    const Mesh m = block(t);
    const CellType facet = facetTypeOf(t);
    for (const auto& side : m.dim() == 2 ? kRectangleSides : kBoxSides) {
      const std::string set = "B/" + side;
      const ContactSurfaceFacets s = ddc::contactSurfaceFromSideSet(m, set);
      const auto& sides = m.sideSet(set);
      EXPECT_EQ(s.type, facet) << set << " of " << ddc::cellTypeName(t);
      ASSERT_EQ(s.nodes.size(), sides.size()) << set;
      ASSERT_EQ(s.elements.size(), sides.size()) << set;
      ASSERT_EQ(s.depths.size(), sides.size()) << set;
      for (std::size_t k = 0; k < sides.size(); ++k) {
        EXPECT_EQ(static_cast<int>(s.nodes[k].size()), ddc::numCellNodes(facet)) << set;
        EXPECT_EQ(s.nodes[k], segmentNodes(sides[k])) << set << " facet " << k;
        EXPECT_EQ(s.elements[k], sides[k].element) << set << " facet " << k;
      }
    }
  }
}

TEST(ContactSurface, FacetNodesAreInTheFacetTypesNodeOrder) {
  // On straight generated meshes node i of a facet sits at reference node i
  // of its type mapped by the corners alone (Quad9 sides: start, end, middle
  // = Line3 ξ = −1, 1, 0; mid-edge and centre nodes of faces likewise).
  for (CellType t : ddc::elementCellTypes()) {
    const Mesh m = block(t);
    const CellType facet = facetTypeOf(t);
    const ddc::ReferenceCell& ref = ddc::referenceCell(facet);
    const CellType linear = ddc::cellDimension(facet) == 1 ? CellType::Line2
                            : ref.simplex                  ? CellType::Tri3
                                                           : CellType::Quad4;
    const ContactSurfaceFacets s = ddc::contactSurfaceFromSideSet(m, m.dim() == 2 ? "B/top" : "B/front");
    for (const auto& nodes : s.nodes)
      for (int i = 0; i < ref.numNodes; ++i) {
        Eigen::VectorXd N;
        ddc::shapeFunctions(linear, ref.nodes[i], &N, nullptr);
        Vec x = Vec::Zero();
        for (int c = 0; c < ref.numCorners; ++c) x += N[c] * position(m, nodes[c]);
        EXPECT_LT((x - position(m, nodes[i])).norm(), kRoundoff) << ddc::cellTypeName(facet) << " node " << i;
      }
  }
}

TEST(ContactSurface, FacetsOfABlockPointOutward) {
  for (CellType t : ddc::elementCellTypes()) {
    const Mesh m = block(t);
    Vec centre = kBlockCentre;
    if (m.dim() == 2) centre.z() = 0.0;
    for (const auto& side : m.dim() == 2 ? kRectangleSides : kBoxSides) {
      const ContactSurfaceFacets s = ddc::contactSurfaceFromSideSet(m, "B/" + side);
      for (const auto& nodes : s.nodes)
        EXPECT_GT(cornerNormal(m, s.type, nodes).dot(cornerCentroid(m, s.type, nodes) - centre), 0.0)
            << side << " of " << ddc::cellTypeName(t);
    }
  }
}

TEST(ContactSurface, DepthOfABlockFacetIsTheElementSizeNormalToIt) {
  // Every Kuhn tetrahedron holds its cell's lowest and highest corner, so it
  // too reaches one cell size behind each of its boundary faces.
  const std::map<std::string, int> axisOf = {{"left", 0}, {"right", 0}, {"bottom", 1},
                                             {"top", 1},  {"back", 2},  {"front", 2}};
  for (CellType t : ddc::elementCellTypes()) {
    const Mesh m = block(t);
    for (const auto& side : m.dim() == 2 ? kRectangleSides : kBoxSides) {
      const ContactSurfaceFacets s = ddc::contactSurfaceFromSideSet(m, "B/" + side);
      for (double d : s.depths)
        EXPECT_NEAR(d, kElementSize[axisOf.at(side)], kRoundoff) << side << " of " << ddc::cellTypeName(t);
    }
  }
}

TEST(ContactSurface, DepthBehindCurvedFacetsIsMeasuredFromTheFacetCentre) {
  // One element through the thickness Ro − Ri, n elements over 90 degrees,
  // half-angle h = 45°/n per element. From the centre of an outer facet (on
  // the arc, normal radial) the element reaches Ro − Ri cos h (the inner
  // corners); from an inner facet's centre Ro − Ri (the outer middle node).
  // Hex20 (Quad8 faces) has its face centre x(0, 0) on the arc as well.
  const double ri = 1.0, ro = 1.25, h = kPi / 4.0 / 6.0;
  auto sector = [&](Teuchos::ParameterList& p) {
    p.set("Inner Radius", ri);
    p.set("Outer Radius", ro);
    p.set("Start Angle", 0.0);
    p.set("End Angle", 90.0);
    p.set("Radial Elements", 1);
    p.set("Circumferential Elements", 6);
  };
  for (CellType t : {CellType::Quad9, CellType::Hex20, CellType::Hex27}) {
    Mesh m;
    if (t == CellType::Quad9) {
      Teuchos::ParameterList p("Annular Sector");
      sector(p);
      ddc::generateAnnularSector(m, "S", t, p, "Annular Sector");
    } else {
      Teuchos::ParameterList p("Cylindrical Shell Sector");
      sector(p);
      p.set("Axial Elements", 1);
      ddc::generateCylindricalShellSector(m, "S", t, p, "Cylindrical Shell Sector");
    }
    for (const auto& [set, expected, sign] :
         {std::tuple<const char*, double, double>{"S/outer", ro - ri * std::cos(h), 1.0}, {"S/inner", ro - ri, -1.0}}) {
      const ContactSurfaceFacets s = ddc::contactSurfaceFromSideSet(m, set);
      ASSERT_EQ(s.depths.size(), 6u) << set;
      for (std::size_t k = 0; k < s.nodes.size(); ++k) {
        EXPECT_NEAR(s.depths[k], expected, kRoundoff) << set << " of " << ddc::cellTypeName(t);
        const Vec c = cornerCentroid(m, s.type, s.nodes[k]);
        const Vec radial(c.x(), c.y(), 0.0);
        EXPECT_GT(sign * cornerNormal(m, s.type, s.nodes[k]).dot(radial), 0.0) << set;
      }
    }
  }
}

TEST(ContactSurface, Line2FacetsAreTheStraightSegmentSearchsExactly) {
  for (double distortion : {0.0, 0.3}) {
    Mesh m;
    auto p = gridParams("Rectangle", {2.0, 1.0}, {6, 4}, distortion);
    ddc::generateRectangle(m, "B", CellType::Quad4, p, "Rectangle");
    for (const auto& side : kRectangleSides) {
      const std::string set = "B/" + side;
      const ContactSurfaceFacets s = ddc::contactSurfaceFromSideSet(m, set);
      const auto segments = ddc::masterSegmentsFromSideSet(m, set);
      const auto depths = ddc::masterElementDepths(m, set);
      EXPECT_EQ(s.type, CellType::Line2);
      ASSERT_EQ(s.nodes.size(), segments.size()) << set;
      for (std::size_t k = 0; k < segments.size(); ++k)
        EXPECT_EQ(s.nodes[k], std::vector<int>(segments[k].begin(), segments[k].end())) << set << " facet " << k;
      EXPECT_EQ(s.depths, depths) << set << ", distortion " << distortion;  // bit for bit
    }
  }
}

TEST(ContactSurface, MissingSideSetIsAnInputErrorAsForTheSegmentSearch) {
  const Mesh m = block(CellType::Hex8);
  const std::string msg = inputErrorOf([&] { ddc::contactSurfaceFromSideSet(m, "B/nope"); });
  EXPECT_THAT(msg, HasSubstr("no side set named 'B/nope'"));
  EXPECT_THAT(msg, HasSubstr("'B/front'"));  // the known ones are listed
  const Mesh q = block(CellType::Quad4);
  EXPECT_EQ(inputErrorOf([&] { ddc::contactSurfaceFromSideSet(q, "B/nope"); }),
            inputErrorOf([&] { ddc::masterSegmentsFromSideSet(q, "B/nope"); }));
}

TEST(ContactSurface, DegenerateElementIsAnInputError) {
  // A Quad4 and a Hex8 flattened onto their bottom facet: no depth.
  Mesh flat2;
  const int b2 = flat2.beginBody("Flat", CellType::Quad4);
  for (double x : {0.0, 1.0, 2.0, 3.0}) flat2.addNode(x, 0.0);
  const int quad[4] = {0, 1, 2, 3};
  flat2.addElement(quad);
  flat2.addSideSet(b2, "bottom", {flat2.makeSegment(0, 0)});
  EXPECT_THAT(inputErrorOf([&] { ddc::contactSurfaceFromSideSet(flat2, "Flat/bottom"); }),
              HasSubstr("side set 'Flat/bottom': element 0 has no extent behind its side 0 (degenerate element)"));

  Mesh flat3;
  const int b3 = flat3.beginBody("Flat", CellType::Hex8);
  for (int layer = 0; layer < 2; ++layer)
    for (const auto& [x, y] : {std::pair<double, double>{0, 0}, {1, 0}, {1, 1}, {0, 1}}) flat3.addNode(x, y, 0.0);
  const int hex[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  flat3.addElement(hex);
  flat3.addSideSet(b3, "back", {flat3.makeSegment(0, 0)});
  EXPECT_THAT(inputErrorOf([&] { ddc::contactSurfaceFromSideSet(flat3, "Flat/back"); }),
              HasSubstr("side set 'Flat/back': element 0 has no extent behind its face 0 (degenerate element)"));
}

TEST(ContactSurface, FacetTypeFromNodeCountAndDimension) {
  const std::vector<std::tuple<int, int, CellType>> types = {
      {2, 2, CellType::Line2}, {2, 3, CellType::Line3}, {3, 3, CellType::Tri3}, {3, 6, CellType::Tri6},
      {3, 4, CellType::Quad4}, {3, 8, CellType::Quad8}, {3, 9, CellType::Quad9}};
  for (const auto& [dim, n, type] : types) EXPECT_EQ(ddc::contactFacetType(dim, n, "S/s"), type);
  EXPECT_THAT(inputErrorOf([] { ddc::contactFacetType(2, 4, "S/s"); }),
              HasSubstr("side set 'S/s': a facet with 4 nodes is no facet of a 2-D element"));
  EXPECT_THAT(inputErrorOf([] { ddc::contactFacetType(3, 2, "S/s"); }), HasSubstr("no facet of a 3-D element"));
}

}  // namespace
