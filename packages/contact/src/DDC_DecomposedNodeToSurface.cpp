// Decomposed node-to-surface counterparts (see DDC_DecomposedNodeToSurface.hpp).
#include "DDC_DecomposedNodeToSurface.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "DDC_NodeToSurface.hpp"
#include "DDC_ShapeFunctions.hpp"

namespace ddc {

DecomposedSurfaceCounterpart::DecomposedSurfaceCounterpart(CellType facet, bool master)
    : facet_(facet),
      master_(master),
      dim_(facetSpaceDimension(facet)),
      numNodes_(master ? referenceCell(facet).numNodes : 1) {}

namespace {

/// The counterpart's coefficients of a frozen direction d: d on the slave,
/// −N_i(ξ^p) d on the master.
Eigen::VectorXd directionRow(CellType facet, bool master, int dim, int numNodes, const FrozenFacetProjection& frozen,
                             const Eigen::Vector3d& d) {
  Eigen::VectorXd c(dim * numNodes);
  if (!master) {
    c = d.head(dim);
    return c;
  }
  std::vector<double> N(numNodes);
  shapeFunctionsT<double>(facet, frozen.xi.data(), N.data(), nullptr);
  for (int i = 0; i < numNodes; ++i)
    for (int k = 0; k < dim; ++k) c[i * dim + k] = -N[i] * d[k];
  return c;
}

}  // namespace

Eigen::VectorXd DecomposedSurfaceCounterpart::constraintRow(const FrozenFacetProjection& frozen) const {
  const double len = frozen.normal.norm();
  if (!(std::abs(len - 1.0) <= 1e-10)) {
    std::ostringstream os;
    os << "decomposed node-to-surface " << (master_ ? "master" : "slave") << " counterpart: frozen normal n^p = ("
       << frozen.normal.transpose() << ") is not a unit vector (|n^p| = " << len
       << "); freeze it from the last converged configuration";
    throw std::invalid_argument(os.str());
  }
  return directionRow(facet_, master_, dim_, numNodes_, frozen, frozen.normal);
}

Eigen::VectorXd DecomposedSurfaceCounterpart::slipRow(const FrozenFacetProjection& frozen, int alpha) const {
  const Eigen::Vector3d& t = frozen.tangent[alpha];
  if (!(std::abs(t.norm() - 1.0) <= 1e-10 && std::abs(t.dot(frozen.normal)) <= 1e-10)) {
    std::ostringstream os;
    os << "decomposed node-to-surface " << (master_ ? "master" : "slave") << " counterpart: frozen tangent tau^p_"
       << alpha + 1 << " = (" << t.transpose() << ") is not a unit vector orthogonal to n^p = ("
       << frozen.normal.transpose() << "); freeze it with the normal (tangentBasis())";
    throw std::invalid_argument(os.str());
  }
  return directionRow(facet_, master_, dim_, numNodes_, frozen, t);
}

double DecomposedSurfaceCounterpart::gapPart(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u,
                                             const FrozenFacetProjection& frozen) const {
  const Eigen::VectorXd c = constraintRow(frozen);
  double g = 0.0;
  for (int i = 0; i < numNodes_; ++i)
    for (int k = 0; k < dim_; ++k) g += c[i * dim_ + k] * (X(i, k) + u(i, k));
  return g;
}

void DecomposedSurfaceCounterpart::computeContact(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u,
                                                  const FrozenFacetProjection& frozen, const ContactPairState& state,
                                                  unsigned what, ElementResult& out) const {
  const int nd = dim_ * numNodes_;
  const int nm = state.numMultipliers(dim_);
  const double lambda = state.multiplier;
  if (!state.active) {
    // The release term ½|λ|² lives in the slave counterpart only, so the two
    // counterparts add up to the decomposed element.
    if (!master_) return releasedContribution(nd + nm, state.multipliers().data(), nm, what, out);
    if (what & kEnergy) out.energy = 0.0;
    if (what & kResidual) out.residual.setZero(nd + nm);
    if (what & kTangent) out.tangent.setZero(nd + nm, nd + nm);
    return;
  }
  const Eigen::VectorXd c = constraintRow(frozen);
  const double g = gapPart(X, u, frozen);
  if (what & kEnergy) out.energy = lambda * g;
  if (what & kResidual) {
    out.residual.setZero(nd + nm);
    out.residual.head(nd) = lambda * c;
    out.residual[nd] = g;
  }
  if (what & kTangent) {
    out.tangent.setZero(nd + nm, nd + nm);
    out.tangent.col(nd).head(nd) = c;
    out.tangent.row(nd).head(nd) = c.transpose();
  }
  if (state.friction.frictional()) addFriction(X, u, frozen, state, what, out);
}

void DecomposedSurfaceCounterpart::addFriction(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u,
                                               const FrozenFacetProjection& frozen, const ContactPairState& state,
                                               unsigned what, ElementResult& out) const {
  const int nd = dim_ * numNodes_, nt = dim_ - 1;
  const FrictionPairState& f = state.friction;
  // This counterpart's part of the slip, from the step start.
  Eigen::MatrixXd ct(nt, nd);
  Eigen::VectorXd part(nt);
  for (int a = 0; a < nt; ++a) {
    ct.row(a) = slipRow(frozen, a).transpose();
    part[a] = 0.0;
    for (int i = 0; i < numNodes_; ++i)
      for (int k = 0; k < dim_; ++k)
        part[a] += ct(a, i * dim_ + k) * (u(i, k) - (f.stepStart.size() ? f.stepStart(i, k) : 0.0));
  }
  const Eigen::Map<const Eigen::VectorXd> lt(f.tangential.data(), nt);
  const FrictionRows rows = frictionRows(nt, f.slip.data(), state.multiplier, f.tangential.data(), f);
  if (what & kEnergy) out.energy += lt.dot(part);
  if (what & kResidual) {
    out.residual.head(nd) += ct.transpose() * lt;
    // Stick: each counterpart its part of u_t; slip: the slave the row.
    if (f.stick)
      out.residual.segment(nd + 1, nt) = part;
    else if (!master_)
      out.residual.segment(nd + 1, nt) = rows.residual;
  }
  if (what & kTangent) {
    out.tangent.block(0, nd + 1, nd, nt) = ct.transpose();
    out.tangent.block(nd + 1, 0, nt, nd) = rows.slipDerivative * ct;
    if (!master_) {
      out.tangent.block(nd + 1, nd, nt, 1) = rows.lambdaNDerivative;
      out.tangent.block(nd + 1, nd + 1, nt, nt) = rows.lambdaTDerivative;
    }
  }
}

}  // namespace ddc
