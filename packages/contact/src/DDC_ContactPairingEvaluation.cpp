// The evaluation side of the pairing part of the contact component (see
// DDC_ContactPairing.hpp): the maps of the counterparts this rank evaluates,
// the active set with its gaps, the constraint rows and the element
// contributions.
#include <algorithm>
#include <cmath>

#include "DDC_ContactPairing.hpp"
#include "DDC_Error.hpp"

namespace ddc {

namespace {

using TpetraImport = Tpetra::Import<LO, GO, Node>;
using TpetraExport = Tpetra::Export<LO, GO, Node>;

Teuchos::RCP<const Map> mapOf(const std::vector<GO>& gids, const Teuchos::RCP<const Teuchos::Comm<int>>& comm) {
  return Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                              Teuchos::ArrayView<const GO>(gids), 0, comm));
}

}  // namespace

/// Field values at this rank's counterpart DOFs (dof) and multipliers (lm).
struct ContactPairing::Field {
  Teuchos::RCP<Vector> dof, lm;
  Teuchos::ArrayRCP<const double> d, l;
  const ContactPairing* c = nullptr;
  double at(GO g) const { return d[c->dofOverlapMap_->getLocalElement(g)]; }
  double multiplier(int k) const { return l[c->lmOverlapMap_->getLocalElement(c->topo_.multiplierId(k))]; }
};

void ContactPairing::requirePaired(const char* what) const {
  if (!pairedOnce_)
    throw std::logic_error(std::string("ContactComponent::") + what +
                           ": no pairing yet, so no slave node is paired and there is nothing to evaluate; call "
                           "updatePairing(u, /*global=*/true, /*freeze=*/true) once after setDofs()");
}

std::vector<GO> ContactPairing::slotDofs(int k) const {
  const ContactSlot& s = slots_[k];
  std::vector<GO> dofs;
  if (s.paired()) {
    topo_.appendNodeDofs(s.slaveNode, dofs);
    for (int a = 0; a < s.numMaster; ++a) topo_.appendNodeDofs(s.master[a], dofs);
  }
  dofs.push_back(topo_.multiplierId(k));
  return dofs;
}

std::vector<GO> ContactPairing::slaveSideDofs(int k) const {
  std::vector<GO> dofs;
  topo_.appendNodeDofs(slots_[k].slaveNode, dofs);
  dofs.push_back(topo_.multiplierId(k));
  return dofs;
}

std::vector<GO> ContactPairing::masterSideDofs(int k) const {
  std::vector<GO> dofs;
  for (int a = 0; a < slots_[k].numMaster; ++a) topo_.appendNodeDofs(slots_[k].master[a], dofs);
  dofs.push_back(topo_.multiplierId(k));
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
  auto add = [&](const std::vector<GO>& d) {
    dofs.insert(dofs.end(), d.begin(), d.end() - 1);
    lms.push_back(d.back());
  };
  for (int k : topo_.ownedSlots()) add(decomposed && slots_[k].paired() ? slaveSideDofs(k) : slotDofs(k));
  for (int k : localMasterSlots_) add(masterSideDofs(k));
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
  f.d = f.dof->getData();
  f.l = f.lm->getData();
  return f;
}

void ContactPairing::evaluate(int k, SurfaceContactRole role, const Field& f, bool forceActive, unsigned what,
                              ElementResult& er, std::vector<GO>& dofs) const {
  // The slave counterpart on [u_s, λ], the master counterpart on
  // [u_1..u_m, λ], the conventional element on [u_s, u_1..u_m, λ].
  const int dim = topo_.dim();
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
  Eigen::MatrixXd X(nn, dim), ue(nn, dim);
  for (int i = 0; i < nn; ++i) {
    X.row(i) = topo_.referencePosition(nodes[i]).head(dim).transpose();
    for (int c = 0; c < dim; ++c) ue(i, c) = f.at(dofs[dim * i + c]);
  }
  topo_.surfaceElement(role, topo_.pair(s.pair).masterType).computeSurfaceContact(X, ue, s.frozen, state, what, er);
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
      dofs.assign(1, topo_.multiplierId(k));
      releasedContribution(1, f.multiplier(k), kAll, er);
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
  auto add = [&](int k, SurfaceContactRole role) {
    evaluate(k, role, f, true, kTangent, er, dofs);
    const int row = int(dofs.size()) - 1;
    const int sub = role == SurfaceContactRole::Master
                        ? topo_.pair(slots_[k].pair).masterFacets[slots_[k].segment].subdomain
                        : -1;
    for (int a = 0; a < row; ++a)
      if (er.tangent(row, a) != 0.0) out.push_back({k, topo_.multiplierId(k), dofs[a], er.tangent(row, a), role, sub});
  };
  for (int k : topo_.ownedSlots())
    if (slots_[k].paired()) add(k, SurfaceContactRole::Slave);
  for (int k : localMasterSlots_) add(k, SurfaceContactRole::Master);
  return out;
}

// ---- the active set ------------------------------------------------------------------

void ContactPairing::gatherSurface(const Vector& u, const Vector* multipliers, std::vector<double>& values) const {
  // Surface DOFs, then every slot's multiplier: one exchange.
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
    const auto& local = topo_.ownedSlots();
    for (size_t i = 0; i < local.size(); ++i)
      owned.replaceLocalValue(LO(i), ud[topo_.hostMap()->getLocalElement(topo_.multiplierId(local[i]))]);
    lm.doImport(owned, *topo_.multiplierAllImporter(), Tpetra::INSERT);
  }
  ++exchanges_;
  bytesExchanged_ += topo_.bytesPerExchange();
  auto d = s.getData();
  values.assign(d.begin(), d.end());
  auto l = lm.getData();
  for (size_t k = 0; k < slots_.size(); ++k) values.push_back(l[allMap.getLocalElement(topo_.multiplierId(int(k)))]);
}

void ContactPairing::refreshSlotGeometry(const std::vector<double>& v) {
  const size_t base = size_t(topo_.dim()) * topo_.surfaceNodes().size();
  const Position position = [&](int n) { return currentPosition(n, v); };
  for (size_t k = 0; k < slots_.size(); ++k) {
    ContactSlot& s = slots_[k];
    s.state.multiplier = v[base + k];
    if (!s.paired()) continue;
    const Pair& pair = topo_.pair(s.pair);
    // The conventional element's own projection (DDC_NodeToSurface.hpp).
    const FacetProjection pr = projectOntoFacet(pair.masterType, facetPositions(pair, s.segment, position),
                                                position(s.slaveNode).head(topo_.dim()));
    s.normal = pr.normal;
    s.gap = pr.gap;
  }
}

void ContactPairing::assembleFrozenGaps(const Vector& u, const Vector* multipliers) {
  // Partial gaps of the counterparts at their multipliers, summed on the
  // multiplier map (Export ADD), then (g_N, λ) of every slot to every rank.
  // Only multiplier-map values travel, no geometry.
  const Field f = gatherField(u, multipliers);
  const auto& local = topo_.ownedSlots();
  Vector gOv(lmOverlapMap_), gOwned(topo_.multiplierMap());
  {
    auto g = gOv.getDataNonConst();
    ElementResult er;
    std::vector<GO> dofs;
    for (int k : local)
      if (slots_[k].paired()) {
        evaluate(k, SurfaceContactRole::Slave, f, true, kResidual, er, dofs);
        g[lmOverlapMap_->getLocalElement(topo_.multiplierId(k))] += er.residual[er.residual.size() - 1];
      }
    for (int k : localMasterSlots_) {
      evaluate(k, SurfaceContactRole::Master, f, true, kResidual, er, dofs);
      g[lmOverlapMap_->getLocalElement(topo_.multiplierId(k))] += er.residual[er.residual.size() - 1];
    }
  }
  gOwned.doExport(gOv, *lmExporter_, Tpetra::ADD);
  MultiVector owned(topo_.multiplierMap(), 2), all(topo_.multiplierAllMap(), 2);
  {
    auto g = gOwned.getData();
    for (size_t i = 0; i < local.size(); ++i) {
      owned.replaceLocalValue(LO(i), 0, g[i]);
      owned.replaceLocalValue(LO(i), 1, f.multiplier(local[i]));
    }
  }
  all.doImport(owned, *topo_.multiplierAllImporter(), Tpetra::INSERT);
  auto g = all.getData(0), lam = all.getData(1);
  for (size_t k = 0; k < slots_.size(); ++k) {
    ContactSlot& s = slots_[k];
    const LO l = topo_.multiplierAllMap()->getLocalElement(topo_.multiplierId(int(k)));
    s.state.multiplier = lam[l];
    if (!s.paired()) continue;
    s.normal = s.frozen.normal;
    s.gap = g[l];
  }
}

void ContactPairing::activateAllPaired() {
  // A pair whose DOFs are all prescribed has a prescribed gap: its
  // constraint row would be empty (a singular system), so it never becomes
  // active (updateActiveSet() reports it if it penetrates).
  for (size_t k = 0; k < slots_.size(); ++k) slots_[k].active = slots_[k].paired() && !fullyPrescribed(int(k));
}

std::vector<int> ContactPairing::updateActiveSet(const Vector& u, const Vector* multipliers) {
  topo_.requireCommitted("updateActiveSet");
  if (topo_.options().decomposed) {
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
  const double tol = topo_.options().penetrationTolerance;
  std::vector<int> changed;
  for (size_t k = 0; k < slots_.size(); ++k) {
    ContactSlot& s = slots_[k];
    if (!s.paired()) continue;
    if (s.active && s.state.multiplier > tensionTol) {
      s.active = false;
      changed.push_back(static_cast<int>(k));
    } else if (!s.active && s.gap < -tol && fullyPrescribed(int(k))) {
      DDC_THROW(InputError, topo_.describeSlot(int(k))
                                << ": the slave node and its master segment have all their displacements "
                                   "prescribed (Boundary Conditions), so contact cannot remove their penetration "
                                   "(gap "
                                << s.gap << "); free the contact surfaces or change the prescribed values");
    } else if (!s.active && s.gap < -tol) {
      s.active = true;
      changed.push_back(static_cast<int>(k));
    }
  }
  return changed;
}

}  // namespace ddc
