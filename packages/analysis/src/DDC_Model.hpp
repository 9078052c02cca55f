// The discrete model: replicated mesh, element evaluators per body, element
// partition, distributed DOF numbering (nodes and contact multipliers),
// boundary conditions, contact pairing / active set, and assembly of the
// global residual and tangent (a distributed Tpetra::CrsMatrix).
#pragma once

#include <Teuchos_Comm.hpp>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "DDC_BoundaryConditions.hpp"
#include "DDC_ContactElement.hpp"
#include "DDC_ContactParameters.hpp"
#include "DDC_ContactSearch.hpp"
#include "DDC_DirectSolver.hpp"
#include "DDC_Element.hpp"
#include "DDC_FetiDpSolver.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_Partition.hpp"

namespace ddc {

class ContactSearch;
struct ContactCandidate;
struct SubdomainSystem;

/// Where assemble() also puts element tangents: the local stiffness of each
/// subdomain (FETI-DP), with `where[e]` = (system index, element position in
/// that system) for this rank's elements.
struct SubdomainSink {
  std::vector<SubdomainSystem>* systems = nullptr;
  std::vector<std::pair<int, int>> where;
};

/// Results of one assembly.
struct AssemblyResult {
  double strainEnergy = 0.0;  ///< Σ U_e over the continuum elements (global)
};

/// One contact slot: a slave node of a pair, its multiplier DOF, and its
/// current pairing and state. Replicated on every rank.
struct ContactSlot {
  int pair = 0;
  int slaveNode = -1;
  int master[2] = {-1, -1};  ///< master segment nodes; -1: not paired
  int segment = -1;          ///< index of that segment in the pair's master surface (-1: not paired)
  int masterElement = -1;    ///< the element whose side the master segment is (-1: not paired)
  bool active = false;
  ContactPairState state;    ///< multiplier, frozen ξ^p / n^p
  double gap = 0.0;          ///< g_N at the last update
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();  ///< normal used by the element
  double tributaryLength = 0.0;  ///< half the reference length of the adjacent slave segments
  /// Contact pressure −λ / tributary length (> 0 in compression), 0 when inactive.
  double pressure() const { return active && tributaryLength > 0 ? -state.multiplier / tributaryLength : 0.0; }
  bool paired() const { return master[0] >= 0; }
};

/// Summary of the contact state for output.
struct ContactSummary {
  int active = 0;
  double force[2] = {0.0, 0.0};  ///< resultant contact force on the slave bodies, Σ -λ n
};

/// The discrete model shared by every strategy. Each rank holds the whole
/// mesh and evaluates the elements of the subdomains it owns. Nodes are
/// owned by the lowest rank among the elements that touch them; a contact
/// multiplier by the owner of its slave node. Each rank's owned DOFs (its
/// nodes' DOFs, then its multipliers) form a contiguous range, so the owned
/// DOF map is contiguous (what MUMPS needs).
class Model {
 public:
  /// \param elements one evaluator per body (index = body index)
  /// \param contactElements evaluators by name: "Node-To-Segment" or the
  ///        pair "Decomposed NTS Slave" / "Decomposed NTS Master" (only the
  ///        ones the formulation needs)
  Model(Teuchos::RCP<const Teuchos::Comm<int>> comm, std::shared_ptr<const Mesh> mesh,
        std::vector<std::shared_ptr<const Element>> elements, Partition partition, BoundaryConditions bcs,
        ContactOptions contact = {}, std::vector<std::shared_ptr<const ContactElement>> contactElements = {});
  ~Model();

  const Mesh& mesh() const { return *mesh_; }
  /// Spatial dimension (the mesh's): the number of DOFs of every node.
  int dim() const { return mesh_->dim(); }
  const Partition& partition() const { return partition_; }
  const Teuchos::RCP<const Teuchos::Comm<int>>& comm() const { return comm_; }
  int subdomainRank(int s) const { return subdomainRank_[s]; }
  const std::vector<int>& localElements() const { return localElements_; }

  Teuchos::RCP<const Map> ownedMap() const { return ownedMap_; }
  Teuchos::RCP<const Map> overlapMap() const { return overlapMap_; }
  /// Global DOF id of component c of mesh node n.
  GO dof(int n, int c) const { return nodeDof_[n] + c; }
  /// Global DOF id of the multiplier of contact slot k.
  GO multiplierDof(int k) const { return lmDof_[k]; }
  bool isConstrained(GO g) const { return constrained_[g] != 0; }

  Teuchos::RCP<Vector> createVector() const;
  /// A matrix with the current sparsity pattern (changes with the pairing:
  /// see topologyVersion()).
  Teuchos::RCP<CrsMatrix> createMatrix() const;
  /// Incremented whenever the sparsity pattern changes (new contact pairing).
  int topologyVersion() const { return topologyVersion_; }

  void applyPrescribed(double lambda, Vector& u) const;
  void prescribedIncrement(double lambda0, double lambda, Vector& du) const;

  /// Assemble at the state u (owned layout, multipliers included):
  ///  - fint: ∂(U + Π_c)/∂u, all DOFs, unmodified (reactions live there);
  ///  - residual r = fint − λ f_ext on free DOFs, 0 on prescribed DOFs, plus
  ///    K·prescribedStep if given (consistent predictor of a prescribed
  ///    increment in the first iteration);
  ///  - K: tangent with rows/columns of prescribed DOFs replaced by the identity.
  /// \throws InadmissibleDeformation on every rank if det F <= 0 anywhere.
  /// With `subdomains`, element tangents (free DOFs only) are also summed
  /// into the subdomain stiffness matrices (zeroed first).
  AssemblyResult assemble(const Vector& u, double lambda, Vector* fint, Vector* residual, CrsMatrix* K,
                          const Vector* prescribedStep = nullptr, SubdomainSink* subdomains = nullptr) const;

  const Vector& externalForce() const { return *fext_; }
  Teuchos::RCP<Vector> toOverlap(const Vector& owned) const;
  const Element& elementOf(int e) const { return *elements_[mesh_->elementBody(e)]; }

  // ---- contact ---------------------------------------------------------------
  bool hasContact() const { return !slots_.empty(); }
  /// Decomposed contact in use: Contact/Formulation = Decomposed
  /// Node-To-Segment *and* at least one pair. With no pairs the formulation
  /// is moot and the model is a plain one (no multiplier maps exist); test
  /// this, never contactOptions().decomposed alone.
  bool decomposedContact() const { return decomposed_; }
  const ContactOptions& contactOptions() const { return contact_; }
  const std::vector<ContactSlot>& contactSlots() const { return slots_; }
  /// Pair every slave node with a master segment at the state u (tracking
  /// from the previous pairing; global search when `global`). With
  /// `freeze`, the projection ξ^p and normal n^p of the decomposed element
  /// are taken from this configuration. Collective: surface positions are
  /// gathered to every rank (one exchange, counted in exchanges()).
  /// \return true if any slave changed its master segment (new topology);
  ///         false without contact (nothing to pair). The slots that did
  ///         are appended to `changedSlots` when given.
  bool updatePairing(const Vector& u, bool global, bool freeze, std::vector<int>* changedSlots = nullptr);
  /// Activate every paired slot (Initial Contact State = In Contact), except
  /// the fully prescribed ones (see fullyPrescribed()).
  void activateAllPaired();
  /// True if slot k is paired and all DOFs of its slave node and master
  /// segment are prescribed: its gap is given, contact cannot act on it.
  bool fullyPrescribed(int k) const;
  /// Update gaps and multipliers from u, then apply the active-set rules:
  /// release an active slot in tension (λ > 0), activate an inactive paired
  /// slot with g_N < -tol. Returns the slots whose state changed.
  /// \throws InputError (on every rank: the slots are replicated) if a fully
  ///         prescribed slot penetrates.
  /// Conventional NTS: gaps from the gathered surface positions (a geometry
  /// exchange). Decomposed: the frozen gap is assembled on the multiplier
  /// map from the partial gaps of the slave and master counterparts,
  /// evaluated where they live; only multiplier-map values (gap, λ per
  /// slot) move between ranks, no geometry.
  /// Without contact: nothing to do, returns no slots.
  std::vector<int> updateActiveSet(const Vector& u);
  /// Decomposed contact in FETI-DP: the constraint row of every contact slot
  /// (row id = the slot's multiplier DOF), split into the entries of the
  /// subdomains on this rank: the slave counterpart's coefficients in a
  /// subdomain having the slave node, the master counterpart's in the
  /// subdomain of the master segment's element. Prescribed DOFs have no
  /// entry (their part of the gap is in the residual). Coefficients are the
  /// multiplier row of each counterpart's tangent, so any registered
  /// counterpart pair works.
  std::vector<std::vector<ConstraintEntry>> contactRowEntries(const std::vector<SubdomainSystem>& systems) const;
  /// This rank's multiplier DOFs (one per slot whose slave node it owns), in
  /// slot order; a one-to-one map. Null without contact.
  Teuchos::RCP<const Map> multiplierMap() const { return multiplierMap_; }
  /// Slots whose multiplier this rank owns, in the order of multiplierMap().
  const std::vector<int>& ownedSlots() const { return localSlots_; }
  /// 1 for nodes on a contact surface (slave or master).
  bool isContactSurfaceNode(int n) const { return !surfaceIndex_.empty() && surfaceIndex_[n] >= 0; }
  ContactSummary contactSummary() const;
  /// Restore slots saved before a failed increment (pairing and state);
  /// rebuilds the topology if the pairing differs.
  void restoreContactState(const std::vector<ContactSlot>& saved);
  /// "pair 'P' slave node n at (x, y)" for messages.
  std::string describeSlot(int k) const;
  /// Collective. Where a vector of the owned layout (a residual or a
  /// correction) first goes wrong, for the failure message of a Newton
  /// iteration: its non-finite entry of smallest global id, or, if every
  /// entry is finite (the norm overflowed), its entry of largest magnitude;
  /// named by node, component, coordinates, body, element and material
  /// (parameters that are non-finite or extreme flagged: see
  /// doc/user-guide.md, "Solution method"), or by contact slot. The same
  /// text on every rank; "" if the vector is finite and its norm is too.
  std::string describeNonFinite(const Vector& v) const;
  /// Contact-geometry exchanges (gathers of surface positions: every pairing
  /// update, and for conventional NTS every active-set update) since
  /// construction; search counters.
  long exchanges() const { return exchanges_; }
  /// Search work summed over the pairs: {tracking queries, tracking fallbacks, global queries}.
  std::array<long, 3> searchCounters() const;
  long bytesExchanged() const { return bytesExchanged_; }

 private:
  void buildDofNumbering();
  void buildConstraints();
  void buildTopology();
  void assembleTractions();
  /// DOF lists of one element / contact slot (global ids).
  void elementDofs(int e, std::vector<GO>& dofs) const;
  void slotDofs(int k, std::vector<GO>& dofs) const;
  /// Decomposed: DOFs of the slave counterpart [u_s, λ] / master counterpart [u_1, u_2, λ].
  void slaveSideDofs(int k, std::vector<GO>& dofs) const;
  void masterSideDofs(int k, std::vector<GO>& dofs) const;
  /// Decomposed: evaluate one counterpart of slot k at the overlap state `ud`.
  void evaluateCounterpart(int k, bool master, const Teuchos::ArrayRCP<const double>& ud, bool forceActive,
                           unsigned what, ElementResult& er, std::vector<LO>& lids) const;
  int slotOwner(int k) const { return nodeOwner_[slots_[k].slaveNode]; }
  /// Gather surface displacements and multipliers to every rank.
  void gatherSurface(const Vector& u, std::vector<double>& values) const;
  Eigen::Vector2d currentPosition(int node, const std::vector<double>& surfaceValues) const;
  void refreshSlotGeometry(const std::vector<double>& surfaceValues);
  /// Decomposed, at step ends: the global search for this rank's slave
  /// nodes over the master-surface nodes that the other ranks send it
  /// because they lie in its slaves' bounding box (inflated by
  /// pairingMargin_); every slot's result then goes to every rank. One
  /// exchange, counted with its bytes.
  void distributedSearch(const Vector& u, std::vector<std::vector<ContactCandidate>>& cands,
                         std::vector<std::vector<char>>& pastFreeEnd);
  /// After the initial pairing: a slave node that starts inside the master
  /// body of its pair and is not paired (farther than the search radius
  /// from the master surface, or rejected by the facing rule) can never be
  /// pushed out; throws InputError naming the pair, the node and the depth
  /// (replicated data: the same on every rank).
  void checkInitialPenetration() const;
  /// Decomposed: g_N and λ of every slot from the counterparts (see updateActiveSet()).
  void assembleFrozenGaps(const Vector& u);

  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::shared_ptr<const Mesh> mesh_;
  std::vector<std::shared_ptr<const Element>> elements_;
  Partition partition_;
  BoundaryConditions bcs_;
  ContactOptions contact_;
  bool decomposed_ = false;  ///< see decomposedContact()
  std::shared_ptr<const ContactElement> ntsElement_, slaveElement_, masterElement_;

  std::vector<int> subdomainRank_;
  std::vector<int> localElements_;
  std::vector<int> nodeOwner_;
  std::vector<GO> nodeDof_;  ///< first DOF of each node
  std::vector<GO> lmDof_;    ///< DOF of each contact slot's multiplier
  GO numGlobalDofs_ = 0;
  std::vector<char> constrained_;
  std::vector<std::pair<int, int>> constraintSource_;
  Teuchos::RCP<const Map> ownedMap_, overlapMap_;
  Teuchos::RCP<const CrsGraph> ownedGraph_, overlapGraph_;
  mutable Teuchos::RCP<CrsMatrix> overlapMatrix_;  ///< assembly buffer on overlapGraph_, reused
  Teuchos::RCP<const Tpetra::Export<LO, GO, Node>> exporter_;
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> importer_;
  Teuchos::RCP<Vector> fext_;
  int topologyVersion_ = 0;

  // contact
  std::vector<ContactSlot> slots_;
  std::vector<std::unique_ptr<ContactSearch>> searches_;  ///< one per pair
  std::vector<FacingRule> pairRules_;                      ///< per pair: slave segments, master element depths
  std::vector<std::pair<int, int>> slaveNeighbourSends_;   ///< decomposed: (owned slave-surface node, rank needing it)
  std::vector<std::vector<int>> pairSlots_;                ///< slots of each pair, in search order
  std::vector<int> surfaceNodes_;                          ///< nodes whose positions are gathered
  std::vector<int> surfaceIndex_;                          ///< node -> index in surfaceNodes_ or -1
  Teuchos::RCP<const Map> surfaceMap_;                     ///< replicated: surface DOFs + multipliers
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> surfaceImporter_;
  std::vector<int> localSlots_;        ///< slots whose slave node (and multiplier) this rank owns
  std::vector<int> localMasterSlots_;  ///< decomposed: paired slots whose master element is on this rank
  std::vector<std::vector<int>> pairMasterElements_;  ///< per pair: element of each master segment
  Teuchos::RCP<const Map> multiplierMap_;             ///< owned multiplier DOFs
  Teuchos::RCP<const Map> multiplierAllMap_;          ///< every slot's multiplier DOF, on every rank
  Teuchos::RCP<const Map> lmOverlapMap_;              ///< decomposed: multipliers of this rank's counterparts
  Teuchos::RCP<const Tpetra::Export<LO, GO, Node>> lmExporter_;    ///< lmOverlapMap_ -> multiplierMap_
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> lmAllImporter_;  ///< multiplierMap_ -> multiplierAllMap_
  std::vector<int> masterSurfaceNodes_;  ///< nodes of the master surfaces (may repeat across pairs)
  double pairingMargin_ = 0.0;
  long distributedQueries_ = 0;  ///< slave queries of distributedSearch(), summed over ranks
  mutable long exchanges_ = 0, bytesExchanged_ = 0;
  long bytesPerExchange_ = 0;
};

}  // namespace ddc
