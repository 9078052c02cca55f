// BodyLocator: which element of a body contains a point (the check that no
// slave node starts inside a master body, doc/contact.md "Which slave nodes
// pair"): interior points, points on mesh lines and nodes inside the body,
// points on the body's boundary and outside, and random points in distorted
// meshes against the body's outline; in 3-D (BodyLocator3D.*) the same on
// boxes of every cell type, the split of non-planar hexahedron faces, and
// random points against a brute-force search over all elements.
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <array>
#include <random>
#include <stdexcept>
#include <vector>

#include "DDC_BodyLocator.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_MeshGenerators.hpp"

using ddc::BodyLocator;
using Vec = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

namespace {

/// Points this far (relative to the O(1) body) from the boundary are clearly
/// on one side of it: 100 times BodyLocator::kInsideMargin, so the margin
/// cannot decide them.
constexpr double kClearlyOff = 1e-6;

/// Points within this distance of the boundary are on it: far below the
/// margin (1e-8 times an edge or element of size 0.25 .. 1), far above
/// round-off.
constexpr double kOnBoundary = 1e-12;

ddc::Mesh rectangle(double lx, double ly, int nx, int ny, double distortion, const std::string& name = "B",
                    double x0 = 0.0, double y0 = 0.0) {
  ddc::Mesh m;
  Teuchos::ParameterList p("Rectangle");
  p.set("Origin X", x0);
  p.set("Origin Y", y0);
  p.set("Length X", lx);
  p.set("Length Y", ly);
  p.set("Elements X", nx);
  p.set("Elements Y", ny);
  p.set("Distortion", distortion);
  ddc::generateRectangle(m, name, ddc::CellType::Quad4, p, "R");
  return m;
}

/// Add the box [x0, x0 + l] of n[0] x n[1] x n[2] cells as body `name`.
void addBox(ddc::Mesh& m, const std::string& name, ddc::CellType type, const Vec3& x0, const Vec3& l,
            const std::array<int, 3>& n, double distortion = 0.0) {
  Teuchos::ParameterList p("Box");
  const char* axis[3] = {"X", "Y", "Z"};
  for (int d = 0; d < 3; ++d) {
    p.set(std::string("Origin ") + axis[d], x0[d]);
    p.set(std::string("Length ") + axis[d], l[d]);
    p.set(std::string("Elements ") + axis[d], n[d]);
  }
  p.set("Distortion", distortion);
  ddc::generateBox(m, name, type, p, "Box");
}

ddc::Mesh box(ddc::CellType type, const Vec3& x0, const Vec3& l, const std::array<int, 3>& n, double distortion = 0.0) {
  ddc::Mesh m;
  addBox(m, "B", type, x0, l, n, distortion);
  return m;
}

const std::vector<ddc::CellType> k3DTypes = {ddc::CellType::Hex8, ddc::CellType::Hex20, ddc::CellType::Hex27,
                                             ddc::CellType::Tet4, ddc::CellType::Tet10};

Vec3 coord(const ddc::Mesh& m, int n) { return Vec3(m.coord(n)[0], m.coord(n)[1], m.coord(n)[2]); }

/// Brute force, independent of the locator's winding numbers and bins: is x
/// in the polyhedron of element e (BodyLocator's rule: corner faces,
/// quadrilaterals split along the diagonal from their smallest node), with
/// barycentric coordinates allowed down to -tol? The polyhedron is the union
/// of the tetrahedra joining its corners' centroid to its face triangles (the
/// generator's elements are star-shaped about it).
bool inElement(const ddc::Mesh& m, int e, const Vec3& x, double tol) {
  const auto& ref = ddc::referenceCell(m.elementType(e));
  const int* nodes = m.elementNodes(e);
  Vec3 g = Vec3::Zero();
  for (int a = 0; a < ref.numCorners; ++a) g += coord(m, nodes[a]) / ref.numCorners;
  for (const auto& face : ref.facets) {
    std::vector<int> c;
    for (int k = 0; k < ddc::referenceCell(face.type).numCorners; ++k) c.push_back(nodes[face.nodes[k]]);
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    for (std::size_t k = 1; k + 1 < c.size(); ++k) {
      Eigen::Matrix3d t;
      t << coord(m, c[0]) - g, coord(m, c[k]) - g, coord(m, c[k + 1]) - g;
      const Vec3 lambda = t.partialPivLu().solve(x - g);
      if (lambda.minCoeff() >= -tol && lambda.sum() <= 1.0 + tol) return true;
    }
  }
  return false;
}

/// The lowest-index element of body `b` whose polyhedron contains x, or -1.
int bruteForce(const ddc::Mesh& m, const Vec3& x, double tol = 0.0, int b = 0) {
  for (int e = m.body(b).firstElement; e < m.body(b).firstElement + m.body(b).numElements; ++e)
    if (inElement(m, e, x, tol)) return e;
  return -1;
}

}  // namespace

TEST(BodyLocator, InteriorPointsMeshLinesAndNodesAreInside) {
  const ddc::Mesh m = rectangle(2.0, 1.0, 4, 2, 0.0);  // elements 0.5 x 0.5
  const BodyLocator loc(m, 0);
  EXPECT_GE(loc.elementContaining(Vec(0.3, 0.2)), 0);
  EXPECT_GE(loc.elementContaining(Vec(0.3, 0.5)), 0) << "on the mesh line between two elements";
  EXPECT_GE(loc.elementContaining(Vec(1.0, 0.5)), 0) << "an interior node";
  EXPECT_GE(loc.elementContaining(Vec(2.0 - kClearlyOff, 0.7)), 0);
  // The element that contains it: its corners bracket the point.
  const int e = loc.elementContaining(Vec(1.2, 0.7));
  ASSERT_GE(e, 0);
  double xmin = 1e9, xmax = -1e9, ymin = 1e9, ymax = -1e9;
  for (int a = 0; a < 4; ++a) {
    const auto& x = m.coord(m.elementNodes(e)[a]);
    xmin = std::min(xmin, x[0]), xmax = std::max(xmax, x[0]);
    ymin = std::min(ymin, x[1]), ymax = std::max(ymax, x[1]);
  }
  EXPECT_TRUE(xmin <= 1.2 && 1.2 <= xmax && ymin <= 0.7 && 0.7 <= ymax);
}

TEST(BodyLocator, BoundaryAndOutsidePointsAreNotInside) {
  const ddc::Mesh m = rectangle(2.0, 1.0, 4, 2, 0.0);
  const BodyLocator loc(m, 0);
  for (const Vec& x : {Vec(0.3, 0.0), Vec(0.0, 0.0), Vec(2.0, 0.7), Vec(1.0, 1.0), Vec(0.5, 1.0),
                       Vec(0.3, kOnBoundary), Vec(2.0 - kOnBoundary, 0.7), Vec(-0.1, 0.5), Vec(3.0, 3.0),
                       Vec(1.0, 1.0 + kClearlyOff), Vec(NAN, 0.5)})
    EXPECT_EQ(loc.elementContaining(x), -1) << "(" << x.transpose() << ")";
}

TEST(BodyLocator, OnlyTheGivenBodyCounts) {
  // Two bodies side by side; each locator sees only its own elements.
  ddc::Mesh m;
  Teuchos::ParameterList p("Rectangle");
  ddc::generateRectangle(m, "Left", ddc::CellType::Quad4, p, "R");
  Teuchos::ParameterList q("Rectangle");
  q.set("Origin X", 1.0);
  ddc::generateRectangle(m, "Right", ddc::CellType::Quad4, q, "R");
  const BodyLocator left(m, 0), right(m, 1);
  EXPECT_GE(left.elementContaining(Vec(0.5, 0.5)), 0);
  EXPECT_EQ(right.elementContaining(Vec(0.5, 0.5)), -1);
  EXPECT_EQ(left.elementContaining(Vec(1.0, 0.5)), -1) << "the shared line is both bodies' boundary";
  EXPECT_EQ(right.elementContaining(Vec(1.0, 0.5)), -1);
  const int e = right.elementContaining(Vec(1.5, 0.5));
  EXPECT_GE(e, m.body(1).firstElement);
}

TEST(BodyLocator, RandomPointsInDistortedMeshesMatchTheOutline) {
  // Distortion moves interior vertices only: the body stays the rectangle,
  // its mesh lines are skewed. Inside the body <=> inside the rectangle.
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  for (int trial = 0; trial < 5; ++trial) {
    const double lx = 1.5 + 0.5 * trial, ly = 1.0;
    const ddc::Mesh m = rectangle(lx, ly, 6 + trial, 4 + trial, 0.3, "B", -0.3, 0.2);
    const BodyLocator loc(m, 0);
    int inside = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec x(-0.3 + lx * u(rng), 0.2 + ly * u(rng));
      const double off = std::min({x.x() + 0.3, -0.3 + lx - x.x(), x.y() - 0.2, 0.2 + ly - x.y()});
      if (std::abs(off) < kClearlyOff) continue;
      const int e = loc.elementContaining(x);
      ASSERT_EQ(e >= 0, off > 0) << "trial " << trial << " point (" << x.transpose() << ")";
      inside += e >= 0;
    }
    EXPECT_GT(inside, 500);
  }
}

TEST(BodyLocator3D, InteriorPointsFacesEdgesAndNodesAreInside) {
  // Elements (cells of the Tet types) 0.5 x 0.5 x 0.5, numbered x fastest.
  // Interior points; points on faces between cells, on edges between cells,
  // the interior node, points on a cell's diagonal (inside the Tet types'
  // cells); points just inside a boundary face, edge and corner.
  const std::vector<Vec3> points = {Vec3(0.3, 0.2, 0.1),
                                    Vec3(1.2, 0.7, 0.6),
                                    Vec3(0.5, 0.3, 0.2),
                                    Vec3(1.3, 0.5, 0.6),
                                    Vec3(0.7, 0.8, 0.5),
                                    Vec3(0.5, 0.5, 0.3),
                                    Vec3(1.5, 0.2, 0.5),
                                    Vec3(1.0, 0.5, 0.5),
                                    Vec3(0.3, 0.3, 0.3),
                                    Vec3(0.6, 0.6, 0.7),
                                    Vec3(2.0 - kClearlyOff, 0.7, 0.6),
                                    Vec3(0.3, kClearlyOff, 0.4),
                                    Vec3(kClearlyOff, kClearlyOff, 0.4),
                                    Vec3(kClearlyOff, 1.0 - kClearlyOff, 1.0 - kClearlyOff)};
  for (ddc::CellType t : k3DTypes) {
    const ddc::Mesh m = box(t, Vec3(0, 0, 0), Vec3(2, 1, 1), {4, 2, 2});
    const BodyLocator loc(m, 0);
    for (const Vec3& x : points) {
      // The lowest index of the elements whose closure holds x.
      const int expected = bruteForce(m, x, 1e-12);
      ASSERT_GE(expected, 0);
      EXPECT_EQ(loc.elementContaining(x), expected) << ddc::cellTypeName(t) << " (" << x.transpose() << ")";
    }
  }
  // Hexahedra by their grid index: the cell of an interior point, the lower
  // cell of a face, the lowest of the four cells at an edge and of the eight
  // at a node.
  const ddc::Mesh m = box(ddc::CellType::Hex8, Vec3(0, 0, 0), Vec3(2, 1, 1), {4, 2, 2});
  const BodyLocator loc(m, 0);
  auto cellIndex = [](int ix, int iy, int iz) { return ix + 4 * (iy + 2 * iz); };
  EXPECT_EQ(loc.elementContaining(Vec3(1.2, 0.7, 0.6)), cellIndex(2, 1, 1));
  EXPECT_EQ(loc.elementContaining(Vec3(1.3, 0.5, 0.6)), cellIndex(2, 0, 1));
  EXPECT_EQ(loc.elementContaining(Vec3(1.5, 0.2, 0.5)), cellIndex(2, 0, 0));
  EXPECT_EQ(loc.elementContaining(Vec3(1.0, 0.5, 0.5)), cellIndex(1, 0, 0));
}

TEST(BodyLocator3D, BoundaryFacesNodesAndOutsidePointsAreNotInside) {
  // Points on boundary faces, on boundary edges, boundary nodes; within
  // round-off of the boundary on either side; outside.
  const std::vector<Vec3> points = {Vec3(0.3, 0.0, 0.4),
                                    Vec3(0.0, 0.7, 0.6),
                                    Vec3(2.0, 0.7, 0.6),
                                    Vec3(0.3, 0.4, 1.0),
                                    Vec3(0.3, 0.0, 0.0),
                                    Vec3(2.0, 0.5, 0.2),
                                    Vec3(0.0, 0.0, 0.0),
                                    Vec3(1.0, 0.5, 0.0),
                                    Vec3(2.0, 1.0, 1.0),
                                    Vec3(0.5, 1.0, 0.5),
                                    Vec3(0.3, kOnBoundary, 0.4),
                                    Vec3(0.3, -kOnBoundary, 0.4),
                                    Vec3(2.0 + kOnBoundary, 0.7, 0.6),
                                    Vec3(-kOnBoundary, -kOnBoundary, -kOnBoundary),
                                    Vec3(-0.1, 0.5, 0.5),
                                    Vec3(3.0, 3.0, 3.0),
                                    Vec3(1.0, 0.5, 1.0 + kClearlyOff),
                                    Vec3(NAN, 0.5, 0.5)};
  for (ddc::CellType t : k3DTypes) {
    const ddc::Mesh m = box(t, Vec3(0, 0, 0), Vec3(2, 1, 1), {4, 2, 2});
    const BodyLocator loc(m, 0);
    for (const Vec3& x : points)
      EXPECT_EQ(loc.elementContaining(x), -1) << ddc::cellTypeName(t) << " (" << x.transpose() << ")";
    // Every node (mid-edge and face nodes of the quadratic cells too): inside
    // unless on the box's surface.
    for (int n = 0; n < m.numNodes(); ++n) {
      const Vec3 x = coord(m, n);
      const bool onSurface = x.minCoeff() == 0.0 || x.x() == 2.0 || x.y() == 1.0 || x.z() == 1.0;
      EXPECT_EQ(loc.elementContaining(x) >= 0, !onSurface) << ddc::cellTypeName(t) << " node " << n;
    }
  }
}

TEST(BodyLocator3D, OnlyTheGivenBodyCounts) {
  // Two unit cubes side by side; each locator sees only its own elements.
  ddc::Mesh m;
  addBox(m, "Left", ddc::CellType::Hex8, Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 2, 2});
  addBox(m, "Right", ddc::CellType::Hex8, Vec3(1, 0, 0), Vec3(1, 1, 1), {2, 2, 2});
  const BodyLocator left(m, 0), right(m, 1);
  EXPECT_GE(left.elementContaining(Vec3(0.3, 0.5, 0.6)), 0);
  EXPECT_EQ(right.elementContaining(Vec3(0.3, 0.5, 0.6)), -1);
  EXPECT_EQ(left.elementContaining(Vec3(1.0, 0.3, 0.5)), -1) << "the shared face is both bodies' boundary";
  EXPECT_EQ(right.elementContaining(Vec3(1.0, 0.3, 0.5)), -1);
  EXPECT_GE(right.elementContaining(Vec3(1.5, 0.3, 0.5)), m.body(1).firstElement);
}

TEST(BodyLocator3D, NonPlanarFacesSplitAlongTheDiagonalFromTheirSmallestNode) {
  // Two stacked unit hexahedra whose shared face has one corner raised by
  // 0.2: split from that corner the face runs through z = 1.1 at its centre,
  // split along the other diagonal through z = 1. The point in between, at
  // z = 1.05, lies in the lower element in the first case, in the upper one
  // in the second. Which diagonal is taken follows the numbering of the
  // face's nodes only, the same for both elements.
  const std::array<Vec3, 12> x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0),   Vec3(0, 1, 0),
                                  Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1.2), Vec3(0, 1, 1),
                                  Vec3(0, 0, 2), Vec3(1, 0, 2), Vec3(1, 1, 2),   Vec3(0, 1, 2)};
  for (bool raisedCornerFirst : {true, false}) {
    // Node numbers of the points: the raised corner (point 6) or its
    // neighbour on the face (point 5) gets the smallest number.
    std::array<int, 12> order = {6, 5, 4, 7, 0, 1, 2, 3, 8, 9, 10, 11};
    if (!raisedCornerFirst) std::swap(order[0], order[1]);
    std::array<int, 12> number{};
    ddc::Mesh m;
    m.beginBody("B", ddc::CellType::Hex8);
    for (int i : order) number[i] = m.addNode(x[i].x(), x[i].y(), x[i].z());
    for (int first : {0, 4}) {
      std::array<int, 8> nodes{};
      for (int a = 0; a < 8; ++a) nodes[a] = number[first + a];
      m.addElement(nodes.data());
    }
    const BodyLocator loc(m, 0);
    const int between = raisedCornerFirst ? 0 : 1;  // the element of the points between the two surfaces
    EXPECT_EQ(loc.elementContaining(Vec3(0.5, 0.5, 1.0 - kClearlyOff)), 0);
    EXPECT_EQ(loc.elementContaining(Vec3(0.5, 0.5, 1.0 + kClearlyOff)), between);
    EXPECT_EQ(loc.elementContaining(Vec3(0.5, 0.5, 1.05)), between);
    EXPECT_EQ(loc.elementContaining(Vec3(0.5, 0.5, 1.1 - kClearlyOff)), between);
    EXPECT_EQ(loc.elementContaining(Vec3(0.5, 0.5, 1.1 + kClearlyOff)), 1);
    EXPECT_EQ(loc.elementContaining(Vec3(0.5, 0.5, raisedCornerFirst ? 1.1 : 1.0)), 0) << "on the face: the lower";
  }
}

TEST(BodyLocator3D, RandomPointsMatchABruteForceSearch) {
  // Distortion moves interior vertices only: the body stays the box, and its
  // hexahedra get non-planar faces. Inside the body <=> inside the box, in
  // the element a search over all elements finds.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.2, 1.2), w(0.0, 1.0);
  const Vec3 x0(-0.3, 0.2, 0.1), l(1.5, 1.0, 0.8);
  for (ddc::CellType t : {ddc::CellType::Hex8, ddc::CellType::Tet4}) {
    for (double distortion : {0.0, 0.25}) {
      const ddc::Mesh m = box(t, x0, l, {3, 3, 2}, distortion);
      const BodyLocator loc(m, 0);
      int inside = 0, compared = 0;
      for (int i = 0; i < 400; ++i) {
        const Vec3 x = x0 + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(l);
        // Only points the brute force places robustly: the same answer when
        // moved by kClearlyOff along any axis (not near any face).
        const int expected = bruteForce(m, x);
        bool robust = true;
        for (int d = 0; d < 3; ++d)
          for (double s : {-kClearlyOff, kClearlyOff})
            robust = robust && bruteForce(m, x + s * Vec3::Unit(d)) == expected;
        if (!robust) continue;
        const bool inBox = ((x - x0).array() > 0.0).all() && ((x - x0 - l).array() < 0.0).all();
        ASSERT_EQ(expected >= 0, inBox) << "the test's brute force disagrees with the body's outline";
        ASSERT_EQ(loc.elementContaining(x), expected)
            << ddc::cellTypeName(t) << " distortion " << distortion << " point (" << x.transpose() << ")";
        inside += expected >= 0;
        ++compared;
      }
      EXPECT_GT(compared, 350);
      EXPECT_GT(inside, 100);
      // Points on the box's faces, moved off them by round-off (outside) or
      // into the body by kClearlyOff (inside).
      for (int i = 0; i < 100; ++i) {
        const int d = i % 3;
        const bool upper = i % 2 == 1;
        Vec3 x = x0 + Vec3(w(rng), w(rng), w(rng)).cwiseProduct(l);
        x[d] = upper ? x0[d] + l[d] : x0[d];
        const Vec3 out = Vec3::Unit(d) * (upper ? 1.0 : -1.0);
        EXPECT_EQ(loc.elementContaining(x), -1);
        EXPECT_EQ(loc.elementContaining(Vec3(x + kOnBoundary * out)), -1);
        EXPECT_EQ(loc.elementContaining(Vec3(x - kOnBoundary * out)), -1);
        const Vec3 in = x - kClearlyOff * out;
        const int e = loc.elementContaining(in);
        EXPECT_GE(e, 0) << "(" << in.transpose() << ")";
        EXPECT_TRUE(e < 0 || inElement(m, e, in, 1e-6))
            << "element " << e << " does not hold (" << in.transpose() << ")";
      }
    }
  }
}

TEST(BodyLocator3D, QuadraticCellsAreLocatedByTheirCorners) {
  // The generator places Hex20/Hex27/Tet10 corners where Hex8/Tet4 have them
  // (the same distortion), so every point gets the same element.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  const Vec3 x0(0, 0, 0), l(1.5, 1.0, 0.8);
  const std::array<std::pair<ddc::CellType, ddc::CellType>, 3> pairs = {{{ddc::CellType::Hex8, ddc::CellType::Hex20},
                                                                         {ddc::CellType::Hex8, ddc::CellType::Hex27},
                                                                         {ddc::CellType::Tet4, ddc::CellType::Tet10}}};
  for (const auto& [linear, quadratic] : pairs) {
    const ddc::Mesh a = box(linear, x0, l, {3, 2, 2}, 0.25), b = box(quadratic, x0, l, {3, 2, 2}, 0.25);
    const BodyLocator la(a, 0), lb(b, 0);
    for (int i = 0; i < 300; ++i) {
      const Vec3 x = x0 + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(l);
      EXPECT_EQ(la.elementContaining(x), lb.elementContaining(x)) << ddc::cellTypeName(quadratic);
    }
    for (int n = 0; n < a.numNodes(); ++n)
      EXPECT_EQ(la.elementContaining(coord(a, n)), lb.elementContaining(coord(a, n))) << ddc::cellTypeName(quadratic);
  }
}

TEST(BodyLocator3D, EachOverloadRefusesABodyOfTheOtherDimension) {
  const ddc::Mesh solid = box(ddc::CellType::Hex8, Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 2, 2});
  const BodyLocator loc3(solid, 0);
  try {
    loc3.elementContaining(Vec(0.5, 0.5));
    ADD_FAILURE() << "a 2-D point for a 3-D body was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "BodyLocator: a 2-D point for body 'B', which is 3-D; pass an Eigen::Vector3d");
  }
  const ddc::Mesh plane = rectangle(1.0, 1.0, 2, 2, 0.0);
  const BodyLocator loc2(plane, 0);
  EXPECT_THROW(loc2.elementContaining(Vec3(0.5, 0.5, 0.0)), std::invalid_argument);
}
