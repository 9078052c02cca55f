// Conventional node-to-surface element on curved facets (see
// DDC_NodeToSurface.hpp for the geometry and the linearisation).
#include "DDC_NodeToSurface.hpp"

#include <Sacado.hpp>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "DDC_ShapeFunctions.hpp"

namespace ddc {

namespace {

using Fad = Sacado::Fad::DFad<double>;

/// Position, tangents and unit normal of a facet at ξ (all in scalar T).
template <class T>
struct FacetPoint {
  T x[3], a[2][3], n[3];
  std::vector<T> N;
};

/// Evaluate the facet with node positions xn (m x dim, row-major) at ξ.
/// \return false if the tangent (2-D) or the tangent area (3-D) vanishes.
template <class T>
bool evaluate(CellType facet, int dim, const std::vector<T>& xn, const T* xi, FacetPoint<T>& p) {
  const ReferenceCell& c = referenceCell(facet);
  const int m = c.numNodes, pd = c.dim;
  p.N.assign(m, T(0.0));
  std::vector<T> dN(size_t(m) * pd, T(0.0));
  shapeFunctionsT<T>(facet, xi, p.N.data(), dN.data());
  for (int k = 0; k < 3; ++k) {
    p.x[k] = 0.0, p.n[k] = 0.0;
    p.a[0][k] = 0.0, p.a[1][k] = 0.0;
  }
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < dim; ++k) {
      p.x[k] += p.N[i] * xn[size_t(i) * dim + k];
      for (int al = 0; al < pd; ++al) p.a[al][k] += dN[size_t(i) * pd + al] * xn[size_t(i) * dim + k];
    }
  if (dim == 2) {
    const T len = std::sqrt(p.a[0][0] * p.a[0][0] + p.a[0][1] * p.a[0][1]);
    if (!(Sacado::ScalarValue<T>::eval(len) > 0.0)) return false;
    p.n[0] = p.a[0][1] / len, p.n[1] = -p.a[0][0] / len;
  } else {
    T cr[3] = {p.a[0][1] * p.a[1][2] - p.a[0][2] * p.a[1][1], p.a[0][2] * p.a[1][0] - p.a[0][0] * p.a[1][2],
               p.a[0][0] * p.a[1][1] - p.a[0][1] * p.a[1][0]};
    const T area = std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
    if (!(Sacado::ScalarValue<T>::eval(area) > 0.0)) return false;
    for (int k = 0; k < 3; ++k) p.n[k] = cr[k] / area;
  }
  return true;
}

/// f_α(ξ) = −(x_s − x(ξ))·a_α(ξ): zero at the closest point.
template <class T>
void stationarity(CellType facet, int dim, const std::vector<T>& xn, const T* xs, const T* xi, T f[2]) {
  FacetPoint<T> p;
  evaluate(facet, dim, xn, xi, p);
  const int pd = referenceCell(facet).dim;
  for (int al = 0; al < pd; ++al) {
    f[al] = 0.0;
    for (int k = 0; k < dim; ++k) f[al] -= (xs[k] - p.x[k]) * p.a[al][k];
  }
}

/// f and J = ∂f/∂ξ at ξ (doubles), J by AD in ξ.
void stationarityAndJacobian(CellType facet, int dim, const std::vector<double>& xn, const double* xs,
                             const double* xi, double f[2], double J[2][2]) {
  const int pd = referenceCell(facet).dim;
  std::vector<Fad> xnF(xn.begin(), xn.end());
  Fad xsF[3], xiF[2], fF[2];
  for (int k = 0; k < dim; ++k) xsF[k] = xs[k];
  for (int al = 0; al < pd; ++al) xiF[al] = Fad(pd, al, xi[al]);
  stationarity(facet, dim, xnF, xsF, xiF, fF);
  for (int al = 0; al < pd; ++al) {
    f[al] = fF[al].val();
    for (int be = 0; be < pd; ++be) J[al][be] = fF[al].dx(be);
  }
}

bool insideReference(CellType facet, const double* xi) {
  const double e = kEndTolerance;
  switch (facet) {
    case CellType::Line2:
    case CellType::Line3:
      return xi[0] >= -1 - e && xi[0] <= 1 + e;
    case CellType::Tri3:
    case CellType::Tri6:
      return xi[0] >= -e && xi[1] >= -e && xi[0] + xi[1] <= 1 + e;
    default:
      return std::abs(xi[0]) <= 1 + e && std::abs(xi[1]) <= 1 + e;
  }
}

}  // namespace

int facetSpaceDimension(CellType facet) {
  switch (facet) {
    case CellType::Line2:
    case CellType::Line3:
      return 2;
    case CellType::Tri3:
    case CellType::Tri6:
    case CellType::Quad4:
    case CellType::Quad8:
    case CellType::Quad9:
      return 3;
    default:
      throw std::invalid_argument(std::string("node-to-surface contact: ") + cellTypeName(facet) +
                                  " is not a facet cell type (Line2, Line3, Tri3, Tri6, Quad4, Quad8, Quad9)");
  }
}

FacetProjection projectOntoFacet(CellType facet, const Eigen::MatrixXd& x, const Eigen::VectorXd& xs,
                                 const std::array<double, 2>* start) {
  const int dim = facetSpaceDimension(facet);
  const ReferenceCell& c = referenceCell(facet);
  const int pd = c.dim;
  std::vector<double> xn(size_t(c.numNodes) * dim);
  for (int i = 0; i < c.numNodes; ++i)
    for (int k = 0; k < dim; ++k) xn[size_t(i) * dim + k] = x(i, k);
  double xi[2] = {0.0, 0.0};
  if (start) {
    xi[0] = (*start)[0], xi[1] = (*start)[1];
  } else if (c.simplex) {
    xi[0] = xi[1] = 1.0 / 3.0;
  }
  FacetProjection out;
  for (int it = 0; it < 30; ++it) {
    double f[2], J[2][2];
    stationarityAndJacobian(facet, dim, xn, xs.data(), xi, f, J);
    double d[2];
    if (pd == 1) {
      if (J[0][0] == 0.0) break;
      d[0] = f[0] / J[0][0], d[1] = 0.0;
    } else {
      const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
      if (det == 0.0) break;
      d[0] = (J[1][1] * f[0] - J[0][1] * f[1]) / det;
      d[1] = (J[0][0] * f[1] - J[1][0] * f[0]) / det;
    }
    xi[0] -= d[0], xi[1] -= d[1];
    out.iterations = it + 1;
    if (std::abs(d[0]) + std::abs(d[1]) <= 1e-13) {
      out.converged = true;
      break;
    }
  }
  FacetPoint<double> p;
  const bool ok = evaluate(facet, dim, xn, xi, p);
  out.converged = out.converged && ok;
  out.xi = {xi[0], xi[1]};
  for (int k = 0; k < dim; ++k) out.normal[k] = p.n[k], out.point[k] = p.x[k];
  out.gap = 0.0;
  for (int k = 0; k < dim; ++k) out.gap += p.n[k] * (xs[k] - p.x[k]);
  out.inside = insideReference(facet, xi);
  return out;
}

bool facetPointAndNormal(CellType facet, const Eigen::MatrixXd& x, const std::array<double, 2>& xi,
                         Eigen::Vector3d& point, Eigen::Vector3d& normal) {
  const int dim = facetSpaceDimension(facet);
  const int m = referenceCell(facet).numNodes;
  std::vector<double> xn(size_t(m) * dim);
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < dim; ++k) xn[size_t(i) * dim + k] = x(i, k);
  FacetPoint<double> p;
  const bool ok = evaluate(facet, dim, xn, xi.data(), p);
  point.setZero(), normal.setZero();
  for (int k = 0; k < dim; ++k) point[k] = p.x[k], normal[k] = p.n[k];
  return ok;
}

NodeToSurfaceElement::NodeToSurfaceElement(CellType facet)
    : facet_(facet), dim_(facetSpaceDimension(facet)), numNodes_(1 + referenceCell(facet).numNodes) {}

FacetProjection NodeToSurfaceElement::project(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u) const {
  const Eigen::MatrixXd x = X + u;
  return projectOntoFacet(facet_, x.bottomRows(numNodes_ - 1), x.row(0).transpose());
}

void NodeToSurfaceElement::computeContact(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u,
                                          const ContactPairState& state, unsigned what, ElementResult& out) const {
  const int nd = dim_ * numNodes_;  // displacement DOFs
  const double lambda = state.multiplier;
  if (!state.active) {
    releasedContribution(nd + 1, lambda, what, out);
    return;
  }
  const Eigen::MatrixXd x = X + u;
  const FacetProjection pr = projectOntoFacet(facet_, x.bottomRows(numNodes_ - 1), x.row(0).transpose());
  if (!pr.converged) {
    std::ostringstream os;
    os << "node-to-surface contact on a " << cellTypeName(facet_)
       << " facet: the closest-point projection did not converge (degenerate or strongly curved facet)";
    throw InadmissibleDeformation(os.str());
  }
  const int pd = referenceCell(facet_).dim, m = numNodes_ - 1;
  // Nodal positions as AD variables (slave first), ξ̄(x) by one Newton step.
  std::vector<Fad> xnF(size_t(m) * dim_);
  Fad xsF[3];
  for (int k = 0; k < dim_; ++k) xsF[k] = Fad(nd, k, x(0, k));
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < dim_; ++k) xnF[size_t(i) * dim_ + k] = Fad(nd, (i + 1) * dim_ + k, x(i + 1, k));
  std::vector<double> xn(size_t(m) * dim_);
  for (size_t q = 0; q < xn.size(); ++q) xn[q] = xnF[q].val();
  double f[2], J[2][2];
  const Eigen::VectorXd xs = x.row(0).transpose();
  stationarityAndJacobian(facet_, dim_, xn, xs.data(), pr.xi.data(), f, J);
  Fad xiConst[2] = {Fad(pr.xi[0]), Fad(pr.xi[1])}, fF[2];
  stationarity(facet_, dim_, xnF, xsF, xiConst, fF);
  Fad xiF[2];
  if (pd == 1) {
    xiF[0] = pr.xi[0] - fF[0] / J[0][0];
    xiF[1] = 0.0;
  } else {
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    xiF[0] = pr.xi[0] - (J[1][1] * fF[0] - J[0][1] * fF[1]) / det;
    xiF[1] = pr.xi[1] - (J[0][0] * fF[1] - J[1][0] * fF[0]) / det;
  }
  FacetPoint<Fad> p;
  evaluate(facet_, dim_, xnF, xiF, p);
  // G = ∂g_N/∂u = [n; −N_i n], differentiated once more for the tangent.
  std::vector<Fad> G(nd);
  for (int k = 0; k < dim_; ++k) G[k] = p.n[k];
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < dim_; ++k) G[(i + 1) * dim_ + k] = -p.N[i] * p.n[k];
  const double g = pr.gap;
  if (what & kEnergy) out.energy = lambda * g;
  if (what & kResidual) {
    out.residual.resize(nd + 1);
    for (int a = 0; a < nd; ++a) out.residual[a] = lambda * G[a].val();
    out.residual[nd] = g;
  }
  if (what & kTangent) {
    out.tangent.setZero(nd + 1, nd + 1);
    for (int a = 0; a < nd; ++a) {
      for (int b = 0; b < nd; ++b) out.tangent(a, b) = lambda * (G[a].hasFastAccess() ? G[a].fastAccessDx(b) : 0.0);
      out.tangent(a, nd) = out.tangent(nd, a) = G[a].val();
    }
  }
}

}  // namespace ddc
