// The evaluation side of the pairing part of the contact component (see
// DDC_ContactPairing.hpp): the maps of the counterparts this rank evaluates,
// the active set with its gaps, the constraint rows and the element
// contributions.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "DDC_NodeToSurface.hpp"
#include "DDC_ShapeFunctions.hpp"

#include "DDC_ContactPairing.hpp"
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

}  // namespace

/// Field values at this rank's counterpart DOFs (dof; dof0 at the step
/// start, frictional pairs) and multipliers (lm).
struct ContactPairing::Field {
  Teuchos::RCP<Vector> dof, dof0, lm;
  Teuchos::ArrayRCP<const double> d, d0, l;
  const ContactPairing* c = nullptr;
  double at(GO g) const { return d[c->dofOverlapMap_->getLocalElement(g)]; }
  /// The step-start value (0 before the first beginStep()).
  double atStart(GO g) const { return d0.size() ? d0[c->dofOverlapMap_->getLocalElement(g)] : 0.0; }
  double multiplier(int k, int m = 0) const {
    return l[c->lmOverlapMap_->getLocalElement(c->topo_.multiplierId(k, m))];
  }
};

/// What an element of a slot reads (ContactPairing::evaluateAt()): the
/// displacements of its nodes now and at the step start (node order of
/// elementNodes(), dim columns) and the slot's multipliers.
struct ContactPairing::SlotValues {
  Eigen::MatrixXd u, u0;
  std::array<double, 3> lambda{{0.0, 0.0, 0.0}};
};

void ContactPairing::requirePaired(const char* what) const {
  if (!pairedOnce_)
    throw std::logic_error(std::string("ContactComponent::") + what +
                           ": no pairing yet, so no slave node is paired and there is nothing to evaluate; call "
                           "updatePairing(u, /*global=*/true, /*freeze=*/true) once after setDofs()");
}

void ContactPairing::appendMultipliers(int k, std::vector<GO>& dofs) const {
  for (int c = 0; c < topo_.numMultipliers(k); ++c) dofs.push_back(topo_.multiplierId(k, c));
}

std::vector<GO> ContactPairing::slotDofs(int k) const {
  const ContactSlot& s = slots_[k];
  std::vector<GO> dofs;
  if (s.paired()) {
    topo_.appendNodeDofs(s.slaveNode, dofs);
    for (int a = 0; a < s.numMaster; ++a) topo_.appendNodeDofs(s.master[a], dofs);
  }
  appendMultipliers(k, dofs);
  return dofs;
}

std::vector<GO> ContactPairing::slaveSideDofs(int k) const {
  std::vector<GO> dofs;
  topo_.appendNodeDofs(slots_[k].slaveNode, dofs);
  appendMultipliers(k, dofs);
  return dofs;
}

std::vector<GO> ContactPairing::masterSideDofs(int k) const {
  std::vector<GO> dofs;
  for (int a = 0; a < slots_[k].numMaster; ++a) topo_.appendNodeDofs(slots_[k].master[a], dofs);
  appendMultipliers(k, dofs);
  return dofs;
}

void ContactPairing::buildEvaluationMaps() {
  const int me = topo_.comm()->getRank();
  const bool decomposed = topo_.options().decomposed;
  // Decomposed: the master counterpart of a slot lives on the rank that
  // registered its master facet.
  localMasterSlots_.clear();
  if (decomposed)
    for (size_t k = 0; k < slots_.size(); ++k)
      if (slots_[k].paired() && topo_.pair(slots_[k].pair).masterFacets[slots_[k].segment].rank == me)
        localMasterSlots_.push_back(static_cast<int>(k));
  // Host DOFs and multipliers this rank's evaluations read.
  std::vector<GO> dofs, lms;
  auto add = [&](int k, const std::vector<GO>& d) {
    const int nm = topo_.numMultipliers(k);
    dofs.insert(dofs.end(), d.begin(), d.end() - nm);
    lms.insert(lms.end(), d.end() - nm, d.end());
  };
  for (int k : topo_.ownedSlots()) add(k, decomposed && slots_[k].paired() ? slaveSideDofs(k) : slotDofs(k));
  for (int k : localMasterSlots_) add(k, masterSideDofs(k));
  for (auto* v : {&dofs, &lms}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  const auto& comm = topo_.comm();
  dofOverlapMap_ = mapOf(dofs, comm);
  dofImporter_ = Teuchos::rcp(new TpetraImport(topo_.hostMap(), dofOverlapMap_));
  lmOverlapMap_ = mapOf(lms, comm);
  lmImporter_ = Teuchos::rcp(new TpetraImport(topo_.multiplierMap(), lmOverlapMap_));
  lmExporter_ = Teuchos::rcp(new TpetraExport(lmOverlapMap_, topo_.multiplierMap()));
  lmHostImporter_ =
      topo_.multipliersInHost() ? Teuchos::rcp(new TpetraImport(topo_.hostMap(), lmOverlapMap_)) : Teuchos::null;
}

ContactPairing::Field ContactPairing::gatherField(const Vector& u, const Vector* multipliers) const {
  Field f;
  f.c = this;
  f.dof = Teuchos::rcp(new Vector(dofOverlapMap_));
  f.dof->doImport(u, *dofImporter_, Tpetra::INSERT);
  f.lm = Teuchos::rcp(new Vector(lmOverlapMap_));
  if (multipliers) {
    f.lm->doImport(*multipliers, *lmImporter_, Tpetra::INSERT);
  } else {
    topo_.requireHostMultipliers();
    f.lm->doImport(u, *lmHostImporter_, Tpetra::INSERT);
  }
  if (stepStart_ != Teuchos::null) {
    f.dof0 = Teuchos::rcp(new Vector(dofOverlapMap_));
    f.dof0->doImport(*stepStart_, *dofImporter_, Tpetra::INSERT);
    f.d0 = f.dof0->getData();
  }
  f.d = f.dof->getData();
  f.l = f.lm->getData();
  return f;
}

std::vector<int> ContactPairing::elementNodes(int k, SurfaceContactRole role) const {
  const ContactSlot& s = slots_[k];
  std::vector<int> nodes;
  if (role != SurfaceContactRole::Master) nodes.push_back(s.slaveNode);
  if (role != SurfaceContactRole::Slave) nodes.insert(nodes.end(), s.master.begin(), s.master.begin() + s.numMaster);
  return nodes;
}

void ContactPairing::evaluate(int k, SurfaceContactRole role, const Field& f, bool forceActive, unsigned what,
                              ElementResult& er, std::vector<GO>& dofs, bool forceStick) const {
  // The slave counterpart on [u_s, λ], the master counterpart on
  // [u_1..u_m, λ], the conventional element on [u_s, u_1..u_m, λ].
  const int dim = topo_.dim();
  dofs = role == SurfaceContactRole::Slave ? slaveSideDofs(k) : role == SurfaceContactRole::Master ? masterSideDofs(k)
                                                                                                    : slotDofs(k);
  const int nn = int(elementNodes(k, role).size());
  SlotValues v;
  v.u.resize(nn, dim);
  v.u0.resize(nn, dim);
  for (int i = 0; i < nn; ++i)
    for (int c = 0; c < dim; ++c) v.u(i, c) = f.at(dofs[dim * i + c]), v.u0(i, c) = f.atStart(dofs[dim * i + c]);
  for (int m = 0; m < topo_.numMultipliers(k); ++m) v.lambda[m] = f.multiplier(k, m);
  evaluateAt(k, role, v, forceActive, what, er, dofs, forceStick);
}

void ContactPairing::evaluateAt(int k, SurfaceContactRole role, const SlotValues& v, bool forceActive, unsigned what,
                                ElementResult& er, const std::vector<GO>& dofs, bool forceStick) const {
  const int dim = topo_.dim();
  const ContactSlot& s = slots_[k];
  ContactPairState state = s.state;
  state.active = s.active || forceActive;
  state.multiplier = v.lambda[0];
  const std::vector<int> nodes = elementNodes(k, role);
  const int nn = int(nodes.size());
  Eigen::MatrixXd X(nn, dim);
  for (int i = 0; i < nn; ++i) X.row(i) = topo_.referencePosition(nodes[i]).head(dim).transpose();
  const Pair& pair = topo_.pair(s.pair);
  if (pair.friction > 0.0) {
    FrictionPairState& fr = state.friction;
    fr.coefficient = pair.friction;
    fr.stiffness = pair.frictionStiffness;
    fr.stick = forceStick || s.friction != FrictionState::Slip;
    for (int c = 1; c < dim; ++c) fr.tangential[c - 1] = v.lambda[c];
    fr.slip = s.tangentialSlip;
    fr.stepStart = v.u0;
  }
  topo_.surfaceElement(role, pair.masterType).computeSurfaceContact(X, v.u, s.frozen, state, what, er);
  if (state.friction.frictional() && state.active) restrainHeldSlip(k, role, dofs, state, er);
}

void ContactPairing::restrainHeldSlip(int k, SurfaceContactRole role, const std::vector<GO>& dofs,
                                      const ContactPairState& state, ElementResult& er) const {
  // A tangential row whose every displacement coefficient sits on a
  // prescribed DOF (a slave node and its master point both on supports
  // along the surface), or whose free coefficients repeat the gap row's and
  // the other tangential row's (the two on a symmetry plane, once the
  // master surface tilts across it: slipRowRedundant()), holds nothing and
  // would make the system singular, like the gap row of a fully prescribed
  // pair: its multiplier is restrained to zero (the supports take the
  // tangential force). The conventional element sees all its coefficients;
  // the decomposed counterparts decide from the frozen rows, replicated on
  // every rank.
  const ContactSlot& s = slots_[k];
  const int dim = topo_.dim(), nm = dim, n = int(dofs.size()), nd = n - nm;
  std::vector<int> nodes;
  if (role != SurfaceContactRole::Master) nodes.push_back(s.slaveNode);
  if (role != SurfaceContactRole::Slave) nodes.insert(nodes.end(), s.master.begin(), s.master.begin() + s.numMaster);
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> sizes;
  if (role == SurfaceContactRole::Conventional) {
    if (er.tangent.rows() != n) return;  // no coefficients to judge by (the element always has them in assemble())
    for (int m = 0; m < nm; ++m) {  // the multipliers' columns of the displacement rows, on free DOFs
      Eigen::VectorXd v = er.tangent.block(0, nd + m, nd, 1);
      sizes.push_back(v.norm());
      for (int a = 0; a < nd; ++a)
        if (topo_.componentPrescribed(nodes[a / dim], a % dim)) v[a] = 0.0;
      rows.push_back(v);
    }
  }
  for (int al = 0; al + 1 < dim; ++al) {
    const bool held = role == SurfaceContactRole::Conventional ? slipRowRedundant(rows, sizes, al, kHeldSlipRow)
                                                               : frozenSlipHeld(k, al);
    if (!held) continue;
    const int row = nd + 1 + al;
    const bool carries = role != SurfaceContactRole::Master;  // the slave / conventional holds the multiplier row
    if (er.residual.size() == n) er.residual[row] = carries ? state.friction.tangential[al] : 0.0;
    if (er.tangent.rows() == n) {
      er.tangent.row(row).setZero();
      if (carries) er.tangent(row, row) = 1.0;
    }
  }
}

bool ContactPairing::frozenSlipHeld(int k, int alpha) const {
  // The frozen rows n^p·(x_s − Σ N_i x_i) and τ^p_α·(x_s − Σ N_i x_i) on
  // the free DOFs (slipRowRedundant()).
  const ContactSlot& s = slots_[k];
  const int dim = topo_.dim(), nn = 1 + s.numMaster;
  std::vector<double> N(s.numMaster);
  shapeFunctionsT<double>(topo_.pair(s.pair).masterType, s.frozen.xi.data(), N.data(), nullptr);
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> sizes;
  for (int m = 0; m < dim; ++m) {
    const Eigen::Vector3d& d = m == 0 ? s.frozen.normal : s.frozen.tangent[m - 1];
    Eigen::VectorXd v = Eigen::VectorXd::Zero(nn * dim);
    double size2 = 0.0;
    for (int i = 0; i < nn; ++i) {
      const int node = i == 0 ? s.slaveNode : s.master[i - 1];
      for (int c = 0; c < dim; ++c) {
        const double a = (i == 0 ? 1.0 : -N[i - 1]) * d[c];
        size2 += a * a;
        if (!topo_.componentPrescribed(node, c)) v[i * dim + c] = a;
      }
    }
    rows.push_back(v);
    sizes.push_back(std::sqrt(size2));
  }
  return slipRowRedundant(rows, sizes, alpha, kHeldSlipRow);
}

void ContactPairing::assemble(const Vector& u, const Vector* multipliers, unsigned what,
                              const std::function<void(const std::vector<GO>&, ElementResult&)>& add) const {
  topo_.requireCommitted("assemble");
  requirePaired("assemble");
  const Field f = gatherField(u, multipliers);
  ElementResult er;
  std::vector<GO> dofs;
  // The conventional element of each owned slot, or the decomposed
  // counterparts where they live (the slave's on the owner of the slave node,
  // the master's on the rank of the master facet); they share only the
  // multiplier. Unpaired slots carry only Π = ½λ² (λ = 0).
  const SurfaceContactRole role =
      topo_.options().decomposed ? SurfaceContactRole::Slave : SurfaceContactRole::Conventional;
  for (int k : topo_.ownedSlots()) {
    if (slots_[k].paired()) {
      evaluate(k, role, f, false, what | kTangent, er, dofs);
    } else {
      dofs.clear();
      appendMultipliers(k, dofs);
      const int nm = int(dofs.size());
      double lambda[3] = {0.0, 0.0, 0.0};
      for (int c = 0; c < nm; ++c) lambda[c] = f.multiplier(k, c);
      releasedContribution(nm, lambda, nm, kAll, er);
    }
    add(dofs, er);
  }
  for (int k : localMasterSlots_) {
    evaluate(k, SurfaceContactRole::Master, f, false, what | kTangent, er, dofs);
    add(dofs, er);
  }
}

std::vector<ContactRowEntry> ContactPairing::contactRows() const {
  topo_.requireCommitted("contactRows");
  requirePaired("contactRows");
  std::vector<ContactRowEntry> out;
  if (!topo_.options().decomposed) return out;
  // Zero state: the coefficients do not depend on it (frozen geometry).
  Field f;
  f.c = this;
  f.dof = Teuchos::rcp(new Vector(dofOverlapMap_));
  f.lm = Teuchos::rcp(new Vector(lmOverlapMap_));
  f.d = f.dof->getData();
  f.l = f.lm->getData();
  ElementResult er;
  std::vector<GO> dofs;
  // Every multiplier's row: the gap's, and a frictional pair's slip rows
  // as they are in stick (the rows of the constraint operator).
  auto add = [&](int k, SurfaceContactRole role) {
    evaluate(k, role, f, true, kTangent, er, dofs, /*forceStick=*/true);
    const int nm = topo_.numMultipliers(k), first = int(dofs.size()) - nm;
    const int sub = role == SurfaceContactRole::Master
                        ? topo_.pair(slots_[k].pair).masterFacets[slots_[k].segment].subdomain
                        : -1;
    for (int c = 0; c < nm; ++c)
      for (int a = 0; a < first; ++a)
        if (er.tangent(first + c, a) != 0.0)
          out.push_back({k, topo_.multiplierId(k, c), dofs[a], er.tangent(first + c, a), role, sub});
  };
  for (int k : topo_.ownedSlots())
    if (slots_[k].paired()) add(k, SurfaceContactRole::Slave);
  for (int k : localMasterSlots_) add(k, SurfaceContactRole::Master);
  return out;
}

// ---- the active set ------------------------------------------------------------------

void ContactPairing::gatherSurface(const Vector& u, const Vector* multipliers, std::vector<double>& values) const {
  // Surface DOFs, then every slot's multiplier: one exchange.
  DDC_CHECK(!topo_.options().decomposed, "gatherSurface: the conventional element's gather");
  Vector s(topo_.surfaceMap());
  s.doImport(u, *topo_.surfaceImporter(), Tpetra::INSERT);
  const Map& allMap = *topo_.multiplierAllMap();
  Vector lm(topo_.multiplierAllMap());
  if (multipliers) {
    lm.doImport(*multipliers, *topo_.multiplierAllImporter(), Tpetra::INSERT);
  } else {
    topo_.requireHostMultipliers();
    Vector owned(topo_.multiplierMap());
    auto ud = u.getData();
    const Map& ownedMap = *topo_.multiplierMap();
    for (size_t i = 0; i < ownedMap.getNodeNumElements(); ++i)
      owned.replaceLocalValue(LO(i), ud[topo_.hostMap()->getLocalElement(ownedMap.getGlobalElement(LO(i)))]);
    lm.doImport(owned, *topo_.multiplierAllImporter(), Tpetra::INSERT);
  }
  ++exchanges_;
  bytesExchanged_ += topo_.bytesPerExchange();
  auto d = s.getData();
  values.assign(d.begin(), d.end());
  auto l = lm.getData();
  for (size_t k = 0; k < slots_.size(); ++k)
    for (int c = 0; c < topo_.numMultipliers(int(k)); ++c)
      values.push_back(l[allMap.getLocalElement(topo_.multiplierId(int(k), c))]);
}

void ContactPairing::refreshSlotGeometry(const std::vector<double>& v) {
  const size_t base = size_t(topo_.dim()) * topo_.surfaceNodes().size();
  const Position position = [&](int n) { return currentPosition(n, v); };
  size_t at = base;
  for (size_t k = 0; k < slots_.size(); ++k) {
    ContactSlot& s = slots_[k];
    const int nm = topo_.numMultipliers(int(k));
    s.state.multiplier = v[at];
    for (int c = 1; c < nm; ++c) s.tangential[c - 1] = v[at + c];
    at += size_t(nm);
    if (!s.paired()) continue;
    const Pair& pair = topo_.pair(s.pair);
    // The conventional element's own projection (DDC_NodeToSurface.hpp).
    const FacetProjection pr = projectOntoFacet(pair.masterType, facetPositions(pair, s.segment, position),
                                                position(s.slaveNode).head(topo_.dim()));
    s.normal = pr.normal;
    s.gap = pr.gap;
    if (nm > 1) {
      refreshSlip(s, pr.xi, position);
      s.slaveTangentialForce = consistentTangentialForce(int(k), v, at - size_t(nm));
      s.hasSlaveTangentialForce = true;
    }
  }
}

Eigen::Vector3d ContactPairing::consistentTangentialForce(int k, const std::vector<double>& v, size_t lambdaAt) const {
  // The slave feels −(its rows of the residual), λ_n n + λ_t·∂u_t/∂x_s
  // (∂g_N/∂x_s = n at the closest point): its tangential part holds the
  // derivative of the basis and of the projection along the slip, which
  // λ_t τ leaves out, so that the slave forces sum to the load the surface
  // transmits (doc/contact.md, "Friction").
  const ContactSlot& s = slots_[k];
  const int dim = topo_.dim(), nm = topo_.numMultipliers(k);
  SlotValues values;
  for (int m = 0; m < nm; ++m) values.lambda[m] = v[lambdaAt + size_t(m)];
  if (values.lambda[0] == 0.0 && values.lambda[1] == 0.0 && values.lambda[2] == 0.0) return Eigen::Vector3d::Zero();
  const std::vector<int> nodes = elementNodes(k, SurfaceContactRole::Conventional);
  const int nn = int(nodes.size());
  values.u.resize(nn, dim);
  values.u0 = Eigen::MatrixXd::Zero(nn, dim);
  for (int i = 0; i < nn; ++i) {
    const Eigen::Vector3d X = topo_.referencePosition(nodes[i]);
    values.u.row(i) = (currentPosition(nodes[i], v) - X).head(dim).transpose();
    if (!stepStartSurface_.empty()) values.u0.row(i) = (currentPosition(nodes[i], stepStartSurface_) - X).head(dim).transpose();
  }
  ElementResult er;
  evaluateAt(k, SurfaceContactRole::Conventional, values, true, kResidual, er, slotDofs(k));
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  for (int c = 0; c < dim; ++c) f[c] = -er.residual[c] + values.lambda[0] * s.normal[c];
  return f;
}

void ContactPairing::refreshSlip(ContactSlot& s, const std::array<double, 2>& xi, const Position& position) const {
  // u_t of the conventional element at its projection, from the surface's
  // step-start positions (beginStep()).
  const Pair& pair = topo_.pair(s.pair);
  const int dim = topo_.dim();
  const Position start = [&](int n) {
    return stepStartSurface_.empty() ? topo_.referencePosition(n) : currentPosition(n, stepStartSurface_);
  };
  Eigen::MatrixXd x(1 + s.numMaster, dim), x0(1 + s.numMaster, dim);
  x.row(0) = position(s.slaveNode).head(dim).transpose();
  x0.row(0) = start(s.slaveNode).head(dim).transpose();
  for (int a = 0; a < s.numMaster; ++a) {
    x.row(1 + a) = position(s.master[a]).head(dim).transpose();
    x0.row(1 + a) = start(s.master[a]).head(dim).transpose();
  }
  s.tangentialSlip = conventionalSlip(pair.masterType, x, x0, xi, &s.tangent);
}

template <class At>
void ContactPairing::takeFrozenValues(int k, const double* g, const double* lam, const At& at) {
  ContactSlot& s = slots_[k];
  const int nm = topo_.numMultipliers(k);
  s.state.multiplier = lam[at(topo_.multiplierId(k, 0))];
  for (int c = 1; c < nm; ++c) s.tangential[c - 1] = lam[at(topo_.multiplierId(k, c))];
  if (!s.paired()) return;
  s.normal = s.frozen.normal;
  s.gap = g[at(topo_.multiplierId(k, 0))];
  if (nm > 1) {
    // A held slip row's residual is its multiplier (restrainHeldSlip()),
    // not a slip: its direction takes no part in the decision.
    s.tangent = s.frozen.tangent;
    for (int c = 1; c < nm; ++c) s.tangentialSlip[c - 1] = frozenSlipHeld(k, c - 1) ? 0.0 : g[at(topo_.multiplierId(k, c))];
  }
}

void ContactPairing::assembleFrozenGaps(const Vector& u, const Vector* multipliers, int counter) {
  // Partial gaps (and slips, frictional pairs) of the counterparts at their
  // multipliers, summed on the multiplier map (Export ADD), then back to the
  // counterparts' map, where the multipliers already are (the field). Only
  // multiplier-map values travel, no geometry.
  const Field f = gatherField(u, multipliers);
  const auto& local = topo_.ownedSlots();
  Vector gOv(lmOverlapMap_), gOwned(topo_.multiplierMap());
  {
    auto g = gOv.getDataNonConst();
    ElementResult er;
    std::vector<GO> dofs;
    // The multiplier rows of a sticking pair: the gap and the slip parts.
    auto addRows = [&](int k, SurfaceContactRole role) {
      evaluate(k, role, f, true, kResidual, er, dofs, /*forceStick=*/true);
      const int nm = topo_.numMultipliers(k), first = int(er.residual.size()) - nm;
      for (int c = 0; c < nm; ++c) g[lmOverlapMap_->getLocalElement(topo_.multiplierId(k, c))] += er.residual[first + c];
    };
    for (int k : local)
      if (slots_[k].paired()) addRows(k, SurfaceContactRole::Slave);
    for (int k : localMasterSlots_) addRows(k, SurfaceContactRole::Master);
  }
  gOwned.doExport(gOv, *lmExporter_, Tpetra::ADD);
  Vector gHeld(lmOverlapMap_);
  gHeld.doImport(gOwned, *lmImporter_, Tpetra::INSERT);
  // Received: the field at the counterparts (and at the step start), the
  // partial gaps at the owners and the summed values back.
  const auto& lmIn = multipliers ? lmImporter_ : lmHostImporter_;
  valueBytes_[counter] += long((dofImporter_->getNumRemoteIDs() * (stepStart_.is_null() ? 1 : 2) +
                                lmIn->getNumRemoteIDs() + lmExporter_->getNumRemoteIDs() +
                                lmImporter_->getNumRemoteIDs()) *
                               sizeof(double));
  auto g = gHeld.getData();
  auto at = [&](GO id) { return lmOverlapMap_->getLocalElement(id); };
  for (int k : local) takeFrozenValues(k, g.getRawPtr(), f.l.getRawPtr(), at);
  for (int k : localMasterSlots_) takeFrozenValues(k, g.getRawPtr(), f.l.getRawPtr(), at);
}

FrictionState ContactPairing::newContactState(const ContactSlot& s) const {
  // A new contact of a frictional pair starts sticking; a frictionless one slips.
  return topo_.pair(s.pair).friction > 0.0 ? FrictionState::Stick : FrictionState::Slip;
}

void ContactPairing::activateAllPaired() {
  // A pair whose DOFs are all prescribed has a prescribed gap: its
  // constraint row would be empty (a singular system), so it never becomes
  // active (updateActiveSet() reports it if it penetrates).
  for (size_t k = 0; k < slots_.size(); ++k) {
    ContactSlot& s = slots_[k];
    const bool was = s.active;
    s.active = s.paired() && !fullyPrescribed(int(k));
    if (!s.active) s.friction = FrictionState::Open;
    if (s.active && !was) s.friction = newContactState(s);
  }
}

std::vector<int> ContactPairing::updateActiveSet(const Vector& u, const Vector* multipliers, bool everySlot) {
  topo_.requireCommitted("updateActiveSet");
  if (topo_.options().decomposed) {
    // The values where the slots are evaluated; with everySlot, then from
    // the owners to every rank.
    ++valueUpdates_[everySlot];
    assembleFrozenGaps(u, multipliers, everySlot);
    std::vector<int> changed = decideOnOwners(everySlot);
    if (everySlot) valueBytes_[1] += shareValues(slots_, slotIndices(slots_.size()));
    return changed;
  }
  std::vector<double> v;
  gatherSurface(u, multipliers, v);
  refreshSlotGeometry(v);
  // Every rank holds every slot's values: each decides every slot alike.
  double lmax = 0.0;
  for (const auto& s : slots_) lmax = std::max(lmax, std::abs(s.state.multiplier));
  std::vector<int> changed, activated;
  for (size_t k = 0; k < slots_.size(); ++k) {
    const std::string fault = applyContactRules(int(k), lmax, changed, activated);
    if (!fault.empty()) throw InputError(fault);
  }
  if (topo_.frictional()) slipNewContactsOfSlidingPairs(activated, /*owned=*/false);
  return changed;
}

std::vector<int> ContactPairing::decideOnOwners(int counter) {
  // The owner of a slot decides it from the values summed on its multiplier
  // map; the ranks agree on the largest multiplier (the tension threshold)
  // and, in frictional pairs, on each pair's contacts, and every rank then
  // takes the changed slots' states. So the active set is the same on every
  // rank while the values of a slot are current only where it is evaluated.
  const MPI_Comm comm = rawComm(topo_.comm());
  double lmax = 0.0;
  for (int k : topo_.ownedSlots()) lmax = std::max(lmax, std::abs(slots_[k].state.multiplier));
  MPI_Allreduce(MPI_IN_PLACE, &lmax, 1, MPI_DOUBLE, MPI_MAX, comm);
  std::vector<int> changed, activated;
  std::string fault;
  int faultSlot = -1;
  for (int k : topo_.ownedSlots()) {
    const std::string why = applyContactRules(k, lmax, changed, activated);
    if (!why.empty() && fault.empty()) fault = why, faultSlot = k;
  }
  if (topo_.frictional()) slipNewContactsOfSlidingPairs(activated, /*owned=*/true);
  // The changed states to every rank, with a record of this rank's first
  // fully prescribed slot that penetrates, if any (friction = -1).
  struct Change {
    int slot;
    signed char active, friction;
  };
  std::vector<Change> mine;
  for (int k : changed) mine.push_back({k, static_cast<signed char>(slots_[k].active),
                                        static_cast<signed char>(slots_[k].friction)});
  if (faultSlot >= 0) mine.push_back({faultSlot, 0, -1});
  const std::vector<Change> all = allGather(comm, mine);
  valueBytes_[counter] += long((all.size() - mine.size()) * sizeof(Change));
  const int me = topo_.comm()->getRank();
  int first = -1;  // the first fully prescribed slot that penetrates, on any rank
  changed.clear();
  for (const Change& c : all) {
    if (c.friction < 0) {
      if (first < 0 || c.slot < first) first = c.slot;
      continue;
    }
    changed.push_back(c.slot);
    if (topo_.slotOwner(c.slot) == me) continue;
    slots_[c.slot].active = c.active != 0;
    slots_[c.slot].friction = FrictionState(c.friction);
  }
  if (first >= 0) raiseCollectively<InputError>(comm, faultSlot == first ? fault : std::string());
  std::sort(changed.begin(), changed.end());
  // The slip of the master counterparts' slots (the owners' is set).
  for (int k : localMasterSlots_) {
    ContactSlot& s = slots_[k];
    if (s.paired()) s.slip = s.active ? std::hypot(s.tangentialSlip[0], s.tangentialSlip[1]) : 0.0;
  }
  return changed;
}

std::string ContactPairing::applyContactRules(int k, double lmax, std::vector<int>& changed,
                                              std::vector<int>& activated) {
  // Tension threshold: λ > 0 up to round-off of the largest multiplier.
  const double tensionTol = 1e-10 * lmax;
  const double tol = topo_.options().penetrationTolerance;
  ContactSlot& s = slots_[k];
  if (!s.paired()) return {};
  if (s.active && s.state.multiplier > tensionTol) {
    s.active = false;
    changed.push_back(k);
  } else if (!s.active && s.gap < -tol && fullyPrescribed(k)) {
    std::ostringstream os;
    os << topo_.describeSlot(k)
       << ": the slave node and its master segment have all their displacements prescribed (Boundary Conditions), "
          "so contact cannot remove their penetration (gap "
       << s.gap << "); free the contact surfaces or change the prescribed values";
    return os.str();
  } else if (!s.active && s.gap < -tol) {
    s.active = true;
    s.friction = newContactState(s);
    changed.push_back(k);
    activated.push_back(k);
  } else if (s.active && updateFriction(k)) {
    changed.push_back(k);
  }
  if (!s.active) s.friction = FrictionState::Open;
  s.slip = s.active ? std::hypot(s.tangentialSlip[0], s.tangentialSlip[1]) : 0.0;
  return {};
}

void ContactPairing::slipNewContactsOfSlidingPairs(const std::vector<int>& activated, bool owned) {
  // A new contact starts sticking (newContactState()), unless every other
  // slave node in contact of its pair slips: then the pair slides, and a
  // new contact sticking alone would hold it for one more iteration (and
  // hide a gross slip from the singularity check). Counted over the slots
  // this rank decides (owned: its own, summed over the ranks).
  std::vector<char> isNew(slots_.size(), 0);
  for (int k : activated) isNew[k] = slots_[k].friction == FrictionState::Stick;
  const int np = topo_.numPairs();
  std::vector<int> counts(2 * size_t(np), 0);  // per pair: the others in contact, the sticking ones
  auto count = [&](int k) {
    if (!slots_[k].active || isNew[k]) return;
    ++counts[slots_[k].pair];
    counts[np + slots_[k].pair] += slots_[k].friction == FrictionState::Stick;
  };
  if (owned) {
    for (int k : topo_.ownedSlots()) count(k);
    MPI_Allreduce(MPI_IN_PLACE, counts.data(), 2 * np, MPI_INT, MPI_SUM, rawComm(topo_.comm()));
  } else {
    for (size_t k = 0; k < slots_.size(); ++k) count(int(k));
  }
  for (int k : activated)
    if (isNew[k] && counts[slots_[k].pair] > 0 && counts[np + slots_[k].pair] == 0)
      slots_[k].friction = FrictionState::Slip;
}

bool ContactPairing::updateFriction(int k) {
  // Stick or slip of an active frictional pair (DDC_Friction.hpp); an
  // active frictionless pair slips freely.
  ContactSlot& s = slots_[k];
  const Pair& pair = topo_.pair(s.pair);
  const FrictionState before = s.friction;
  if (pair.friction == 0.0) {
    s.friction = FrictionState::Slip;
    return false;
  }
  FrictionPairState f;
  f.coefficient = pair.friction;
  f.stiffness = pair.frictionStiffness;
  f.stick = before != FrictionState::Slip;
  const int nt = topo_.dim() - 1;
  bool stick = sticks(nt, s.tangentialSlip.data(), s.state.multiplier, s.tangential.data(), f);
  s.reversals = slipReverses(nt, s.tangentialSlip.data(), s.tangential.data(), f) ? s.reversals + 1 : 0;
  if (s.reversals >= 2) stick = true, s.reversals = 0;
  s.friction = stick ? FrictionState::Stick : FrictionState::Slip;
  return before != FrictionState::Open && s.friction != before;
}

void ContactPairing::beginStep(const Vector& u0) {
  // The step start of the slip (DDC_Friction.hpp): kept for the
  // counterparts' imports, and, for the conventional element, the surface's
  // positions (one gather per step).
  if (!topo_.frictional()) return;
  stepStart_ = Teuchos::rcp(new Vector(u0, Teuchos::Copy));
  if (!topo_.options().decomposed) {
    Vector v(topo_.surfaceMap());
    v.doImport(u0, *topo_.surfaceImporter(), Tpetra::INSERT);
    auto d = v.getData();
    stepStartSurface_.assign(d.begin(), d.end());
    ++exchanges_;
    bytesExchanged_ += topo_.bytesPerExchange();
  }
  for (auto& s : slots_) {
    s.tangentialSlip = {0.0, 0.0};
    s.reversals = 0;
  }
}

}  // namespace ddc
