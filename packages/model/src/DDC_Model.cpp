#include "DDC_Model.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "DDC_BodyLocator.hpp"
#include "DDC_ContactSurface.hpp"
#include "DDC_ContinuumElement.hpp"
#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_NodeDirectory.hpp"
#include "DDC_ShapeFunctions.hpp"
#include "DDC_Substructuring.hpp"

namespace ddc {

namespace {

/// doc/contact.md "Which slave nodes pair": for each slave node of the pairs
/// (by its id in the whole mesh), points of the slave body next to it,
/// halfway from the node to the centroid of the corners of each of its
/// elements, in the order of the elements' ids; none for a pair of two
/// surfaces of one body (self-contact: the slave body is the master body).
/// A part of a mesh gathers them over `comm` (surface-sized), so that every
/// rank holds every slave node's points.
std::function<std::vector<Eigen::VectorXd>(int, int)> slaveBodyPoints(const Mesh& mesh,
                                                                      const ContactOptions& contact, MPI_Comm comm) {
  struct Point {
    Mesh::GlobalId node, element;
    double x[3];
  };
  std::set<int> bodies;
  std::vector<char> isSlave(mesh.numNodes(), 0), selfContact;
  for (const auto& def : contact.pairs) {
    const int slave = mesh.bodyIndex(def.slaveSet.substr(0, def.slaveSet.find('/')));
    selfContact.push_back(slave == mesh.bodyIndex(def.masterSet.substr(0, def.masterSet.find('/'))));
    if (selfContact.back()) continue;
    bodies.insert(slave);
    for (int n : mesh.nodeSet(def.slaveSet)) isSlave[n] = 1;
  }
  const int dim = mesh.dim();
  std::vector<Point> mine;
  for (int b : bodies) {
    const int corners = referenceCell(mesh.body(b).cellType).numCorners;
    for (int e = mesh.body(b).firstElement; e < mesh.body(b).firstElement + mesh.body(b).numElements; ++e) {
      const int* en = mesh.elementNodes(e);
      Eigen::VectorXd c = Eigen::VectorXd::Zero(dim);
      for (int i = 0; i < corners; ++i) c += Eigen::Map<const Eigen::VectorXd>(mesh.coord(en[i]).data(), dim);
      c /= corners;
      for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
        if (!isSlave[en[i]]) continue;
        const Eigen::VectorXd x = 0.5 * (Eigen::Map<const Eigen::VectorXd>(mesh.coord(en[i]).data(), dim) + c);
        mine.push_back({mesh.nodeId(en[i]), mesh.elementId(e), {x[0], x[1], dim == 3 ? x[2] : 0.0}});
      }
    }
  }
  std::vector<Point> all = mesh.isPart() ? allGather(comm, mine) : std::move(mine);
  std::stable_sort(all.begin(), all.end(), [](const Point& a, const Point& b) {
    return a.node != b.node ? a.node < b.node : a.element < b.element;
  });
  auto points = std::make_shared<std::map<int, std::vector<Eigen::VectorXd>>>();
  for (const Point& p : all) (*points)[int(p.node)].push_back(Eigen::Map<const Eigen::VectorXd>(p.x, dim));
  return [points, selfContact](int pair, int n) {
    const auto it = points->find(n);
    return selfContact.at(pair) || it == points->end() ? std::vector<Eigen::VectorXd>() : it->second;
  };
}

}  // namespace

Model::Model(Teuchos::RCP<const Teuchos::Comm<int>> comm, std::shared_ptr<const Mesh> mesh,
             std::vector<std::shared_ptr<const Element>> elements, Partition partition, BoundaryConditions bcs,
             ContactOptions contact, ContactComponent::SurfaceElementSource surfaceElements)
    : comm_(std::move(comm)),
      mesh_(std::move(mesh)),
      elements_(std::move(elements)),
      partition_(std::move(partition)),
      bcs_(std::move(bcs)),
      contactOptions_(std::move(contact)) {
  DDC_CHECK(static_cast<int>(elements_.size()) == mesh_->numBodies(), "one element evaluator per body");
  for (int b = 0; b < mesh_->numBodies(); ++b)
    DDC_CHECK(elements_[b]->dim() == mesh_->dim(), "body '" << mesh_->body(b).name << "': a " << elements_[b]->dim()
                                                              << "-D element on a " << mesh_->dim() << "-D mesh");
  subdomainRank_ = subdomainOwnerRank(partition_.numSubdomains, comm_->getSize());
  for (int e = 0; e < mesh_->numElements(); ++e)
    if (subdomainRank_[partition_.elementSubdomain[e]] == comm_->getRank()) localElements_.push_back(e);
  if (mesh_->isPart()) {
    // A part of a mesh (Mesh::part()) is this rank's elements and nodes.
    DDC_CHECK(static_cast<int>(localElements_.size()) == mesh_->numElements(),
              "Model: the part of the mesh on rank " << comm_->getRank() << " holds elements of other ranks");
  }

  computeNodeOwners();
  if (contactOptions_.enabled()) buildContact(std::move(surfaceElements));
  // The formulation alone says nothing about whether the contact maps exist:
  // with no pairs there are none, and the run is a plain analysis.
  decomposed_ = contactOptions_.decomposed && hasContact();
  buildDofNumbering();
  buildConstraints();
  if (hasContact()) {
    // The model's DOFs of the surface nodes it owns, and its multipliers.
    std::vector<ContactNodeDofs> nodeDofs;
    for (int id : contact_->surfaceNodes()) {
      const int n = meshNodeOfContactNode(id);
      if (n < 0 || nodeOwner_[n] != comm_->getRank()) continue;
      ContactNodeDofs d;
      d.id = id;
      for (int c = 0; c < mesh_->dim(); ++c) {
        d.dofs[c] = dof(n, c);
        d.prescribed[c] = constrained_[dof(n, c)] != 0;
      }
      nodeDofs.push_back(d);
    }
    std::vector<GO> lm;
    for (int k : contact_->ownedSlots())
      for (int c = 0; c < contact_->numMultipliers(k); ++c) lm.push_back(lmDof_[k] + c);
    contact_->setDofs(ownedMap_, nodeDofs, lm);
    // Initial pairing in the reference configuration.
    auto zero = createVector();
    contact_->updatePairing(*zero, /*global=*/true, /*freeze=*/true);
    std::vector<std::unique_ptr<BodyLocator>> locators;
    std::vector<std::function<int(const Eigen::VectorXd&)>> locate;
    for (const auto& def : contactOptions_.pairs) {
      // The master body's elements this rank holds, found by element id.
      const std::string body = def.masterSet.substr(0, def.masterSet.find('/'));
      locators.push_back(std::make_unique<BodyLocator>(*mesh_, mesh_->bodyIndex(body), rawComm(*comm_)));
      const BodyLocator* l = locators.back().get();
      locate.push_back([this, l](const Eigen::VectorXd& x) {
        const int e = mesh_->dim() == 2 ? l->elementContaining(Eigen::Vector2d(x))
                                        : l->elementContaining(Eigen::Vector3d(x));
        return e >= 0 ? contactElementId(e) : -1;
      });
    }
    contact_->checkInitialPenetration(locate, slaveBodyPoints(*mesh_, contactOptions_, rawComm(*comm_)));
  }
  buildTopology();
  assembleTractions();
}

void Model::buildContact(ContactComponent::SurfaceElementSource surfaceElements) {
  // Register the contact surfaces with the component: each rank the surface
  // nodes it owns and the facets of its elements (doc/embedding.md,
  // "(c) The contact component"); the component merges them. Nodes,
  // elements and facets are named by their ids in the whole mesh
  // (contactNodeId()), so a part of the mesh registers what the whole mesh
  // would, and a facet's id, which orders the facets (search tie-breaks),
  // is its element's id and side (contactFacetId()), not its position in
  // the side set, whose order a part does not keep.
  const Mesh& mesh = *mesh_;
  const int me = comm_->getRank();
  ContactComponentOptions options;
  options.decomposed = contactOptions_.decomposed;
  options.searchRadius = contactOptions_.searchRadius;
  options.penetrationTolerance = contactOptions_.penetrationTolerance;
  contact_ = std::make_unique<ContactComponent>(comm_, options, std::move(surfaceElements));
  std::vector<char> isSurface(mesh.numNodes(), 0);
  auto facets = [&](const std::string& set, bool master, CellType& type) {
    const ContactSurfaceFacets surface = contactSurfaceFromSideSet(mesh, set);
    type = mesh.isPart() ? agreedFacetType(surface, set) : surface.type;
    std::vector<ContactFacet> mine;
    for (size_t i = 0; i < surface.nodes.size(); ++i) {
      for (int n : surface.nodes[i]) isSurface[n] = 1;
      const int e = surface.elements[i];
      const int sub = partition_.elementSubdomain[e];
      if (subdomainRank_[sub] != me) continue;
      ContactFacet f;
      f.id = contactFacetId(e, surface.sides[i]);
      for (int n : surface.nodes[i]) f.nodes.push_back(contactNodeId(n));
      f.element = contactElementId(e);
      f.subdomain = sub;
      if (master) f.depth = surface.depths[i];
      mine.push_back(f);
    }
    return mine;
  };
  for (const auto& def : contactOptions_.pairs) {
    ContactPairSurfaces pair;
    pair.name = def.name;
    pair.path = "Contact/Pairs/" + def.name;
    pair.slaveName = def.slaveSet;
    pair.masterName = def.masterSet;
    pair.slaveFacets = facets(def.slaveSet, false, pair.slaveFacetType);
    pair.masterFacets = facets(def.masterSet, true, pair.masterFacetType);
    pair.friction = def.friction;
    if (def.friction > 0.0) pair.frictionStiffness = frictionStiffness(def);
    for (int n : mesh.nodeSet(def.slaveSet)) {
      isSurface[n] = 1;
      if (nodeOwner_[n] == me) pair.slaveNodes.push_back(contactNodeId(n));
    }
    // A part may hold a master node without a master facet (an element that
    // touches the surface at an edge or a corner) and own it: the node set
    // of the side set names it there.
    for (int n : mesh.nodeSet(def.masterSet)) isSurface[n] = 1;
    contact_->registerPair(std::move(pair));
  }
  std::vector<ContactNode> nodes;
  for (int n = 0; n < mesh.numNodes(); ++n)
    if (isSurface[n] && nodeOwner_[n] == me)
      nodes.push_back({contactNodeId(n), Eigen::Vector3d(mesh.coord(n)[0], mesh.coord(n)[1], mesh.coord(n)[2])});
  contact_->registerNodes(nodes);
  contact_->commit();
}

CellType Model::agreedFacetType(const ContactSurfaceFacets& surface, const std::string& set) const {
  // A part may hold none of a side set's facets, and then knows no type.
  int type[2] = {surface.nodes.empty() ? std::numeric_limits<int>::max() : int(surface.type),
                 surface.nodes.empty() ? std::numeric_limits<int>::min() : int(surface.type)};
  MPI_Allreduce(MPI_IN_PLACE, &type[0], 1, MPI_INT, MPI_MIN, rawComm(*comm_));
  MPI_Allreduce(MPI_IN_PLACE, &type[1], 1, MPI_INT, MPI_MAX, rawComm(*comm_));
  if (type[0] == std::numeric_limits<int>::max()) return surface.type;  // empty on every rank
  DDC_INPUT_REQUIRE(type[0] == type[1], "side set '" << set << "' has " << cellTypeName(CellType(type[0])) << " and "
                                                     << cellTypeName(CellType(type[1]))
                                                     << " facets; a contact surface has facets of one type");
  return CellType(type[0]);
}

int Model::contactNodeId(int n) const {
  const Mesh::GlobalId id = mesh_->nodeId(n);
  DDC_CHECK(id <= std::numeric_limits<int>::max(), "contact: node id " << id << " exceeds the contact component's int ids");
  return static_cast<int>(id);
}

int Model::contactElementId(int e) const {
  const Mesh::GlobalId id = mesh_->elementId(e);
  DDC_CHECK(id <= std::numeric_limits<int>::max(),
            "contact: element id " << id << " exceeds the contact component's int ids");
  return static_cast<int>(id);
}

long Model::contactFacetId(int e, int side) const { return long(mesh_->elementId(e)) * kMaxElementFacets + side; }

int Model::meshNodeOfContactNode(int id) const { return mesh_->localNode(id); }

std::vector<std::string> Model::pairsInGrossSlip() const {
  std::vector<std::string> out;
  if (!contact_) return out;
  const auto& pairs = contactOptions_.pairs;
  std::vector<int> active(pairs.size(), 0), stick(pairs.size(), 0);
  for (const auto& s : contact_->slots()) {
    active[s.pair] += s.active;
    stick[s.pair] += s.active && s.friction == FrictionState::Stick;
  }
  for (size_t p = 0; p < pairs.size(); ++p)
    if (pairs[p].friction > 0.0 && active[p] > 0 && stick[p] == 0) {
      auto body = [](const std::string& set) { return set.substr(0, set.find('/')); };
      out.push_back("'Contact/Pairs/" + pairs[p].name + "' (bodies '" + body(pairs[p].slaveSet) + "' and '" +
                    body(pairs[p].masterSet) + "')");
    }
  return out;
}

double Model::frictionStiffness(const ContactPairDefinition& def) const {
  // c_t of a frictional pair (DDC_Friction.hpp): kFrictionStiffnessFactor
  // times the smaller Young's modulus of its two bodies times h^(dim−2), h
  // the mean master facet size — a tenth of the stiffness of a facet-sized
  // piece of material, force per length, so c_t u_t compares with the nodal
  // force λ_t (doc/contact.md, "Friction"). A body whose element has no
  // Young's modulus counts as 1.
  double E = std::numeric_limits<double>::infinity();
  for (const std::string& set : {def.slaveSet, def.masterSet}) {
    const int b = mesh_->bodyIndex(set.substr(0, set.find('/')));
    const auto* ce = b >= 0 ? dynamic_cast<const ContinuumElement*>(elements_[b].get()) : nullptr;
    E = std::min(E, ce ? ce->material().youngsModulus() : 1.0);
  }
  return kFrictionStiffnessFactor * E * std::pow(contactOptions_.length, mesh_->dim() - 2);
}

Model::~Model() = default;

void Model::computeNodeOwners() {
  const Mesh& mesh = *mesh_;
  if (mesh.isPart()) {
    computePartNodeOwners();
    return;
  }
  nodeOwner_ = nodeOwnerRanks(mesh, partition_, comm_->getSize());
}

void Model::computePartNodeOwners() {
  // The owner of a node is the lowest rank that holds it.
  nodeOwner_ = NodeDirectory(rawComm(*comm_), *mesh_).lowestHolder();
}

std::vector<GO> Model::numberNodeDofs(std::vector<GO>& count) {
  const Mesh& mesh = *mesh_;
  const int nranks = comm_->getSize(), me = comm_->getRank();
  const size_t numSlots = contact_ ? contact_->slots().size() : 0;
  const int d = mesh.dim();
  // Per rank: its nodes' DOFs, then its multipliers; ranks in order, a
  // rank's nodes in the order of their ids.
  std::vector<GO> nodeDofs(nranks, 0);
  if (mesh.isPart()) {
    GO mine = 0;
    for (int n = 0; n < mesh.numNodes(); ++n) mine += nodeOwner_[n] == me ? d : 0;
    Teuchos::gatherAll<int, GO>(*comm_, 1, &mine, nranks, nodeDofs.data());
  } else {
    for (int n = 0; n < mesh.numNodes(); ++n) nodeDofs[nodeOwner_[n]] += d;
  }
  count = nodeDofs;
  for (size_t k = 0; k < numSlots; ++k)  // the slots are on every rank
    count[contact_->slotOwner(static_cast<int>(k))] += contact_->numMultipliers(static_cast<int>(k));
  std::vector<GO> offset(nranks + 1, 0);
  for (int r = 0; r < nranks; ++r) offset[r + 1] = offset[r] + count[r];
  numGlobalDofs_ = offset[nranks];
  std::vector<GO> next(offset.begin(), offset.end() - 1);
  nodeDof_.assign(mesh.numNodes(), -1);
  for (int n = 0; n < mesh.numNodes(); ++n) {
    if (mesh.isPart() && nodeOwner_[n] != me) continue;
    nodeDof_[n] = next[nodeOwner_[n]];
    next[nodeOwner_[n]] += d;
  }
  // Each rank's multipliers follow its node DOFs (a part numbers only its own nodes).
  for (int r = 0; r < nranks; ++r) next[r] = offset[r] + nodeDofs[r];
  if (mesh.isPart()) {
    // The DOFs of the nodes other ranks own, from their owners.
    struct Request {
      Mesh::GlobalId node;
      GO dof;  ///< the requesting rank in the request, the first DOF in the answer
    };
    std::vector<std::vector<Request>> send(nranks);
    for (int n = 0; n < mesh.numNodes(); ++n)
      if (nodeOwner_[n] != me) send[nodeOwner_[n]].push_back({mesh.nodeId(n), me});
    const std::vector<Request> asked = exchangeRecords(rawComm(*comm_), send);
    for (auto& v : send) v.clear();
    for (const Request& q : asked) {
      const int n = mesh.localNode(q.node);
      DDC_CHECK(n >= 0 && nodeOwner_[n] == me, "Model: rank " << me << " asked for node " << q.node << " it does not own");
      send[static_cast<int>(q.dof)].push_back({q.node, nodeDof_[n]});
    }
    for (const Request& a : exchangeRecords(rawComm(*comm_), send)) nodeDof_[mesh.localNode(a.node)] = a.dof;
  }
  return next;
}

void Model::buildDofNumbering() {
  const Mesh& mesh = *mesh_;
  const int me = comm_->getRank();
  const size_t numSlots = contact_ ? contact_->slots().size() : 0;
  const int d = mesh.dim();
  std::vector<GO> count;
  std::vector<GO> next = numberNodeDofs(count);
  const GO myFirst = std::accumulate(count.begin(), count.begin() + me, GO(0));
  // A slot's multipliers are consecutive: λ_n, then λ_t (frictional pairs).
  lmDof_.assign(numSlots, -1);
  lmFreeOffset_.assign(numSlots, 0);
  int maxMultipliers = 1;
  for (size_t k = 0; k < numSlots; ++k) {
    const int nm = contact_->numMultipliers(static_cast<int>(k));
    if (k + 1 < numSlots) lmFreeOffset_[k + 1] = lmFreeOffset_[k] + nm;
    maxMultipliers = std::max(maxMultipliers, nm);
    lmDof_[k] = next[contact_->slotOwner(static_cast<int>(k))];
    next[contact_->slotOwner(static_cast<int>(k))] += nm;
  }
  // The owned part of overlapEntity_ (the overlap map lists the owned DOFs
  // first; buildGhostGraph() adds the others).
  overlapEntity_.assign(static_cast<size_t>(count[me]), 0);
  for (int n = 0; n < mesh.numNodes(); ++n)
    if (nodeOwner_[n] == me)
      for (int c = 0; c < d; ++c) overlapEntity_[nodeDof_[n] - myFirst + c] = n;
  for (size_t k = 0; k < numSlots; ++k)
    if (contact_->slotOwner(static_cast<int>(k)) == me)
      for (int c = 0; c < contact_->numMultipliers(static_cast<int>(k)); ++c)
        overlapEntity_[lmDof_[k] - myFirst + c] = -1 - static_cast<int>(k);
  // One row per multiplier: slot k's c-th at k * maxMultipliers + c.
  rigidRowsPerSlot_ = maxMultipliers;
  rigidCheck_ = std::make_unique<RigidMotionCheck>(mesh, static_cast<int>(numSlots) * maxMultipliers, comm_.get(),
                                                   [this, me](int n) { return nodeOwner_[n] == me; });
  ownedMap_ = Teuchos::rcp(new Map(numGlobalDofs_, static_cast<size_t>(count[me]), 0, comm_));
}

void Model::buildConstraints() {
  // Every rank marks every prescribed DOF (one bit each); the owner of a DOF
  // records which condition prescribes it and checks that two conditions on
  // it (e.g. at the shared corner of two fixed edges) agree.
  const Mesh& mesh = *mesh_;
  const int me = comm_->getRank();
  const GO first = ownedMap_->getMinGlobalIndex();
  constrained_.assign(static_cast<size_t>(numGlobalDofs_), false);
  constraintSource_.assign(ownedMap_->getNodeNumElements(), {-1, -1});
  std::string conflict;
  for (int b = 0; b < static_cast<int>(bcs_.displacements.size()); ++b) {
    const auto& bc = bcs_.displacements[b];
    for (int n : mesh.nodeSet(bc.setName))
      for (int c = 0; c < mesh.dim(); ++c) {
        if (!bc.fix[c]) continue;
        const GO g = dof(n, c);
        constrained_[static_cast<size_t>(g)] = true;
        if (nodeOwner_[n] != me) continue;
        auto& src = constraintSource_[static_cast<size_t>(g - first)];
        if (src.first < 0) {
          src = {b, n};
        } else if (conflict.empty()) {
          conflict = prescriptionConflict(bcs_.displacements[src.first], bc, n, c);
        }
      }
  }
  raiseCollectively<InputError>(rawComm(*comm_), conflict);
  if (mesh.isPart()) shareConstrainedBits();
}

void Model::shareConstrainedBits() {
  // A part marks the DOFs of its own nodes; every rank answers
  // isConstrained() for any DOF, so the bits are OR-ed over the ranks.
  constexpr size_t kBits = 64;
  std::vector<std::uint64_t> words((constrained_.size() + kBits - 1) / kBits, 0), all(words.size(), 0);
  for (size_t g = 0; g < constrained_.size(); ++g)
    if (constrained_[g]) words[g / kBits] |= std::uint64_t(1) << (g % kBits);
  MPI_Allreduce(words.data(), all.data(), static_cast<int>(words.size()), MPI_UINT64_T, MPI_BOR, rawComm(*comm_));
  for (size_t g = 0; g < constrained_.size(); ++g) constrained_[g] = (all[g / kBits] >> (g % kBits)) & 1;
}

std::string Model::prescriptionConflict(const DisplacementCondition& a, const DisplacementCondition& b, int n,
                                        int c) const {
  // Sampled at 0.5, 1 and every load-curve point of either.
  const auto& X = mesh_->coord(n);
  std::vector<double> samples = {0.5, 1.0};
  for (const auto* d : {&a, &b})
    for (const auto& pt : d->curve) samples.push_back(pt[0]);
  for (double lam : samples) {
    const double u = a.prescribed(c, X, lam), v = b.prescribed(c, X, lam);
    // The same value computed by two conditions' formulas (an affine field
    // and a fixed value, say) differs by round-off only.
    constexpr double kAgreement = 1e-12;
    if (std::abs(u - v) > kAgreement * (1.0 + std::abs(u) + std::abs(v))) {
      std::ostringstream os;
      os << "boundary conditions '" << a.name << "' and '" << b.name << "' prescribe different " << "xyz"[c]
         << " displacements at node " << mesh_->nodeId(n) << " (" << mesh_->coordText(n) << ")";
      return os.str();
    }
  }
  return "";
}

GO Model::partitionFreeDof(GO g) const {
  const GO d = mesh_->dim();
  const int e = entityAt(overlapMap_->getLocalElement(g), g);
  if (e >= 0) return GO(entityNodeId(e)) * d + (g - entityFirstDof(e));
  const int k = -1 - e;
  return GO(mesh_->numGlobalNodes()) * d + lmFreeOffset_[k] + (g - lmDof_[k]);
}

GO Model::entityFirstDof(int entity) const {
  if (entity < mesh_->numNodes()) return nodeDof_[entity];
  return contact_->surfaceNodeDof(remoteSurfaceNodes_.at(size_t(entity - mesh_->numNodes())), 0);
}

Mesh::GlobalId Model::entityNodeId(int entity) const {
  if (entity < mesh_->numNodes()) return mesh_->nodeId(entity);
  return remoteSurfaceNodes_.at(size_t(entity - mesh_->numNodes()));
}

int Model::entityBody(int entity) const {
  // Each body's nodes are consecutive, in body order, in a part and in the
  // whole mesh (their ids).
  if (entity < mesh_->numNodes()) {
    for (int b = 0; b < mesh_->numBodies(); ++b)
      if (entity < mesh_->body(b).firstNode + mesh_->body(b).numNodes) return b;
  }
  const Mesh::GlobalId id = entityNodeId(entity);
  Mesh::GlobalId end = 0;
  for (int b = 0; b < mesh_->numBodies(); ++b)
    if (id < (end += mesh_->bodyGlobalNodes(b))) return b;
  throw std::logic_error("Model: node id " + std::to_string(id) + " is in no body");
}

std::array<double, 3> Model::entityReference(int entity) const {
  if (entity < mesh_->numNodes()) return mesh_->coord(entity);
  const Eigen::Vector3d X = contact_->referencePosition(int(entityNodeId(entity)));
  return {X.x(), X.y(), X.z()};
}

int Model::entityAt(LO l, GO g) const {
  if (l == Teuchos::OrdinalTraits<LO>::invalid() || static_cast<size_t>(l) >= overlapEntity_.size())
    throw std::logic_error("Model: DOF " + std::to_string(g) + " is not one of this rank's DOFs");
  return overlapEntity_[static_cast<size_t>(l)];
}

void Model::elementDofs(int e, std::vector<GO>& dofs) const {
  const int nn = mesh_->elementNumNodes(e), d = mesh_->dim();
  dofs.resize(d * nn);
  for (int i = 0; i < nn; ++i)
    for (int c = 0; c < d; ++c) dofs[d * i + c] = dof(mesh_->elementNodes(e)[i], c);
}

void Model::assembleTractions() {
  std::vector<int> all, proportional;
  curvedTractions_.clear();
  for (int k = 0; k < int(bcs_.tractions.size()); ++k) {
    all.push_back(k);
    if (bcs_.tractions[k].curve.empty())
      proportional.push_back(k);
    else
      curvedTractions_.emplace_back(k, tractionForce({k}));
  }
  fext_ = tractionForce(all);
  proportionalForce_ = curvedTractions_.empty() ? Teuchos::null : tractionForce(proportional);
}

void Model::externalForceAt(double lambda, Vector& out) const {
  if (curvedTractions_.empty()) {
    out.update(lambda, *fext_, 0.0);
    return;
  }
  out.update(lambda, *proportionalForce_, 0.0);
  for (const auto& [k, f] : curvedTractions_) out.update(bcs_.tractions[k].scale(lambda), *f, 1.0);
}

Teuchos::RCP<Vector> Model::tractionForce(const std::vector<int>& which) const {
  const Mesh& mesh = *mesh_;
  auto fov = Teuchos::rcp(new Vector(overlapMap_));
  auto f = fov->getDataNonConst();
  std::vector<char> isLocal(mesh.numElements(), 0);
  for (int e : localElements_) isLocal[e] = 1;
  // Each side (2-D) or face (3-D) integrated with its facet cell's rule
  // (facetQuadratureRule()): f_a = sum_q w_q N_a t |dx/dxi|.
  const int d = mesh.dim();
  Eigen::VectorXd N;
  Eigen::MatrixXd dN, xf;
  for (int k : which) {
    const TractionCondition& t = bcs_.tractions[k];
    for (const Segment& s : mesh.sideSet(t.setName)) {
      if (!isLocal[s.element]) continue;
      const CellType facet = referenceCell(mesh.body(mesh.elementBody(s.element)).cellType).facets[s.localSide].type;
      const QuadratureRule& rule = facetQuadratureRule(facet);
      xf.resize(s.numNodes, d);
      for (int i = 0; i < s.numNodes; ++i)
        for (int c = 0; c < d; ++c) xf(i, c) = mesh.coord(s.nodes[i])[c];
      for (size_t q = 0; q < rule.points.size(); ++q) {
        shapeFunctions(facet, rule.points[q], &N, &dN);
        const Eigen::MatrixXd a = xf.transpose() * dN;  // d x (d-1): the tangents dx/dxi
        const double jac = d == 2 ? a.col(0).norm()
                                  : Eigen::Vector3d(a.col(0)).cross(Eigen::Vector3d(a.col(1))).norm();
        for (int i = 0; i < s.numNodes; ++i)
          for (int c = 0; c < d; ++c)
            f[overlapMap_->getLocalElement(dof(s.nodes[i], c))] += N[i] * t.traction[c] * jac * rule.weights[q];
      }
    }
  }
  f = Teuchos::null;
  auto owned = createVector();
  owned->doExport(*fov, *exporter_, Tpetra::ADD);
  return owned;
}

Teuchos::RCP<Vector> Model::createVector() const { return Teuchos::rcp(new Vector(ownedMap_)); }

Teuchos::RCP<CrsMatrix> Model::createMatrix() const {
  auto K = Teuchos::rcp(new CrsMatrix(ownedGraph_));
  K->fillComplete(ownedMap_, ownedMap_);
  return K;
}

Teuchos::RCP<Vector> Model::toOverlap(const Vector& owned) const {
  auto v = Teuchos::rcp(new Vector(overlapMap_));
  v->doImport(owned, *importer_, Tpetra::INSERT);
  return v;
}

void Model::applyPrescribed(double lambda, Vector& u) const {
  auto d = u.getDataNonConst();
  const GO first = ownedMap_->getMinGlobalIndex();
  for (size_t l = 0; l < ownedMap_->getNodeNumElements(); ++l) {
    const auto& src = constraintSource_[l];
    if (src.first < 0) continue;
    const int c = static_cast<int>((first + l) - nodeDof_[src.second]);
    d[l] = bcs_.displacements[src.first].prescribed(c, mesh_->coord(src.second), lambda);
  }
}

void Model::prescribedIncrement(double lambda0, double lambda, Vector& du) const {
  du.putScalar(0.0);
  auto d = du.getDataNonConst();
  const GO first = ownedMap_->getMinGlobalIndex();
  for (size_t l = 0; l < ownedMap_->getNodeNumElements(); ++l) {
    const auto& src = constraintSource_[l];
    if (src.first < 0) continue;
    const auto& bc = bcs_.displacements[src.first];
    const int c = static_cast<int>((first + l) - nodeDof_[src.second]);
    d[l] = bc.prescribed(c, mesh_->coord(src.second), lambda) - bc.prescribed(c, mesh_->coord(src.second), lambda0);
  }
}

void Model::setMassLumping(MassLumping lumping) {
  if (lumping != massLumping_) elementMass_.clear();
  massLumping_ = lumping;
}

void Model::setContactSurfaceMassRedistributed(bool redistributed) {
  if (redistributed && contact_)
    for (int e = 0; e < mesh_->numElements(); ++e) {
      const int nn = mesh_->elementNumNodes(e);
      const int* en = mesh_->elementNodes(e);
      int onSurface = 0;
      for (int a = 0; a < nn; ++a) onSurface += contact_->isSurfaceNode(en[a]) ? 1 : 0;
      DDC_INPUT_REQUIRE(onSurface < nn, "element " << e << " of body '" << mesh_->body(mesh_->elementBody(e)).name
                                                   << "' has all its nodes on contact surfaces, so the mass of "
                                                      "its surface nodes has nowhere to go; use more elements "
                                                      "across the body or keep the surface mass");
    }
  if (redistributed != redistributeSurfaceMass_) elementMass_.clear();
  redistributeSurfaceMass_ = redistributed && contact_;
}

std::vector<std::string> Model::bodiesWithoutMass() const {
  std::vector<std::string> out;
  for (int b = 0; b < mesh_->numBodies(); ++b)
    if (!elements_[b]->hasMass()) out.push_back(mesh_->body(b).name);
  return out;
}

void Model::requireMass() const {
  // The bodies are known on every rank: every rank throws alike, also one
  // without elements (no rank is left waiting in a collective call).
  const auto missing = bodiesWithoutMass();
  if (!missing.empty())
    throw std::logic_error("Model: body '" + missing.front() + "' has no mass (Material/Density = 0)");
}

const Eigen::MatrixXd& Model::elementMass(size_t i) const {
  if (elementMass_.size() != localElements_.size()) {
    requireMass();
    elementMass_.resize(localElements_.size());
    Eigen::MatrixXd X;
    for (size_t k = 0; k < localElements_.size(); ++k) {
      const int e = localElements_[k];
      const int nn = mesh_->elementNumNodes(e), d = mesh_->dim();
      const int* en = mesh_->elementNodes(e);
      X.resize(nn, d);
      for (int a = 0; a < nn; ++a)
        for (int c = 0; c < d; ++c) X(a, c) = mesh_->coord(en[a])[c];
      elements_[mesh_->elementBody(e)]->mass(X, massLumping_, elementMass_[k]);
      if (redistributeSurfaceMass_) {
        std::vector<char> massless(nn);
        for (int a = 0; a < nn; ++a) massless[a] = contact_->isSurfaceNode(en[a]) ? 1 : 0;
        // setContactSurfaceMassRedistributed() refused elements without
        // another node, on every rank.
        if (!redistributeNodalMass(elementMass_[k], massless, d))
          throw std::logic_error("Model: element " + std::to_string(e) + " has no node off the contact surfaces");
      }
    }
  }
  return elementMass_[i];
}

void Model::sumOverElementMasses(
    const std::function<Eigen::VectorXd(const Eigen::MatrixXd&, const std::vector<GO>&)>& perElement,
    Vector& out) const {
  requireMass();
  Vector ov(overlapMap_);
  {
    auto od = ov.getDataNonConst();
    std::vector<GO> dofs;
    for (size_t i = 0; i < localElements_.size(); ++i) {
      elementDofs(localElements_[i], dofs);
      const Eigen::VectorXd f = perElement(elementMass(i), dofs);
      for (size_t a = 0; a < dofs.size(); ++a) od[overlapMap_->getLocalElement(dofs[a])] += f[a];
    }
  }
  out.putScalar(0.0);
  out.doExport(ov, *exporter_, Tpetra::ADD);
}

void Model::applyMass(const Vector& v, Vector& Mv) const {
  requireMass();
  auto vov = toOverlap(v);
  auto vd = vov->getData();
  sumOverElementMasses(
      [&](const Eigen::MatrixXd& M, const std::vector<GO>& dofs) {
        Eigen::VectorXd ve(dofs.size());
        for (size_t a = 0; a < dofs.size(); ++a) ve[a] = vd[overlapMap_->getLocalElement(dofs[a])];
        return Eigen::VectorXd(M * ve);
      },
      Mv);
}

void Model::massDiagonal(Vector& d) const {
  sumOverElementMasses([](const Eigen::MatrixXd& M, const std::vector<GO>&) { return Eigen::VectorXd(M.diagonal()); },
                       d);
}

void Model::setBodyForce(const Vector& f) {
  bodyForce_ = createVector();
  bodyForce_->assign(f);
}

void Model::applyElementTangent(const Vector& u, const Vector& v, Vector& Kv) const {
  auto uov = toOverlap(u), vov = toOverlap(v);
  auto ud = uov->getData(), vd = vov->getData();
  Vector ov(overlapMap_);
  std::string failure;
  {
    auto od = ov.getDataNonConst();
    std::vector<GO> dofs;
    Eigen::MatrixXd X, ue;
    Eigen::VectorXd ve;
    ElementResult er;
    const int d = mesh_->dim();
    for (size_t i = 0; i < localElements_.size(); ++i) {
      const int e = localElements_[i];
      const int nn = mesh_->elementNumNodes(e);
      const int* en = mesh_->elementNodes(e);
      elementDofs(e, dofs);
      X.resize(nn, d);
      ue.resize(nn, d);
      ve.resize(nn * d);
      for (int a = 0; a < nn; ++a)
        for (int c = 0; c < d; ++c) {
          const LO l = overlapMap_->getLocalElement(dofs[d * a + c]);
          X(a, c) = mesh_->coord(en[a])[c];
          ue(a, c) = ud[l];
          ve[d * a + c] = vd[l];
        }
      try {
        elements_[mesh_->elementBody(e)]->compute(X, ue, kTangent, er);
      } catch (const InadmissibleDeformation& ex) {
        failure = ex.what();
        break;
      }
      const Eigen::VectorXd f = er.tangent * ve;
      for (size_t a = 0; a < dofs.size(); ++a) od[overlapMap_->getLocalElement(dofs[a])] += f[a];
    }
  }
  failure = firstErrorOnAnyRank(*comm_, failure);
  if (!failure.empty()) DDC_THROW(InadmissibleDeformation, failure);
  Kv.putScalar(0.0);
  Kv.doExport(ov, *exporter_, Tpetra::ADD);
}

double Model::kineticEnergy(const Vector& v) const {
  auto Mv = createVector();
  applyMass(v, *Mv);
  return 0.5 * v.dot(*Mv);
}

// ---- contact -------------------------------------------------------------------

const std::vector<ContactSlot>& Model::contactSlots() const {
  static const std::vector<ContactSlot> none;
  return contact_ ? contact_->slots() : none;
}

Teuchos::RCP<const Map> Model::multiplierMap() const { return contact_ ? contact_->multiplierMap() : Teuchos::null; }

const std::vector<int>& Model::ownedSlots() const {
  static const std::vector<int> none;
  return contact_ ? contact_->ownedSlots() : none;
}

bool Model::updatePairing(const Vector& u, bool global, bool freeze, std::vector<int>* changedSlots) {
  if (!contact_) return false;  // nothing to pair
  const bool changed = contact_->updatePairing(u, global, freeze, changedSlots);
  if (changed && ownedGraph_.get()) buildTopology();
  return changed;
}

void Model::activateAllPaired() {
  if (contact_) contact_->activateAllPaired();
}

bool Model::fullyPrescribed(int k) const { return contact_ && contact_->fullyPrescribed(k); }

std::vector<int> Model::updateActiveSet(const Vector& u, bool everySlot) {
  if (!contact_) return {};  // no surface or multiplier maps exist
  // A geometry the update cannot evaluate (a closest-point projection that
  // does not converge, at an iterate far from the solution) is raised on
  // every rank, so that all of them fail the iteration together.
  std::vector<int> changed;
  std::string failure;
  try {
    changed = contact_->updateActiveSet(u, nullptr, everySlot);
  } catch (const InadmissibleDeformation& e) {
    failure = e.what();
  }
  raiseCollectively<InadmissibleDeformation>(rawComm(*comm_), failure);
  return changed;
}

void Model::restoreContactState(const std::vector<ContactSlot>& saved) {
  if (contact_ && contact_->restoreSlots(saved)) buildTopology();
}

std::array<long, 3> Model::searchCounters() const {
  return contact_ ? contact_->searchCounters() : std::array<long, 3>{0, 0, 0};
}

void Model::subtractContactRowForces(const std::vector<ContactRowEntry>& rows, const Vector& values, Vector& b) const {
  Vector ov(overlapMap_), fov(overlapMap_), f(ownedMap_);
  ov.doImport(values, *importer_, Tpetra::INSERT);
  {
    auto v = ov.getData();
    auto fv = fov.getDataNonConst();
    // A prescribed DOF takes the force as a reaction: it is no part of b
    // (as it has no entry in contactRowEntries()).
    for (const ContactRowEntry& e : rows) {
      const double value = v[overlapMap_->getLocalElement(e.row)];
      if (value != 0.0 && !constrained_[e.dof]) fv[overlapMap_->getLocalElement(e.dof)] += e.coefficient * value;
    }
  }
  f.doExport(fov, *exporter_, Tpetra::ADD);
  b.update(-1.0, f, 1.0);
}

std::vector<std::vector<ConstraintEntry>> Model::contactRowEntries(const std::vector<SubdomainSystem>& systems) const {
  std::vector<std::vector<ConstraintEntry>> out(systems.size());
  if (!contact_) return out;
  auto localIndex = [&](const SubdomainSystem& sys, GO g) {
    const auto it = std::lower_bound(sys.dofs.begin(), sys.dofs.end(), g);
    return it != sys.dofs.end() && *it == g ? int(it - sys.dofs.begin()) : -1;
  };
  // The slave counterpart goes to the first (lowest-index) local subdomain
  // having the slave node, the master counterpart to its facet's subdomain.
  int slot = -1;
  size_t slaveSystem = systems.size();
  for (const ContactRowEntry& e : contact_->contactRows()) {
    if (e.role == SurfaceContactRole::Slave && e.slot != slot) {
      slot = e.slot;
      slaveSystem = systems.size();
      const int id = contact_->slots()[e.slot].slaveNode;
      for (size_t i = 0; i < systems.size() && slaveSystem == systems.size(); ++i)
        for (int c = 0; c < mesh_->dim(); ++c)
          if (slaveSystem == systems.size() && localIndex(systems[i], contact_->surfaceNodeDof(id, c)) >= 0)
            slaveSystem = i;
    }
    for (size_t i = 0; i < systems.size(); ++i) {
      if (e.role == SurfaceContactRole::Master ? systems[i].id != e.subdomain : i != slaveSystem) continue;
      const int l = localIndex(systems[i], e.dof);
      if (l >= 0) out[i].push_back({e.row, LO(l), e.coefficient});
    }
  }
  return out;
}

namespace {

/// A material parameter for a message, flagged if it is non-finite or
/// extreme (beyond what products in the element arithmetic survive).
std::string materialValue(const char* name, double v, bool extreme) {
  std::ostringstream os;
  os << name << " = " << v;
  if (!std::isfinite(v))
    os << " (non-finite)";
  else if (extreme)
    os << " (extreme)";
  return os.str();
}

}  // namespace

std::string Model::describeNonFinite(const Vector& v) const {
  const auto data = v.getData();
  const auto& map = *v.getMap();
  // Non-finite entry of smallest global id; otherwise largest |entry|.
  GO firstBad = std::numeric_limits<GO>::max();
  double largest = 0.0;
  GO largestAt = -1;
  for (size_t l = 0; l < data.size(); ++l) {
    const GO g = map.getGlobalElement(static_cast<LO>(l));
    if (!std::isfinite(data[l])) {
      firstBad = std::min(firstBad, g);
    } else if (std::abs(data[l]) > largest) {
      largest = std::abs(data[l]);
      largestAt = g;
    }
  }
  GO bad = firstBad;
  Teuchos::reduceAll<int, GO>(*comm_, Teuchos::REDUCE_MIN, firstBad, Teuchos::outArg(bad));
  GO at = bad;
  std::string what;
  if (bad != std::numeric_limits<GO>::max()) {
    // What the value is, from its owner (a NaN would not survive a sum
    // over ranks, so the owner sends a code).
    double code = 0.0, agreed = 0.0;
    if (map.isNodeGlobalElement(bad)) {
      const double value = data[map.getLocalElement(bad)];
      code = std::isnan(value) ? 1.0 : (value > 0 ? 2.0 : 3.0);
    }
    Teuchos::reduceAll<int, double>(*comm_, Teuchos::REDUCE_MAX, code, Teuchos::outArg(agreed));
    what = agreed == 1.0 ? "NaN" : agreed == 2.0 ? "+inf" : "-inf";
  } else {
    double globalLargest = 0.0;
    Teuchos::reduceAll<int, double>(*comm_, Teuchos::REDUCE_MAX, largest, Teuchos::outArg(globalLargest));
    double normSquared = 0.0;
    for (size_t l = 0; l < data.size(); ++l) normSquared += data[l] * data[l];
    double total = 0.0;
    Teuchos::reduceAll<int, double>(*comm_, Teuchos::REDUCE_SUM, normSquared, Teuchos::outArg(total));
    if (std::isfinite(total)) return "";
    GO candidate = largest == globalLargest ? largestAt : std::numeric_limits<GO>::max();
    Teuchos::reduceAll<int, GO>(*comm_, Teuchos::REDUCE_MIN, candidate, Teuchos::outArg(at));
    std::ostringstream os;
    os << "no entry is non-finite but the norm overflows; the largest entry is " << globalLargest;
    what = os.str();
  }

  // A whole mesh and its DOF numbering are on every rank: each names the
  // same place. A part holds only its own nodes: the DOF's owner names it.
  if (!mesh_->isPart()) return placeOf(at, bad == at, what);
  return firstErrorOnAnyRank(*comm_, ownedMap_->isNodeGlobalElement(at) ? placeOf(at, bad == at, what) : "");
}

std::string Model::placeOf(GO at, bool nonFinite, const std::string& what) const {
  std::ostringstream os;
  for (size_t k = 0; k < lmDof_.size(); ++k)
    if (lmDof_[k] == at) {
      os << (nonFinite ? what + " at the contact multiplier of " : what + ", at the contact multiplier of ")
         << describeSlot(static_cast<int>(k));
      return os.str();
    }
  int node = -1, component = -1;
  for (int n = 0; n < mesh_->numNodes() && node < 0; ++n)
    for (int c = 0; c < mesh_->dim(); ++c)
      if (dof(n, c) == at) node = n, component = c;
  if (node < 0) {
    os << what << " at DOF " << at;
    return os.str();
  }
  os << what << (nonFinite ? " at " : ", at ") << "u_" << "xyz"[component] << " of node " << mesh_->nodeId(node) << " ("
     << mesh_->coordText(node) << ")";
  for (int e = 0; e < mesh_->numElements(); ++e) {
    const int* nodes = mesh_->elementNodes(e);
    if (std::find(nodes, nodes + mesh_->elementNumNodes(e), node) == nodes + mesh_->elementNumNodes(e)) continue;
    const int b = mesh_->elementBody(e);
    os << ", in element " << mesh_->elementId(e) << " of body '" << mesh_->body(b).name << "'";
    if (const auto* ce = dynamic_cast<const ContinuumElement*>(elements_[b].get())) {
      const Material& m = ce->material();
      // Extreme: beyond 1e100 or below 1e-100 (energies and tangents carry
      // the modulus times squared strains), or lambda/mu > 1e8 (Poisson's
      // ratio within about 5e-9 of 0.5).
      const double E = m.youngsModulus();
      const bool extremeE = std::abs(E) > 1e100 || std::abs(E) < 1e-100;
      const bool extremeNu = m.mu() != 0.0 && std::abs(m.lambda() / m.mu()) > 1e8;
      os << " (material " << m.typeName() << ": " << materialValue("Young's Modulus", E, extremeE) << ", "
         << materialValue("Poisson's Ratio", m.poissonsRatio(), extremeNu) << ")";
    }
    break;
  }
  return os.str();
}

bool Model::tangentIsConstant() const { return !hasContact() && elementTangentsAreConstant(); }

bool Model::elementTangentsAreConstant() const {
  for (const auto& e : elements_)
    if (e && !e->tangentIsConstant()) return false;
  return true;
}

}  // namespace ddc
