// The topology part of the contact component: registration, commit(),
// setDofs() (see DDC_ContactTopology.hpp).
#include "DDC_ContactTopology.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_NodeToSurface.hpp"
#include "DDC_ShapeFunctions.hpp"

namespace ddc {

namespace {

using TpetraImport = Tpetra::Import<LO, GO, Node>;

Teuchos::RCP<const Map> mapOf(const std::vector<GO>& gids, const Teuchos::RCP<const Teuchos::Comm<int>>& comm) {
  return Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                              Teuchos::ArrayView<const GO>(gids), 0, comm));
}

/// Records of the registration gather (plain data for exchangeRecords()).
struct NodeRecord {
  int id, rank;
  double x, y, z;
};

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

ContactTopology::ContactTopology(Teuchos::RCP<const Teuchos::Comm<int>> comm, ContactComponentOptions options,
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

ContactTopology::~ContactTopology() = default;

void ContactTopology::requireCommitted(const char* what) const {
  if (!committed_ || !hasDofs_)
    throw std::logic_error(std::string("ContactComponent::") + what + ": call commit() and setDofs() first");
}

void ContactTopology::requireHostMultipliers() const {
  if (!multipliersInHost_)
    throw std::logic_error("ContactComponent: the multipliers are not in the host's vector (setDofs() got no "
                           "multiplier DOFs); pass them on multiplierMap()");
}

// ---- registration ----------------------------------------------------------------

void ContactTopology::registerNodes(const std::vector<ContactNode>& nodes) {
  if (committed_) throw std::logic_error("ContactComponent::registerNodes after commit()");
  myNodes_.insert(myNodes_.end(), nodes.begin(), nodes.end());
}

int ContactTopology::registerPair(ContactPairSurfaces pair) {
  if (committed_) throw std::logic_error("ContactComponent::registerPair after commit()");
  Pair p;
  p.name = pair.name;
  p.path = pair.path.empty() ? pair.name : pair.path;
  p.slaveName = pair.slaveName;
  p.masterName = pair.masterName;
  p.friction = pair.friction;
  p.frictionStiffness = pair.frictionStiffness;
  DDC_INPUT_REQUIRE(std::isfinite(pair.friction) && pair.friction >= 0.0,
                    "contact pair '" << p.path << "': friction coefficient " << pair.friction
                                     << " is not a finite number >= 0");
  DDC_INPUT_REQUIRE(pair.friction == 0.0 || (std::isfinite(pair.frictionStiffness) && pair.frictionStiffness > 0.0),
                    "contact pair '" << p.path << "': a frictional pair needs a finite complementarity parameter "
                                        "c_t > 0 (ContactPairSurfaces::frictionStiffness), got "
                                     << pair.frictionStiffness);
  p.slaveType = pair.slaveFacetType;
  p.masterType = pair.masterFacetType;
  pairs_.push_back(std::move(p));
  myPairs_.push_back(std::move(pair));
  return static_cast<int>(pairs_.size()) - 1;
}

// ---- commit ----------------------------------------------------------------------

void ContactTopology::commit() {
  if (committed_) throw std::logic_error("ContactComponent::commit called twice");
  checkDimensions();
  if (!pairs_.empty()) dim_ = facetSpaceDimension(pairs_[0].masterType);
  fetchSurfaceElements();
  mergeNodes();
  for (int p = 0; p < numPairs(); ++p) mergePair(p);
  myPairs_.clear();
  const int me = comm_->getRank();
  for (size_t k = 0; k < slots_.size(); ++k)
    if (slots_[k].owner == me) localSlots_.push_back(static_cast<int>(k));
  // Multipliers per slot: λ_n, and λ_t (dim − 1) in a frictional pair.
  lmStart_.assign(slots_.size() + 1, 0);
  for (size_t k = 0; k < slots_.size(); ++k) {
    const bool friction = pairs_[slots_[k].pair].friction > 0.0;
    frictional_ = frictional_ || friction;
    lmStart_[k + 1] = lmStart_[k] + (friction ? dim_ : 1);
  }
  lmGid_.assign(size_t(lmStart_.back()), -1);
  if (options_.decomposed) findSlaveNeighbourSends();
  committed_ = true;
}

void ContactTopology::checkDimensions() const {
  // Every pair's facets agree on the space dimension.
  for (const Pair& pair : pairs_) {
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
}

void ContactTopology::fetchSurfaceElements() {
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
}

void ContactTopology::mergeNodes() {
  // Every rank learns every surface node and its owner.
  const int me = comm_->getRank();
  std::vector<NodeRecord> mine;
  for (const auto& n : myNodes_) mine.push_back({n.id, me, n.X.x(), n.X.y(), n.X.z()});
  std::vector<NodeRecord> all = allGather(rawComm(comm_), mine);
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
}

void ContactTopology::requireNode(const Pair& p, int id, const char* role) const {
  DDC_INPUT_REQUIRE(index(id) >= 0, "contact pair '" << p.path << "': " << role << " node " << id
                                                     << " is not a registered surface node (no rank registered it)");
}

void ContactTopology::mergePair(int p) {
  // The pair's facets and slave nodes merged, its slots and search data.
  Pair& pair = pairs_[p];
  ContactPairSurfaces& mine = myPairs_[p];
  checkFacetSizes(pair, mine);
  pair.slaveFacets = gatherFacets(pair, mine.slaveFacets, pair.slaveType, "slave");
  pair.masterFacets = gatherFacets(pair, mine.masterFacets, pair.masterType, "master");
  std::vector<int> candidates = allGather(rawComm(comm_), mine.slaveNodes);
  mine = ContactPairSurfaces();
  DDC_INPUT_REQUIRE(!pair.masterFacets.empty(), "contact pair '" << pair.path << "': the master surface '"
                                                                 << pair.masterName << "' has no facets");
  std::set<int> masterSet;
  for (const auto& f : pair.masterFacets) masterSet.insert(f.nodes.begin(), f.nodes.begin() + f.numNodes);
  const std::vector<int> masterNodes(masterSet.begin(), masterSet.end());
  const std::vector<int> slaves = slaveNodesOf(pair, candidates, masterNodes);
  checkOrientation(pair);
  pair.slaves = slaves;
  std::map<int, double> tributary = tributaryLengths(pair);
  for (int n : slaves) {
    pair.slots.push_back(static_cast<int>(slots_.size()));
    slots_.push_back({p, n, owner_[index(n)], tributary[n]});
  }
  addSearchData(pair, masterNodes);
}

void ContactTopology::checkFacetSizes(const Pair& pair, const ContactPairSurfaces& mine) const {
  // The facet sizes are checked on each rank's share: agree before merging.
  std::string error;
  for (const auto& [facets, type, role] : {std::make_tuple(&mine.slaveFacets, pair.slaveType, "slave"),
                                           std::make_tuple(&mine.masterFacets, pair.masterType, "master")})
    for (const auto& f : *facets)
      if (int(f.nodes.size()) != numCellNodes(type) && error.empty())
        error = "contact pair '" + pair.path + "': " + role + " facet " + std::to_string(f.id) + " has " +
                std::to_string(f.nodes.size()) + " nodes; a " + cellTypeName(type) + " facet has " +
                std::to_string(numCellNodes(type));
  raiseCollectively<InputError>(rawComm(comm_), error);
}

std::vector<ContactTopology::Facet> ContactTopology::gatherFacets(const Pair& pair,
                                                                  const std::vector<ContactFacet>& facets,
                                                                  CellType type, const char* role) const {
  const int m = numCellNodes(type);
  std::vector<Facet> recs;
  for (const auto& f : facets) {
    Facet r{f.id, m, {}, f.element, f.subdomain, comm_->getRank(), f.depth};
    r.nodes.fill(-1);
    std::copy(f.nodes.begin(), f.nodes.end(), r.nodes.begin());
    recs.push_back(r);
  }
  auto merged = allGather(rawComm(comm_), recs);
  std::sort(merged.begin(), merged.end(), [](const Facet& a, const Facet& b) { return a.id < b.id; });
  for (size_t i = 1; i < merged.size(); ++i)
    DDC_INPUT_REQUIRE(merged[i].id != merged[i - 1].id, "contact pair '" << pair.path << "': " << role << " facet "
                                                                         << merged[i].id
                                                                         << " is registered twice (ranks "
                                                                         << merged[i - 1].rank << " and "
                                                                         << merged[i].rank << ")");
  for (const auto& f : merged)
    for (int a = 0; a < f.numNodes; ++a) requireNode(pair, f.nodes[a], role);
  return merged;
}

std::vector<int> ContactTopology::slaveNodesOf(const Pair& pair, const std::vector<int>& candidates,
                                               const std::vector<int>& masterNodes) const {
  std::vector<int> slaveNodes = candidates;
  std::sort(slaveNodes.begin(), slaveNodes.end());
  slaveNodes.erase(std::unique(slaveNodes.begin(), slaveNodes.end()), slaveNodes.end());
  std::vector<int> slaves;
  for (int n : slaveNodes) {
    // A node of both surfaces (shared corner) is not a slave.
    if (std::binary_search(masterNodes.begin(), masterNodes.end(), n)) continue;
    requireNode(pair, n, "slave");
    slaves.push_back(n);
  }
  DDC_INPUT_REQUIRE(!slaves.empty(), "contact pair '" << pair.path << "': the slave side set '" << pair.slaveName
                                                      << "' has no nodes off the master surface");
  return slaves;
}

void ContactTopology::checkOrientation(const Pair& pair) const {
  // Both surfaces consistently oriented: a side two facets share is run
  // through in opposite directions (otherwise some normals point inwards).
  for (const auto* facets : {&pair.slaveFacets, &pair.masterFacets}) {
    const CellType type = facets == &pair.slaveFacets ? pair.slaveType : pair.masterType;
    const char* role = facets == &pair.slaveFacets ? "slave" : "master";
    std::map<std::pair<int, int>, long> directed;
    for (const auto& f : *facets) {
      if (referenceCell(type).dim == 1) {
        // Segments: a node is the start of one segment and the end of another.
        for (int end = 0; end < 2; ++end) {
          const auto [it, fresh] = directed.insert({{f.nodes[end], end}, f.id});
          DDC_INPUT_REQUIRE(fresh, "contact pair '" << pair.path << "': the " << role
                                                    << " surface is not consistently oriented: facets " << it->second
                                                    << " and " << f.id << " both " << (end ? "end" : "start")
                                                    << " at node " << f.nodes[end]
                                                    << " (a normal points into the body)");
        }
        continue;
      }
      for (const auto& e : referenceCell(type).edges) {
        const auto [it, fresh] = directed.insert({{f.nodes[e.start], f.nodes[e.end]}, f.id});
        DDC_INPUT_REQUIRE(fresh, "contact pair '" << pair.path << "': the " << role
                                                  << " surface is not consistently oriented: facets " << it->second
                                                  << " and " << f.id << " both run from node " << f.nodes[e.start]
                                                  << " to node " << f.nodes[e.end]
                                                  << " along their shared side (one of them has an inward normal)");
      }
    }
  }
}

std::map<int, double> ContactTopology::tributaryLengths(const Pair& pair) const {
  // The slave node's share of the slave surface: the facet's measure lumped
  // to its nodes by the HRZ rule (Hinton, Rock & Zienkiewicz 1976): ∫N_i² dA
  // scaled to the facet's measure, positive for quadratic facets too, exact
  // shares on regular linear facets.
  std::map<int, double> tributary;
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
  return tributary;
}

void ContactTopology::addSearchData(Pair& pair, const std::vector<int>& masterNodes) {
  // Margin of the bounding-box exchange: the search radius plus two master
  // facets (a slave's facet and its neighbours), with room for stretching (x 2).
  double longest = 0.0;
  for (const auto& f : pair.masterFacets)
    for (int a = 0; a < f.numNodes; ++a)
      for (int b = a + 1; b < f.numNodes; ++b) {
        const Eigen::Vector3d d = X_[index(f.nodes[b])] - X_[index(f.nodes[a])];
        longest = std::max(longest, dim_ == 2 ? std::hypot(d.x(), d.y()) : d.norm());
      }
  pairingMargin_ = std::max(pairingMargin_, options_.searchRadius + 4.0 * longest);
  masterSurfaceNodes_.insert(masterSurfaceNodes_.end(), masterNodes.begin(), masterNodes.end());
  for (const auto& f : pair.masterFacets)
    DDC_INPUT_REQUIRE(f.depth > 0.0, "contact pair '" << pair.path << "': master facet " << f.id
                                                      << " has no depth (> 0 expected)");
  for (size_t f = 0; f < pair.slaveFacets.size(); ++f)
    for (int a = 0; a < pair.slaveFacets[f].numNodes; ++a)
      pair.slaveFacetsAt[pair.slaveFacets[f].nodes[a]].emplace_back(int(f), a);
  for (int n : pair.slaves)
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

void ContactTopology::findSlaveNeighbourSends() {
  // Decomposed pairing: the slave nodal normals need the positions of the
  // nodes of the slave facets at each slave node; those owned by another
  // rank than the slave's are sent to it.
  const int me = comm_->getRank();
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

// ---- DOFs and multipliers ----------------------------------------------------------

void ContactTopology::setDofs(Teuchos::RCP<const Map> hostMap, const std::vector<ContactNodeDofs>& nodeDofs,
                              const std::vector<GO>& multiplierDofs) {
  if (!committed_) throw std::logic_error("ContactComponent::setDofs before commit()");
  if (hasDofs_) throw std::logic_error("ContactComponent::setDofs called twice");
  const MPI_Comm mpi = rawComm(comm_);
  hostMap_ = hostMap;
  // Check locally, agree collectively: every rank throws the same message.
  std::string error = checkNodeDofs(*hostMap, nodeDofs);
  if (error.empty() && !multiplierDofs.empty()) error = checkMultiplierDofs(*hostMap, nodeDofs, multiplierDofs);
  raiseCollectively<InputError>(mpi, error);
  // Multipliers in the host's vector: every rank or none.
  const bool hostLm = !multiplierDofs.empty() || localSlots_.empty();
  const bool allHost = !anyRank(mpi, !hostLm);
  const bool anyHost = anyRank(mpi, !multiplierDofs.empty());
  DDC_INPUT_REQUIRE(allHost || !anyHost, "contact: some ranks give multiplier DOFs to setDofs() and others do not");
  multipliersInHost_ = anyHost;
  replicateDofs(nodeDofs);
  buildMultiplierMaps(multiplierDofs);
  surfaceMap_ = Teuchos::null;  // new DOFs: rebuilt on first use
  surfaceImporter_ = Teuchos::null;
  hasDofs_ = true;
}

std::string ContactTopology::checkNodeDofs(const Map& hostMap, const std::vector<ContactNodeDofs>& nodeDofs) const {
  const int me = comm_->getRank();
  std::string error;
  for (const auto& nd : nodeDofs) {
    std::ostringstream os;
    const int i = index(nd.id);
    if (i < 0 || owner_[i] != me) {
      os << "contact: rank " << me << " gives DOFs for node " << nd.id << ", which "
         << (i < 0 ? "is not a registered surface node" : "rank " + std::to_string(i < 0 ? -1 : owner_[i]) +
                                                                 " registered");
    } else {
      for (int c = 0; c < dim_ && os.tellp() == 0; ++c)
        if (!hostMap.isNodeGlobalElement(nd.dofs[c]))
          os << "contact: surface node " << nd.id << " (rank " << me << ") has DOF id " << nd.dofs[c] << " for u_"
             << "xyz"[c] << ", which rank " << me << " does not own in the host's DOF map: register each surface "
             << "node on the rank that owns its DOFs";
    }
    if (os.tellp() != 0 && error.empty()) error = os.str();
  }
  return error;
}

std::string ContactTopology::checkMultiplierDofs(const Map& hostMap, const std::vector<ContactNodeDofs>& nodeDofs,
                                                 const std::vector<GO>& multiplierDofs) const {
  const int me = comm_->getRank();
  size_t expected = 0;
  for (int k : localSlots_) expected += size_t(numMultipliers(k));
  if (multiplierDofs.size() != expected)
    return "contact: rank " + std::to_string(me) + " gives " + std::to_string(multiplierDofs.size()) +
           " multiplier DOFs for its " + std::to_string(localSlots_.size()) + " contact slots, which have " +
           std::to_string(expected) + " multipliers";
  // A multiplier needs an id of its own: not a surface node's DOF, not
  // another multiplier's (the DOFs of the host's other nodes are beyond
  // what the component sees).
  std::string error;
  std::map<GO, std::string> taken;
  for (const auto& nd : nodeDofs)
    for (int c = 0; c < dim_; ++c)
      taken[nd.dofs[c]] = std::string("the u_") + "xyz"[c] + " DOF of surface node " + std::to_string(nd.id);
  size_t i = 0;
  for (int k : localSlots_)
    for (int c = 0; c < numMultipliers(k) && error.empty(); ++c, ++i) {
      const GO g = multiplierDofs[i];
      if (!hostMap.isNodeGlobalElement(g)) {
        error = "contact: multiplier DOF id " + std::to_string(g) + " is not owned by rank " + std::to_string(me) +
                " (the owner of its slave node) in the host's DOF map";
      } else if (const auto it = taken.find(g); it != taken.end()) {
        error = "contact: multiplier DOF id " + std::to_string(g) + " of " + describeSlot(k) + " is also " +
                it->second + ": each multiplier needs a DOF id of its own in the host's map";
      }
      taken[g] = "the multiplier of " + describeSlot(k);
    }
  return error;
}

void ContactTopology::replicateDofs(const std::vector<ContactNodeDofs>& nodeDofs) {
  // The DOF ids and prescribed flags of every surface node on every rank.
  struct DofRecord {
    int id;
    GO d[3];
    int p[3];
  };
  std::vector<DofRecord> mine;
  for (const auto& nd : nodeDofs)
    mine.push_back({nd.id, {nd.dofs[0], nd.dofs[1], nd.dofs[2]}, {nd.prescribed[0], nd.prescribed[1], nd.prescribed[2]}});
  const auto all = allGather(rawComm(comm_), mine);
  dofs_.assign(nodeIds_.size(), {{-1, -1, -1}});
  prescribed_.assign(nodeIds_.size(), {{0, 0, 0}});
  for (const auto& r : all) {
    const int i = index(r.id);
    for (int c = 0; c < dim_; ++c) {
      dofs_[i][c] = r.d[c];
      prescribed_[i][c] = char(r.p[c]);
    }
  }
}

void ContactTopology::buildMultiplierMaps(const std::vector<GO>& multiplierDofs) {
  // Multiplier ids: the host's DOFs, or consecutive numbers slot by slot
  // (the slot index when no pair has friction).
  std::vector<GO> ids(lmGid_.size(), -1);
  if (multipliersInHost_) {
    struct LmRecord {
      int at;
      GO gid;
    };
    std::vector<LmRecord> lm;
    size_t i = 0;
    for (int k : localSlots_)
      for (int c = 0; c < numMultipliers(k); ++c) lm.push_back({lmStart_[k] + c, multiplierDofs[i++]});
    for (const auto& r : allGather(rawComm(comm_), lm)) ids[r.at] = r.gid;
  } else {
    for (size_t a = 0; a < ids.size(); ++a) ids[a] = GO(a);
  }
  lmGid_ = std::move(ids);
  std::vector<GO> ownedLm;
  for (int k : localSlots_)
    for (int c = 0; c < numMultipliers(k); ++c) ownedLm.push_back(multiplierId(k, c));
  multiplierMap_ = mapOf(ownedLm, comm_);
  // Every multiplier on every rank: the conventional element's gather only
  // (the decomposed element moves a slot's multipliers to where it is
  // evaluated).
  if (!options_.decomposed) {
    multiplierAllMap_ = mapOf(lmGid_, comm_);
    lmAllImporter_ = Teuchos::rcp(new TpetraImport(multiplierMap_, multiplierAllMap_));
  }
}

const Teuchos::RCP<const Map>& ContactTopology::surfaceMap() const {
  if (surfaceMap_.is_null()) buildSurfaceMap();
  return surfaceMap_;
}

const Teuchos::RCP<const Tpetra::Import<LO, GO, Node>>& ContactTopology::surfaceImporter() const {
  if (surfaceImporter_.is_null()) buildSurfaceMap();
  return surfaceImporter_;
}

long ContactTopology::bytesPerExchange() const {
  if (surfaceMap_.is_null()) buildSurfaceMap();
  return bytesPerExchange_;
}

void ContactTopology::buildSurfaceMap() const {
  // Replicated map of every surface DOF: the gather of the conventional
  // element and of the pairing outside step ends.
  requireCommitted("surfaceMap");
  const int me = comm_->getRank();
  std::vector<GO> gids;
  for (const auto& d : dofs_) gids.insert(gids.end(), d.begin(), d.begin() + dim_);
  surfaceMap_ = mapOf(gids, comm_);
  surfaceImporter_ = Teuchos::rcp(new TpetraImport(hostMap_, surfaceMap_));
  long received = 0;
  for (GO g : gids)
    if (!hostMap_->isNodeGlobalElement(g)) ++received;
  for (const Slot& s : slots_)
    if (s.owner != me) ++received;
  long total = 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, received, Teuchos::outArg(total));
  bytesPerExchange_ = total * static_cast<long>(sizeof(double));
}

// ---- queries -------------------------------------------------------------------------

int ContactTopology::index(int id) const {
  const auto it = std::lower_bound(nodeIds_.begin(), nodeIds_.end(), id);
  return it != nodeIds_.end() && *it == id ? int(it - nodeIds_.begin()) : -1;
}

Eigen::Vector3d ContactTopology::referencePosition(int id) const {
  const int i = index(id);
  DDC_CHECK(i >= 0, "node " << id << " is not on a contact surface");
  return X_[i];
}

void ContactTopology::appendNodeDofs(int id, std::vector<GO>& dofs) const {
  const auto& d = dofs_[index(id)];
  dofs.insert(dofs.end(), d.begin(), d.begin() + dim_);
}

bool ContactTopology::nodePrescribed(int id) const {
  for (int c = 0; c < dim_; ++c)
    if (!prescribed_[index(id)][c]) return false;
  return true;
}

const SurfaceContactElement& ContactTopology::surfaceElement(SurfaceContactRole role, CellType facet) const {
  const auto it = surfaceElements_.find({role, facet});
  DDC_CHECK(it != surfaceElements_.end(), "no " << surfaceContactElementName(role, facet) << " element");
  return *it->second;
}

std::string ContactTopology::describeSlot(int k) const {
  const Slot& s = slots_[k];
  std::ostringstream os;
  const Eigen::Vector3d X = referencePosition(s.slaveNode);
  os << "pair '" << pairs_[s.pair].name << "' slave node " << s.slaveNode << " at (" << X.x() << ", " << X.y();
  if (dim_ == 3) os << ", " << X.z();
  os << ")";
  return os.str();
}

}  // namespace ddc
