#include "DDC_ShapeFunctions.hpp"

#include <Sacado.hpp>
#include <cmath>
#include <stdexcept>

namespace ddc {

namespace {

// The families below are templates on the scalar T (double, or a Sacado
// forward-AD type for derivatives with respect to xi, e.g. the contact
// projection). N: numNodes values; dN: numNodes x dim, row-major. Either may
// be null.

/// 1-D Lagrange polynomials of order 1 (nodes -1, 1) or 2 (nodes -1, 0, 1),
/// and their derivatives, at x; index i is the node's position in that list.
template <class T>
void lagrange1d(int order, const T& x, T L[3], T dL[3]) {
  if (order == 1) {
    L[0] = 0.5 * (1 - x), L[1] = 0.5 * (1 + x);
    dL[0] = -0.5, dL[1] = 0.5;
  } else {
    L[0] = 0.5 * x * (x - 1), L[1] = 1 - x * x, L[2] = 0.5 * x * (x + 1);
    dL[0] = x - 0.5, dL[1] = -2 * x, dL[2] = x + 0.5;
  }
}

/// Tensor-product Lagrange: N_a = prod_m L_{i_m(a)}(xi_m), with the 1-D
/// node index i_m(a) read from the node's reference coordinate.
template <class T>
void lagrangeBox(const ReferenceCell& c, int order, const T* xi, T* N, T* dN) {
  T L[3][3], dL[3][3];
  for (int m = 0; m < c.dim; ++m) lagrange1d(order, xi[m], L[m], dL[m]);
  for (int a = 0; a < c.numNodes; ++a) {
    int idx[3];
    // Coordinate -1, 0, +1 -> index 0, 1, 2 (order 2) or -1, +1 -> 0, 1.
    for (int m = 0; m < c.dim; ++m) idx[m] = static_cast<int>(std::lround((c.nodes[a][m] + 1) * 0.5 * order));
    if (N) {
      T p = 1.0;
      for (int m = 0; m < c.dim; ++m) p *= L[m][idx[m]];
      N[a] = p;
    }
    if (dN)
      for (int k = 0; k < c.dim; ++k) {
        T p = 1.0;
        for (int m = 0; m < c.dim; ++m) p *= m == k ? dL[m][idx[m]] : L[m][idx[m]];
        dN[a * c.dim + k] = p;
      }
  }
}

/// Serendipity (Quad8, Hex20): corner and mid-edge nodes only.
template <class T>
void serendipity(const ReferenceCell& c, const T* xi, T* N, T* dN) {
  const int d = c.dim;
  for (int a = 0; a < c.numNodes; ++a) {
    const auto& xa = c.nodes[a];
    T f[3];  // 1 + xa_m xi_m (unused in the direction of a mid-edge node)
    for (int m = 0; m < d; ++m) f[m] = 1 + xa[m] * xi[m];
    auto productExcept = [&](int skip1, int skip2) {
      T p = 1.0;
      for (int m = 0; m < d; ++m)
        if (m != skip1 && m != skip2) p *= f[m];
      return p;
    };
    int k = -1;  // the direction in which a mid-edge node sits at 0
    for (int m = 0; m < d; ++m)
      if (xa[m] == 0) k = m;
    if (k < 0) {
      const double scale = std::ldexp(1.0, -d);
      T s = -(d - 1);
      for (int m = 0; m < d; ++m) s += xa[m] * xi[m];
      if (N) N[a] = scale * productExcept(-1, -1) * s;
      if (dN)
        for (int j = 0; j < d; ++j)
          dN[a * d + j] = scale * xa[j] * productExcept(j, -1) * s + scale * productExcept(-1, -1) * xa[j];
    } else {
      const double scale = std::ldexp(1.0, 1 - d);
      const T bubble = 1 - xi[k] * xi[k];
      if (N) N[a] = scale * bubble * productExcept(k, -1);
      if (dN)
        for (int j = 0; j < d; ++j)
          dN[a * d + j] = j == k ? T(scale * (-2 * xi[k]) * productExcept(k, -1))
                                 : T(scale * bubble * xa[j] * productExcept(k, j));
    }
  }
}

/// Simplex (Tri3/Tri6/Tet4/Tet10) in barycentric coordinates lambda_0 =
/// 1 - sum xi, lambda_{m+1} = xi_m; quadratic cells take their mid-edge
/// nodes from the reference cell's edges.
template <class T>
void simplex(const ReferenceCell& c, const T* xi, T* N, T* dN) {
  const int d = c.dim;
  T lam[4];
  Eigen::Matrix<double, 4, 3> dlam = Eigen::Matrix<double, 4, 3>::Zero();
  lam[0] = 1;
  for (int m = 0; m < d; ++m) {
    lam[0] -= xi[m];
    lam[m + 1] = xi[m];
    dlam(0, m) = -1;
    dlam(m + 1, m) = 1;
  }
  const bool quadratic = c.numNodes > c.numCorners;
  for (int a = 0; a < c.numCorners; ++a) {
    if (N) N[a] = quadratic ? T(lam[a] * (2 * lam[a] - 1)) : lam[a];
    if (dN)
      for (int k = 0; k < d; ++k) dN[a * d + k] = quadratic ? T((4 * lam[a] - 1) * dlam(a, k)) : T(dlam(a, k));
  }
  if (!quadratic) return;
  for (const auto& e : c.edges) {
    const int s = e.start, t = e.end;
    if (N) N[e.middle] = 4 * lam[s] * lam[t];
    if (dN)
      for (int k = 0; k < d; ++k) dN[e.middle * d + k] = 4 * (dlam(s, k) * lam[t] + lam[s] * dlam(t, k));
  }
}

/// Tensor-product Gauss-Legendre rule with P = 2 or 3 points per direction,
/// first direction fastest.
QuadratureRule gaussBox(int dim, int P) {
  static constexpr double p2[2] = {-0.57735026918962576451, 0.57735026918962576451};
  static constexpr double w2[2] = {1.0, 1.0};
  // +-sqrt(3/5), 0 with weights 5/9, 8/9, 5/9.
  static constexpr double p3[3] = {-0.77459666924148337704, 0.0, 0.77459666924148337704};
  static constexpr double w3[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double* p = P == 2 ? p2 : p3;
  const double* w = P == 2 ? w2 : w3;
  QuadratureRule r;
  r.degree = 2 * P - 1;
  r.name = std::to_string(P);
  for (int m = 1; m < dim; ++m) r.name += "x" + std::to_string(P);
  r.name += " Gauss";
  int total = 1;
  for (int m = 0; m < dim; ++m) total *= P;
  for (int q = 0; q < total; ++q) {
    std::array<double, 3> x{0, 0, 0};
    double weight = 1.0;
    for (int m = 0, rest = q; m < dim; ++m, rest /= P) {
      x[m] = p[rest % P];
      weight *= w[rest % P];
    }
    r.points.push_back(x);
    r.weights.push_back(weight);
  }
  return r;
}

QuadratureRule tetRule(int points) {
  QuadratureRule r;
  if (points == 1) {
    r.points = {{0.25, 0.25, 0.25}};
    r.weights = {1.0 / 6.0};
    r.degree = 1;
    r.name = "1-point (centroid)";
  } else {
    // Hammer, Marlowe & Stroud: a = (5 - sqrt 5)/20, b = (5 + 3 sqrt 5)/20.
    const double a = (5 - std::sqrt(5.0)) / 20, b = (5 + 3 * std::sqrt(5.0)) / 20;
    r.points = {{a, a, a}, {b, a, a}, {a, b, a}, {a, a, b}};
    r.weights = {1.0 / 24.0, 1.0 / 24.0, 1.0 / 24.0, 1.0 / 24.0};
    r.degree = 2;
    r.name = "4-point degree 2";
  }
  return r;
}

/// Conical product rule on the reference tetrahedron (vertices 0, e1, e2,
/// e3): the Gauss-Legendre rule of P points per direction on the unit cube
/// mapped by ξ1 = a, ξ2 = b (1 − a), ξ3 = c (1 − a)(1 − b), whose Jacobian
/// (1 − a)² (1 − b) is absorbed in the weights. A polynomial of total degree
/// p becomes one of degree ≤ p + 2 per direction: exact for p ≤ 2P − 3.
QuadratureRule collapsedTetRule(int P) {
  // Gauss-Legendre on [-1, 1]: P = 3 and P = 4.
  static constexpr double x3[3] = {-0.77459666924148337704, 0.0, 0.77459666924148337704};
  static constexpr double w3[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  static constexpr double x4[4] = {-0.86113631159405257522, -0.33998104358485626480, 0.33998104358485626480,
                                   0.86113631159405257522};
  static constexpr double w4[4] = {0.34785484513745385737, 0.65214515486254614263, 0.65214515486254614263,
                                   0.34785484513745385737};
  const double* x = P == 3 ? x3 : x4;
  const double* w = P == 3 ? w3 : w4;
  QuadratureRule r;
  r.degree = 2 * P - 3;
  r.name = std::to_string(P * P * P) + "-point collapsed Gauss (degree " + std::to_string(r.degree) + ")";
  for (int i = 0; i < P; ++i)
    for (int j = 0; j < P; ++j)
      for (int k = 0; k < P; ++k) {
        const double a = 0.5 * (1 + x[i]), b = 0.5 * (1 + x[j]), c = 0.5 * (1 + x[k]);
        r.points.push_back({a, b * (1 - a), c * (1 - a) * (1 - b)});
        r.weights.push_back(0.125 * w[i] * w[j] * w[k] * (1 - a) * (1 - a) * (1 - b));
      }
  return r;
}

/// Triangle rules on the reference triangle (area 1/2): 3 points of degree
/// 2 (Strang & Fix 1973) and 6 points of degree 4 (Dunavant 1985).
QuadratureRule triRule(int points) {
  QuadratureRule r;
  if (points == 3) {
    r.points = {{1.0 / 6, 1.0 / 6, 0}, {2.0 / 3, 1.0 / 6, 0}, {1.0 / 6, 2.0 / 3, 0}};
    r.weights = {1.0 / 6, 1.0 / 6, 1.0 / 6};
    r.degree = 2;
    r.name = "3-point degree 2";
  } else {
    const double a = 0.445948490915965, wa = 0.223381589678011 / 2;
    const double b = 0.091576213509771, wb = 0.109951743655322 / 2;
    r.points = {{a, a, 0}, {1 - 2 * a, a, 0}, {a, 1 - 2 * a, 0}, {b, b, 0}, {1 - 2 * b, b, 0}, {b, 1 - 2 * b, 0}};
    r.weights = {wa, wa, wa, wb, wb, wb};
    r.degree = 4;
    r.name = "6-point degree 4";
  }
  return r;
}

}  // namespace

const QuadratureRule& facetQuadratureRule(CellType facet) {
  static const QuadratureRule line3 = gaussBox(1, 3), quad2x2 = gaussBox(2, 2), quad3x3 = gaussBox(2, 3),
                              tri3 = triRule(3), tri6 = triRule(6);
  switch (facet) {
    case CellType::Line2:
    case CellType::Line3:
      return line3;
    case CellType::Quad4:
      return quad2x2;
    case CellType::Quad8:
    case CellType::Quad9:
      return quad3x3;
    case CellType::Tri3:
      return tri3;
    case CellType::Tri6:
      return tri6;
    default:
      throw std::invalid_argument(std::string("facetQuadratureRule: ") + cellTypeName(facet) +
                                  " is not a facet cell type");
  }
}

template <class T>
void shapeFunctionsT(CellType cell, const T* xi, T* N, T* dN) {
  const ReferenceCell& c = referenceCell(cell);
  switch (cell) {
    case CellType::Line2:
    case CellType::Quad4:
    case CellType::Hex8:
      return lagrangeBox(c, 1, xi, N, dN);
    case CellType::Line3:
    case CellType::Quad9:
    case CellType::Hex27:
      return lagrangeBox(c, 2, xi, N, dN);
    case CellType::Quad8:
    case CellType::Hex20:
      return serendipity(c, xi, N, dN);
    case CellType::Tri3:
    case CellType::Tri6:
    case CellType::Tet4:
    case CellType::Tet10:
      return simplex(c, xi, N, dN);
  }
  throw std::invalid_argument("shapeFunctions: unknown cell type");
}

template void shapeFunctionsT<double>(CellType, const double*, double*, double*);
template void shapeFunctionsT<Sacado::Fad::DFad<double>>(CellType, const Sacado::Fad::DFad<double>*,
                                                          Sacado::Fad::DFad<double>*, Sacado::Fad::DFad<double>*);
// Nested: the second derivatives of the frictional contact element
// (DDC_NodeToSurface.cpp) through the projection.
template void shapeFunctionsT<Sacado::Fad::DFad<Sacado::Fad::DFad<double>>>(
    CellType, const Sacado::Fad::DFad<Sacado::Fad::DFad<double>>*, Sacado::Fad::DFad<Sacado::Fad::DFad<double>>*,
    Sacado::Fad::DFad<Sacado::Fad::DFad<double>>*);

void shapeFunctions(CellType cell, const std::array<double, 3>& xi, Eigen::VectorXd* N, Eigen::MatrixXd* dN) {
  const ReferenceCell& c = referenceCell(cell);
  if (N) N->resize(c.numNodes);
  if (dN) dN->resize(c.numNodes, c.dim);
  // dN is column-major in Eigen; the families write row-major.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> d;
  if (dN) d.resize(c.numNodes, c.dim);
  shapeFunctionsT<double>(cell, xi.data(), N ? N->data() : nullptr, dN ? d.data() : nullptr);
  if (dN) *dN = d;
}

const QuadratureRule& quadratureRule(CellType cell) {
  static const QuadratureRule gauss2x2 = gaussBox(2, 2), gauss3x3 = gaussBox(2, 3), gauss2x2x2 = gaussBox(3, 2),
                              gauss3x3x3 = gaussBox(3, 3), tet1 = tetRule(1), tet4 = tetRule(4);
  switch (cell) {
    case CellType::Quad4:
      return gauss2x2;
    case CellType::Quad9:
      return gauss3x3;
    case CellType::Hex8:
      return gauss2x2x2;
    case CellType::Hex20:
    case CellType::Hex27:
      return gauss3x3x3;
    case CellType::Tet4:
      return tet1;
    case CellType::Tet10:
      return tet4;
    default:
      throw std::invalid_argument(std::string("quadratureRule: ") + cellTypeName(cell) +
                                  " is not an element cell type");
  }
}

const QuadratureRule& massQuadratureRule(CellType cell) {
  static const QuadratureRule gauss2x2 = gaussBox(2, 2), gauss3x3 = gaussBox(2, 3), gauss3x3x3 = gaussBox(3, 3),
                              tet27 = collapsedTetRule(3), tet64 = collapsedTetRule(4);
  switch (cell) {
    case CellType::Quad4:
      return gauss2x2;
    case CellType::Quad9:
      return gauss3x3;
    case CellType::Hex8:
    case CellType::Hex20:
    case CellType::Hex27:
      return gauss3x3x3;
    case CellType::Tet4:
      return tet27;
    case CellType::Tet10:
      return tet64;
    default:
      throw std::invalid_argument(std::string("massQuadratureRule: ") + cellTypeName(cell) +
                                  " is not an element cell type");
  }
}

}  // namespace ddc
