// Shape functions of every cell type and the quadrature rules of the
// element cells, on the reference cells of DDC_ReferenceCell.hpp (their node
// coordinates and Gmsh node order are used here, not restated).
//
// Families (Hughes, The Finite Element Method, ch. 3; Zienkiewicz, Taylor &
// Zhu, The Finite Element Method: Its Basis and Fundamentals, ch. 6):
//   Line2, Quad4, Hex8     tensor-product Lagrange, order 1, on [-1,1]^dim
//   Line3, Quad9, Hex27    tensor-product Lagrange, order 2 (nodes -1, 0, 1)
//   Quad8, Hex20           serendipity: corner N = 2^-dim prod(1 + xi_a xi)
//                          (sum(xi_a xi) - (dim - 1)), mid-edge N = 2^(1-dim)
//                          (1 - xi_k^2) prod_{m != k}(1 + xi_a,m xi_m)
//   Tri3, Tet4             linear simplex: N_a = lambda_a (barycentric)
//   Tri6, Tet10            quadratic simplex: corners lambda_a (2 lambda_a - 1),
//                          mid-edge 4 lambda_s lambda_e
#pragma once

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "DDC_ReferenceCell.hpp"

namespace ddc {

/// Shape function values and reference gradients of a cell type at a point.
/// \param cell any cell type
/// \param xi reference coordinates (the first cellDimension(cell) are used)
/// \param N if not null: resized to numCellNodes(cell), N_a(xi)
/// \param dN if not null: resized to numCellNodes(cell) x cellDimension(cell),
///        dN_a/dxi_k
void shapeFunctions(CellType cell, const std::array<double, 3>& xi, Eigen::VectorXd* N, Eigen::MatrixXd* dN);

/// The same for a scalar type T: double or Sacado::Fad::DFad<double> (for
/// derivatives with respect to xi, e.g. of a contact projection). `xi` has
/// cellDimension(cell) entries; N (numCellNodes values) and dN
/// (numCellNodes x cellDimension, row-major) may be null.
template <class T>
void shapeFunctionsT(CellType cell, const T* xi, T* N, T* dN);

/// A quadrature rule on a reference cell: sum_q w_q f(xi_q) ~ integral of f.
struct QuadratureRule {
  std::vector<std::array<double, 3>> points;  ///< reference coordinates
  std::vector<double> weights;                ///< sum: reference volume (2^dim, or 1/6 for a tetrahedron)
  int degree;                                 ///< polynomials of this total degree are integrated exactly
  std::string name;                           ///< e.g. "3x3x3 Gauss"
};

/// The quadrature rule the continuum elements of a cell type use:
///   Quad4 2x2, Quad9 3x3, Hex8 2x2x2, Hex20 and Hex27 3x3x3 Gauss-Legendre
///   (full integration; 2x2x2 for Hex20 has spurious zero-energy modes);
///   Tet4 1 point (the centroid): F and det(dX/dxi) are constant in a
///   4-node tetrahedron, so one point is exact for any material;
///   Tet10 4 points, degree 2 (Hammer, Marlowe & Stroud 1956), exact for the
///   small-strain stiffness of a straight-edged Tet10 (a degree-2
///   integrand); Keast's 5-point degree-3 rule has a negative weight, which
///   can make a tangent indefinite, so the positive 4-point rule is the one
///   used in practice. On a curved Tet10 (mid-edge nodes off the edge
///   middles) the internal-force integrand has degree 3, so the constant-
///   stress patch test then holds only to the quadrature error.
/// Points are ordered with the first coordinate running fastest.
/// \throws std::invalid_argument for a facet cell type (Line*, Tri*, Quad8)
const QuadratureRule& quadratureRule(CellType cell);

/// The quadrature rule of the consistent mass matrix M_ab = ∫ ρ N_a N_b dV,
/// exact for it on every straight-sided (affine) element and, for Quad4 and
/// Hex8, on any bilinear / trilinear element:
///   Quad4 2x2, Quad9 3x3, Hex8, Hex20 and Hex27 3x3x3 Gauss-Legendre;
///   Tet4 and Tet10: the collapsed (Duffy) product of 3 and 4 Gauss points
///   per direction, exact for total degree 3 and 5 with positive weights
///   (Stroud 1971, conical product rules).
/// \throws std::invalid_argument for a facet cell type
const QuadratureRule& massQuadratureRule(CellType cell);

/// The quadrature rule for integrals over a facet (tractions on sides and
/// faces, sum_q w_q |dx/dxi| N_a(xi_q)):
///   Line2, Line3   3-point Gauss (exact for N |J| of a quadratic side);
///   Quad4          2x2 Gauss (exact on a flat parallelogram face);
///   Quad8, Quad9   3x3 Gauss;
///   Tri3           3 points, degree 2 (Strang & Fix 1973);
///   Tri6           6 points, degree 4 (Dunavant 1985): exact for N |J| of
///                  a curved 6-node face up to the square root in |J|.
/// \throws std::invalid_argument for a volume cell type (Hex*, Tet*).
const QuadratureRule& facetQuadratureRule(CellType facet);

}  // namespace ddc
