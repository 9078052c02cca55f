#include "DDC_MeshGenerators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

using Point = std::array<double, 3>;
using Index = std::array<int, 3>;

constexpr double kPi = 3.14159265358979323846;
/// Largest accepted "Distortion" of a Rectangle (see the proof sketch in the
/// header).
constexpr double kMaxDistortion = 0.3;
/// Largest accepted "Distortion" of a Box: below 1/(2 sqrt 3) = 0.2887 (see
/// the header).
constexpr double kMaxDistortion3D = 0.25;
/// Fixed seed of the distortion generator: same mesh on every rank and run.
constexpr std::uint32_t kDistortionSeed = 20220804u;

/// A structured grid of n[0] x n[1] (x n[2] in 3-D) cells in index space.
/// Quadratic cell types use the "fine" grid with m = 2 points per cell and
/// direction (corners at even indices), linear ones m = 1. Grid points are
/// numbered with index 0 fastest, then 1, then 2.
struct Grid {
  int dim = 2;
  Index n{{1, 1, 1}};
  int m = 1;
  int points(int d) const { return d < dim ? m * n[d] + 1 : 1; }
  std::size_t numPoints() const {
    return static_cast<std::size_t>(points(0)) * static_cast<std::size_t>(points(1)) *
           static_cast<std::size_t>(points(2));
  }
  std::size_t index(const Index& p) const {
    return (static_cast<std::size_t>(p[2]) * points(1) + p[1]) * points(0) + p[0];
  }
  /// Calls f(point) for every grid point whose indices are multiples of
  /// `step`, in numbering order.
  template <class F>
  void forEachPoint(int step, F f) const {
    for (int c = 0; c < points(2); c += step)
      for (int b = 0; b < points(1); b += step)
        for (int a = 0; a < points(0); a += step) f(Index{{a, b, c}});
  }
};

/// Grid points per cell and direction: 2 if the cell type has nodes besides
/// its corners (Quad9, Hex20, Hex27, Tet10), else 1.
int pointsPerCell(CellType t) { return numCellNodes(t) == referenceCell(t).numCorners ? 1 : 2; }

/// Calls `visit` with the corners of every cell of `g` as grid points, in the
/// corner order of cell type `t`, cells in grid order (one cell at a time: a
/// list of all cells would cost a fine grid's generator tens of MB). A
/// quadrilateral or hexahedron fills one grid cell; tetrahedra split each
/// grid cell into the six tetrahedra of the Kuhn (Freudenthal) triangulation, one per path 000 -> 111 along the edges
/// of the cube, i.e. one per ordering of the three axes. All of them share
/// the main diagonal and every face of the cube is cut along the diagonal
/// from its lowest to its highest corner, so the face splits of two
/// neighbouring cells agree: the mesh is conforming (Freudenthal 1942; Bey,
/// "Simplicial grid refinement", BIT 2000).
///
/// The cells are positively oriented in index space, or negatively if
/// `reversed` (for a map from indices to coordinates that reverses
/// orientation, so that the cells are positive in space): quadrilaterals and
/// hexahedra then swap the roles of index directions 0 and 1, tetrahedra swap
/// two corners.
void forEachGridCell(const Grid& g, CellType t, bool reversed,
                     const std::function<void(const std::vector<Index>&)>& visit);

/// Cells per grid cell: six tetrahedra, or one quadrilateral / hexahedron.
int cellsPerGridCell(CellType t) { return referenceCell(t).simplex ? 6 : 1; }

/// The corners of cell `o` (0 unless tetrahedra) of grid cell (i, j, k), as
/// forEachGridCell() visits it.
std::vector<Index> gridCellCorners(const Grid& g, CellType t, bool reversed, int i, int j, int k, int o) {
  const ReferenceCell& ref = referenceCell(t);
  static const std::array<Index, 6> orders = {{{{0, 1, 2}}, {{0, 2, 1}}, {{1, 0, 2}}, {{1, 2, 0}}, {{2, 0, 1}}, {{2, 1, 0}}}};
  static const std::array<int, 6> orderSign = {{1, -1, -1, 1, 1, -1}};
  const Index base{{g.m * i, g.m * j, g.m * k}};
  if (!ref.simplex) {
    std::vector<Index> corners;
    for (int c = 0; c < ref.numCorners; ++c) {
      Index p = base;
      for (int d = 0; d < g.dim; ++d) {
        const int axis = reversed && d < 2 ? 1 - d : d;
        p[axis] += ref.nodes[c][d] > 0 ? g.m : 0;
      }
      corners.push_back(p);
    }
    return corners;
  }
  // det[w1 - w0, w2 - w0, w3 - w0] = det[e_o0, e_o1, e_o2] = orderSign.
  std::vector<Index> w(4, base);
  for (int s = 1; s <= 3; ++s) {
    w[s] = w[s - 1];
    w[s][orders[o][s - 1]] += g.m;
  }
  if ((orderSign[o] > 0) == reversed) std::swap(w[1], w[2]);
  return w;
}

void forEachGridCell(const Grid& g, CellType t, bool reversed,
                     const std::function<void(const std::vector<Index>&)>& visit) {
  const ReferenceCell& ref = referenceCell(t);
  DDC_CHECK(ref.dim == g.dim && (!ref.simplex || g.dim == 3), "grid of dimension " << g.dim << " for " << ref.name);
  for (int k = 0; k < (g.dim == 3 ? g.n[2] : 1); ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        for (int o = 0; o < cellsPerGridCell(t); ++o) visit(gridCellCorners(g, t, reversed, i, j, k, o));
}

/// The grid point of every node of a cell from its corners: the node's
/// reference coordinates mapped by the corner map (multilinear for
/// quadrilaterals / hexahedra, affine for simplices). With m = 2 every node
/// of Quad9, Hex20, Hex27 and Tet10 lands on a grid point.
std::vector<Index> cellNodePoints(CellType t, const std::vector<Index>& corners) {
  const ReferenceCell& ref = referenceCell(t);
  std::vector<Index> points;
  for (const Point& xi : ref.nodes) {
    Point p{0, 0, 0};
    for (int c = 0; c < ref.numCorners; ++c) {
      double w = 1.0;
      if (ref.simplex) {
        w = c == 0 ? 1.0 - xi[0] - xi[1] - xi[2] : xi[c - 1];
      } else {
        for (int d = 0; d < ref.dim; ++d) w *= 0.5 * (1.0 + xi[d] * ref.nodes[c][d]);
      }
      for (int d = 0; d < 3; ++d) p[d] += w * corners[c][d];
    }
    Index q;
    for (int d = 0; d < 3; ++d) {
      q[d] = static_cast<int>(std::lround(p[d]));
      DDC_CHECK(std::abs(p[d] - q[d]) < 1e-9, ref.name << " node off the grid");
    }
    points.push_back(q);
  }
  return points;
}

/// Order segments so that each one ends where the next begins (a walk along
/// the boundary in the counter-clockwise sense of the body, as the segments
/// themselves are oriented that way). 2-D only.
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
    DDC_CHECK(found, "structured boundary is not a chain");
  }
  return out;
}

/// Add the nodes and elements of a structured grid to body `body` (the
/// current body of `mesh`) and define its side sets and node set "all".
/// \param x coordinates of every grid point, indexed by g.index(); only the
///        points that are nodes of some cell become nodes (Hex20 leaves out
///        face and cell centres), numbered in grid order.
/// \param sideNames name of the side set on the grid side index d = 0 (at
///        2d) and index d = max (at 2d + 1), for d < g.dim; sides with the
///        same name (3-D) make one side set. 2-D side sets
///        are chained (chainSegments), 3-D ones list faces in element order.
/// \return the node number of every grid point (-1 if it is no node).
std::vector<int> addStructuredBody(Mesh& mesh, int body, const Grid& g, CellType type, bool reversed,
                                   const std::vector<Point>& x, const std::vector<std::string>& sideNames) {
  DDC_CHECK(static_cast<int>(sideNames.size()) == 2 * g.dim, "one side name per grid side");
  const ReferenceCell& ref = referenceCell(type);
  std::vector<int> node(g.numPoints(), -1);
  forEachGridCell(g, type, reversed, [&](const std::vector<Index>& corners) {
    for (const Index& p : cellNodePoints(type, corners)) node[g.index(p)] = 0;
  });
  std::vector<int> all;
  for (std::size_t k = 0; k < node.size(); ++k)
    if (node[k] == 0) {
      node[k] = g.dim == 3 ? mesh.addNode(x[k][0], x[k][1], x[k][2]) : mesh.addNode(x[k][0], x[k][1]);
      all.push_back(node[k]);
    }
  std::vector<std::vector<Segment>> sides(sideNames.size());
  std::vector<int> nodes(ref.numNodes);
  forEachGridCell(g, type, reversed, [&](const std::vector<Index>& corners) {
    const std::vector<Index> points = cellNodePoints(type, corners);
    for (int i = 0; i < ref.numNodes; ++i) nodes[i] = node[g.index(points[i])];
    const int e = mesh.addElement(nodes.data());
    for (int f = 0; f < static_cast<int>(ref.facets.size()); ++f) {
      const ReferenceFacet& facet = ref.facets[f];
      for (std::size_t side = 0; side < sides.size(); ++side) {
        const int d = static_cast<int>(side / 2);
        const int at = side % 2 == 0 ? 0 : g.points(d) - 1;
        bool on = true;
        for (int k = 0; k < referenceCell(facet.type).numCorners; ++k) on = on && corners[facet.nodes[k]][d] == at;
        if (on) sides[side].push_back(mesh.makeSegment(e, f));
      }
    }
  });
  // Grid sides of the same name make one side set (3-D only: the Sphere
  // Octant's curved surface is three grid sides), in order of first mention.
  for (std::size_t side = 0; side < sides.size(); ++side) {
    const auto first = std::find(sideNames.begin(), sideNames.end(), sideNames[side]) - sideNames.begin();
    if (static_cast<std::size_t>(first) != side) continue;
    for (std::size_t other = side + 1; other < sides.size(); ++other)
      if (sideNames[other] == sideNames[side]) {
        DDC_CHECK(g.dim == 3, "only 3-D side sets can merge grid sides");
        sides[side].insert(sides[side].end(), sides[other].begin(), sides[other].end());
      }
    mesh.addSideSet(body, sideNames[side], g.dim == 2 ? chainSegments(std::move(sides[side])) : std::move(sides[side]));
  }
  mesh.addNodeSet(body, "all", std::move(all));
  return node;
}

/// Uniform double in [0, 1) from the raw 32-bit Mersenne twister output
/// (std::uniform_real_distribution is implementation-defined, this is not).
double uniform01(std::mt19937& gen) { return static_cast<double>(gen()) / 4294967296.0; }

/// Coordinate of grid point p (of np points) on an axis from `origin` over
/// `length`: affine, and exactly origin + length at the last point.
double axisCoordinate(double origin, double length, int p, int np) {
  return p == np - 1 ? origin + length : origin + length * (static_cast<double>(p) / (np - 1));
}

/// Coordinates of every grid point of the box [origin, origin + length]
/// (g.dim axes; z = 0 in 2-D).
///
/// Element vertices (indices multiples of g.m) are affine in the index;
/// interior ones are moved by a random vector, uniform in the disc (2-D) or
/// ball (3-D) of radius distortion * (smallest element size), drawn in grid
/// order from a fixed-seed Mersenne twister: the same vertices move the same
/// way for linear and quadratic cells.
///
/// The other grid points lie on the straight geometry of their cell: for
/// quadrilaterals / hexahedra at the average of the 2^k vertices around a
/// point with k odd indices (so the quadratic cell equals the bilinear /
/// trilinear map of its corners); for tetrahedra at the midpoint of the
/// tetrahedron edge through it, which runs from the vertex below to the
/// vertex above in every odd index (forEachGridCell: Kuhn edges are monotone).
/// The radius of the vertices' random displacement.
double distortionRadius(const Grid& g, const Point& length, double distortion) {
  double hmin = std::numeric_limits<double>::max();
  for (int d = 0; d < g.dim; ++d) hmin = std::min(hmin, length[d] / g.n[d]);
  return distortion * hmin;
}

/// Vertex p (indices multiples of g.m) before its displacement, and whether
/// it is interior (displaced).
Point boxVertex(const Grid& g, const Point& origin, const Point& length, const Index& p, bool& interior) {
  Point q{0, 0, 0};
  interior = true;
  for (int d = 0; d < g.dim; ++d) {
    q[d] = axisCoordinate(origin[d], length[d], p[d], g.points(d));
    interior = interior && p[d] > 0 && p[d] < g.points(d) - 1;
  }
  return q;
}

/// Move an interior vertex by the next draws of `gen` (2 in 2-D, 3 in 3-D).
void displaceVertex(Point& q, int dim, double radius, std::mt19937& gen) {
  if (dim == 2) {
    // Uniform in the disc.
    const double r = radius * std::sqrt(uniform01(gen));
    const double phi = 2.0 * kPi * uniform01(gen);
    q[0] += r * std::cos(phi);
    q[1] += r * std::sin(phi);
  } else {
    // Uniform in the ball: radius ~ cbrt(u), direction uniform on the sphere.
    const double r = radius * std::cbrt(uniform01(gen));
    const double cosTheta = 2.0 * uniform01(gen) - 1.0;
    const double phi = 2.0 * kPi * uniform01(gen);
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    q[0] += r * sinTheta * std::cos(phi);
    q[1] += r * sinTheta * std::sin(phi);
    q[2] += r * cosTheta;
  }
}

/// The vertices a point that is no vertex (an odd index, m = 2) is placed
/// between: for tetrahedra the ends of the edge through it (below, above in
/// every odd index), else the 2^k vertices around it in Gray-code order
/// (00, 10, 11, 01 in 2-D: the order of the corners around a face).
std::vector<Index> surroundingVertices(const Grid& g, const Index& p, bool simplexCells) {
  std::vector<int> odd;
  for (int d = 0; d < g.dim; ++d)
    if (p[d] % 2 == 1) odd.push_back(d);
  if (simplexCells) {
    Index lo = p, hi = p;
    for (int d : odd) {
      --lo[d];
      ++hi[d];
    }
    return {lo, hi};
  }
  const int k = static_cast<int>(odd.size());
  std::vector<Index> out;
  for (int i = 0; i < (1 << k); ++i) {
    const int gray = i ^ (i >> 1);
    Index v = p;
    for (int j = 0; j < k; ++j) v[odd[j]] += (gray >> j) & 1 ? 1 : -1;
    out.push_back(v);
  }
  return out;
}

/// A point that is no vertex from its surrounding vertices' coordinates:
/// the midpoint of a tetrahedron edge, else their average.
Point betweenVertices(const std::vector<Point>& around, bool simplexCells) {
  Point q{0, 0, 0};
  if (simplexCells) {
    for (int i = 0; i < 3; ++i) q[i] = 0.5 * (around[0][i] + around[1][i]);
    return q;
  }
  Point sum{0, 0, 0};
  for (const Point& v : around)
    for (int c = 0; c < 3; ++c) sum[c] += v[c];
  for (int c = 0; c < 3; ++c) q[c] = sum[c] / static_cast<double>(around.size());
  return q;
}

std::vector<Point> boxPoints(const Grid& g, const Point& origin, const Point& length, double distortion,
                             bool simplexCells) {
  std::vector<Point> x(g.numPoints(), Point{0, 0, 0});
  const double radius = distortionRadius(g, length, distortion);
  std::mt19937 gen(kDistortionSeed);
  g.forEachPoint(g.m, [&](const Index& p) {
    bool interior = true;
    Point& q = x[g.index(p)] = boxVertex(g, origin, length, p, interior);
    if (interior && radius > 0.0) displaceVertex(q, g.dim, radius, gen);
  });
  if (g.m == 1) return x;
  g.forEachPoint(1, [&](const Index& p) {
    bool vertex = true;
    for (int d = 0; d < g.dim; ++d) vertex = vertex && p[d] % 2 == 0;
    if (vertex) return;
    std::vector<Point> around;
    for (const Index& v : surroundingVertices(g, p, simplexCells)) around.push_back(x[g.index(v)]);
    x[g.index(p)] = betweenVertices(around, simplexCells);
  });
  return x;
}

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

/// Element count times refinement, checked so that one direction of the
/// node grid fits an int (the count itself is > 0 by its validator).
int refinedCount(Teuchos::ParameterList& params, const std::string& name, int refinement,
                 const std::string& path) {
  const int n = params.get<int>(name);
  const long long r = static_cast<long long>(n) * refinement;
  DDC_INPUT_REQUIRE(2 * r + 1 < 46000, "parameter '" << joinPath(path, name) << "' times 'Refinement' ("
                                                     << r << ") is too large for a structured mesh");
  return static_cast<int>(r);
}

/// A grid of the given cell counts for cell type `type`, which must be of
/// dimension `counts.size()`; the grid's nodes must fit an int.
Grid makeGrid(CellType type, const std::vector<int>& counts, const std::string& generator, const std::string& path) {
  const int dim = static_cast<int>(counts.size());
  std::ostringstream types;
  for (CellType t : elementCellTypes())
    if (cellDimension(t) == dim) types << (types.tellp() > 0 ? ", " : "") << cellTypeName(t);
  DDC_INPUT_REQUIRE(cellDimension(type) == dim, "'" << path << "': the " << generator << " generator makes a " << dim
                                                    << "-D body, but its element type " << cellTypeName(type)
                                                    << " is " << cellDimension(type) << "-D; use one of "
                                                    << types.str());
  Grid g;
  g.dim = dim;
  for (int d = 0; d < dim; ++d) g.n[d] = counts[d];
  g.m = pointsPerCell(type);
  DDC_INPUT_REQUIRE(g.numPoints() < static_cast<std::size_t>(std::numeric_limits<int>::max()),
                    "'" << path << "': the mesh (after 'Refinement') would have " << g.numPoints()
                        << " grid points, more than a node number can hold");
  return g;
}

/// Mesh::requireRoom() for a structured body on grid g (before its points
/// are allocated).
void requireRoom(const Mesh& mesh, const Grid& g, CellType type, const std::string& path) {
  double cells = 1.0;
  for (int d = 0; d < g.dim; ++d) cells *= g.n[d];
  if (referenceCell(type).simplex) cells *= g.dim == 3 ? 6.0 : 2.0;
  mesh.requireRoom(static_cast<double>(g.numPoints()), cells, numCellNodes(type), path);
}

/// Annular-sector geometry read from (and checked against) a parameter
/// list holding the AnnularSectorGenerator parameters.
struct SectorGeometry {
  double cx = 0, cy = 0, ri = 0, ro = 0, start = 0, end = 0;
  int refinement = 1, nr = 0, nc = 0;
};

SectorGeometry readSector(Teuchos::ParameterList& params, const std::string& path) {
  SectorGeometry s;
  s.cx = params.get<double>("Center X");
  s.cy = params.get<double>("Center Y");
  s.ri = params.get<double>("Inner Radius");
  s.ro = params.get<double>("Outer Radius");
  s.start = params.get<double>("Start Angle");
  s.end = params.get<double>("End Angle");
  // Each value is in range by its validator; these are the relations between them.
  DDC_INPUT_REQUIRE(s.ro > s.ri, "parameter '" << joinPath(path, "Outer Radius")
                                               << "' must be greater than 'Inner Radius' (" << s.ri << "), got "
                                               << s.ro);
  const double sweep = s.end - s.start;
  DDC_INPUT_REQUIRE(sweep != 0.0 && std::abs(sweep) < 360.0,
                    "parameters '" << joinPath(path, "Start Angle") << "' (" << s.start << ") and 'End Angle' ("
                                   << s.end << ") must differ by more than 0 and less than 360 degrees (a "
                                   << "closed ring is not supported; use two sectors)");
  s.refinement = params.get<int>("Refinement");
  s.nr = refinedCount(params, "Radial Elements", s.refinement, path);
  s.nc = refinedCount(params, "Circumferential Elements", s.refinement, path);
  return s;
}

/// Coordinates of grid point p of an annular sector (index 0 radial,
/// inner -> outer; index 1 angular, Start -> End; index 2, in 3-D, axial from
/// z0 over `length`). Every point is mapped from (r, theta) directly, so
/// quadratic nodes lie on their circles; the 2-D and the 3-D sector compute
/// x and y by this one function and agree to the last bit, and so do a
/// whole sector and one made by element range.
Point sectorPoint(const Grid& g, const SectorGeometry& s, const Index& p, double z0, double length) {
  // (1-t) s + t e is exact at both ends (t = 0, 1).
  const double t = static_cast<double>(p[1]) / (g.points(1) - 1);
  const auto cs = cosSinDegrees((1.0 - t) * s.start + t * s.end);
  const double u = static_cast<double>(p[0]) / (g.points(0) - 1);
  const double r = (1.0 - u) * s.ri + u * s.ro;
  const double z = g.dim == 3 ? axisCoordinate(z0, length, p[2], g.points(2)) : 0.0;
  return {s.cx + r * cs[0], s.cy + r * cs[1], z};
}

/// sectorPoint() of every grid point, by g.index().
std::vector<Point> sectorPoints(const Grid& g, const SectorGeometry& s, double z0 = 0.0, double length = 0.0) {
  std::vector<Point> x(g.numPoints());
  g.forEachPoint(1, [&](const Index& p) { x[g.index(p)] = sectorPoint(g, s, p, z0, length); });
  return x;
}

const char* const kAxisName[3] = {"X", "Y", "Z"};
const char* const kAxisLower[3] = {"x", "y", "z"};

/// "Refinement" of a generator with element counts in `dim` directions.
void setRefinementParameter(Teuchos::ParameterList& pl, int dim) {
  pl.set("Refinement", 1,
         std::string("multiplies ") + (dim == 2 ? "both" : "all three") +
             " element counts; refine a benchmark from the command line with --set",
         atLeast(1));
}

/// Origin, Length and Elements of every axis of a Rectangle (2) or Box (3),
/// then Refinement and Distortion.
Teuchos::RCP<Teuchos::ParameterList> boxParameters(const std::string& name, int dim, double maxDistortion) {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList(name));
  const std::string corner = dim == 2 ? "lower-left corner" : "corner with the smallest coordinates";
  for (int d = 0; d < dim; ++d)
    pl->set(std::string("Origin ") + kAxisName[d], 0.0, std::string(kAxisLower[d]) + " of the " + corner,
            finiteNumber());
  for (int d = 0; d < dim; ++d)
    pl->set(std::string("Length ") + kAxisName[d], 1.0, std::string("extent along ") + kAxisLower[d],
            greaterThan(0.0));
  for (int d = 0; d < dim; ++d)
    pl->set(std::string("Elements ") + kAxisName[d], 4,
            std::string("number of elements along ") + kAxisLower[d] + ", before refinement", greaterThan(0));
  setRefinementParameter(*pl, dim);
  pl->set("Distortion", 0.0,
          "random but reproducible (fixed seed) displacement of the interior element vertices, as "
          "a fraction of the element size (larger values than the maximum can invert elements); for "
          "patch tests on distorted meshes",
          between(0.0, maxDistortion));
  return pl;
}

/// The box of a Rectangle or Box parameter list: grid, origin, lengths.
struct BoxGeometry {
  Grid grid;
  Point origin{0, 0, 0}, length{0, 0, 0};
  double distortion = 0.0;
};

BoxGeometry readBox(Teuchos::ParameterList& params, CellType type, int dim, const std::string& generator,
                    const std::string& path) {
  BoxGeometry b;
  const int refinement = params.get<int>("Refinement");
  std::vector<int> counts;
  for (int d = 0; d < dim; ++d) {
    b.origin[d] = params.get<double>(std::string("Origin ") + kAxisName[d]);
    b.length[d] = params.get<double>(std::string("Length ") + kAxisName[d]);
    counts.push_back(refinedCount(params, std::string("Elements ") + kAxisName[d], refinement, path));
  }
  b.distortion = params.get<double>("Distortion");
  b.grid = makeGrid(type, counts, generator, path);
  return b;
}

/// Annular Sector parameters (shared by the Cylindrical Shell Sector).
void setSectorParameters(Teuchos::ParameterList& pl) {
  pl.set("Center X", 0.0, "x of the centre of the circles", finiteNumber());
  pl.set("Center Y", 0.0, "y of the centre of the circles", finiteNumber());
  pl.set("Inner Radius", 1.5, "inner radius", greaterThan(0.0));
  pl.set("Outer Radius", 2.0, "outer radius (> Inner Radius)", greaterThan(0.0));
  pl.set("Start Angle", 0.0,
         "angle of the 'start' radial edge in degrees, counter-clockwise from the +x axis", finiteNumber());
  pl.set("End Angle", 180.0,
         "angle of the 'end' radial edge in degrees; may be smaller than Start Angle (the sector "
         "is then swept clockwise); End Angle - Start Angle must be nonzero and less than 360 in "
         "magnitude",
         finiteNumber());
  pl.set("Radial Elements", 4, "number of elements through the thickness, before refinement", greaterThan(0));
  pl.set("Circumferential Elements", 64, "number of elements along the arc, before refinement", greaterThan(0));
}

}  // namespace

// ---------------------------------------------------------------- Rectangle

Teuchos::RCP<const Teuchos::ParameterList> RectangleGenerator::getValidParameters() {
  static const Teuchos::RCP<const Teuchos::ParameterList> valid = boxParameters("Rectangle", 2, kMaxDistortion);
  return valid;
}

int generateRectangle(Mesh& mesh, const std::string& bodyName, CellType type,
                      Teuchos::ParameterList& params, const std::string& path) {
  validateLevel(params, *RectangleGenerator::getValidParameters(), path);
  const BoxGeometry box = readBox(params, type, 2, "Rectangle", path);
  const Grid& g = box.grid;
  requireRoom(mesh, g, type, path);
  const int body = mesh.beginBody(bodyName, type);
  const auto x = boxPoints(g, box.origin, box.length, box.distortion, /*simplexCells=*/false);
  const auto node = addStructuredBody(mesh, body, g, type, /*reversed=*/false, x, {"left", "right", "bottom", "top"});
  const int na = g.points(0), nb = g.points(1);
  mesh.addNodeSet(body, "bottom left", {node[g.index({{0, 0, 0}})]});
  mesh.addNodeSet(body, "bottom right", {node[g.index({{na - 1, 0, 0}})]});
  mesh.addNodeSet(body, "top left", {node[g.index({{0, nb - 1, 0}})]});
  mesh.addNodeSet(body, "top right", {node[g.index({{na - 1, nb - 1, 0}})]});
  return body;
}

// ---------------------------------------------------------------------- Box

Teuchos::RCP<const Teuchos::ParameterList> BoxGenerator::getValidParameters() {
  static const Teuchos::RCP<const Teuchos::ParameterList> valid = boxParameters("Box", 3, kMaxDistortion3D);
  return valid;
}

int generateBox(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                const std::string& path) {
  validateLevel(params, *BoxGenerator::getValidParameters(), path);
  const BoxGeometry box = readBox(params, type, 3, "Box", path);
  const Grid& g = box.grid;
  requireRoom(mesh, g, type, path);
  const int body = mesh.beginBody(bodyName, type);
  const auto x = boxPoints(g, box.origin, box.length, box.distortion, referenceCell(type).simplex);
  const auto node =
      addStructuredBody(mesh, body, g, type, /*reversed=*/false, x, {"left", "right", "bottom", "top", "back", "front"});
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) {
        const std::string name = std::string(b ? "top" : "bottom") + (a ? " right" : " left") + (c ? " front" : " back");
        mesh.addNodeSet(body, name, {node[g.index({{a * (g.points(0) - 1), b * (g.points(1) - 1), c * (g.points(2) - 1)}})]});
      }
  return body;
}

// ------------------------------------------- Rectangle and Box by element range

namespace {

/// Whether grid point p is a node of cell type t: every point is, but the
/// face and cell centres of Hex20 (two or three odd indices).
bool isNodePoint(CellType t, const Index& p) {
  if (t != CellType::Hex20) return true;
  return (p[0] % 2) + (p[1] % 2) + (p[2] % 2) <= 1;
}

/// The number of node points before grid point p in grid order: the node
/// number addStructuredBody() gives p (within its body). Past the last
/// point (p = (0, 0, points(2))) it is the body's node count.
long long nodePointsBefore(const Grid& g, CellType t, const Index& p) {
  if (t != CellType::Hex20) return static_cast<long long>(g.index(p));
  const long long P0 = g.points(0), P1 = g.points(1);
  const long long E0 = (P0 + 1) / 2, E1 = (P1 + 1) / 2, O1 = P1 - E1;
  const long long evenLayer = E1 * P0 + O1 * E0, oddLayer = E1 * E0;  // b even: all a or even a; b odd: even a or none
  long long count = (p[2] + 1) / 2 * evenLayer + p[2] / 2 * oddLayer;
  const bool evenC = p[2] % 2 == 0;
  count += evenC ? (p[1] + 1) / 2 * P0 + p[1] / 2 * E0 : (p[1] + 1) / 2 * E0;
  count += evenC && p[1] % 2 == 0 ? p[0] : (p[0] + 1) / 2;
  return count;
}

/// The interior vertices before vertex p in the order boxPoints() draws
/// their displacements (grid order, axis 0 fastest): those of the complete
/// slabs of the slowest axis before p, then, if p is interior along it, of
/// the rows before p within its slab, and so on.
long long interiorVerticesBefore(const Grid& g, const Index& p) {
  std::array<long long, 3> inside{{0, 0, 0}};  // interior vertices along each axis
  for (int d = 0; d < g.dim; ++d) inside[d] = std::max(g.n[d] - 1, 0);
  long long before = 0;
  for (int d = g.dim - 1; d >= 0; --d) {
    const long long at = p[d] / g.m;
    long long perSlab = 1;
    for (int e = 0; e < d; ++e) perSlab *= inside[e];
    before += std::clamp(at - 1, 0LL, inside[d]) * perSlab;
    if (at == 0 || at == g.n[d]) break;  // p's slab along d holds no interior vertex
  }
  return before;
}

/// The coordinates of the grid points `points` (grid indices, ascending) as
/// boxPoints() gives them, without the others: each vertex they need is
/// displaced by the draws boxPoints() makes for it, found by skipping the
/// draws of the vertices before it.
std::vector<Point> rangeBoxPoints(const Grid& g, const Point& origin, const Point& length, double distortion,
                                  bool simplexCells, const std::vector<Index>& points) {
  std::vector<Index> vertices;
  auto isVertex = [&](const Index& p) {
    for (int d = 0; d < g.dim; ++d)
      if (p[d] % g.m != 0) return false;
    return true;
  };
  for (const Index& p : points) {
    if (isVertex(p)) vertices.push_back(p);
    else
      for (const Index& v : surroundingVertices(g, p, simplexCells)) vertices.push_back(v);
  }
  auto byIndex = [&](const Index& a, const Index& b) { return g.index(a) < g.index(b); };
  std::sort(vertices.begin(), vertices.end(), byIndex);
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  const double radius = distortionRadius(g, length, distortion);
  std::mt19937 gen(kDistortionSeed);
  const long long drawsPerVertex = g.dim;  // displaceVertex(): 2 in 2-D, 3 in 3-D
  long long drawn = 0;
  std::vector<Point> at(vertices.size());
  for (size_t i = 0; i < vertices.size(); ++i) {
    bool interior = true;
    at[i] = boxVertex(g, origin, length, vertices[i], interior);
    if (!interior || radius <= 0.0) continue;
    const long long skip = interiorVerticesBefore(g, vertices[i]) * drawsPerVertex - drawn;
    DDC_CHECK(skip >= 0, "vertex draws out of order");
    gen.discard(static_cast<unsigned long long>(skip));
    displaceVertex(at[i], g.dim, radius, gen);
    drawn += skip + drawsPerVertex;
  }
  auto vertexAt = [&](const Index& v) {
    return at[std::lower_bound(vertices.begin(), vertices.end(), v, byIndex) - vertices.begin()];
  };
  std::vector<Point> x;
  for (const Index& p : points) {
    if (isVertex(p)) {
      x.push_back(vertexAt(p));
      continue;
    }
    std::vector<Point> around;
    for (const Index& v : surroundingVertices(g, p, simplexCells)) around.push_back(vertexAt(v));
    x.push_back(betweenVertices(around, simplexCells));
  }
  return x;
}

/// The coordinates of some grid points of a body (grid indices, ascending).
using PointsOf = std::function<std::vector<Point>(const std::vector<Index>&)>;

/// addStructuredBody() for the elements of the body whose ids in the whole
/// mesh lie in `range`, into the part `mesh` (Mesh::startPart()): the
/// elements in grid order with their ids, their nodes in id order, the
/// sets restricted to them as Mesh::part() restricts them (grid sides of
/// one name one set; 2-D side sets in their chain order: in element order
/// along grid sides 1 and 2, backward along 0 and 3, the other way round
/// when `reversed`), and the whole mesh grown by the body.
/// \param coordinates the points' coordinates, as the whole body has them
/// \return the part's index of each node point it holds, by grid index.
std::map<std::size_t, int> addStructuredBodyRange(Mesh& mesh, int body, const Grid& g, CellType type, bool reversed,
                                                  const PointsOf& coordinates, const ElementRange& range,
                                                  const std::vector<std::string>& sideNames, const std::string& path) {
  const ReferenceCell& ref = referenceCell(type);
  const int per = cellsPerGridCell(type);
  const long long cells = static_cast<long long>(g.n[0]) * g.n[1] * (g.dim == 3 ? g.n[2] : 1);
  const long long firstElement = mesh.numGlobalElements(), firstNode = mesh.numGlobalNodes();
  const long long lo = std::clamp(range.first - firstElement, 0LL, cells * per);
  const long long hi = std::clamp(range.last - firstElement, lo, cells * per);
  // The range's share of the body's points, before any is listed.
  const double share = double(hi - lo) / double(cells * per);
  mesh.requireRoom(share * static_cast<double>(g.numPoints()), double(hi - lo), numCellNodes(type), path);
  // The corners of the chosen elements and their node points.
  std::vector<std::vector<Index>> corners;
  std::vector<Index> points;
  for (long long le = lo; le < hi; ++le) {
    const long long c = le / per;
    const int i = static_cast<int>(c % g.n[0]), j = static_cast<int>(c / g.n[0] % g.n[1]);
    const int k = static_cast<int>(c / (static_cast<long long>(g.n[0]) * g.n[1]));
    corners.push_back(gridCellCorners(g, type, reversed, i, j, k, static_cast<int>(le % per)));
    for (const Index& p : cellNodePoints(type, corners.back())) points.push_back(p);
  }
  auto byIndex = [&](const Index& a, const Index& b) { return g.index(a) < g.index(b); };
  std::sort(points.begin(), points.end(), byIndex);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  const std::vector<Point> x = coordinates(points);
  std::map<std::size_t, int> node;
  std::vector<int> all;
  for (size_t q = 0; q < points.size(); ++q) {
    const long long id = firstNode + nodePointsBefore(g, type, points[q]);
    node[g.index(points[q])] = mesh.addPartNode(id, x[q][0], x[q][1], g.dim == 3 ? x[q][2] : 0.0);
    all.push_back(node[g.index(points[q])]);
  }
  std::vector<std::vector<Segment>> sides(sideNames.size());
  std::vector<int> nodes(ref.numNodes);
  for (long long le = lo; le < hi; ++le) {
    const std::vector<Index>& cc = corners[static_cast<size_t>(le - lo)];
    const std::vector<Index> cellPoints = cellNodePoints(type, cc);
    for (int i = 0; i < ref.numNodes; ++i) nodes[i] = node.at(g.index(cellPoints[i]));
    const int e = mesh.addPartElement(firstElement + le, nodes.data());
    for (int f = 0; f < static_cast<int>(ref.facets.size()); ++f)
      for (std::size_t side = 0; side < sides.size(); ++side) {
        const int d = static_cast<int>(side / 2);
        const int at = side % 2 == 0 ? 0 : g.points(d) - 1;
        bool on = true;
        for (int k = 0; k < referenceCell(ref.facets[f].type).numCorners; ++k)
          on = on && cc[ref.facets[f].nodes[k]][d] == at;
        if (on) sides[side].push_back(mesh.makeSegment(e, f));
      }
  }
  for (std::size_t side = 0; side < sides.size(); ++side) {
    // Grid sides of one name make one set, in order of first mention.
    if (std::find(sideNames.begin(), sideNames.end(), sideNames[side]) - sideNames.begin() != long(side)) continue;
    std::vector<Segment> segments;
    std::vector<int> onSide;
    for (std::size_t other = side; other < sides.size(); ++other) {
      if (sideNames[other] != sideNames[side]) continue;
      // The whole mesh's 2-D chains run counter-clockwise in space: backward
      // in element order along grid sides 0 and 3, or 1 and 2 when the map
      // reverses the orientation.
      const bool backward = (other == 0 || other == 3) != reversed;
      if (g.dim == 2 && backward) std::reverse(sides[other].begin(), sides[other].end());
      segments.insert(segments.end(), sides[other].begin(), sides[other].end());
      // The node set holds every node on the side, also those of elements
      // whose facets on it this part does not hold (a tetrahedron may touch
      // a side at an edge or a corner).
      const int d = static_cast<int>(other / 2), at = other % 2 == 0 ? 0 : g.points(d) - 1;
      for (const Index& p : points)
        if (p[d] == at) onSide.push_back(node.at(g.index(p)));
    }
    mesh.addSideSet(body, sideNames[side], std::move(segments));
    mesh.addNodeSet(body, sideNames[side], std::move(onSide));  // sorted, and united with the segments' nodes
  }
  mesh.addNodeSet(body, "all", std::move(all));
  mesh.growWhole(nodePointsBefore(g, type, Index{{0, 0, g.points(2)}}), cells * per);
  return node;
}

/// The points of a Rectangle or Box, displaced as the whole body's are.
PointsOf boxPointsOf(const BoxGeometry& box, CellType type) {
  return [box, simplex = referenceCell(type).simplex](const std::vector<Index>& points) {
    return rangeBoxPoints(box.grid, box.origin, box.length, box.distortion, simplex, points);
  };
}

/// The part's index of the node at grid index `index` as a one-node set,
/// or an empty set where the part does not hold that node.
std::vector<int> heldNode(const std::map<std::size_t, int>& node, std::size_t index) {
  const auto it = node.find(index);
  return it == node.end() ? std::vector<int>() : std::vector<int>{it->second};
}

}  // namespace

int generateRectangle(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                      const std::string& path, const ElementRange& range) {
  DDC_CHECK(part.isPart(), "generateRectangle() by range into a whole mesh");
  validateLevel(params, *RectangleGenerator::getValidParameters(), path);
  const BoxGeometry box = readBox(params, type, 2, "Rectangle", path);
  const Grid& g = box.grid;
  const int body = part.beginBody(bodyName, type);
  const auto node = addStructuredBodyRange(part, body, g, type, /*reversed=*/false, boxPointsOf(box, type), range,
                                           {"left", "right", "bottom", "top"}, path);
  const int na = g.points(0), nb = g.points(1);
  part.addNodeSet(body, "bottom left", heldNode(node, g.index({{0, 0, 0}})));
  part.addNodeSet(body, "bottom right", heldNode(node, g.index({{na - 1, 0, 0}})));
  part.addNodeSet(body, "top left", heldNode(node, g.index({{0, nb - 1, 0}})));
  part.addNodeSet(body, "top right", heldNode(node, g.index({{na - 1, nb - 1, 0}})));
  return body;
}

int generateBox(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                const std::string& path, const ElementRange& range) {
  DDC_CHECK(part.isPart(), "generateBox() by range into a whole mesh");
  validateLevel(params, *BoxGenerator::getValidParameters(), path);
  const BoxGeometry box = readBox(params, type, 3, "Box", path);
  const Grid& g = box.grid;
  const int body = part.beginBody(bodyName, type);
  const auto node = addStructuredBodyRange(part, body, g, type, /*reversed=*/false, boxPointsOf(box, type), range,
                                           {"left", "right", "bottom", "top", "back", "front"}, path);
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) {
        const std::string name = std::string(b ? "top" : "bottom") + (a ? " right" : " left") + (c ? " front" : " back");
        part.addNodeSet(body, name,
                        heldNode(node, g.index({{a * (g.points(0) - 1), b * (g.points(1) - 1), c * (g.points(2) - 1)}})));
      }
  return body;
}

// ----------------------------------------------------------- Annular sector

Teuchos::RCP<const Teuchos::ParameterList> AnnularSectorGenerator::getValidParameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid;
  if (valid.is_null()) {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Annular Sector"));
    setSectorParameters(*pl);
    setRefinementParameter(*pl, 2);
    valid = pl;
  }
  return valid;
}

int generateAnnularSector(Mesh& mesh, const std::string& bodyName, CellType type,
                          Teuchos::ParameterList& params, const std::string& path) {
  validateLevel(params, *AnnularSectorGenerator::getValidParameters(), path);
  const SectorGeometry s = readSector(params, path);
  const Grid g = makeGrid(type, {s.nr, s.nc}, "Annular Sector", path);
  requireRoom(mesh, g, type, path);
  const int body = mesh.beginBody(bodyName, type);
  // (r, theta) -> (x, y) preserves orientation when theta increases.
  addStructuredBody(mesh, body, g, type, /*reversed=*/s.end < s.start, sectorPoints(g, s),
                    {"inner", "outer", "start", "end"});
  return body;
}

// ------------------------------------------------- Cylindrical shell sector

Teuchos::RCP<const Teuchos::ParameterList> CylindricalShellSectorGenerator::getValidParameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid;
  if (valid.is_null()) {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Cylindrical Shell Sector"));
    setSectorParameters(*pl);
    pl->set("Origin Z", 0.0, "z of the 'back' face", finiteNumber());
    pl->set("Axial Length", 1.0, "extent along the axis (z) from Origin Z", greaterThan(0.0));
    pl->set("Axial Elements", 1, "number of elements along the axis, before refinement", greaterThan(0));
    setRefinementParameter(*pl, 3);
    valid = pl;
  }
  return valid;
}

int generateCylindricalShellSector(Mesh& mesh, const std::string& bodyName, CellType type,
                                   Teuchos::ParameterList& params, const std::string& path) {
  validateLevel(params, *CylindricalShellSectorGenerator::getValidParameters(), path);
  const SectorGeometry s = readSector(params, path);
  const int nz = refinedCount(params, "Axial Elements", s.refinement, path);
  const Grid g = makeGrid(type, {s.nr, s.nc, nz}, "Cylindrical Shell Sector", path);
  requireRoom(mesh, g, type, path);
  const int body = mesh.beginBody(bodyName, type);
  // (r, theta, z) -> (x, y, z) preserves orientation when theta increases.
  addStructuredBody(mesh, body, g, type, /*reversed=*/s.end < s.start,
                    sectorPoints(g, s, params.get<double>("Origin Z"), params.get<double>("Axial Length")),
                    {"inner", "outer", "start", "end", "back", "front"});
  return body;
}

// ------------------------------------------------------------ Sphere octant

Teuchos::RCP<const Teuchos::ParameterList> SphereOctantGenerator::getValidParameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid;
  if (valid.is_null()) {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Sphere Octant"));
    for (int d = 0; d < 3; ++d)
      pl->set(std::string("Center ") + kAxisName[d], 0.0, std::string(kAxisLower[d]) + " of the centre of the sphere",
              finiteNumber());
    pl->set("Radius", 1.0, "radius of the sphere", greaterThan(0.0));
    pl->set("Elements", 8, "number of elements along each edge of the mapped cube, before refinement",
            greaterThan(0));
    pl->set("Progression", 1.0,
            "ratio of each element's size to that of its neighbour nearer the pole, along every "
            "grid direction (1: uniform; > 1 refines towards the pole, where a contact starts); "
            "with Refinement k the ratio becomes Progression^(1/k), so refining keeps the grading",
            between(1.0, 2.0));
    setRefinementParameter(*pl, 3);
    valid = pl;
  }
  return valid;
}

namespace {

/// Graded cell ends 0 = v_0 < v_1 < ... < v_n = 1 with v_{k+1} - v_k =
/// r^k (v_1 - v_0), returned on the grid of m points per cell (n m + 1
/// values; for m = 2 a cell's middle point at the mean of its ends).
std::vector<double> gradedParameters(int n, int m, double r) {
  std::vector<double> t(static_cast<std::size_t>(n * m + 1), 0.0);
  double h = 1.0, sum = 0.0;
  std::vector<double> vertex(n + 1, 0.0);
  for (int k = 0; k < n; ++k, h *= r) vertex[k + 1] = (sum += h);
  for (int k = 0; k <= n; ++k) vertex[k] /= sum;
  vertex[n] = 1.0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < m; ++j) t[k * m + j] = vertex[k] + (vertex[k + 1] - vertex[k]) * j / m;
  t[n * m] = 1.0;
  return t;
}

}  // namespace

namespace {

/// The Sphere Octant's map of grid points to space (see the header): cube
/// point p = (a, b, w) in [0,1] x [0,1] x [-1,0], graded towards the pole
/// (0, 0, -1), mapped to the ball by p (1 - m + m^2/|p|), m = |p|_inf: the
/// outer cube faces (m = 1) onto the sphere, the planes a = 0, b = 0, w = 0
/// onto themselves. One function for the whole body and its ranges.
struct OctantMap {
  Point centre{0, 0, 0};
  double radius = 1.0;
  std::vector<double> t;  ///< graded parameter of each grid index
  OctantMap(const Grid& g, Teuchos::ParameterList& params, int n) {
    const int refinement = params.get<int>("Refinement");
    radius = params.get<double>("Radius");
    centre = {params.get<double>("Center X"), params.get<double>("Center Y"), params.get<double>("Center Z")};
    t = gradedParameters(n, g.m, std::pow(params.get<double>("Progression"), 1.0 / refinement));
  }
  Point operator()(const Index& p) const {
    const double a = t[p[0]], b = t[p[1]], w = t[p[2]] - 1.0;
    const double norm = std::sqrt(a * a + b * b + w * w);
    const double m = std::max({a, b, -w});
    const double scale = norm > 0.0 ? radius * (1.0 - m + m * m / norm) : 0.0;
    return {centre[0] + scale * a, centre[1] + scale * b, centre[2] + scale * w};
  }
};

/// The Sphere Octant's grid: n elements along each edge of the cube.
Grid octantGrid(CellType type, Teuchos::ParameterList& params, const std::string& path, int& n) {
  n = refinedCount(params, "Elements", params.get<int>("Refinement"), path);
  return makeGrid(type, {n, n, n}, "Sphere Octant", path);
}

const std::vector<std::string> kOctantSides = {"symmetry x", "sphere", "symmetry y", "sphere", "sphere", "top"};

}  // namespace

int generateSphereOctant(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                         const std::string& path) {
  validateLevel(params, *SphereOctantGenerator::getValidParameters(), path);
  int n = 0;
  const Grid g = octantGrid(type, params, path, n);
  requireRoom(mesh, g, type, path);
  const OctantMap map(g, params, n);
  std::vector<Point> x(g.numPoints());
  g.forEachPoint(1, [&](const Index& p) { x[g.index(p)] = map(p); });
  const int body = mesh.beginBody(bodyName, type);
  const auto node = addStructuredBody(mesh, body, g, type, /*reversed=*/false, x, kOctantSides);
  mesh.addNodeSet(body, "pole", {node[g.index({{0, 0, 0}})]});
  return body;
}

// ------------------------------- Sectors and the octant by element range

namespace {

/// sectorPoint() of the given grid points.
PointsOf sectorPointsOf(const Grid& g, const SectorGeometry& s, double z0, double length) {
  return [g, s, z0, length](const std::vector<Index>& points) {
    std::vector<Point> x;
    x.reserve(points.size());
    for (const Index& p : points) x.push_back(sectorPoint(g, s, p, z0, length));
    return x;
  };
}

}  // namespace

int generateAnnularSector(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                          const std::string& path, const ElementRange& range) {
  DDC_CHECK(part.isPart(), "generateAnnularSector() by range into a whole mesh");
  validateLevel(params, *AnnularSectorGenerator::getValidParameters(), path);
  const SectorGeometry s = readSector(params, path);
  const Grid g = makeGrid(type, {s.nr, s.nc}, "Annular Sector", path);
  const int body = part.beginBody(bodyName, type);
  addStructuredBodyRange(part, body, g, type, /*reversed=*/s.end < s.start, sectorPointsOf(g, s, 0.0, 0.0), range,
                         {"inner", "outer", "start", "end"}, path);
  return body;
}

int generateCylindricalShellSector(Mesh& part, const std::string& bodyName, CellType type,
                                   Teuchos::ParameterList& params, const std::string& path,
                                   const ElementRange& range) {
  DDC_CHECK(part.isPart(), "generateCylindricalShellSector() by range into a whole mesh");
  validateLevel(params, *CylindricalShellSectorGenerator::getValidParameters(), path);
  const SectorGeometry s = readSector(params, path);
  const int nz = refinedCount(params, "Axial Elements", s.refinement, path);
  const Grid g = makeGrid(type, {s.nr, s.nc, nz}, "Cylindrical Shell Sector", path);
  const int body = part.beginBody(bodyName, type);
  addStructuredBodyRange(part, body, g, type, /*reversed=*/s.end < s.start,
                         sectorPointsOf(g, s, params.get<double>("Origin Z"), params.get<double>("Axial Length")),
                         range, {"inner", "outer", "start", "end", "back", "front"}, path);
  return body;
}

int generateSphereOctant(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                         const std::string& path, const ElementRange& range) {
  DDC_CHECK(part.isPart(), "generateSphereOctant() by range into a whole mesh");
  validateLevel(params, *SphereOctantGenerator::getValidParameters(), path);
  int n = 0;
  const Grid g = octantGrid(type, params, path, n);
  const OctantMap map(g, params, n);
  const int body = part.beginBody(bodyName, type);
  const auto node = addStructuredBodyRange(
      part, body, g, type, /*reversed=*/false,
      [&map](const std::vector<Index>& points) {
        std::vector<Point> x;
        x.reserve(points.size());
        for (const Index& p : points) x.push_back(map(p));
        return x;
      },
      range, kOctantSides, path);
  part.addNodeSet(body, "pole", heldNode(node, g.index({{0, 0, 0}})));
  return body;
}

bool generatesByRange(const std::string& generator) {
  return generator == "Rectangle" || generator == "Box" || generator == "Annular Sector" ||
         generator == "Cylindrical Shell Sector" || generator == "Sphere Octant";
}

long long structuredElementCount(const std::string& generator, CellType type, Teuchos::ParameterList& params,
                                 const std::string& path) {
  DDC_CHECK(generatesByRange(generator), "structuredElementCount() of a " << generator);
  Grid g;
  if (generator == "Rectangle" || generator == "Box") {
    const bool box3 = generator == "Box";
    validateLevel(params, box3 ? *BoxGenerator::getValidParameters() : *RectangleGenerator::getValidParameters(),
                  path);
    g = readBox(params, type, box3 ? 3 : 2, generator, path).grid;
  } else if (generator == "Sphere Octant") {
    validateLevel(params, *SphereOctantGenerator::getValidParameters(), path);
    int n = 0;
    g = octantGrid(type, params, path, n);
  } else {
    const bool shell = generator == "Cylindrical Shell Sector";
    validateLevel(params,
                  shell ? *CylindricalShellSectorGenerator::getValidParameters()
                        : *AnnularSectorGenerator::getValidParameters(),
                  path);
    const SectorGeometry s = readSector(params, path);
    g = shell ? makeGrid(type, {s.nr, s.nc, refinedCount(params, "Axial Elements", s.refinement, path)}, generator,
                         path)
              : makeGrid(type, {s.nr, s.nc}, generator, path);
  }
  return static_cast<long long>(g.n[0]) * g.n[1] * (g.dim == 3 ? g.n[2] : 1) * cellsPerGridCell(type);
}

}  // namespace ddc
