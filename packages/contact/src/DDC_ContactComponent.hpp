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
// owner, and every contact slot (one per slave node: its pairing, state,
// frozen projection and normal) — the same numbers on every rank. Field
// values (displacements, multipliers) stay distributed in the host's map and
// move only in the counted exchanges (exchanges(), bytesExchanged()):
//  - conventional element: the surface positions are gathered to every rank
//    at each pairing and active-set update;
//  - decomposed element: at step ends the owner of each slave node searches
//    over the master-surface nodes the other ranks send it because they lie
//    in its bounding box (one exchange); the contact state is checked on the
//    multiplier map (partial gaps of the two counterparts summed there), with
//    no geometry moving (doc/contact.md).
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
#pragma once

#include <Eigen/Dense>
#include <Teuchos_Comm.hpp>
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "DDC_ContactState.hpp"
#include "DDC_DecomposedNodeToSurface.hpp"
#include "DDC_FacetSearch.hpp"
#include "DDC_ReferenceCell.hpp"
#include "DDC_SurfaceContactElement.hpp"
#include "DDC_TpetraTypes.hpp"

namespace ddc {

/// One contact slot: a slave node of a pair, its multiplier, and its
/// current pairing and state. Replicated on every rank.
struct ContactSlot {
  /// Most nodes a master facet has (Quad9).
  static constexpr int kMaxFacetNodes = 9;
  int pair = 0;              ///< the pair (registration order)
  int slaveNode = -1;        ///< host node id
  /// The master facet's nodes (host node ids, facet node order; the first
  /// numMaster are used); master[0] = -1: not paired.
  std::array<int, kMaxFacetNodes> master{{-1, -1, -1, -1, -1, -1, -1, -1, -1}};
  int numMaster = 0;         ///< nodes of the master facet (0: not paired)
  int segment = -1;          ///< index of that facet in the pair's master surface (-1: not paired)
  int masterElement = -1;    ///< the host element whose facet it is (-1: not paired)
  bool active = false;       ///< in the active set (the constraint g_N = 0 is enforced)
  /// The multiplier λ (state.multiplier; λ < 0 in compression) and the
  /// state handed to the elements (state.frozenXi/frozenNormal are unused).
  ContactPairState state;
  /// The frozen projection ξ^p (reference coordinates of the master facet)
  /// and normal n^p of the decomposed counterparts, from the last pairing
  /// with freeze (paper eq. 1).
  FrozenFacetProjection frozen;
  double gap = 0.0;          ///< g_N at the last update
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< normal used by the element (z = 0 in 2-D)
  /// The slave node's share of the slave surface in the reference
  /// configuration: a length in 2-D (half the adjacent slave segments), an
  /// area in 3-D (doc/contact.md, "Curved facets and 3-D").
  double tributaryLength = 0.0;
  /// Contact pressure −λ / tributary length (> 0 in compression), 0 when inactive.
  double pressure() const { return active && tributaryLength > 0 ? -state.multiplier / tributaryLength : 0.0; }
  /// Whether the slot has a master facet.
  bool paired() const { return master[0] >= 0; }
};

/// The slots as numbers, for a checkpoint (every field; integers exactly).
std::vector<double> packSlots(const std::vector<ContactSlot>& slots);
/// The slots packSlots() gave.
/// \throws std::invalid_argument if `packed` is not a whole number of slots
std::vector<ContactSlot> unpackSlots(const std::vector<double>& packed);

/// Summary of the contact state for output.
struct ContactSummary {
  int active = 0;  ///< active slots
  double force[3] = {0.0, 0.0, 0.0};  ///< resultant contact force on the slave bodies, Σ -λ n (z = 0 in 2-D)
};

/// A contact-surface node, registered by the rank that owns its DOFs.
struct ContactNode {
  int id = -1;                  ///< the host's node id (≥ 0, unique)
  Eigen::Vector3d X = Eigen::Vector3d::Zero();  ///< reference coordinates (z = 0 in 2-D)
  ContactNode() = default;
  /// A 2-D node (z = 0).
  ContactNode(int id_, const Eigen::Vector2d& X2) : id(id_), X(X2.x(), X2.y(), 0.0) {}
  /// A 3-D node.
  ContactNode(int id_, const Eigen::Vector3d& X3) : id(id_), X(X3) {}
};

/// The DOFs of a registered node (setDofs()).
struct ContactNodeDofs {
  int id = -1;                     ///< a node this rank registered
  /// Host DOF ids of u_x, u_y (, u_z in 3-D), owned here in the host's map;
  /// entries past the space dimension are not read.
  std::array<GO, 3> dofs{{-1, -1, -1}};
  /// The DOF is prescribed (a Dirichlet condition): a pair whose DOFs are
  /// all prescribed has a given gap and never becomes active.
  std::array<bool, 3> prescribed{{false, false, false}};
};

/// A facet of a contact surface, registered by the rank that evaluates its
/// element.
struct ContactFacet {
  long id = -1;  ///< position of the facet in its surface: orders the facets (search tie-breaks), unique per surface
  /// Host node ids in the facet type's node order (DDC_ReferenceCell.hpp),
  /// oriented outward: in 2-D with the body on the left of nodes[0] →
  /// nodes[1], in 3-D counter-clockwise seen from outside.
  std::vector<int> nodes;
  int element = -1;    ///< host element id (messages; ContactSlot::masterElement)
  int subdomain = -1;  ///< host subdomain of the element: the label of the master counterpart's rows
  /// Master facets: depth of the element behind the facet (> 0; the facing
  /// rule, doc/contact.md "Which slave nodes pair", masterElementDepths()).
  double depth = 0.0;
};

/// One contact pair as this rank registers it: its share of the facets and
/// slave nodes (every rank registers the same pairs in the same order; the
/// shares are merged in commit()).
struct ContactPairSurfaces {
  std::string name;        ///< short name: "pair 'name' slave node ..." (describeSlot())
  std::string path;        ///< where the host defined it (e.g. a parameter path), for errors; default: name
  std::string slaveName;   ///< the slave surface, for messages
  std::string masterName;  ///< the master surface, for messages
  /// Cell type of the slave facets (Line2, Line3, Tri3, Tri6, Quad4, Quad8, Quad9).
  CellType slaveFacetType = CellType::Line2;
  /// Cell type of the master facets (the same choice).
  CellType masterFacetType = CellType::Line2;
  std::vector<int> slaveNodes;  ///< candidate slave nodes; nodes on the master surface are skipped
  std::vector<ContactFacet> slaveFacets;   ///< oriented with the slave body on the left
  std::vector<ContactFacet> masterFacets;  ///< with depth
};

/// Options of the component (resolved values, not parameter names).
struct ContactComponentOptions {
  /// false: conventional nonlinear NTS (one element per pair, projection and
  /// normal follow the current configuration); true: the decomposed slave and
  /// master counterparts with projection and normal frozen over each step.
  bool decomposed = false;
  double searchRadius = 0.0;          ///< absolute, > 0
  double penetrationTolerance = 0.0;  ///< absolute: activate when g_N < -tol
};

/// One coefficient of a contact constraint row (decomposed element): the
/// pair's frozen gap is g_N = Σ coefficient · x(dof) over its entries.
struct ContactRowEntry {
  int slot = -1;       ///< the contact slot (replicated index)
  GO row = -1;         ///< its multiplier id (multiplierMap())
  GO dof = -1;         ///< host DOF id
  double coefficient = 0.0;  ///< multiplies the position x = X + u of that DOF
  /// The counterpart the entry comes from: SurfaceContactRole::Slave or
  /// SurfaceContactRole::Master.
  SurfaceContactRole role = SurfaceContactRole::Slave;
  int subdomain = -1;   ///< master: the master facet's subdomain; slave: -1 (any subdomain holding the slave node)
};

/// The frozen-geometry error of a converged step of the decomposed element
/// in energy units (per unit thickness in 2-D): ContactComponent::
/// frozenGeometryError(), doc/contact.md "Step control by the
/// frozen-geometry error".
struct FrozenGeometryError {
  /// |Σ λ (g − g^p)| over the slots active at convergence: the gap g^p = 0
  /// the step enforced against the gap g of the updated projection.
  double gapWork = 0.0;
  /// Σ |λ| |n − n^p| s over the same slots: the force the frozen normal n^p
  /// puts across the updated normal n, over the slip s of the contact point
  /// along the master surface in the step (reference lengths).
  double normalWork = 0.0;
  /// The indicator: gapWork + normalWork.
  double total() const { return gapWork + normalWork; }
};

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
  /// bounding-box-limited exchange; otherwise the surface positions are
  /// gathered. One counted exchange either way.
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
  /// Update gaps and multipliers from (u, λ), then apply the contact-state
  /// rules: release an active slot in tension (λ > 0), activate an inactive
  /// paired slot with g_N < −tol. Returns the slots whose state changed.
  /// λ: `multipliers` on multiplierMap(), or, when the host gave multiplier
  /// DOFs to setDofs(), null (read from u).
  /// \throws InputError (every rank: the slots are replicated) if a fully
  ///         prescribed slot penetrates.
  std::vector<int> updateActiveSet(const Vector& u, const Vector* multipliers = nullptr);
  /// Decomposed element, after the step-end pairing: the frozen-geometry
  /// error of the step, from `converged` (the slots after the step's last
  /// active-set update, before the pairing) and the slots now. Replicated
  /// data: the same numbers on every rank, no exchange, not collective.
  /// \throws std::invalid_argument if `converged` is not a list of this
  ///         component's slots
  FrozenGeometryError frozenGeometryError(const std::vector<ContactSlot>& converged) const;
  /// Restore slots saved before a failed increment (pairing and state).
  /// \return true if the pairing differs from the current one (new topology).
  bool restoreSlots(const std::vector<ContactSlot>& saved);

  // ---- what the host assembles or solves with ---------------------------------
  /// Decomposed element: the constraint row of every paired slot whose
  /// counterparts this rank evaluates (slave: the slots it owns; master: the
  /// slots whose master facet it registered), in host DOF ids. The
  /// coefficients are the multiplier row of each counterpart's tangent, so
  /// any registered counterpart pair works; they do not depend on the state
  /// (frozen geometry). Zero coefficients are left out.
  /// \throws std::logic_error before the first updatePairing().
  std::vector<ContactRowEntry> contactRows() const;
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
  bool decomposed() const { return options_.decomposed; }
  /// The options given to the constructor.
  const ContactComponentOptions& options() const { return options_; }
  /// Number of registered pairs.
  int numPairs() const;
  /// Every slot (one per slave node of every pair), replicated on every rank.
  const std::vector<ContactSlot>& slots() const { return slots_; }
  /// Owner rank of slot k (the owner of its slave node).
  int slotOwner(int k) const;
  /// Slots this rank owns, ascending (the order of multiplierMap()).
  const std::vector<int>& ownedSlots() const { return localSlots_; }
  /// Decomposed: paired slots whose master counterpart this rank evaluates.
  const std::vector<int>& localMasterSlots() const { return localMasterSlots_; }
  /// This rank's multipliers, one per owned slot: a one-to-one map.
  Teuchos::RCP<const Map> multiplierMap() const { return multiplierMap_; }
  /// Multiplier id of slot k (host DOF id when the host gave them).
  GO multiplierId(int k) const { return lmGid_[k]; }
  /// Host DOF ids of the DOFs of the conventional element of slot k
  /// ([u_s, u_1, ..., u_m, λ]; [λ] when unpaired) and of the decomposed
  /// counterparts ([u_s, λ] / [u_1, ..., u_m, λ]).
  std::vector<GO> slotDofs(int k) const;
  /// The slave counterpart's DOF ids of slot k ([u_s, λ]).
  std::vector<GO> slaveSideDofs(int k) const;
  /// The master counterpart's DOF ids of slot k ([u_1, ..., u_m, λ]).
  std::vector<GO> masterSideDofs(int k) const;
  /// True if slot k is paired and all DOFs of its slave node and master
  /// facet are prescribed: its gap is given, contact cannot act on it.
  bool fullyPrescribed(int k) const;
  /// Host node ids of every surface node (slave or master), ascending.
  const std::vector<int>& surfaceNodes() const { return nodeIds_; }
  /// Whether host node `id` is a registered surface node.
  bool isSurfaceNode(int id) const { return index(id) >= 0; }
  /// Reference coordinates of a surface node (z = 0 in 2-D).
  Eigen::Vector3d referencePosition(int id) const;
  /// Space dimension of the contact surfaces (2 or 3; known after commit()).
  int dim() const { return dim_; }
  /// Active slots and the resultant contact force, from the replicated slots
  /// (the same on every rank; not collective).
  ContactSummary summary() const;
  /// "pair 'P' slave node n at (x, y[, z])" for messages.
  std::string describeSlot(int k) const;
  /// The pair's registered name (messages).
  const std::string& pairName(int p) const;
  /// Contact-geometry exchanges (every pairing update, and for conventional
  /// NTS every active-set update) since construction, and the bytes they
  /// moved between ranks.
  long exchanges() const { return exchanges_; }
  /// Bytes the exchanges() moved between ranks (see exchanges()).
  long bytesExchanged() const { return bytesExchanged_; }
  /// Search work summed over the pairs: {tracking queries, tracking fallbacks, global queries}.
  std::array<long, 3> searchCounters() const;

  /// After the initial pairing: a slave node that starts inside the master
  /// body of its pair and is not paired (farther than the search radius from
  /// the master surface, or rejected by the facing rule) can never be pushed
  /// out. `locate[p]` returns the element of pair p's master body containing
  /// a reference point (dim() coordinates), or −1 (e.g.
  /// BodyLocator::elementContaining; an empty function skips the pair).
  /// Replicated data: the same verdict on every rank.
  /// \throws InputError naming the pair, the node, the depth and why.
  void checkInitialPenetration(const std::vector<std::function<int(const Eigen::VectorXd&)>>& locate) const;

 private:
  struct Pair;
  struct Field;
  struct Found;
  int index(int id) const;
  /// Current position of a surface node from gathered surface values (dim_ per node; z = 0 in 2-D).
  Eigen::Vector3d currentPosition(int id, const std::vector<double>& surfaceValues) const;
  void gatherSurface(const Vector& u, const Vector* multipliers, std::vector<double>& values) const;
  void refreshSlotGeometry(const std::vector<double>& surfaceValues);
  /// After a pairing: the per-pair record behind takeWarnings() and
  /// neverPairedPairs().
  void notePairing(const std::vector<std::vector<Found>>& found);
  /// Decomposed step-end pairing: the bounding-box-limited exchange and the
  /// search of the owners of the slave nodes (one exchange).
  void distributedSearch(const Vector& u, std::vector<std::vector<Found>>& found);
  template <int D>
  void distributedSearchIn(const Vector& u, std::vector<std::vector<Found>>& found);
  /// The surface contact element of `role` on `facet` (commit() fetched it).
  const SurfaceContactElement& surfaceElement(SurfaceContactRole role, CellType facet) const;
  /// The pairing of every pair's slaves from replicated positions.
  void replicatedSearch(const std::function<Eigen::Vector3d(int)>& position, bool global,
                        std::vector<std::vector<Found>>& found);
  /// Facet pairs: the pairing of `slaves` over `facets` (indices into the
  /// pair's master facets) at `position`, with the facing rule and the
  /// free-boundary rule (doc/contact.md, "Curved facets and 3-D").
  std::vector<Found> facetPairing(const Pair& pair, FacetSearch& search, const std::vector<int>& facets,
                                  const std::vector<int>& slaves,
                                  const std::function<Eigen::Vector3d(int)>& position) const;
  /// Facet pairs: the slave node's outward normal (normalised sum of its
  /// slave facets' normals there; zero if they cancel).
  Eigen::Vector3d slaveNormal(const Pair& pair, int node, const std::function<Eigen::Vector3d(int)>& position) const;
  /// Node positions of facet f of a pair's master surface (numNodes x dim_).
  Eigen::MatrixXd facetPositions(const Pair& pair, int f, const std::function<Eigen::Vector3d(int)>& position) const;
  void assembleFrozenGaps(const Vector& u, const Vector* multipliers);
  void buildTopology();
  /// Field values at this rank's counterpart DOFs and multipliers.
  Field gatherField(const Vector& u, const Vector* multipliers) const;
  /// The element of `role` on slot k at the field f (a released slot unless
  /// forceActive); dofs: its DOF ids, the multiplier last.
  void evaluate(int k, SurfaceContactRole role, const Field& f, bool forceActive, unsigned what, ElementResult& er,
                std::vector<GO>& dofs) const;
  void requireCommitted(const char* what) const;
  /// Throws std::logic_error before the first updatePairing() (nothing is
  /// paired: rows and contributions would be silently empty).
  void requirePaired(const char* what) const;
  /// Throws std::logic_error unless the host gave multiplier DOFs to setDofs().
  void requireHostMultipliers() const;
  void appendNodeDofs(int node, std::vector<GO>& dofs) const;

  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  ContactComponentOptions options_;
  SurfaceElementSource surfaceSource_;
  std::map<std::pair<SurfaceContactRole, CellType>, std::shared_ptr<const SurfaceContactElement>> surfaceElements_;
  bool committed_ = false, hasDofs_ = false, multipliersInHost_ = false;
  int dim_ = 2;

  std::vector<ContactNode> myNodes_;  ///< registered here, before commit()
  std::vector<Pair> pairs_;
  bool pairedOnce_ = false;  ///< updatePairing() has run (requirePaired())
  std::vector<char> everPaired_;      ///< per pair: some slave node has paired (neverPairedPairs())
  std::vector<char> facingReported_;  ///< per pair: the facing warning was given
  std::vector<std::string> warnings_;  ///< takeWarnings()
  // Surface nodes after commit(), ascending id: replicated.
  std::vector<int> nodeIds_;
  std::vector<Eigen::Vector3d> X_;
  std::vector<int> owner_;
  std::vector<std::array<GO, 3>> dofs_;
  std::vector<std::array<char, 3>> prescribed_;

  std::vector<ContactSlot> slots_;
  std::vector<int> slotOwner_;
  std::vector<GO> lmGid_;
  std::vector<int> localSlots_, localMasterSlots_;
  std::vector<std::pair<int, int>> slaveNeighbourSends_;  ///< decomposed: (owned slave-surface node, rank needing it)
  std::vector<int> masterSurfaceNodes_;  ///< nodes of the master surfaces (may repeat across pairs)
  double pairingMargin_ = 0.0;

  Teuchos::RCP<const Map> hostMap_;
  Teuchos::RCP<const Map> surfaceMap_;    ///< replicated: every surface DOF
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> surfaceImporter_;
  Teuchos::RCP<const Map> multiplierMap_, multiplierAllMap_;
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> lmAllImporter_;  ///< multiplierMap_ -> multiplierAllMap_
  Teuchos::RCP<const Map> dofOverlapMap_;  ///< host DOFs of this rank's counterparts / elements
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> dofImporter_;
  Teuchos::RCP<const Map> lmOverlapMap_;   ///< multipliers of this rank's counterparts
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> lmImporter_;      ///< multiplierMap_ -> lmOverlapMap_
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> lmHostImporter_;  ///< hostMap_ -> lmOverlapMap_ (host multipliers)
  Teuchos::RCP<const Tpetra::Export<LO, GO, Node>> lmExporter_;      ///< lmOverlapMap_ -> multiplierMap_
  long distributedQueries_ = 0;
  mutable long exchanges_ = 0, bytesExchanged_ = 0;
  long bytesPerExchange_ = 0;
};

}  // namespace ddc
