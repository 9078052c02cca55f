// The pairing part of the contact component (DDC_ContactComponent.hpp): the
// state that changes per step and per Newton iteration, on the topology the
// topology part fixed (DDC_ContactTopology.hpp).
//
//   slots         one per topology slot, replicated: its master facet, the
//                 frozen projection ξ^p and normal n^p, the gap, the
//                 multiplier and whether it is active. The pairing (master
//                 facet and nodes) and the states are the same on every
//                 rank; the decomposed element's values (frozen projection
//                 and basis, gap, slips, multipliers) are current where the
//                 slot is evaluated (its owner, its master facet's rank),
//                 and elsewhere once brought from the owner
//                 (shareSlotValues(), or updateActiveSet() with everySlot);
//   pairing       updatePairing(): the search and tracking over each pair's
//                 master facets (FacetSearch), with the facing and
//                 free-boundary rules (doc/contact.md, "Which slave nodes
//                 pair" and "Curved facets and 3-D") — replicated on gathered
//                 surface positions, or, for the decomposed element at step
//                 ends, by the owners of the slave nodes after one
//                 bounding-box-limited exchange, the results going to the
//                 master facets' ranks, and to every rank only where a
//                 slot's facet changes (DDC_ContactPairingSearch.cpp);
//                 the exchanges and bytes moved; the warnings and the record
//                 of the pairs that ever paired;
//   evaluation    the active set, the gaps, the constraint rows and the
//                 element contributions on the maps of the counterparts this
//                 rank evaluates (DDC_ContactPairingEvaluation.cpp);
//   step control  restoring saved slots;
//   values        what a step's end and the output read of the slots'
//                 values: sums over the slots' owners (the summary, the
//                 frictional work, the frozen-geometry error) and values
//                 brought from the owners (DDC_ContactSlotValues.cpp).
#pragma once

#include <Eigen/Dense>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "DDC_ContactData.hpp"
#include "DDC_ContactTopology.hpp"
#include "DDC_FacetSearch.hpp"
#include "DDC_TpetraTypes.hpp"

namespace ddc {

/// The per-step and per-iteration state of the contact component (see the
/// top of this file). The functions are ContactComponent's of the same name.
class ContactPairing {
 public:
  /// \param topology read for the life of this object
  explicit ContactPairing(const ContactTopology& topology);
  ~ContactPairing();
  /// After the topology's commit(): every slot unpaired, the pairs' searches.
  void start();
  /// After the topology's setDofs() and after any change of pairing: the
  /// maps and importers of the counterparts this rank evaluates.
  void buildEvaluationMaps();

  // ---- per step: the pairing -------------------------------------------------
  bool updatePairing(const Vector& u, bool global, bool freeze, std::vector<int>* changedSlots);
  std::vector<std::string> takeWarnings();
  std::vector<std::string> neverPairedPairs() const;
  std::vector<char> pairedRecord() const;
  void addPairedRecord(const std::vector<char>& record);
  void checkInitialPenetration(const std::vector<std::function<int(const Eigen::VectorXd&)>>& locate,
                               const std::function<std::vector<Eigen::VectorXd>(int, int)>& inward) const;
  /// {tracking queries, tracking fallbacks, global queries}.
  std::array<long, 3> searchCounters() const;
  long exchanges() const { return exchanges_; }
  long bytesExchanged() const { return bytesExchanged_; }
  /// ContactComponent::valueBytesReceived(), valueUpdates().
  std::array<long, 2> valueBytesReceived() const { return valueBytes_; }
  std::array<long, 2> valueUpdates() const { return valueUpdates_; }

  // ---- per iteration: the active set and what the host assembles ---------------
  void activateAllPaired();
  /// The step start of the slip of frictional pairs (ContactComponent::beginStep()).
  void beginStep(const Vector& u0);
  /// ContactComponent::updateActiveSet().
  std::vector<int> updateActiveSet(const Vector& u, const Vector* multipliers, bool everySlot);
  std::vector<ContactRowEntry> contactRows() const;
  /// ContactComponent::slipRowHeld().
  bool frozenSlipHeld(int k, int alpha) const;
  void assemble(const Vector& u, const Vector* multipliers, unsigned what,
                const std::function<void(const std::vector<GO>& dofs, ElementResult& result)>& add) const;

  // ---- step control --------------------------------------------------------------
  bool restoreSlots(const std::vector<ContactSlot>& saved);

  // ---- the values across ranks (DDC_ContactSlotValues.cpp) ---------------------------
  FrozenGeometryError frozenGeometryError(const std::vector<ContactSlot>& converged) const;
  ContactSummary reduceSummary() const;
  int numActive() const;
  double frictionalWork(const std::vector<ContactSlot>& converged) const;
  void shareSlotValues(std::vector<ContactSlot>& slots, const std::vector<int>& wanted) const;
  /// Every slot's values from its owner into this rank's slots (collective).
  void shareEverySlotsValues();
  static long sharedSlotBytes();

  // ---- queries ---------------------------------------------------------------------
  const std::vector<ContactSlot>& slots() const { return slots_; }
  const std::vector<int>& localMasterSlots() const { return localMasterSlots_; }
  std::vector<GO> slotDofs(int k) const;
  std::vector<GO> slaveSideDofs(int k) const;
  std::vector<GO> masterSideDofs(int k) const;
  bool fullyPrescribed(int k) const;

 private:
  using Pair = ContactTopology::Pair;
  using Position = std::function<Eigen::Vector3d(int)>;
  /// The pairing of one slave node found by a search.
  struct Found {
    int facet = -1;            ///< master facet in the pair (-1: not paired)
    bool pastFreeEnd = false;  ///< nearest point on the master surface's free boundary: not paired
    bool viaCorner = false;    ///< the slave projects outside the facet (corner / edge rule)
    std::array<double, 2> xi{{0.0, 0.0}};  ///< ξ^p (reference coordinates of the facet; xi[1] unused in 2-D)
    double gap = 0.0, distance = 0.0;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    Eigen::Vector3d slaveNormal = Eigen::Vector3d::Zero();  ///< replicated search: n_s (hysteresis, messages)
    /// Not paired only because of the facing rule's normal test: a master
    /// facet within the search radius does not face the slave surface.
    bool notFacing = false;
    /// Distributed search, 3-D frictional pairs: τ_1 of the tangent basis
    /// the slot's owner froze (zero: freeze it here, freezeGeometry()).
    Eigen::Vector3d tangent = Eigen::Vector3d::Zero();
    /// False: this rank did not learn the slot's pairing (the distributed
    /// search sends it only where the slot is evaluated or changes); the
    /// slot keeps its pairing.
    bool known = true;
  };
  /// Per pair, per slave node (the pair's slot order).
  using FoundAll = std::vector<std::vector<Found>>;
  /// Field values at this rank's counterpart DOFs and multipliers.
  struct Field;

  // search (DDC_ContactPairingSearch.cpp)
  Eigen::MatrixXd facetPositions(const Pair& pair, int f, const Position& position) const;
  Eigen::Vector3d slaveNormal(const Pair& pair, int node, const Position& position) const;
  std::vector<Found> facetPairing(const Pair& pair, FacetSearch& search, const std::vector<int>& facets,
                                  const std::vector<int>& slaves, const Position& position) const;
  bool pastFreeBoundary(const Pair& pair, int g, const FacetCandidate& c, const Eigen::Vector3d& d,
                        const Eigen::Vector3d& normal, const Position& position) const;
  void replicatedSearch(const Position& position, bool global, FoundAll& found);
  void distributedSearch(const Vector& u, FoundAll& found);
  template <int D>
  long sendPositions(const Vector& u, std::map<int, Eigen::Vector3d>& known) const;
  std::vector<std::pair<int, Found>> searchOwnedSlaves(const std::map<int, Eigen::Vector3d>& known, long& queries) const;
  template <int D>
  long shareFound(const std::vector<std::pair<int, Found>>& mine, FoundAll& found) const;

  // pairing (DDC_ContactPairing.cpp)
  Eigen::Vector3d currentPosition(int id, const std::vector<double>& surfaceValues) const;
  bool keepPreviousFacet(const Pair& pair, ContactSlot& s, const Found& c, const Position& position,
                         bool freeze) const;
  bool assignFacet(const Pair& pair, ContactSlot& s, const Found& c, bool freeze) const;
  /// `tangent`: τ_1 as the slot's owner froze it, or zero.
  void freezeGeometry(const Pair& pair, ContactSlot& s, const std::array<double, 2>& xi,
                      const Eigen::Vector3d& normal, const Eigen::Vector3d& tangent = Eigen::Vector3d::Zero()) const;
  void notePairing(const FoundAll& found);
  std::string whyNotPaired(const Pair& pair, int node, double& depth) const;

  // evaluation (DDC_ContactPairingEvaluation.cpp)
  void gatherSurface(const Vector& u, const Vector* multipliers, std::vector<double>& values) const;
  void refreshSlotGeometry(const std::vector<double>& surfaceValues);
  /// Decomposed element: the summed gaps (and slips) and the multipliers
  /// into the slots this rank evaluates (owned and master counterparts);
  /// the bytes received count in valueBytes_[counter].
  void assembleFrozenGaps(const Vector& u, const Vector* multipliers, int counter);
  /// Slot k's multipliers, gap and slips from summed values `g` and
  /// multipliers `lam`, indexed by at(multiplier id).
  template <class At>
  void takeFrozenValues(int k, const double* g, const double* lam, const At& at);
  /// Decomposed element: the owners decide their slots (applyContactRules()),
  /// every rank takes the changed states; returns every changed slot,
  /// ascending. The bytes received count in valueBytes_[counter]. Collective.
  std::vector<int> decideOnOwners(int counter);
  /// The contact-state rules for slot k (ContactComponent::updateActiveSet()),
  /// with lmax the largest |λ| of all slots; appends k to `changed` (and to
  /// `activated`). Returns the message of a fully prescribed slot that
  /// penetrates ("" otherwise).
  std::string applyContactRules(int k, double lmax, std::vector<int>& changed, std::vector<int>& activated);
  Field gatherField(const Vector& u, const Vector* multipliers) const;
  /// forceStick: a frictional pair's tangential rows as in stick (its slip parts).
  void evaluate(int k, SurfaceContactRole role, const Field& f, bool forceActive, unsigned what, ElementResult& er,
                std::vector<GO>& dofs, bool forceStick = false) const;
  struct SlotValues;
  /// evaluate() at given values (`dofs` as evaluate() sets them).
  void evaluateAt(int k, SurfaceContactRole role, const SlotValues& values, bool forceActive, unsigned what,
                  ElementResult& er, const std::vector<GO>& dofs, bool forceStick = false) const;
  /// The slave node and/or the master facet's nodes of slot k, as the element of `role` orders them.
  std::vector<int> elementNodes(int k, SurfaceContactRole role) const;
  /// The conventional element's tangential force on the slave node of
  /// frictional slot k (the slave rows of its residual less the normal
  /// force), from the surface values of gatherSurface().
  Eigen::Vector3d consistentTangentialForce(int k, const std::vector<double>& surfaceValues, size_t lambdaAt) const;
  void appendMultipliers(int k, std::vector<GO>& dofs) const;
  /// A tangential row that holds nothing the supports and the gap row do not
  /// (on prescribed DOFs only, or redundant on a symmetry plane): its
  /// multiplier restrained to zero.
  void restrainHeldSlip(int k, SurfaceContactRole role, const std::vector<GO>& dofs, const ContactPairState& state,
                        ElementResult& er) const;
  void refreshSlip(ContactSlot& s, const std::array<double, 2>& xi, const Position& position) const;
  FrictionState newContactState(const ContactSlot& s) const;
  /// `owned`: counted over this rank's slots and summed over the ranks (collective).
  void slipNewContactsOfSlidingPairs(const std::vector<int>& activated, bool owned);
  /// Stick or slip of active slot k; true if a frictional pair's state flipped.
  bool updateFriction(int k);
  /// Throws std::logic_error before the first updatePairing().
  void requirePaired(const char* what) const;
  /// shareSlotValues(); returns the bytes this rank received.
  long shareValues(std::vector<ContactSlot>& slots, const std::vector<int>& wanted) const;
  /// Throws std::invalid_argument naming `what` unless `slots` has one entry per slot.
  void requireSlotList(const std::vector<ContactSlot>& slots, const char* what) const;

  const ContactTopology& topo_;
  std::vector<ContactSlot> slots_;
  std::vector<int> localMasterSlots_;
  std::vector<std::unique_ptr<FacetSearch>> searches_;  ///< per pair: the replicated search and tracking
  bool pairedOnce_ = false;            ///< updatePairing() has run (requirePaired())
  std::vector<char> everPaired_;       ///< per pair: some slave node has paired (neverPairedPairs())
  std::vector<char> facingReported_;   ///< per pair: the facing warning was given
  std::vector<std::string> warnings_;  ///< takeWarnings()
  long distributedQueries_ = 0;
  mutable long exchanges_ = 0, bytesExchanged_ = 0;
  /// valueBytesReceived(), valueUpdates(): [0] without everySlot, [1] with it.
  std::array<long, 2> valueBytes_{{0, 0}}, valueUpdates_{{0, 0}};

  Teuchos::RCP<Vector> stepStart_;        ///< u at the step start (frictional pairs; beginStep())
  std::vector<double> stepStartSurface_;  ///< its surface values (conventional element)
  Teuchos::RCP<const Map> dofOverlapMap_;  ///< host DOFs of this rank's counterparts / elements
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> dofImporter_;
  Teuchos::RCP<const Map> lmOverlapMap_;   ///< multipliers of this rank's counterparts
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> lmImporter_;      ///< multiplierMap -> lmOverlapMap_
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> lmHostImporter_;  ///< hostMap -> lmOverlapMap_ (host multipliers)
  Teuchos::RCP<const Tpetra::Export<LO, GO, Node>> lmExporter_;      ///< lmOverlapMap_ -> multiplierMap
};

}  // namespace ddc
