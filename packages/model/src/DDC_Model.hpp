// The discrete model: the mesh (whole, or this rank's part of it without
// contact), element evaluators per body, element
// partition, distributed DOF numbering (nodes and contact multipliers),
// boundary conditions, and assembly of the global residual and tangent (a
// distributed Tpetra::CrsMatrix). Contact is a ContactComponent the model
// registers its surfaces with and drives (packages/contact); the model
// computes no contact geometry itself.
#pragma once

#include <Teuchos_Comm.hpp>
#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "DDC_BoundaryConditions.hpp"
#include "DDC_ContactComponent.hpp"
#include "DDC_ContactParameters.hpp"
#include "DDC_DirectSolver.hpp"
#include "DDC_Element.hpp"
#include "DDC_FetiDpSolver.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_Partition.hpp"
#include "DDC_RigidMotionCheck.hpp"

namespace ddc {

struct SubdomainSystem;
struct ContactSurfaceFacets;

/// Where assemble() also puts element tangents: the local stiffness of each
/// subdomain (FETI-DP), with `where[e]` = (system index, element position in
/// that system) for this rank's elements.
struct SubdomainSink {
  std::vector<SubdomainSystem>* systems = nullptr;
  std::vector<std::pair<int, int>> where;
};

/// Inertia in an assembly (a dynamic analysis' time integrator): the
/// residual gains M a and the tangent c M, with M the element mass matrices
/// (Element::mass, Model::setMassLumping()). The external and internal
/// forces (fint) are unchanged.
struct Inertia {
  /// The acceleration a on the owned map (multiplier entries unused).
  const Vector* acceleration = nullptr;
  /// c: the derivative of a with respect to u in the integrator (e.g.
  /// 1/(β h²) for Newmark), times any weight it gives the inertia term.
  double tangentFactor = 0.0;
  /// Weight of M a in the residual (1 for Newmark; (1 − α_m)/(1 − α_f) for
  /// the α-methods).
  double residualFactor = 1.0;
  /// If given: a force added to the residual's free DOFs (the α-methods'
  /// terms of the previous step), owned map.
  const Vector* force = nullptr;
  /// Rayleigh damping C = massDamping M + stiffnessDamping K, K the element
  /// tangents at the iterate: with `velocity` (v(u) of the integrator, owned
  /// map) the residual gains C v and the tangent velocityFactor · C
  /// (velocityFactor = dv/du, γ/(β h) for Newmark; the change of K with u
  /// in C v is left out of the tangent).
  const Vector* velocity = nullptr;
  double massDamping = 0.0;
  double stiffnessDamping = 0.0;
  double velocityFactor = 0.0;
  bool damped() const { return velocity && (massDamping != 0.0 || stiffnessDamping != 0.0); }
};

/// What one Model::assemble() computes besides the strain energy: every
/// member is optional (null: not wanted).
struct AssemblyRequest {
  /// ∂(U + Π_c)/∂u at all DOFs, unmodified (the reactions live at the
  /// prescribed DOFs).
  Vector* fint = nullptr;
  /// r = fint − λ f_ext − f_body (Model::setBodyForce()) on free DOFs, 0 on
  /// prescribed DOFs.
  Vector* residual = nullptr;
  /// The tangent, rows and columns of prescribed DOFs replaced by the identity.
  CrsMatrix* tangent = nullptr;
  /// If given: K · prescribedStep is added to the residual (the consistent
  /// predictor of a prescribed increment in the first Newton iteration).
  const Vector* prescribedStep = nullptr;
  /// If given: the element tangents (free DOFs only) are also summed into
  /// the subdomain stiffness matrices (zeroed first), for FETI-DP.
  SubdomainSink* subdomains = nullptr;
  /// Dynamics: the residual also gets M a and every tangent c M; a tangent
  /// with c > 0 is then nonsingular, and the rigid-motion check is skipped.
  const Inertia* inertia = nullptr;
};

/// Results of one assembly.
struct AssemblyResult {
  double strainEnergy = 0.0;  ///< Σ U_e over the continuum elements (global)
  /// With a tangent (K or subdomain matrices): the rigid-body motions that no
  /// prescribed displacement and no active contact row restrains, described
  /// for a message (RigidMotionCheck::freeMotions()); "" if none. Non-empty
  /// means the tangent is singular. Equal on every rank.
  std::string freeMotions;
};

/// The discrete model shared by every strategy. Each rank holds the whole
/// mesh, or without contact its part of it (Mesh::part(): its elements and
/// their nodes, doc/architecture.md), and evaluates the elements of the
/// subdomains it owns; on a part, node indices are the part's and the mesh's
/// nodeId() names them across ranks. Nodes are
/// owned by the lowest rank among the elements that touch them; a contact
/// multiplier by the owner of its slave node. Each rank's owned DOFs (its
/// nodes' DOFs, then its multipliers) form a contiguous range, so the owned
/// DOF map is contiguous (what MUMPS needs).
class Model {
 public:
  /// \param elements one evaluator per body (index = body index)
  /// \param surfaceElements the contact elements by role and facet type
  ///        (ContactComponent)
  Model(Teuchos::RCP<const Teuchos::Comm<int>> comm, std::shared_ptr<const Mesh> mesh,
        std::vector<std::shared_ptr<const Element>> elements, Partition partition, BoundaryConditions bcs,
        ContactOptions contact = {}, ContactComponent::SurfaceElementSource surfaceElements = makeSurfaceContactElement);
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
  /// Global DOF id of multiplier c of contact slot k (c = 0: λ_n; 1..dim−1:
  /// a frictional pair's λ_t).
  GO multiplierDof(int k, int c = 0) const { return lmDof_[k] + c; }
  /// The id of DOF g that does not depend on the partition or the number of
  /// ranks (a checkpoint's): node·dim + component for a node's DOF (the
  /// node's id in the whole mesh), numGlobalNodes·dim + m for the
  /// multipliers, m counting them slot by slot
  /// (slot k's c-th: the slots before it have m multipliers; without
  /// friction m = k).
  /// \throws std::logic_error if g is not a DOF of this rank's overlap map
  GO partitionFreeDof(GO g) const;
  /// Whether global DOF g is prescribed (any DOF of the model: the FETI-DP
  /// primal selection asks about every subdomain's nodes).
  bool isConstrained(GO g) const { return constrained_[static_cast<size_t>(g)]; }

  Teuchos::RCP<Vector> createVector() const;
  /// A matrix with the current sparsity pattern (changes with the pairing:
  /// see topologyVersion()).
  Teuchos::RCP<CrsMatrix> createMatrix() const;
  /// Incremented whenever the sparsity pattern changes (new contact pairing).
  int topologyVersion() const { return topologyVersion_; }

  void applyPrescribed(double lambda, Vector& u) const;
  void prescribedIncrement(double lambda0, double lambda, Vector& du) const;

  /// Assemble at the state u (owned layout, multipliers included) what
  /// `request` asks for (AssemblyRequest); λ scales the external loads.
  /// The strain energy is always computed.
  /// \throws InadmissibleDeformation on every rank if det F <= 0 anywhere.
  AssemblyResult assemble(const Vector& u, double lambda, const AssemblyRequest& request) const;

  // ---- inertia (dynamic analyses) ----------------------------------------------
  /// The form of the element mass matrices (default: consistent). Collective
  /// only in the sense that every rank must choose the same.
  void setMassLumping(MassLumping lumping);
  MassLumping massLumping() const { return massLumping_; }
  /// Move the mass of the contact-surface nodes (slave and master surfaces
  /// of every pair) to the other nodes of their elements
  /// (redistributeNodalMass()), or keep it (default). Collective only in the
  /// sense that every rank must choose the same.
  /// \throws InputError (on every rank: the mesh is replicated) naming the
  ///         body and element if an element has only surface nodes
  void setContactSurfaceMassRedistributed(bool redistributed);
  bool contactSurfaceMassRedistributed() const { return redistributeSurfaceMass_; }
  /// The bodies whose element has no mass (Element::hasMass() false), by
  /// name; empty when every body has one (what a dynamic analysis needs).
  std::vector<std::string> bodiesWithoutMass() const;
  /// The frictional contact pairs in gross slip: some slave node in
  /// contact, none sticking (doc/contact.md, "Friction"); for each, its
  /// parameter path and its two bodies ("'Contact/Pairs/P' (bodies 'A' and
  /// 'B')").
  std::vector<std::string> pairsInGrossSlip() const;
  /// Kinetic energy ½ vᵀ M v of the velocities v (owned map). Collective.
  /// \throws std::logic_error if a body has no mass
  double kineticEnergy(const Vector& v) const;
  /// M v on the owned map (multiplier entries 0). Collective.
  /// \throws std::logic_error if a body has no mass
  void applyMass(const Vector& v, Vector& Mv) const;
  /// K(u) v with the element tangents at u (contact and prescribed rows
  /// aside: the continuum elements only), owned map. Collective.
  /// \throws InadmissibleDeformation on every rank if det F <= 0 anywhere
  void applyElementTangent(const Vector& u, const Vector& v, Vector& Kv) const;

  /// The diagonal of M on the owned map (multiplier entries 0). Collective.
  /// \throws std::logic_error if a body has no mass
  void massDiagonal(Vector& d) const;
  /// A constant external force (gravity, M g: Analysis "Dynamics/Gravity"),
  /// subtracted from the residual's free DOFs at every load factor, unlike
  /// externalForce(), which the load factor scales. Owned map.
  void setBodyForce(const Vector& f);
  /// The force of setBodyForce(), or nullptr if none was set.
  const Vector* bodyForce() const { return bodyForce_.get(); }

  /// The force of every traction at s = 1 (its Load Curve aside), which the
  /// load factor scales: the external force at load factor λ is λ times it
  /// when no traction has a Load Curve. Owned map.
  const Vector& externalForce() const { return *fext_; }
  /// The external force at load factor λ, Σ s_t(λ) f_t over the tractions
  /// (s_t their Load Curve, else λ), into `out` (owned map).
  void externalForceAt(double lambda, Vector& out) const;
  /// Whether a traction has a Load Curve (externalForceAt() is then not
  /// λ externalForce()).
  bool hasTractionCurves() const { return !curvedTractions_.empty(); }
  Teuchos::RCP<Vector> toOverlap(const Vector& owned) const;
  const Element& elementOf(int e) const { return *elements_[mesh_->elementBody(e)]; }

  // ---- contact (the ContactComponent, driven in the model's DOF numbering) -----
  bool hasContact() const { return contact_ != nullptr; }
  /// The tangent does not depend on u: no contact and every body's element
  /// has Element::tangentIsConstant() (linear elasticity). The strategies
  /// then factorise once per analysis.
  bool tangentIsConstant() const;
  /// Every body's element has Element::tangentIsConstant(), contact aside:
  /// the subdomain matrices of FETI-DP hold the element tangents only (the
  /// decomposed contact element enters as constraint rows), so with a
  /// linear material they are factorised once per analysis even with
  /// contact (doc/feti-dp.md "Extra rows").
  bool elementTangentsAreConstant() const;
  /// Decomposed contact in use: Contact/Formulation = Decomposed
  /// Node-To-Segment *and* at least one pair. With no pairs the formulation
  /// is moot and the model is a plain one (no multiplier maps exist); test
  /// this, never contactOptions().decomposed alone.
  bool decomposedContact() const { return decomposed_; }
  const ContactOptions& contactOptions() const { return contactOptions_; }
  /// The contact component (null without contact). Its node ids are mesh
  /// node ids, its DOF ids this model's, its multipliers the model's
  /// multiplier DOFs (multiplierDof()).
  const ContactComponent* contact() const { return contact_.get(); }
  /// A restart: add the earlier run's ContactComponent::pairedRecord().
  void addPairedRecord(const std::vector<char>& record) {
    if (contact_) contact_->addPairedRecord(record);
  }
  const std::vector<ContactSlot>& contactSlots() const;
  /// ContactComponent::updatePairing(); rebuilds the model's sparsity
  /// pattern when the pairing changes.
  bool updatePairing(const Vector& u, bool global, bool freeze, std::vector<int>* changedSlots = nullptr);
  /// ContactComponent::activateAllPaired().
  void activateAllPaired();
  /// ContactComponent::fullyPrescribed().
  bool fullyPrescribed(int k) const;
  /// ContactComponent::updateActiveSet() with the multipliers of u
  /// (`everySlot`: every slot's values to every rank; a Newton iteration
  /// and a step's end need only the evaluated slots').
  /// Without contact: nothing to do, returns no slots. Collective.
  /// \throws InadmissibleDeformation on every rank when some rank meets a
  ///         geometry it cannot evaluate
  std::vector<int> updateActiveSet(const Vector& u, bool everySlot = true);
  /// ContactComponent::beginStep(): a step (Newton's increment) starts
  /// from u. Without contact: nothing to do.
  void beginContactStep(const Vector& u) {
    if (contact_) contact_->beginStep(u);
  }
  /// b −= Σ over `rows` of coefficient · values(row) at the entry's DOF
  /// (free DOFs only: a prescribed one takes it as a reaction):
  /// the forces of contact multiplier increments that are known before a
  /// solve (a slipping pair's under FETI-DP, doc/feti-dp.md "Friction
  /// rows"). `values` holds them at the multiplier DOFs (owned map); `rows`
  /// are this rank's ContactComponent::contactRows(). Collective.
  void subtractContactRowForces(const std::vector<ContactRowEntry>& rows, const Vector& values, Vector& b) const;
  /// Decomposed contact in FETI-DP: the constraint row of every contact slot
  /// (row id = the slot's multiplier DOF; ContactComponent::contactRows()),
  /// split into the entries of the subdomains on this rank: the slave
  /// counterpart's coefficients in the first subdomain having the slave
  /// node, the master counterpart's in the subdomain of the master segment's
  /// element. Prescribed DOFs have no entry (their part of the gap is in the
  /// residual).
  std::vector<std::vector<ConstraintEntry>> contactRowEntries(const std::vector<SubdomainSystem>& systems) const;
  /// This rank's multiplier DOFs (one per slot whose slave node it owns), in
  /// slot order; a one-to-one map. Null without contact.
  Teuchos::RCP<const Map> multiplierMap() const;
  /// Slots whose multiplier this rank owns, in the order of multiplierMap().
  const std::vector<int>& ownedSlots() const;
  /// 1 for nodes on a contact surface (slave or master).
  bool isContactSurfaceNode(int n) const { return contact_ && contact_->isSurfaceNode(contactNodeId(n)); }
  /// The reference coordinates of contact surface node `id` (an id in the
  /// whole mesh, as ContactSlot::slaveNode), known on every rank.
  Eigen::Vector3d contactNodeReference(int id) const { return contact_->referencePosition(id); }
  /// ContactComponent::reduceSummary(); none without contact. Collective.
  ContactSummary reduceContactSummary() const { return contact_ ? contact_->reduceSummary() : ContactSummary(); }
  /// The active contact slots (ContactComponent::numActive(); not collective).
  int activeContacts() const { return contact_ ? contact_->numActive() : 0; }
  /// ContactComponent::shareEverySlotsValues(): every slot's values on
  /// every rank, for a host that reads contactSlots() after a run. Collective.
  void shareContactValues() {
    if (contact_) contact_->shareEverySlotsValues();
  }
  /// Restore slots saved before a failed increment (pairing and state);
  /// rebuilds the topology if the pairing differs.
  void restoreContactState(const std::vector<ContactSlot>& saved);
  /// "pair 'P' slave node n at (x, y)" for messages.
  std::string describeSlot(int k) const { return contact_->describeSlot(k); }
  /// Collective. Where a vector of the owned layout (a residual or a
  /// correction) first goes wrong, for the failure message of a Newton
  /// iteration: its non-finite entry of smallest global id, or, if every
  /// entry is finite (the norm overflowed), its entry of largest magnitude;
  /// named by node, component, coordinates, body, element and material
  /// (parameters that are non-finite or extreme flagged: see
  /// doc/user-guide.md, "Solution method"), or by contact slot. The same
  /// text on every rank; "" if the vector is finite and its norm is too.
  std::string describeNonFinite(const Vector& v) const;
  /// ContactComponent::exchanges(), searchCounters(), bytesExchanged() (0 without contact).
  long exchanges() const { return contact_ ? contact_->exchanges() : 0; }
  /// ContactComponent::takeWarnings() (none without contact).
  std::vector<std::string> takeContactWarnings() { return contact_ ? contact_->takeWarnings() : std::vector<std::string>(); }
  /// ContactComponent::neverPairedPairs() (none without contact).
  std::vector<std::string> neverPairedPairs() const {
    return contact_ ? contact_->neverPairedPairs() : std::vector<std::string>();
  }
  std::array<long, 3> searchCounters() const;
  long bytesExchanged() const { return contact_ ? contact_->bytesExchanged() : 0; }
  /// ContactComponent::valueBytesReceived() and valueUpdates() (0 without contact).
  std::array<long, 2> contactValueBytesReceived() const {
    return contact_ ? contact_->valueBytesReceived() : std::array<long, 2>{0, 0};
  }
  std::array<long, 2> contactValueUpdates() const {
    return contact_ ? contact_->valueUpdates() : std::array<long, 2>{0, 0};
  }

 private:
  /// One assemble() call's buffers and passes (DDC_ModelAssembly.cpp).
  class Assembly;
  friend class Assembly;
  void computeNodeOwners();
  /// describeNonFinite()'s place of DOF `at` (a node's component, with its
  /// element and material, or a slot's multiplier) after `what` ("NaN",
  /// ...); `nonFinite`: `at` holds the non-finite entry (else the largest).
  std::string placeOf(GO at, bool nonFinite, const std::string& what) const;
  /// c_t of a frictional pair (DDC_Friction.hpp), from its bodies' materials.
  double frictionStiffness(const ContactPairDefinition& def) const;
  /// c_t over E h^(dim−2): with the whole stiffness of a facet-sized piece
  /// of material (1) the stick/slip decision followed the slip predictor's
  /// noise in 3-D — FETI-DP's lagged slip direction diverged on the Hertz
  /// sphere at Refinement 3, and the monolithic solve took 15 iterations a
  /// step — while a tenth converges in 8–9 and under FETI-DP (measured with
  /// 1 and 0.1 in doc/contact.md, "Friction"; 2-D the same within 5 %).
  static constexpr double kFrictionStiffnessFactor = 0.1;
  void buildContact(ContactComponent::SurfaceElementSource surfaceElements);
  /// The contact component names nodes and elements by their ids in the
  /// whole mesh (equal to the index on a whole mesh), and a facet by its
  /// element's id and its side: the same on every layout of the mesh.
  /// \throws std::logic_error if an id exceeds the component's int ids
  int contactNodeId(int n) const;
  int contactElementId(int e) const;
  long contactFacetId(int e, int side) const;
  /// The facet type of a contact side set on a part of a mesh: the one
  /// type of the facets of all parts (collective).
  /// \throws InputError naming the set if the parts' facets differ in type
  CellType agreedFacetType(const ContactSurfaceFacets& surface, const std::string& set) const;
  /// The local node of a contact node id, −1 if this rank's mesh lacks it.
  int meshNodeOfContactNode(int id) const;
  /// The most facets an element has (a hexahedron's 6): the stride of
  /// contactFacetId().
  static constexpr int kMaxElementFacets = 6;
  /// computeNodeOwners() on a part of a mesh: by a directory of node ids.
  /// Collective.
  void computePartNodeOwners();
  /// nodeDof_ and numGlobalDofs_; `count`: each rank's owned DOFs (node
  /// DOFs and multipliers). \returns per rank the next free DOF after its
  /// nodes' (its first multiplier). Collective.
  std::vector<GO> numberNodeDofs(std::vector<GO>& count);
  void buildDofNumbering();
  void buildConstraints();
  /// A part of a mesh: OR constrained_ over the ranks. Collective.
  void shareConstrainedBits();
  /// "" if displacement conditions `a` and `b` prescribe the same component
  /// c at node n, else the message saying that they do not.
  std::string prescriptionConflict(const DisplacementCondition& a, const DisplacementCondition& b, int n,
                                   int c) const;
  /// The sparsity patterns (DDC_ModelTopology.cpp): the owned graph, then
  /// the overlap map, its import/export and the ghost graph.
  void buildTopology();
  /// The nodes of this rank's elements and their neighbours
  /// (DDC_ModelTopology.cpp). Collective.
  struct LocalNodes;
  std::unique_ptr<LocalNodes> localNodes() const;
  void buildOwnedGraph(const LocalNodes& local);
  void buildGhostGraph(const LocalNodes& local);
  void assembleTractions();
  /// The nodal forces of the tractions `which` (indices in bcs_.tractions)
  /// at s = 1, owned map.
  Teuchos::RCP<Vector> tractionForce(const std::vector<int>& which) const;
  /// DOF list of one element (global ids).
  void elementDofs(int e, std::vector<GO>& dofs) const;
  /// The mass matrix of the i-th local element (localElements_[i]), computed
  /// once per lumping.
  const Eigen::MatrixXd& elementMass(size_t i) const;
  /// Throws std::logic_error (on every rank) if a body has no mass.
  void requireMass() const;
  /// Σ over this rank's elements of perElement(M_e, element DOFs) (one
  /// entry per element DOF), exported to `out` on the owned map. Collective.
  void sumOverElementMasses(
      const std::function<Eigen::VectorXd(const Eigen::MatrixXd&, const std::vector<GO>&)>& perElement,
      Vector& out) const;

  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::shared_ptr<const Mesh> mesh_;
  std::vector<std::shared_ptr<const Element>> elements_;
  Partition partition_;
  BoundaryConditions bcs_;
  ContactOptions contactOptions_;
  bool decomposed_ = false;  ///< see decomposedContact()
  std::unique_ptr<ContactComponent> contact_;

  std::vector<int> subdomainRank_;
  std::vector<int> localElements_;
  Teuchos::RCP<Vector> bodyForce_;  ///< setBodyForce(); null if none
  MassLumping massLumping_ = MassLumping::Consistent;
  bool redistributeSurfaceMass_ = false;  ///< setContactSurfaceMassRedistributed()
  mutable std::vector<Eigen::MatrixXd> elementMass_;  ///< per local element (elementMass())
  std::vector<int> nodeOwner_;
  std::vector<GO> nodeDof_;  ///< first DOF of each node
  std::vector<GO> lmDof_;    ///< DOF of each contact slot's first multiplier (λ_n; λ_t follow it)
  std::vector<GO> lmFreeOffset_;  ///< multipliers of the slots before slot k (partitionFreeDof())
  int rigidRowsPerSlot_ = 1;  ///< rows of the rigid-motion check per slot (its most multipliers)
  /// Per DOF of the overlap map (by LID; the owned DOFs first): its node
  /// (a mesh node below mesh().numNodes(), a remote surface node from
  /// there: remoteSurfaceNodes_), or −1 − k for a multiplier of slot k.
  /// Only this rank's DOFs:
  /// a per-DOF array of the whole model on every rank would not shrink
  /// with the ranks (doc/performance.md, "Memory at set-up").
  std::vector<int> overlapEntity_;
  /// Contact surface nodes whose DOFs this rank's overlap map holds (for a
  /// slot or a counterpart) but whose elements are on other ranks (a part of
  /// a mesh only): their ids, entity numNodes() + i of overlapEntity_.
  std::vector<int> remoteSurfaceNodes_;
  /// Of a node entity of overlapEntity_ (local node or remote surface
  /// node): its first DOF, its id in the whole mesh, its body, and its
  /// reference coordinates.
  GO entityFirstDof(int entity) const;
  Mesh::GlobalId entityNodeId(int entity) const;
  int entityBody(int entity) const;
  std::array<double, 3> entityReference(int entity) const;
  /// overlapEntity_ of overlap LID l; throws std::logic_error for an
  /// invalid LID (a DOF this rank does not have).
  int entityAt(LO l, GO g) const;
  /// overlapEntity_ of the overlap map's ghosts (`gids`: its GIDs; `row`:
  /// ≥ 0 for the nodes of local elements; `nodeLid`: by row, the overlap
  /// LID of the node's first DOF), after the owned part.
  void setGhostEntities(const std::vector<GO>& gids, const std::vector<int>& row, const std::vector<LO>& nodeLid);
  static constexpr int kUnresolvedEntity = std::numeric_limits<int>::min();
  mutable std::unique_ptr<RigidMotionCheck> rigidCheck_;  ///< see AssemblyResult::freeMotions
  GO numGlobalDofs_ = 0;
  /// One bit per global DOF: prescribed (isConstrained()).
  std::vector<bool> constrained_;
  /// Per owned DOF (owned LID): the displacement condition prescribing it
  /// (index in bcs_.displacements) and its node; {-1, -1} if free.
  std::vector<std::pair<int, int>> constraintSource_;
  Teuchos::RCP<const Map> ownedMap_, overlapMap_;
  Teuchos::RCP<const CrsGraph> ownedGraph_;
  /// The rows of the overlap map other ranks own (its LIDs from the number
  /// of owned DOFs on), their pattern (columns: overlap LIDs), the assembly
  /// buffer on it (reused while the pattern lasts) and the export that adds
  /// it into the owners' rows of the tangent.
  Teuchos::RCP<const Map> ghostRowMap_;
  Teuchos::RCP<const CrsGraph> ghostGraph_;
  mutable Teuchos::RCP<CrsMatrix> ghostMatrix_;
  Teuchos::RCP<const Tpetra::Export<LO, GO, Node>> ghostExporter_;
  /// Overlap LID -> column LID of the owned graph (invalid for a DOF no
  /// owned row couples with): owned rows are assembled in place.
  std::vector<LO> ownedColumn_;
  Teuchos::RCP<const Tpetra::Export<LO, GO, Node>> exporter_;
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> importer_;
  Teuchos::RCP<Vector> fext_;
  /// With curvedTractions_: the force of the tractions without a Load Curve.
  Teuchos::RCP<Vector> proportionalForce_;
  /// Each traction with a Load Curve (index in bcs_.tractions) and its force at s = 1.
  std::vector<std::pair<int, Teuchos::RCP<Vector>>> curvedTractions_;
  int topologyVersion_ = 0;
};

}  // namespace ddc
