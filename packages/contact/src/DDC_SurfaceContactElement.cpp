// Surface contact elements and their factory entries (see the header).
#include "DDC_SurfaceContactElement.hpp"

#include "DDC_ElementFactory.hpp"

namespace ddc {

namespace {

const CellType kFacetTypes[] = {CellType::Line2, CellType::Line3, CellType::Tri3, CellType::Tri6,
                                CellType::Quad4, CellType::Quad8, CellType::Quad9};

/// The conventional element: NodeToSurfaceElement behind the interface.
class NodeToSurfaceContact : public SurfaceContactElement {
 public:
  explicit NodeToSurfaceContact(CellType facet) : element_(facet) {}
  int numNodes() const override { return element_.numNodes(); }
  int dim() const override { return element_.dim(); }
  CellType facet() const override { return element_.facet(); }
  SurfaceContactRole role() const override { return SurfaceContactRole::Conventional; }
  void computeSurfaceContact(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u, const FrozenFacetProjection&,
                             const ContactPairState& state, unsigned what, ElementResult& out) const override {
    element_.computeContact(X, u, state, what, out);
  }

 private:
  NodeToSurfaceElement element_;
};

/// A decomposed counterpart: DecomposedSurfaceCounterpart behind the interface.
class DecomposedSurfaceContact : public SurfaceContactElement {
 public:
  DecomposedSurfaceContact(CellType facet, bool master) : facet_(facet), counterpart_(facet, master) {}
  int numNodes() const override { return counterpart_.numNodes(); }
  int dim() const override { return counterpart_.dim(); }
  CellType facet() const override { return facet_; }
  SurfaceContactRole role() const override {
    return counterpart_.isMaster() ? SurfaceContactRole::Master : SurfaceContactRole::Slave;
  }
  void computeSurfaceContact(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u, const FrozenFacetProjection& frozen,
                             const ContactPairState& state, unsigned what, ElementResult& out) const override {
    counterpart_.computeContact(X, u, frozen, state, what, out);
  }

 private:
  CellType facet_;
  DecomposedSurfaceCounterpart counterpart_;
};

}  // namespace

std::string surfaceContactElementName(SurfaceContactRole role, CellType facet) {
  const char* prefix = role == SurfaceContactRole::Conventional ? "Node-To-Surface "
                       : role == SurfaceContactRole::Slave      ? "Decomposed NTS Slave "
                                                                : "Decomposed NTS Master ";
  return prefix + std::string(cellTypeName(facet));
}

std::shared_ptr<const SurfaceContactElement> makeSurfaceContactElement(SurfaceContactRole role, CellType facet) {
  if (role == SurfaceContactRole::Conventional) return std::make_shared<NodeToSurfaceContact>(facet);
  return std::make_shared<DecomposedSurfaceContact>(facet, role == SurfaceContactRole::Master);
}

void registerSurfaceContactElements(ElementFactory& f) {
  const auto none = Teuchos::rcp(new Teuchos::ParameterList());
  for (CellType facet : kFacetTypes)
    for (SurfaceContactRole role :
         {SurfaceContactRole::Conventional, SurfaceContactRole::Slave, SurfaceContactRole::Master}) {
      const auto prototype = makeSurfaceContactElement(role, facet);
      const std::string what = role == SurfaceContactRole::Conventional
                                   ? "Conventional nonlinear node-to-surface contact element"
                                   : role == SurfaceContactRole::Slave ? "Slave counterpart of the decomposed "
                                                                         "node-to-surface element"
                                                                       : "Master counterpart of the decomposed "
                                                                         "node-to-surface element";
      f.add(surfaceContactElementName(role, facet),
            ElementFactory::Entry{[role, facet](const Teuchos::ParameterList&) -> std::shared_ptr<Element> {
                                    return std::const_pointer_cast<SurfaceContactElement>(
                                        makeSurfaceContactElement(role, facet));
                                  },
                                  none,
                                  what + " on a " + cellTypeName(facet) +
                                      " master facet (doc/contact.md, 'Curved facets and 3-D'); no parameters.",
                                  prototype->numNodes(), prototype->dim(), /*contact=*/true});
    }
}

}  // namespace ddc
