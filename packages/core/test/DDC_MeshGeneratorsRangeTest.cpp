// The Rectangle and Box generators by element range (generateRectangle() /
// generateBox() with an ElementRange into Mesh::startPart()): the part they
// make is the part Mesh::part() cuts out of the whole mesh, bit for bit
// (ids, coordinates with the vertices' random displacements, connectivity,
// bodies, node and side sets in their order), for every cell type, two
// bodies of different cell types, and ranges that are empty, whole, inside
// one body, across both, or split a grid cell's tetrahedra.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

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

void expectRangesMatch(const std::vector<BodySpec>& bodies) {
  Mesh whole;
  addBodies(whole, bodies, nullptr);
  const long long ne = whole.numElements();
  const long long first = whole.body(0).numElements;  // the second body's first element
  const std::vector<ddc::ElementRange> ranges = {
      {0, 0}, {0, ne}, {ne / 3, 2 * ne / 3}, {first - 7, first + 5}, {first + 1, ne}, {5, 11}, {ne - 1, ne}};
  for (const auto& r : ranges) {
    SCOPED_TRACE("range [" + std::to_string(r.first) + ", " + std::to_string(r.last) + ")");
    Mesh part = Mesh::startPart();
    addBodies(part, bodies, &r);
    std::vector<int> ids;
    for (long long e = r.first; e < r.last; ++e) ids.push_back(static_cast<int>(e));
    const Mesh cut = whole.part(ids);
    ddc::test::expectSameParts(part, cut);
    EXPECT_EQ(orderedSets(part), orderedSets(cut));
  }
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

}  // namespace
