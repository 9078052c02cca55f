// Geometry helpers for core unit tests: isoparametric Jacobians and areas of
// Quad4 / Quad9 elements (Gmsh node order), outward normals of segments.
#pragma once

#include <array>
#include <cmath>
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

}  // namespace ddc::test
