// Facet search and tracking (DDC_FacetSearch.hpp): the binned global search
// against a brute-force search over all facets, tracking against the global
// search after small motions, and the edge / corner rule (convex: nearest
// point on the edge or corner with the direction as normal; concave: the
// nearer interior projection).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "DDC_FacetSearch.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using ddc::CellType;
using ddc::FacetCandidate;
using ddc::FacetPointKind;
using ddc::FacetSearch;

/// A warped surface z = f(x, y) over [0, 4] x [0, 3], nx x ny cells split
/// into facets of `type` (counter-clockwise seen from +z: outward normal up).
struct Surface {
  std::map<int, Eigen::VectorXd> X;
  std::vector<std::vector<int>> facets;
  static double height(double x, double y) { return 0.1 * std::sin(x) * std::cos(y); }
  Surface(CellType type, int nx = 8, int ny = 6) {
    const bool quadratic = type == CellType::Quad9 || type == CellType::Tri6;
    const int px = quadratic ? 2 * nx : nx, py = quadratic ? 2 * ny : ny;  // node grid
    auto id = [&](int i, int j) { return j * (px + 1) + i; };
    for (int j = 0; j <= py; ++j)
      for (int i = 0; i <= px; ++i) {
        const double x = 4.0 * i / px, y = 3.0 * j / py;
        Eigen::VectorXd p(3);
        p << x, y, height(x, y);
        X[id(i, j)] = p;
      }
    const int s = quadratic ? 2 : 1;
    for (int b = 0; b < ny; ++b)
      for (int a = 0; a < nx; ++a) {
        const int i = s * a, j = s * b;
        if (type == CellType::Quad4) {
          facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
        } else if (type == CellType::Quad9) {
          facets.push_back({id(i, j), id(i + 2, j), id(i + 2, j + 2), id(i, j + 2), id(i + 1, j), id(i + 2, j + 1),
                            id(i + 1, j + 2), id(i, j + 1), id(i + 1, j + 1)});
        } else {  // Tri3: two triangles per cell
          facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
          facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
      }
  }
  std::function<Eigen::VectorXd(int)> position() const {
    return [this](int n) { return X.at(n); };
  }
};

/// The pairing by evaluating every facet (the same key as the search).
FacetCandidate bruteForce(CellType type, const Surface& s, const Eigen::VectorXd& xs, double radius) {
  FacetCandidate best;
  for (size_t f = 0; f < s.facets.size(); ++f) {
    Eigen::MatrixXd x(s.facets[f].size(), 3);
    for (size_t i = 0; i < s.facets[f].size(); ++i) x.row(i) = s.X.at(s.facets[f][i]).transpose();
    FacetCandidate c = ddc::nearestPoint(type, x, xs);
    c.facet = int(f);
    if (c.distance > radius) continue;
    const bool better = best.facet < 0 || c.distance < best.distance ||
                        (c.distance == best.distance && c.kind == FacetPointKind::Interior &&
                         best.kind != FacetPointKind::Interior);
    if (better) best = c;
  }
  return best;
}

TEST(FacetSearch, GlobalSearchEqualsBruteForceAndTrackingFollows) {
  for (CellType type : {CellType::Quad4, CellType::Quad9, CellType::Tri3}) {
    SCOPED_TRACE(ddc::cellTypeName(type));
    Surface s(type);
    const double radius = 0.6;
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> ux(0.2, 3.8), uy(0.2, 2.8), uz(-0.05, 0.3);
    std::vector<int> slaves;
    for (int q = 0; q < 60; ++q) {
      const int id = 100000 + q;
      Eigen::VectorXd p(3);
      p << ux(gen), uy(gen), 0.0;
      p[2] = Surface::height(p[0], p[1]) + uz(gen);
      s.X[id] = p;
      slaves.push_back(id);
    }
    FacetSearch search(type, s.facets, radius);
    search.update(slaves, s.position(), /*forceGlobal=*/true);
    for (size_t q = 0; q < slaves.size(); ++q) {
      const FacetCandidate ref = bruteForce(type, s, s.X.at(slaves[q]), radius);
      const FacetCandidate& c = search.candidates()[q];
      ASSERT_GE(c.facet, 0) << "slave " << q;
      EXPECT_NEAR(c.distance, ref.distance, ddc::test::kRoundoff) << "slave " << q;
      EXPECT_EQ(c.facet, ref.facet) << "slave " << q;
      EXPECT_EQ(c.kind, FacetPointKind::Interior) << "slaves above the surface project inside some facet";
      EXPECT_NEAR(c.gap, s.X.at(slaves[q])[2] > Surface::height(s.X.at(slaves[q])[0], s.X.at(slaves[q])[1]) ? c.distance
                                                                                                           : -c.distance,
                  ddc::test::kRoundoff)
          << "signed gap";
    }
    // Move every slave a little and track; a fresh global search agrees.
    std::uniform_real_distribution<double> step(-0.12, 0.12);
    for (int id : slaves) s.X[id] += Eigen::Vector3d(step(gen), step(gen), 0.3 * step(gen));
    search.update(slaves, s.position(), false);
    FacetSearch fresh(type, s.facets, radius);
    fresh.update(slaves, s.position(), true);
    for (size_t q = 0; q < slaves.size(); ++q) {
      EXPECT_NEAR(search.candidates()[q].distance, fresh.candidates()[q].distance, ddc::test::kRoundoff) << q;
      EXPECT_EQ(search.candidates()[q].facet, fresh.candidates()[q].facet) << q;
    }
    EXPECT_EQ(search.trackingQueries(), long(slaves.size()));
  }
}

TEST(FacetSearch, ConvexEdgeAndCornerUseTheNearestPointAndItsDirection) {
  // Flat unit square facet in z = 0. Beyond its corner (0, 0) and beyond its
  // edge y = 0: no interior projection; the nearest point is the corner / the
  // edge point, the normal the unit direction to the slave, the gap the
  // distance (contact is not lost at a convex edge).
  Eigen::MatrixXd x(4, 3);
  x << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  Eigen::VectorXd corner(3), edge(3);
  corner << -0.3, -0.4, 0.0;
  edge << 0.6, -0.3, 0.4;
  const FacetCandidate c = ddc::nearestPoint(CellType::Quad4, x, corner);
  EXPECT_EQ(c.kind, FacetPointKind::Vertex);
  EXPECT_NEAR(c.distance, 0.5, ddc::test::kRoundoff);
  EXPECT_NEAR(c.normal[0], -0.6, ddc::test::kRoundoff);
  EXPECT_NEAR(c.normal[1], -0.8, ddc::test::kRoundoff);
  const FacetCandidate e = ddc::nearestPoint(CellType::Quad4, x, edge);
  EXPECT_EQ(e.kind, FacetPointKind::Edge);
  EXPECT_NEAR(e.point[0], 0.6, ddc::test::kRoundoff);
  EXPECT_NEAR(e.distance, 0.5, ddc::test::kRoundoff);
  EXPECT_NEAR(e.normal[1], -0.6, ddc::test::kRoundoff);
  EXPECT_NEAR(e.normal[2], 0.8, ddc::test::kRoundoff);
  EXPECT_NEAR(e.gap, 0.5, ddc::test::kRoundoff);
}

TEST(FacetSearch, ConcaveFoldPairsWithTheNearerFacet) {
  // Two facets forming a valley along x = 1 (z = |x - 1| tilted): a slave
  // above the fold, slightly to the right, projects into both; the nearer
  // interior projection wins and the pairing is interior.
  std::map<int, Eigen::VectorXd> X;
  auto put = [&](int id, double a, double b, double c) {
    Eigen::VectorXd p(3);
    p << a, b, c;
    X[id] = p;
  };
  put(0, 0, 0, 0.5), put(1, 1, 0, 0), put(2, 2, 0, 0.5), put(3, 0, 1, 0.5), put(4, 1, 1, 0), put(5, 2, 1, 0.5);
  put(9, 1.05, 0.5, 0.2);
  std::vector<std::vector<int>> facets = {{0, 1, 4, 3}, {1, 2, 5, 4}};
  FacetSearch search(CellType::Quad4, facets, 1.0);
  search.update({9}, [&](int n) { return X.at(n); }, true);
  const FacetCandidate& c = search.candidates()[0];
  EXPECT_EQ(c.facet, 1) << "the right-hand facet is nearer";
  EXPECT_EQ(c.kind, FacetPointKind::Interior);
  EXPECT_GT(c.gap, 0.0);
}

TEST(FacetSearch, BadInputIsRejected) {
  EXPECT_THROW(FacetSearch(CellType::Quad4, {}, 1.0), std::invalid_argument);
  EXPECT_THROW(FacetSearch(CellType::Quad4, {{0, 1, 2}}, 1.0), std::invalid_argument);
  EXPECT_THROW(FacetSearch(CellType::Quad4, {{0, 1, 2, 3}}, 0.0), std::invalid_argument);
  EXPECT_THROW(FacetSearch(CellType::Hex8, {{0, 1, 2, 3, 4, 5, 6, 7}}, 1.0), std::invalid_argument);
}

}  // namespace
