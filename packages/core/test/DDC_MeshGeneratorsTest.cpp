// Built-in generators: counts, sets, areas and volumes, orientation,
// refinement, distortion, conformity of the 3-D meshes, the 2-D / 3-D
// sector equivalence, and parameter errors.
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

double totalArea(const Mesh& m, double* minDet) { return ddc::test::meshMeasure(m, minDet); }

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
  for (auto valid : {ddc::RectangleGenerator::getValidParameters(), ddc::AnnularSectorGenerator::getValidParameters(),
                     ddc::BoxGenerator::getValidParameters(),
                     ddc::CylindricalShellSectorGenerator::getValidParameters(),
                     ddc::SphereOctantGenerator::getValidParameters()}) {
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

/// The Annular Sector parameters of `s` (also the in-plane ones of the
/// Cylindrical Shell Sector).
Teuchos::ParameterList sectorParams(const Sector& s, int nr, int nc, int refinement) {
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
  return p;
}

Mesh makeSector(CellType t, const Sector& s, int nr, int nc, int refinement = 1) {
  Mesh m;
  Teuchos::ParameterList p = sectorParams(s, nr, nc, refinement);
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

// ---------------------------------------------------------------------- box

namespace {

using ddc::test::Vec3;

const std::vector<CellType> k3DTypes = {CellType::Hex8, CellType::Hex20, CellType::Hex27, CellType::Tet4,
                                        CellType::Tet10};

bool isTet(CellType t) { return t == CellType::Tet4 || t == CellType::Tet10; }

Teuchos::ParameterList boxParams(const Vec3& x0, const Vec3& l, const std::array<int, 3>& n) {
  Teuchos::ParameterList p("Box");
  const char* axis[3] = {"X", "Y", "Z"};
  for (int d = 0; d < 3; ++d) {
    p.set(std::string("Origin ") + axis[d], x0[d]);
    p.set(std::string("Length ") + axis[d], l[d]);
    p.set(std::string("Elements ") + axis[d], n[d]);
  }
  return p;
}

double totalVolume(const Mesh& m, double* minDet) { return ddc::test::meshMeasure(m, minDet); }

/// Node count of a box of n cells for each cell type (header of
/// DDC_MeshGenerators.hpp).
int boxNodes(CellType t, int nx, int ny, int nz) {
  if (t == CellType::Hex8 || t == CellType::Tet4) return (nx + 1) * (ny + 1) * (nz + 1);
  if (t == CellType::Hex20)
    return (nx + 1) * (ny + 1) * (nz + 1) + nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) +
           (nx + 1) * (ny + 1) * nz;
  return (2 * nx + 1) * (2 * ny + 1) * (2 * nz + 1);
}

/// Faces per grid-cell face: 1 quadrilateral or 2 triangles.
int facesPerCellFace(CellType t) { return isTet(t) ? 2 : 1; }

/// Every face of a 3-D side set is outward: a point a little outside its
/// centroid along the normal is not in the body, one a little inside is.
/// "A little" is 1/10 of the face's longest corner-to-corner edge: more than
/// the sagitta of a chord of an arc of up to 45 degrees (tan(angle/4)/2 of
/// the chord), by which a curved face's centroid lies off the true surface,
/// and less than the distance to the other faces in these meshes.
template <class Inside>
void expectOutwardFaces(const Mesh& m, const std::string& set, Inside inside) {
  for (const Segment& s : m.sideSet(set)) {
    const Vec3 n = ddc::test::faceNormal(m, s);
    const double area = std::sqrt(ddc::test::dot(n, n));
    const Vec3 c = ddc::test::faceCentroid(m, s);
    const int nc = s.numNodes == 3 || s.numNodes == 6 ? 3 : 4;
    double edge = 0.0;
    for (int i = 0; i < nc; ++i) {
      const Vec3 d = ddc::test::sub(m.coord(s.nodes[(i + 1) % nc]), m.coord(s.nodes[i]));
      edge = std::max(edge, std::sqrt(ddc::test::dot(d, d)));
    }
    const double eps = 0.1 * edge / area;
    EXPECT_FALSE(inside({c[0] + eps * n[0], c[1] + eps * n[1], c[2] + eps * n[2]})) << set;
    EXPECT_TRUE(inside({c[0] - eps * n[0], c[1] - eps * n[1], c[2] - eps * n[2]})) << set;
  }
}

/// Every node of a quadratic 3-D cell beyond its corners lies where the
/// corner map puts its reference point (the straight geometry).
void expectStraightNodes(const Mesh& m) {
  for (int e = 0; e < m.numElements(); ++e) {
    const auto& ref = ddc::referenceCell(m.elementType(e));
    for (int i = ref.numCorners; i < ref.numNodes; ++i) {
      Vec3 xi = ref.nodes[i];
      const Vec3 x = ddc::test::cornerMap(m, e, xi);
      for (int d = 0; d < 3; ++d) ASSERT_NEAR(m.coord(m.elementNodes(e)[i])[d], x[d], ddc::test::kRoundoff) << e << " " << i;
    }
  }
}

/// Boundary faces by facetKey are exactly the side-set faces, and no face is
/// shared by more than two elements (a conforming mesh).
void expectConforming(const Mesh& m, const std::vector<std::string>& sets) {
  int maxShare = 0, interior = 0;
  const int boundary = ddc::test::countBoundaryFaces(m, &maxShare, &interior);
  size_t inSets = 0;
  for (const auto& s : sets) inSets += m.sideSet(s).size();
  EXPECT_EQ(static_cast<size_t>(boundary), inSets);
  EXPECT_LE(maxShare, 2);
  int faces = 0;
  for (int e = 0; e < m.numElements(); ++e) faces += m.elementNumFacets(e);
  EXPECT_EQ(faces, boundary + 2 * interior);
}

const std::vector<std::string> kBoxSides = {"B/left", "B/right", "B/bottom", "B/top", "B/back", "B/front"};

}  // namespace

TEST(BoxGenerator, Hex8CountsSetsVolumeOrientation) {
  Mesh m;
  auto p = boxParams({1.0, -1.0, 0.5}, {2.0, 1.5, 0.75}, {4, 3, 2});
  EXPECT_EQ(ddc::generateBox(m, "B", CellType::Hex8, p, "Mesh/Bodies/B/Box"), 0);
  EXPECT_EQ(m.dim(), 3);
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.numNodes(), 5 * 4 * 3);
  EXPECT_EQ(m.numElements(), 24);
  double minDet;
  EXPECT_NEAR(totalVolume(m, &minDet), 2.0 * 1.5 * 0.75, ddc::test::kRoundoff);
  EXPECT_GT(minDet, 0.0);
  EXPECT_EQ(m.sideSet("B/left").size(), 6u);
  EXPECT_EQ(m.sideSet("B/right").size(), 6u);
  EXPECT_EQ(m.sideSet("B/bottom").size(), 8u);
  EXPECT_EQ(m.sideSet("B/top").size(), 8u);
  EXPECT_EQ(m.sideSet("B/back").size(), 12u);
  EXPECT_EQ(m.sideSet("B/front").size(), 12u);
  EXPECT_EQ(m.nodeSet("B/left").size(), 12u);
  EXPECT_EQ(m.nodeSet("B/front").size(), 20u);
  EXPECT_EQ(m.nodeSet("B/all").size(), 60u);
  const auto corner = [&](const std::string& n) { return m.coord(m.nodeSet("B/" + n).at(0)); };
  EXPECT_EQ(corner("bottom left back"), (Vec3{1.0, -1.0, 0.5}));
  EXPECT_EQ(corner("bottom right back"), (Vec3{3.0, -1.0, 0.5}));
  EXPECT_EQ(corner("top left back"), (Vec3{1.0, 0.5, 0.5}));
  EXPECT_EQ(corner("top right front"), (Vec3{3.0, 0.5, 1.25}));
  EXPECT_EQ(corner("bottom left front"), (Vec3{1.0, -1.0, 1.25}));
  // Each face set lies in its plane, its normals point along the outward
  // axis and away from the centroid.
  const Vec3 c = ddc::test::nodeCentroid(m, 0);
  const std::vector<std::pair<int, double>> plane = {{0, 1.0}, {0, 3.0}, {1, -1.0}, {1, 0.5}, {2, 0.5}, {2, 1.25}};
  for (size_t k = 0; k < kBoxSides.size(); ++k) {
    const int axis = plane[k].first;
    for (int n : m.nodeSet(kBoxSides[k])) EXPECT_EQ(m.coord(n)[axis], plane[k].second) << kBoxSides[k];
    double area = 0;
    for (const Segment& s : m.sideSet(kBoxSides[k])) {
      EXPECT_EQ(s.numNodes, 4);
      const Vec3 n = ddc::test::faceNormal(m, s);
      const double sign = k % 2 == 0 ? -1.0 : 1.0;
      EXPECT_NEAR(sign * n[axis], std::sqrt(ddc::test::dot(n, n)), ddc::test::kRoundoff) << kBoxSides[k];
      EXPECT_GT(ddc::test::dot(n, ddc::test::sub(ddc::test::faceCentroid(m, s), c)), 0.0) << kBoxSides[k];
      area += sign * n[axis];
    }
    const double lengths[3] = {2.0, 1.5, 0.75};
    EXPECT_NEAR(area, lengths[(axis + 1) % 3] * lengths[(axis + 2) % 3], ddc::test::kRoundoff) << kBoxSides[k];
  }
  expectConforming(m, kBoxSides);
  // Defaults were filled in.
  EXPECT_EQ(p.get<int>("Refinement"), 1);
  EXPECT_EQ(p.get<double>("Distortion"), 0.0);
}

TEST(BoxGenerator, EveryCellTypeIsConformingStraightAndOutward) {
  const int nx = 3, ny = 2, nz = 2;
  for (CellType t : k3DTypes) {
    Mesh m;
    auto p = boxParams({0, 0, 0}, {1.5, 1.0, 2.0}, {nx, ny, nz});
    ddc::generateBox(m, "B", t, p, "Box");
    EXPECT_NO_THROW(m.check()) << ddc::cellTypeName(t);
    const int tets = isTet(t) ? 6 : 1;
    EXPECT_EQ(m.numElements(), tets * nx * ny * nz) << ddc::cellTypeName(t);
    EXPECT_EQ(m.numNodes(), boxNodes(t, nx, ny, nz)) << ddc::cellTypeName(t);
    double minDet;
    EXPECT_NEAR(totalVolume(m, &minDet), 3.0, ddc::test::kRoundoff) << ddc::cellTypeName(t);
    EXPECT_GT(minDet, 0.0);
    EXPECT_EQ(m.sideSet("B/left").size(), static_cast<size_t>(facesPerCellFace(t) * ny * nz));
    EXPECT_EQ(m.sideSet("B/top").size(), static_cast<size_t>(facesPerCellFace(t) * nx * nz));
    EXPECT_EQ(m.sideSet("B/front").size(), static_cast<size_t>(facesPerCellFace(t) * nx * ny));
    for (const Segment& s : m.sideSet("B/back")) EXPECT_EQ(s.numNodes, numCellNodes(ddc::referenceCell(t).facets[0].type));
    expectConforming(m, kBoxSides);
    expectStraightNodes(m);
    // Nodes on shared edges and faces are shared: no two nodes coincide.
    std::set<Vec3> distinct;
    for (int n = 0; n < m.numNodes(); ++n) distinct.insert(m.coord(n));
    EXPECT_EQ(distinct.size(), static_cast<size_t>(m.numNodes())) << ddc::cellTypeName(t);
    auto inside = [](const Vec3& x) { return x[0] > 0 && x[0] < 1.5 && x[1] > 0 && x[1] < 1 && x[2] > 0 && x[2] < 2; };
    for (const auto& s : kBoxSides) expectOutwardFaces(m, s, inside);
    // Every node of a face set lies on its plane (quadratic nodes too).
    for (int n : m.nodeSet("B/right")) EXPECT_EQ(m.coord(n)[0], 1.5);
    for (int n : m.nodeSet("B/front")) EXPECT_EQ(m.coord(n)[2], 2.0);
  }
}

TEST(BoxGenerator, RefinementMultipliesAllCounts) {
  for (CellType t : {CellType::Hex8, CellType::Hex20, CellType::Tet10}) {
    Mesh m;
    auto p = boxParams({0, 0, 0}, {1, 1, 1}, {2, 1, 3});
    p.set("Refinement", 2);
    ddc::generateBox(m, "B", t, p, "Box");
    EXPECT_EQ(m.numElements(), (isTet(t) ? 6 : 1) * 4 * 2 * 6);
    EXPECT_EQ(m.numNodes(), boxNodes(t, 4, 2, 6));
    EXPECT_EQ(m.sideSet("B/back").size(), static_cast<size_t>(facesPerCellFace(t) * 4 * 2));
  }
}

TEST(BoxGenerator, DistortionKeepsEveryJacobianPositiveAndIsDeterministic) {
  auto make = [](CellType t, double d, int refinement = 1) {
    Mesh m;
    auto p = boxParams({0, 0, 0}, {2.0, 1.0, 3.0}, {4, 3, 4});
    p.set("Distortion", d);
    p.set("Refinement", refinement);
    ddc::generateBox(m, "B", t, p, "Box");
    return m;
  };
  for (CellType t : k3DTypes) {
    const Mesh a = make(t, 0.25), b = make(t, 0.25), plain = make(t, 0.0);
    ASSERT_EQ(a.numNodes(), plain.numNodes());
    EXPECT_NO_THROW(a.check());
    double minDet;
    // Boundary vertices stay: the faces are plane and the volume exact.
    EXPECT_NEAR(totalVolume(a, &minDet), 6.0, ddc::test::kRoundoff);
    EXPECT_GT(minDet, 0.0);
    int moved = 0;
    for (int n = 0; n < a.numNodes(); ++n) {
      EXPECT_EQ(a.coord(n), b.coord(n)) << "distortion is not reproducible";
      moved += a.coord(n) != plain.coord(n);
    }
    EXPECT_GE(moved, 3 * 2 * 3);  // the interior vertices
    for (const auto& s : kBoxSides)
      for (int n : a.nodeSet(s)) EXPECT_EQ(a.coord(n), plain.coord(n)) << "boundary node " << n << " moved";
    expectStraightNodes(a);
    expectConforming(a, kBoxSides);
  }
  // Hex8, Hex27, Tet4 and Tet10 share the distorted vertices.
  const Mesh h8 = make(CellType::Hex8, 0.2), h27 = make(CellType::Hex27, 0.2), t4 = make(CellType::Tet4, 0.2);
  for (int e = 0; e < h8.numElements(); ++e)
    for (int k = 0; k < 8; ++k) EXPECT_EQ(h8.coord(h8.elementNodes(e)[k]), h27.coord(h27.elementNodes(e)[k]));
  for (int n = 0; n < h8.numNodes(); ++n) EXPECT_EQ(h8.coord(n), t4.coord(n));
  // Finer meshes (more draws) at the largest distortion: the smallest det J
  // of the corner maps stays above the header's bound (1 - 2 sqrt(3) d)^3
  // hx hy hz / 8 (det J of the map from [-1,1]^3 is the cell volume / 8;
  // for a tetrahedron from the unit tetrahedron it is 6 times its volume,
  // i.e. the cell volume, with the same relative bound).
  const double d = 0.25, relBound = std::pow(1.0 - 2.0 * std::sqrt(3.0) * d, 3);
  for (int r : {1, 2}) {
    for (CellType t : {CellType::Hex8, CellType::Tet4}) {
      const Mesh m = make(t, d, r);
      double minDet;
      totalVolume(m, &minDet);
      const double cellVolume = (2.0 / (4 * r)) * (1.0 / (3 * r)) * (3.0 / (4 * r));
      const double rel = minDet / (isTet(t) ? cellVolume : cellVolume / 8.0);
      EXPECT_GT(rel, relBound) << ddc::cellTypeName(t) << " refinement " << r;
      std::printf("[ measured ] %s refinement %d, Distortion 0.25: min det J / undistorted det J = %.3f (bound %.4f)\n",
                  ddc::cellTypeName(t), r, rel, relBound);
    }
  }
}

TEST(BoxGenerator, ParameterErrorsNameThePath) {
  const std::string path = "Mesh/Bodies/B/Box";
  auto run = [&](Teuchos::ParameterList p, CellType t = CellType::Hex8) {
    return inputErrorOf([&] {
      Mesh m;
      ddc::generateBox(m, "B", t, p, path);
    });
  };
  auto p = boxParams({0, 0, 0}, {1, 1, 0}, {2, 2, 2});
  EXPECT_THAT(run(p), HasSubstr(path + "/Length Z' must be > 0"));
  p = boxParams({0, 0, 0}, {1, 1, 1}, {2, 2, 0});
  EXPECT_THAT(run(p), HasSubstr(path + "/Elements Z' must be > 0"));
  p = boxParams({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  p.set("Distortion", 0.26);
  EXPECT_THAT(run(p), HasSubstr(path + "/Distortion' must lie in [0, 0.25]"));
  p = boxParams({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  p.set("Elements W", 2);
  EXPECT_THAT(run(p), HasSubstr("unknown parameter '" + path + "/Elements W'"));
  p = boxParams({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  EXPECT_THAT(run(p, CellType::Quad4),
              HasSubstr("'" + path + "': the Box generator makes a 3-D body, but its element type Quad4 is 2-D; "
                        "use one of Hex8, Hex20, Hex27, Tet4, Tet10"));
  p = boxParams({0, 0, 0}, {1, 1, 1}, {2000, 2000, 2000});
  EXPECT_THAT(run(p), HasSubstr("grid points, more than a node number can hold"));
  Teuchos::ParameterList r = rectParams(0, 0, 1, 1, 2, 2);
  EXPECT_THAT(inputErrorOf([&] {
                Mesh m;
                ddc::generateRectangle(m, "R", CellType::Hex8, r, "Mesh/Bodies/R/Rectangle");
              }),
              HasSubstr("the Rectangle generator makes a 2-D body, but its element type Hex8 is 3-D; use one of "
                        "Quad4, Quad9"));
}

// ------------------------------------------------- cylindrical shell sector

namespace {

struct ShellSector : Sector {
  double z0 = 0.0, length = 1.0;
  bool inside(const Vec3& x) const { return Sector::inside(x[0], x[1]) && x[2] > z0 && x[2] < z0 + length; }
};

Mesh makeShell(CellType t, const ShellSector& s, int nr, int nc, int nz, int refinement = 1) {
  Mesh m;
  Teuchos::ParameterList p = sectorParams(s, nr, nc, refinement);
  p.set("Origin Z", s.z0);
  p.set("Axial Length", s.length);
  p.set("Axial Elements", nz);
  ddc::generateCylindricalShellSector(m, "Ring", t, p, "Mesh/Bodies/Ring/Cylindrical Shell Sector");
  return m;
}

const std::vector<std::string> kShellSides = {"Ring/inner", "Ring/outer", "Ring/start",
                                              "Ring/end",   "Ring/back",  "Ring/front"};

}  // namespace

TEST(CylindricalShellSectorGenerator, DefaultHalfRingChordVolume) {
  Mesh m;
  Teuchos::ParameterList p;
  ddc::generateCylindricalShellSector(m, "Ring", CellType::Hex8, p, "S");
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.numElements(), 4 * 64);
  EXPECT_EQ(m.numNodes(), 5 * 65 * 2);
  EXPECT_EQ(m.sideSet("Ring/inner").size(), 64u);
  EXPECT_EQ(m.sideSet("Ring/outer").size(), 64u);
  EXPECT_EQ(m.sideSet("Ring/start").size(), 4u);
  EXPECT_EQ(m.sideSet("Ring/end").size(), 4u);
  EXPECT_EQ(m.sideSet("Ring/back").size(), 256u);
  EXPECT_EQ(m.sideSet("Ring/front").size(), 256u);
  EXPECT_EQ(m.nodeSet("Ring/all").size(), 650u);
  for (int n : m.nodeSet("Ring/start")) {
    EXPECT_EQ(m.coord(n)[1], 0.0);
    EXPECT_GT(m.coord(n)[0], 0.0);
  }
  for (int n : m.nodeSet("Ring/front")) EXPECT_EQ(m.coord(n)[2], 1.0);
  // Straight chords: each cell is a prism over a trapezoid of area
  // (1/2) sin(dtheta) (Ro^2 - Ri^2) summed over the radial cells.
  double minDet;
  const double chord = 1.0 * 64 * 0.5 * std::sin(kPi / 64) * (2.0 * 2.0 - 1.5 * 1.5);
  EXPECT_NEAR(totalVolume(m, &minDet), chord, ddc::test::kRoundoff * chord);
  EXPECT_GT(minDet, 0.0);
  expectConforming(m, kShellSides);
  EXPECT_EQ(p.get<int>("Axial Elements"), 1);
  EXPECT_EQ(p.get<double>("Axial Length"), 1.0);
}

TEST(CylindricalShellSectorGenerator, EveryCellTypeOnCirclesOutwardConforming) {
  for (CellType t : k3DTypes) {
    for (ShellSector s : {ShellSector{}, ShellSector{{-3.0, 3.5, 1.5, 2.0, 180, 360}, -1.0, 0.5},
                          ShellSector{{1, 2, 0.5, 3.0, 360, 180}, 2.0, 3.0}, ShellSector{{0, 0, 1.0, 1.2, 30, -45}, 0, 0.2}}) {
      const Mesh m = makeShell(t, s, 2, 6, 2);
      EXPECT_NO_THROW(m.check()) << ddc::cellTypeName(t) << " start " << s.start << " end " << s.end;
      const int tets = isTet(t) ? 6 : 1;
      EXPECT_EQ(m.numElements(), tets * 2 * 6 * 2);
      EXPECT_EQ(m.numNodes(), boxNodes(t, 2, 6, 2));
      double minDet;
      totalVolume(m, &minDet);
      EXPECT_GT(minDet, 0.0) << ddc::cellTypeName(t) << " start " << s.start << " end " << s.end;
      const auto radius = [&](int n) { return std::hypot(m.coord(n)[0] - s.cx, m.coord(n)[1] - s.cy); };
      for (int n : m.nodeSet("Ring/inner")) EXPECT_NEAR(radius(n), s.ri, ddc::test::kRoundoff);
      for (int n : m.nodeSet("Ring/outer")) EXPECT_NEAR(radius(n), s.ro, ddc::test::kRoundoff);
      for (int n : m.nodeSet("Ring/back")) EXPECT_EQ(m.coord(n)[2], s.z0);
      for (int n : m.nodeSet("Ring/front")) EXPECT_EQ(m.coord(n)[2], s.z0 + s.length);
      for (int n = 0; n < m.numNodes(); ++n) {
        EXPECT_GE(radius(n), s.ri - ddc::test::kRoundoff);
        EXPECT_LE(radius(n), s.ro + ddc::test::kRoundoff);
      }
      auto inside = [&](const Vec3& x) { return s.inside(x); };
      for (const auto& name : kShellSides) expectOutwardFaces(m, name, inside);
      expectConforming(m, kShellSides);
    }
  }
}

TEST(CylindricalShellSectorGenerator, ExtrudedAnnularSectorHasTheSameNodesInPlane) {
  // One axial element: every node layer of the 3-D mesh repeats the 2-D
  // mesh's nodes in the same order, computed by the same code -- so they
  // agree exactly (well within the 1e-14 asked for).
  for (ShellSector s : {ShellSector{}, ShellSector{{1, 2, 0.5, 3.0, 360, 180}, 2.0, 3.0},
                        ShellSector{{-0.3, 0.7, 1.0, 1.2, 30, -45}, 0, 0.2}}) {
    for (auto types : {std::make_pair(CellType::Quad4, CellType::Hex8), std::make_pair(CellType::Quad9, CellType::Hex27)}) {
      const Mesh flat = makeSector(types.first, s, 3, 10);
      const Mesh solid = makeShell(types.second, s, 3, 10, 1);
      const int layers = types.second == CellType::Hex8 ? 2 : 3;
      ASSERT_EQ(solid.numNodes(), layers * flat.numNodes());
      for (int n = 0; n < solid.numNodes(); ++n) {
        const auto& p = flat.coord(n % flat.numNodes());
        const auto& q = solid.coord(n);
        EXPECT_EQ(q[0], p[0]) << n;
        EXPECT_EQ(q[1], p[1]) << n;
        EXPECT_EQ(q[2], n / flat.numNodes() == 0 ? s.z0 : n / flat.numNodes() == layers - 1 ? s.z0 + s.length
                                                                                           : s.z0 + 0.5 * s.length);
      }
      // The back face of element e is element e of the 2-D mesh.
      ASSERT_EQ(solid.numElements(), flat.numElements());
      for (int e = 0; e < flat.numElements(); ++e)
        for (int k = 0; k < 4; ++k) EXPECT_EQ(solid.elementNodes(e)[k], flat.elementNodes(e)[k]);
      // Side sets: the extruded ones have as many faces as the 2-D segments.
      for (const char* side : {"inner", "outer", "start", "end"})
        EXPECT_EQ(solid.sideSet(std::string("Ring/") + side).size(), flat.sideSet(std::string("Ring/") + side).size());
    }
  }
}

TEST(CylindricalShellSectorGenerator, Hex27VolumeIsQuad9AreaTimesLength) {
  const ShellSector s{{0, 0, 1.5, 2.0, 0, 180}, 0.0, 0.6};
  const Mesh flat = makeSector(CellType::Quad9, s, 2, 8);
  const Mesh solid = makeShell(CellType::Hex27, s, 2, 8, 3);
  double area = 0, volume = 0, minDet;
  area = totalArea(flat, &minDet);
  for (int e = 0; e < solid.numElements(); ++e) volume += ddc::test::hex27Volume(solid, e);
  EXPECT_NEAR(volume, area * s.length, ddc::test::kRoundoff * volume);
  // ... and is close to the exact pi/2 (Ro^2 - Ri^2) L: the Quad9 arcs over
  // 22.5 degrees per element err by O(h^4); 1e-4 is twice the measured error.
  const double exact = 0.5 * kPi * (s.ro * s.ro - s.ri * s.ri) * s.length;
  std::printf("[ measured ] Hex27 half-ring 2x8x3: relative volume error %.2e\n", std::abs(volume - exact) / exact);
  EXPECT_LT(std::abs(volume - exact) / exact, 1e-4);
  // Tet4 cells fill the same chord prisms as Hex8.
  const Mesh h8 = makeShell(CellType::Hex8, s, 2, 8, 3), t4 = makeShell(CellType::Tet4, s, 2, 8, 3);
  const double vh = totalVolume(h8, &minDet), vt = totalVolume(t4, &minDet);
  EXPECT_NEAR(vt, vh, ddc::test::kRoundoff * vh);
}

TEST(CylindricalShellSectorGenerator, RefinementAndParameterErrors) {
  const Mesh m = makeShell(CellType::Hex20, ShellSector{}, 2, 8, 1, 2);
  EXPECT_EQ(m.numElements(), 4 * 16 * 2);
  EXPECT_EQ(m.sideSet("Ring/outer").size(), 16u * 2u);
  EXPECT_EQ(m.sideSet("Ring/start").size(), 4u * 2u);
  const std::string path = "Mesh/Bodies/Ring/Cylindrical Shell Sector";
  auto run = [&](ShellSector s, int nz = 1, CellType t = CellType::Hex8) {
    return inputErrorOf([&] { makeShell(t, s, 2, 4, nz); });
  };
  ShellSector s;
  s.length = 0.0;
  EXPECT_THAT(run(s), HasSubstr(path + "/Axial Length' must be > 0"));
  EXPECT_THAT(run(ShellSector{}, 0), HasSubstr(path + "/Axial Elements' must be > 0"));
  s = ShellSector{};
  s.ro = 1.0;
  EXPECT_THAT(run(s), HasSubstr(path + "/Outer Radius' must be greater than 'Inner Radius'"));
  s = ShellSector{};
  s.end = -360.0;
  EXPECT_THAT(run(s), HasSubstr("closed ring is not supported"));
  EXPECT_THAT(run(ShellSector{}, 1, CellType::Quad9),
              HasSubstr("the Cylindrical Shell Sector generator makes a 3-D body, but its element type Quad9 is 2-D"));
  EXPECT_THAT(inputErrorOf([&] { makeSector(CellType::Tet4, Sector{}, 2, 4); }),
              HasSubstr("the Annular Sector generator makes a 2-D body, but its element type Tet4 is 3-D"));
}

// ------------------------------------------------------------- sphere octant

namespace {

struct Octant {
  double cx = 0.5, cy = -1.0, cz = 2.0, radius = 1.5;
  /// Is x strictly inside the octant?
  bool inside(const Vec3& x) const {
    const double dx = x[0] - cx, dy = x[1] - cy, dz = x[2] - cz;
    return dx > 0 && dy > 0 && dz < 0 && dx * dx + dy * dy + dz * dz < radius * radius;
  }
};

Mesh makeOctant(CellType t, const Octant& o, int n, double progression, int refinement = 1) {
  Mesh m;
  Teuchos::ParameterList p;
  p.set("Center X", o.cx);
  p.set("Center Y", o.cy);
  p.set("Center Z", o.cz);
  p.set("Radius", o.radius);
  p.set("Elements", n);
  p.set("Progression", progression);
  p.set("Refinement", refinement);
  ddc::generateSphereOctant(m, "Ball", t, p, "Mesh/Bodies/Ball/Sphere Octant");
  return m;
}

const std::vector<std::string> kOctantSides = {"Ball/sphere", "Ball/symmetry x", "Ball/symmetry y", "Ball/top"};

}  // namespace

TEST(SphereOctantGenerator, EveryCellTypeOnTheSphereOutwardConforming) {
  const Octant o;
  for (CellType t : k3DTypes)
    for (double progression : {1.0, 1.4}) {
      const Mesh m = makeOctant(t, o, 4, progression);
      EXPECT_NO_THROW(m.check()) << ddc::cellTypeName(t);
      EXPECT_EQ(m.numElements(), (isTet(t) ? 6 : 1) * 64);
      EXPECT_EQ(m.numNodes(), boxNodes(t, 4, 4, 4));
      double minDet;
      const double volume = totalVolume(m, &minDet);
      EXPECT_GT(minDet, 0.0) << ddc::cellTypeName(t) << " progression " << progression;
      // Chords cut the sphere: the volume lies below the octant's, by less
      // than the coarse 4 x 4 x 4 linear mesh's 4 %.
      const double exact = kPi * o.radius * o.radius * o.radius / 6.0;
      EXPECT_LT(volume, exact * (1.0 + ddc::test::kRoundoff)) << ddc::cellTypeName(t);
      EXPECT_GT(volume, 0.96 * exact) << ddc::cellTypeName(t);
      const auto r = [&](int nd) {
        const auto& x = m.coord(nd);
        return std::sqrt((x[0] - o.cx) * (x[0] - o.cx) + (x[1] - o.cy) * (x[1] - o.cy) + (x[2] - o.cz) * (x[2] - o.cz));
      };
      for (int nd : m.nodeSet("Ball/sphere")) EXPECT_NEAR(r(nd), o.radius, ddc::test::kRoundoff);
      for (int nd : m.nodeSet("Ball/symmetry x")) EXPECT_EQ(m.coord(nd)[0], o.cx);
      for (int nd : m.nodeSet("Ball/symmetry y")) EXPECT_EQ(m.coord(nd)[1], o.cy);
      for (int nd : m.nodeSet("Ball/top")) EXPECT_EQ(m.coord(nd)[2], o.cz);
      for (int nd = 0; nd < m.numNodes(); ++nd) EXPECT_LE(r(nd), o.radius + ddc::test::kRoundoff);
      ASSERT_EQ(m.nodeSet("Ball/pole").size(), 1u);
      const auto& pole = m.coord(m.nodeSet("Ball/pole")[0]);
      EXPECT_EQ(pole[0], o.cx);
      EXPECT_EQ(pole[1], o.cy);
      EXPECT_NEAR(pole[2], o.cz - o.radius, ddc::test::kRoundoff);
      // The three outer cube faces make one side set.
      EXPECT_EQ(m.sideSet("Ball/sphere").size(), 3u * 16u * facesPerCellFace(t));
      EXPECT_EQ(m.sideSet("Ball/top").size(), 16u * facesPerCellFace(t));
      auto inside = [&](const Vec3& x) { return o.inside(x); };
      for (const auto& name : kOctantSides) expectOutwardFaces(m, name, inside);
      expectConforming(m, kOctantSides);
    }
}

TEST(SphereOctantGenerator, VolumeConvergesAndProgressionGradesTowardsThePole) {
  const Octant o;
  const double exact = kPi * o.radius * o.radius * o.radius / 6.0;
  double previous = 1.0;
  for (int refinement : {1, 2, 4}) {
    double minDet;
    const double error = std::abs(totalVolume(makeOctant(CellType::Hex8, o, 3, 1.0, refinement), &minDet) - exact) / exact;
    std::printf("[ measured ] Hex8 sphere octant %d^3: relative volume error %.2e\n", 3 * refinement, error);
    // Chords of a smooth surface: second order, the error at least halves.
    EXPECT_LT(error, 0.5 * previous);
    previous = error;
  }
  // Graded: the cell at the pole is the smallest; its vertex next to the
  // pole along x is the cube point (f, 0, -1), f = (r - 1)/(r^n - 1),
  // projected onto the sphere.
  const double r = 1.5;
  const Mesh m = makeOctant(CellType::Hex8, o, 4, r);
  const auto& pole = m.coord(m.nodeSet("Ball/pole")[0]);
  double nearest = 1e30;
  for (int nd : m.nodeSet("Ball/symmetry y")) {
    const auto& x = m.coord(nd);
    if (x[0] > o.cx && std::abs(x[1] - o.cy) == 0.0) nearest = std::min(nearest, std::hypot(x[0] - pole[0], x[2] - pole[2]));
  }
  const double f = (r - 1.0) / (std::pow(r, 4) - 1.0), len = std::hypot(f, 1.0);
  EXPECT_NEAR(nearest, o.radius * std::hypot(f / len, 1.0 - 1.0 / len), ddc::test::kRoundoff);
  // Refinement keeps the grading (Progression^(1/k) over k times the cells)
  // and every cell valid, also where three cube faces meet on the sphere.
  for (int refinement : {2, 4}) {
    const Mesh fine = makeOctant(CellType::Hex8, o, 4, r, refinement);
    EXPECT_EQ(fine.numElements(), 64 * refinement * refinement * refinement);
    double minDet;
    totalVolume(fine, &minDet);
    EXPECT_GT(minDet, 0.0) << "refinement " << refinement;
    EXPECT_NO_THROW(fine.check()) << "refinement " << refinement;
  }
}

TEST(SphereOctantGenerator, ParameterErrors) {
  const std::string path = "Mesh/Bodies/Ball/Sphere Octant";
  EXPECT_THAT(inputErrorOf([&] { makeOctant(CellType::Hex8, Octant{}, 4, 2.5); }),
              HasSubstr(path + "/Progression"));
  EXPECT_THAT(inputErrorOf([&] { makeOctant(CellType::Hex8, Octant{}, 0, 1.0); }),
              HasSubstr(path + "/Elements' must be > 0"));
  Octant o;
  o.radius = -1.0;
  EXPECT_THAT(inputErrorOf([&] { makeOctant(CellType::Hex8, o, 4, 1.0); }), HasSubstr(path + "/Radius' must be > 0"));
  EXPECT_THAT(inputErrorOf([&] { makeOctant(CellType::Quad4, Octant{}, 4, 1.0); }),
              HasSubstr("the Sphere Octant generator makes a 3-D body, but its element type Quad4 is 2-D"));
}
