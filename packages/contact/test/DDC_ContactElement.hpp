// The interface of the closed-form 2-D contact elements on a straight
// segment (DDC_NodeToSegment.hpp, DDC_DecomposedNodeToSegment.hpp): elements
// that carry one Lagrange multiplier and a contact state. A test reference:
// the node-to-surface elements of the library (DDC_SurfaceContactElement.hpp)
// are checked against these on Line2 facets.
#pragma once

#include <Eigen/Dense>

#include "DDC_ContactState.hpp"
#include "DDC_Element.hpp"

namespace ddc {

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
