#include "DDC_ContactComponent.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_ShapeFunctions.hpp"

namespace ddc {

namespace {

using TpetraImport = Tpetra::Import<LO, GO, Node>;
using TpetraExport = Tpetra::Export<LO, GO, Node>;

Teuchos::RCP<const Map> mapOf(const std::vector<GO>& gids, const Teuchos::RCP<const Teuchos::Comm<int>>& comm) {
  return Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                              Teuchos::ArrayView<const GO>(gids), 0, comm));
}

/// Records of the registration gather (plain data for exchangeRecords()).
struct NodeRecord {
  int id, rank;
  double x, y, z;
};
struct FacetRecord {
  long id;
  int numNodes;
  std::array<int, ContactSlot::kMaxFacetNodes> nodes;
  int element, subdomain, rank;
  double depth;
};

/// Every rank's records on every rank, ordered by source rank.
template <class T>
std::vector<T> allGather(MPI_Comm comm, const std::vector<T>& mine) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  return exchangeRecords(comm, std::vector<std::vector<T>>(size, mine));
}

/// Corner node ids of a facet's side `s` (sorted), and the polyline through
/// the side's nodes (corner, middle, corner): the facet's boundary pieces
/// for the free-boundary rule. Line facets: the end node itself.
struct FacetSide {
  std::vector<int> key;       ///< sorted corner node ids
  std::vector<int> polyline;  ///< node ids along the side
};
std::vector<FacetSide> facetSides(CellType type, const int* nodes) {
  const ReferenceCell& ref = referenceCell(type);
  std::vector<FacetSide> sides;
  if (ref.dim == 1) {
    for (int end = 0; end < 2; ++end) sides.push_back({{nodes[end]}, {nodes[end]}});
    return sides;
  }
  for (const auto& e : ref.edges) {
    FacetSide s;
    s.key = {std::min(nodes[e.start], nodes[e.end]), std::max(nodes[e.start], nodes[e.end])};
    s.polyline = e.middle >= 0 ? std::vector<int>{nodes[e.start], nodes[e.middle], nodes[e.end]}
                               : std::vector<int>{nodes[e.start], nodes[e.end]};
    sides.push_back(s);
  }
  return sides;
}

}  // namespace

/// A pair after commit(): merged facets (ascending facet id), its search.
struct ContactComponent::Pair {
  std::string name, path, slaveName, masterName;
  CellType slaveType = CellType::Line2, masterType = CellType::Line2;
  // Registration shares (before commit()).
  std::vector<int> mySlaves;
  std::vector<ContactFacet> mySlaveFacets, myMasterFacets;
  // After commit().
  std::vector<FacetRecord> masterFacets;  ///< in surface (search) order
  std::vector<FacetRecord> slaveFacets;   ///< ascending id
  std::unique_ptr<FacetSearch> facetSearch;
  std::vector<int> slaves;                   ///< slave node ids, in slot order
  /// Per slave node, its slave facets and its local node number in each
  /// (the nodal normal of the facing rule).
  std::map<int, std::vector<std::pair<int, int>>> slaveFacetsAt;
  /// Per master facet, its sides on the surface's free boundary (polylines
  /// of node ids).
  std::vector<std::vector<std::vector<int>>> freeSides;
  std::vector<int> slots;  ///< slots of the pair, in search order
  std::vector<int> facetNodes(int f) const {
    return {masterFacets[f].nodes.begin(), masterFacets[f].nodes.begin() + masterFacets[f].numNodes};
  }
};

/// The pairing of one slave node found by a search.
struct ContactComponent::Found {
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
};

/// Field values at this rank's counterpart DOFs (dof) and multipliers (lm).
struct ContactComponent::Field {
  Teuchos::RCP<Vector> dof, lm;
  Teuchos::ArrayRCP<const double> d, l;
  const ContactComponent* c = nullptr;
  double at(GO g) const { return d[c->dofOverlapMap_->getLocalElement(g)]; }
  double multiplier(int k) const { return l[c->lmOverlapMap_->getLocalElement(c->lmGid_[k])]; }
};

ContactComponent::ContactComponent(Teuchos::RCP<const Teuchos::Comm<int>> comm, ContactComponentOptions options,
                                   SurfaceElementSource surfaceElements)
    : comm_(std::move(comm)), options_(options), surfaceSource_(std::move(surfaceElements)) {
  if (!(options_.searchRadius > 0.0) || !std::isfinite(options_.searchRadius))
    throw std::invalid_argument("ContactComponent: options.searchRadius must be > 0 and finite (an absolute "
                                "distance), got " + std::to_string(options_.searchRadius));
  if (!(options_.penetrationTolerance >= 0.0) || !std::isfinite(options_.penetrationTolerance))
    throw std::invalid_argument("ContactComponent: options.penetrationTolerance must be >= 0 and finite (an "
                                "absolute distance), got " + std::to_string(options_.penetrationTolerance));
  if (!surfaceSource_) throw std::invalid_argument("ContactComponent: no source of surface contact elements");
}

ContactComponent::~ContactComponent() = default;

void ContactComponent::requireCommitted(const char* what) const {
  if (!committed_ || !hasDofs_)
    throw std::logic_error(std::string("ContactComponent::") + what + ": call commit() and setDofs() first");
}

void ContactComponent::requirePaired(const char* what) const {
  if (!pairedOnce_)
    throw std::logic_error(std::string("ContactComponent::") + what +
                           ": no pairing yet, so no slave node is paired and there is nothing to evaluate; call "
                           "updatePairing(u, /*global=*/true, /*freeze=*/true) once after setDofs()");
}

void ContactComponent::requireHostMultipliers() const {
  if (!multipliersInHost_)
    throw std::logic_error("ContactComponent: the multipliers are not in the host's vector (setDofs() got no "
                           "multiplier DOFs); pass them on multiplierMap()");
}

void ContactComponent::registerNodes(const std::vector<ContactNode>& nodes) {
  if (committed_) throw std::logic_error("ContactComponent::registerNodes after commit()");
  myNodes_.insert(myNodes_.end(), nodes.begin(), nodes.end());
}

int ContactComponent::registerPair(ContactPairSurfaces pair) {
  if (committed_) throw std::logic_error("ContactComponent::registerPair after commit()");
  Pair p;
  p.name = pair.name;
  p.path = pair.path.empty() ? pair.name : pair.path;
  p.slaveName = pair.slaveName;
  p.masterName = pair.masterName;
  p.slaveType = pair.slaveFacetType;
  p.masterType = pair.masterFacetType;
  p.mySlaves = std::move(pair.slaveNodes);
  p.mySlaveFacets = std::move(pair.slaveFacets);
  p.myMasterFacets = std::move(pair.masterFacets);
  pairs_.push_back(std::move(p));
  return static_cast<int>(pairs_.size()) - 1;
}

int ContactComponent::index(int id) const {
  const auto it = std::lower_bound(nodeIds_.begin(), nodeIds_.end(), id);
  return it != nodeIds_.end() && *it == id ? int(it - nodeIds_.begin()) : -1;
}

Eigen::Vector3d ContactComponent::referencePosition(int id) const {
  const int i = index(id);
  DDC_CHECK(i >= 0, "node " << id << " is not on a contact surface");
  return X_[i];
}

int ContactComponent::slotOwner(int k) const { return slotOwner_[k]; }

const std::string& ContactComponent::pairName(int p) const { return pairs_[p].name; }

int ContactComponent::numPairs() const { return static_cast<int>(pairs_.size()); }

void ContactComponent::commit() {
  if (committed_) throw std::logic_error("ContactComponent::commit called twice");
  const MPI_Comm mpi = rawComm(comm_);
  const int me = comm_->getRank();
  // 0. The space dimension: every pair's facets agree on it.
  for (size_t p = 0; p < pairs_.size(); ++p) {
    const Pair& pair = pairs_[p];
    for (CellType t : {pair.slaveType, pair.masterType}) {
      int d = 0;
      try {
        d = facetSpaceDimension(t);
      } catch (const std::invalid_argument&) {
        DDC_THROW(InputError, "contact pair '" << pair.path << "': " << cellTypeName(t)
                                               << " is not a facet cell type (Line2, Line3, Tri3, Tri6, Quad4, "
                                                  "Quad8, Quad9): contact surfaces are sides (2-D) or faces (3-D)");
      }
      const int first = facetSpaceDimension(pairs_[0].masterType);
      DDC_INPUT_REQUIRE(d == first, "contact pair '" << pair.path << "': its " << cellTypeName(t) << " facets are "
                                                     << d << "-D but pair '" << pairs_[0].path << "' has "
                                                     << cellTypeName(pairs_[0].masterType)
                                                     << " master facets; all contact surfaces have one dimension");
    }
  }
  if (!pairs_.empty()) dim_ = facetSpaceDimension(pairs_[0].masterType);
  // The surface contact elements of the facet types in use.
  for (const auto& pair : pairs_) {
    const auto roles = options_.decomposed
                           ? std::vector<SurfaceContactRole>{SurfaceContactRole::Slave, SurfaceContactRole::Master}
                           : std::vector<SurfaceContactRole>{SurfaceContactRole::Conventional};
    for (SurfaceContactRole role : roles) {
      auto& el = surfaceElements_[{role, pair.masterType}];
      if (el) continue;
      el = surfaceSource_(role, pair.masterType);
      if (!el || el->facet() != pair.masterType || el->role() != role || el->dim() != dim_)
        throw std::invalid_argument("ContactComponent: the surface contact element source gave no '" +
                                    surfaceContactElementName(role, pair.masterType) + "' element");
    }
  }
  // 1. Surface nodes: every rank learns every node and its owner.
  std::vector<NodeRecord> mine;
  for (const auto& n : myNodes_) mine.push_back({n.id, me, n.X.x(), n.X.y(), n.X.z()});
  std::vector<NodeRecord> all = allGather(mpi, mine);
  std::sort(all.begin(), all.end(), [](const NodeRecord& a, const NodeRecord& b) {
    return a.id < b.id || (a.id == b.id && a.rank < b.rank);
  });
  for (size_t i = 0; i < all.size(); ++i) {
    DDC_INPUT_REQUIRE(all[i].id >= 0, "contact: a surface node has the negative id " << all[i].id);
    DDC_INPUT_REQUIRE(i == 0 || all[i].id != all[i - 1].id,
                      "contact: surface node " << all[i].id << " is registered by ranks " << all[i - 1].rank << " and "
                                               << all[i].rank << "; each node must be registered once, by its owner");
    nodeIds_.push_back(all[i].id);
    X_.emplace_back(all[i].x, all[i].y, dim_ == 2 ? 0.0 : all[i].z);
    owner_.push_back(all[i].rank);
  }
  myNodes_.clear();
  myNodes_.shrink_to_fit();
  auto requireNode = [&](const Pair& p, int id, const char* role) {
    DDC_INPUT_REQUIRE(index(id) >= 0, "contact pair '" << p.path << "': " << role << " node " << id
                                                       << " is not a registered surface node (no rank registered it)");
  };

  // 2. Per pair: merge the facets and slave nodes, build the slots and the search.
  for (int p = 0; p < numPairs(); ++p) {
    Pair& pair = pairs_[p];
    auto gatherFacets = [&](const std::vector<ContactFacet>& facets, CellType type, const char* role) {
      const int m = numCellNodes(type);
      std::vector<FacetRecord> recs;
      for (const auto& f : facets) {
        FacetRecord r{f.id, m, {}, f.element, f.subdomain, me, f.depth};
        r.nodes.fill(-1);
        std::copy(f.nodes.begin(), f.nodes.end(), r.nodes.begin());
        recs.push_back(r);
      }
      auto merged = allGather(mpi, recs);
      std::sort(merged.begin(), merged.end(), [](const FacetRecord& a, const FacetRecord& b) { return a.id < b.id; });
      for (size_t i = 1; i < merged.size(); ++i)
        DDC_INPUT_REQUIRE(merged[i].id != merged[i - 1].id, "contact pair '" << pair.path << "': " << role << " facet "
                                                                             << merged[i].id
                                                                             << " is registered twice (ranks "
                                                                             << merged[i - 1].rank << " and "
                                                                             << merged[i].rank << ")");
      for (const auto& f : merged)
        for (int a = 0; a < f.numNodes; ++a) requireNode(pair, f.nodes[a], role);
      return merged;
    };
    // The facet sizes are checked on each rank's share: agree before merging.
    std::string error;
    for (const auto& [facets, type, role] :
         {std::make_tuple(&pair.mySlaveFacets, pair.slaveType, "slave"),
          std::make_tuple(&pair.myMasterFacets, pair.masterType, "master")})
      for (const auto& f : *facets)
        if (int(f.nodes.size()) != numCellNodes(type) && error.empty())
          error = "contact pair '" + pair.path + "': " + role + " facet " + std::to_string(f.id) + " has " +
                  std::to_string(f.nodes.size()) + " nodes; a " + cellTypeName(type) + " facet has " +
                  std::to_string(numCellNodes(type));
    raiseCollectively<InputError>(mpi, error);
    pair.slaveFacets = gatherFacets(pair.mySlaveFacets, pair.slaveType, "slave");
    pair.masterFacets = gatherFacets(pair.myMasterFacets, pair.masterType, "master");
    std::vector<int> slaveNodes = allGather(mpi, pair.mySlaves);
    std::sort(slaveNodes.begin(), slaveNodes.end());
    slaveNodes.erase(std::unique(slaveNodes.begin(), slaveNodes.end()), slaveNodes.end());
    pair.mySlaves.clear();
    pair.mySlaveFacets.clear();
    pair.myMasterFacets.clear();
    DDC_INPUT_REQUIRE(!pair.masterFacets.empty(), "contact pair '" << pair.path << "': the master surface '"
                                                                   << pair.masterName << "' has no facets");
    std::set<int> masterNodes;
    for (const auto& f : pair.masterFacets) masterNodes.insert(f.nodes.begin(), f.nodes.begin() + f.numNodes);
    std::vector<int> slaves;
    for (int n : slaveNodes) {
      if (masterNodes.count(n)) continue;  // a node of both surfaces (shared corner) is not a slave
      requireNode(pair, n, "slave");
      slaves.push_back(n);
    }
    DDC_INPUT_REQUIRE(!slaves.empty(), "contact pair '" << pair.path << "': the slave side set '" << pair.slaveName
                                                        << "' has no nodes off the master surface");
    // Both surfaces consistently oriented: a side two facets share is run
    // through in opposite directions (otherwise some normals point inwards).
    for (const auto* facets : {&pair.slaveFacets, &pair.masterFacets}) {
      const CellType type = facets == &pair.slaveFacets ? pair.slaveType : pair.masterType;
      std::map<std::pair<int, int>, long> directed;
      for (const auto& f : *facets) {
        if (referenceCell(type).dim == 1) {
          // Segments: a node is the start of one segment and the end of another.
          for (int end = 0; end < 2; ++end) {
            const auto [it, fresh] = directed.insert({{f.nodes[end], end}, f.id});
            DDC_INPUT_REQUIRE(fresh, "contact pair '" << pair.path << "': the "
                                                      << (facets == &pair.slaveFacets ? "slave" : "master")
                                                      << " surface is not consistently oriented: facets " << it->second
                                                      << " and " << f.id << " both " << (end ? "end" : "start")
                                                      << " at node " << f.nodes[end]
                                                      << " (a normal points into the body)");
          }
          continue;
        }
        for (const auto& e : referenceCell(type).edges) {
          const auto [it, fresh] = directed.insert({{f.nodes[e.start], f.nodes[e.end]}, f.id});
          DDC_INPUT_REQUIRE(fresh, "contact pair '" << pair.path << "': the "
                                                    << (facets == &pair.slaveFacets ? "slave" : "master")
                                                    << " surface is not consistently oriented: facets " << it->second
                                                    << " and " << f.id << " both run from node " << f.nodes[e.start]
                                                    << " to node " << f.nodes[e.end]
                                                    << " along their shared side (one of them has an inward normal)");
        }
      }
    }
    pair.slaves = slaves;
    std::map<int, double> tributary;
    {  // the slave node's share of the slave surface
      // The facet's measure lumped to its nodes by the HRZ rule (Hinton, Rock
      // & Zienkiewicz 1976): ∫N_i² dA scaled to the facet's measure, positive
      // for quadratic facets too, exact shares on regular linear facets.
      const QuadratureRule& q = facetQuadratureRule(pair.slaveType);
      const int m = numCellNodes(pair.slaveType);
      const int pd = referenceCell(pair.slaveType).dim;
      for (const auto& f : pair.slaveFacets) {
        std::vector<double> share(m, 0.0);
        double measure = 0.0, sum = 0.0;
        for (size_t g = 0; g < q.weights.size(); ++g) {
          Eigen::VectorXd N;
          Eigen::MatrixXd dN;
          shapeFunctions(pair.slaveType, q.points[g], &N, &dN);
          Eigen::Vector3d a[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
          for (int i = 0; i < m; ++i)
            for (int al = 0; al < pd; ++al) a[al] += dN(i, al) * X_[index(f.nodes[i])];
          const double J = pd == 1 ? a[0].norm() : a[0].cross(a[1]).norm();
          measure += q.weights[g] * J;
          for (int i = 0; i < m; ++i) share[i] += q.weights[g] * J * N[i] * N[i];
        }
        for (double s : share) sum += s;
        for (int i = 0; i < m; ++i) tributary[f.nodes[i]] += sum > 0 ? share[i] * measure / sum : 0.0;
      }
    }
    for (int n : slaves) {
      ContactSlot s;
      s.pair = p;
      s.slaveNode = n;
      s.tributaryLength = tributary[n];
      pair.slots.push_back(static_cast<int>(slots_.size()));
      slots_.push_back(s);
      slotOwner_.push_back(owner_[index(n)]);
    }
    // Margin of the bounding-box exchange: the search radius plus two
    // master facets (a slave's facet and its neighbours), with room
    // for stretching (x 2).
    double longest = 0.0;
    for (const auto& f : pair.masterFacets)
      for (int a = 0; a < f.numNodes; ++a)
        for (int b = a + 1; b < f.numNodes; ++b) {
          const Eigen::Vector3d d = X_[index(f.nodes[b])] - X_[index(f.nodes[a])];
          longest = std::max(longest, dim_ == 2 ? std::hypot(d.x(), d.y()) : d.norm());
        }
    pairingMargin_ = std::max(pairingMargin_, options_.searchRadius + 4.0 * longest);
    for (int n : masterNodes) masterSurfaceNodes_.push_back(n);
    std::vector<std::vector<int>> facets;
    for (size_t f = 0; f < pair.masterFacets.size(); ++f) {
      facets.push_back(pair.facetNodes(int(f)));
      DDC_INPUT_REQUIRE(pair.masterFacets[f].depth > 0.0, "contact pair '" << pair.path << "': master facet "
                                                                           << pair.masterFacets[f].id
                                                                           << " has no depth (> 0 expected)");
    }
    pair.facetSearch = std::make_unique<FacetSearch>(pair.masterType, facets, options_.searchRadius);
    for (size_t f = 0; f < pair.slaveFacets.size(); ++f)
      for (int a = 0; a < pair.slaveFacets[f].numNodes; ++a)
        pair.slaveFacetsAt[pair.slaveFacets[f].nodes[a]].emplace_back(int(f), a);
    for (int n : slaves)
      DDC_INPUT_REQUIRE(pair.slaveFacetsAt.count(n), "contact pair '" << pair.path << "': slave node " << n
                                                                       << " is on no facet of the slave surface '"
                                                                       << pair.slaveName
                                                                       << "' (slave nodes must lie on a surface)");
    // Free boundary: sides only one master facet has.
    std::map<std::vector<int>, int> count;
    for (const auto& f : pair.masterFacets)
      for (const auto& s : facetSides(pair.masterType, f.nodes.data())) ++count[s.key];
    for (const auto& f : pair.masterFacets) {
      pair.freeSides.emplace_back();
      for (const auto& s : facetSides(pair.masterType, f.nodes.data()))
        if (count[s.key] == 1) pair.freeSides.back().push_back(s.polyline);
    }
  }
  for (size_t k = 0; k < slots_.size(); ++k)
    if (slotOwner_[k] == me) localSlots_.push_back(static_cast<int>(k));

  // 3. Decomposed pairing (distributedSearch()): the slave nodal normals need
  //    the positions of the nodes of the slave facets at each slave node;
  //    those owned by another rank than the slave's are sent to it.
  if (options_.decomposed) {
    std::vector<std::pair<int, int>> sends;  // (node, rank) with node owned here
    for (const auto& pair : pairs_) {
      std::vector<int> slaveNodes;
      for (int k : pair.slots) slaveNodes.push_back(slots_[k].slaveNode);
      std::sort(slaveNodes.begin(), slaveNodes.end());
      for (const auto& f : pair.slaveFacets)
        for (int i = 0; i < f.numNodes; ++i) {
          const int a = f.nodes[i];
          if (!std::binary_search(slaveNodes.begin(), slaveNodes.end(), a)) continue;
          for (int j = 0; j < f.numNodes; ++j) {
            const int b = f.nodes[j];
            if (j == i) continue;
            const int oa = owner_[index(a)], ob = owner_[index(b)];
            if (ob == me && oa != ob) sends.emplace_back(b, oa);
          }
        }
    }
    std::sort(sends.begin(), sends.end());
    sends.erase(std::unique(sends.begin(), sends.end()), sends.end());
    slaveNeighbourSends_ = std::move(sends);
  }
  committed_ = true;
}

void ContactComponent::setDofs(Teuchos::RCP<const Map> hostMap, const std::vector<ContactNodeDofs>& nodeDofs,
                               const std::vector<GO>& multiplierDofs) {
  if (!committed_) throw std::logic_error("ContactComponent::setDofs before commit()");
  if (hasDofs_) throw std::logic_error("ContactComponent::setDofs called twice");
  const MPI_Comm mpi = rawComm(comm_);
  const int me = comm_->getRank();
  hostMap_ = hostMap;
  // Check locally, agree collectively: every rank throws the same message.
  std::string error;
  std::vector<char> given(nodeIds_.size(), 0);
  struct DofRecord {
    int id;
    GO d[3];
    int p[3];
  };
  std::vector<DofRecord> mine;
  for (const auto& nd : nodeDofs) {
    std::ostringstream os;
    const int i = index(nd.id);
    if (i < 0 || owner_[i] != me) {
      os << "contact: rank " << me << " gives DOFs for node " << nd.id << ", which "
         << (i < 0 ? "is not a registered surface node" : "rank " + std::to_string(i < 0 ? -1 : owner_[i]) +
                                                                 " registered");
    } else {
      for (int c = 0; c < dim_ && os.tellp() == 0; ++c)
        if (!hostMap->isNodeGlobalElement(nd.dofs[c]))
          os << "contact: surface node " << nd.id << " (rank " << me << ") has DOF id " << nd.dofs[c] << " for u_"
             << "xyz"[c] << ", which rank " << me << " does not own in the host's DOF map: register each surface "
             << "node on the rank that owns its DOFs";
    }
    if (os.tellp() != 0 && error.empty()) error = os.str();
    if (i >= 0) given[i] = 1;
    DofRecord r{nd.id, {nd.dofs[0], nd.dofs[1], nd.dofs[2]}, {nd.prescribed[0], nd.prescribed[1], nd.prescribed[2]}};
    mine.push_back(r);
  }
  if (error.empty() && !multiplierDofs.empty()) {
    if (multiplierDofs.size() != localSlots_.size()) {
      error = "contact: rank " + std::to_string(me) + " gives " + std::to_string(multiplierDofs.size()) +
              " multiplier DOFs for its " + std::to_string(localSlots_.size()) + " contact slots";
    } else {
      // A multiplier needs an id of its own: not a surface node's DOF, not
      // another multiplier's (the DOFs of the host's other nodes are beyond
      // what the component sees).
      std::map<GO, std::string> taken;
      for (const auto& nd : nodeDofs)
        for (int c = 0; c < dim_; ++c)
          taken[nd.dofs[c]] = std::string("the u_") + "xyz"[c] + " DOF of surface node " + std::to_string(nd.id);
      for (size_t i = 0; i < multiplierDofs.size() && error.empty(); ++i) {
        const GO g = multiplierDofs[i];
        if (!hostMap->isNodeGlobalElement(g)) {
          error = "contact: multiplier DOF id " + std::to_string(g) + " is not owned by rank " + std::to_string(me) +
                  " (the owner of its slave node) in the host's DOF map";
        } else if (const auto it = taken.find(g); it != taken.end()) {
          error = "contact: multiplier DOF id " + std::to_string(g) + " of " + describeSlot(localSlots_[i]) +
                  " is also " + it->second + ": each multiplier needs a DOF id of its own in the host's map";
        }
        taken[g] = "the multiplier of " + describeSlot(localSlots_[i]);
      }
    }
  }
  raiseCollectively<InputError>(mpi, error);
  // Multipliers in the host's vector: every rank or none.
  const bool hostLm = !multiplierDofs.empty() || localSlots_.empty();
  const bool allHost = !anyRank(mpi, !hostLm);
  const bool anyHost = anyRank(mpi, !multiplierDofs.empty());
  DDC_INPUT_REQUIRE(allHost || !anyHost, "contact: some ranks give multiplier DOFs to setDofs() and others do not");
  multipliersInHost_ = anyHost;

  // Replicate the DOF ids and prescribed flags.
  const auto all = allGather(mpi, mine);
  dofs_.assign(nodeIds_.size(), {{-1, -1, -1}});
  prescribed_.assign(nodeIds_.size(), {{0, 0, 0}});
  for (const auto& r : all) {
    const int i = index(r.id);
    for (int c = 0; c < dim_; ++c) {
      dofs_[i][c] = r.d[c];
      prescribed_[i][c] = char(r.p[c]);
    }
  }
  // Multiplier ids: the host's DOFs, or the slot index.
  lmGid_.assign(slots_.size(), -1);
  if (multipliersInHost_) {
    struct LmRecord {
      int slot;
      GO gid;
    };
    std::vector<LmRecord> lm;
    for (size_t i = 0; i < localSlots_.size(); ++i) lm.push_back({localSlots_[i], multiplierDofs[i]});
    for (const auto& r : allGather(mpi, lm)) lmGid_[r.slot] = r.gid;
  } else {
    for (size_t k = 0; k < slots_.size(); ++k) lmGid_[k] = GO(k);
  }
  std::vector<GO> ownedLm;
  for (int k : localSlots_) ownedLm.push_back(lmGid_[k]);
  multiplierMap_ = mapOf(ownedLm, comm_);
  multiplierAllMap_ = mapOf(lmGid_, comm_);
  lmAllImporter_ = Teuchos::rcp(new TpetraImport(multiplierMap_, multiplierAllMap_));
  // Replicated map of every surface DOF: the gather of the conventional
  // element and of the pairing outside step ends.
  std::vector<GO> gids;
  for (const auto& d : dofs_) gids.insert(gids.end(), d.begin(), d.begin() + dim_);
  surfaceMap_ = mapOf(gids, comm_);
  surfaceImporter_ = Teuchos::rcp(new TpetraImport(hostMap_, surfaceMap_));
  long received = 0;
  for (GO g : gids)
    if (!hostMap_->isNodeGlobalElement(g)) ++received;
  for (int k = 0; k < int(slots_.size()); ++k)
    if (slotOwner_[k] != me) ++received;
  long total = 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, received, Teuchos::outArg(total));
  bytesPerExchange_ = total * static_cast<long>(sizeof(double));
  hasDofs_ = true;
  buildTopology();
}

void ContactComponent::appendNodeDofs(int node, std::vector<GO>& dofs) const {
  const auto& d = dofs_[index(node)];
  dofs.insert(dofs.end(), d.begin(), d.begin() + dim_);
}

std::vector<GO> ContactComponent::slotDofs(int k) const {
  const ContactSlot& s = slots_[k];
  std::vector<GO> dofs;
  if (s.paired()) {
    appendNodeDofs(s.slaveNode, dofs);
    for (int a = 0; a < s.numMaster; ++a) appendNodeDofs(s.master[a], dofs);
  }
  dofs.push_back(lmGid_[k]);
  return dofs;
}

std::vector<GO> ContactComponent::slaveSideDofs(int k) const {
  std::vector<GO> dofs;
  appendNodeDofs(slots_[k].slaveNode, dofs);
  dofs.push_back(lmGid_[k]);
  return dofs;
}

std::vector<GO> ContactComponent::masterSideDofs(int k) const {
  std::vector<GO> dofs;
  for (int a = 0; a < slots_[k].numMaster; ++a) appendNodeDofs(slots_[k].master[a], dofs);
  dofs.push_back(lmGid_[k]);
  return dofs;
}

void ContactComponent::buildTopology() {
  const int me = comm_->getRank();
  // Decomposed: the master counterpart of a slot lives on the rank that
  // registered its master facet.
  localMasterSlots_.clear();
  if (options_.decomposed)
    for (size_t k = 0; k < slots_.size(); ++k)
      if (slots_[k].paired() && pairs_[slots_[k].pair].masterFacets[slots_[k].segment].rank == me)
        localMasterSlots_.push_back(static_cast<int>(k));
  // Host DOFs and multipliers this rank's evaluations read.
  std::vector<GO> dofs, lms;
  auto add = [&](const std::vector<GO>& d) {
    dofs.insert(dofs.end(), d.begin(), d.end() - 1);
    lms.push_back(d.back());
  };
  for (int k : localSlots_) add(options_.decomposed && slots_[k].paired() ? slaveSideDofs(k) : slotDofs(k));
  for (int k : localMasterSlots_) add(masterSideDofs(k));
  for (auto* v : {&dofs, &lms}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  dofOverlapMap_ = mapOf(dofs, comm_);
  dofImporter_ = Teuchos::rcp(new TpetraImport(hostMap_, dofOverlapMap_));
  lmOverlapMap_ = mapOf(lms, comm_);
  lmImporter_ = Teuchos::rcp(new TpetraImport(multiplierMap_, lmOverlapMap_));
  lmExporter_ = Teuchos::rcp(new TpetraExport(lmOverlapMap_, multiplierMap_));
  lmHostImporter_ = multipliersInHost_ ? Teuchos::rcp(new TpetraImport(hostMap_, lmOverlapMap_)) : Teuchos::null;
}

ContactComponent::Field ContactComponent::gatherField(const Vector& u, const Vector* multipliers) const {
  Field f;
  f.c = this;
  f.dof = Teuchos::rcp(new Vector(dofOverlapMap_));
  f.dof->doImport(u, *dofImporter_, Tpetra::INSERT);
  f.lm = Teuchos::rcp(new Vector(lmOverlapMap_));
  if (multipliers) {
    f.lm->doImport(*multipliers, *lmImporter_, Tpetra::INSERT);
  } else {
    requireHostMultipliers();
    f.lm->doImport(u, *lmHostImporter_, Tpetra::INSERT);
  }
  f.d = f.dof->getData();
  f.l = f.lm->getData();
  return f;
}

void ContactComponent::evaluate(int k, SurfaceContactRole role, const Field& f, bool forceActive, unsigned what,
                                ElementResult& er, std::vector<GO>& dofs) const {
  // The slave counterpart on [u_s, λ], the master counterpart on
  // [u_1..u_m, λ], the conventional element on [u_s, u_1..u_m, λ].
  const ContactSlot& s = slots_[k];
  dofs = role == SurfaceContactRole::Slave ? slaveSideDofs(k) : role == SurfaceContactRole::Master ? masterSideDofs(k)
                                                                                                    : slotDofs(k);
  ContactPairState state = s.state;
  state.active = s.active || forceActive;
  state.multiplier = f.multiplier(k);
  std::vector<int> nodes;
  if (role != SurfaceContactRole::Master) nodes.push_back(s.slaveNode);
  if (role != SurfaceContactRole::Slave) nodes.insert(nodes.end(), s.master.begin(), s.master.begin() + s.numMaster);
  const int nn = int(nodes.size());
  Eigen::MatrixXd X(nn, dim_), ue(nn, dim_);
  for (int i = 0; i < nn; ++i) {
    X.row(i) = X_[index(nodes[i])].head(dim_).transpose();
    for (int c = 0; c < dim_; ++c) ue(i, c) = f.at(dofs[dim_ * i + c]);
  }
  surfaceElement(role, pairs_[s.pair].masterType).computeSurfaceContact(X, ue, s.frozen, state, what, er);
}

const SurfaceContactElement& ContactComponent::surfaceElement(SurfaceContactRole role, CellType facet) const {
  const auto it = surfaceElements_.find({role, facet});
  DDC_CHECK(it != surfaceElements_.end(), "no " << surfaceContactElementName(role, facet) << " element");
  return *it->second;
}

void ContactComponent::assemble(const Vector& u, const Vector* multipliers, unsigned what,
                                const std::function<void(const std::vector<GO>&, ElementResult&)>& add) const {
  requireCommitted("assemble");
  requirePaired("assemble");
  const Field f = gatherField(u, multipliers);
  ElementResult er;
  std::vector<GO> dofs;
  // The conventional element of each owned slot, or the decomposed
  // counterparts where they live (the slave's on the owner of the slave node,
  // the master's on the rank of the master facet); they share only the
  // multiplier. Unpaired slots carry only Π = ½λ² (λ = 0).
  const SurfaceContactRole role = options_.decomposed ? SurfaceContactRole::Slave : SurfaceContactRole::Conventional;
  for (int k : localSlots_) {
    if (slots_[k].paired()) {
      evaluate(k, role, f, false, what | kTangent, er, dofs);
    } else {
      dofs.assign(1, lmGid_[k]);
      releasedContribution(1, f.multiplier(k), kAll, er);
    }
    add(dofs, er);
  }
  for (int k : localMasterSlots_) {
    evaluate(k, SurfaceContactRole::Master, f, false, what | kTangent, er, dofs);
    add(dofs, er);
  }
}

std::vector<ContactRowEntry> ContactComponent::contactRows() const {
  requireCommitted("contactRows");
  requirePaired("contactRows");
  std::vector<ContactRowEntry> out;
  if (!options_.decomposed) return out;
  // Zero state: the coefficients do not depend on it (frozen geometry).
  Field f;
  f.c = this;
  f.dof = Teuchos::rcp(new Vector(dofOverlapMap_));
  f.lm = Teuchos::rcp(new Vector(lmOverlapMap_));
  f.d = f.dof->getData();
  f.l = f.lm->getData();
  ElementResult er;
  std::vector<GO> dofs;
  auto add = [&](int k, SurfaceContactRole role) {
    evaluate(k, role, f, true, kTangent, er, dofs);
    const int row = int(dofs.size()) - 1;
    const int sub =
        role == SurfaceContactRole::Master ? pairs_[slots_[k].pair].masterFacets[slots_[k].segment].subdomain : -1;
    for (int a = 0; a < row; ++a)
      if (er.tangent(row, a) != 0.0) out.push_back({k, lmGid_[k], dofs[a], er.tangent(row, a), role, sub});
  };
  for (int k : localSlots_)
    if (slots_[k].paired()) add(k, SurfaceContactRole::Slave);
  for (int k : localMasterSlots_) add(k, SurfaceContactRole::Master);
  return out;
}

// ---- pairing -------------------------------------------------------------------

void ContactComponent::gatherSurface(const Vector& u, const Vector* multipliers, std::vector<double>& values) const {
  // Surface DOFs, then every slot's multiplier: one exchange.
  Vector s(surfaceMap_);
  s.doImport(u, *surfaceImporter_, Tpetra::INSERT);
  Vector lm(multiplierAllMap_);
  if (multipliers) {
    lm.doImport(*multipliers, *lmAllImporter_, Tpetra::INSERT);
  } else {
    requireHostMultipliers();
    Vector owned(multiplierMap_);
    auto ud = u.getData();
    for (size_t i = 0; i < localSlots_.size(); ++i)
      owned.replaceLocalValue(LO(i), ud[hostMap_->getLocalElement(lmGid_[localSlots_[i]])]);
    lm.doImport(owned, *lmAllImporter_, Tpetra::INSERT);
  }
  ++exchanges_;
  bytesExchanged_ += bytesPerExchange_;
  auto d = s.getData();
  values.assign(d.begin(), d.end());
  auto l = lm.getData();
  for (size_t k = 0; k < slots_.size(); ++k) values.push_back(l[multiplierAllMap_->getLocalElement(lmGid_[k])]);
}

Eigen::Vector3d ContactComponent::currentPosition(int id, const std::vector<double>& v) const {
  const int i = index(id);
  DDC_CHECK(i >= 0, "node " << id << " is not on a contact surface");
  Eigen::Vector3d x = X_[i];
  for (int c = 0; c < dim_; ++c) x[c] += v[size_t(dim_) * i + c];
  return x;
}

namespace {
/// A surface node's current position, sent to the ranks whose slave bounding
/// box contains it (D coordinates: the 2-D records stay as small as before).
template <int D>
struct NodePosition {
  int node;
  double x[D];
};
/// The pairing of one slot, found by the owner of its slave node.
template <int D>
struct SlotPairing {
  enum Flag { kPastFreeEnd = 1, kViaCorner = 2, kNotFacing = 4 };
  int slot, facet, flags;
  double xi[D - 1], gap, distance, n[D];
};
}  // namespace

Eigen::MatrixXd ContactComponent::facetPositions(const Pair& pair, int f,
                                                 const std::function<Eigen::Vector3d(int)>& position) const {
  const FacetRecord& r = pair.masterFacets[f];
  Eigen::MatrixXd x(r.numNodes, dim_);
  for (int a = 0; a < r.numNodes; ++a) x.row(a) = position(r.nodes[a]).head(dim_).transpose();
  return x;
}

Eigen::Vector3d ContactComponent::slaveNormal(const Pair& pair, int node,
                                              const std::function<Eigen::Vector3d(int)>& position) const {
  // The normalised sum of the unit outward normals of the slave facets at
  // the node, each at the node's reference coordinates in that facet.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const auto it = pair.slaveFacetsAt.find(node);
  if (it == pair.slaveFacetsAt.end()) return sum;
  const ReferenceCell& ref = referenceCell(pair.slaveType);
  for (const auto& [f, a] : it->second) {
    const FacetRecord& r = pair.slaveFacets[f];
    Eigen::MatrixXd x(r.numNodes, dim_);
    for (int b = 0; b < r.numNodes; ++b) x.row(b) = position(r.nodes[b]).head(dim_).transpose();
    Eigen::Vector3d point, normal;
    if (facetPointAndNormal(pair.slaveType, x, {ref.nodes[a][0], ref.nodes[a][1]}, point, normal)) sum += normal;
  }
  const double n = sum.norm();
  // Normals that cancel (a fold of the slave surface) give no direction: such
  // a node faces nothing.
  return n > 0.0 ? Eigen::Vector3d(sum / n) : Eigen::Vector3d::Zero();
}

std::vector<ContactComponent::Found> ContactComponent::facetPairing(
    const Pair& pair, FacetSearch& search, const std::vector<int>& facets, const std::vector<int>& slaves,
    const std::function<Eigen::Vector3d(int)>& position) const {
  // doc/contact.md, "Curved facets and 3-D": the nearest point of the
  // surface (interior projection, else the nearest point of a facet's
  // boundary with the direction as normal); not paired if that point is on
  // the surface's free boundary (past its edge) or the facing rule rejects it.
  std::vector<Found> out(slaves.size());
  for (size_t i = 0; i < slaves.size(); ++i) {
    const FacetCandidate& c = search.candidates()[i];
    Found& f = out[i];
    f.slaveNormal = slaveNormal(pair, slaves[i], position);
    if (c.facet < 0) continue;
    const int g = facets[c.facet];
    const Eigen::Vector3d xs = position(slaves[i]);
    f.xi = c.xi;
    f.viaCorner = c.kind != FacetPointKind::Interior;
    if (f.viaCorner) {
      // The nearest boundary point on the facet itself (x(ξ) of the chord
      // point's reference coordinates) is the projection, and the facet's
      // normal there the normal: g = n·(x_s − x(ξ)), as the 2-D segments
      // pair "via corner" with the nearest segment's normal (so an extruded
      // 2-D model pairs exactly as in 2-D). The slave never loses a convex
      // edge or corner it presses on.
      Eigen::Vector3d point, normal;
      facetPointAndNormal(pair.masterType, facetPositions(pair, g, position), c.xi, point, normal);
      const Eigen::Vector3d d = xs - point;
      f.distance = d.norm();
      f.gap = normal.dot(d);
      f.normal = normal;
      // Past the free boundary: the point lies on a side no other facet has
      // and the slave lies beyond that side, along the facet's outward
      // in-surface direction m across it, by more than kFreeBoundaryMargin
      // of the facet's size. A slave beside a convex ridge that ends at the
      // free boundary (d·m = 0) keeps its pairing, and so does a slave
      // surface that ends flush with the master surface (two bodies of one
      // depth): its edge nodes drift across the master's edge by round-off
      // and Poisson contraction, and would flip in and out of contact.
      constexpr double kFreeBoundaryMargin = 1e-2;
      const Eigen::MatrixXd x = facetPositions(pair, g, position);
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      const int corners = referenceCell(pair.masterType).numCorners;
      double size = 0.0;
      for (int a = 0; a < corners; ++a) {
        centre.head(dim_) += x.row(a).transpose() / corners;
        for (int b = a + 1; b < corners; ++b) size = std::max(size, (x.row(a) - x.row(b)).norm());
      }
      const double onSide = 1e-9 * size;  // round-off: the chord point is computed from these nodes
      for (const auto& side : pair.freeSides[g]) {
        // The side's pieces: its chords, or the end node of a segment.
        const size_t pieces = side.size() == 1 ? 1 : side.size() - 1;
        for (size_t a = 0; a < pieces && !f.pastFreeEnd; ++a) {
          const Eigen::Vector3d p = position(side[a]), q = position(side[side.size() == 1 ? a : a + 1]);
          const Eigen::Vector3d t = q - p;
          const double s = t.squaredNorm() > 0 ? std::clamp((c.point - p).dot(t) / t.squaredNorm(), 0.0, 1.0) : 0.0;
          if ((c.point - p - s * t).norm() > onSide) continue;
          Eigen::Vector3d m = c.point - centre;
          m -= m.dot(normal) * normal;
          if (t.squaredNorm() > 0) m -= m.dot(t) / t.squaredNorm() * t;
          f.pastFreeEnd = m.norm() > 0 && d.dot(m) > kFreeBoundaryMargin * size * m.norm();
        }
      }
    } else {
      f.gap = c.gap;
      f.distance = c.distance;
      f.normal = c.normal;
    }
    f.facet = g;
    if (f.pastFreeEnd) continue;
    const double limit = kFacingDepthFraction * pair.masterFacets[g].depth;
    const ContactRejection verdict = facingVerdict(f.slaveNormal, f.normal, f.gap, limit);
    if (verdict != ContactRejection::None) f.facet = -1;
    f.notFacing = verdict == ContactRejection::NotFacing;
  }
  return out;
}

void ContactComponent::replicatedSearch(const std::function<Eigen::Vector3d(int)>& position, bool global,
                                        std::vector<std::vector<Found>>& found) {
  found.assign(pairs_.size(), {});
  for (size_t p = 0; p < pairs_.size(); ++p) {
    Pair& pair = pairs_[p];
    std::vector<int> all(pair.masterFacets.size());
    for (size_t g = 0; g < all.size(); ++g) all[g] = int(g);
    pair.facetSearch->update(
        pair.slaves, [&](int n) { return Eigen::VectorXd(position(n).head(dim_)); }, global);
    found[p] = facetPairing(pair, *pair.facetSearch, all, pair.slaves, position);
  }
}

void ContactComponent::distributedSearch(const Vector& u, std::vector<std::vector<Found>>& found) {
  if (dim_ == 2)
    distributedSearchIn<2>(u, found);
  else
    distributedSearchIn<3>(u, found);
}

template <int D>
void ContactComponent::distributedSearchIn(const Vector& u, std::vector<std::vector<Found>>& found) {
  const MPI_Comm mpi = rawComm(comm_);
  const int me = comm_->getRank(), P = comm_->getSize();
  auto ud = u.getData();
  auto ownedPosition = [&](int n) {
    const int i = index(n);
    Eigen::Vector3d x = X_[i];
    for (int c = 0; c < D; ++c) x[c] += ud[hostMap_->getLocalElement(dofs_[i][c])];
    return x;
  };
  auto owner = [&](int n) { return owner_[index(n)]; };
  // 1. Bounding box of this rank's slave nodes, inflated by a margin that
  //    covers every master facet (and its neighbours) a slave can pair with.
  double box[2 * D];
  for (int c = 0; c < D; ++c) box[c] = 1e300, box[D + c] = -1e300;
  for (int k : localSlots_) {
    const Eigen::Vector3d x = ownedPosition(slots_[k].slaveNode);
    for (int c = 0; c < D; ++c) box[c] = std::min(box[c], x[c]), box[D + c] = std::max(box[D + c], x[c]);
  }
  std::vector<double> boxes(2 * D * P);
  MPI_Allgather(box, 2 * D, MPI_DOUBLE, boxes.data(), 2 * D, MPI_DOUBLE, mpi);
  // 2. Each rank sends the current positions of the master-surface nodes it
  //    owns to the ranks whose inflated box contains them.
  std::vector<std::vector<NodePosition<D>>> send(P);
  auto record = [](int n, const Eigen::Vector3d& x) {
    NodePosition<D> r{n, {}};
    for (int c = 0; c < D; ++c) r.x[c] = x[c];
    return r;
  };
  for (int n : masterSurfaceNodes_) {
    if (owner(n) != me) continue;
    const Eigen::Vector3d x = ownedPosition(n);
    for (int r = 0; r < P; ++r) {
      const double* b = &boxes[2 * D * r];
      bool inside = true;
      for (int c = 0; c < D; ++c) inside = inside && x[c] >= b[c] - pairingMargin_ && x[c] <= b[D + c] + pairingMargin_;
      if (inside) send[r].push_back(record(n, x));
    }
  }
  //    With them, the slave-surface neighbours of other ranks' slave nodes
  //    (the facing rule's nodal normals), unless already on the way.
  for (const auto& [node, r] : slaveNeighbourSends_) {
    const int n = node;
    if (std::any_of(send[r].begin(), send[r].end(), [n](const NodePosition<D>& q) { return q.node == n; })) continue;
    send[r].push_back(record(n, ownedPosition(n)));
  }
  long bytes = 0;
  for (int r = 0; r < P; ++r)
    if (r != me) bytes += long(send[r].size() * sizeof(NodePosition<D>));
  const std::vector<NodePosition<D>> recv = exchangeRecords(mpi, send);
  std::map<int, Eigen::Vector3d> known;
  for (const auto& np : recv) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int c = 0; c < D; ++c) x[c] = np.x[c];
    known[np.node] = x;
  }
  for (int k : localSlots_) known[slots_[k].slaveNode] = ownedPosition(slots_[k].slaveNode);
  for (const auto& pair : pairs_)  // slave-surface neighbours owned here
    for (const auto& f : pair.slaveFacets)
      for (int a = 0; a < f.numNodes; ++a)
        if (owner(f.nodes[a]) == me && !known.count(f.nodes[a])) known[f.nodes[a]] = ownedPosition(f.nodes[a]);
  auto position = [&](int n) { return known.at(n); };
  // 3. Per pair: the global search for this rank's slaves over the master
  //    facets whose nodes arrived (kept in their global order, so ties
  //    break as in the replicated search).
  std::vector<std::vector<SlotPairing<D>>> results(P);
  long queries = 0;
  for (const auto& pair : pairs_) {
    std::vector<int> localSlaves, localSlotIds;
    for (int k : pair.slots)
      if (slotOwner_[k] == me) localSlaves.push_back(slots_[k].slaveNode), localSlotIds.push_back(k);
    std::vector<int> globalIndex;
    for (int g = 0; g < int(pair.masterFacets.size()); ++g) {
      const FacetRecord& r = pair.masterFacets[g];
      if (std::all_of(r.nodes.begin(), r.nodes.begin() + r.numNodes, [&](int n) { return known.count(n) > 0; }))
        globalIndex.push_back(g);
    }
    std::vector<Found> here(localSlaves.size());
    if (!localSlaves.empty() && !globalIndex.empty()) {
      queries += long(localSlaves.size());
      std::vector<std::vector<int>> facets;
      for (int g : globalIndex) facets.push_back(pair.facetNodes(g));
      FacetSearch search(pair.masterType, facets, options_.searchRadius);
      search.update(localSlaves, [&](int n) { return Eigen::VectorXd(known.at(n).head(D)); }, true);
      here = facetPairing(pair, search, globalIndex, localSlaves, position);
    }
    for (size_t i = 0; i < here.size(); ++i) {
      const Found& f = here[i];
      const int flags = (f.pastFreeEnd ? SlotPairing<D>::kPastFreeEnd : 0) | (f.viaCorner ? SlotPairing<D>::kViaCorner : 0) |
                        (f.notFacing ? SlotPairing<D>::kNotFacing : 0);
      SlotPairing<D> rec{localSlotIds[i], f.facet, flags, {}, f.gap, f.distance, {}};
      for (int a = 0; a < D - 1; ++a) rec.xi[a] = f.xi[a];
      for (int c = 0; c < D; ++c) rec.n[c] = f.normal[c];
      for (int r = 0; r < P; ++r) results[r].push_back(rec);
    }
  }
  for (int r = 0; r < P; ++r)
    if (r != me) bytes += long(results[r].size() * sizeof(SlotPairing<D>));
  // 4. Every rank learns every slot's pairing (the slots are replicated).
  const std::vector<SlotPairing<D>> all = exchangeRecords(mpi, results);
  found.assign(pairs_.size(), {});
  std::vector<int> indexInPair(slots_.size(), -1);
  for (size_t p = 0; p < pairs_.size(); ++p) {
    found[p].assign(pairs_[p].slots.size(), Found{});
    for (size_t i = 0; i < pairs_[p].slots.size(); ++i) indexInPair[pairs_[p].slots[i]] = int(i);
  }
  for (const auto& a : all) {
    Found& f = found[slots_[a.slot].pair][indexInPair[a.slot]];
    f.facet = a.facet;
    f.pastFreeEnd = (a.flags & SlotPairing<D>::kPastFreeEnd) != 0;
    f.viaCorner = (a.flags & SlotPairing<D>::kViaCorner) != 0;
    f.notFacing = (a.flags & SlotPairing<D>::kNotFacing) != 0;
    for (int c = 0; c < D - 1; ++c) f.xi[c] = a.xi[c];
    f.gap = a.gap;
    f.distance = a.distance;
    for (int c = 0; c < D; ++c) f.normal[c] = a.n[c];
  }
  long total[2] = {bytes, queries}, sum[2];
  MPI_Allreduce(total, sum, 2, MPI_LONG, MPI_SUM, mpi);
  ++exchanges_;
  bytesExchanged_ += sum[0];
  distributedQueries_ += sum[1];
}

bool ContactComponent::updatePairing(const Vector& u, bool global, bool freeze, std::vector<int>* changedSlots) {
  requireCommitted("updatePairing");
  // Decomposed contact pairs at step ends only (global search): the
  // geometry goes only where bounding boxes say it is needed. Conventional
  // NTS (the monolithic reference) tracks the pairing inside Newton on
  // replicated surface positions.
  const bool distributed = options_.decomposed && global;
  std::vector<double> v;
  std::vector<std::vector<Found>> found;
  auto position = [&](int n) { return currentPosition(n, v); };
  if (distributed) {
    distributedSearch(u, found);
  } else {
    // Positions only: the multipliers are not read here.
    Vector s(surfaceMap_);
    s.doImport(u, *surfaceImporter_, Tpetra::INSERT);
    ++exchanges_;
    bytesExchanged_ += bytesPerExchange_;
    auto d = s.getData();
    v.assign(d.begin(), d.end());
    replicatedSearch(position, global, found);
  }
  bool changed = false;
  for (size_t p = 0; p < pairs_.size(); ++p) {
    const Pair& pair = pairs_[p];
    for (size_t i = 0; i < found[p].size(); ++i) {
      ContactSlot& s = slots_[pair.slots[i]];
      const Found& c = found[p][i];
      const bool paired = c.facet >= 0 && !c.pastFreeEnd;
      // Hysteresis (Newton iterations only): a slave whose projection onto
      // its previous facet lies within kPairingHysteresis of that facet
      // keeps it. Without it a slave sitting on a master node can flip
      // between the two adjacent facets every iteration and Newton stalls;
      // and a slave sitting on the free end of the master surface (two
      // blocks of one width) flips between paired and "past the end" with
      // the round-off of its position (a different summation order on two
      // ranks is enough), which the active-set check reports as cycling.
      constexpr double kPairingHysteresis = 1e-2;  // fraction of the facet's reference size
      // The kept facet must pass the facing rule like any pairing.
      if (!distributed && !global && s.paired() && (paired ? c.facet != s.segment : c.pastFreeEnd)) {
        const FacetProjection pr = projectOntoFacet(pair.masterType, facetPositions(pair, s.segment, position),
                                                    currentPosition(s.slaveNode, v).head(dim_));
        const double h = 2.0 * kPairingHysteresis;  // reference facets have sides 1 (simplex) or 2
        const bool near = pr.converged && (referenceCell(pair.masterType).simplex
                                               ? pr.xi[0] >= -h / 2 && pr.xi[1] >= -h / 2 &&
                                                     pr.xi[0] + pr.xi[1] <= 1 + h / 2
                                               : std::abs(pr.xi[0]) <= 1 + h &&
                                                     (dim_ == 2 || std::abs(pr.xi[1]) <= 1 + h));
        if (near && facingVerdict(c.slaveNormal, pr.normal, pr.gap,
                                  kFacingDepthFraction * pair.masterFacets[s.segment].depth) ==
                        ContactRejection::None) {
          s.gap = pr.gap;
          s.normal = pr.normal;
          if (freeze) s.frozen = {pr.xi, pr.normal};
          continue;
        }
      }
      const int facet = paired ? c.facet : -1;
      if (facet != s.segment) {
        changed = true;
        if (changedSlots) changedSlots->push_back(pair.slots[i]);
      }
      s.segment = facet;
      s.master.fill(-1);
      s.numMaster = 0;
      s.masterElement = -1;
      if (facet < 0) {
        s.active = false;
        s.gap = 0.0;
        continue;
      }
      const FacetRecord& r = pair.masterFacets[facet];
      std::copy(r.nodes.begin(), r.nodes.begin() + r.numNodes, s.master.begin());
      s.numMaster = r.numNodes;
      s.masterElement = r.element;
      s.gap = c.gap;
      s.normal = c.normal;
      if (freeze) s.frozen = {c.xi, c.normal};
    }
  }
  notePairing(found);
  pairedOnce_ = true;
  if (changed) buildTopology();
  return changed;
}

void ContactComponent::notePairing(const std::vector<std::vector<Found>>& found) {
  // `found` and the slots are the same on every rank: so are the warnings.
  everPaired_.resize(pairs_.size(), 0);
  facingReported_.resize(pairs_.size(), 0);
  for (size_t p = 0; p < pairs_.size(); ++p) {
    const Pair& pair = pairs_[p];
    int notFacing = 0, example = -1;
    for (size_t i = 0; i < pair.slots.size() && i < found[p].size(); ++i) {
      if (slots_[pair.slots[i]].paired()) everPaired_[p] = 1;
      if (found[p][i].notFacing && !slots_[pair.slots[i]].paired() && notFacing++ == 0) example = int(i);
    }
    if (everPaired_[p] || facingReported_[p] || notFacing == 0) continue;
    facingReported_[p] = 1;
    const int node = slots_[pair.slots[example]].slaveNode;
    const Eigen::Vector3d x = X_[index(node)], n = found[p][example].normal + Eigen::Vector3d::Zero();  // + 0: no "-0"
    std::ostringstream os;
    os << "contact pair '" << pair.path << "': none of its " << pair.slots.size() << " slave nodes pairs, and "
       << notFacing << " of them lie within the search radius of master facets that do not face them (e.g. slave "
       << "node " << node << " at (" << x.x() << ", " << x.y();
    if (dim_ == 3) os << ", " << x.z();
    os << "), nearest master facet normal (" << n.x() << ", " << n.y();
    if (dim_ == 3) os << ", " << n.z();
    os << ")): the master side set '" << pair.masterName << "' faces away from or across the slave side set '"
       << pair.slaveName << "'; contact there is not enforced (doc/contact.md, 'Which slave nodes pair')";
    warnings_.push_back(os.str());
  }
}

std::vector<std::string> ContactComponent::takeWarnings() {
  std::vector<std::string> out;
  out.swap(warnings_);
  return out;
}

std::vector<std::string> ContactComponent::neverPairedPairs() const {
  std::vector<std::string> out;
  for (size_t p = 0; p < pairs_.size(); ++p)
    if (p >= everPaired_.size() || !everPaired_[p])
      out.push_back("contact pair '" + pairs_[p].path + "' (slave '" + pairs_[p].slaveName + "', master '" +
                    pairs_[p].masterName + "')");
  return out;
}

std::vector<char> ContactComponent::pairedRecord() const {
  std::vector<char> out(pairs_.size(), 0);
  for (size_t p = 0; p < pairs_.size() && p < everPaired_.size(); ++p) out[p] = everPaired_[p];
  return out;
}

void ContactComponent::addPairedRecord(const std::vector<char>& record) {
  if (record.size() != pairs_.size())
    throw std::invalid_argument("addPairedRecord: " + std::to_string(record.size()) + " entries for " +
                                std::to_string(pairs_.size()) + " pairs");
  everPaired_.resize(pairs_.size(), 0);
  for (size_t p = 0; p < pairs_.size(); ++p)
    if (record[p]) everPaired_[p] = 1;
}

void ContactComponent::checkInitialPenetration(
    const std::vector<std::function<int(const Eigen::VectorXd&)>>& locate) const {
  // doc/contact.md "Which slave nodes pair": a slave node inside the master
  // body that the search does not pair keeps λ = 0 for ever, so the bodies
  // would silently stay overlapped there. Reference configuration,
  // replicated surfaces and slots: every rank reaches the same verdict.
  auto reference = [&](int n) { return referencePosition(n); };
  for (size_t p = 0; p < pairs_.size() && p < locate.size(); ++p) {
    if (!locate[p]) continue;
    const Pair& pair = pairs_[p];
    int first = -1, count = 0, element = -1;
    for (int k : pair.slots) {
      if (slots_[k].paired()) continue;
      const int e = locate[p](Eigen::VectorXd(referencePosition(slots_[k].slaveNode).head(dim_)));
      if (e < 0) continue;
      if (first < 0) first = k, element = e;
      ++count;
    }
    if (first < 0) continue;
    const int node = slots_[first].slaveNode;
    const Eigen::Vector3d xs = reference(node);
    std::ostringstream why, where;
    where << "(" << xs.x() << ", " << xs.y();
    if (dim_ == 3) where << ", " << xs.z();
    where << ")";
    double depth = std::numeric_limits<double>::infinity();
    // Why the first such node is not paired: the nearest point of the
    // whole surface (all facets: a diagnostic, once), then the pairing
    // rules on that facet. In 2-D a facet is a segment of the side set.
    const char* word = referenceCell(pair.masterType).dim == 1 ? "segment" : "facet";
    auto vec = [&](const Eigen::Vector3d& a) {
      std::ostringstream o;
      const Eigen::Vector3d z = a + Eigen::Vector3d::Zero();  // + 0: no "-0"
      o << "(" << z.x() << ", " << z.y();
      if (dim_ == 3) o << ", " << z.z();
      o << ")";
      return o.str();
    };
    FacetCandidate nearest;
    nearest.distance = std::numeric_limits<double>::infinity();
    for (int g = 0; g < int(pair.masterFacets.size()); ++g) {
      FacetCandidate c = nearestPoint(pair.masterType, facetPositions(pair, g, reference), xs.head(dim_));
      c.facet = g;
      if (c.distance < nearest.distance) nearest = c;
    }
    depth = nearest.distance;
    FacetSearch probe(pair.masterType, {pair.facetNodes(nearest.facet)},
                      std::max(2.0 * nearest.distance, std::numeric_limits<double>::min()));
    probe.update({node}, [&](int n) { return Eigen::VectorXd(reference(n).head(dim_)); }, true);
    const Found f = facetPairing(pair, probe, {nearest.facet}, {node}, reference)[0];
    const FacetRecord& r = pair.masterFacets[nearest.facet];
    std::ostringstream facet;
    facet << word << " " << r.id << " (element " << r.element << ")";
    const double limit = kFacingDepthFraction * r.depth;
    if (nearest.distance > options_.searchRadius) {
      why << "it is farther than the search radius (" << options_.searchRadius
          << ", Contact/Search Radius) from every master " << word;
    } else if (f.pastFreeEnd) {
      why << "its nearest point of the master surface is on the surface's free boundary (" << facet.str() << ")";
    } else if (!(f.slaveNormal.dot(f.normal) < 0.0)) {
      why << "its outward normal " << vec(f.slaveNormal) << " does not face the outward normal " << vec(f.normal)
          << " of its nearest master " << facet.str();
    } else {
      why << "it lies " << -f.gap << " behind its nearest master " << facet.str() << ", not less than half the depth of that "
          << word << "'s element (" << limit << " = " << kFacingDepthFraction << " x " << r.depth << ")";
    }
    DDC_THROW(InputError, "contact pair '"
                              << pair.path << "': slave node " << node << " at " << where.str()
                              << " of the slave side set '" << pair.slaveName
                              << "' starts inside the master body (element " << element << "), at depth " << depth
                              << " below the master side set '" << pair.masterName
                              << "', and contact cannot push it out: " << why.str()
                              << " (doc/contact.md, 'Which slave nodes pair')"
                              << (count > 1 ? "; " + std::to_string(count - 1) + " more slave node(s) of this pair likewise"
                                            : std::string())
                              << ". Move the bodies apart so that they at most touch, or overlap by less than half an "
                                 "element, in the reference configuration");
  }
}

std::array<long, 3> ContactComponent::searchCounters() const {
  std::array<long, 3> c{0, 0, distributedQueries_};
  for (const auto& p : pairs_) {
    c[0] += p.facetSearch->trackingQueries();
    c[1] += p.facetSearch->trackingFallbacks();
    c[2] += p.facetSearch->globalQueries();
  }
  return c;
}

bool ContactComponent::fullyPrescribed(int k) const {
  const ContactSlot& s = slots_[k];
  if (!s.paired()) return false;
  auto prescribed = [&](int n) {
    for (int c = 0; c < dim_; ++c)
      if (!prescribed_[index(n)][c]) return false;
    return true;
  };
  if (!prescribed(s.slaveNode)) return false;
  for (int a = 0; a < s.numMaster; ++a)
    if (!prescribed(s.master[a])) return false;
  return true;
}

void ContactComponent::activateAllPaired() {
  // A pair whose DOFs are all prescribed has a prescribed gap: its
  // constraint row would be empty (a singular system), so it never becomes
  // active (updateActiveSet() reports it if it penetrates).
  for (size_t k = 0; k < slots_.size(); ++k) slots_[k].active = slots_[k].paired() && !fullyPrescribed(int(k));
}

void ContactComponent::refreshSlotGeometry(const std::vector<double>& v) {
  const size_t base = size_t(dim_) * nodeIds_.size();
  auto position = [&](int n) { return currentPosition(n, v); };
  for (size_t k = 0; k < slots_.size(); ++k) {
    ContactSlot& s = slots_[k];
    s.state.multiplier = v[base + k];
    if (!s.paired()) continue;
    const Pair& pair = pairs_[s.pair];
    // The conventional element's own projection (DDC_NodeToSurface.hpp).
    const FacetProjection pr = projectOntoFacet(pair.masterType, facetPositions(pair, s.segment, position),
                                                position(s.slaveNode).head(dim_));
    s.normal = pr.normal;
    s.gap = pr.gap;
  }
}

void ContactComponent::assembleFrozenGaps(const Vector& u, const Vector* multipliers) {
  // Partial gaps of the counterparts at their multipliers, summed on the
  // multiplier map (Export ADD), then (g_N, λ) of every slot to every rank.
  // Only multiplier-map values travel, no geometry.
  const Field f = gatherField(u, multipliers);
  Vector gOv(lmOverlapMap_), gOwned(multiplierMap_);
  {
    auto g = gOv.getDataNonConst();
    ElementResult er;
    std::vector<GO> dofs;
    for (int k : localSlots_)
      if (slots_[k].paired()) {
        evaluate(k, SurfaceContactRole::Slave, f, true, kResidual, er, dofs);
        g[lmOverlapMap_->getLocalElement(lmGid_[k])] += er.residual[er.residual.size() - 1];
      }
    for (int k : localMasterSlots_) {
      evaluate(k, SurfaceContactRole::Master, f, true, kResidual, er, dofs);
      g[lmOverlapMap_->getLocalElement(lmGid_[k])] += er.residual[er.residual.size() - 1];
    }
  }
  gOwned.doExport(gOv, *lmExporter_, Tpetra::ADD);
  MultiVector owned(multiplierMap_, 2), all(multiplierAllMap_, 2);
  {
    auto g = gOwned.getData();
    for (size_t i = 0; i < localSlots_.size(); ++i) {
      owned.replaceLocalValue(LO(i), 0, g[i]);
      owned.replaceLocalValue(LO(i), 1, f.multiplier(localSlots_[i]));
    }
  }
  all.doImport(owned, *lmAllImporter_, Tpetra::INSERT);
  auto g = all.getData(0), lam = all.getData(1);
  for (size_t k = 0; k < slots_.size(); ++k) {
    ContactSlot& s = slots_[k];
    const LO l = multiplierAllMap_->getLocalElement(lmGid_[k]);
    s.state.multiplier = lam[l];
    if (!s.paired()) continue;
    s.normal = s.frozen.normal;
    s.gap = g[l];
  }
}

std::vector<int> ContactComponent::updateActiveSet(const Vector& u, const Vector* multipliers) {
  requireCommitted("updateActiveSet");
  if (options_.decomposed) {
    assembleFrozenGaps(u, multipliers);
  } else {
    std::vector<double> v;
    gatherSurface(u, multipliers, v);
    refreshSlotGeometry(v);
  }
  // Tension threshold: λ > 0 up to round-off of the largest multiplier.
  double lmax = 0.0;
  for (const auto& s : slots_) lmax = std::max(lmax, std::abs(s.state.multiplier));
  const double tensionTol = 1e-10 * lmax;
  std::vector<int> changed;
  for (size_t k = 0; k < slots_.size(); ++k) {
    ContactSlot& s = slots_[k];
    if (!s.paired()) continue;
    if (s.active && s.state.multiplier > tensionTol) {
      s.active = false;
      changed.push_back(static_cast<int>(k));
    } else if (!s.active && s.gap < -options_.penetrationTolerance && fullyPrescribed(int(k))) {
      DDC_THROW(InputError, describeSlot(int(k))
                                << ": the slave node and its master segment have all their displacements "
                                   "prescribed (Boundary Conditions), so contact cannot remove their penetration "
                                   "(gap "
                                << s.gap << "); free the contact surfaces or change the prescribed values");
    } else if (!s.active && s.gap < -options_.penetrationTolerance) {
      s.active = true;
      changed.push_back(static_cast<int>(k));
    }
  }
  return changed;
}

ContactSummary ContactComponent::summary() const {
  ContactSummary c;
  for (const auto& s : slots_) {
    if (!s.active || !s.paired()) continue;
    ++c.active;
    // The slave feels −λ n (compression: λ < 0 pushes it along +n).
    for (int d = 0; d < 3; ++d) c.force[d] -= s.state.multiplier * s.normal[d];
  }
  return c;
}

bool ContactComponent::restoreSlots(const std::vector<ContactSlot>& saved) {
  DDC_CHECK(saved.size() == slots_.size(), "restoreSlots: " << saved.size() << " slots for " << slots_.size());
  bool changed = false;
  for (size_t k = 0; k < slots_.size(); ++k)
    if (saved[k].segment != slots_[k].segment) changed = true;
  slots_ = saved;
  if (changed && hasDofs_) buildTopology();
  return changed;
}

std::string ContactComponent::describeSlot(int k) const {
  const ContactSlot& s = slots_[k];
  std::ostringstream os;
  const Eigen::Vector3d X = referencePosition(s.slaveNode);
  os << "pair '" << pairs_[s.pair].name << "' slave node " << s.slaveNode << " at (" << X.x() << ", " << X.y();
  if (dim_ == 3) os << ", " << X.z();
  os << ")";
  return os.str();
}

FrozenGeometryError ContactComponent::frozenGeometryError(const std::vector<ContactSlot>& converged) const {
  if (converged.size() != slots_.size())
    throw std::invalid_argument("frozenGeometryError: " + std::to_string(converged.size()) + " slots for " +
                                std::to_string(slots_.size()));
  // Reference position of facet point xi on the master facet with `nodes`.
  auto referencePoint = [&](CellType type, const ContactSlot& s, const std::array<double, 2>& xi) {
    Eigen::MatrixXd X(s.numMaster, dim_);
    for (int a = 0; a < s.numMaster; ++a) X.row(a) = referencePosition(s.master[a]).head(dim_).transpose();
    Eigen::Vector3d point, normal;
    return facetPointAndNormal(type, X, xi, point, normal) ? std::optional<Eigen::Vector3d>(point) : std::nullopt;
  };
  double gapWork = 0.0, normalWork = 0.0;
  for (size_t k = 0; k < slots_.size(); ++k) {
    const ContactSlot& before = converged[k];
    const ContactSlot& now = slots_[k];
    if (!before.active || !before.paired()) continue;
    const double lambda = before.state.multiplier;
    gapWork += lambda * (now.gap - before.gap);
    if (!now.paired()) continue;
    const CellType type = pairs_[before.pair].masterType;
    const auto from = referencePoint(type, before, before.frozen.xi);
    const auto to = referencePoint(type, now, now.frozen.xi);
    if (from && to) normalWork += std::abs(lambda) * (now.normal - before.frozen.normal).norm() * (*to - *from).norm();
  }
  return {std::abs(gapWork), normalWork};
}

namespace {
/// Numbers per slot in packSlots().
constexpr size_t kPackedSlot = 30;
}  // namespace

std::vector<double> packSlots(const std::vector<ContactSlot>& slots) {
  std::vector<double> out;
  out.reserve(slots.size() * kPackedSlot);
  for (const ContactSlot& s : slots) {
    out.insert(out.end(), {double(s.pair), double(s.slaveNode)});
    for (int m : s.master) out.push_back(m);
    out.insert(out.end(), {double(s.numMaster), double(s.segment), double(s.masterElement), double(s.active),
                           double(s.state.active), s.state.multiplier, s.state.frozenXi, s.state.frozenNormal.x(),
                           s.state.frozenNormal.y(), s.frozen.xi[0], s.frozen.xi[1], s.frozen.normal.x(),
                           s.frozen.normal.y(), s.frozen.normal.z(), s.gap, s.normal.x(), s.normal.y(), s.normal.z(),
                           s.tributaryLength});
  }
  return out;
}

std::vector<ContactSlot> unpackSlots(const std::vector<double>& packed) {
  if (packed.size() % kPackedSlot != 0)
    throw std::invalid_argument("unpackSlots: " + std::to_string(packed.size()) + " numbers are not whole slots of " +
                                std::to_string(kPackedSlot));
  std::vector<ContactSlot> slots(packed.size() / kPackedSlot);
  const double* p = packed.data();
  for (ContactSlot& s : slots) {
    s.pair = int(*p++);
    s.slaveNode = int(*p++);
    for (int& m : s.master) m = int(*p++);
    s.numMaster = int(*p++);
    s.segment = int(*p++);
    s.masterElement = int(*p++);
    s.active = *p++ != 0.0;
    s.state.active = *p++ != 0.0;
    s.state.multiplier = *p++;
    s.state.frozenXi = *p++;
    s.state.frozenNormal.x() = *p++;
    s.state.frozenNormal.y() = *p++;
    s.frozen.xi[0] = *p++;
    s.frozen.xi[1] = *p++;
    for (int c = 0; c < 3; ++c) s.frozen.normal(c) = *p++;
    s.gap = *p++;
    for (int c = 0; c < 3; ++c) s.normal(c) = *p++;
    s.tributaryLength = *p++;
  }
  return slots;
}

}  // namespace ddc
