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

Eigen::VectorXd DecomposedSurfaceCounterpart::constraintRow(const FrozenFacetProjection& frozen) const {
  const double len = frozen.normal.norm();
  if (!(std::abs(len - 1.0) <= 1e-10)) {
    std::ostringstream os;
    os << "decomposed node-to-surface " << (master_ ? "master" : "slave") << " counterpart: frozen normal n^p = ("
       << frozen.normal.transpose() << ") is not a unit vector (|n^p| = " << len
       << "); freeze it from the last converged configuration";
    throw std::invalid_argument(os.str());
  }
  Eigen::VectorXd c(dim_ * numNodes_);
  if (!master_) {
    c = frozen.normal.head(dim_);
    return c;
  }
  std::vector<double> N(numNodes_);
  shapeFunctionsT<double>(facet_, frozen.xi.data(), N.data(), nullptr);
  for (int i = 0; i < numNodes_; ++i)
    for (int k = 0; k < dim_; ++k) c[i * dim_ + k] = -N[i] * frozen.normal[k];
  return c;
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
  const double lambda = state.multiplier;
  if (!state.active) {
    // The release term ½λ² lives in the slave counterpart only, so the two
    // counterparts add up to the decomposed element.
    if (!master_) return releasedContribution(nd + 1, lambda, what, out);
    if (what & kEnergy) out.energy = 0.0;
    if (what & kResidual) out.residual.setZero(nd + 1);
    if (what & kTangent) out.tangent.setZero(nd + 1, nd + 1);
    return;
  }
  const Eigen::VectorXd c = constraintRow(frozen);
  const double g = gapPart(X, u, frozen);
  if (what & kEnergy) out.energy = lambda * g;
  if (what & kResidual) {
    out.residual.resize(nd + 1);
    out.residual.head(nd) = lambda * c;
    out.residual[nd] = g;
  }
  if (what & kTangent) {
    out.tangent.setZero(nd + 1, nd + 1);
    out.tangent.col(nd).head(nd) = c;
    out.tangent.row(nd).head(nd) = c.transpose();
  }
}

}  // namespace ddc
