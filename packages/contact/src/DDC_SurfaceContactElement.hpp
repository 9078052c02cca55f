// Contact elements on master facets of any type, as the contact component
// evaluates them for every pair (2-D segments and 3-D faces): the
// conventional node-to-surface element (DDC_NodeToSurface.hpp) and the two
// counterparts of the decomposed element (DDC_DecomposedNodeToSurface.hpp).
// They register in the element factory (registerSurfaceContactElements()),
// one entry per facet type, so the factory's node count and dimension
// describe them exactly:
//
//   "Node-To-Surface <Facet>"       nodes [slave, facet nodes...]
//   "Decomposed NTS Slave <Facet>"  nodes [slave]
//   "Decomposed NTS Master <Facet>" nodes [facet nodes...]
//
// with <Facet> one of Line2, Line3, Tri3, Tri6, Quad4, Quad8, Quad9 (on Line2
// the generic form of the closed-form node-to-segment elements, a test
// reference in packages/contact/test). DOFs: dim per node, node-major, the
// multiplier λ last.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>

#include "DDC_ContactState.hpp"
#include "DDC_DecomposedNodeToSurface.hpp"
#include "DDC_NodeToSurface.hpp"

namespace ddc {

class ElementFactory;

/// What a surface contact element is within the formulation.
enum class SurfaceContactRole {
  Conventional,  ///< the conventional element: nodes [slave, facet nodes...]
  Slave,         ///< the decomposed element's slave counterpart: nodes [slave]
  Master         ///< the decomposed element's master counterpart: nodes [facet nodes...]
};

/// A contact element on one facet type (see the top of this file).
class SurfaceContactElement : public Element {
 public:
  /// The master facet type the element is made for.
  virtual CellType facet() const = 0;
  /// The element's role in the formulation (its nodes and DOFs).
  virtual SurfaceContactRole role() const = 0;
  /// Energy, residual and tangent of the element (DOFs as at the top of
  /// this file). Not collective; called on the rank that evaluates the slot.
  /// \param X, u reference positions and displacements, numNodes() x dim()
  /// \param frozen ξ^p and n^p (paper eq. 1), read by the decomposed
  ///        counterparts only
  /// \param state active or released, and the multiplier λ (λ < 0 in
  ///        compression); a released element contributes ½λ² only
  /// \param what which of kEnergy, kResidual, kTangent to compute
  /// \param out the results, in the element's DOF order
  virtual void computeSurfaceContact(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u,
                                     const FrozenFacetProjection& frozen, const ContactPairState& state,
                                     unsigned what, ElementResult& out) const = 0;

  // Continuum-style entry points make no sense without a multiplier and a state.
  void compute(const NodalArray&, const NodalArray&, unsigned, ElementResult&) const override {
    throw std::logic_error("SurfaceContactElement::compute: use computeSurfaceContact");
  }
  void postprocess(const NodalArray&, const NodalArray&, ElementPostResult& out) const override {
    out = ElementPostResult();
  }
  double minReferenceJacobian(const NodalArray&) const override { return 1.0; }
};

/// The factory name of the surface contact element of `role` on `facet`
/// ("Node-To-Surface Quad8", ...).
std::string surfaceContactElementName(SurfaceContactRole role, CellType facet);

/// The built-in element of `role` on `facet` (what the factory entries create).
/// \throws std::invalid_argument for a cell type that is not a facet.
std::shared_ptr<const SurfaceContactElement> makeSurfaceContactElement(SurfaceContactRole role, CellType facet);

/// Register the surface contact elements of every facet type in `f`.
void registerSurfaceContactElements(ElementFactory& f);

}  // namespace ddc
