// The state of one contact pair handed to a contact element, and the
// contribution of a released pair: shared by the node-to-surface elements
// (DDC_NodeToSurface.hpp, DDC_DecomposedNodeToSurface.hpp) and the contact
// component's slots (DDC_ContactData.hpp).
#pragma once

#include <Eigen/Dense>

#include "DDC_Element.hpp"
#include "DDC_Friction.hpp"

namespace ddc {

/// State of one contact pair handed to a contact element.
struct ContactPairState {
  /// Active (in contact): potential Π_c = λ g_N. Inactive (released):
  /// Π_c = ½ λ², which restrains the multiplier to zero (paper eq. 2).
  bool active = false;
  /// The Lagrange multiplier λ. Sign convention (Fang & Izzuddin): a
  /// compressive contact force has λ < 0.
  double multiplier = 0.0;
  /// Frozen geometry of the last converged configuration in the closed form
  /// of a straight segment: projection parameter ξ^p on the master segment
  /// (ξ ∈ [0, 1] from master node 1 to node 2) and unit outward master
  /// normal n^p (paper eq. 1). Read only by the closed-form Line2 reference
  /// elements of the tests (packages/contact/test); the node-to-surface
  /// elements take the frozen geometry as a FrozenFacetProjection. Kept in
  /// the state (and in checkpoints, packSlots()) as it was.
  double frozenXi = 0.0;
  /// n^p of the closed-form reference (see frozenXi).
  Eigen::Vector2d frozenNormal = Eigen::Vector2d::Zero();
  /// Coulomb friction (DDC_Friction.hpp): with a coefficient > 0 the
  /// element has the tangential multipliers after λ (dim − 1 of them).
  FrictionPairState friction;
  /// The element's multipliers: 1, or dim with friction.
  int numMultipliers(int dim) const { return friction.frictional() ? dim : 1; }
  /// The multipliers in the element's DOF order: λ, then λ_t.
  std::array<double, 3> multipliers() const {
    return {multiplier, friction.tangential[0], friction.tangential[1]};
  }
};

/// The released (inactive) contribution Π_c = ½ λ² (paper eq. 2) on an
/// element whose multiplier is its last of `numDofs` DOFs: energy ½λ²,
/// residual λ on the multiplier, tangent 1 there; it restrains λ to zero and
/// does not depend on the geometry.
inline void releasedContribution(int numDofs, double lambda, unsigned what, ElementResult& out) {
  if (what & kEnergy) out.energy = 0.5 * lambda * lambda;
  if (what & kResidual) {
    out.residual.setZero(numDofs);
    out.residual(numDofs - 1) = lambda;
  }
  if (what & kTangent) {
    out.tangent.setZero(numDofs, numDofs);
    out.tangent(numDofs - 1, numDofs - 1) = 1.0;
  }
}

/// The released contribution of an element whose last `numMultipliers`
/// DOFs (of `numDofs`) are multipliers with the values `lambda`: Π_c =
/// ½ |λ|², which restrains every multiplier to zero.
inline void releasedContribution(int numDofs, const double* lambda, int numMultipliers, unsigned what,
                                 ElementResult& out) {
  const int first = numDofs - numMultipliers;
  if (what & kEnergy) {
    out.energy = 0.0;
    for (int a = 0; a < numMultipliers; ++a) out.energy += 0.5 * lambda[a] * lambda[a];
  }
  if (what & kResidual) {
    out.residual.setZero(numDofs);
    for (int a = 0; a < numMultipliers; ++a) out.residual(first + a) = lambda[a];
  }
  if (what & kTangent) {
    out.tangent.setZero(numDofs, numDofs);
    for (int a = 0; a < numMultipliers; ++a) out.tangent(first + a, first + a) = 1.0;
  }
}

}  // namespace ddc
