// Contact as a component a host code drives (doc/embedding.md, "(c) The
// contact component"): the whole node-to-surface contact lifecycle behind one class,
// in the host's node and DOF numbering, with nothing of a mesh, a partition,
// FETI-DP or a Newton loop inside. The shape follows LLNL Tribol's interface
// (register the surfaces, then the fields; update at step ends; read rows,
// gaps and contributions):
//
//   ContactComponent c(comm, options);     // options: formulation, radius, tolerance
//   c.registerNodes(myOwnedSurfaceNodes);   // id, reference coordinates
//   c.registerPair(pair);                   // facets of my elements, slave nodes
//   c.commit();                             // collective: slots, ownership
//   c.setDofs(hostOwnedMap, nodeDofs, multiplierDofs);  // host DOF ids
//   c.updatePairing(u, /*global=*/true, /*freeze=*/true);
//   per Newton iteration: c.contactRows() / c.assemble(...); c.updateActiveSet(u, λ)
//   per converged step:   c.updatePairing(u, true, freeze)
//
// Data layout. The surfaces are small against the bodies, so after commit()
// every rank holds every surface node's reference coordinates, DOF ids and
// owner, and every contact slot (one per slave node: its pairing and state
// the same on every rank; its frozen projection and normal, see below). Field
// values (displacements, multipliers) stay distributed in the host's map and
// move only in the counted exchanges (exchanges(), bytesExchanged()):
//  - conventional element: the surface positions are gathered to every rank
//    at each pairing and active-set update;
//  - decomposed element: at step ends the owner of each slave node searches
//    over the master-surface nodes the other ranks send it because they lie
//    in its bounding box, and sends the frozen projection and normal to the
//    rank of the master facet, and to every rank only if the slot's facet
//    changed (one exchange; the frozen values of a slot are current where
//    it is evaluated, the pairing is the same everywhere); the contact
//    state is checked on the multiplier map (partial gaps of the two
//    counterparts summed there, and decided by the slot's owner), with no
//    geometry moving; in a Newton
//    iteration and at a step's end only the evaluated slots' values come
//    back (updateActiveSet(); doc/contact.md): the step's sums are taken
//    on the slots' owners, and output brings the values it writes from
//    there (shareSlotValues()).
//
// Facets. A pair's facets are of one cell type per surface
// (ContactPairSurfaces::masterFacetType / slaveFacetType): Line2 or Line3
// segments in 2-D, Tri3/Tri6/Quad4/Quad8/Quad9 faces in 3-D. Every facet
// type takes the same path: the facet search of DDC_FacetSearch.hpp and the
// node-to-surface elements of DDC_SurfaceContactElement.hpp, one per role
// and facet type (doc/contact.md, "Curved facets and 3-D"). Every pair of a
// component has the same space dimension.
//
// Ownership. A surface node belongs to the rank that registers it, and its
// DOF ids must be owned by that rank in the host's map (setDofs() checks).
// A slot and its multiplier belong to the owner of its slave node. The
// master counterpart of a pair is evaluated on the rank that registered its
// master facet, and its constraint row is labelled with that facet's host
// subdomain (ContactFacet::subdomain).
//
// Inside, two parts, each readable alone: the topology
// (DDC_ContactTopology.hpp: registration, commit(), setDofs(), the surface
// nodes, the slots' static data, the DOF and multiplier maps — fixed once
// setDofs() has run) and the pairing (DDC_ContactPairing.hpp: search and
// tracking, the slots' pairing and state, the step-end exchange and its
// counters, the active set, rows and contributions, the frozen-geometry
// error — what changes per step and per iteration). This class is the
// host-facing facade over the two; the values it exchanges with the host are
// in DDC_ContactData.hpp.
#pragma once

#include <Eigen/Dense>
#include <Teuchos_Comm.hpp>
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "DDC_ContactData.hpp"
#include "DDC_ReferenceCell.hpp"
#include "DDC_SurfaceContactElement.hpp"
#include "DDC_TpetraTypes.hpp"

namespace ddc {

class ContactTopology;
class ContactPairing;

/// The contact component (see the top of this file).
class ContactComponent {
 public:
  /// Surface contact elements by role and facet type (e.g. from the element
  /// factory, surfaceContactElementName()).
  using SurfaceElementSource =
      std::function<std::shared_ptr<const SurfaceContactElement>(SurfaceContactRole role, CellType facet)>;
  /// \param comm the host's ranks (collective calls are collective over it)
  /// \param options the formulation, search radius and penetration tolerance
  /// \param surfaceElements the contact elements by role and facet type
  ///        (default: the built-in ones, makeSurfaceContactElement()); commit()
  ///        asks it for the roles of the formulation (Conventional, or Slave
  ///        and Master) on every master facet type in use
  /// \throws std::invalid_argument if options.searchRadius is not > 0 or
  ///         options.penetrationTolerance not >= 0 (both finite), or
  ///         `surfaceElements` is empty.
  ContactComponent(Teuchos::RCP<const Teuchos::Comm<int>> comm, ContactComponentOptions options,
                   SurfaceElementSource surfaceElements = makeSurfaceContactElement);
  ~ContactComponent();

  // ---- registration ----------------------------------------------------------
  /// Register surface nodes this rank owns (may be called several times).
  void registerNodes(const std::vector<ContactNode>& nodes);
  /// Register this rank's share of a pair; returns the pair index.
  int registerPair(ContactPairSurfaces pair);
  /// Collective: merge the registrations, build the slots (one per slave
  /// node, in ascending node id; owner = the slave node's owner) and the
  /// searches. Every node a facet or a slave list names must be registered
  /// by exactly one rank.
  /// \throws InputError (every rank) naming the pair and the node/facet, also
  ///         for a facet with the wrong number of nodes for its type, pairs
  ///         of different space dimensions, and a surface whose facets are
  ///         not consistently oriented (two facets running the same way
  ///         along a shared side: some normals point inwards).
  void commit();
  /// Collective, after commit(): the host DOF ids of the nodes this rank
  /// registered (every one of them) and, optionally, the host DOF id of the
  /// multiplier of each slot this rank owns (ownedSlots() order) when the
  /// host carries the multipliers in its own vector (monolithic
  /// saddle-point system); otherwise the multipliers are ids 0..numSlots−1
  /// of multiplierMap() and the host passes them to the calls that read them.
  /// \throws InputError (every rank) if a DOF id is not owned by this rank in
  ///         `hostMap`, a registered node has no DOFs, or the multipliers do
  ///         not match the owned slots, or a multiplier id is also a
  ///         registered node's DOF id or another multiplier's.
  void setDofs(Teuchos::RCP<const Map> hostMap, const std::vector<ContactNodeDofs>& nodeDofs,
               const std::vector<GO>& multiplierDofs = {});

  // ---- lifecycle -------------------------------------------------------------
  /// Pair every slave node with a master facet at the state u (host owned
  /// map; tracking from the previous pairing, a global search when
  /// `global`). With `freeze`, the decomposed element's projection ξ^p and
  /// normal n^p are taken from this configuration. Decomposed + global: the
  /// bounding-box-limited exchange, after which a slot's projection,
  /// normal and gap are current on its owner and its master facet's rank
  /// (and on every rank for a slot whose facet changed); otherwise the
  /// surface positions are gathered. One counted exchange either way.
  /// \return true if any slave changed its master facet (new topology);
  ///         the slots that did are appended to `changedSlots` when given.
  bool updatePairing(const Vector& u, bool global, bool freeze, std::vector<int>* changedSlots = nullptr);
  /// Warnings from the pairings since the last call, each once per run: a
  /// pair none of whose slave nodes has paired yet while some lie within
  /// the search radius of master facets that do not face them (a master
  /// side set facing away from or across the slave surface). The same on
  /// every rank.
  std::vector<std::string> takeWarnings();
  /// The pairs (path and side sets) none of whose slave nodes any pairing so
  /// far has paired: contact was never enforced on them.
  std::vector<std::string> neverPairedPairs() const;
  /// Per pair, 1 if some pairing so far paired a slave node: the record
  /// behind neverPairedPairs(), for a checkpoint.
  std::vector<char> pairedRecord() const;
  /// Add the record of the run a restart continues (pairedRecord() of it).
  /// \throws std::invalid_argument if it is not one entry per pair
  void addPairedRecord(const std::vector<char>& record);
  /// Activate every paired slot (Initial Contact State = In Contact), except
  /// the fully prescribed ones (fullyPrescribed()).
  void activateAllPaired();
  /// Start a step (an increment of Newton's method) from the displacements
  /// u0: the slip of frictional pairs is measured from there
  /// (DDC_Friction.hpp). Collective; nothing to do without friction.
  void beginStep(const Vector& u0);
  /// Update gaps and multipliers from (u, λ), then apply the contact-state
  /// rules: release an active slot in tension (λ > 0), activate an inactive
  /// paired slot with g_N < −tol; an active slot of a frictional pair sticks
  /// or slips by Coulomb's law (DDC_Friction.hpp), a new contact sticking.
  /// Returns the slots whose state changed (a stick/slip flip included),
  /// ascending, the same on every rank. Collective.
  /// λ: `multipliers` on multiplierMap(), or, when the host gave multiplier
  /// DOFs to setDofs(), null (read from u).
  ///
  /// Decomposed element: the owner of a slot decides it from the partial
  /// gaps summed on the multiplier map, and every rank takes the states
  /// (active, stick/slip) of the changed slots, so the active set is
  /// replicated. With `everySlot` (the default) every rank then also
  /// receives every slot's values from its owner (shareEverySlotsValues());
  /// without it only the slots whose counterparts it evaluates
  /// (ownedSlots(), localMasterSlots()):
  /// what a Newton iteration or a step's end needs, with bytes that grow
  /// with the rank's part of the contact zone, not with the surface. The
  /// other slots' values then stay as an earlier update left them: the
  /// sums over the slots (reduceSummary(), frictionalWork(),
  /// frozenGeometryError()) are taken on the owners, and a host that reads
  /// other slots' values brings them from their owners (shareSlotValues()).
  /// The conventional element gathers the surface either way, and every
  /// rank decides every slot and holds every value.
  /// \throws InputError (every rank) if a fully prescribed slot penetrates
  ///         (the message of the first such slot).
  std::vector<int> updateActiveSet(const Vector& u, const Vector* multipliers = nullptr, bool everySlot = true);
  /// Decomposed element, after the step-end pairing: the frozen-geometry
  /// error of the step, from `converged` (a copy of slots() after the
  /// step's last active-set update, before the pairing) and the slots now,
  /// summed over the slots' owners: the same numbers on every rank.
  /// Collective.
  /// \throws std::invalid_argument (every rank) if `converged` is not a
  ///         list of this component's slots
  FrozenGeometryError frozenGeometryError(const std::vector<ContactSlot>& converged) const;
  /// The work of the friction forces against the slip of a step, Σ λ_t·u_t
  /// over the active slots of `converged` (as for frozenGeometryError()),
  /// summed over the slots' owners; 0 without friction. Collective.
  /// \throws std::invalid_argument as frozenGeometryError()
  double frictionalWork(const std::vector<ContactSlot>& converged) const;
  /// Bring the values of the `wanted` slots of `slots` (a copy of slots(),
  /// or slots() itself through the host's copy, laid out alike) from their
  /// owners' copies into this rank's: the multipliers, gap, slips, normal
  /// and tangent basis an update without everySlot left current only where
  /// the slot is evaluated (updateActiveSet()). `wanted` may differ per
  /// rank (e.g. the slave nodes a rank writes, or every slot on the rank
  /// that writes a file). Nothing moves for the conventional element.
  /// Collective (two exchanges of records).
  /// \throws std::invalid_argument (every rank) if some rank's `slots` is
  ///         not a list of this component's slots or its `wanted` names a
  ///         slot that does not exist
  void shareSlotValues(std::vector<ContactSlot>& slots, const std::vector<int>& wanted) const;
  /// The bytes a rank receives per slot whose values it asks for
  /// (shareSlotValues()).
  static long sharedSlotBytes();
  /// shareSlotValues() of every slot of slots() into slots(): every rank
  /// holds every value, as after an update with everySlot (once, e.g. at
  /// the end of a run, for a host that reads them). Collective.
  void shareEverySlotsValues();
  /// Restore slots saved before a failed increment (pairing and state).
  /// \return true if the pairing differs from the current one (new topology).
  bool restoreSlots(const std::vector<ContactSlot>& saved);

  // ---- what the host assembles or solves with ---------------------------------
  /// Decomposed element: the constraint rows of every paired slot whose
  /// counterparts this rank evaluates (slave: the slots it owns; master: the
  /// slots whose master facet it registered), in host DOF ids: the gap's,
  /// and a frictional pair's slip rows as they are in stick. The
  /// coefficients are the multiplier row of each counterpart's tangent, so
  /// any registered counterpart pair works; they do not depend on the state
  /// (frozen geometry). Zero coefficients are left out.
  /// \throws std::logic_error before the first updatePairing().
  std::vector<ContactRowEntry> contactRows() const;
  /// Decomposed element: whether slip row `alpha` (0-based tangent
  /// direction) of frictional slot k has its every displacement coefficient
  /// on a prescribed DOF, so its multiplier is restrained to zero and the
  /// row is no constraint (replicated data: any rank, not collective).
  bool slipRowHeld(int k, int alpha) const;
  /// The linearised slip rows of frictional slot k as it slips
  /// (frictionRows() of DDC_Friction.hpp), at the multipliers and slip of
  /// the last updateActiveSet() or beginStep(), the state the elements
  /// assemble with (replicated data: any rank, not collective).
  FrictionRows slipLinearisation(int k) const;
  /// Every contact contribution evaluated on this rank at (u, λ) — the
  /// conventional element of each owned slot, or the two counterparts where
  /// they live; a released or unpaired slot contributes Π = ½λ² on its
  /// multiplier — handed to `add` with its DOF ids (host ids; the
  /// multiplier last, its id as in multiplierMap()). `what` as for elements;
  /// the tangent is always computed.
  /// \throws std::logic_error before the first updatePairing().
  void assemble(const Vector& u, const Vector* multipliers, unsigned what,
                const std::function<void(const std::vector<GO>& dofs, ElementResult& result)>& add) const;

  // ---- queries ---------------------------------------------------------------
  /// Whether the decomposed counterparts are used (options().decomposed).
  bool decomposed() const;
  /// The options given to the constructor.
  const ContactComponentOptions& options() const;
  /// Number of registered pairs.
  int numPairs() const;
  /// Every slot (one per slave node of every pair), replicated on every
  /// rank: the pairing and the states are the same everywhere; the values
  /// are current where the slot is evaluated (updateActiveSet()).
  const std::vector<ContactSlot>& slots() const;
  /// Owner rank of slot k (the owner of its slave node).
  int slotOwner(int k) const;
  /// Slots this rank owns, ascending (the order of multiplierMap()).
  const std::vector<int>& ownedSlots() const;
  /// Decomposed: paired slots whose master counterpart this rank evaluates.
  const std::vector<int>& localMasterSlots() const;
  /// This rank's multipliers, one per owned slot: a one-to-one map.
  Teuchos::RCP<const Map> multiplierMap() const;
  /// Multiplier c of slot k (host DOF id when the host gave them): c = 0 the
  /// normal λ_n, 1..dim−1 a frictional pair's tangential λ_t.
  GO multiplierId(int k, int c = 0) const;
  /// The multipliers of slot k: 1, or dim in a frictional pair (μ > 0).
  int numMultipliers(int k) const;
  /// Whether some pair has friction.
  bool frictional() const;
  /// Host DOF ids of the DOFs of the conventional element of slot k
  /// ([u_s, u_1, ..., u_m, λ]; [λ] when unpaired) and of the decomposed
  /// counterparts ([u_s, λ] / [u_1, ..., u_m, λ]); λ stands for all the
  /// slot's multipliers (numMultipliers()).
  std::vector<GO> slotDofs(int k) const;
  /// The slave counterpart's DOF ids of slot k ([u_s, λ]).
  std::vector<GO> slaveSideDofs(int k) const;
  /// The master counterpart's DOF ids of slot k ([u_1, ..., u_m, λ]).
  std::vector<GO> masterSideDofs(int k) const;
  /// True if slot k is paired and all DOFs of its slave node and master
  /// facet are prescribed: its gap is given, contact cannot act on it.
  bool fullyPrescribed(int k) const;
  /// Host node ids of every surface node (slave or master), ascending.
  const std::vector<int>& surfaceNodes() const;
  /// Whether host node `id` is a registered surface node.
  bool isSurfaceNode(int id) const;
  /// Reference coordinates of a surface node (z = 0 in 2-D).
  Eigen::Vector3d referencePosition(int id) const;
  /// The host DOF id of component c of surface node `id` (known on every
  /// rank after setDofs(), as the rows of a slot need it).
  /// \throws std::out_of_range if `id` is no surface node
  GO surfaceNodeDof(int id, int c) const;
  /// Space dimension of the contact surfaces (2 or 3; known after commit()).
  int dim() const;
  /// Active slots (replicated) and the resultant contact force, summed over
  /// the slots' owners: the same on every rank. Collective.
  ContactSummary reduceSummary() const;
  /// The active paired slots (replicated data: any rank, not collective).
  int numActive() const;
  /// "pair 'P' slave node n at (x, y[, z])" for messages.
  std::string describeSlot(int k) const;
  /// The pair's registered name (messages).
  const std::string& pairName(int p) const;
  /// Contact-geometry exchanges (every pairing update, and for conventional
  /// NTS every active-set update) since construction, and the bytes they
  /// moved between ranks.
  long exchanges() const;
  /// Bytes the exchanges() moved between ranks (see exchanges()).
  long bytesExchanged() const;
  /// Decomposed element: the bytes this rank received in the active-set
  /// updates since construction (the displacements and multipliers at the
  /// counterparts, the partial gaps at the owners, the summed gaps and
  /// slips and the multipliers back, and the other ranks' changed states;
  /// see updateActiveSet()): {in the updates without everySlot, with it}.
  std::array<long, 2> valueBytesReceived() const;
  /// Decomposed element: the active-set updates since construction,
  /// {without everySlot, with it} (the same on every rank).
  std::array<long, 2> valueUpdates() const;
  /// Search work summed over the pairs: {tracking queries, tracking fallbacks, global queries}.
  std::array<long, 3> searchCounters() const;

  /// After the initial pairing: a slave node that starts inside the master
  /// body of its pair and is not paired (farther than the search radius from
  /// the master surface, or rejected by the facing rule) can never be pushed
  /// out. `locate[p]` returns the host's id of an element of pair p's master
  /// body that this rank holds and that contains a reference point (dim()
  /// coordinates), or −1 (e.g. BodyLocator::elementContaining; an empty
  /// function skips the pair); the ranks agree on the lowest id.
  /// If no unpaired slave node of a pair is inside, a node on the master
  /// body's boundary counts as inside if a point of `inward(p, node)` is:
  /// points of the slave body next to the node (e.g. halfway to the
  /// centroids of its elements there; none for a pair of two surfaces of one
  /// body, whose slave body is the master body), so that a slave body
  /// lying in the master body with its nodes on the master's far surface (a
  /// body one element across) is found; an empty function: the nodes only
  /// (doc/contact.md, "Which slave nodes pair").
  /// `inward` gives every rank the same points. Collective: the same
  /// verdict on every rank.
  /// \throws InputError naming the pair, the node, the depth and why.
  void checkInitialPenetration(const std::vector<std::function<int(const Eigen::VectorXd&)>>& locate,
                               const std::function<std::vector<Eigen::VectorXd>(int, int)>& inward = {}) const;

 private:
  std::unique_ptr<ContactTopology> topology_;
  std::unique_ptr<ContactPairing> pairing_;
};

}  // namespace ddc
