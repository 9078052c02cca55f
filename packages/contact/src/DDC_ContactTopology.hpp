// The topology part of the contact component (DDC_ContactComponent.hpp): what
// is fixed once the host has registered its surfaces and DOFs.
//
//   registration  registerNodes(), registerPair(): each rank's share;
//   commit()      merges the shares so that every rank holds every surface
//                 node (reference coordinates, owner), every pair's facets
//                 (ascending facet id, with the rank, element, subdomain and
//                 depth of each) and the slots' static data (slave node,
//                 owner, tributary area: one slot per slave node, in
//                 ascending node id per pair), and the searches' static
//                 data (free boundary, slave facets at each slave node, the
//                 bounding-box margin and the nodes the decomposed pairing
//                 exchanges);
//   setDofs()     the host DOF ids of every surface node and the multipliers:
//                 multiplierMap(), the replicated surface map the gathers
//                 use, and the bytes one such gather moves.
//
// Nothing here changes after setDofs(): the pairing, the slots' state and
// everything evaluated per step or iteration are the pairing part's
// (DDC_ContactPairing.hpp), which reads this one.
#pragma once

#include <Eigen/Dense>
#include <Teuchos_Comm.hpp>
#include <Tpetra_Import.hpp>
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "DDC_ContactData.hpp"
#include "DDC_ReferenceCell.hpp"
#include "DDC_SurfaceContactElement.hpp"
#include "DDC_TpetraTypes.hpp"

namespace ddc {

/// Registration, merged surfaces, slots' static data, DOF and multiplier
/// maps (see the top of this file).
class ContactTopology {
 public:
  /// Surface contact elements by role and facet type (ContactComponent::SurfaceElementSource).
  using SurfaceElementSource =
      std::function<std::shared_ptr<const SurfaceContactElement>(SurfaceContactRole role, CellType facet)>;

  /// A facet after commit(): merged over the ranks (plain data, exchanged as a record).
  struct Facet {
    long id;                                            ///< ContactFacet::id
    int numNodes;                                       ///< nodes of the facet type
    std::array<int, ContactSlot::kMaxFacetNodes> nodes; ///< host node ids (the first numNodes)
    int element, subdomain, rank;                       ///< host element and subdomain; the registering rank
    double depth;                                       ///< ContactFacet::depth
  };

  /// A pair: its names and facet types from registration, the rest after commit().
  struct Pair {
    std::string name, path, slaveName, masterName;  ///< ContactPairSurfaces
    CellType slaveType = CellType::Line2;           ///< slave facet type
    CellType masterType = CellType::Line2;          ///< master facet type
    std::vector<Facet> masterFacets;  ///< in surface (search) order: ascending id
    std::vector<Facet> slaveFacets;   ///< ascending id
    std::vector<int> slaves;          ///< slave node ids, in slot order
    /// Per slave node, its slave facets and its local node number in each
    /// (the nodal normal of the facing rule).
    std::map<int, std::vector<std::pair<int, int>>> slaveFacetsAt;
    /// Per master facet, its sides on the surface's free boundary (polylines
    /// of node ids).
    std::vector<std::vector<std::vector<int>>> freeSides;
    std::vector<int> slots;  ///< slots of the pair, in search order
    double friction = 0.0;           ///< μ (ContactPairSurfaces::friction)
    double frictionStiffness = 0.0;  ///< c_t (ContactPairSurfaces::frictionStiffness)
    /// Node ids of master facet f.
    std::vector<int> facetNodes(int f) const {
      return {masterFacets[f].nodes.begin(), masterFacets[f].nodes.begin() + masterFacets[f].numNodes};
    }
  };

  /// The static data of a slot.
  struct Slot {
    int pair = 0;                  ///< ContactSlot::pair
    int slaveNode = -1;            ///< ContactSlot::slaveNode
    int owner = -1;                ///< owner rank of the slave node (and of the slot)
    double tributaryLength = 0.0;  ///< ContactSlot::tributaryLength
  };

  /// \throws std::invalid_argument as ContactComponent's constructor
  ContactTopology(Teuchos::RCP<const Teuchos::Comm<int>> comm, ContactComponentOptions options,
                  SurfaceElementSource surfaceElements);
  ~ContactTopology();

  // ---- registration (ContactComponent::registerNodes/registerPair/commit/setDofs)
  void registerNodes(const std::vector<ContactNode>& nodes);
  int registerPair(ContactPairSurfaces pair);
  void commit();
  void setDofs(Teuchos::RCP<const Map> hostMap, const std::vector<ContactNodeDofs>& nodeDofs,
               const std::vector<GO>& multiplierDofs);
  /// Throws std::logic_error ("ContactComponent::what: ...") before commit() and setDofs().
  void requireCommitted(const char* what) const;
  /// Throws std::logic_error unless the host gave multiplier DOFs to setDofs().
  void requireHostMultipliers() const;
  /// setDofs() has run.
  bool hasDofs() const { return hasDofs_; }

  // ---- what the pairing part reads ---------------------------------------------
  const Teuchos::RCP<const Teuchos::Comm<int>>& comm() const { return comm_; }
  const ContactComponentOptions& options() const { return options_; }
  int dim() const { return dim_; }
  int numPairs() const { return static_cast<int>(pairs_.size()); }
  const Pair& pair(int p) const { return pairs_[p]; }
  const std::vector<Pair>& pairs() const { return pairs_; }
  /// Every slot's static data (ascending node id per pair, pairs in order).
  const std::vector<Slot>& slots() const { return slots_; }
  int slotOwner(int k) const { return slots_[k].owner; }
  /// Slots this rank owns, ascending (the order of multiplierMap()).
  const std::vector<int>& ownedSlots() const { return localSlots_; }
  /// "pair 'P' slave node n at (x, y[, z])" for messages.
  std::string describeSlot(int k) const;
  /// The surface contact element of `role` on `facet` (commit() fetched it).
  const SurfaceContactElement& surfaceElement(SurfaceContactRole role, CellType facet) const;

  // ---- surface nodes (replicated, ascending id) -----------------------------------
  const std::vector<int>& surfaceNodes() const { return nodeIds_; }
  /// Position of node `id` in surfaceNodes(), −1 if it is not a surface node.
  int index(int id) const;
  /// Reference coordinates of a surface node (z = 0 in 2-D).
  Eigen::Vector3d referencePosition(int id) const;
  /// Reference coordinates of the i-th surface node.
  const Eigen::Vector3d& referenceAt(int i) const { return X_[i]; }
  /// Owner rank of the i-th surface node.
  int ownerAt(int i) const { return owner_[i]; }
  /// Host DOF ids of the i-th surface node (the first dim() are set).
  const std::array<GO, 3>& dofsAt(int i) const { return dofs_[i]; }
  /// Append the host DOF ids of node `id` (dim() of them).
  void appendNodeDofs(int id, std::vector<GO>& dofs) const;
  /// Every DOF of node `id` is prescribed.
  bool nodePrescribed(int id) const;
  /// Component c of node `id` is prescribed.
  bool componentPrescribed(int id, int c) const { return prescribed_[index(id)][c] != 0; }

  // ---- multipliers and gathers (after setDofs()) ----------------------------------
  bool multipliersInHost() const { return multipliersInHost_; }
  /// Multiplier c of slot k: 0 the normal λ_n, 1..dim−1 the tangential
  /// λ_t of a frictional pair (host DOF id when the host gave them).
  GO multiplierId(int k, int c = 0) const { return lmGid_[lmStart_[k] + c]; }
  /// The multipliers of slot k: 1, or dim in a frictional pair.
  int numMultipliers(int k) const { return lmStart_[k + 1] - lmStart_[k]; }
  /// Whether some pair has friction.
  bool frictional() const { return frictional_; }
  const Teuchos::RCP<const Map>& hostMap() const { return hostMap_; }
  const Teuchos::RCP<const Map>& multiplierMap() const { return multiplierMap_; }
  /// Every slot's multiplier on every rank.
  /// Every multiplier id, on every rank (the conventional element's
  /// gather; null for the decomposed element).
  const Teuchos::RCP<const Map>& multiplierAllMap() const { return multiplierAllMap_; }
  const Teuchos::RCP<const Tpetra::Import<LO, GO, Node>>& multiplierAllImporter() const { return lmAllImporter_; }
  /// Every surface DOF on every rank (the gathers of the replicated pairing:
  /// the conventional element, and the decomposed element's tracking
  /// outside step ends). Built by the first call, which is collective: the
  /// decomposed element's runs, which pair at step ends only
  /// (ContactPairing::distributedSearch()), never build it.
  const Teuchos::RCP<const Map>& surfaceMap() const;
  const Teuchos::RCP<const Tpetra::Import<LO, GO, Node>>& surfaceImporter() const;
  /// Bytes one gather of the surface moves between ranks (collective on
  /// the first call, as surfaceMap()).
  long bytesPerExchange() const;

  // ---- the decomposed pairing's exchange ----------------------------------------
  /// Nodes of the master surfaces (may repeat across pairs).
  const std::vector<int>& masterSurfaceNodes() const { return masterSurfaceNodes_; }
  /// (owned slave-surface node, rank needing it for a slave node's normal).
  const std::vector<std::pair<int, int>>& slaveNeighbourSends() const { return slaveNeighbourSends_; }
  /// Margin of the bounding boxes of the exchange.
  double pairingMargin() const { return pairingMargin_; }

 private:
  // commit() in steps
  void checkDimensions() const;
  void fetchSurfaceElements();
  void mergeNodes();
  void mergePair(int p);
  std::vector<Facet> gatherFacets(const Pair& pair, const std::vector<ContactFacet>& facets, CellType type,
                                  const char* role) const;
  void checkFacetSizes(const Pair& pair, const ContactPairSurfaces& mine) const;
  std::vector<int> slaveNodesOf(const Pair& pair, const std::vector<int>& candidates,
                                const std::vector<int>& masterNodes) const;
  void checkOrientation(const Pair& pair) const;
  std::map<int, double> tributaryLengths(const Pair& pair) const;
  void addSearchData(Pair& pair, const std::vector<int>& masterNodes);
  void findSlaveNeighbourSends();
  void requireNode(const Pair& pair, int id, const char* role) const;
  // setDofs() in steps
  std::string checkNodeDofs(const Map& hostMap, const std::vector<ContactNodeDofs>& nodeDofs) const;
  std::string checkMultiplierDofs(const Map& hostMap, const std::vector<ContactNodeDofs>& nodeDofs,
                                  const std::vector<GO>& multiplierDofs) const;
  void replicateDofs(const std::vector<ContactNodeDofs>& nodeDofs);
  void buildMultiplierMaps(const std::vector<GO>& multiplierDofs);
  void buildSurfaceMap() const;

  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  ContactComponentOptions options_;
  SurfaceElementSource surfaceSource_;
  std::map<std::pair<SurfaceContactRole, CellType>, std::shared_ptr<const SurfaceContactElement>> surfaceElements_;
  bool committed_ = false, hasDofs_ = false, multipliersInHost_ = false;
  int dim_ = 2;

  // Registration shares (before commit()).
  std::vector<ContactNode> myNodes_;
  std::vector<ContactPairSurfaces> myPairs_;

  std::vector<Pair> pairs_;
  // Surface nodes after commit(), ascending id: replicated.
  std::vector<int> nodeIds_;
  std::vector<Eigen::Vector3d> X_;
  std::vector<int> owner_;
  std::vector<std::array<GO, 3>> dofs_;
  std::vector<std::array<char, 3>> prescribed_;

  std::vector<Slot> slots_;
  std::vector<int> localSlots_;
  std::vector<std::pair<int, int>> slaveNeighbourSends_;
  std::vector<int> masterSurfaceNodes_;
  double pairingMargin_ = 0.0;

  std::vector<GO> lmGid_;   ///< every slot's multiplier ids, slot by slot
  std::vector<int> lmStart_;  ///< slot k's ids are lmGid_[lmStart_[k] .. lmStart_[k + 1])
  bool frictional_ = false;
  Teuchos::RCP<const Map> hostMap_;
  // The replicated surface map (surfaceMap()), built on first use.
  mutable Teuchos::RCP<const Map> surfaceMap_;
  mutable Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> surfaceImporter_;
  mutable long bytesPerExchange_ = 0;
  Teuchos::RCP<const Map> multiplierMap_, multiplierAllMap_;
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> lmAllImporter_;  ///< multiplierMap_ -> multiplierAllMap_
};

}  // namespace ddc
