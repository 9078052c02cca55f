#include "DDC_ContactComponent.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"

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
  double x, y;
};
struct FacetRecord {
  long id;
  int n0, n1, element, subdomain, rank;
  double depth;
};

/// Every rank's records on every rank, ordered by source rank.
template <class T>
std::vector<T> allGather(MPI_Comm comm, const std::vector<T>& mine) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  return exchangeRecords(comm, std::vector<std::vector<T>>(size, mine));
}

}  // namespace

/// A pair after commit(): merged facets (ascending facet id), its search.
struct ContactComponent::Pair {
  std::string name, path, slaveName, masterName;
  // Registration shares (before commit()).
  std::vector<int> mySlaves;
  std::vector<ContactFacet> mySlaveFacets, myMasterFacets;
  // After commit().
  std::vector<FacetRecord> masterFacets;  ///< in surface (search) order
  FacingRule rule;                        ///< slave segments, master depths
  std::unique_ptr<ContactSearch> search;
  std::vector<int> slots;  ///< slots of the pair, in search order
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
                                   std::vector<std::shared_ptr<const ContactElement>> elements)
    : comm_(std::move(comm)), options_(options) {
  if (options_.decomposed) {
    if (elements.size() != 2 || !elements[0] || !elements[1])
      throw std::invalid_argument("ContactComponent: decomposed contact needs the slave and master counterparts "
                                  "(\"Decomposed NTS Slave\", \"Decomposed NTS Master\")");
    slaveElement_ = elements[0];
    masterElement_ = elements[1];
  } else {
    if (elements.size() != 1 || !elements[0])
      throw std::invalid_argument("ContactComponent: conventional contact needs the \"Node-To-Segment\" element");
    ntsElement_ = elements[0];
  }
}

ContactComponent::~ContactComponent() = default;

void ContactComponent::requireCommitted(const char* what) const {
  if (!committed_ || !hasDofs_)
    throw std::logic_error(std::string("ContactComponent::") + what + ": call commit() and setDofs() first");
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

Eigen::Vector2d ContactComponent::referencePosition(int id) const {
  const int i = index(id);
  DDC_ASSERT(i >= 0, "node " << id << " is not on a contact surface");
  return X_[i];
}

int ContactComponent::slotOwner(int k) const { return slotOwner_[k]; }

const std::string& ContactComponent::pairName(int p) const { return pairs_[p].name; }

int ContactComponent::numPairs() const { return static_cast<int>(pairs_.size()); }

void ContactComponent::commit() {
  if (committed_) throw std::logic_error("ContactComponent::commit called twice");
  const MPI_Comm mpi = rawComm(comm_);
  const int me = comm_->getRank();
  // 1. Surface nodes: every rank learns every node and its owner.
  std::vector<NodeRecord> mine;
  for (const auto& n : myNodes_) mine.push_back({n.id, me, n.X.x(), n.X.y()});
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
    X_.emplace_back(all[i].x, all[i].y);
    owner_.push_back(all[i].rank);
  }
  myNodes_.clear();
  myNodes_.shrink_to_fit();
  auto requireNode = [&](const Pair& p, int id, const char* role) {
    DDC_INPUT_REQUIRE(index(id) >= 0, "contact pair '" << p.path << "': " << role << " node " << id
                                                       << " is not a registered surface node (no rank registered it)");
  };

  // 2. Per pair: merge the facets and slave nodes, build the slots and the search.
  std::vector<char> isMasterNode(nodeIds_.size(), 0);
  for (int p = 0; p < numPairs(); ++p) {
    Pair& pair = pairs_[p];
    auto gatherFacets = [&](const std::vector<ContactFacet>& facets, const char* role) {
      std::vector<FacetRecord> recs;
      for (const auto& f : facets)
        recs.push_back({f.id, f.nodes[0], f.nodes[1], f.element, f.subdomain, me, f.depth});
      auto merged = allGather(mpi, recs);
      std::sort(merged.begin(), merged.end(), [](const FacetRecord& a, const FacetRecord& b) { return a.id < b.id; });
      for (size_t i = 1; i < merged.size(); ++i)
        DDC_INPUT_REQUIRE(merged[i].id != merged[i - 1].id, "contact pair '" << pair.path << "': " << role << " facet "
                                                                             << merged[i].id
                                                                             << " is registered twice (ranks "
                                                                             << merged[i - 1].rank << " and "
                                                                             << merged[i].rank << ")");
      for (const auto& f : merged) {
        requireNode(pair, f.n0, role);
        requireNode(pair, f.n1, role);
      }
      return merged;
    };
    const auto slaveFacets = gatherFacets(pair.mySlaveFacets, "slave");
    pair.masterFacets = gatherFacets(pair.myMasterFacets, "master");
    std::vector<int> slaveNodes = allGather(mpi, pair.mySlaves);
    std::sort(slaveNodes.begin(), slaveNodes.end());
    slaveNodes.erase(std::unique(slaveNodes.begin(), slaveNodes.end()), slaveNodes.end());
    pair.mySlaves.clear();
    pair.mySlaveFacets.clear();
    pair.myMasterFacets.clear();
    DDC_INPUT_REQUIRE(!pair.masterFacets.empty(), "contact pair '" << pair.path << "': the master surface '"
                                                                   << pair.masterName << "' has no facets");
    std::vector<std::array<int, 2>> masterSegments, slaveSegments;
    for (const auto& f : pair.masterFacets) {
      masterSegments.push_back({f.n0, f.n1});
      pair.rule.masterDepths.push_back(f.depth);
    }
    for (const auto& f : slaveFacets) slaveSegments.push_back({f.n0, f.n1});
    MasterSurface master(masterSegments);
    for (int n : master.nodes()) isMasterNode[index(n)] = 1;
    std::vector<int> slaves;
    for (int n : slaveNodes) {
      if (master.localNode(n) >= 0) continue;  // a node of both surfaces (shared corner) is not a slave
      requireNode(pair, n, "slave");
      slaves.push_back(n);
    }
    DDC_INPUT_REQUIRE(!slaves.empty(), "contact pair '" << pair.path << "': the slave side set '" << pair.slaveName
                                                        << "' has no nodes off the master surface");
    std::map<int, double> tributary;
    for (const auto& sg : slaveSegments) {
      const Eigen::Vector2d& a = X_[index(sg[0])];
      const Eigen::Vector2d& b = X_[index(sg[1])];
      const double half = 0.5 * std::hypot(b.x() - a.x(), b.y() - a.y());
      tributary[sg[0]] += half;
      tributary[sg[1]] += half;
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
    // master segments (a slave's segment and its neighbours), with room
    // for stretching (x 2).
    double longest = 0.0;
    for (int g = 0; g < master.numSegments(); ++g) {
      const Eigen::Vector2d& a = X_[index(master.segment(g)[0])];
      const Eigen::Vector2d& b = X_[index(master.segment(g)[1])];
      longest = std::max(longest, std::hypot(b.x() - a.x(), b.y() - a.y()));
    }
    pairingMargin_ = std::max(pairingMargin_, options_.searchRadius + 4.0 * longest);
    for (int n : master.nodes()) masterSurfaceNodes_.push_back(n);
    // The facing rule (doc/contact.md "Which slave nodes pair"): slave nodal
    // normals from the slave segments, master element depths from the host.
    pair.rule.slaveSegments = std::move(slaveSegments);
    pair.search = std::make_unique<ContactSearch>(std::move(master), slaves, options_.searchRadius, pair.rule);
  }
  for (size_t k = 0; k < slots_.size(); ++k)
    if (slotOwner_[k] == me) localSlots_.push_back(static_cast<int>(k));

  // 3. Decomposed pairing (distributedSearch()): the slave nodal normals need
  //    the positions of the nodes next to each slave node on the slave
  //    surface; those owned by another rank than the slave's are sent to it.
  if (options_.decomposed) {
    std::vector<std::pair<int, int>> sends;  // (node, rank) with node owned here
    for (const auto& pair : pairs_) {
      std::vector<int> slaveNodes;
      for (int k : pair.slots) slaveNodes.push_back(slots_[k].slaveNode);
      std::sort(slaveNodes.begin(), slaveNodes.end());
      for (const auto& sg : pair.rule.slaveSegments)
        for (int end = 0; end < 2; ++end) {
          const int a = sg[end], b = sg[1 - end];
          if (!std::binary_search(slaveNodes.begin(), slaveNodes.end(), a)) continue;
          const int oa = owner_[index(a)], ob = owner_[index(b)];
          if (ob == me && oa != ob) sends.emplace_back(b, oa);
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
    GO d0, d1;
    int p0, p1;
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
      for (int c = 0; c < 2 && os.tellp() == 0; ++c)
        if (!hostMap->isNodeGlobalElement(nd.dofs[c]))
          os << "contact: surface node " << nd.id << " (rank " << me << ") has DOF id " << nd.dofs[c] << " for u_"
             << "xy"[c] << ", which rank " << me << " does not own in the host's DOF map: register each surface "
             << "node on the rank that owns its DOFs";
    }
    if (os.tellp() != 0 && error.empty()) error = os.str();
    if (i >= 0) given[i] = 1;
    mine.push_back({nd.id, nd.dofs[0], nd.dofs[1], int(nd.prescribed[0]), int(nd.prescribed[1])});
  }
  for (size_t i = 0; i < nodeIds_.size() && error.empty(); ++i)
    if (owner_[i] == me && !given[i])
      error = "contact: rank " + std::to_string(me) + " registered surface node " + std::to_string(nodeIds_[i]) +
              " but gave no DOFs for it";
  if (error.empty() && !multiplierDofs.empty()) {
    if (multiplierDofs.size() != localSlots_.size()) {
      error = "contact: rank " + std::to_string(me) + " gives " + std::to_string(multiplierDofs.size()) +
              " multiplier DOFs for its " + std::to_string(localSlots_.size()) + " contact slots";
    } else {
      for (GO g : multiplierDofs)
        if (!hostMap->isNodeGlobalElement(g)) {
          error = "contact: multiplier DOF id " + std::to_string(g) + " is not owned by rank " + std::to_string(me) +
                  " (the owner of its slave node) in the host's DOF map";
          break;
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
  dofs_.assign(nodeIds_.size(), {{-1, -1}});
  prescribed_.assign(nodeIds_.size(), {{0, 0}});
  for (const auto& r : all) {
    const int i = index(r.id);
    dofs_[i] = {{r.d0, r.d1}};
    prescribed_[i] = {{char(r.p0), char(r.p1)}};
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
  for (const auto& d : dofs_) gids.insert(gids.end(), {d[0], d[1]});
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

std::vector<GO> ContactComponent::slotDofs(int k) const {
  const ContactSlot& s = slots_[k];
  std::vector<GO> dofs;
  if (s.paired())
    for (int n : {s.slaveNode, s.master[0], s.master[1]}) dofs.insert(dofs.end(), dofs_[index(n)].begin(), dofs_[index(n)].end());
  dofs.push_back(lmGid_[k]);
  return dofs;
}

std::vector<GO> ContactComponent::slaveSideDofs(int k) const {
  const auto& d = dofs_[index(slots_[k].slaveNode)];
  return {d[0], d[1], lmGid_[k]};
}

std::vector<GO> ContactComponent::masterSideDofs(int k) const {
  const auto& a = dofs_[index(slots_[k].master[0])];
  const auto& b = dofs_[index(slots_[k].master[1])];
  return {a[0], a[1], b[0], b[1], lmGid_[k]};
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

void ContactComponent::evaluate(int k, int side, const Field& f, bool forceActive, unsigned what, ElementResult& er,
                                std::vector<GO>& dofs) const {
  // side: 0 slave counterpart, 1 master counterpart, 2 conventional element.
  const ContactSlot& s = slots_[k];
  dofs = side == 0 ? slaveSideDofs(k) : side == 1 ? masterSideDofs(k) : slotDofs(k);
  ContactPairState state = s.state;
  state.active = s.active || forceActive;
  state.multiplier = f.multiplier(k);
  const int nn = side == 0 ? 1 : side == 1 ? 2 : 3;
  const int all[3] = {s.slaveNode, s.master[0], s.master[1]};
  const int* nodes = side == 1 ? all + 1 : all;
  Eigen::MatrixX2d X(nn, 2), ue(nn, 2);
  for (int i = 0; i < nn; ++i) {
    X.row(i) = X_[index(nodes[i])].transpose();
    for (int c = 0; c < 2; ++c) ue(i, c) = f.at(dofs[2 * i + c]);
  }
  const ContactElement& el = side == 0 ? *slaveElement_ : side == 1 ? *masterElement_ : *ntsElement_;
  el.computeContact(X, ue, state, what, er);
}

void ContactComponent::assemble(const Vector& u, const Vector* multipliers, unsigned what,
                                const std::function<void(const std::vector<GO>&, ElementResult&)>& add) const {
  requireCommitted("assemble");
  const Field f = gatherField(u, multipliers);
  ElementResult er;
  std::vector<GO> dofs;
  // The conventional element of each owned slot, or the decomposed
  // counterparts where they live (the slave's on the owner of the slave node,
  // the master's on the rank of the master facet); they share only the
  // multiplier. Unpaired slots carry only Π = ½λ² (λ = 0).
  const int side = options_.decomposed ? 0 : 2;
  for (int k : localSlots_) {
    if (slots_[k].paired()) {
      evaluate(k, side, f, false, what | kTangent, er, dofs);
    } else {
      dofs.assign(1, lmGid_[k]);
      releasedContribution(1, f.multiplier(k), kAll, er);
    }
    add(dofs, er);
  }
  for (int k : localMasterSlots_) {
    evaluate(k, 1, f, false, what | kTangent, er, dofs);
    add(dofs, er);
  }
}

std::vector<ContactRowEntry> ContactComponent::contactRows() const {
  requireCommitted("contactRows");
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
  auto add = [&](int k, bool master) {
    evaluate(k, master ? 1 : 0, f, true, kTangent, er, dofs);
    const int row = int(dofs.size()) - 1;
    const int sub = master ? pairs_[slots_[k].pair].masterFacets[slots_[k].segment].subdomain : -1;
    for (int a = 0; a < row; ++a)
      if (er.tangent(row, a) != 0.0) out.push_back({k, lmGid_[k], dofs[a], er.tangent(row, a), master, sub});
  };
  for (int k : localSlots_)
    if (slots_[k].paired()) add(k, false);
  for (int k : localMasterSlots_) add(k, true);
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

Eigen::Vector2d ContactComponent::currentPosition(int id, const std::vector<double>& v) const {
  const int i = index(id);
  DDC_ASSERT(i >= 0, "node " << id << " is not on a contact surface");
  return {X_[i].x() + v[2 * i], X_[i].y() + v[2 * i + 1]};
}

namespace {
/// A surface node's current position, sent to the ranks whose slave bounding box contains it.
struct NodePosition {
  int node;
  double x, y;
};
/// The pairing of one slot, found by the owner of its slave node.
struct SlotPairing {
  int slot, segment, pastFreeEnd, viaCorner;
  double xi, gap, distance, nx, ny;
};
}  // namespace

void ContactComponent::distributedSearch(const Vector& u, std::vector<std::vector<ContactCandidate>>& cands,
                                         std::vector<std::vector<char>>& pastFreeEnd) {
  const MPI_Comm mpi = rawComm(comm_);
  const int me = comm_->getRank(), P = comm_->getSize();
  auto ud = u.getData();
  auto ownedPosition = [&](int n) {
    const int i = index(n);
    const LO l0 = hostMap_->getLocalElement(dofs_[i][0]), l1 = hostMap_->getLocalElement(dofs_[i][1]);
    return Eigen::Vector2d(X_[i].x() + ud[l0], X_[i].y() + ud[l1]);
  };
  auto owner = [&](int n) { return owner_[index(n)]; };
  // 1. Bounding box of this rank's slave nodes, inflated by a margin that
  //    covers every master segment (and its neighbours) a slave can pair with.
  double box[4] = {1e300, 1e300, -1e300, -1e300};
  for (int k : localSlots_) {
    const Eigen::Vector2d x = ownedPosition(slots_[k].slaveNode);
    box[0] = std::min(box[0], x.x()), box[1] = std::min(box[1], x.y());
    box[2] = std::max(box[2], x.x()), box[3] = std::max(box[3], x.y());
  }
  std::vector<double> boxes(4 * P);
  MPI_Allgather(box, 4, MPI_DOUBLE, boxes.data(), 4, MPI_DOUBLE, mpi);
  // 2. Each rank sends the current positions of the master-surface nodes it
  //    owns to the ranks whose inflated box contains them.
  std::vector<std::vector<NodePosition>> send(P);
  for (int n : masterSurfaceNodes_) {
    if (owner(n) != me) continue;
    const Eigen::Vector2d x = ownedPosition(n);
    for (int r = 0; r < P; ++r) {
      const double* b = &boxes[4 * r];
      if (x.x() >= b[0] - pairingMargin_ && x.x() <= b[2] + pairingMargin_ && x.y() >= b[1] - pairingMargin_ &&
          x.y() <= b[3] + pairingMargin_)
        send[r].push_back({n, x.x(), x.y()});
    }
  }
  //    With them, the slave-surface neighbours of other ranks' slave nodes
  //    (the facing rule's nodal normals), unless already on the way.
  for (const auto& [node, r] : slaveNeighbourSends_) {
    const int n = node;
    if (std::any_of(send[r].begin(), send[r].end(), [n](const NodePosition& q) { return q.node == n; })) continue;
    const Eigen::Vector2d x = ownedPosition(n);
    send[r].push_back({n, x.x(), x.y()});
  }
  long bytes = 0;
  for (int r = 0; r < P; ++r)
    if (r != me) bytes += long(send[r].size() * sizeof(NodePosition));
  const std::vector<NodePosition> recv = exchangeRecords(mpi, send);
  std::map<int, Eigen::Vector2d> known;
  for (const auto& np : recv) known[np.node] = Eigen::Vector2d(np.x, np.y);
  for (int k : localSlots_) known[slots_[k].slaveNode] = ownedPosition(slots_[k].slaveNode);
  for (const auto& pair : pairs_)  // slave-surface neighbours owned here
    for (const auto& sg : pair.rule.slaveSegments)
      for (int n : sg)
        if (owner(n) == me && !known.count(n)) known[n] = ownedPosition(n);
  // 3. Per pair: the global search for this rank's slaves over the master
  //    segments whose nodes arrived (kept in their global order, so ties
  //    break as in the replicated search).
  std::vector<std::vector<SlotPairing>> results(P);
  long queries = 0;
  for (const auto& pair : pairs_) {
    const MasterSurface& whole = pair.search->master();
    std::vector<int> localSlaves, localSlotIds;
    for (int k : pair.slots)
      if (slotOwner_[k] == me) localSlaves.push_back(slots_[k].slaveNode), localSlotIds.push_back(k);
    std::vector<std::array<int, 2>> segs;
    std::vector<int> globalIndex;
    for (int g = 0; g < whole.numSegments(); ++g)
      if (known.count(whole.segment(g)[0]) && known.count(whole.segment(g)[1]))
        segs.push_back(whole.segment(g)), globalIndex.push_back(g);
    std::vector<ContactCandidate> found(localSlaves.size());
    if (!localSlaves.empty() && !segs.empty()) {
      // The pair's facing rule on the segments that arrived (same numbers as
      // the replicated search: the rule needs nothing else).
      FacingRule rule;
      rule.slaveSegments = pair.rule.slaveSegments;
      for (int g : globalIndex) rule.masterDepths.push_back(pair.rule.masterDepths[g]);
      ContactSearch search(MasterSurface(segs), localSlaves, pair.search->searchRadius(), std::move(rule));
      search.update([&](int n) { return known.at(n); }, true);
      found = search.candidates();
      queries += long(localSlaves.size());
    }
    for (size_t i = 0; i < found.size(); ++i) {
      const ContactCandidate& c = found[i];
      const int g = c.segment >= 0 ? globalIndex[c.segment] : -1;
      // Past a free end of the whole surface (not of the part that arrived).
      const int pe = g >= 0 && c.viaCorner && whole.neighbour(g, c.xi < 0.5 ? 0 : 1) < 0;
      for (int r = 0; r < P; ++r)
        results[r].push_back({localSlotIds[i], g, pe, int(c.viaCorner), c.xi, c.gap, c.distance, c.normal.x(),
                              c.normal.y()});
    }
  }
  for (int r = 0; r < P; ++r)
    if (r != me) bytes += long(results[r].size() * sizeof(SlotPairing));
  // 4. Every rank learns every slot's pairing (the slots are replicated).
  const std::vector<SlotPairing> all = exchangeRecords(mpi, results);
  cands.assign(pairs_.size(), {});
  pastFreeEnd.assign(pairs_.size(), {});
  std::vector<int> indexInPair(slots_.size(), -1);
  for (size_t p = 0; p < pairs_.size(); ++p) {
    cands[p].assign(pairs_[p].slots.size(), ContactCandidate{});
    pastFreeEnd[p].assign(pairs_[p].slots.size(), 0);
    for (size_t i = 0; i < pairs_[p].slots.size(); ++i) indexInPair[pairs_[p].slots[i]] = int(i);
  }
  for (const auto& a : all) {
    const int p = slots_[a.slot].pair, i = indexInPair[a.slot];
    ContactCandidate& c = cands[p][i];
    c.segment = a.segment;
    c.xi = a.xi;
    c.gap = a.gap;
    c.distance = a.distance;
    c.normal = Eigen::Vector2d(a.nx, a.ny);
    c.viaCorner = a.viaCorner != 0;
    pastFreeEnd[p][i] = static_cast<char>(a.pastFreeEnd);
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
  std::vector<std::vector<ContactCandidate>> found;
  std::vector<std::vector<char>> pastEnd;
  if (distributed) {
    distributedSearch(u, found, pastEnd);
  } else {
    // Positions only: the multipliers are not read here.
    Vector s(surfaceMap_);
    s.doImport(u, *surfaceImporter_, Tpetra::INSERT);
    ++exchanges_;
    bytesExchanged_ += bytesPerExchange_;
    auto d = s.getData();
    v.assign(d.begin(), d.end());
    for (auto& pair : pairs_) {
      ContactSearch& search = *pair.search;
      search.update([&](int n) { return currentPosition(n, v); }, global);
      found.push_back(search.candidates());
      pastEnd.emplace_back();
      // A slave beyond a free end of the master surface is not in contact
      // with it (only a convex corner between two segments pairs "via corner").
      for (const auto& c : found.back())
        pastEnd.back().push_back(c.segment >= 0 && c.viaCorner &&
                                 search.master().neighbour(c.segment, c.xi < 0.5 ? 0 : 1) < 0);
    }
  }
  bool changed = false;
  for (size_t p = 0; p < pairs_.size(); ++p) {
    const ContactSearch& search = *pairs_[p].search;
    const auto& cands = found[p];
    for (size_t i = 0; i < cands.size(); ++i) {
      ContactSlot& s = slots_[pairs_[p].slots[i]];
      const auto& c = cands[i];
      int m0 = -1, m1 = -1;
      const bool pastFreeEnd = pastEnd[p][i] != 0;
      if (c.segment >= 0 && !pastFreeEnd) {
        m0 = search.master().segment(c.segment)[0];
        m1 = search.master().segment(c.segment)[1];
      }
      // Hysteresis (Newton iterations only): a slave whose projection onto
      // its previous segment lies within kPairingHysteresis of that segment
      // keeps it. Without it a slave sitting on a master node can flip
      // between the two adjacent segments every iteration and Newton stalls;
      // and a slave sitting on the free end of the master surface (two
      // blocks of one width) flips between paired and "past the end" with
      // the round-off of its position (a different summation order on two
      // ranks is enough), which the active-set check reports as cycling.
      constexpr double kPairingHysteresis = 1e-2;  // fraction of the segment length
      // The kept segment must pass the facing rule like any pairing.
      if (!distributed && !global && s.paired() && (m0 >= 0 || pastFreeEnd) &&
          (m0 != s.master[0] || m1 != s.master[1])) {
        const Eigen::Vector2d xs = currentPosition(s.slaveNode, v), x1 = currentPosition(s.master[0], v),
                              x2 = currentPosition(s.master[1], v);
        const Eigen::Vector2d t = x2 - x1;
        const double xi = (xs - x1).dot(t) / t.squaredNorm();
        const Eigen::Vector2d n = Eigen::Vector2d(t.y(), -t.x()).normalized();
        const double gap = n.dot(xs - x1);
        if (xi >= -kPairingHysteresis && xi <= 1.0 + kPairingHysteresis &&
            facingVerdict(c.slaveNormal, n, gap, search.penetrationLimit(s.segment)) == ContactRejection::None) {
          s.gap = gap;
          s.normal = n;
          if (freeze) {
            s.state.frozenXi = xi;
            s.state.frozenNormal = s.normal;
          }
          continue;
        }
      }
      if (m0 != s.master[0] || m1 != s.master[1]) {
        changed = true;
        if (changedSlots) changedSlots->push_back(pairs_[p].slots[i]);
      }
      s.master[0] = m0;
      s.master[1] = m1;
      s.segment = m0 >= 0 ? c.segment : -1;
      s.masterElement = m0 >= 0 ? pairs_[p].masterFacets[c.segment].element : -1;
      if (m0 < 0) {
        s.active = false;
        s.gap = 0.0;
        continue;
      }
      s.gap = c.gap;
      s.normal = c.normal;
      if (freeze) {
        s.state.frozenXi = c.xi;
        s.state.frozenNormal = c.normal;
      }
    }
  }
  if (changed) buildTopology();
  return changed;
}

void ContactComponent::checkInitialPenetration(
    const std::vector<std::function<int(const Eigen::Vector2d&)>>& locate) const {
  // doc/contact.md "Which slave nodes pair": a slave node inside the master
  // body that the search does not pair keeps λ = 0 for ever, so the bodies
  // would silently stay overlapped there. Reference configuration,
  // replicated surfaces and slots: every rank reaches the same verdict.
  for (size_t p = 0; p < pairs_.size() && p < locate.size(); ++p) {
    if (!locate[p]) continue;
    const Pair& pair = pairs_[p];
    int first = -1, count = 0, element = -1;
    for (int k : pair.slots) {
      if (slots_[k].paired()) continue;
      const int e = locate[p](referencePosition(slots_[k].slaveNode));
      if (e < 0) continue;
      if (first < 0) first = k, element = e;
      ++count;
    }
    if (first < 0) continue;
    // Why the first such node is not paired: the pair's search (same radius,
    // same facing rule) on that node alone.
    const ContactSearch& whole = *pair.search;
    const int node = slots_[first].slaveNode;
    auto reference = [&](int n) { return referencePosition(n); };
    ContactSearch probe(whole.master(), {node}, whole.searchRadius(), pair.rule);
    probe.update(reference, true);
    const ContactCandidate& c = probe.candidates()[0];
    // Depth: distance to the nearest point of the master surface.
    const Eigen::Vector2d xs = reference(node);
    double depth = std::numeric_limits<double>::infinity();
    for (int g = 0; g < whole.master().numSegments(); ++g) {
      const Eigen::Vector2d a = reference(whole.master().segment(g)[0]), b = reference(whole.master().segment(g)[1]);
      const double xi = std::min(1.0, std::max(0.0, (xs - a).dot(b - a) / (b - a).squaredNorm()));
      depth = std::min(depth, (xs - a - xi * (b - a)).norm());
    }
    std::ostringstream why;
    const int seg = c.rejectedSegment >= 0 ? c.rejectedSegment : c.segment;
    const auto segNodes = [&](int g) {
      std::ostringstream o;
      o << "(nodes " << whole.master().segment(g)[0] << ", " << whole.master().segment(g)[1] << ")";
      return o.str();
    };
    if (c.rejection == ContactRejection::TooDeep) {
      why << "it lies " << -c.gap << " behind its nearest master segment " << segNodes(seg)
          << ", not less than half the depth of that segment's element (" << whole.penetrationLimit(seg) << " = "
          << kFacingDepthFraction << " x " << pair.rule.masterDepths[seg] << ")";
    } else if (c.rejection == ContactRejection::NotFacing) {
      why << "its outward normal (" << c.slaveNormal.x() << ", " << c.slaveNormal.y()
          << ") does not face the outward normal (" << c.normal.x() << ", " << c.normal.y()
          << ") of its nearest master segment " << segNodes(seg);
    } else if (c.segment < 0) {
      why << "it is farther than the search radius (" << whole.searchRadius()
          << ", Contact/Search Radius) from every master segment";
    } else {
      // Paired by the search but past a free end of the master surface
      // (updatePairing()): the only other way a node stays unpaired.
      why << "it lies beyond a free end of the master surface (nearest segment " << segNodes(seg) << ")";
    }
    DDC_THROW(InputError, "contact pair '"
                              << pair.path << "': slave node " << node << " at (" << xs.x() << ", " << xs.y()
                              << ") of the slave side set '" << pair.slaveName
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
    c[0] += p.search->counters().trackingCalls;
    c[1] += p.search->counters().trackingFallbacks;
    c[2] += p.search->counters().globalSearches;
  }
  return c;
}

bool ContactComponent::fullyPrescribed(int k) const {
  const ContactSlot& s = slots_[k];
  if (!s.paired()) return false;
  for (int n : {s.slaveNode, s.master[0], s.master[1]})
    for (int c = 0; c < 2; ++c)
      if (!prescribed_[index(n)][c]) return false;
  return true;
}

void ContactComponent::activateAllPaired() {
  // A pair whose DOFs are all prescribed has a prescribed gap: its
  // constraint row would be empty (a singular system), so it never becomes
  // active (updateActiveSet() reports it if it penetrates).
  for (size_t k = 0; k < slots_.size(); ++k) slots_[k].active = slots_[k].paired() && !fullyPrescribed(int(k));
}

void ContactComponent::refreshSlotGeometry(const std::vector<double>& v) {
  const size_t base = 2 * nodeIds_.size();
  for (size_t k = 0; k < slots_.size(); ++k) {
    ContactSlot& s = slots_[k];
    s.state.multiplier = v[base + k];
    if (!s.paired()) continue;
    const Eigen::Vector2d xs = currentPosition(s.slaveNode, v);
    const Eigen::Vector2d x1 = currentPosition(s.master[0], v);
    const Eigen::Vector2d x2 = currentPosition(s.master[1], v);
    const Eigen::Vector2d t = x2 - x1;
    s.normal = Eigen::Vector2d(t.y(), -t.x()) / t.norm();
    s.gap = s.normal.dot(xs - x1);
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
        evaluate(k, 0, f, true, kResidual, er, dofs);
        g[lmOverlapMap_->getLocalElement(lmGid_[k])] += er.residual[er.residual.size() - 1];
      }
    for (int k : localMasterSlots_) {
      evaluate(k, 1, f, true, kResidual, er, dofs);
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
    s.normal = s.state.frozenNormal;
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
    c.force[0] -= s.state.multiplier * s.normal.x();
    c.force[1] -= s.state.multiplier * s.normal.y();
  }
  return c;
}

bool ContactComponent::restoreSlots(const std::vector<ContactSlot>& saved) {
  DDC_ASSERT(saved.size() == slots_.size(), "restoreSlots: " << saved.size() << " slots for " << slots_.size());
  bool changed = false;
  for (size_t k = 0; k < slots_.size(); ++k)
    if (saved[k].master[0] != slots_[k].master[0] || saved[k].master[1] != slots_[k].master[1]) changed = true;
  slots_ = saved;
  if (changed && hasDofs_) buildTopology();
  return changed;
}

std::string ContactComponent::describeSlot(int k) const {
  const ContactSlot& s = slots_[k];
  std::ostringstream os;
  const Eigen::Vector2d X = referencePosition(s.slaveNode);
  os << "pair '" << pairs_[s.pair].name << "' slave node " << s.slaveNode << " at (" << X.x() << ", " << X.y()
     << ")";
  return os.str();
}

}  // namespace ddc
