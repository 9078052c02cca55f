// Conventional node-to-surface element on curved facets (see
// DDC_NodeToSurface.hpp for the geometry and the linearisation).
#include "DDC_NodeToSurface.hpp"

#include <Sacado.hpp>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "DDC_Friction.hpp"
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

namespace {

/// The nodal positions x as AD variables (slave first) and ξ̄(x) by one
/// Newton step from the converged ξ̄: exact first derivatives (the file
/// comment of DDC_NodeToSurface.hpp).
void projectionOfPositions(CellType facet_, int dim_, int numNodes_, const Eigen::MatrixXd& x,
                           const FacetProjection& pr, std::vector<Fad>& xnF, Fad xiF[2]) {
  const int nd = dim_ * numNodes_, pd = referenceCell(facet_).dim, m = numNodes_ - 1;
  xnF.assign(size_t(m) * dim_, Fad());
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
  if (pd == 1) {
    xiF[0] = pr.xi[0] - fF[0] / J[0][0];
    xiF[1] = 0.0;
  } else {
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    xiF[0] = pr.xi[0] - (J[1][1] * fF[0] - J[0][1] * fF[1]) / det;
    xiF[1] = pr.xi[1] - (J[0][0] * fF[1] - J[1][0] * fF[0]) / det;
  }
}

/// The gap and the slip of the conventional element at ξ (DDC_Friction.hpp)
/// from the evaluated facet point p: q[0] = g_N = n·(x_s − x(ξ)), q[1 + α]
/// = u_t,α = τ_α·[(x_s − x_s⁰) − Σ N_i(ξ)(x_i − x_i⁰)], with τ_1 = a_1/|a_1|
/// and, in 3-D, τ_2 = n × τ_1 (the basis follows the facet); tau gets τ.
/// \param x0 step-start positions, slave first (numNodes x dim)
template <class T>
void gapAndSlip(int dim, const FacetPoint<T>& p, const std::vector<T>& xn, const T* xs, const Eigen::MatrixXd& x0,
                T q[3], T tau[2][3]) {
  const int m = int(p.N.size());
  q[0] = 0.0;
  for (int k = 0; k < dim; ++k) q[0] += p.n[k] * (xs[k] - p.x[k]);
  T len = 0.0;
  for (int k = 0; k < dim; ++k) len += p.a[0][k] * p.a[0][k];
  len = std::sqrt(len);
  for (int k = 0; k < 3; ++k) tau[0][k] = k < dim ? T(p.a[0][k] / len) : T(0.0), tau[1][k] = 0.0;
  if (dim == 3)
    for (int k = 0; k < 3; ++k)
      tau[1][k] = p.n[(k + 1) % 3] * tau[0][(k + 2) % 3] - p.n[(k + 2) % 3] * tau[0][(k + 1) % 3];
  for (int al = 0; al < dim - 1; ++al) {
    q[1 + al] = 0.0;
    for (int k = 0; k < dim; ++k) {
      T rel = xs[k] - x0(0, k);
      for (int i = 0; i < m; ++i) rel -= p.N[i] * (xn[size_t(i) * dim + k] - x0(i + 1, k));
      q[1 + al] += tau[al][k] * rel;
    }
  }
}

using Fad2 = Sacado::Fad::DFad<Fad>;

/// The frictional conventional element (DDC_Friction.hpp): residual and
/// exact tangent of Π = λ_n g_N + λ_t·u_t on [u, λ_n, λ_t], with the
/// tangential rows of the stick or slip state. Second derivatives through
/// the projection by nested AD: the outer level differentiates in (x, ξ)
/// independently, the inner one in x along ξ = ξ̄(x) (projectionOfPositions(),
/// exact first derivatives); the gradient dq/dx = ∂q/∂x − ∂q/∂ξ J⁻¹ ∂f/∂x
/// (implicit function of the stationarity f = 0) is then an inner-level
/// quantity whose derivatives are the exact Hessian.
void frictionalContact(CellType facet, int dim, int numNodes, const Eigen::MatrixXd& x, const Eigen::MatrixXd& X,
                       const FacetProjection& pr, const Fad xiF[2], const ContactPairState& state, unsigned what,
                       ElementResult& out) {
  const int nd = dim * numNodes, pd = referenceCell(facet).dim, m = numNodes - 1, nt = dim - 1, nz = nd + pd;
  std::vector<Fad2> xn2(size_t(m) * dim);
  Fad2 xs2[3], xi2[2], f[2], q[3], tau[2][3];
  for (int k = 0; k < dim; ++k) xs2[k] = Fad2(nz, k, Fad(nd, k, x(0, k)));
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < dim; ++k)
      xn2[size_t(i) * dim + k] = Fad2(nz, (i + 1) * dim + k, Fad(nd, (i + 1) * dim + k, x(i + 1, k)));
  for (int al = 0; al < pd; ++al) xi2[al] = Fad2(nz, nd + al, xiF[al]);
  xi2[1] = pd == 1 ? Fad2(0.0) : xi2[1];
  FacetPoint<Fad2> p;
  evaluate(facet, dim, xn2, xi2, p);
  const FrictionPairState& fr = state.friction;
  const Eigen::MatrixXd x0 = fr.stepStart.size() ? Eigen::MatrixXd(X + fr.stepStart) : X;
  gapAndSlip(dim, p, xn2, xs2, x0, q, tau);
  for (int be = 0; be < pd; ++be) {
    f[be] = 0.0;
    for (int k = 0; k < dim; ++k) f[be] -= (xs2[k] - p.x[k]) * p.a[be][k];
  }
  // dξ/dx = −J⁻¹ ∂f/∂x, J = ∂f/∂ξ (inner-level values).
  Fad Ji[2][2];
  if (pd == 1) {
    Ji[0][0] = 1.0 / f[0].dx(nd);
  } else {
    const Fad a = f[0].dx(nd), b = f[0].dx(nd + 1), c = f[1].dx(nd), d = f[1].dx(nd + 1);
    const Fad det = a * d - b * c;
    Ji[0][0] = d / det, Ji[0][1] = -b / det, Ji[1][0] = -c / det, Ji[1][1] = a / det;
  }
  std::vector<Fad> G(size_t(1 + nt) * nd);
  for (int k = 0; k < nd; ++k) {
    Fad dxi[2];
    for (int al = 0; al < pd; ++al) {
      dxi[al] = 0.0;
      for (int be = 0; be < pd; ++be) dxi[al] -= Ji[al][be] * f[be].dx(k);
    }
    for (int r = 0; r <= nt; ++r) {
      Fad g = q[r].dx(k);
      for (int al = 0; al < pd; ++al) g += q[r].dx(nd + al) * dxi[al];
      G[size_t(r) * nd + k] = g;
    }
  }
  double lam[3] = {state.multiplier, fr.tangential[0], fr.tangential[1]}, ut[2] = {0.0, 0.0};
  for (int al = 0; al < nt; ++al) ut[al] = q[1 + al].val().val();
  const FrictionRows rows = frictionRows(nt, ut, lam[0], lam + 1, fr);
  const int n = nd + 1 + nt;
  if (what & kEnergy) out.energy = lam[0] * q[0].val().val() + lam[1] * ut[0] + lam[2] * ut[1];
  if (what & kResidual) {
    out.residual.setZero(n);
    for (int a = 0; a < nd; ++a)
      for (int r = 0; r <= nt; ++r) out.residual[a] += lam[r] * G[size_t(r) * nd + a].val();
    out.residual[nd] = q[0].val().val();
    out.residual.tail(nt) = rows.residual;
  }
  if (what & kTangent) {
    out.tangent.setZero(n, n);
    for (int a = 0; a < nd; ++a) {
      for (int b = 0; b < nd; ++b)
        for (int r = 0; r <= nt; ++r) out.tangent(a, b) += lam[r] * G[size_t(r) * nd + a].dx(b);
      for (int r = 0; r <= nt; ++r) out.tangent(a, nd + r) = G[size_t(r) * nd + a].val();
      out.tangent(nd, a) = G[a].val();
      for (int al = 0; al < nt; ++al)
        for (int be = 0; be < nt; ++be)
          out.tangent(nd + 1 + al, a) += rows.slipDerivative(al, be) * G[size_t(1 + be) * nd + a].val();
    }
    out.tangent.block(nd + 1, nd, nt, 1) = rows.lambdaNDerivative;
    out.tangent.block(nd + 1, nd + 1, nt, nt) = rows.lambdaTDerivative;
  }
}

}  // namespace

std::array<double, 2> conventionalSlip(CellType facet, const Eigen::MatrixXd& x, const Eigen::MatrixXd& x0,
                                       const std::array<double, 2>& xi, std::array<Eigen::Vector3d, 2>* basis) {
  const int dim = facetSpaceDimension(facet), m = referenceCell(facet).numNodes;
  std::vector<double> xn(size_t(m) * dim);
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < dim; ++k) xn[size_t(i) * dim + k] = x(i + 1, k);
  double xs[3] = {x(0, 0), x(0, 1), dim == 3 ? x(0, 2) : 0.0}, q[3], tau[2][3];
  FacetPoint<double> p;
  evaluate(facet, dim, xn, xi.data(), p);
  gapAndSlip(dim, p, xn, xs, x0, q, tau);
  if (basis)
    for (int al = 0; al < 2; ++al) (*basis)[al] = Eigen::Vector3d(tau[al][0], tau[al][1], tau[al][2]);
  return {q[1], dim == 3 ? q[2] : 0.0};
}

void NodeToSurfaceElement::computeContact(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u,
                                          const ContactPairState& state, unsigned what, ElementResult& out) const {
  const int nd = dim_ * numNodes_;  // displacement DOFs
  const double lambda = state.multiplier;
  if (!state.active) {
    const int nm = state.numMultipliers(dim_);
    releasedContribution(nd + nm, state.multipliers().data(), nm, what, out);
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
  Fad xiF[2];
  std::vector<Fad> xnF;
  projectionOfPositions(facet_, dim_, numNodes_, x, pr, xnF, xiF);
  if (state.friction.frictional()) return frictionalContact(facet_, dim_, numNodes_, x, X, pr, xiF, state, what, out);
  const int m = numNodes_ - 1;
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
