#include "DDC_DecomposedNodeToSegment.hpp"

#include <cmath>
#include <stdexcept>

#include "DDC_Error.hpp"

namespace ddc {

namespace {

/// n^p, checked to be a unit vector. A frozen normal is produced by
/// normalisation (|n| = 1 to round-off); anything else — in particular the
/// default zero vector of a state nobody filled in — is a caller bug.
const Eigen::Vector2d& frozenUnitNormal(const char* who, const ContactPairState& state) {
  const double len = state.frozenNormal.norm();
  if (!(std::abs(len - 1.0) <= 1e-10))
    DDC_THROW(std::invalid_argument, who << ": frozen normal n^p = (" << state.frozenNormal.x() << ", "
                                         << state.frozenNormal.y() << ") is not a unit vector (|n^p| = " << len
                                         << "); set ContactPairState::frozenNormal from the last converged "
                                            "configuration");
  return state.frozenNormal;
}

void requireShape(const char* who, int numNodes, const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u) {
  if (X.rows() != numNodes || u.rows() != numNodes)
    DDC_THROW(std::invalid_argument, who << ": expected " << numNodes << " nodes, got X with " << X.rows()
                                         << " and u with " << u.rows() << " rows");
}

}  // namespace

double decomposedGap(const Eigen::Vector2d& xs, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                     const ContactPairState& state) {
  const Eigen::Vector2d& n = frozenUnitNormal("decomposedGap", state);
  const double xi = state.frozenXi;
  return n.dot(xs - (1.0 - xi) * x1 - xi * x2);  // paper eq. 1
}

// ---------------------------------------------------------------------------
// Slave counterpart: Π = λ n^p·x_s (active), ½ λ² (inactive).
// ---------------------------------------------------------------------------

Teuchos::RCP<const Teuchos::ParameterList> DecomposedNtsSlaveElement::getValidParameters() {
  return Teuchos::rcp(new Teuchos::ParameterList("Element"));
}

Eigen::Vector2d DecomposedNtsSlaveElement::constraintCoefficients(const ContactPairState& state) {
  return frozenUnitNormal("Decomposed NTS Slave", state);
}

double DecomposedNtsSlaveElement::gap(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u,
                                      const ContactPairState& state) const {
  requireShape("Decomposed NTS Slave gap", 1, X, u);
  const Eigen::Vector2d xs = (X.row(0) + u.row(0)).transpose();
  return frozenUnitNormal("Decomposed NTS Slave gap", state).dot(xs);
}

void DecomposedNtsSlaveElement::computeContact(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u,
                                               const ContactPairState& state, unsigned what,
                                               ElementResult& out) const {
  requireShape("Decomposed NTS Slave computeContact", 1, X, u);
  constexpr int kN = 3;  // [u_s, λ]
  constexpr int kLam = 2;
  const double lam = state.multiplier;
  if (!state.active) {
    // The release term of the pair lives here only (the master's is zero).
    releasedContribution(kN, lam, what, out);
    return;
  }
  const Eigen::Vector2d& n = frozenUnitNormal("Decomposed NTS Slave computeContact", state);
  const Eigen::Vector2d xs = (X.row(0) + u.row(0)).transpose();
  const double gs = n.dot(xs);
  if (what & kEnergy) out.energy = lam * gs;
  if (what & kResidual) {
    out.residual.resize(kN);
    out.residual.head<2>() = lam * n;
    out.residual(kLam) = gs;
  }
  if (what & kTangent) {
    // Π is bilinear in (u_s, λ): only the coupling block is non-zero.
    out.tangent.setZero(kN, kN);
    out.tangent.block<2, 1>(0, kLam) = n;
    out.tangent.block<1, 2>(kLam, 0) = n.transpose();
  }
}

// ---------------------------------------------------------------------------
// Master counterpart: Π = −λ n^p·Σ N_i(ξ^p) x_i (active), 0 (inactive).
// ---------------------------------------------------------------------------

Teuchos::RCP<const Teuchos::ParameterList> DecomposedNtsMasterElement::getValidParameters() {
  return Teuchos::rcp(new Teuchos::ParameterList("Element"));
}

Eigen::Vector4d DecomposedNtsMasterElement::constraintCoefficients(const ContactPairState& state) {
  const Eigen::Vector2d& n = frozenUnitNormal("Decomposed NTS Master", state);
  const double xi = state.frozenXi;
  Eigen::Vector4d c;
  c << -(1.0 - xi) * n, -xi * n;
  return c;
}

double DecomposedNtsMasterElement::gap(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u,
                                       const ContactPairState& state) const {
  requireShape("Decomposed NTS Master gap", 2, X, u);
  const Eigen::Matrix<double, 2, 2> x = X + u;
  Eigen::Vector4d xv;
  xv << x.row(0).transpose(), x.row(1).transpose();
  return constraintCoefficients(state).dot(xv);
}

void DecomposedNtsMasterElement::computeContact(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u,
                                                const ContactPairState& state, unsigned what,
                                                ElementResult& out) const {
  requireShape("Decomposed NTS Master computeContact", 2, X, u);
  constexpr int kN = 5;  // [u_1, u_2, λ]
  constexpr int kLam = 4;
  if (!state.active) {
    // Inactive: nothing; the pair's ½ λ² is in the slave counterpart.
    if (what & kEnergy) out.energy = 0.0;
    if (what & kResidual) out.residual.setZero(kN);
    if (what & kTangent) out.tangent.setZero(kN, kN);
    return;
  }
  const double lam = state.multiplier;
  const Eigen::Vector4d c = constraintCoefficients(state);
  const Eigen::Matrix<double, 2, 2> x = X + u;
  Eigen::Vector4d xv;
  xv << x.row(0).transpose(), x.row(1).transpose();
  const double gm = c.dot(xv);
  if (what & kEnergy) out.energy = lam * gm;
  if (what & kResidual) {
    out.residual.resize(kN);
    out.residual.head<4>() = lam * c;
    out.residual(kLam) = gm;
  }
  if (what & kTangent) {
    out.tangent.setZero(kN, kN);
    out.tangent.block<4, 1>(0, kLam) = c;
    out.tangent.block<1, 4>(kLam, 0) = c.transpose();
  }
}

}  // namespace ddc
