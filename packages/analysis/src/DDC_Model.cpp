#include "DDC_Model.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <limits>
#include <map>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "DDC_BodyLocator.hpp"
#include "DDC_ContactSearch.hpp"
#include "DDC_ContinuumElement.hpp"
#include "DDC_DecomposedNodeToSegment.hpp"
#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_ShapeFunctions.hpp"
#include "DDC_Substructuring.hpp"

namespace ddc {

Model::Model(Teuchos::RCP<const Teuchos::Comm<int>> comm, std::shared_ptr<const Mesh> mesh,
             std::vector<std::shared_ptr<const Element>> elements, Partition partition, BoundaryConditions bcs,
             ContactOptions contact, std::vector<std::shared_ptr<const ContactElement>> contactElements)
    : comm_(std::move(comm)),
      mesh_(std::move(mesh)),
      elements_(std::move(elements)),
      partition_(std::move(partition)),
      bcs_(std::move(bcs)),
      contact_(std::move(contact)) {
  DDC_ASSERT(static_cast<int>(elements_.size()) == mesh_->numBodies(), "one element evaluator per body");
  for (int b = 0; b < mesh_->numBodies(); ++b)
    DDC_ASSERT(elements_[b]->dim() == mesh_->dim(), "body '" << mesh_->body(b).name << "': a " << elements_[b]->dim()
                                                              << "-D element on a " << mesh_->dim() << "-D mesh");
  // Contact is two-dimensional (node-to-segment); the 3-D node-to-facet
  // element is not available yet (doc/contact.md).
  DDC_INPUT_REQUIRE(mesh_->dim() == 2 || !contact_.enabled(),
                    "contact pair 'Contact/Pairs/" << contact_.pairs[0].name << "': the mesh is 3-D (body '"
                                                   << mesh_->body(0).name << "' has "
                                                   << cellTypeName(mesh_->body(0).cellType)
                                                   << " cells); contact is available for 2-D meshes only");
  subdomainRank_ = subdomainOwnerRank(partition_.numSubdomains, comm_->getSize());
  for (int e = 0; e < mesh_->numElements(); ++e)
    if (subdomainRank_[partition_.elementSubdomain[e]] == comm_->getRank()) localElements_.push_back(e);

  // Contact slots: one multiplier per slave node of each pair.
  if (contact_.enabled()) {
    if (contact_.decomposed) {
      if (contactElements.size() != 2 || !contactElements[0] || !contactElements[1])
        throw std::invalid_argument("Model: decomposed contact needs the slave and master counterparts "
                                    "(\"Decomposed NTS Slave\", \"Decomposed NTS Master\") in contactElements");
      slaveElement_ = contactElements[0];
      masterElement_ = contactElements[1];
    } else {
      if (contactElements.size() != 1 || !contactElements[0])
        throw std::invalid_argument("Model: conventional contact needs the \"Node-To-Segment\" element in "
                                    "contactElements");
      ntsElement_ = contactElements[0];
    }
    std::vector<char> isSurface(mesh_->numNodes(), 0);
    for (int p = 0; p < static_cast<int>(contact_.pairs.size()); ++p) {
      const auto& def = contact_.pairs[p];
      const auto& slaveNodes = mesh_->nodeSet(def.slaveSet);
      MasterSurface master(masterSegmentsFromSideSet(*mesh_, def.masterSet));
      for (int n : master.nodes()) isSurface[n] = 1;
      std::vector<int> slaves;
      for (int n : slaveNodes) {
        if (master.localNode(n) >= 0) continue;  // a node of both surfaces (shared corner) is not a slave
        slaves.push_back(n);
      }
      DDC_INPUT_REQUIRE(!slaves.empty(), "contact pair 'Contact/Pairs/" << def.name << "': the slave side set '"
                                                                        << def.slaveSet << "' has no nodes off the master surface");
      std::map<int, double> tributary;
      for (const Segment& seg : mesh_->sideSet(def.slaveSet)) {
        const auto& a = mesh_->coord(seg.nodes[0]);
        const auto& b = mesh_->coord(seg.nodes[1]);
        const double half = 0.5 * std::hypot(b[0] - a[0], b[1] - a[1]);
        tributary[seg.nodes[0]] += half;
        tributary[seg.nodes[1]] += half;
      }
      pairMasterElements_.emplace_back();
      for (const Segment& seg : mesh_->sideSet(def.masterSet)) pairMasterElements_.back().push_back(seg.element);
      pairSlots_.emplace_back();
      for (int n : slaves) {
        isSurface[n] = 1;
        ContactSlot s;
        s.pair = p;
        s.slaveNode = n;
        s.tributaryLength = tributary[n];
        pairSlots_.back().push_back(static_cast<int>(slots_.size()));
        slots_.push_back(s);
      }
      // Margin of the bounding-box exchange: the search radius plus two
      // master segments (a slave's segment and its neighbours), with room
      // for stretching (x 2).
      double longest = 0.0;
      for (int g = 0; g < master.numSegments(); ++g) {
        const auto& a = mesh_->coord(master.segment(g)[0]);
        const auto& b = mesh_->coord(master.segment(g)[1]);
        longest = std::max(longest, std::hypot(b[0] - a[0], b[1] - a[1]));
      }
      pairingMargin_ = std::max(pairingMargin_, contact_.searchRadius + 4.0 * longest);
      for (int n : master.nodes()) masterSurfaceNodes_.push_back(n);
      // The facing rule (doc/contact.md "Which slave nodes pair"): slave
      // nodal normals from the slave segments, master element depths from
      // the reference mesh. Every search of this pair applies it.
      FacingRule rule;
      rule.slaveSegments = masterSegmentsFromSideSet(*mesh_, def.slaveSet);
      rule.masterDepths = masterElementDepths(*mesh_, def.masterSet);
      for (const auto& sg : rule.slaveSegments)
        for (int n : sg) isSurface[n] = 1;
      pairRules_.push_back(rule);
      searches_.push_back(
          std::make_unique<ContactSearch>(std::move(master), slaves, contact_.searchRadius, std::move(rule)));
    }
    for (int n = 0; n < mesh_->numNodes(); ++n)
      if (isSurface[n]) surfaceNodes_.push_back(n);
  }
  // The formulation alone says nothing about whether the contact maps exist:
  // with no pairs there are none, and the run is a plain analysis.
  decomposed_ = contact_.decomposed && hasContact();
  buildDofNumbering();
  buildConstraints();
  if (hasContact()) {
    // Replicated map of the surface DOFs and all multipliers: the one
    // collective exchange of contact geometry and state.
    std::vector<GO> gids;
    for (int n : surfaceNodes_) gids.insert(gids.end(), {dof(n, 0), dof(n, 1)});
    for (size_t k = 0; k < slots_.size(); ++k) gids.push_back(lmDof_[k]);
    surfaceMap_ = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                       Teuchos::ArrayView<const GO>(gids), 0, comm_));
    surfaceImporter_ = Teuchos::rcp(new Tpetra::Import<LO, GO, Node>(ownedMap_, surfaceMap_));
    long received = 0;
    for (GO g : gids)
      if (!ownedMap_->isNodeGlobalElement(g)) ++received;
    long total = 0;
    Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, received, Teuchos::outArg(total));
    bytesPerExchange_ = total * static_cast<long>(sizeof(double));
    surfaceIndex_.assign(mesh_->numNodes(), -1);
    for (size_t i = 0; i < surfaceNodes_.size(); ++i) surfaceIndex_[surfaceNodes_[i]] = static_cast<int>(i);
    std::vector<GO> ownedLm;
    for (size_t k = 0; k < slots_.size(); ++k)
      if (slotOwner(static_cast<int>(k)) == comm_->getRank()) {
        localSlots_.push_back(static_cast<int>(k));
        ownedLm.push_back(lmDof_[k]);
      }
    multiplierMap_ = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                          Teuchos::ArrayView<const GO>(ownedLm), 0, comm_));
    multiplierAllMap_ = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                             Teuchos::ArrayView<const GO>(lmDof_), 0, comm_));
    // Decomposed pairing (distributedSearch()): the slave nodal normals need
    // the positions of the nodes next to each slave node on the slave
    // surface; those owned by another rank than the slave's are sent to it.
    if (decomposed_) {
      std::vector<std::pair<int, int>> sends;  // (node, rank) with node owned here
      for (size_t p = 0; p < pairSlots_.size(); ++p) {
        std::vector<int> slaveNodes;
        for (int k : pairSlots_[p]) slaveNodes.push_back(slots_[k].slaveNode);
        std::sort(slaveNodes.begin(), slaveNodes.end());
        for (const auto& sg : pairRules_[p].slaveSegments)
          for (int end = 0; end < 2; ++end) {
            const int a = sg[end], b = sg[1 - end];
            if (!std::binary_search(slaveNodes.begin(), slaveNodes.end(), a)) continue;
            if (nodeOwner_[b] == comm_->getRank() && nodeOwner_[a] != nodeOwner_[b])
              sends.emplace_back(b, nodeOwner_[a]);
          }
      }
      std::sort(sends.begin(), sends.end());
      sends.erase(std::unique(sends.begin(), sends.end()), sends.end());
      slaveNeighbourSends_ = std::move(sends);
    }
    // Initial pairing in the reference configuration.
    auto zero = createVector();
    updatePairing(*zero, /*global=*/true, /*freeze=*/true);
    checkInitialPenetration();
  }
  buildTopology();
  assembleTractions();
}

Model::~Model() = default;

void Model::buildDofNumbering() {
  const Mesh& mesh = *mesh_;
  const int nranks = comm_->getSize(), me = comm_->getRank();
  nodeOwner_.assign(mesh.numNodes(), nranks);
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int r = subdomainRank_[partition_.elementSubdomain[e]];
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
      int& o = nodeOwner_[mesh.elementNodes(e)[i]];
      o = std::min(o, r);
    }
  }
  // Per rank: its nodes' DOFs, then its multipliers; ranks in order.
  std::vector<GO> count(nranks, 0);
  const int d = mesh.dim();
  for (int n = 0; n < mesh.numNodes(); ++n) count[nodeOwner_[n]] += d;
  for (size_t k = 0; k < slots_.size(); ++k) count[slotOwner(static_cast<int>(k))] += 1;
  std::vector<GO> offset(nranks + 1, 0);
  for (int r = 0; r < nranks; ++r) offset[r + 1] = offset[r] + count[r];
  numGlobalDofs_ = offset[nranks];
  std::vector<GO> next(offset.begin(), offset.end() - 1);
  nodeDof_.assign(mesh.numNodes(), -1);
  for (int n = 0; n < mesh.numNodes(); ++n) {
    nodeDof_[n] = next[nodeOwner_[n]];
    next[nodeOwner_[n]] += d;
  }
  lmDof_.assign(slots_.size(), -1);
  for (size_t k = 0; k < slots_.size(); ++k) lmDof_[k] = next[slotOwner(static_cast<int>(k))]++;
  ownedMap_ = Teuchos::rcp(new Map(numGlobalDofs_, static_cast<size_t>(count[me]), 0, comm_));
}

void Model::buildConstraints() {
  const Mesh& mesh = *mesh_;
  constrained_.assign(numGlobalDofs_, 0);
  constraintSource_.assign(numGlobalDofs_, {-1, -1});
  for (int b = 0; b < static_cast<int>(bcs_.displacements.size()); ++b) {
    const auto& bc = bcs_.displacements[b];
    for (int n : mesh.nodeSet(bc.setName))
      for (int c = 0; c < mesh.dim(); ++c) {
        if (!bc.fix[c]) continue;
        const GO g = dof(n, c);
        auto& src = constraintSource_[g];
        if (src.first >= 0) {
          // Two conditions on one DOF must agree (e.g. shared corner of two fixed edges).
          const auto& other = bcs_.displacements[src.first];
          const auto& X = mesh.coord(n);
          for (double lam : {0.5, 1.0}) {
            const double a = other.prescribed(c, X, lam), v = bc.prescribed(c, X, lam);
            DDC_INPUT_REQUIRE(std::abs(a - v) <= 1e-12 * (1.0 + std::abs(a) + std::abs(v)),
                              "boundary conditions '" << other.name << "' and '" << bc.name
                                                      << "' prescribe different " << "xyz"[c]
                                                      << " displacements at node " << n << " ("
                                                      << mesh.coordText(n) << ")");
          }
          continue;
        }
        src = {b, n};
        constrained_[g] = 1;
      }
  }
}

void Model::elementDofs(int e, std::vector<GO>& dofs) const {
  const int nn = mesh_->elementNumNodes(e), d = mesh_->dim();
  dofs.resize(d * nn);
  for (int i = 0; i < nn; ++i)
    for (int c = 0; c < d; ++c) dofs[d * i + c] = dof(mesh_->elementNodes(e)[i], c);
}

void Model::slotDofs(int k, std::vector<GO>& dofs) const {
  const ContactSlot& s = slots_[k];
  dofs.clear();
  if (s.paired())
    for (int n : {s.slaveNode, s.master[0], s.master[1]}) dofs.insert(dofs.end(), {dof(n, 0), dof(n, 1)});
  dofs.push_back(lmDof_[k]);
}

void Model::slaveSideDofs(int k, std::vector<GO>& dofs) const {
  const ContactSlot& s = slots_[k];
  dofs.assign({dof(s.slaveNode, 0), dof(s.slaveNode, 1), lmDof_[k]});
}

void Model::masterSideDofs(int k, std::vector<GO>& dofs) const {
  const ContactSlot& s = slots_[k];
  dofs.assign({dof(s.master[0], 0), dof(s.master[0], 1), dof(s.master[1], 0), dof(s.master[1], 1), lmDof_[k]});
}

void Model::evaluateCounterpart(int k, bool master, const Teuchos::ArrayRCP<const double>& ud, bool forceActive,
                                unsigned what, ElementResult& er, std::vector<LO>& lids) const {
  const ContactSlot& s = slots_[k];
  std::vector<GO> dofs;
  master ? masterSideDofs(k, dofs) : slaveSideDofs(k, dofs);
  lids.resize(dofs.size());
  for (size_t a = 0; a < dofs.size(); ++a) lids[a] = overlapMap_->getLocalElement(dofs[a]);
  ContactPairState state = s.state;
  state.active = s.active || forceActive;
  state.multiplier = ud[lids.back()];
  const int nn = master ? 2 : 1;
  const int nodes[2] = {master ? s.master[0] : s.slaveNode, s.master[1]};
  Eigen::MatrixX2d X(nn, 2), ue(nn, 2);
  for (int i = 0; i < nn; ++i)
    for (int c = 0; c < 2; ++c) {
      X(i, c) = mesh_->coord(nodes[i])[c];
      ue(i, c) = ud[lids[2 * i + c]];
    }
  (master ? masterElement_ : slaveElement_)->computeContact(X, ue, state, what, er);
}

void Model::buildTopology() {
  // Decomposed contact: the master counterpart of a slot lives on the rank
  // of its master segment's element.
  localMasterSlots_.clear();
  if (decomposed_)
    for (size_t k = 0; k < slots_.size(); ++k)
      if (slots_[k].paired() &&
          subdomainRank_[partition_.elementSubdomain[slots_[k].masterElement]] == comm_->getRank())
        localMasterSlots_.push_back(static_cast<int>(k));
  if (decomposed_) {
    // Multiplier DOFs of this rank's counterparts, and the transfers of the
    // contact-state check (assembleFrozenGaps()).
    std::vector<GO> lmOv;
    for (int k : localSlots_) lmOv.push_back(lmDof_[k]);
    for (int k : localMasterSlots_) lmOv.push_back(lmDof_[k]);
    std::sort(lmOv.begin(), lmOv.end());
    lmOv.erase(std::unique(lmOv.begin(), lmOv.end()), lmOv.end());
    lmOverlapMap_ = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                         Teuchos::ArrayView<const GO>(lmOv), 0, comm_));
    lmExporter_ = Teuchos::rcp(new Tpetra::Export<LO, GO, Node>(lmOverlapMap_, multiplierMap_));
    if (lmAllImporter_.is_null())
      lmAllImporter_ = Teuchos::rcp(new Tpetra::Import<LO, GO, Node>(multiplierMap_, multiplierAllMap_));
  }

  const Mesh& mesh = *mesh_;
  const int me = comm_->getRank();
  const GO first = ownedMap_->getMinGlobalIndex();
  const size_t numOwned = ownedMap_->getNodeNumElements();
  std::vector<GO> dofs;

  // Owned graph: rows of owned DOFs with the columns of every element and
  // contact slot touching them (the whole mesh and all pairs are known on
  // every rank, so no communication is needed).
  std::vector<std::vector<GO>> rows(numOwned);
  auto addOwned = [&](const std::vector<GO>& d) {
    for (GO r : d)
      if (r >= first && r < first + static_cast<GO>(numOwned)) {
        auto& row = rows[r - first];
        row.insert(row.end(), d.begin(), d.end());
      }
  };
  for (int e = 0; e < mesh.numElements(); ++e) {
    elementDofs(e, dofs);
    addOwned(dofs);
  }
  for (int k = 0; k < static_cast<int>(slots_.size()); ++k) {
    slotDofs(k, dofs);
    addOwned(dofs);
  }
  Teuchos::Array<size_t> nnz(numOwned);
  for (size_t r = 0; r < numOwned; ++r) {
    std::sort(rows[r].begin(), rows[r].end());
    rows[r].erase(std::unique(rows[r].begin(), rows[r].end()), rows[r].end());
    nnz[r] = rows[r].size();
  }
  auto owned = Teuchos::rcp(new CrsGraph(ownedMap_, nnz()));
  for (size_t r = 0; r < numOwned; ++r) owned->insertGlobalIndices(first + r, Teuchos::ArrayView<const GO>(rows[r]));
  owned->fillComplete(ownedMap_, ownedMap_);
  ownedGraph_ = owned;
  rows.clear();

  // Overlap map: owned DOFs first, then the ghosts of local elements and slots.
  std::vector<GO> ghosts;
  auto addGhosts = [&](const std::vector<GO>& d) {
    for (GO g : d)
      if (g < first || g >= first + static_cast<GO>(numOwned)) ghosts.push_back(g);
  };
  for (int e : localElements_) {
    elementDofs(e, dofs);
    addGhosts(dofs);
  }
  for (int k : localSlots_) {
    decomposed_ && slots_[k].paired() ? slaveSideDofs(k, dofs) : slotDofs(k, dofs);
    addGhosts(dofs);
  }
  for (int k : localMasterSlots_) {
    masterSideDofs(k, dofs);
    addGhosts(dofs);
  }
  std::sort(ghosts.begin(), ghosts.end());
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
  std::vector<GO> gids(numOwned);
  std::iota(gids.begin(), gids.end(), first);
  gids.insert(gids.end(), ghosts.begin(), ghosts.end());
  overlapMap_ = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                     Teuchos::ArrayView<const GO>(gids), 0, comm_));
  importer_ = Teuchos::rcp(new Tpetra::Import<LO, GO, Node>(ownedMap_, overlapMap_));
  exporter_ = Teuchos::rcp(new Tpetra::Export<LO, GO, Node>(overlapMap_, ownedMap_));

  // Overlap graph: entries of local elements and slots only, columns indexed
  // by the overlap map so element DOF lists are local column indices.
  const size_t numOv = overlapMap_->getNodeNumElements();
  std::vector<std::vector<LO>> ovRows(numOv);
  std::vector<LO> l;
  auto addLocal = [&](const std::vector<GO>& d) {
    l.resize(d.size());
    for (size_t i = 0; i < d.size(); ++i) l[i] = overlapMap_->getLocalElement(d[i]);
    for (LO r : l) ovRows[r].insert(ovRows[r].end(), l.begin(), l.end());
  };
  for (int e : localElements_) {
    elementDofs(e, dofs);
    addLocal(dofs);
  }
  for (int k : localSlots_) {
    decomposed_ && slots_[k].paired() ? slaveSideDofs(k, dofs) : slotDofs(k, dofs);
    addLocal(dofs);
  }
  for (int k : localMasterSlots_) {
    masterSideDofs(k, dofs);
    addLocal(dofs);
  }
  Teuchos::Array<size_t> ovnnz(numOv);
  for (size_t r = 0; r < numOv; ++r) {
    std::sort(ovRows[r].begin(), ovRows[r].end());
    ovRows[r].erase(std::unique(ovRows[r].begin(), ovRows[r].end()), ovRows[r].end());
    ovnnz[r] = ovRows[r].size();
  }
  auto ov = Teuchos::rcp(new CrsGraph(overlapMap_, overlapMap_, ovnnz()));
  for (size_t r = 0; r < numOv; ++r) ov->insertLocalIndices(r, Teuchos::ArrayView<const LO>(ovRows[r]));
  ov->fillComplete(ownedMap_, ownedMap_);
  overlapGraph_ = ov;
  ++topologyVersion_;
  (void)me;
}

void Model::assembleTractions() {
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
  for (const auto& t : bcs_.tractions) {
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
  fext_ = createVector();
  fext_->doExport(*fov, *exporter_, Tpetra::ADD);
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
    const auto& src = constraintSource_[first + l];
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
    const auto& src = constraintSource_[first + l];
    if (src.first < 0) continue;
    const auto& bc = bcs_.displacements[src.first];
    const int c = static_cast<int>((first + l) - nodeDof_[src.second]);
    d[l] = bc.prescribed(c, mesh_->coord(src.second), lambda) - bc.prescribed(c, mesh_->coord(src.second), lambda0);
  }
}

AssemblyResult Model::assemble(const Vector& u, double lambda, Vector* fint, Vector* residual, CrsMatrix* K,
                               const Vector* prescribedStep, SubdomainSink* subdomains) const {
  const Mesh& mesh = *mesh_;
  auto uov = toOverlap(u);
  auto ud = uov->getData();
  Teuchos::RCP<Vector> dpov;
  Teuchos::ArrayRCP<const double> dp;
  if (prescribedStep) {
    dpov = toOverlap(*prescribedStep);
    dp = dpov->getData();
  }
  Teuchos::RCP<Vector> fov, rov;
  Teuchos::ArrayRCP<double> fd, rd;
  if (fint) {
    fov = Teuchos::rcp(new Vector(overlapMap_));
    fd = fov->getDataNonConst();
  }
  if (residual) {
    rov = Teuchos::rcp(new Vector(overlapMap_));
    rd = rov->getDataNonConst();
  }
  // The overlap matrix is kept between calls (same graph until the topology
  // changes): refill it instead of allocating its values every iteration.
  CrsMatrix* Kov = nullptr;
  if (K) {
    if (overlapMatrix_.is_null() || overlapMatrix_->getCrsGraph() != overlapGraph_)
      overlapMatrix_ = Teuchos::rcp(new CrsMatrix(overlapGraph_));
    else
      overlapMatrix_->resumeFill();
    Kov = overlapMatrix_.get();
    Kov->setAllToScalar(0.0);
  }
  unsigned what = kEnergy;
  if (fint || residual) what |= kResidual;
  if (K || prescribedStep || subdomains) what |= kTangent;
  if (subdomains)
    for (auto& sys : *subdomains->systems) {
      sys.K->resumeFill();
      sys.K->setAllToScalar(0.0);
    }

  std::vector<LO> lids;
  std::vector<char> con;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Ke;
  // Scatter one element's contribution (DOF lids `lids`) into the overlap
  // structures: prescribed rows/columns dropped, predictor term added.
  auto scatter = [&](ElementResult& er) {
    const int n = static_cast<int>(lids.size());
    con.resize(n);
    for (int a = 0; a < n; ++a) con[a] = constrained_[overlapMap_->getGlobalElement(lids[a])];
    if (fint)
      for (int a = 0; a < n; ++a) fd[lids[a]] += er.residual[a];
    if (residual) {
      if (prescribedStep) {
        Eigen::VectorXd d(n);
        for (int a = 0; a < n; ++a) d[a] = con[a] ? dp[lids[a]] : 0.0;
        er.residual += er.tangent * d;
      }
      for (int a = 0; a < n; ++a)
        if (!con[a]) rd[lids[a]] += er.residual[a];
    }
    if (K) {
      for (int a = 0; a < n; ++a)
        if (con[a]) {
          er.tangent.row(a).setZero();
          er.tangent.col(a).setZero();
        }
      Ke = er.tangent;  // row-major copy: host elements need not be symmetric
      for (int a = 0; a < n; ++a)
        Kov->sumIntoLocalValues(lids[a], Teuchos::ArrayView<const LO>(lids.data(), n),
                                Teuchos::ArrayView<const double>(Ke.data() + a * n, n));
    }
  };

  AssemblyResult result;
  double energy = 0.0;
  int failedElement = -1;
  std::string failure;
  ElementResult er;
  Eigen::MatrixXd X, ue;
  std::vector<GO> dofs;
  std::vector<LO> cols;  // subdomain scatter buffers, reused across elements
  std::vector<double> vals;
  for (int e : localElements_) {
    const int nn = mesh.elementNumNodes(e);
    const int* en = mesh.elementNodes(e);
    const int d = mesh.dim();
    X.resize(nn, d);
    ue.resize(nn, d);
    elementDofs(e, dofs);
    lids.resize(dofs.size());
    for (int i = 0; i < nn; ++i)
      for (int c = 0; c < d; ++c) {
        X(i, c) = mesh.coord(en[i])[c];
        lids[d * i + c] = overlapMap_->getLocalElement(dofs[d * i + c]);
        ue(i, c) = ud[lids[d * i + c]];
      }
    try {
      elements_[mesh.elementBody(e)]->compute(X, ue, what, er);
    } catch (const InadmissibleDeformation& ex) {
      failedElement = e;
      failure = ex.what();
      break;
    }
    energy += er.energy;
    if (subdomains) {
      // Free-DOF block of the element tangent into its subdomain's matrix.
      const auto [sysIndex, pos] = subdomains->where[e];
      auto& sys = (*subdomains->systems)[sysIndex];
      const auto& l = sys.elementLocal[pos];
      for (size_t a = 0; a < l.size(); ++a) {
        if (l[a] < 0) continue;
        cols.clear();
        vals.clear();
        for (size_t b = 0; b < l.size(); ++b)
          if (l[b] >= 0) {
            cols.push_back(l[b]);
            vals.push_back(er.tangent(a, b));
          }
        sys.K->sumIntoLocalValues(l[a], Teuchos::ArrayView<const LO>(cols), Teuchos::ArrayView<const double>(vals));
      }
    }
    scatter(er);
  }
  if (subdomains)
    for (auto& sys : *subdomains->systems) sys.K->fillComplete(sys.K->getDomainMap(), sys.K->getRangeMap());

  // Decomposed contact: each counterpart where it lives (the slave's on the
  // owner of the slave node, the master's on the rank of the master
  // segment's element); they share only the multiplier DOF.
  if (failedElement < 0 && decomposed_) {
    for (int k : localSlots_) {
      if (!slots_[k].paired()) {
        lids.assign(1, overlapMap_->getLocalElement(lmDof_[k]));
        releasedContribution(1, ud[lids[0]], kAll, er);
        scatter(er);
        continue;
      }
      evaluateCounterpart(k, false, ud, false, what | kTangent, er, lids);
      scatter(er);
    }
    for (int k : localMasterSlots_) {
      evaluateCounterpart(k, true, ud, false, what | kTangent, er, lids);
      scatter(er);
    }
  }
  // Contact slots owned here. Unpaired slots carry only Π = ½λ² (λ = 0).
  if (failedElement < 0 && !decomposed_)
    for (int k : localSlots_) {
      const ContactSlot& s = slots_[k];
      slotDofs(k, dofs);
      lids.resize(dofs.size());
      for (size_t a = 0; a < dofs.size(); ++a) lids[a] = overlapMap_->getLocalElement(dofs[a]);
      ContactPairState state = s.state;
      state.active = s.active;
      state.multiplier = ud[lids.back()];
      if (!s.paired()) {
        releasedContribution(1, state.multiplier, kAll, er);
        scatter(er);
        continue;
      }
      const int nodes[3] = {s.slaveNode, s.master[0], s.master[1]};
      X.resize(3, 2);
      ue.resize(3, 2);
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 2; ++c) {
          X(i, c) = mesh.coord(nodes[i])[c];
          ue(i, c) = ud[lids[2 * i + c]];
        }
      ntsElement_->computeContact(X, ue, state, what | kTangent, er);
      scatter(er);
    }

  // Every rank learns whether any element failed, so all take the same path.
  int failedAny = -1;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, failedElement, Teuchos::outArg(failedAny));
  if (failedAny >= 0) {
    DDC_THROW(InadmissibleDeformation, "inadmissible deformation in element " << failedAny << " (body '"
                                           << mesh.body(mesh.elementBody(failedAny)).name << "')"
                                           << (failure.empty() ? "" : ": " + failure));
  }
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, energy, Teuchos::outArg(result.strainEnergy));

  const GO first = ownedMap_->getMinGlobalIndex();
  const size_t numOwned = ownedMap_->getNodeNumElements();
  if (fint) {
    fd = Teuchos::null;
    fint->putScalar(0.0);
    fint->doExport(*fov, *exporter_, Tpetra::ADD);
  }
  if (residual) {
    rd = Teuchos::null;
    residual->putScalar(0.0);
    residual->doExport(*rov, *exporter_, Tpetra::ADD);
    auto r = residual->getDataNonConst();
    auto f = fext_->getData();
    for (size_t l = 0; l < numOwned; ++l)
      if (!constrained_[first + l]) r[l] -= lambda * f[l];
  }
  if (K) {
    Kov->fillComplete(ownedMap_, ownedMap_);
    K->resumeFill();
    K->setAllToScalar(0.0);
    K->doExport(*Kov, *exporter_, Tpetra::ADD);
    for (size_t l = 0; l < numOwned; ++l) {
      const GO g = first + l;
      if (constrained_[g]) K->replaceGlobalValues(g, Teuchos::tuple<GO>(g), Teuchos::tuple<double>(1.0));
    }
    K->fillComplete(ownedMap_, ownedMap_);
  }
  return result;
}

// ---- contact -------------------------------------------------------------------

void Model::gatherSurface(const Vector& u, std::vector<double>& values) const {
  Vector s(surfaceMap_);
  s.doImport(u, *surfaceImporter_, Tpetra::INSERT);
  ++exchanges_;
  bytesExchanged_ += bytesPerExchange_;
  auto d = s.getData();
  values.assign(d.begin(), d.end());
}

Eigen::Vector2d Model::currentPosition(int node, const std::vector<double>& v) const {
  const int i = surfaceIndex_[node];
  DDC_ASSERT(i >= 0, "node " << node << " is not on a contact surface");
  return {mesh_->coord(node)[0] + v[2 * i], mesh_->coord(node)[1] + v[2 * i + 1]};
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

void Model::distributedSearch(const Vector& u, std::vector<std::vector<ContactCandidate>>& cands,
                              std::vector<std::vector<char>>& pastFreeEnd) {
  const MPI_Comm mpi = rawComm(comm_);
  const int me = comm_->getRank(), P = comm_->getSize();
  auto ud = u.getData();
  auto ownedPosition = [&](int n) {
    const LO l = ownedMap_->getLocalElement(dof(n, 0));
    return Eigen::Vector2d(mesh_->coord(n)[0] + ud[l], mesh_->coord(n)[1] + ud[l + 1]);
  };
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
    if (nodeOwner_[n] != me) continue;
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
  for (size_t p = 0; p < pairRules_.size(); ++p)  // slave-surface neighbours owned here
    for (const auto& sg : pairRules_[p].slaveSegments)
      for (int n : sg)
        if (nodeOwner_[n] == me && !known.count(n)) known[n] = ownedPosition(n);
  // 3. Per pair: the global search for this rank's slaves over the master
  //    segments whose nodes arrived (kept in their global order, so ties
  //    break as in the replicated search).
  std::vector<std::vector<SlotPairing>> results(P);
  long queries = 0;
  for (size_t p = 0; p < searches_.size(); ++p) {
    const MasterSurface& whole = searches_[p]->master();
    std::vector<int> localSlaves, localSlotIds;
    for (int k : pairSlots_[p])
      if (slotOwner(k) == me) localSlaves.push_back(slots_[k].slaveNode), localSlotIds.push_back(k);
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
      rule.slaveSegments = pairRules_[p].slaveSegments;
      for (int g : globalIndex) rule.masterDepths.push_back(pairRules_[p].masterDepths[g]);
      ContactSearch search(MasterSurface(segs), localSlaves, searches_[p]->searchRadius(), std::move(rule));
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
  cands.assign(searches_.size(), {});
  pastFreeEnd.assign(searches_.size(), {});
  std::vector<int> indexInPair(slots_.size(), -1);
  for (size_t p = 0; p < searches_.size(); ++p) {
    cands[p].assign(pairSlots_[p].size(), ContactCandidate{});
    pastFreeEnd[p].assign(pairSlots_[p].size(), 0);
    for (size_t i = 0; i < pairSlots_[p].size(); ++i) indexInPair[pairSlots_[p][i]] = int(i);
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

bool Model::updatePairing(const Vector& u, bool global, bool freeze, std::vector<int>* changedSlots) {
  if (!hasContact()) return false;  // no surface maps exist
  // Decomposed contact pairs at step ends only (global search): the
  // geometry goes only where bounding boxes say it is needed. Conventional
  // NTS (the monolithic reference) tracks the pairing inside Newton on
  // replicated surface positions.
  const bool distributed = decomposed_ && global;
  std::vector<double> v;
  std::vector<std::vector<ContactCandidate>> found;
  std::vector<std::vector<char>> pastEnd;
  if (distributed) {
    distributedSearch(u, found, pastEnd);
  } else {
    gatherSurface(u, v);
    for (size_t p = 0; p < searches_.size(); ++p) {
      ContactSearch& search = *searches_[p];
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
  for (size_t p = 0; p < searches_.size(); ++p) {
    const ContactSearch& search = *searches_[p];
    const auto& cands = found[p];
    for (size_t i = 0; i < cands.size(); ++i) {
      ContactSlot& s = slots_[pairSlots_[p][i]];
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
        if (changedSlots) changedSlots->push_back(pairSlots_[p][i]);
      }
      s.master[0] = m0;
      s.master[1] = m1;
      s.segment = m0 >= 0 ? c.segment : -1;
      s.masterElement = m0 >= 0 ? pairMasterElements_[p][c.segment] : -1;
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
  if (changed && ownedGraph_.get()) buildTopology();
  return changed;
}

void Model::checkInitialPenetration() const {
  // doc/contact.md "Which slave nodes pair": a slave node inside the master
  // body that the search does not pair keeps λ = 0 for ever, so the bodies
  // would silently stay overlapped there. Reference configuration,
  // replicated mesh and slots: every rank reaches the same verdict.
  const Mesh& mesh = *mesh_;
  for (size_t p = 0; p < pairSlots_.size(); ++p) {
    const auto& def = contact_.pairs[p];
    std::unique_ptr<BodyLocator> locator;
    int first = -1, count = 0, element = -1;
    for (int k : pairSlots_[p]) {
      if (slots_[k].paired()) continue;
      if (!locator) {
        const std::string body = def.masterSet.substr(0, def.masterSet.find('/'));
        locator = std::make_unique<BodyLocator>(mesh, mesh.bodyIndex(body));
      }
      const auto& X = mesh.coord(slots_[k].slaveNode);
      const int e = locator->elementContaining(Eigen::Vector2d(X[0], X[1]));
      if (e < 0) continue;
      if (first < 0) first = k, element = e;
      ++count;
    }
    if (first < 0) continue;
    // Why the first such node is not paired: the pair's search (same radius,
    // same facing rule) on that node alone.
    const ContactSearch& whole = *searches_[p];
    const int node = slots_[first].slaveNode;
    auto reference = [&](int n) { return Eigen::Vector2d(mesh.coord(n)[0], mesh.coord(n)[1]); };
    ContactSearch probe(whole.master(), {node}, whole.searchRadius(), pairRules_[p]);
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
          << kFacingDepthFraction << " x " << pairRules_[p].masterDepths[seg] << ")";
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
    DDC_THROW(InputError, "contact pair 'Contact/Pairs/"
                              << def.name << "': slave node " << node << " at (" << xs.x() << ", " << xs.y()
                              << ") of the slave side set '" << def.slaveSet << "' starts inside the master body (element "
                              << element << "), at depth " << depth << " below the master side set '" << def.masterSet
                              << "', and contact cannot push it out: " << why.str()
                              << " (doc/contact.md, 'Which slave nodes pair')"
                              << (count > 1 ? "; " + std::to_string(count - 1) + " more slave node(s) of this pair likewise"
                                            : std::string())
                              << ". Move the bodies apart so that they at most touch, or overlap by less than half an "
                                 "element, in the reference configuration");
  }
}

std::vector<std::vector<ConstraintEntry>> Model::contactRowEntries(const std::vector<SubdomainSystem>& systems) const {
  std::vector<std::vector<ConstraintEntry>> out(systems.size());
  auto localIndex = [&](const SubdomainSystem& sys, GO g) {
    const auto it = std::lower_bound(sys.dofs.begin(), sys.dofs.end(), g);
    return it != sys.dofs.end() && *it == g ? int(it - sys.dofs.begin()) : -1;
  };
  // Zero state: the coefficients do not depend on it (frozen geometry).
  Vector zero(overlapMap_);
  auto ud = zero.getData();
  ElementResult er;
  std::vector<LO> lids;
  std::vector<GO> dofs;
  auto add = [&](size_t sys, int k, bool master) {
    evaluateCounterpart(k, master, ud, true, kTangent, er, lids);
    master ? masterSideDofs(k, dofs) : slaveSideDofs(k, dofs);
    const int row = int(dofs.size()) - 1;
    for (int a = 0; a < row; ++a) {
      const int l = localIndex(systems[sys], dofs[a]);
      if (l >= 0 && er.tangent(row, a) != 0.0) out[sys].push_back({lmDof_[k], LO(l), er.tangent(row, a)});
    }
  };
  for (int k : localSlots_) {
    if (!slots_[k].paired()) continue;
    // The first (lowest-id) local subdomain having the slave node.
    for (size_t i = 0; i < systems.size(); ++i)
      if (localIndex(systems[i], dof(slots_[k].slaveNode, 0)) >= 0 ||
          localIndex(systems[i], dof(slots_[k].slaveNode, 1)) >= 0) {
        add(i, k, false);
        break;
      }
  }
  for (int k : localMasterSlots_) {
    const int sub = partition_.elementSubdomain[slots_[k].masterElement];
    for (size_t i = 0; i < systems.size(); ++i)
      if (systems[i].id == sub) add(i, k, true);
  }
  return out;
}

std::array<long, 3> Model::searchCounters() const {
  std::array<long, 3> c{0, 0, distributedQueries_};
  for (const auto& s : searches_) {
    c[0] += s->counters().trackingCalls;
    c[1] += s->counters().trackingFallbacks;
    c[2] += s->counters().globalSearches;
  }
  return c;
}

bool Model::fullyPrescribed(int k) const {
  const ContactSlot& s = slots_[k];
  if (!s.paired()) return false;
  for (int n : {s.slaveNode, s.master[0], s.master[1]})
    for (int c = 0; c < 2; ++c)
      if (!constrained_[dof(n, c)]) return false;
  return true;
}

void Model::activateAllPaired() {
  // A pair whose DOFs are all prescribed has a prescribed gap: its
  // constraint row would be empty (a singular system), so it never becomes
  // active (updateActiveSet() reports it if it penetrates).
  for (size_t k = 0; k < slots_.size(); ++k) slots_[k].active = slots_[k].paired() && !fullyPrescribed(int(k));
}

void Model::refreshSlotGeometry(const std::vector<double>& v) {
  const size_t base = 2 * surfaceNodes_.size();
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

void Model::assembleFrozenGaps(const Vector& u) {
  // Partial gaps of the counterparts at the multiplier DOFs, summed on the
  // multiplier map (Export ADD), then (g_N, λ) of every slot to every rank.
  Vector ov(overlapMap_);
  {
    auto uov = toOverlap(u);
    auto ud = uov->getData();
    auto g = ov.getDataNonConst();
    ElementResult er;
    std::vector<LO> lids;
    for (int k : localSlots_)
      if (slots_[k].paired()) {
        evaluateCounterpart(k, false, ud, true, kResidual, er, lids);
        g[lids.back()] += er.residual[er.residual.size() - 1];
      }
    for (int k : localMasterSlots_) {
      evaluateCounterpart(k, true, ud, true, kResidual, er, lids);
      g[lids.back()] += er.residual[er.residual.size() - 1];
    }
  }
  // Only the multiplier entries travel: Export from the overlap multiplier
  // DOFs to their owners.
  Vector gOv(lmOverlapMap_), gOwned(multiplierMap_);
  {
    auto src = ov.getData();
    auto dst = gOv.getDataNonConst();
    for (size_t i = 0; i < lmOverlapMap_->getNodeNumElements(); ++i)
      dst[i] = src[overlapMap_->getLocalElement(lmOverlapMap_->getGlobalElement(LO(i)))];
  }
  gOwned.doExport(gOv, *lmExporter_, Tpetra::ADD);
  MultiVector owned(multiplierMap_, 2), all(multiplierAllMap_, 2);
  {
    auto g = gOwned.getData();
    auto ud = u.getData();
    for (size_t i = 0; i < localSlots_.size(); ++i) {
      owned.replaceLocalValue(LO(i), 0, g[i]);
      owned.replaceLocalValue(LO(i), 1, ud[ownedMap_->getLocalElement(lmDof_[localSlots_[i]])]);
    }
  }
  all.doImport(owned, *lmAllImporter_, Tpetra::INSERT);
  auto g = all.getData(0), lam = all.getData(1);
  for (size_t k = 0; k < slots_.size(); ++k) {
    ContactSlot& s = slots_[k];
    const LO l = multiplierAllMap_->getLocalElement(lmDof_[k]);
    s.state.multiplier = lam[l];
    if (!s.paired()) continue;
    s.normal = s.state.frozenNormal;
    s.gap = g[l];
  }
}

std::vector<int> Model::updateActiveSet(const Vector& u) {
  if (!hasContact()) return {};  // no surface or multiplier maps exist
  if (decomposed_) {
    assembleFrozenGaps(u);
  } else {
    std::vector<double> v;
    gatherSurface(u, v);
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
    } else if (!s.active && s.gap < -contact_.penetrationTolerance && fullyPrescribed(int(k))) {
      DDC_THROW(InputError, describeSlot(int(k))
                                << ": the slave node and its master segment have all their displacements "
                                   "prescribed (Boundary Conditions), so contact cannot remove their penetration "
                                   "(gap "
                                << s.gap << "); free the contact surfaces or change the prescribed values");
    } else if (!s.active && s.gap < -contact_.penetrationTolerance) {
      s.active = true;
      changed.push_back(static_cast<int>(k));
    }
  }
  return changed;
}

ContactSummary Model::contactSummary() const {
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

void Model::restoreContactState(const std::vector<ContactSlot>& saved) {
  bool changed = false;
  for (size_t k = 0; k < slots_.size(); ++k)
    if (saved[k].master[0] != slots_[k].master[0] || saved[k].master[1] != slots_[k].master[1]) changed = true;
  slots_ = saved;
  if (changed) buildTopology();
}

std::string Model::describeSlot(int k) const {
  const ContactSlot& s = slots_[k];
  std::ostringstream os;
  const auto& X = mesh_->coord(s.slaveNode);
  os << "pair '" << contact_.pairs[s.pair].name << "' slave node " << s.slaveNode << " at (" << X[0] << ", " << X[1]
     << ")";
  return os.str();
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

  std::ostringstream os;
  // The mesh and the DOF numbering are replicated: every rank names the same place.
  for (size_t k = 0; k < lmDof_.size(); ++k)
    if (lmDof_[k] == at) {
      os << (bad == at ? what + " at the contact multiplier of " : what + ", at the contact multiplier of ")
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
  os << what << (bad == at ? " at " : ", at ") << "u_" << "xyz"[component] << " of node " << node << " ("
     << mesh_->coordText(node) << ")";
  for (int e = 0; e < mesh_->numElements(); ++e) {
    const int* nodes = mesh_->elementNodes(e);
    if (std::find(nodes, nodes + mesh_->elementNumNodes(e), node) == nodes + mesh_->elementNumNodes(e)) continue;
    const int b = mesh_->elementBody(e);
    os << ", in element " << e << " of body '" << mesh_->body(b).name << "'";
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

}  // namespace ddc
