// Contact search and tracking: the binned global search and the tracking walk
// against a brute-force all-pairs reference of the rule in
// DDC_ContactSearch.hpp, hand-computed corner / free-end / leaving cases,
// counters, and master surfaces from mesh side sets.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>

#include <cmath>
#include <functional>
#include <random>

#include "DDC_ContactSearch.hpp"
#include "DDC_Error.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

using ddc::ContactCandidate;
using ddc::ContactSearch;
using ddc::InputError;
using ddc::MasterSurface;
using ddc::test::kRoundoff;
using ::testing::HasSubstr;
using Vec = Eigen::Vector2d;
using Segs = std::vector<std::array<int, 2>>;

namespace {

using ddc::test::inputErrorOf;

constexpr double kPi = 3.14159265358979323846;

/// Search and reference evaluate the same formulas on O(1) coordinates, so ξ,
/// gap and distance agree to round-off; two different segments are accepted
/// only as a tie, i.e. at the same distance to round-off.
constexpr double kSameGeometry = kRoundoff;

/// Nodes (positions indexed by node id) and master segments.
struct Geometry {
  std::vector<Vec> x;
  Segs segs;
  std::function<Vec(int)> position() const {
    return [this](int n) { return x.at(n); };
  }
  int addNode(const Vec& p) {
    x.push_back(p);
    return static_cast<int>(x.size()) - 1;
  }
};

/// Brute-force reference: every segment, the rule of DDC_ContactSearch.hpp
/// written out independently (plain doubles, explicit clamping).
ContactCandidate bruteForce(const Geometry& g, const Vec& xs, double radius) {
  ContactCandidate best;
  double bestD = 0.0;
  bool bestOutside = false;
  for (int k = 0; k < static_cast<int>(g.segs.size()); ++k) {
    const double ax = g.x[g.segs[k][0]].x(), ay = g.x[g.segs[k][0]].y();
    const double bx = g.x[g.segs[k][1]].x(), by = g.x[g.segs[k][1]].y();
    const double tx = bx - ax, ty = by - ay, len = std::sqrt(tx * tx + ty * ty);
    const double xiRaw = ((xs.x() - ax) * tx + (xs.y() - ay) * ty) / (tx * tx + ty * ty);
    const bool outside = xiRaw < -ddc::kEndTolerance || xiRaw > 1.0 + ddc::kEndTolerance;
    const double xi = std::min(1.0, std::max(0.0, xiRaw));
    const double px = xi == 0.0 ? ax : xi == 1.0 ? bx : ax + xi * tx;
    const double py = xi == 0.0 ? ay : xi == 1.0 ? by : ay + xi * ty;
    const double d = std::hypot(xs.x() - px, xs.y() - py);
    if (d > radius) continue;
    const bool better = best.segment < 0 || d < bestD || (d == bestD && !outside && bestOutside);
    if (!better) continue;
    best.segment = k;
    best.xi = xi;
    best.distance = d;
    best.normal = Vec(ty / len, -tx / len);
    best.gap = best.normal.x() * (xs.x() - ax) + best.normal.y() * (xs.y() - ay);
    best.point = Vec(px, py);
    best.viaCorner = outside;
    bestD = d;
    bestOutside = outside;
  }
  return best;
}

/// Compare one search result with the reference; returns a failure message.
::testing::AssertionResult sameCandidate(const ContactCandidate& c, const ContactCandidate& ref) {
  if ((c.segment < 0) != (ref.segment < 0))
    return ::testing::AssertionFailure() << "segment " << c.segment << " vs reference " << ref.segment;
  if (c.segment < 0) return ::testing::AssertionSuccess();
  if (std::abs(c.distance - ref.distance) > kSameGeometry)
    return ::testing::AssertionFailure() << "segment " << c.segment << " at distance " << c.distance
                                         << " vs reference " << ref.segment << " at " << ref.distance;
  if (c.segment != ref.segment) return ::testing::AssertionSuccess();  // a tie, same distance
  if (std::abs(c.xi - ref.xi) > kSameGeometry || std::abs(c.gap - ref.gap) > kSameGeometry ||
      (c.normal - ref.normal).norm() > kSameGeometry || (c.point - ref.point).norm() > kSameGeometry ||
      c.viaCorner != ref.viaCorner)
    return ::testing::AssertionFailure() << "segment " << c.segment << ": xi " << c.xi << " / " << ref.xi << ", gap "
                                         << c.gap << " / " << ref.gap << ", viaCorner " << c.viaCorner << " / "
                                         << ref.viaCorner;
  return ::testing::AssertionSuccess();
}

/// Open "wavy" polyline y = A sin(2πx/λ) + noise over x ∈ [0, L], nodes
/// 0..n, oriented right to left so the outward normal points +y (body below).
void addWavyPolyline(Geometry& g, int n, double L, double A, double lambda, double noise, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int first = static_cast<int>(g.x.size());
  for (int i = 0; i <= n; ++i) {
    const double x = L * i / n + noise * u(rng);
    g.addNode(Vec(x, A * std::sin(2 * kPi * x / lambda) + noise * u(rng)));
  }
  for (int i = 0; i < n; ++i) g.segs.push_back({first + i + 1, first + i});
}

/// Closed star-shaped loop r(θ) = R0 (1 + a sin(kθ)) + noise around c,
/// counter-clockwise (body inside, outward normals point away from c).
void addStarLoop(Geometry& g, int n, const Vec& c, double R0, double a, int k, double noise, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int first = static_cast<int>(g.x.size());
  for (int i = 0; i < n; ++i) {
    const double th = 2 * kPi * i / n;
    const double r = R0 * (1 + a * std::sin(k * th)) + noise * u(rng);
    g.addNode(c + r * Vec(std::cos(th), std::sin(th)));
  }
  for (int i = 0; i < n; ++i) g.segs.push_back({first + i, first + (i + 1) % n});
}

/// Bounding box of the master nodes, inflated by `pad`.
std::array<double, 4> masterBox(const Geometry& g, double pad) {
  std::array<double, 4> b{{1e300, 1e300, -1e300, -1e300}};
  for (const auto& s : g.segs)
    for (int n : s) {
      b[0] = std::min(b[0], g.x[n].x() - pad);
      b[1] = std::min(b[1], g.x[n].y() - pad);
      b[2] = std::max(b[2], g.x[n].x() + pad);
      b[3] = std::max(b[3], g.x[n].y() + pad);
    }
  return b;
}

/// Add `count` random slave nodes uniformly in `box`; returns their ids.
std::vector<int> addRandomSlaves(Geometry& g, int count, const std::array<double, 4>& box, std::mt19937& rng) {
  std::uniform_real_distribution<double> ux(box[0], box[2]), uy(box[1], box[3]);
  std::vector<int> ids;
  for (int i = 0; i < count; ++i) ids.push_back(g.addNode(Vec(ux(rng), uy(rng))));
  return ids;
}

/// Check every candidate of `search` against the brute-force reference.
void expectMatchesBruteForce(const ContactSearch& search, const Geometry& g, const std::string& where) {
  const auto& c = search.candidates();
  for (std::size_t i = 0; i < c.size(); ++i)
    EXPECT_TRUE(sameCandidate(c[i], bruteForce(g, g.x[search.slaveNodes()[i]], search.searchRadius())))
        << where << ", slave " << i << " at (" << g.x[search.slaveNodes()[i]].transpose() << ")";
}

Teuchos::ParameterList rectParams(double lx, double ly, int nx, int ny) {
  Teuchos::ParameterList p("Rectangle");
  p.set("Length X", lx);
  p.set("Length Y", ly);
  p.set("Elements X", nx);
  p.set("Elements Y", ny);
  return p;
}

/// Unit square [0,1]² as a closed counter-clockwise loop: segments
/// 0 bottom (n = -y), 1 right (+x), 2 top (+y), 3 left (-x).
Geometry unitSquare() {
  Geometry g;
  for (const Vec& p : {Vec(0, 0), Vec(1, 0), Vec(1, 1), Vec(0, 1)}) g.addNode(p);
  g.segs = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  return g;
}

}  // namespace

// --- master surface --------------------------------------------------------

TEST(MasterSurface, AdjacencyOfOpenChainAndClosedLoop) {
  const MasterSurface open(Segs{{5, 4}, {4, 3}, {3, 2}});
  EXPECT_EQ(open.neighbour(0, 0), -1);  // free end at node 5
  EXPECT_EQ(open.neighbour(0, 1), 1);
  EXPECT_EQ(open.neighbour(1, 0), 0);
  EXPECT_EQ(open.neighbour(1, 1), 2);
  EXPECT_EQ(open.neighbour(2, 1), -1);  // free end at node 2
  EXPECT_EQ(open.nodes(), (std::vector<int>{2, 3, 4, 5}));
  EXPECT_EQ(open.localNode(4), 2);
  EXPECT_EQ(open.localNode(7), -1);

  // Segments listed out of order still chain through shared nodes.
  const MasterSurface loop(Segs{{2, 3}, {0, 1}, {3, 0}, {1, 2}});
  EXPECT_EQ(loop.neighbour(0, 0), 3);
  EXPECT_EQ(loop.neighbour(0, 1), 2);
  EXPECT_EQ(loop.neighbour(2, 1), 1);
  EXPECT_EQ(loop.neighbour(1, 0), 2);
  for (int k = 0; k < 4; ++k)
    for (int e = 0; e < 2; ++e) EXPECT_GE(loop.neighbour(k, e), 0) << k << "," << e;
}

TEST(MasterSurface, RejectsSurfacesThatAreNotSimpleOrientedChains) {
  EXPECT_THAT(inputErrorOf([] { MasterSurface(Segs{}); }), HasSubstr("no segments"));
  EXPECT_THAT(inputErrorOf([] { MasterSurface(Segs{{1, 1}}); }), HasSubstr("starts and ends at node 1"));
  EXPECT_THAT(inputErrorOf([] { MasterSurface(Segs{{-1, 1}}); }), HasSubstr("negative node id"));
  // Reversed orientation of the second segment: node 1 ends two segments.
  EXPECT_THAT(inputErrorOf([] { MasterSurface(Segs{{0, 1}, {2, 1}}); }), HasSubstr("node 1 ends segments 0 and 1"));
  // A branch: node 1 starts two segments.
  EXPECT_THAT(inputErrorOf([] { MasterSurface(Segs{{0, 1}, {1, 2}, {1, 3}}); }),
              HasSubstr("node 1 starts segments 1 and 2"));
}

TEST(ContactSearch, RejectsBadArguments) {
  const MasterSurface m(Segs{{0, 1}});
  EXPECT_THAT(inputErrorOf([&] { ContactSearch(m, {2}, 0.0); }), HasSubstr("search radius must be positive"));
  EXPECT_THAT(inputErrorOf([&] { ContactSearch(m, {2}, NAN); }), HasSubstr("search radius must be positive"));
  EXPECT_THAT(inputErrorOf([&] { ContactSearch(m, {2}, 1.0, -1); }), HasSubstr("step limit"));
  EXPECT_THAT(inputErrorOf([&] { ContactSearch(m, {2, 3, 2}, 1.0); }), HasSubstr("slave node 2 is listed twice"));
  EXPECT_THAT(inputErrorOf([&] { ContactSearch(m, {2, 1}, 1.0); }), HasSubstr("slave node 1 is also a node"));
}

TEST(ContactSearch, ZeroLengthMasterSegmentIsASolverError) {
  Geometry g;
  g.addNode(Vec(0, 0));
  g.addNode(Vec(0, 0));
  g.addNode(Vec(0, 1));
  ContactSearch s(MasterSurface(Segs{{0, 1}}), {2}, 1.0);
  EXPECT_THROW(s.update(g.position(), true), ddc::SolverError);
}

// --- hand-computed cases ---------------------------------------------------

TEST(ContactSearch, ProjectionGapAndNormalOnASquare) {
  Geometry g = unitSquare();
  const int above = g.addNode(Vec(0.25, 1.5));   // over the top side, separated
  const int inside = g.addNode(Vec(0.95, 0.9));  // penetrated, nearest the right side
  const int corner = g.addNode(Vec(1.1, 1.2));   // blind spot of the convex corner (1,1)
  const int far = g.addNode(Vec(3.0, 0.5));      // farther than the radius from everything
  ContactSearch s(MasterSurface(g.segs), {above, inside, corner, far}, 0.6);
  s.update(g.position(), false);
  const auto& c = s.candidates();

  EXPECT_EQ(c[0].segment, 2);  // top: from (1,1) to (0,1)
  EXPECT_NEAR(c[0].xi, 0.75, kRoundoff);
  EXPECT_NEAR(c[0].gap, 0.5, kRoundoff);
  EXPECT_NEAR(c[0].distance, 0.5, kRoundoff);
  EXPECT_TRUE(c[0].normal.isApprox(Vec(0, 1)));
  EXPECT_TRUE(c[0].point.isApprox(Vec(0.25, 1.0)));
  EXPECT_FALSE(c[0].viaCorner);

  EXPECT_EQ(c[1].segment, 1);  // right: from (1,0) to (1,1)
  EXPECT_NEAR(c[1].xi, 0.9, kRoundoff);
  EXPECT_NEAR(c[1].gap, -0.05, kRoundoff);  // penetration
  EXPECT_FALSE(c[1].viaCorner);

  // Blind spot: projects outside the right (ξ = 1.2) and the top side (ξ = −0.1);
  // both are at the corner's distance, the lower index wins.
  EXPECT_EQ(c[2].segment, 1);
  EXPECT_TRUE(c[2].viaCorner);
  EXPECT_EQ(c[2].xi, 1.0);
  EXPECT_EQ(c[2].point, Vec(1.0, 1.0));
  EXPECT_NEAR(c[2].distance, std::hypot(0.1, 0.2), kRoundoff);
  EXPECT_NEAR(c[2].gap, 0.1, kRoundoff);  // along the right side's normal +x

  EXPECT_EQ(c[3].segment, -1);  // leaves the surface
}

TEST(ContactSearch, ExactTiePrefersTheSegmentProjectedInsideOverTheLowerIndex) {
  // Left of corner (0,0): on the extension of the bottom side (segment 0,
  // ξ = −0.5, outside) and exactly on the normal line of the left side at its
  // end (segment 3, ξ = 1, inside). Same distance 0.5; segment 3 wins.
  Geometry g = unitSquare();
  const int s0 = g.addNode(Vec(-0.5, 0.0));
  ContactSearch s(MasterSurface(g.segs), {s0}, 1.0);
  s.update(g.position(), true);
  EXPECT_EQ(s.candidates()[0].segment, 3);
  EXPECT_FALSE(s.candidates()[0].viaCorner);
  EXPECT_NEAR(s.candidates()[0].gap, 0.5, kRoundoff);
}

TEST(ContactSearch, BlindSpotTieGoesToTheLowerIndexForAnyCoordinates) {
  // Random convex corners with coordinates that are not exactly representable:
  // both segments at the corner must report the corner node itself (not
  // x1 + 1·t, which rounds), so the tie is exact and the lower index wins.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    Geometry g;
    const Vec corner(0.1 + 0.3 * u(rng), 0.7 + 0.3 * u(rng));
    // A left turn of 0.3 .. 2.7 rad: convex, the body being on the left.
    const double a0 = kPi * u(rng), turn = 0.3 + 1.2 * (u(rng) + 1.0);
    const Vec d1(std::cos(a0), std::sin(a0)), d2(std::cos(a0 + turn), std::sin(a0 + turn));
    g.addNode(corner - 0.37 * d1);
    g.addNode(corner);
    g.addNode(corner + 0.53 * d2);
    // In the blind spot: outward normals of both segments, mixed.
    const Vec n1(d1.y(), -d1.x()), n2(d2.y(), -d2.x());
    const double w = 0.5 * (u(rng) + 1.0);
    const int sl = g.addNode(corner + 0.1 * (w * n1 + (1 - w) * n2).normalized());
    const bool firstIsLower = trial % 2 == 0;  // list the segments in either order
    g.segs = firstIsLower ? Segs{{0, 1}, {1, 2}} : Segs{{1, 2}, {0, 1}};
    ContactSearch s(MasterSurface(g.segs), {sl}, 0.5);
    s.update(g.position(), true);
    const ContactCandidate& c = s.candidates()[0];
    ASSERT_EQ(c.segment, 0) << "trial " << trial;
    EXPECT_TRUE(c.viaCorner);
    EXPECT_EQ(c.point, corner);
    EXPECT_EQ(c.xi, firstIsLower ? 1.0 : 0.0);
    EXPECT_NEAR(c.distance, 0.1, kRoundoff);
    // Tracking from the other segment (index 1) agrees.
    const Vec blindSpot = g.x[sl];
    ContactSearch t(MasterSurface(g.segs), {sl}, 0.5);
    g.x[sl] = firstIsLower ? Vec(corner + 0.25 * d2 + 0.1 * n2) : Vec(corner - 0.25 * d1 + 0.1 * n1);
    t.update(g.position(), true);
    ASSERT_EQ(t.candidates()[0].segment, 1);
    g.x[sl] = blindSpot;
    t.update(g.position(), false);
    EXPECT_EQ(t.counters().trackingFallbacks, 0);
    EXPECT_EQ(t.candidates()[0].segment, 0) << "trial " << trial;
  }
}

TEST(ContactSearch, SearchRadiusIsInclusive) {
  Geometry g;
  g.addNode(Vec(1, 0));
  g.addNode(Vec(0, 0));
  const int at = g.addNode(Vec(0.5, 0.5)), beyond = g.addNode(Vec(0.5, std::nextafter(0.5, 1.0)));
  ContactSearch s(MasterSurface(Segs{{0, 1}}), {at, beyond}, 0.5);
  s.update(g.position(), true);
  EXPECT_EQ(s.candidates()[0].segment, 0);
  EXPECT_EQ(s.candidates()[1].segment, -1);
  g.x[at].y() = 0.4;
  s.update(g.position(), true);
  g.x[at].y() = 0.5;  // back to exactly the radius, found by tracking
  s.update(g.position(), false);
  EXPECT_EQ(s.candidates()[0].segment, 0);
  EXPECT_EQ(s.counters().trackingFallbacks, 0);
}

TEST(ContactSearch, ConcaveCornerTakesTheNearerSide) {
  // L-shaped body (counter-clockwise), concave corner at (1,1).
  Geometry g;
  for (const Vec& p : {Vec(0, 0), Vec(2, 0), Vec(2, 1), Vec(1, 1), Vec(1, 2), Vec(0, 2)}) g.addNode(p);
  for (int i = 0; i < 6; ++i) g.segs.push_back({i, (i + 1) % 6});
  // Projects inside both segment 2 ((2,1)→(1,1), n = +y) and 3 ((1,1)→(1,2), n = +x).
  const int a = g.addNode(Vec(1.3, 1.1));  // nearer the horizontal side
  const int b = g.addNode(Vec(1.1, 1.3));  // nearer the vertical side
  ContactSearch s(MasterSurface(g.segs), {a, b}, 0.5);
  s.update(g.position(), true);
  EXPECT_EQ(s.candidates()[0].segment, 2);
  EXPECT_NEAR(s.candidates()[0].gap, 0.1, kRoundoff);
  EXPECT_EQ(s.candidates()[1].segment, 3);
  EXPECT_NEAR(s.candidates()[1].gap, 0.1, kRoundoff);
  // Tracking from the other side of the corner must switch to the nearer one.
  std::swap(g.x[a], g.x[b]);
  s.update(g.position(), false);
  EXPECT_EQ(s.candidates()[0].segment, 3);
  EXPECT_EQ(s.candidates()[1].segment, 2);
  EXPECT_EQ(s.counters().trackingFallbacks, 0);
}

TEST(ContactSearch, TrackingAroundAClosedLoop) {
  // A slave circling the unit square at distance 0.2 crosses every corner,
  // including the wrap from segment 3 back to segment 0.
  Geometry g = unitSquare();
  const int sl = g.addNode(Vec(0, 0));
  ContactSearch s(MasterSurface(g.segs), {sl}, 0.5);
  const int steps = 400;
  for (int i = 0; i <= 2 * steps; ++i) {  // two turns
    const double th = 2 * kPi * i / steps;
    g.x[sl] = Vec(0.5, 0.5) + 0.5 * std::sqrt(2.0) * Vec(std::cos(th), std::sin(th)) * 1.1;
    s.update(g.position(), false);
    ASSERT_TRUE(sameCandidate(s.candidates()[0], bruteForce(g, g.x[sl], 0.5))) << "step " << i;
    ASSERT_GE(s.candidates()[0].segment, 0);
  }
  EXPECT_EQ(s.globalSearches(), 1);  // the first update only
  EXPECT_EQ(s.trackingCalls(), 2 * steps);
}

TEST(ContactSearch, FreeEndAndLeavingTheSurface) {
  // Open chain along y = 0 from (0,0) to (3,0), body below (n = +y):
  // segments (1→0), (2→1), (3→2); free ends at nodes 0 and 3.
  Geometry g;
  for (int i = 0; i <= 3; ++i) g.addNode(Vec(i, 0));
  g.segs = {{1, 0}, {2, 1}, {3, 2}};
  const MasterSurface m(g.segs);
  const int sl = g.addNode(Vec(2.5, 0.1));
  ContactSearch s(m, {sl}, 0.5);
  s.update(g.position(), false);
  EXPECT_EQ(s.candidates()[0].segment, 2);
  EXPECT_FALSE(s.candidates()[0].viaCorner);

  // Past the free end at x = 3, within the radius: paired via the end node;
  // the tracking walk would leave the surface and falls back to the global search.
  g.x[sl] = Vec(3.3, 0.1);
  s.update(g.position(), false);
  const ContactCandidate& c = s.candidates()[0];
  EXPECT_EQ(c.segment, 2);
  EXPECT_TRUE(c.viaCorner);
  EXPECT_EQ(c.xi, 0.0);
  EXPECT_EQ(c.point, Vec(3.0, 0.0));
  EXPECT_EQ(m.neighbour(c.segment, c.xi < 0.5 ? 0 : 1), -1);  // the documented free-end test
  EXPECT_NEAR(c.gap, 0.1, kRoundoff);
  EXPECT_EQ(s.counters().trackingFallbacks, 1);

  // Farther than the radius: leaves the surface.
  g.x[sl] = Vec(3.6, 0.1);
  s.update(g.position(), false);
  EXPECT_EQ(s.candidates()[0].segment, -1);
  EXPECT_EQ(s.counters().trackingFallbacks, 2);
  // Without a previous segment the next update searches globally (not a fallback).
  g.x[sl] = Vec(1.5, -0.2);
  s.update(g.position(), false);
  EXPECT_EQ(s.candidates()[0].segment, 1);
  EXPECT_NEAR(s.candidates()[0].gap, -0.2, kRoundoff);
  EXPECT_EQ(s.counters().trackingFallbacks, 2);
  EXPECT_EQ(s.globalSearches(), 4);
  EXPECT_EQ(s.trackingCalls(), 2);
}

TEST(ContactSearch, ASlaveOnTheFreeEndNodeStaysInsideDespiteRoundOff) {
  // A patch whose slave and master surfaces end together: the slave end node
  // sits on the master end node (3, 0). Round-off of its position (1e-15
  // past the end) must not make it "past the free end" (a pair that cannot
  // be active); a real overhang (1e-6) still is.
  Geometry g;
  for (int i = 0; i <= 3; ++i) g.addNode(Vec(i, 0));
  g.segs = {{1, 0}, {2, 1}, {3, 2}};
  const MasterSurface m(g.segs);
  const int sl = g.addNode(Vec(3.0 + 1e-15, 0.0));
  ContactSearch s(m, {sl}, 0.5);
  for (bool global : {true, false}) {
    s.update(g.position(), global);
    EXPECT_EQ(s.candidates()[0].segment, 2);
    EXPECT_FALSE(s.candidates()[0].viaCorner) << (global ? "global" : "tracking");
    EXPECT_EQ(s.candidates()[0].xi, 0.0);
    EXPECT_TRUE(sameCandidate(s.candidates()[0], bruteForce(g, g.x[sl], 0.5)));
  }
  g.x[sl] = Vec(3.0 + 1e-6, 0.0);
  s.update(g.position(), true);
  EXPECT_TRUE(s.candidates()[0].viaCorner);
  EXPECT_TRUE(sameCandidate(s.candidates()[0], bruteForce(g, g.x[sl], 0.5)));
}

TEST(ContactSearch, StepLimitFallsBackToTheGlobalSearch) {
  Geometry g;
  for (int i = 0; i <= 40; ++i) g.addNode(Vec(0.1 * i, 0));
  for (int i = 0; i < 40; ++i) g.segs.push_back({i + 1, i});
  const int sl = g.addNode(Vec(0.05, 0.05));
  ContactSearch s(MasterSurface(g.segs), {sl}, 0.2, 5);
  s.update(g.position(), false);
  EXPECT_EQ(s.candidates()[0].segment, 0);
  g.x[sl] = Vec(0.45, 0.05);  // 4 segments on: within the limit
  s.update(g.position(), false);
  EXPECT_EQ(s.candidates()[0].segment, 4);
  EXPECT_EQ(s.counters().trackingFallbacks, 0);
  g.x[sl] = Vec(1.55, 0.05);  // 11 segments on: over the limit
  s.update(g.position(), false);
  EXPECT_EQ(s.candidates()[0].segment, 15);
  EXPECT_EQ(s.counters().trackingFallbacks, 1);
  EXPECT_EQ(s.globalSearches(), 2);
}

// --- random meshes against brute force -------------------------------------

TEST(ContactSearch, GlobalSearchMatchesBruteForceOnRandomWavyPolylines) {
  std::mt19937 rng(20240611);
  std::uniform_int_distribution<int> nseg(50, 200);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int trial = 0; trial < 30; ++trial) {
    Geometry g;
    const int n = nseg(rng);
    const double L = 10.0, h = L / n;
    // Smooth to very jagged (noise up to a whole segment length): corners of
    // both kinds, blind spots, near-folds.
    addWavyPolyline(g, n, L, 2.0 * u01(rng), 0.5 + 4.0 * u01(rng), h * u01(rng), rng);
    const double radius = h * (0.05 + 5.0 * u01(rng));
    const auto slaves = addRandomSlaves(g, 600, masterBox(g, 1.5 * radius), rng);
    ContactSearch s(MasterSurface(g.segs), slaves, radius);
    s.update(g.position(), true);
    expectMatchesBruteForce(s, g, "trial " + std::to_string(trial));
    EXPECT_EQ(s.counters().gridBuilds, 1);
  }
}

TEST(ContactSearch, GlobalSearchMatchesBruteForceOnRandomClosedLoops) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Geometry g;
    const int n = 50 + static_cast<int>(150 * u01(rng));
    addStarLoop(g, n, Vec(u01(rng), u01(rng)), 1.0, 0.4 * u01(rng), 2 + trial % 7, 0.02 * u01(rng), rng);
    // A second, separate chain: the surface need not be connected.
    addWavyPolyline(g, 30, 3.0, 0.1, 1.0, 0.0, rng);
    for (int i = n; i < static_cast<int>(g.x.size()); ++i) g.x[i] += Vec(-1.5, -1.8);
    const double radius = 0.02 + 0.5 * u01(rng);
    const auto slaves = addRandomSlaves(g, 800, masterBox(g, 1.2 * radius), rng);
    ContactSearch s(MasterSurface(g.segs), slaves, radius);
    s.update(g.position(), true);
    expectMatchesBruteForce(s, g, "loop trial " + std::to_string(trial));
  }
}

TEST(ContactSearch, GlobalSearchIsNotAllPairs) {
  std::mt19937 rng(11);
  Geometry g;
  const int n = 2000;
  addWavyPolyline(g, n, 100.0, 3.0, 7.0, 0.01, rng);
  const double radius = 0.2;  // a few segment lengths (0.05)
  const auto slaves = addRandomSlaves(g, 1000, masterBox(g, radius), rng);
  ContactSearch s(MasterSurface(g.segs), slaves, radius);
  s.update(g.position(), true);
  expectMatchesBruteForce(s, g, "large");
  // All pairs would be 2e6 projections; the bins need a few per slave.
  EXPECT_LT(s.counters().projections, 100L * static_cast<long>(slaves.size()));
}

// --- tracking ----------------------------------------------------------------

TEST(ContactSearch, TrackingAfterSmallRandomMotionsEqualsAFreshGlobalSearch) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    Geometry g;
    const int n = 100 + 20 * trial;
    const double L = 10.0, h = L / n;
    // Curvature radius λ²/(4π²A) ≈ 0.5 is well above the radius: the nearest
    // point is unique for every slave within the radius (no folds).
    addWavyPolyline(g, n, L, 0.2, 2.0, 0.0, rng);
    const double radius = 0.25;
    // Slaves near the surface, away from the free ends. Each update moves
    // everything by a smooth random field (up to ~0.5 h: a translation plus a
    // wave) and jitters every node around its carried position (slaves by up
    // to 0.3 h per coordinate, master nodes by 0.01 h), so the slaves never
    // drift out of the radius and the surface never folds.
    std::vector<int> slaves;
    for (int i = 0; i < 300; ++i) {
      const double x = L * (0.5 + 0.3 * u(rng));
      const double y = 0.2 * std::sin(2 * kPi * x / 2.0) + 0.1 * u(rng);
      slaves.push_back(g.addNode(Vec(x, y)));
    }
    std::vector<Vec> carried = g.x;
    ContactSearch tracked(MasterSurface(g.segs), slaves, radius);
    tracked.update(g.position(), false);  // no previous segments: global
    EXPECT_EQ(tracked.globalSearches(), 300);
    long walkProjections = 0;
    const int updates = 20;
    const int firstSlave = slaves.front();
    for (int step = 0; step < updates; ++step) {
      const double cx = u(rng), cy = u(rng), phase = kPi * u(rng);
      for (std::size_t i = 0; i < g.x.size(); ++i) {
        const Vec& p = carried[i];
        carried[i] += 0.3 * h * Vec(cx + 0.5 * std::sin(p.x() + phase), cy + 0.5 * std::cos(p.x() + phase));
        const double jitter = static_cast<int>(i) >= firstSlave ? 0.3 * h : 0.01 * h;
        g.x[i] = carried[i] + jitter * Vec(u(rng), u(rng));
      }
      const long before = tracked.counters().projections;
      tracked.update(g.position(), false);
      walkProjections += tracked.counters().projections - before;
      ContactSearch fresh(MasterSurface(g.segs), slaves, radius);
      fresh.update(g.position(), true);
      for (std::size_t i = 0; i < slaves.size(); ++i) {
        const auto& a = tracked.candidates()[i];
        const auto& b = fresh.candidates()[i];
        ASSERT_GE(b.segment, 0);
        ASSERT_EQ(a.segment, b.segment) << "trial " << trial << " step " << step << " slave " << i;
        ASSERT_EQ(a.xi, b.xi);  // same formula, same numbers: bitwise
        ASSERT_EQ(a.gap, b.gap);
        ASSERT_EQ(a.viaCorner, b.viaCorner);
        ASSERT_TRUE(sameCandidate(a, bruteForce(g, g.x[slaves[i]], radius)));
      }
    }
    // Tracking answered every later query: one global search per slave (the
    // first update), one grid, and a walk of a few projections per query.
    EXPECT_EQ(tracked.globalSearches(), 300);
    EXPECT_EQ(tracked.trackingCalls(), 300L * updates);
    EXPECT_EQ(tracked.counters().trackingFallbacks, 0);
    EXPECT_EQ(tracked.counters().gridBuilds, 1);
    EXPECT_LT(walkProjections, 8L * 300 * updates);
  }
}

TEST(ContactSearch, TrackingWithLargerMotionsStillMatchesBruteForce) {
  // Slaves wander (some leave the radius, some pass the free ends, some jump
  // past the step limit); whatever tracking cannot answer falls back.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Geometry g;
  addWavyPolyline(g, 150, 10.0, 0.2, 2.0, 0.0, rng);
  const double radius = 0.25;
  const auto slaves = addRandomSlaves(g, 400, masterBox(g, 0.4), rng);
  ContactSearch s(MasterSurface(g.segs), slaves, radius, 4);
  for (int step = 0; step < 30; ++step) {
    for (int n : slaves) g.x[n] += 0.15 * Vec(u(rng), u(rng));
    s.update(g.position(), step % 10 == 9);
    expectMatchesBruteForce(s, g, "step " + std::to_string(step));
  }
  EXPECT_GT(s.counters().trackingFallbacks, 0);
  EXPECT_GT(s.trackingCalls(), s.counters().trackingFallbacks);
}

TEST(ContactSearch, ForceGlobalIgnoresPreviousPairings) {
  Geometry g = unitSquare();
  const int sl = g.addNode(Vec(0.5, 1.2));
  ContactSearch s(MasterSurface(g.segs), {sl}, 0.5);
  s.update(g.position(), true);
  s.update(g.position(), true);
  EXPECT_EQ(s.globalSearches(), 2);
  EXPECT_EQ(s.trackingCalls(), 0);
  EXPECT_EQ(s.counters().gridBuilds, 2);
  s.update(g.position(), false);
  EXPECT_EQ(s.globalSearches(), 2);
  EXPECT_EQ(s.trackingCalls(), 1);
  EXPECT_EQ(s.counters().gridBuilds, 2);  // tracking needs no grid
}

// --- mesh side sets ----------------------------------------------------------

TEST(MasterSegmentsFromSideSet, RectangleTopHasUpwardNormals) {
  ddc::Mesh m;
  auto p = rectParams(2.0, 1.0, 4, 2);
  ddc::generateRectangle(m, "Block", ddc::CellType::Quad4, p, "R");
  const Segs segs = masterSegmentsFromSideSet(m, "Block/top");
  ASSERT_EQ(segs.size(), 4u);
  Geometry g;
  for (int n = 0; n < m.numNodes(); ++n) g.addNode(Vec(m.coord(n)[0], m.coord(n)[1]));
  g.segs = segs;
  for (const auto& s : segs) {
    const Vec t = g.x[s[1]] - g.x[s[0]];
    EXPECT_NEAR(g.x[s[0]].y(), 1.0, kRoundoff);
    EXPECT_TRUE(Vec(t.y(), -t.x()).normalized().isApprox(Vec(0, 1))) << s[0] << "->" << s[1];
  }
  // A slave above the block is separated (g > 0), one inside penetrates.
  const int above = g.addNode(Vec(0.3, 1.1)), below = g.addNode(Vec(1.3, 0.95));
  ContactSearch search(MasterSurface(segs), {above, below}, 0.3);
  search.update(g.position(), true);
  EXPECT_NEAR(search.candidates()[0].gap, 0.1, kRoundoff);
  EXPECT_NEAR(search.candidates()[1].gap, -0.05, kRoundoff);
  EXPECT_TRUE(search.candidates()[1].normal.isApprox(Vec(0, 1)));
}

TEST(MasterSegmentsFromSideSet, RejectsQuad9SidesAndUnknownSets) {
  ddc::Mesh m;
  auto p = rectParams(2.0, 1.0, 2, 1);
  ddc::generateRectangle(m, "B", ddc::CellType::Quad9, p, "R");
  const std::string msg = inputErrorOf([&] { masterSegmentsFromSideSet(m, "B/top"); });
  EXPECT_THAT(msg, HasSubstr("contact surfaces must be Quad4 sides for now"));
  EXPECT_THAT(msg, HasSubstr("B/top"));
  EXPECT_THAT(inputErrorOf([&] { masterSegmentsFromSideSet(m, "B/nope"); }), HasSubstr("B/nope"));
}

// --- the facing rule ------------------------------------------------------------

namespace {

/// The facing rule written out independently of DDC_ContactSearch.cpp: the
/// slave normal as the normalised sum of its segments' unit outward normals,
/// then n_s·n_m < 0 and, behind the segment, −g < ½ depth.
ddc::ContactRejection referenceVerdict(const Geometry& g, const Segs& slaveSegs, int slave, const ContactCandidate& c,
                                       double depth) {
  double sx = 0.0, sy = 0.0;
  for (const auto& s : slaveSegs) {
    if (s[0] != slave && s[1] != slave) continue;
    const double tx = g.x[s[1]].x() - g.x[s[0]].x(), ty = g.x[s[1]].y() - g.x[s[0]].y();
    const double len = std::sqrt(tx * tx + ty * ty);
    sx += ty / len;
    sy += -tx / len;
  }
  const double len = std::sqrt(sx * sx + sy * sy);
  const double dot = len > 0.0 ? (sx * c.normal.x() + sy * c.normal.y()) / len : 0.0;
  if (!(dot < 0.0)) return ddc::ContactRejection::NotFacing;
  if (c.gap < 0.0 && !(-c.gap < 0.5 * depth)) return ddc::ContactRejection::TooDeep;
  return ddc::ContactRejection::None;
}

ddc::FacingRule uniformRule(const Segs& slaveSegs, int numMasterSegments, double depth) {
  ddc::FacingRule r;
  r.slaveSegments = slaveSegs;
  r.masterDepths.assign(numMasterSegments, depth);
  return r;
}

/// Master: y = 0 from x = 1 to x = 0 (body below, n = +y), element depth 0.25.
/// Slave: one node at (0.5, y) on two slave segments to (0.3, y') and
/// (0.7, y'), ordered so that the slave body is above (n_s = −y) or, with
/// `facingAway`, below (n_s = +y).
struct OneSlave {
  Geometry g;
  Segs slaveSegs;
  int slave = -1;
  OneSlave(double y, bool facingAway) {
    g.addNode(Vec(1, 0));
    g.addNode(Vec(0, 0));
    g.segs = {{0, 1}};
    const int left = g.addNode(Vec(0.3, y + 0.01)), right = g.addNode(Vec(0.7, y + 0.01));
    slave = g.addNode(Vec(0.5, y));
    // Body above: travel left to right along its bottom (n = (t_y, −t_x) points down).
    slaveSegs = facingAway ? Segs{{right, slave}, {slave, left}} : Segs{{left, slave}, {slave, right}};
  }
  ContactCandidate pair(double radius = 0.5) {
    ContactSearch s(MasterSurface(g.segs), {slave}, radius, uniformRule(slaveSegs, 1, 0.25));
    s.update(g.position(), true);
    return s.candidates()[0];
  }
};

}  // namespace

TEST(FacingRule, VerdictIsStrictInBothParts) {
  const Vec up(0, 1), down(0, -1), side(1, 0);
  EXPECT_EQ(ddc::facingVerdict(down, up, 0.1, 0.125), ddc::ContactRejection::None);
  EXPECT_EQ(ddc::facingVerdict(up, up, 0.1, 0.125), ddc::ContactRejection::NotFacing);
  // Perpendicular normals do not face each other (n_s·n_m = 0 exactly).
  EXPECT_EQ(ddc::facingVerdict(side, up, 0.1, 0.125), ddc::ContactRejection::NotFacing);
  // A node without a normal (its segments' normals cancel) faces nothing.
  EXPECT_EQ(ddc::facingVerdict(Vec::Zero(), up, 0.1, 0.125), ddc::ContactRejection::NotFacing);
  EXPECT_EQ(ddc::facingVerdict(down, up, -0.1, 0.125), ddc::ContactRejection::None);
  EXPECT_EQ(ddc::facingVerdict(down, up, -0.125, 0.125), ddc::ContactRejection::TooDeep);  // −g < limit, strictly
  EXPECT_EQ(ddc::facingVerdict(down, up, -0.2, 0.125), ddc::ContactRejection::TooDeep);
  // In front of the segment the depth limit does not apply (the search radius does).
  EXPECT_EQ(ddc::facingVerdict(down, up, 5.0, 0.125), ddc::ContactRejection::None);
}

TEST(FacingRule, PenetratingNodeOfAnotherBodyPairsUpToHalfTheElementDepth) {
  // Separated, touching and penetrating by less than ½ · 0.25: paired, and
  // exactly as without the rule.
  for (double y : {0.1, 0.0, -0.05, -0.124}) {
    OneSlave o(y, false);
    const ContactCandidate c = o.pair();
    ContactSearch plain(MasterSurface(o.g.segs), {o.slave}, 0.5);
    plain.update(o.g.position(), true);
    EXPECT_EQ(c.segment, 0) << "y = " << y;
    EXPECT_EQ(c.rejection, ddc::ContactRejection::None);
    EXPECT_EQ(c.gap, plain.candidates()[0].gap);
    EXPECT_EQ(c.xi, plain.candidates()[0].xi);
    EXPECT_TRUE(c.slaveNormal.isApprox(Vec(0, -1)));
  }
  // At or beyond half the depth: not paired, and the candidate says why.
  for (double y : {-0.125, -0.2}) {
    const ContactCandidate c = OneSlave(y, false).pair();
    EXPECT_EQ(c.segment, -1) << "y = " << y;
    EXPECT_EQ(c.rejection, ddc::ContactRejection::TooDeep);
    EXPECT_EQ(c.rejectedSegment, 0);
    EXPECT_NEAR(c.gap, y, kRoundoff);
  }
}

TEST(FacingRule, SlaveSurfaceFacingAwayIsNotPaired) {
  // Same positions, the slave body below its surface: both normals point up.
  for (double y : {0.1, -0.05}) {
    const ContactCandidate c = OneSlave(y, true).pair();
    EXPECT_EQ(c.segment, -1) << "y = " << y;
    EXPECT_EQ(c.rejection, ddc::ContactRejection::NotFacing);
    EXPECT_TRUE(c.slaveNormal.isApprox(Vec(0, 1)));
  }
}

TEST(FacingRule, ThinBodyBottomIsNotPairedWithItsOwnTop) {
  // One element through the thickness (0.25), 12 along 4: every bottom node
  // is 0.25 from the top segment above it, inside the radius 1/3 (the mean
  // top segment length).
  ddc::Mesh m;
  auto p = rectParams(4.0, 0.25, 12, 1);
  ddc::generateRectangle(m, "Strip", ddc::CellType::Quad4, p, "R");
  const Segs top = masterSegmentsFromSideSet(m, "Strip/top");
  const auto depths = ddc::masterElementDepths(m, "Strip/top");
  ASSERT_EQ(depths.size(), top.size());
  for (double d : depths) EXPECT_NEAR(d, 0.25, kRoundoff);
  Geometry g;
  for (int n = 0; n < m.numNodes(); ++n) g.addNode(Vec(m.coord(n)[0], m.coord(n)[1]));
  const std::vector<int> bottom = m.nodeSet("Strip/bottom");
  ddc::FacingRule rule{masterSegmentsFromSideSet(m, "Strip/bottom"), depths};
  ContactSearch with(MasterSurface(top), bottom, 1.0 / 3.0, rule), without(MasterSurface(top), bottom, 1.0 / 3.0);
  with.update(g.position(), true);
  without.update(g.position(), true);
  ASSERT_EQ(bottom.size(), 13u);
  for (std::size_t i = 0; i < bottom.size(); ++i) {
    // Without the rule: paired through the body (the reported 13 spurious contacts).
    EXPECT_GE(without.candidates()[i].segment, 0);
    EXPECT_NEAR(without.candidates()[i].gap, -0.25, kRoundoff);
    // Opposed normals (bottom down, top up), but behind by the full depth.
    const ContactCandidate& c = with.candidates()[i];
    EXPECT_EQ(c.segment, -1) << "bottom node " << bottom[i];
    EXPECT_EQ(c.rejection, ddc::ContactRejection::TooDeep);
    EXPECT_LT(c.slaveNormal.dot(c.normal), 0.0);
  }
  // Bending the strip (tracking from the rejected state, then global) keeps
  // every bottom node unpaired: the thickness stays near 0.25.
  for (int n = 0; n < m.numNodes(); ++n) {
    const double x = m.coord(n)[0];
    g.x[n] += Vec(0.0, -0.05 * x * x);
  }
  with.update(g.position(), false);
  for (const auto& c : with.candidates()) EXPECT_EQ(c.rejection, ddc::ContactRejection::TooDeep);
}

TEST(FacingRule, TrackingAndGlobalSearchAgreeWithTheReference) {
  // A slave chain (body above, n_s ≈ −y) lowered in steps onto and through a
  // wavy master surface (body below, n ≈ +y) of element depth 0.1: nodes are
  // paired, then rejected as too deep, some not facing where the chain is
  // tilted by noise. Tracking, a fresh global search and the brute-force
  // reference with the rule written out independently must agree.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Geometry g;
  addWavyPolyline(g, 80, 8.0, 0.1, 2.0, 0.0, rng);
  const int numMaster = static_cast<int>(g.segs.size());
  const double depth = 0.1, radius = 0.3;
  std::vector<int> slaves;
  Segs slaveSegs;
  for (int i = 0; i <= 60; ++i) slaves.push_back(g.addNode(Vec(1.0 + 0.1 * i, 0.25 + 0.02 * u(rng))));
  for (int i = 0; i < 60; ++i) slaveSegs.push_back({slaves[i], slaves[i + 1]});
  // Two slave nodes turned upside down (a fold of the slave chain): they face away.
  std::swap(g.x[slaves[20]], g.x[slaves[21]]);
  ContactSearch tracked(MasterSurface(g.segs), slaves, radius, uniformRule(slaveSegs, numMaster, depth));
  int accepted = 0, tooDeep = 0, notFacing = 0;
  for (int step = 0; step < 40; ++step) {
    for (int n : slaves) g.x[n] += Vec(0.01 * u(rng), -0.01);
    tracked.update(g.position(), false);
    ContactSearch fresh(MasterSurface(g.segs), slaves, radius, uniformRule(slaveSegs, numMaster, depth));
    fresh.update(g.position(), true);
    for (std::size_t i = 0; i < slaves.size(); ++i) {
      const ContactCandidate& a = tracked.candidates()[i];
      const ContactCandidate& b = fresh.candidates()[i];
      ASSERT_EQ(a.segment, b.segment) << "step " << step << " slave " << i;
      ASSERT_EQ(a.rejection, b.rejection) << "step " << step << " slave " << i;
      ASSERT_EQ(a.rejectedSegment, b.rejectedSegment);
      ASSERT_EQ(a.gap, b.gap);
      // The reference: the nearest segment by brute force, then the rule.
      const ContactCandidate ref = bruteForce(g, g.x[slaves[i]], radius);
      const int k = b.segment >= 0 ? b.segment : b.rejectedSegment;
      ASSERT_EQ(k >= 0, ref.segment >= 0) << "step " << step << " slave " << i;
      if (k < 0) continue;
      ContactCandidate c = b;
      c.segment = k;
      ASSERT_TRUE(sameCandidate(c, ref)) << "step " << step << " slave " << i;
      ASSERT_EQ(b.rejection, referenceVerdict(g, slaveSegs, slaves[i], b, depth)) << "step " << step << " slave " << i;
      if (b.rejection == ddc::ContactRejection::None) ++accepted;
      if (b.rejection == ddc::ContactRejection::TooDeep) ++tooDeep;
      if (b.rejection == ddc::ContactRejection::NotFacing) ++notFacing;
    }
  }
  // All three outcomes occurred.
  EXPECT_GT(accepted, 0);
  EXPECT_GT(tooDeep, 0);
  EXPECT_GT(notFacing, 0);
}

TEST(FacingRule, RejectsInconsistentRuleData) {
  const MasterSurface m(Segs{{0, 1}, {1, 2}});
  EXPECT_THAT(inputErrorOf([&] { ContactSearch(m, {3}, 1.0, uniformRule(Segs{{3, 4}}, 1, 0.1)); }),
              HasSubstr("1 master element depths for 2 master segments"));
  EXPECT_THAT(inputErrorOf([&] { ContactSearch(m, {3}, 1.0, uniformRule(Segs{{3, 4}}, 2, 0.0)); }),
              HasSubstr("must be positive"));
  EXPECT_THAT(inputErrorOf([&] { ContactSearch(m, {3, 5}, 1.0, uniformRule(Segs{{3, 4}}, 2, 0.1)); }),
              HasSubstr("slave node 5 is on no slave segment"));
  EXPECT_THAT(inputErrorOf([&] { ContactSearch(m, {3}, 1.0, uniformRule(Segs{{3, 3}}, 2, 0.1)); }),
              HasSubstr("must join two distinct nodes"));
}

TEST(MasterSegmentsFromSideSet, ElementDepthIsTheExtentBehindTheSide) {
  ddc::Mesh m;
  auto p = rectParams(2.0, 1.0, 4, 2);  // elements 0.5 x 0.5
  ddc::generateRectangle(m, "Block", ddc::CellType::Quad4, p, "R");
  for (const char* set : {"Block/top", "Block/left", "Block/right", "Block/bottom"})
    for (double d : ddc::masterElementDepths(m, set)) EXPECT_NEAR(d, 0.5, kRoundoff) << set;
  ddc::Mesh flat;
  auto q = rectParams(2.0, 0.3, 4, 3);  // 0.5 x 0.1
  ddc::generateRectangle(flat, "F", ddc::CellType::Quad4, q, "R");
  for (double d : ddc::masterElementDepths(flat, "F/top")) EXPECT_NEAR(d, 0.1, kRoundoff);
  for (double d : ddc::masterElementDepths(flat, "F/left")) EXPECT_NEAR(d, 0.5, kRoundoff);
}
