// The values the contact component (DDC_ContactComponent.hpp, doc/embedding.md
// "(c) The contact component") and its host exchange: what the host registers
// (nodes, facets, pairs, DOFs, options), the contact slots it reads and
// checkpoints, the constraint rows, the summary and the frozen-geometry error.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "DDC_ContactState.hpp"
#include "DDC_DecomposedNodeToSurface.hpp"
#include "DDC_ReferenceCell.hpp"
#include "DDC_SurfaceContactElement.hpp"
#include "DDC_TpetraTypes.hpp"

namespace ddc {

/// The contact state of a slot as doc/contact.md ("Friction") names it:
/// open (not in contact), stick (in contact, no tangential slip) or slip
/// (in contact, the tangential force on the Coulomb cone). An active slot
/// of a frictionless pair slips freely (Slip, no tangential force).
enum class FrictionState : int { Open = 0, Stick = 1, Slip = 2 };

/// One contact slot: a slave node of a pair, its multiplier, and its
/// current pairing and state. Every rank holds every slot: the pairing and
/// the state are the same everywhere, the decomposed element's values where
/// the slot is evaluated (ContactComponent::slots(), shareSlotValues()).
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
  /// The unit tangent basis τ_α used by the element, orthogonal to `normal`
  /// (z = 0 and τ_2 = 0 in 2-D): frozen with n^p for the decomposed element,
  /// at the current projection for the conventional one.
  std::array<Eigen::Vector3d, 2> tangent{{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}};
  /// The tangential multipliers λ_t,α of a frictional pair, along
  /// `tangent` (doc/contact.md, "Friction"): the tangential force on the
  /// slave node is −Σ λ_t,α τ_α; zero in a frictionless pair.
  std::array<double, 2> tangential{{0.0, 0.0}};
  /// Stick or slip while active; Open otherwise (see contactState()).
  FrictionState friction = FrictionState::Open;
  /// u_t,α: the slip along `tangent` since the step start at the last
  /// update of the active set (frictional pairs).
  std::array<double, 2> tangentialSlip{{0.0, 0.0}};
  /// Consecutive updates of the active set at which the slot's slip
  /// reversed (slipReverses()); reset by beginStep().
  int reversals = 0;
  /// |u_t|: the tangential slip of the slave node along the master surface
  /// in the last step (zero while it sticks or is open).
  double slip = 0.0;
  /// The slave node's share of the slave surface in the reference
  /// configuration: a length in 2-D (half the adjacent slave segments), an
  /// area in 3-D (doc/contact.md, "Curved facets and 3-D").
  double tributaryLength = 0.0;
  /// Contact pressure −λ / tributary length (> 0 in compression), 0 when inactive.
  double pressure() const { return active && tributaryLength > 0 ? -state.multiplier / tributaryLength : 0.0; }
  /// Whether the slot has a master facet.
  bool paired() const { return master[0] >= 0; }
  /// The tangential contact force on the slave node, −Σ λ_t,α τ_α (zero
  /// when inactive or frictionless).
  Eigen::Vector3d tangentialForce() const {
    if (!active) return Eigen::Vector3d::Zero();
    if (hasSlaveTangentialForce) return slaveTangentialForce;
    return Eigen::Vector3d(-tangential[0] * tangent[0] - tangential[1] * tangent[1]);
  }
  /// The conventional element's tangential force on the slave node, from
  /// its residual (ContactPairing::consistentTangentialForce()): −λ_t·∂u_t/∂x_s,
  /// which differs from −Σ λ_t,α τ_α by the derivatives of the basis and of
  /// the projection along the slip. The decomposed element's basis is
  /// frozen, so its force is −Σ λ_t,α τ_α exactly.
  Eigen::Vector3d slaveTangentialForce = Eigen::Vector3d::Zero();
  bool hasSlaveTangentialForce = false;  ///< slaveTangentialForce is set (the conventional element)
  /// The state for output: Open when inactive, else `friction` (an active
  /// slot of a frictionless pair slips).
  FrictionState contactState() const {
    return !active ? FrictionState::Open : friction == FrictionState::Stick ? FrictionState::Stick : FrictionState::Slip;
  }
};

/// 0, 1, ..., count − 1: every slot of a list of `count` slots (e.g. the
/// `wanted` slots of ContactComponent::shareSlotValues()).
std::vector<int> slotIndices(size_t count);

/// The slots as numbers, for a checkpoint (every field; integers exactly):
/// packedSlotSize() numbers per slot, in the slots' order.
std::vector<double> packSlots(const std::vector<ContactSlot>& slots);
/// The numbers packSlots() gives a slot.
size_t packedSlotSize();
/// The slots packSlots() gave.
/// \throws std::invalid_argument if `packed` is not a whole number of slots
std::vector<ContactSlot> unpackSlots(const std::vector<double>& packed);

/// Summary of the contact state for output.
struct ContactSummary {
  int active = 0;  ///< active slots
  /// Resultant contact force on the slave bodies, Σ −λ n − Σ λ_t,α τ_α
  /// (the tangential part in frictional pairs; z = 0 in 2-D).
  double force[3] = {0.0, 0.0, 0.0};
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
  long id = -1;  ///< the host's id of the facet: orders the facets (search tie-breaks), unique per surface
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
  /// Coulomb friction coefficient μ ≥ 0 (doc/contact.md, "Friction"); 0:
  /// frictionless, one multiplier per slot. With μ > 0 every slot of the
  /// pair has dim multipliers: λ_n, then λ_t along the tangent basis.
  double friction = 0.0;
  /// The complementarity parameter c_t > 0 of a frictional pair (force per
  /// length; DDC_Friction.hpp): the stick/slip decision and the slip rows'
  /// scale.
  double frictionStiffness = 0.0;
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
  /// Σ_α |λ_t,α| |τ_α − τ^p_α| s over the same slots of frictional pairs:
  /// the tangential force along the frozen basis τ^p across the updated
  /// one, over the same slip (0 without friction).
  double tangentWork = 0.0;
  /// The indicator: gapWork + normalWork + tangentWork.
  double total() const { return gapWork + normalWork + tangentWork; }
};

}  // namespace ddc
