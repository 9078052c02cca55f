// Built-in generators: counts, sets, areas, orientation, refinement,
// distortion and parameter errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>

#include "DDC_CoreTestUtils.hpp"
#include "DDC_Error.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

using ddc::CellType;
using ddc::InputError;
using ddc::Mesh;
using ddc::Segment;
using ::testing::HasSubstr;

namespace {

using ddc::test::inputErrorOf;

constexpr double kPi = 3.14159265358979323846;

Teuchos::ParameterList rectParams(double x0, double y0, double lx, double ly, int nx, int ny) {
  Teuchos::ParameterList p("Rectangle");
  p.set("Origin X", x0);
  p.set("Origin Y", y0);
  p.set("Length X", lx);
  p.set("Length Y", ly);
  p.set("Elements X", nx);
  p.set("Elements Y", ny);
  return p;
}

double totalArea(const Mesh& m, double* minDet) {
  double a = 0, mn = 1e300;
  for (int e = 0; e < m.numElements(); ++e) {
    double d;
    a += ddc::test::elementArea(m, e, &d);
    mn = std::min(mn, d);
  }
  *minDet = mn;
  return a;
}

/// Every segment of a side set: outward (a point a little outside along the
/// normal is not in the region, one a little inside is), and consecutive
/// segments chain end-to-start. "A little" is 1/10 of the segment length:
/// more than the sagitta of the chord of an arc of up to 45 degrees
/// (tan(angle/4)/2 < 1/10 of the chord), less than the distance to the other
/// boundaries in these meshes.
template <class Inside>
void expectOutwardChain(const Mesh& m, const std::string& set, Inside inside) {
  const auto& segs = m.sideSet(set);
  for (size_t k = 0; k < segs.size(); ++k) {
    const Segment& s = segs[k];
    const auto n = ddc::test::segmentNormal(m, s);
    const double len = std::hypot(n[0], n[1]);
    const auto mid = ddc::test::segmentMidpoint(m, s);
    const double eps = 0.1 * len;
    EXPECT_FALSE(inside(mid[0] + eps * n[0] / len, mid[1] + eps * n[1] / len)) << set << " segment " << k;
    EXPECT_TRUE(inside(mid[0] - eps * n[0] / len, mid[1] - eps * n[1] / len)) << set << " segment " << k;
    EXPECT_EQ(s.numNodes, m.elementType(s.element) == CellType::Quad9 ? 3 : 2);
    if (k + 1 < segs.size()) {
      EXPECT_EQ(s.nodes[1], segs[k + 1].nodes[0]) << set << " is not a chain at " << k;
    }
  }
}

}  // namespace

TEST(RectangleGenerator, Quad4CountsSetsAreaOrientation) {
  Mesh m;
  auto p = rectParams(1.0, -1.0, 2.0, 1.5, 4, 3);
  const int b = ddc::generateRectangle(m, "Block", CellType::Quad4, p, "Mesh/Bodies/Block/Rectangle");
  EXPECT_EQ(b, 0);
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.numNodes(), 5 * 4);
  EXPECT_EQ(m.numElements(), 12);
  double minDet;
  EXPECT_NEAR(totalArea(m, &minDet), 3.0, ddc::test::kRoundoff);
  EXPECT_GT(minDet, 0.0);
  EXPECT_EQ(m.sideSet("Block/bottom").size(), 4u);
  EXPECT_EQ(m.sideSet("Block/top").size(), 4u);
  EXPECT_EQ(m.sideSet("Block/left").size(), 3u);
  EXPECT_EQ(m.sideSet("Block/right").size(), 3u);
  EXPECT_EQ(m.nodeSet("Block/bottom").size(), 5u);
  EXPECT_EQ(m.nodeSet("Block/left").size(), 4u);
  EXPECT_EQ(m.nodeSet("Block/all").size(), 20u);
  const auto corner = [&](const std::string& n) { return m.coord(m.nodeSet("Block/" + n).at(0)); };
  EXPECT_EQ(m.nodeSet("Block/top right").size(), 1u);
  EXPECT_EQ(corner("bottom left"), (std::array<double, 3>{1.0, -1.0, 0.0}));
  EXPECT_EQ(corner("bottom right"), (std::array<double, 3>{3.0, -1.0, 0.0}));
  EXPECT_EQ(corner("top left"), (std::array<double, 3>{1.0, 0.5, 0.0}));
  EXPECT_EQ(corner("top right"), (std::array<double, 3>{3.0, 0.5, 0.0}));
  for (int n : m.nodeSet("Block/right")) EXPECT_EQ(m.coord(n)[0], 3.0);
  for (int n : m.nodeSet("Block/top")) EXPECT_EQ(m.coord(n)[1], 0.5);
  auto inside = [](double x, double y) { return x > 1.0 && x < 3.0 && y > -1.0 && y < 0.5; };
  for (const char* s : {"bottom", "right", "top", "left"}) expectOutwardChain(m, std::string("Block/") + s, inside);
  // Defaults were filled in.
  EXPECT_EQ(p.get<int>("Refinement"), 1);
  EXPECT_EQ(p.get<double>("Distortion"), 0.0);
}

TEST(RectangleGenerator, Quad9CountsAndMidNodes) {
  Mesh m;
  auto p = rectParams(0, 0, 2.0, 1.0, 4, 3);
  ddc::generateRectangle(m, "B", CellType::Quad9, p, "R");
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.numNodes(), 9 * 7);
  EXPECT_EQ(m.numElements(), 12);
  double minDet;
  EXPECT_NEAR(totalArea(m, &minDet), 2.0, ddc::test::kRoundoff);
  EXPECT_GT(minDet, 0.0);
  EXPECT_EQ(m.nodeSet("B/bottom").size(), 9u);
  EXPECT_EQ(m.nodeSet("B/left").size(), 7u);
  for (const auto& s : m.sideSet("B/top")) {
    ASSERT_EQ(s.numNodes, 3);
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(m.coord(s.nodes[2])[i], 0.5 * (m.coord(s.nodes[0])[i] + m.coord(s.nodes[1])[i]),
                  ddc::test::kRoundoff);
  }
  auto inside = [](double x, double y) { return x > 0 && x < 2 && y > 0 && y < 1; };
  for (const char* s : {"bottom", "right", "top", "left"}) expectOutwardChain(m, std::string("B/") + s, inside);
}

TEST(RectangleGenerator, RefinementMultipliesCounts) {
  for (CellType t : {CellType::Quad4, CellType::Quad9}) {
    Mesh m;
    auto p = rectParams(0, 0, 1, 1, 3, 2);
    p.set("Refinement", 3);
    ddc::generateRectangle(m, "B", t, p, "R");
    EXPECT_EQ(m.numElements(), 9 * 6);
    const int k = t == CellType::Quad9 ? 2 : 1;
    EXPECT_EQ(m.numNodes(), (k * 9 + 1) * (k * 6 + 1));
    EXPECT_EQ(m.sideSet("B/bottom").size(), 9u);
    EXPECT_EQ(m.sideSet("B/left").size(), 6u);
  }
}

TEST(RectangleGenerator, DistortionKeepsElementsValidAndIsDeterministic) {
  auto make = [](CellType t, double d) {
    Mesh m;
    auto p = rectParams(0, 0, 2.0, 1.0, 8, 6);
    p.set("Distortion", d);
    ddc::generateRectangle(m, "B", t, p, "R");
    return m;
  };
  for (CellType t : {CellType::Quad4, CellType::Quad9}) {
    const Mesh a = make(t, 0.3), b = make(t, 0.3), plain = make(t, 0.0);
    ASSERT_EQ(a.numNodes(), plain.numNodes());
    double minDet;
    // The boundary is not moved and edges stay straight: the area is exact.
    EXPECT_NEAR(totalArea(a, &minDet), 2.0, ddc::test::kRoundoff);
    EXPECT_GT(minDet, 0.0);
    int moved = 0;
    for (int n = 0; n < a.numNodes(); ++n) {
      EXPECT_EQ(a.coord(n), b.coord(n)) << "distortion is not reproducible";
      moved += a.coord(n) != plain.coord(n);
    }
    // Interior vertices: 7 x 5 (Quad9: their mid-side and centre nodes move too).
    EXPECT_GE(moved, 35);
    const std::set<int> boundary = [&] {
      std::set<int> s;
      for (const char* n : {"B/bottom", "B/right", "B/top", "B/left"})
        for (int i : a.nodeSet(n)) s.insert(i);
      return s;
    }();
    for (int n : boundary) EXPECT_EQ(a.coord(n), plain.coord(n)) << "boundary node " << n << " moved";
    if (t == CellType::Quad9) {
      // Mid-side nodes at the midpoints of straight edges, centre at the corner average.
      for (int e = 0; e < a.numElements(); ++e) {
        const int* en = a.elementNodes(e);
        for (int s = 0; s < 4; ++s)
          for (int i = 0; i < 2; ++i)
            EXPECT_NEAR(a.coord(en[4 + s])[i], 0.5 * (a.coord(en[s])[i] + a.coord(en[(s + 1) % 4])[i]),
                        ddc::test::kRoundoff);
        for (int i = 0; i < 2; ++i)
          EXPECT_NEAR(a.coord(en[8])[i],
                      0.25 * (a.coord(en[0])[i] + a.coord(en[1])[i] + a.coord(en[2])[i] + a.coord(en[3])[i]),
                      ddc::test::kRoundoff);
      }
    }
  }
  // Quad4 and Quad9 share the distorted vertices.
  const Mesh q4 = make(CellType::Quad4, 0.2), q9 = make(CellType::Quad9, 0.2);
  for (int e = 0; e < q4.numElements(); ++e)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(q4.coord(q4.elementNodes(e)[k]), q9.coord(q9.elementNodes(e)[k]));
}

TEST(RectangleGenerator, DistortionOnFineMeshesStaysValid) {
  // Many random draws at the largest distortion: no inverted element.
  for (int r : {1, 2, 4}) {
    Mesh m;
    auto p = rectParams(0, 0, 1.0, 3.0, 10, 10);  // aspect ratio 3
    p.set("Distortion", 0.3);
    p.set("Refinement", r);
    ddc::generateRectangle(m, "B", CellType::Quad9, p, "R");
    double minDet;
    EXPECT_NEAR(totalArea(m, &minDet), 3.0, 1e-11);
    EXPECT_GT(minDet, 0.0);
  }
}

TEST(RectangleGenerator, ParameterErrorsNameThePath) {
  const std::string path = "Mesh/Bodies/Block/Rectangle";
  auto run = [&](Teuchos::ParameterList p) {
    return inputErrorOf([&] {
      Mesh m;
      ddc::generateRectangle(m, "Block", CellType::Quad4, p, path);
    });
  };
  auto p = rectParams(0, 0, 0.0, 1, 2, 2);
  EXPECT_THAT(run(p), HasSubstr(path + "/Length X' must be > 0"));
  p = rectParams(0, 0, 1, -1, 2, 2);
  EXPECT_THAT(run(p), HasSubstr(path + "/Length Y"));
  p = rectParams(0, 0, 1, 1, 0, 2);
  EXPECT_THAT(run(p), HasSubstr(path + "/Elements X' must be > 0"));
  p = rectParams(0, 0, 1, 1, 2, -3);
  EXPECT_THAT(run(p), HasSubstr(path + "/Elements Y"));
  p = rectParams(0, 0, 1, 1, 2, 2);
  p.set("Refinement", 0);
  EXPECT_THAT(run(p), HasSubstr(path + "/Refinement"));
  p = rectParams(0, 0, 1, 1, 2, 2);
  p.set("Distortion", 0.31);
  EXPECT_THAT(run(p), HasSubstr(path + "/Distortion' must lie in [0, 0.3]"));
  p = rectParams(0, 0, 1, 1, 2, 2);
  p.set("Elements Z", 3);
  EXPECT_THAT(run(p), HasSubstr("unknown parameter '" + path + "/Elements Z'"));
  p = rectParams(0, 0, 1, 1, 2, 2);
  p.set("Elements X", 2.0);  // wrong type
  EXPECT_THAT(run(p), HasSubstr(path + "/Elements X"));
}

TEST(MeshGenerators, ValidParametersAreDocumented) {
  for (auto valid : {ddc::RectangleGenerator::getValidParameters(),
                     ddc::AnnularSectorGenerator::getValidParameters()}) {
    EXPECT_GT(valid->numParams(), 0);
    for (auto it = valid->begin(); it != valid->end(); ++it)
      EXPECT_FALSE(valid->entry(it).docString().empty()) << valid->name(it) << " has no doc string";
  }
  const auto& s = *ddc::AnnularSectorGenerator::getValidParameters();
  EXPECT_EQ(s.get<double>("Inner Radius"), 1.5);
  EXPECT_EQ(s.get<double>("Outer Radius"), 2.0);
  EXPECT_EQ(s.get<int>("Radial Elements"), 4);
  EXPECT_EQ(s.get<int>("Circumferential Elements"), 64);
  EXPECT_EQ(s.get<double>("End Angle"), 180.0);
}

// ------------------------------------------------------------ annular sector

namespace {

struct Sector {
  double cx = 0, cy = 0, ri = 1.5, ro = 2.0, start = 0, end = 180;
  /// Is (x, y) strictly inside the sector?
  bool inside(double x, double y) const {
    const double r = std::hypot(x - cx, y - cy);
    if (!(r > ri && r < ro)) return false;
    double lo = std::min(start, end), hi = std::max(start, end);
    double th = std::atan2(y - cy, x - cx) * 180.0 / kPi;
    while (th < lo) th += 360.0;
    while (th >= lo + 360.0) th -= 360.0;
    return th > lo && th < hi;
  }
};

Mesh makeSector(CellType t, const Sector& s, int nr, int nc, int refinement = 1) {
  Mesh m;
  Teuchos::ParameterList p;
  p.set("Center X", s.cx);
  p.set("Center Y", s.cy);
  p.set("Inner Radius", s.ri);
  p.set("Outer Radius", s.ro);
  p.set("Start Angle", s.start);
  p.set("End Angle", s.end);
  p.set("Radial Elements", nr);
  p.set("Circumferential Elements", nc);
  p.set("Refinement", refinement);
  ddc::generateAnnularSector(m, "Ring", t, p, "Mesh/Bodies/Ring/Annular Sector");
  return m;
}

}  // namespace

TEST(AnnularSectorGenerator, DefaultHalfRing) {
  Mesh m;
  Teuchos::ParameterList p;
  ddc::generateAnnularSector(m, "Ring", CellType::Quad4, p, "S");
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.numElements(), 4 * 64);
  EXPECT_EQ(m.numNodes(), 5 * 65);
  EXPECT_EQ(m.sideSet("Ring/inner").size(), 64u);
  EXPECT_EQ(m.sideSet("Ring/outer").size(), 64u);
  EXPECT_EQ(m.sideSet("Ring/start").size(), 4u);
  EXPECT_EQ(m.sideSet("Ring/end").size(), 4u);
  EXPECT_EQ(m.nodeSet("Ring/all").size(), 325u);
  EXPECT_EQ(m.nodeSet("Ring/outer").size(), 65u);
  // End faces exactly on y = 0: start at x > 0, end at x < 0.
  for (int n : m.nodeSet("Ring/start")) {
    EXPECT_EQ(m.coord(n)[1], 0.0);
    EXPECT_GT(m.coord(n)[0], 0.0);
  }
  for (int n : m.nodeSet("Ring/end")) {
    EXPECT_EQ(m.coord(n)[1], 0.0);
    EXPECT_LT(m.coord(n)[0], 0.0);
  }
  double minDet;
  const double exact = 0.5 * kPi * (2.0 * 2.0 - 1.5 * 1.5);
  // Quad4 chords cut the arcs: relative area error ~ (pi/64)^2 / 6 = 4e-4.
  EXPECT_NEAR(totalArea(m, &minDet), exact, 1e-3 * exact);
  EXPECT_GT(minDet, 0.0);
}

TEST(AnnularSectorGenerator, NodesOnCirclesAndOutwardSides) {
  for (CellType t : {CellType::Quad4, CellType::Quad9}) {
    for (Sector s : {Sector{}, Sector{-3.0, 3.5, 1.5, 2.0, 180, 360}, Sector{1, 2, 0.5, 3.0, 360, 180},
                     Sector{0, 0, 1.0, 1.2, 30, -45}}) {
      const Mesh m = makeSector(t, s, 3, 12);
      EXPECT_NO_THROW(m.check());
      double minDet;
      totalArea(m, &minDet);
      EXPECT_GT(minDet, 0.0) << "start " << s.start << " end " << s.end;
      const auto radius = [&](int n) { return std::hypot(m.coord(n)[0] - s.cx, m.coord(n)[1] - s.cy); };
      for (int n : m.nodeSet("Ring/inner")) EXPECT_NEAR(radius(n), s.ri, ddc::test::kRoundoff);
      for (int n : m.nodeSet("Ring/outer")) EXPECT_NEAR(radius(n), s.ro, ddc::test::kRoundoff);
      // "start" lies on the ray at Start Angle.
      const double c = std::cos(s.start * kPi / 180), sn = std::sin(s.start * kPi / 180);
      for (int n : m.nodeSet("Ring/start")) {
        const double dx = m.coord(n)[0] - s.cx, dy = m.coord(n)[1] - s.cy;
        EXPECT_NEAR(dx * sn - dy * c, 0.0, ddc::test::kRoundoff);
        EXPECT_GT(dx * c + dy * sn, 0.0);
      }
      auto inside = [&](double x, double y) { return s.inside(x, y); };
      for (const char* name : {"inner", "outer", "start", "end"})
        expectOutwardChain(m, std::string("Ring/") + name, inside);
    }
  }
}

TEST(AnnularSectorGenerator, Quad9AreaConvergesFast) {
  const Sector s;
  const double exact = 0.5 * kPi * (s.ro * s.ro - s.ri * s.ri);
  auto err = [&](CellType t, int r) {
    const Mesh m = makeSector(t, s, 2, 8, r);
    double minDet;
    return std::abs(totalArea(m, &minDet) - exact) / exact;
  };
  const double e4a = err(CellType::Quad4, 1), e4b = err(CellType::Quad4, 2);
  const double e9a = err(CellType::Quad9, 1), e9b = err(CellType::Quad9, 2);
  // Quad4: O(h^2) -> ratio about 4; Quad9 with nodes on the arcs: O(h^4) -> about 16.
  EXPECT_NEAR(e4a / e4b, 4.0, 0.2);
  EXPECT_GT(e9a / e9b, 12.0);
  EXPECT_LT(e9a, 1e-2 * e4a);
  // The default half-ring mesh in Quad9 represents the area to ~1e-8.
  Mesh m;
  Teuchos::ParameterList p;
  ddc::generateAnnularSector(m, "Ring", CellType::Quad9, p, "S");
  EXPECT_EQ(m.numNodes(), 9 * 129);
  double minDet;
  EXPECT_LT(std::abs(totalArea(m, &minDet) - exact) / exact, 1e-7);
  // Quad9 mid-side nodes of the arcs are on the circles.
  for (const auto& seg : m.sideSet("Ring/outer"))
    EXPECT_NEAR(std::hypot(m.coord(seg.nodes[2])[0], m.coord(seg.nodes[2])[1]), 2.0, ddc::test::kRoundoff);
}

TEST(AnnularSectorGenerator, RefinementMultipliesCounts) {
  const Mesh m = makeSector(CellType::Quad4, Sector{}, 4, 64, 2);
  EXPECT_EQ(m.numElements(), 8 * 128);
  EXPECT_EQ(m.sideSet("Ring/outer").size(), 128u);
  EXPECT_EQ(m.sideSet("Ring/start").size(), 8u);
}

TEST(AnnularSectorGenerator, ParameterErrors) {
  const std::string path = "Mesh/Bodies/Ring/Annular Sector";
  auto run = [&](Sector s, int nr = 2, int nc = 4) {
    return inputErrorOf([&] { makeSector(CellType::Quad4, s, nr, nc); });
  };
  Sector s;
  s.end = s.start;
  EXPECT_THAT(run(s), HasSubstr(path + "/Start Angle"));
  s.end = 360.0;
  EXPECT_THAT(run(s), HasSubstr("closed ring is not supported"));
  s = Sector{};
  s.ri = 2.0;
  EXPECT_THAT(run(s), HasSubstr(path + "/Outer Radius' must be greater than 'Inner Radius'"));
  s = Sector{};
  s.ri = 0.0;
  EXPECT_THAT(run(s), HasSubstr(path + "/Inner Radius' must be > 0"));
  EXPECT_THAT(run(Sector{}, 0, 4), HasSubstr(path + "/Radial Elements"));
  EXPECT_THAT(run(Sector{}, 2, -1), HasSubstr(path + "/Circumferential Elements"));
  Mesh m;
  Teuchos::ParameterList p;
  p.set("Inner radius", 1.0);  // misspelt
  EXPECT_THAT(inputErrorOf([&] { ddc::generateAnnularSector(m, "Ring", CellType::Quad4, p, path); }),
              HasSubstr("unknown parameter '" + path + "/Inner radius'"));
}

TEST(MeshGenerators, SeveralBodiesAndDuplicateNames) {
  Mesh m;
  auto p = rectParams(0, 0, 1, 1, 2, 2);
  Teuchos::ParameterList q;
  EXPECT_EQ(ddc::generateRectangle(m, "Block", CellType::Quad4, p, "R"), 0);
  EXPECT_EQ(ddc::generateAnnularSector(m, "Ring", CellType::Quad9, q, "S"), 1);
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.body(1).firstNode, 9);
  EXPECT_EQ(m.body(1).firstElement, 4);
  for (int n : m.nodeSet("Ring/all")) EXPECT_GE(n, 9);
  auto p2 = rectParams(0, 0, 1, 1, 2, 2);
  EXPECT_THAT(inputErrorOf([&] { ddc::generateRectangle(m, "Block", CellType::Quad4, p2, "R"); }),
              HasSubstr("two bodies are named 'Block'"));
}
