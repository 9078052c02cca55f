// The generators by element range (generateRectangle(), generateBox(),
// generateAnnularSector(), generateCylindricalShellSector() and
// generateSphereOctant() with an ElementRange into Mesh::startPart()): the part they
// make is the part Mesh::part() cuts out of the whole mesh, bit for bit
// (ids, coordinates with the vertices' random displacements, connectivity,
// bodies, node and side sets in their order), for every cell type, two
// bodies of different cell types, and ranges that are empty, whole, inside
// one body, across both, or split a grid cell's tetrahedra.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "DDC_MeshGenerators.hpp"
#include "DDC_MeshPartCompare.hpp"

namespace {

using PL = Teuchos::ParameterList;
using ddc::CellType;
using ddc::Mesh;

struct BodySpec {
  CellType type;
  int nx, ny, nz;
  double originX, distortion;
};

PL grid(const BodySpec& b, int dim) {
  PL p(dim == 3 ? "Box" : "Rectangle");
  p.set("Elements X", b.nx);
  p.set("Elements Y", b.ny);
  p.set("Length X", 1.5 * b.nx);
  p.set("Origin X", b.originX);
  p.set("Distortion", b.distortion);
  if (dim == 3) p.set("Elements Z", b.nz);
  return p;
}

/// Adds the bodies "A", "B", ... to `mesh`, whole or (with a range) the
/// elements of the range.
void addBodies(Mesh& mesh, const std::vector<BodySpec>& bodies, const ddc::ElementRange* range) {
  for (size_t i = 0; i < bodies.size(); ++i) {
    const int dim = ddc::cellDimension(bodies[i].type);
    PL p = grid(bodies[i], dim);
    const std::string name(1, char('A' + i));
    if (dim == 3 && range) ddc::generateBox(mesh, name, bodies[i].type, p, "Box", *range);
    else if (dim == 3) ddc::generateBox(mesh, name, bodies[i].type, p, "Box");
    else if (range) ddc::generateRectangle(mesh, name, bodies[i].type, p, "Rectangle", *range);
    else ddc::generateRectangle(mesh, name, bodies[i].type, p, "Rectangle");
  }
}

/// Node sets and side sets of `m` in their order, by ids.
std::vector<std::vector<long long>> orderedSets(const Mesh& m) {
  std::vector<std::vector<long long>> out;
  for (const auto& name : m.nodeSetNames()) {
    out.emplace_back();
    for (int n : m.nodeSet(name)) out.back().push_back(m.nodeId(n));
  }
  for (const auto& name : m.sideSetNames()) {
    out.emplace_back();
    for (const auto& s : m.sideSet(name)) out.back().push_back(m.elementId(s.element) * 8 + s.localSide);
  }
  return out;
}

/// The bodies `add` makes, whole and by ranges that are empty, whole,
/// inside one body, across the first two, or at the ends: each range's part
/// is the part Mesh::part() cuts from the whole mesh, sets in their order.
void expectRangesMatchOf(const std::function<void(Mesh&, const ddc::ElementRange*)>& add) {
  Mesh whole;
  add(whole, nullptr);
  const long long ne = whole.numElements();
  const long long first = whole.body(0).numElements;  // the second body's first element
  const std::vector<ddc::ElementRange> ranges = {
      {0, 0}, {0, ne}, {ne / 3, 2 * ne / 3}, {first - 7, first + 5}, {first + 1, ne}, {5, 11}, {ne - 1, ne}};
  for (const auto& r : ranges) {
    SCOPED_TRACE("range [" + std::to_string(r.first) + ", " + std::to_string(r.last) + ")");
    Mesh part = Mesh::startPart();
    add(part, &r);
    std::vector<int> ids;
    for (long long e = r.first; e < r.last; ++e) ids.push_back(static_cast<int>(e));
    const Mesh cut = whole.part(ids);
    ddc::test::expectSameParts(part, cut);
    EXPECT_EQ(orderedSets(part), orderedSets(cut));
  }
}

void expectRangesMatch(const std::vector<BodySpec>& bodies) {
  expectRangesMatchOf([&](Mesh& m, const ddc::ElementRange* r) { addBodies(m, bodies, r); });
}

TEST(MeshGeneratorsRange, Rectangles) {
  expectRangesMatch({{CellType::Quad4, 7, 5, 1, 0.0, 0.2}, {CellType::Quad9, 4, 3, 1, 20.0, 0.25}});
}

TEST(MeshGeneratorsRange, BoxesOfHexahedra) {
  expectRangesMatch({{CellType::Hex8, 4, 3, 3, 0.0, 0.2}, {CellType::Hex20, 3, 2, 3, 20.0, 0.2}});
  expectRangesMatch({{CellType::Hex27, 3, 3, 2, 0.0, 0.15}, {CellType::Hex8, 2, 2, 2, 20.0, 0.0}});
}

TEST(MeshGeneratorsRange, BoxesOfTetrahedra) {
  expectRangesMatch({{CellType::Tet4, 3, 3, 2, 0.0, 0.2}, {CellType::Tet10, 2, 3, 2, 20.0, 0.2}});
}

/// A body of any generator by range.
struct AnyBody {
  std::string generator;
  CellType type;
  PL params;
};

void addAnyBodies(Mesh& mesh, const std::vector<AnyBody>& bodies, const ddc::ElementRange* range) {
  for (size_t i = 0; i < bodies.size(); ++i) {
    const std::string name(1, char('A' + i));
    PL p = bodies[i].params;
    const std::string& g = bodies[i].generator;
    const CellType t = bodies[i].type;
    if (g == "Annular Sector")
      range ? ddc::generateAnnularSector(mesh, name, t, p, g, *range) : ddc::generateAnnularSector(mesh, name, t, p, g);
    else if (g == "Cylindrical Shell Sector")
      range ? ddc::generateCylindricalShellSector(mesh, name, t, p, g, *range)
            : ddc::generateCylindricalShellSector(mesh, name, t, p, g);
    else if (g == "Sphere Octant")
      range ? ddc::generateSphereOctant(mesh, name, t, p, g, *range) : ddc::generateSphereOctant(mesh, name, t, p, g);
    else
      range ? ddc::generateBox(mesh, name, t, p, g, *range) : ddc::generateBox(mesh, name, t, p, g);
  }
}

/// As expectRangesMatch(), for bodies of any generator; and
/// structuredElementCount() counts each body's elements.
void expectAnyRangesMatch(const std::vector<AnyBody>& bodies) {
  Mesh whole;
  addAnyBodies(whole, bodies, nullptr);
  for (int b = 0; b < whole.numBodies(); ++b) {
    PL p = bodies[size_t(b)].params;
    EXPECT_EQ(ddc::structuredElementCount(bodies[size_t(b)].generator, bodies[size_t(b)].type, p, "x"),
              whole.body(b).numElements);
  }
  expectRangesMatchOf([&](Mesh& m, const ddc::ElementRange* r) { addAnyBodies(m, bodies, r); });
}

PL sector(int nr, int nc, double start, double end, double cx = 0.0) {
  PL p("Annular Sector");
  p.set("Radial Elements", nr);
  p.set("Circumferential Elements", nc);
  p.set("Start Angle", start);
  p.set("End Angle", end);
  p.set("Center X", cx);
  return p;
}

PL shell(int nr, int nc, int nz, double start, double end, double cx = 0.0) {
  PL p = sector(nr, nc, start, end, cx);
  p.setName("Cylindrical Shell Sector");
  p.set("Axial Elements", nz);
  p.set("Axial Length", 2.0);
  return p;
}

PL octant(int n, double progression, double cz = 0.0) {
  PL p("Sphere Octant");
  p.set("Elements", n);
  p.set("Progression", progression);
  p.set("Center Z", cz);
  return p;
}

TEST(MeshGeneratorsRange, AnnularSectorsEitherWayRound) {
  // Start < End, and End < Start (the map reverses orientation: the cells'
  // corners and the boundary chains run the other way in index space).
  expectAnyRangesMatch({{"Annular Sector", CellType::Quad4, sector(3, 8, 0.0, 120.0)},
                        {"Annular Sector", CellType::Quad9, sector(2, 5, 170.0, 30.0, 9.0)}});
  expectAnyRangesMatch({{"Annular Sector", CellType::Quad4, sector(4, 6, 200.0, 10.0)},
                        {"Annular Sector", CellType::Quad4, sector(2, 7, -30.0, 90.0, 9.0)}});
}

TEST(MeshGeneratorsRange, CylindricalShellSectors) {
  expectAnyRangesMatch({{"Cylindrical Shell Sector", CellType::Hex8, shell(2, 6, 3, 0.0, 180.0)},
                        {"Cylindrical Shell Sector", CellType::Hex20, shell(2, 3, 2, 150.0, 20.0, 9.0)}});
  expectAnyRangesMatch({{"Cylindrical Shell Sector", CellType::Tet4, shell(2, 3, 2, 90.0, 0.0)},
                        {"Cylindrical Shell Sector", CellType::Tet10, shell(1, 3, 2, 0.0, 60.0, 9.0)}});
}

TEST(MeshGeneratorsRange, SphereOctantsAndABlock) {
  // The curved surface "sphere" is three grid sides in one set.
  expectAnyRangesMatch({{"Sphere Octant", CellType::Hex8, octant(4, 1.3)},
                        {"Sphere Octant", CellType::Hex27, octant(2, 1.0, -3.0)}});
  PL box("Box");
  box.set("Elements X", 3);
  box.set("Elements Y", 2);
  box.set("Elements Z", 2);
  box.set("Origin Z", -5.0);
  expectAnyRangesMatch({{"Sphere Octant", CellType::Tet10, octant(2, 1.2)}, {"Box", CellType::Hex8, box}});
}

}  // namespace
