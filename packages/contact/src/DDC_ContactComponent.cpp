// The contact component's facade: every function forwards to the topology
// part (DDC_ContactTopology.hpp) or the pairing part (DDC_ContactPairing.hpp).
#include "DDC_ContactComponent.hpp"

#include "DDC_ContactPairing.hpp"
#include "DDC_ContactTopology.hpp"

namespace ddc {

ContactComponent::ContactComponent(Teuchos::RCP<const Teuchos::Comm<int>> comm, ContactComponentOptions options,
                                   SurfaceElementSource surfaceElements)
    : topology_(std::make_unique<ContactTopology>(std::move(comm), options, std::move(surfaceElements))),
      pairing_(std::make_unique<ContactPairing>(*topology_)) {}

ContactComponent::~ContactComponent() = default;

// ---- registration ----------------------------------------------------------------------

void ContactComponent::registerNodes(const std::vector<ContactNode>& nodes) { topology_->registerNodes(nodes); }

int ContactComponent::registerPair(ContactPairSurfaces pair) { return topology_->registerPair(std::move(pair)); }

void ContactComponent::commit() {
  topology_->commit();
  pairing_->start();
}

void ContactComponent::setDofs(Teuchos::RCP<const Map> hostMap, const std::vector<ContactNodeDofs>& nodeDofs,
                               const std::vector<GO>& multiplierDofs) {
  topology_->setDofs(std::move(hostMap), nodeDofs, multiplierDofs);
  pairing_->buildEvaluationMaps();
}

// ---- lifecycle -----------------------------------------------------------------------------

bool ContactComponent::updatePairing(const Vector& u, bool global, bool freeze, std::vector<int>* changedSlots) {
  return pairing_->updatePairing(u, global, freeze, changedSlots);
}

std::vector<std::string> ContactComponent::takeWarnings() { return pairing_->takeWarnings(); }

std::vector<std::string> ContactComponent::neverPairedPairs() const { return pairing_->neverPairedPairs(); }

std::vector<char> ContactComponent::pairedRecord() const { return pairing_->pairedRecord(); }

void ContactComponent::addPairedRecord(const std::vector<char>& record) { pairing_->addPairedRecord(record); }

void ContactComponent::activateAllPaired() { pairing_->activateAllPaired(); }

void ContactComponent::beginStep(const Vector& u0) {
  topology_->requireCommitted("beginStep");
  pairing_->beginStep(u0);
}

std::vector<int> ContactComponent::updateActiveSet(const Vector& u, const Vector* multipliers, bool everySlot) {
  return pairing_->updateActiveSet(u, multipliers, everySlot);
}

FrozenGeometryError ContactComponent::frozenGeometryError(const std::vector<ContactSlot>& converged) const {
  return pairing_->frozenGeometryError(converged);
}

double ContactComponent::frictionalWork(const std::vector<ContactSlot>& converged) const {
  return pairing_->frictionalWork(converged);
}

void ContactComponent::shareSlotValues(std::vector<ContactSlot>& slots, const std::vector<int>& wanted) const {
  pairing_->shareSlotValues(slots, wanted);
}

void ContactComponent::shareEverySlotsValues() { pairing_->shareEverySlotsValues(); }

long ContactComponent::sharedSlotBytes() { return ContactPairing::sharedSlotBytes(); }

bool ContactComponent::restoreSlots(const std::vector<ContactSlot>& saved) { return pairing_->restoreSlots(saved); }

// ---- what the host assembles or solves with ------------------------------------------------

std::vector<ContactRowEntry> ContactComponent::contactRows() const { return pairing_->contactRows(); }

void ContactComponent::assemble(const Vector& u, const Vector* multipliers, unsigned what,
                                const std::function<void(const std::vector<GO>&, ElementResult&)>& add) const {
  pairing_->assemble(u, multipliers, what, add);
}

// ---- queries ---------------------------------------------------------------------------------

bool ContactComponent::decomposed() const { return topology_->options().decomposed; }

const ContactComponentOptions& ContactComponent::options() const { return topology_->options(); }

int ContactComponent::numPairs() const { return topology_->numPairs(); }

const std::vector<ContactSlot>& ContactComponent::slots() const { return pairing_->slots(); }

int ContactComponent::slotOwner(int k) const { return topology_->slotOwner(k); }

const std::vector<int>& ContactComponent::ownedSlots() const { return topology_->ownedSlots(); }

const std::vector<int>& ContactComponent::localMasterSlots() const { return pairing_->localMasterSlots(); }

Teuchos::RCP<const Map> ContactComponent::multiplierMap() const { return topology_->multiplierMap(); }

GO ContactComponent::multiplierId(int k, int c) const { return topology_->multiplierId(k, c); }

int ContactComponent::numMultipliers(int k) const { return topology_->numMultipliers(k); }

bool ContactComponent::slipRowHeld(int k, int alpha) const { return pairing_->frozenSlipHeld(k, alpha); }

bool ContactComponent::frictional() const { return topology_->frictional(); }

FrictionRows ContactComponent::slipLinearisation(int k) const {
  const ContactSlot& s = pairing_->slots()[k];
  const auto& pair = topology_->pair(s.pair);
  FrictionPairState f;
  f.coefficient = pair.friction;
  f.stiffness = pair.frictionStiffness;
  f.stick = false;
  return frictionRows(topology_->dim() - 1, s.tangentialSlip.data(), s.state.multiplier, s.tangential.data(), f);
}

std::vector<GO> ContactComponent::slotDofs(int k) const { return pairing_->slotDofs(k); }

std::vector<GO> ContactComponent::slaveSideDofs(int k) const { return pairing_->slaveSideDofs(k); }

std::vector<GO> ContactComponent::masterSideDofs(int k) const { return pairing_->masterSideDofs(k); }

bool ContactComponent::fullyPrescribed(int k) const { return pairing_->fullyPrescribed(k); }

const std::vector<int>& ContactComponent::surfaceNodes() const { return topology_->surfaceNodes(); }

bool ContactComponent::isSurfaceNode(int id) const { return topology_->index(id) >= 0; }

Eigen::Vector3d ContactComponent::referencePosition(int id) const { return topology_->referencePosition(id); }

GO ContactComponent::surfaceNodeDof(int id, int c) const {
  topology_->requireCommitted("surfaceNodeDof");
  const int i = topology_->index(id);
  if (i < 0) throw std::out_of_range("ContactComponent::surfaceNodeDof: node " + std::to_string(id) + " is no surface node");
  return topology_->dofsAt(i).at(size_t(c));
}

int ContactComponent::dim() const { return topology_->dim(); }

ContactSummary ContactComponent::reduceSummary() const { return pairing_->reduceSummary(); }

int ContactComponent::numActive() const { return pairing_->numActive(); }

std::string ContactComponent::describeSlot(int k) const { return topology_->describeSlot(k); }

const std::string& ContactComponent::pairName(int p) const { return topology_->pair(p).name; }

long ContactComponent::exchanges() const { return pairing_->exchanges(); }

long ContactComponent::bytesExchanged() const { return pairing_->bytesExchanged(); }

std::array<long, 2> ContactComponent::valueBytesReceived() const { return pairing_->valueBytesReceived(); }

std::array<long, 2> ContactComponent::valueUpdates() const { return pairing_->valueUpdates(); }

std::array<long, 3> ContactComponent::searchCounters() const { return pairing_->searchCounters(); }

void ContactComponent::checkInitialPenetration(
    const std::vector<std::function<int(const Eigen::VectorXd&)>>& locate,
    const std::function<std::vector<Eigen::VectorXd>(int, int)>& inward) const {
  pairing_->checkInitialPenetration(locate, inward);
}

}  // namespace ddc
