// BodyLocator: which element of a body contains a point (the check that no
// slave node starts inside a master body, doc/contact.md "Which slave nodes
// pair"): interior points, points on mesh lines and nodes inside the body,
// points on the body's boundary and outside, and random points in distorted
// meshes against the body's outline.
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>

#include <random>

#include "DDC_BodyLocator.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_MeshGenerators.hpp"

using ddc::BodyLocator;
using Vec = Eigen::Vector2d;

namespace {

/// Points this far (relative to the O(1) body) from the boundary are clearly
/// on one side of it: 100 times BodyLocator::kInsideMargin, so the margin
/// cannot decide them.
constexpr double kClearlyOff = 1e-6;

/// Points within this distance of the boundary are on it: far below the
/// margin (1e-8 times an edge of length 0.25 .. 1), far above round-off.
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
