// Geometry helpers for core unit tests: isoparametric Jacobians and areas of
// Quad4 / Quad9 elements (Gmsh node order), outward normals of segments;
// in 3-D, volumes of the corner map (trilinear hexahedra, affine
// tetrahedra) and of the Hex27 isoparametric map, face normals, and the
// check that every interior face is shared by exactly two elements.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "DDC_Mesh.hpp"

namespace ddc::test {

/// 1-D Lagrange basis on the nodes -1, 1, 0 (Gmsh order for 3-node lines)
/// and its derivative.
inline void lagrange3(double x, double* n, double* dn) {
  n[0] = 0.5 * x * (x - 1.0);
  n[1] = 0.5 * x * (x + 1.0);
  n[2] = 1.0 - x * x;
  dn[0] = x - 0.5;
  dn[1] = x + 0.5;
  dn[2] = -2.0 * x;
}

/// Jacobian determinant of element e at (xi, eta).
inline double jacobianDet(const Mesh& mesh, int e, double xi, double eta) {
  const int* en = mesh.elementNodes(e);
  double j[2][2] = {{0, 0}, {0, 0}};  // j[i][k] = d x_i / d xi_k
  if (mesh.elementNumNodes(e) == 4) {
    const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    for (int a = 0; a < 4; ++a) {
      const double dxi = 0.25 * sx[a] * (1 + sy[a] * eta), deta = 0.25 * sy[a] * (1 + sx[a] * xi);
      for (int i = 0; i < 2; ++i) {
        j[i][0] += mesh.coord(en[a])[i] * dxi;
        j[i][1] += mesh.coord(en[a])[i] * deta;
      }
    }
  } else {
    // Index of each Gmsh Quad9 node in the 1-D bases (0: -1, 1: +1, 2: 0).
    const int ix[9] = {0, 1, 1, 0, 2, 1, 2, 0, 2}, iy[9] = {0, 0, 1, 1, 0, 2, 1, 2, 2};
    double nx[3], dnx[3], ny[3], dny[3];
    lagrange3(xi, nx, dnx);
    lagrange3(eta, ny, dny);
    for (int a = 0; a < 9; ++a)
      for (int i = 0; i < 2; ++i) {
        j[i][0] += mesh.coord(en[a])[i] * dnx[ix[a]] * ny[iy[a]];
        j[i][1] += mesh.coord(en[a])[i] * nx[ix[a]] * dny[iy[a]];
      }
  }
  return j[0][0] * j[1][1] - j[0][1] * j[1][0];
}

/// Gauss points (3 per direction, exact for the Quad9 area of polynomial
/// degree <= 5 per direction) and the sampled minimum of det J.
inline double elementArea(const Mesh& mesh, int e, double* minDet = nullptr) {
  const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double area = 0.0, mn = 1e300;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double d = jacobianDet(mesh, e, g[a], g[b]);
      area += w[a] * w[b] * d;
      mn = std::min(mn, d);
    }
  for (double xi : {-1.0, 1.0})
    for (double eta : {-1.0, 1.0}) mn = std::min(mn, jacobianDet(mesh, e, xi, eta));
  if (minDet) *minDet = mn;
  return area;
}

/// Area-weighted centroid of body b.
inline std::array<double, 2> bodyCentroid(const Mesh& mesh, int b) {
  const Body& body = mesh.body(b);
  double a = 0, x = 0, y = 0;
  for (int e = body.firstElement; e < body.firstElement + body.numElements; ++e) {
    const double ae = elementArea(mesh, e);
    double cx = 0, cy = 0;
    for (int k = 0; k < 4; ++k) {
      cx += 0.25 * mesh.coord(mesh.elementNodes(e)[k])[0];
      cy += 0.25 * mesh.coord(mesh.elementNodes(e)[k])[1];
    }
    a += ae;
    x += ae * cx;
    y += ae * cy;
  }
  return {x / a, y / a};
}

/// Unnormalised outward normal (dy, -dx) of a segment (Segment doc).
inline std::array<double, 2> segmentNormal(const Mesh& mesh, const Segment& s) {
  const auto& p = mesh.coord(s.nodes[0]);
  const auto& q = mesh.coord(s.nodes[1]);
  return {q[1] - p[1], -(q[0] - p[0])};
}

/// Midpoint of a segment's end nodes.
inline std::array<double, 2> segmentMidpoint(const Mesh& mesh, const Segment& s) {
  const auto& p = mesh.coord(s.nodes[0]);
  const auto& q = mesh.coord(s.nodes[1]);
  return {0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])};
}


// ------------------------------------------------------------------- 3-D

using Vec3 = std::array<double, 3>;

inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double det3(const Vec3& c0, const Vec3& c1, const Vec3& c2) { return dot(c0, cross(c1, c2)); }

/// Hexahedron corner signs in Gmsh order (corners 0..3 at zeta = -1
/// counter-clockwise seen from +zeta, 4..7 above them).
constexpr int kHexSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

/// Position of 3-D element e's corner map at reference point xi: trilinear
/// in [-1,1]^3 for hexahedra, affine in the unit tetrahedron for tetrahedra.
inline Vec3 cornerMap(const Mesh& mesh, int e, const Vec3& xi) {
  const int* en = mesh.elementNodes(e);
  Vec3 x{0, 0, 0};
  const bool tet = mesh.elementType(e) == CellType::Tet4 || mesh.elementType(e) == CellType::Tet10;
  for (int a = 0; a < (tet ? 4 : 8); ++a) {
    double w = 1.0;
    if (tet)
      w = a == 0 ? 1.0 - xi[0] - xi[1] - xi[2] : xi[a - 1];
    else
      for (int d = 0; d < 3; ++d) w *= 0.5 * (1.0 + kHexSign[a][d] * xi[d]);
    for (int d = 0; d < 3; ++d) x[d] += w * mesh.coord(en[a])[d];
  }
  return x;
}

/// det J of the corner map of 3-D element e at xi.
inline double cornerDet(const Mesh& mesh, int e, const Vec3& xi) {
  const int* en = mesh.elementNodes(e);
  const auto X = [&](int a) { return mesh.coord(en[a]); };
  if (mesh.elementType(e) == CellType::Tet4 || mesh.elementType(e) == CellType::Tet10)
    return det3(sub(X(1), X(0)), sub(X(2), X(0)), sub(X(3), X(0)));
  Vec3 col[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 3; ++k) {
      double dn = 0.5 * kHexSign[a][k];
      for (int m = 0; m < 3; ++m)
        if (m != k) dn *= 0.5 * (1.0 + kHexSign[a][m] * xi[m]);
      for (int d = 0; d < 3; ++d) col[k][d] += dn * X(a)[d];
    }
  return det3(col[0], col[1], col[2]);
}

/// Volume of the corner map of 3-D element e and (optionally) the smallest
/// det J sampled at its corners, its centre and the Gauss points. For a
/// hexahedron 2 Gauss points per direction integrate det J exactly (it is
/// of degree <= 2 in each variable); a tetrahedron's det J is constant.
inline double cornerVolume(const Mesh& mesh, int e, double* minDet = nullptr) {
  double v = 0.0, mn = 1e300;
  if (mesh.elementType(e) == CellType::Tet4 || mesh.elementType(e) == CellType::Tet10) {
    mn = cornerDet(mesh, e, {0, 0, 0});
    v = mn / 6.0;
  } else {
    const double g = 1.0 / std::sqrt(3.0);
    for (int a = 0; a < 8; ++a) {
      const Vec3 gp{kHexSign[a][0] * g, kHexSign[a][1] * g, kHexSign[a][2] * g};
      const double d = cornerDet(mesh, e, gp);
      v += d;
      mn = std::min({mn, d, cornerDet(mesh, e, {1.0 * kHexSign[a][0], 1.0 * kHexSign[a][1], 1.0 * kHexSign[a][2]})});
    }
    mn = std::min(mn, cornerDet(mesh, e, {0, 0, 0}));
  }
  if (minDet) *minDet = mn;
  return v;
}

/// Volume of a Hex27 element through its isoparametric (triquadratic) map,
/// 3 Gauss points per direction. Node a's 1-D basis index per direction
/// follows from its reference coordinate (-1 -> 0, 1 -> 1, 0 -> 2).
inline double hex27Volume(const Mesh& mesh, int e) {
  const auto& ref = referenceCell(CellType::Hex27);
  const int* en = mesh.elementNodes(e);
  const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  const auto basisIndex = [](double r) { return r < -0.5 ? 0 : r > 0.5 ? 1 : 2; };
  double v = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const double xi[3] = {g[i], g[j], g[k]};
        double n[3][3], dn[3][3];
        for (int d = 0; d < 3; ++d) lagrange3(xi[d], n[d], dn[d]);
        Vec3 col[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        for (int a = 0; a < 27; ++a) {
          int b[3];
          for (int d = 0; d < 3; ++d) b[d] = basisIndex(ref.nodes[a][d]);
          for (int c = 0; c < 3; ++c) {
            double f = 1.0;
            for (int d = 0; d < 3; ++d) f *= d == c ? dn[d][b[d]] : n[d][b[d]];
            for (int x = 0; x < 3; ++x) col[c][x] += f * mesh.coord(en[a])[x];
          }
        }
        v += w[i] * w[j] * w[k] * det3(col[0], col[1], col[2]);
      }
  return v;
}

/// Total area (2-D: elementArea) or corner-map volume (3-D: cornerVolume)
/// of the mesh, and the smallest sampled det J in *minDet.
inline double meshMeasure(const Mesh& mesh, double* minDet) {
  double sum = 0, mn = 1e300;
  for (int e = 0; e < mesh.numElements(); ++e) {
    double d;
    sum += mesh.dim() == 3 ? cornerVolume(mesh, e, &d) : elementArea(mesh, e, &d);
    mn = std::min(mn, d);
  }
  *minDet = mn;
  return sum;
}

/// Area-weighted normal of a face's corner polygon (|n| = its area for a
/// flat face): (x2 - x0) x (x3 - x1) / 2 for quadrilaterals, (x1 - x0) x
/// (x2 - x0) / 2 for triangles. Outward if the face is oriented as the
/// Segment doc says.
inline Vec3 faceNormal(const Mesh& mesh, const Segment& s) {
  const auto X = [&](int i) { return mesh.coord(s.nodes[i]); };
  const bool tri = s.numNodes == 3 || s.numNodes == 6;
  Vec3 n = tri ? cross(sub(X(1), X(0)), sub(X(2), X(0))) : cross(sub(X(2), X(0)), sub(X(3), X(1)));
  for (double& c : n) c *= 0.5;
  return n;
}

/// Average of a face's corners.
inline Vec3 faceCentroid(const Mesh& mesh, const Segment& s) {
  const int nc = s.numNodes == 3 || s.numNodes == 6 ? 3 : 4;
  Vec3 c{0, 0, 0};
  for (int i = 0; i < nc; ++i)
    for (int d = 0; d < 3; ++d) c[d] += mesh.coord(s.nodes[i])[d] / nc;
  return c;
}

/// Average of the nodes of body b (the centroid of a box of straight cells
/// with its nodes on a uniform grid).
inline Vec3 nodeCentroid(const Mesh& mesh, int b) {
  const Body& body = mesh.body(b);
  Vec3 c{0, 0, 0};
  for (int n = body.firstNode; n < body.firstNode + body.numNodes; ++n)
    for (int d = 0; d < 3; ++d) c[d] += mesh.coord(n)[d] / body.numNodes;
  return c;
}

/// How many element faces share each face (by Mesh::facetKey): 1 on the
/// boundary, 2 inside a conforming mesh. Returns the number of boundary
/// faces and sets *maxShare to the largest count and *interior to the
/// number of faces shared by two.
inline int countBoundaryFaces(const Mesh& mesh, int* maxShare, int* interior) {
  std::map<std::vector<int>, int> count;
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int f = 0; f < mesh.elementNumFacets(e); ++f) ++count[mesh.facetKey(e, f)];
  int boundary = 0;
  *maxShare = 0;
  *interior = 0;
  for (const auto& kv : count) {
    boundary += kv.second == 1;
    *interior += kv.second == 2;
    *maxShare = std::max(*maxShare, kv.second);
  }
  return boundary;
}

}  // namespace ddc::test
