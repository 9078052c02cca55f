#include "DDC_ReferenceCell.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "DDC_Error.hpp"

namespace ddc {
namespace {

using Point = std::array<double, 3>;

Point midpoint(const std::vector<Point>& x, const std::vector<int>& of) {
  Point m{0, 0, 0};
  for (int i : of)
    for (int d = 0; d < 3; ++d) m[d] += x[i][d] / static_cast<double>(of.size());
  return m;
}

std::vector<int> identity(int n) {
  std::vector<int> p(n);
  std::iota(p.begin(), p.end(), 0);
  return p;
}

/// The middle node of the edge between corners a and b (either direction).
int edgeMiddle(const std::vector<ReferenceEdge>& edges, int a, int b) {
  for (const auto& e : edges)
    if ((e.start == a && e.end == b) || (e.start == b && e.end == a)) return e.middle;
  DDC_CHECK(false, "reference cell: no edge " << a << "-" << b);
  return -1;
}

/// Edges from corner pairs; middle nodes numbered from `firstMiddle` in edge
/// order (or -1 if `quadratic` is false). Adds the middle-node coordinates.
std::vector<ReferenceEdge> makeEdges(const std::vector<std::array<int, 2>>& pairs, bool quadratic,
                                     std::vector<Point>& nodes) {
  std::vector<ReferenceEdge> edges;
  const int first = static_cast<int>(nodes.size());
  for (const auto& p : pairs) {
    const int middle = quadratic ? first + static_cast<int>(edges.size()) : -1;
    edges.push_back({p[0], p[1], middle});
  }
  if (quadratic)
    for (const auto& e : edges) nodes.push_back(midpoint(nodes, {e.start, e.end}));
  return edges;
}

/// A facet from its corners (outward order): corners, then the middle nodes
/// of its edges (c0-c1, c1-c2, ...) if `quadratic`, then `centre` if >= 0.
ReferenceFacet makeFacet(CellType type, const std::vector<int>& corners, const std::vector<ReferenceEdge>& edges,
                         bool quadratic, int centre = -1) {
  ReferenceFacet f{type, corners};
  const int nc = static_cast<int>(corners.size());
  if (quadratic && nc > 1)
    for (int k = 0; k < (nc == 2 ? 1 : nc); ++k)
      f.nodes.push_back(edgeMiddle(edges, corners[k], corners[(k + 1) % nc]));
  if (centre >= 0) f.nodes.push_back(centre);
  return f;
}

ReferenceCell line(bool quadratic) {
  ReferenceCell c{quadratic ? CellType::Line3 : CellType::Line2, quadratic ? "Line3" : "Line2", 1, 0, 2, true};
  c.nodes = {{-1, 0, 0}, {1, 0, 0}};
  c.edges = makeEdges({{{0, 1}}}, quadratic, c.nodes);
  c.numNodes = static_cast<int>(c.nodes.size());
  c.vtkType = quadratic ? 21 : 3;
  c.vtkOrder = identity(c.numNodes);
  return c;
}

ReferenceCell triangle(bool quadratic) {
  ReferenceCell c{quadratic ? CellType::Tri6 : CellType::Tri3, quadratic ? "Tri6" : "Tri3", 2, 0, 3, true};
  c.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  c.edges = makeEdges({{{0, 1}}, {{1, 2}}, {{2, 0}}}, quadratic, c.nodes);
  const CellType side = quadratic ? CellType::Line3 : CellType::Line2;
  for (const auto& e : c.edges) c.facets.push_back(makeFacet(side, {e.start, e.end}, c.edges, quadratic));
  c.numNodes = static_cast<int>(c.nodes.size());
  c.vtkType = quadratic ? 22 : 5;
  c.vtkOrder = identity(c.numNodes);
  return c;
}

/// Quad4 (order 1), Quad8 (serendipity) or Quad9 (order 2 with centre).
ReferenceCell quadrilateral(CellType type) {
  const bool quadratic = type != CellType::Quad4;
  ReferenceCell c{type, type == CellType::Quad4 ? "Quad4" : type == CellType::Quad8 ? "Quad8" : "Quad9", 2, 0, 4,
                  false};
  c.nodes = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  c.edges = makeEdges({{{0, 1}}, {{1, 2}}, {{2, 3}}, {{3, 0}}}, quadratic, c.nodes);
  if (type == CellType::Quad9) c.nodes.push_back({0, 0, 0});
  const CellType side = quadratic ? CellType::Line3 : CellType::Line2;
  for (const auto& e : c.edges) c.facets.push_back(makeFacet(side, {e.start, e.end}, c.edges, quadratic));
  c.numNodes = static_cast<int>(c.nodes.size());
  c.vtkType = type == CellType::Quad4 ? 9 : type == CellType::Quad8 ? 23 : 28;
  c.vtkOrder = identity(c.numNodes);
  return c;
}

ReferenceCell hexahedron(CellType type) {
  const bool quadratic = type != CellType::Hex8;
  ReferenceCell c{type, type == CellType::Hex8 ? "Hex8" : type == CellType::Hex20 ? "Hex20" : "Hex27", 3, 0, 8,
                  false};
  c.nodes = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  c.edges = makeEdges({{{0, 1}}, {{0, 3}}, {{0, 4}}, {{1, 2}}, {{1, 5}}, {{2, 3}}, {{2, 6}}, {{3, 7}}, {{4, 5}},
                       {{4, 7}}, {{5, 6}}, {{6, 7}}},
                      quadratic, c.nodes);
  // Faces, corners counter-clockwise seen from outside; for Hex27 their
  // centres are nodes 20..25 in this order.
  const std::vector<std::vector<int>> faces = {{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 4, 7, 3},
                                               {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}};
  const CellType faceType = type == CellType::Hex8 ? CellType::Quad4 : type == CellType::Hex20 ? CellType::Quad8
                                                                                               : CellType::Quad9;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    int centre = -1;
    if (type == CellType::Hex27) {
      centre = static_cast<int>(c.nodes.size());
      c.nodes.push_back(midpoint(c.nodes, faces[f]));
    }
    c.facets.push_back(makeFacet(faceType, faces[f], c.edges, quadratic, centre));
  }
  if (type == CellType::Hex27) c.nodes.push_back({0, 0, 0});
  c.numNodes = static_cast<int>(c.nodes.size());
  // VTK orders the edges 0-1 1-2 2-3 3-0, 4-5 5-6 6-7 7-4, 0-4 1-5 2-6 3-7
  // and the face centres x-, x+, y-, y+, z-, z+.
  c.vtkType = type == CellType::Hex8 ? 12 : type == CellType::Hex20 ? 25 : 29;
  c.vtkOrder = identity(8);
  if (quadratic)
    for (int i : {8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15}) c.vtkOrder.push_back(i);
  if (type == CellType::Hex27)
    for (int i : {22, 23, 21, 24, 20, 25, 26}) c.vtkOrder.push_back(i);
  return c;
}

ReferenceCell tetrahedron(bool quadratic) {
  ReferenceCell c{quadratic ? CellType::Tet10 : CellType::Tet4, quadratic ? "Tet10" : "Tet4", 3, 0, 4, true};
  c.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  c.edges = makeEdges({{{0, 1}}, {{1, 2}}, {{2, 0}}, {{3, 0}}, {{3, 2}}, {{3, 1}}}, quadratic, c.nodes);
  const CellType faceType = quadratic ? CellType::Tri6 : CellType::Tri3;
  for (const auto& f : std::vector<std::vector<int>>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}})
    c.facets.push_back(makeFacet(faceType, f, c.edges, quadratic));
  c.numNodes = static_cast<int>(c.nodes.size());
  // VTK's edges are 0-1 1-2 2-0 0-3 1-3 2-3: Gmsh's last two swapped.
  c.vtkType = quadratic ? 24 : 10;
  c.vtkOrder = quadratic ? std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 9, 8} : identity(4);
  return c;
}

std::vector<ReferenceCell> makeTable() {
  std::vector<ReferenceCell> t;
  t.push_back(quadrilateral(CellType::Quad4));
  t.push_back(quadrilateral(CellType::Quad9));
  t.push_back(hexahedron(CellType::Hex8));
  t.push_back(hexahedron(CellType::Hex20));
  t.push_back(hexahedron(CellType::Hex27));
  t.push_back(tetrahedron(false));
  t.push_back(tetrahedron(true));
  t.push_back(line(false));
  t.push_back(line(true));
  t.push_back(triangle(false));
  t.push_back(triangle(true));
  t.push_back(quadrilateral(CellType::Quad8));
  for (std::size_t i = 0; i < t.size(); ++i)
    DDC_CHECK(static_cast<std::size_t>(t[i].type) == i, "reference cell table out of enum order at " << i);
  return t;
}

}  // namespace

const ReferenceCell& referenceCell(CellType t) {
  static const std::vector<ReferenceCell> table = makeTable();
  return table.at(static_cast<std::size_t>(t));
}

int numCellNodes(CellType t) { return referenceCell(t).numNodes; }
const char* cellTypeName(CellType t) { return referenceCell(t).name; }
int cellDimension(CellType t) { return referenceCell(t).dim; }

const std::vector<CellType>& elementCellTypes() {
  static const std::vector<CellType> types = {CellType::Quad4, CellType::Quad9, CellType::Hex8, CellType::Hex20,
                                              CellType::Hex27, CellType::Tet4,  CellType::Tet10};
  return types;
}

namespace {

/// Determinant of the d x d matrix j (row-major 3 x 3 storage).
double determinant(const double j[3][3], int d) {
  if (d == 1) return j[0][0];
  if (d == 2) return j[0][0] * j[1][1] - j[0][1] * j[1][0];
  return j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1]) - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0]) +
         j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
}

/// The corner map's evaluation points of cornerJacobian() -- the centre
/// (-1), then each corner of a multilinear cell -- and there
/// dn[p][a][k] = d N_a / d xi_k of the corner map's shape functions
/// N_a = prod_m (1 + xi_m xi_a,m) / 2 (xi_a,m = +-1), computed once per cell
/// type in the order the Jacobian used to compute them at every call.
struct CornerMapWeights {
  int points = 0;
  std::array<int, 9> where{};
  double dn[9][8][3] = {};
};

CornerMapWeights buildCornerMapWeights(const ReferenceCell& c) {
  CornerMapWeights t;
  t.where[t.points++] = -1;
  for (int a = 0; a < c.numCorners; ++a) t.where[t.points++] = a;
  for (int p = 0; p < t.points; ++p) {
    const Point xi = t.where[p] < 0 ? Point{0, 0, 0} : c.nodes[t.where[p]];
    for (int a = 0; a < c.numCorners; ++a) {
      const Point& ca = c.nodes[a];
      for (int k = 0; k < c.dim; ++k) {
        double dn = 0.5 * ca[k];
        for (int m = 0; m < c.dim; ++m)
          if (m != k) dn *= 0.5 * (1.0 + xi[m] * ca[m]);
        t.dn[p][a][k] = dn;
      }
    }
  }
  return t;
}

/// The weights of a multilinear cell type (Quad*, Hex*: their corners are
/// a Quad4's or a Hex8's).
const CornerMapWeights& cornerMapWeights(const ReferenceCell& c) {
  static const CornerMapWeights quad = buildCornerMapWeights(referenceCell(CellType::Quad4));
  static const CornerMapWeights hex = buildCornerMapWeights(referenceCell(CellType::Hex8));
  return c.dim == 2 ? quad : hex;
}

/// J[i][k] = d x_i / d xi_k of the corner map at evaluation point `p` of
/// cornerMapWeights() (a simplex's affine map: the same everywhere).
void cornerMapJacobian(const ReferenceCell& c, const std::array<double, 3>* x, int p, double j[3][3]) {
  const int d = c.dim;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) j[i][k] = 0.0;
  if (c.simplex) {
    // x = x_0 + sum_k xi_k (x_{k+1} - x_0).
    for (int i = 0; i < d; ++i)
      for (int k = 0; k < d; ++k) j[i][k] = x[k + 1][i] - x[0][i];
    return;
  }
  const auto& dn = cornerMapWeights(c).dn[p];
  for (int a = 0; a < c.numCorners; ++a)
    for (int k = 0; k < d; ++k)
      for (int i = 0; i < d; ++i) j[i][k] += x[a][i] * dn[a][k];
}

}  // namespace

CornerJacobian cornerJacobian(CellType t, const std::array<double, 3>* corners) {
  const ReferenceCell& c = referenceCell(t);
  const int d = c.dim;
  DDC_CHECK(d >= 2, "cornerJacobian: " << c.name << " is not a 2-D or 3-D cell");
  double h = 0.0;
  for (int a = 0; a < c.numCorners; ++a)
    for (int b = a + 1; b < c.numCorners; ++b) {
      double s = 0.0;
      for (int i = 0; i < d; ++i) s += (corners[a][i] - corners[b][i]) * (corners[a][i] - corners[b][i]);
      h = std::max(h, std::sqrt(s));
    }
  CornerJacobian r;
  r.tolerance = 1e-12 * std::pow(h, d);
  // Evaluation points: the centre (-1), then the corners of multilinear cells.
  const int points = c.simplex ? 1 : c.numCorners + 1;
  double lowest = 0.0;
  bool first = true, degenerate = false;
  int degenerateAt = -1;
  double degenerateDet = 0.0;
  for (int p = 0; p < points; ++p) {
    const int w = p - 1;
    double j[3][3];
    cornerMapJacobian(c, corners, p, j);
    const double det = determinant(j, d);
    if (first || det < lowest) {
      lowest = det;
      r.where = w;
    }
    if (std::abs(det) <= r.tolerance && !degenerate) {
      degenerate = true;
      degenerateAt = w;
      degenerateDet = det;
    }
    first = false;
  }
  r.det = lowest;
  if (!(lowest >= -r.tolerance)) {  // also catches NaN coordinates
    r.verdict = CornerJacobian::Verdict::Inverted;
  } else if (degenerate || h == 0.0) {
    r.verdict = CornerJacobian::Verdict::Degenerate;
    r.where = degenerateAt;
    r.det = degenerateDet;
  }
  return r;
}

std::string describeCornerJacobian(CellType t, const CornerJacobian& j) {
  std::ostringstream os;
  os << (j.verdict == CornerJacobian::Verdict::Inverted ? "inverted" : "degenerate") << " (det J = " << j.det;
  if (j.where >= 0)
    os << " at corner " << j.where;
  else if (!referenceCell(t).simplex)
    os << " at the centre";
  os << " of the " << cellTypeName(t) << " corner map";
  if (j.verdict == CornerJacobian::Verdict::Degenerate)
    os << ": zero " << (cellDimension(t) == 3 ? "volume" : "area")
       << " there, e.g. coincident corners or a flat corner";
  os << "); ";
  switch (t) {
    case CellType::Hex8:
    case CellType::Hex20:
    case CellType::Hex27:
      os << "corners 0-3 must run counter-clockwise seen from corners 4-7, 4-7 above 0-3 in the same order "
            "(Gmsh node order)";
      break;
    case CellType::Tet4:
    case CellType::Tet10:
      os << "corners 0, 1, 2 must run counter-clockwise seen from corner 3 (Gmsh node order)";
      break;
    default:
      os << "corners must run counter-clockwise (Gmsh node order)";
  }
  return os.str();
}

}  // namespace ddc
