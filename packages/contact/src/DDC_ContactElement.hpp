// Contact elements: elements that carry one Lagrange multiplier and a contact
// state. They register in the ElementFactory like any element; the analysis
// recognises them by this interface.
#pragma once

#include <Eigen/Dense>

#include "DDC_Element.hpp"

namespace ddc {

/// State of one contact pair handed to a contact element.
struct ContactPairState {
  /// Active (in contact): potential Π_c = λ g_N. Inactive (released):
  /// Π_c = ½ λ², which restrains the multiplier to zero (paper eq. 2).
  bool active = false;
  /// The Lagrange multiplier λ. Sign convention (Fang & Izzuddin): a
  /// compressive contact force has λ < 0.
  double multiplier = 0.0;
  /// Frozen geometry of the last converged configuration, used by the
  /// decomposed counterparts (paper eq. 1): projection parameter ξ^p on the
  /// master segment (ξ ∈ [0, 1] from master node 1 to node 2) and unit
  /// outward master normal n^p. Ignored by the conventional element.
  double frozenXi = 0.0;
  Eigen::Vector2d frozenNormal = Eigen::Vector2d::Zero();
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

/// An element with one Lagrange multiplier. DOFs: the nodal DOFs (node-major,
/// 2 per node) followed by the multiplier, so residual/tangent have size
/// 2·numNodes() + 1.
class ContactElement : public Element {
 public:
  /// Evaluate contact energy Π_c, residual ∂Π_c/∂(u, λ) and tangent.
  /// \param X reference coordinates of the element's nodes (numNodes() x 2)
  /// \param u their displacements
  virtual void computeContact(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u, const ContactPairState& state,
                              unsigned what, ElementResult& out) const = 0;
  /// Normal gap g_N of the pair (the quantity the active set tests).
  virtual double gap(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u, const ContactPairState& state) const = 0;

  int dim() const override { return 2; }
  // Continuum-style entry points make no sense without a multiplier and a state.
  void compute(const NodalArray&, const NodalArray&, unsigned, ElementResult&) const override {
    throw std::logic_error("ContactElement::compute: use computeContact (a multiplier and a state are needed)");
  }
  void postprocess(const NodalArray&, const NodalArray&, ElementPostResult& out) const override {
    out = ElementPostResult();
  }
  double minReferenceJacobian(const NodalArray&) const override { return 1.0; }
};

}  // namespace ddc
