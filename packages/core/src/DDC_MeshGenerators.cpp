#include "DDC_MeshGenerators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Largest accepted "Distortion" (see the proof sketch in the header).
constexpr double kMaxDistortion = 0.3;
/// Fixed seed of the distortion generator: same mesh on every rank and run.
constexpr std::uint32_t kDistortionSeed = 20220804u;

/// A structured grid of na x nb cells. For Quad9 the node grid is the
/// "fine" grid with m = 2 nodes per cell and direction, for Quad4 m = 1; in
/// both cases every point of the (m na + 1) x (m nb + 1) node grid is a node.
struct Grid {
  int na = 0, nb = 0, m = 1;
  int firstNode = 0;
  int numA() const { return m * na + 1; }
  int numB() const { return m * nb + 1; }
  int node(int a, int b) const { return firstNode + b * numA() + a; }
};

/// Fine-grid coordinates (a, b) of the four corners of cell (i, j), counter-
/// clockwise if the map (a, b) -> (x, y) preserves orientation; `flip`
/// reverses the order for an orientation-reversing map.
std::array<std::array<int, 2>, 4> cellCorners(const Grid& g, int i, int j, bool flip) {
  const int a0 = g.m * i, a1 = g.m * (i + 1), b0 = g.m * j, b1 = g.m * (j + 1);
  if (!flip) return {{{a0, b0}, {a1, b0}, {a1, b1}, {a0, b1}}};
  return {{{a0, b0}, {a0, b1}, {a1, b1}, {a1, b0}}};
}

/// Which straight boundary line of the grid a fine-grid point lies on.
enum GridSide { kSideB0 = 0, kSideAMax = 1, kSideBMax = 2, kSideA0 = 3 };

bool onGridSide(const Grid& g, const std::array<int, 2>& p, int side) {
  switch (side) {
    case kSideB0: return p[1] == 0;
    case kSideAMax: return p[0] == g.numA() - 1;
    case kSideBMax: return p[1] == g.numB() - 1;
    default: return p[0] == 0;
  }
}

/// Order segments so that each one ends where the next begins (a walk along
/// the boundary in the counter-clockwise sense of the body, as the segments
/// themselves are oriented that way).
std::vector<Segment> chainSegments(std::vector<Segment> segs) {
  if (segs.size() < 2) return segs;
  std::vector<Segment> out;
  out.reserve(segs.size());
  // The first segment is the one whose start is no other segment's end.
  size_t first = 0;
  for (size_t k = 0; k < segs.size(); ++k) {
    bool isEnd = false;
    for (const auto& t : segs) isEnd = isEnd || t.nodes[1] == segs[k].nodes[0];
    if (!isEnd) {
      first = k;
      break;
    }
  }
  std::vector<char> used(segs.size(), 0);
  out.push_back(segs[first]);
  used[first] = 1;
  while (out.size() < segs.size()) {
    bool found = false;
    for (size_t k = 0; k < segs.size() && !found; ++k) {
      if (!used[k] && segs[k].nodes[0] == out.back().nodes[1]) {
        out.push_back(segs[k]);
        used[k] = 1;
        found = true;
      }
    }
    DDC_ASSERT(found, "structured boundary is not a chain");
  }
  return out;
}

/// Add the nodes (coordinates `xy`, indexed like g.node() - firstNode) and the
/// elements of a structured grid to the current body of `mesh`, and define
/// side sets `sideNames[GridSide]` plus node set "all".
void addStructuredBody(Mesh& mesh, int body, const Grid& g, CellType type, bool flip,
                       const std::vector<std::array<double, 2>>& xy,
                       const std::array<std::string, 4>& sideNames) {
  for (const auto& p : xy) mesh.addNode(p[0], p[1]);
  const ReferenceCell& ref = referenceCell(type);
  std::vector<Segment> sides[4];
  for (int j = 0; j < g.nb; ++j) {
    for (int i = 0; i < g.na; ++i) {
      const auto c = cellCorners(g, i, j, flip);
      int nodes[9];
      for (int k = 0; k < 4; ++k) nodes[k] = g.node(c[k][0], c[k][1]);
      for (const auto& edge : ref.edges)
        if (edge.middle >= 0) {
          const auto& p = c[edge.start];
          const auto& q = c[edge.end];
          nodes[edge.middle] = g.node((p[0] + q[0]) / 2, (p[1] + q[1]) / 2);
        }
      if (type == CellType::Quad9) nodes[8] = g.node(g.m * i + 1, g.m * j + 1);
      const int e = mesh.addElement(nodes);
      for (int s = 0; s < static_cast<int>(ref.facets.size()); ++s)
        for (int side = 0; side < 4; ++side)
          if (onGridSide(g, c[ref.facets[s].nodes[0]], side) && onGridSide(g, c[ref.facets[s].nodes[1]], side))
            sides[side].push_back(mesh.makeSegment(e, s));
    }
  }
  for (int side = 0; side < 4; ++side) mesh.addSideSet(body, sideNames[side], chainSegments(sides[side]));
  std::vector<int> all(xy.size());
  for (size_t k = 0; k < all.size(); ++k) all[k] = g.firstNode + static_cast<int>(k);
  mesh.addNodeSet(body, "all", std::move(all));
}

/// Uniform double in [0, 1) from the raw 32-bit Mersenne twister output
/// (std::uniform_real_distribution is implementation-defined, this is not).
double uniform01(std::mt19937& gen) { return static_cast<double>(gen()) / 4294967296.0; }

/// cos and sin of an angle in degrees, exact at multiples of 90 degrees so
/// that e.g. the end faces of a half-ring lie exactly on y = 0.
std::array<double, 2> cosSinDegrees(double deg) {
  const double q = deg / 90.0;
  if (q == std::floor(q) && std::abs(q) < 1e9) {
    const long k = ((static_cast<long>(q) % 4) + 4) % 4;
    static const double c[4] = {1.0, 0.0, -1.0, 0.0};
    static const double s[4] = {0.0, 1.0, 0.0, -1.0};
    return {c[k], s[k]};
  }
  const double rad = deg * kPi / 180.0;
  return {std::cos(rad), std::sin(rad)};
}

/// Element count times refinement, checked so that the node grid fits an int
/// (the count itself is > 0 by its validator).
int refinedCount(Teuchos::ParameterList& params, const std::string& name, int refinement,
                 const std::string& path) {
  const int n = params.get<int>(name);
  const long long r = static_cast<long long>(n) * refinement;
  DDC_INPUT_REQUIRE(2 * r + 1 < 46000, "parameter '" << joinPath(path, name) << "' times 'Refinement' ("
                                                     << r << ") is too large for a 2-D structured mesh");
  return static_cast<int>(r);
}

int getRefinement(Teuchos::ParameterList& params) { return params.get<int>("Refinement"); }

}  // namespace

// ---------------------------------------------------------------- Rectangle

Teuchos::RCP<const Teuchos::ParameterList> RectangleGenerator::getValidParameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid;
  if (valid.is_null()) {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Rectangle"));
    pl->set("Origin X", 0.0, "x of the lower-left corner", finiteNumber());
    pl->set("Origin Y", 0.0, "y of the lower-left corner", finiteNumber());
    pl->set("Length X", 1.0, "width", greaterThan(0.0));
    pl->set("Length Y", 1.0, "height", greaterThan(0.0));
    pl->set("Elements X", 4, "number of elements along x, before refinement", greaterThan(0));
    pl->set("Elements Y", 4, "number of elements along y, before refinement", greaterThan(0));
    pl->set("Refinement", 1,
            "multiplies both element counts; refine a benchmark from the command line with --set", atLeast(1));
    pl->set("Distortion", 0.0,
            "random but reproducible (fixed seed) displacement of the interior element vertices, as "
            "a fraction of the element size (larger values than the maximum can invert elements); for "
            "patch tests on distorted meshes",
            between(0.0, kMaxDistortion));
    valid = pl;
  }
  return valid;
}

int generateRectangle(Mesh& mesh, const std::string& bodyName, CellType type,
                      Teuchos::ParameterList& params, const std::string& path) {
  validateLevel(params, *RectangleGenerator::getValidParameters(), path);
  const double x0 = params.get<double>("Origin X");
  const double y0 = params.get<double>("Origin Y");
  const double lx = params.get<double>("Length X");
  const double ly = params.get<double>("Length Y");
  const int refinement = getRefinement(params);
  const int nx = refinedCount(params, "Elements X", refinement, path);
  const int ny = refinedCount(params, "Elements Y", refinement, path);
  const double distortion = params.get<double>("Distortion");

  const int body = mesh.beginBody(bodyName, type);
  Grid g;
  g.na = nx;
  g.nb = ny;
  g.m = numCellNodes(type) == 9 ? 2 : 1;
  g.firstNode = mesh.numNodes();
  const int na = g.numA(), nb = g.numB();
  std::vector<std::array<double, 2>> xy(static_cast<size_t>(na) * nb);
  auto at = [&](int a, int b) -> std::array<double, 2>& { return xy[static_cast<size_t>(b) * na + a]; };

  // Vertices of the element grid (a, b multiples of m), distorted inside.
  const double hx = lx / nx, hy = ly / ny;
  const double radius = distortion * std::min(hx, hy);
  std::mt19937 gen(kDistortionSeed);
  for (int b = 0; b < nb; b += g.m) {
    for (int a = 0; a < na; a += g.m) {
      double x = x0 + lx * (static_cast<double>(a) / (na - 1));
      double y = y0 + ly * (static_cast<double>(b) / (nb - 1));
      if (a == na - 1) x = x0 + lx;
      if (b == nb - 1) y = y0 + ly;
      const bool interior = a > 0 && a < na - 1 && b > 0 && b < nb - 1;
      if (interior && radius > 0.0) {
        // Uniform in the disc of radius `radius`.
        const double r = radius * std::sqrt(uniform01(gen));
        const double phi = 2.0 * kPi * uniform01(gen);
        x += r * std::cos(phi);
        y += r * std::sin(phi);
      }
      at(a, b) = {x, y};
    }
  }
  // Quad9: mid-side nodes at edge midpoints, centre at the corner average.
  if (g.m == 2) {
    for (int b = 0; b < nb; ++b) {
      for (int a = 0; a < na; ++a) {
        const bool oddA = a % 2 == 1, oddB = b % 2 == 1;
        if (oddA && !oddB) {
          at(a, b) = {0.5 * (at(a - 1, b)[0] + at(a + 1, b)[0]), 0.5 * (at(a - 1, b)[1] + at(a + 1, b)[1])};
        } else if (!oddA && oddB) {
          at(a, b) = {0.5 * (at(a, b - 1)[0] + at(a, b + 1)[0]), 0.5 * (at(a, b - 1)[1] + at(a, b + 1)[1])};
        } else if (oddA && oddB) {
          const auto& p00 = at(a - 1, b - 1);
          const auto& p10 = at(a + 1, b - 1);
          const auto& p11 = at(a + 1, b + 1);
          const auto& p01 = at(a - 1, b + 1);
          at(a, b) = {0.25 * (p00[0] + p10[0] + p11[0] + p01[0]), 0.25 * (p00[1] + p10[1] + p11[1] + p01[1])};
        }
      }
    }
  }
  addStructuredBody(mesh, body, g, type, /*flip=*/false, xy, {"bottom", "right", "top", "left"});
  mesh.addNodeSet(body, "bottom left", {g.node(0, 0)});
  mesh.addNodeSet(body, "bottom right", {g.node(na - 1, 0)});
  mesh.addNodeSet(body, "top left", {g.node(0, nb - 1)});
  mesh.addNodeSet(body, "top right", {g.node(na - 1, nb - 1)});
  return body;
}

// ----------------------------------------------------------- Annular sector

Teuchos::RCP<const Teuchos::ParameterList> AnnularSectorGenerator::getValidParameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid;
  if (valid.is_null()) {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Annular Sector"));
    pl->set("Center X", 0.0, "x of the centre of the circles", finiteNumber());
    pl->set("Center Y", 0.0, "y of the centre of the circles", finiteNumber());
    pl->set("Inner Radius", 1.5, "inner radius", greaterThan(0.0));
    pl->set("Outer Radius", 2.0, "outer radius (> Inner Radius)", greaterThan(0.0));
    pl->set("Start Angle", 0.0,
            "angle of the 'start' radial edge in degrees, counter-clockwise from the +x axis", finiteNumber());
    pl->set("End Angle", 180.0,
            "angle of the 'end' radial edge in degrees; may be smaller than Start Angle (the sector "
            "is then swept clockwise); End Angle - Start Angle must be nonzero and less than 360 in "
            "magnitude",
            finiteNumber());
    pl->set("Radial Elements", 4, "number of elements through the thickness, before refinement", greaterThan(0));
    pl->set("Circumferential Elements", 64, "number of elements along the arc, before refinement", greaterThan(0));
    pl->set("Refinement", 1,
            "multiplies both element counts; refine a benchmark from the command line with --set", atLeast(1));
    valid = pl;
  }
  return valid;
}

int generateAnnularSector(Mesh& mesh, const std::string& bodyName, CellType type,
                          Teuchos::ParameterList& params, const std::string& path) {
  validateLevel(params, *AnnularSectorGenerator::getValidParameters(), path);
  const double cx = params.get<double>("Center X");
  const double cy = params.get<double>("Center Y");
  const double ri = params.get<double>("Inner Radius");
  const double ro = params.get<double>("Outer Radius");
  const double start = params.get<double>("Start Angle");
  const double end = params.get<double>("End Angle");
  // Each value is in range by its validator; these are the relations between them.
  DDC_INPUT_REQUIRE(ro > ri, "parameter '" << joinPath(path, "Outer Radius") << "' must be greater than 'Inner Radius' ("
                                            << ri << "), got " << ro);
  const double sweep = end - start;
  DDC_INPUT_REQUIRE(sweep != 0.0 && std::abs(sweep) < 360.0,
                    "parameters '" << joinPath(path, "Start Angle") << "' (" << start << ") and 'End Angle' ("
                                   << end << ") must differ by more than 0 and less than 360 degrees (a "
                                   << "closed ring is not supported; use two sectors)");
  const int refinement = getRefinement(params);
  const int nr = refinedCount(params, "Radial Elements", refinement, path);
  const int nc = refinedCount(params, "Circumferential Elements", refinement, path);

  const int body = mesh.beginBody(bodyName, type);
  Grid g;
  g.na = nr;  // a: radial index, inner -> outer
  g.nb = nc;  // b: angle index, Start -> End
  g.m = numCellNodes(type) == 9 ? 2 : 1;
  g.firstNode = mesh.numNodes();
  const int na = g.numA(), nb = g.numB();
  std::vector<std::array<double, 2>> xy(static_cast<size_t>(na) * nb);
  for (int b = 0; b < nb; ++b) {
    // (1-t) s + t e is exact at both ends (t = 0, 1).
    const double t = static_cast<double>(b) / (nb - 1);
    const auto cs = cosSinDegrees((1.0 - t) * start + t * end);
    for (int a = 0; a < na; ++a) {
      const double u = static_cast<double>(a) / (na - 1);
      const double r = (1.0 - u) * ri + u * ro;
      xy[static_cast<size_t>(b) * na + a] = {cx + r * cs[0], cy + r * cs[1]};
    }
  }
  // (r, theta) -> (x, y) preserves orientation when theta increases with b.
  addStructuredBody(mesh, body, g, type, /*flip=*/sweep < 0, xy, {"start", "outer", "end", "inner"});
  return body;
}

}  // namespace ddc
