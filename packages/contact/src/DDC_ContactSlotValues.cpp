// Reading the slots' values across ranks (see DDC_ContactPairing.hpp): the
// summary, the frictional work and the frozen-geometry error of a step as
// sums over the slots' owners, and the values of chosen slots brought from
// their owners. After an active-set update without everySlot a slot's
// values (multipliers, gap, slips) are current only where it is evaluated,
// always on its owner; what a step's end and the output read comes from
// there (doc/contact.md, "Across partitions").
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "DDC_ContactPairing.hpp"
#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_NodeToSurface.hpp"

namespace ddc {

namespace {

/// What is current only where a slot is evaluated (its owner and the rank
/// of its master facet): from an active-set update the multipliers, the gap
/// and the slips, and the normal and tangent basis the element used; from
/// the step-end pairing the frozen projection, normal and tangent basis.
struct SlotValueRecord {
  int slot = -1;
  double multiplier = 0.0, tangential[2] = {0.0, 0.0}, gap = 0.0, slip = 0.0, tangentialSlip[2] = {0.0, 0.0};
  double normal[3] = {0.0, 0.0, 0.0}, tangent[2][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  double frozenXi[2] = {0.0, 0.0}, frozenNormal[3] = {0.0, 0.0, 0.0};
  double frozenTangent[2][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
};

SlotValueRecord valuesOf(const ContactSlot& s, int k) {
  SlotValueRecord r;
  r.slot = k;
  r.multiplier = s.state.multiplier;
  r.gap = s.gap;
  r.slip = s.slip;
  for (int a = 0; a < 2; ++a) {
    r.tangential[a] = s.tangential[a];
    r.tangentialSlip[a] = s.tangentialSlip[a];
    r.frozenXi[a] = s.frozen.xi[a];
    for (int c = 0; c < 3; ++c) r.tangent[a][c] = s.tangent[a][c], r.frozenTangent[a][c] = s.frozen.tangent[a][c];
  }
  for (int c = 0; c < 3; ++c) r.normal[c] = s.normal[c], r.frozenNormal[c] = s.frozen.normal[c];
  return r;
}

void takeValues(const SlotValueRecord& r, ContactSlot& s) {
  s.state.multiplier = r.multiplier;
  s.gap = r.gap;
  s.slip = r.slip;
  for (int a = 0; a < 2; ++a) {
    s.tangential[a] = r.tangential[a];
    s.tangentialSlip[a] = r.tangentialSlip[a];
    s.frozen.xi[a] = r.frozenXi[a];
    for (int c = 0; c < 3; ++c) s.tangent[a][c] = r.tangent[a][c], s.frozen.tangent[a][c] = r.frozenTangent[a][c];
  }
  for (int c = 0; c < 3; ++c) s.normal[c] = r.normal[c], s.frozen.normal[c] = r.frozenNormal[c];
}

}  // namespace

void ContactPairing::requireSlotList(const std::vector<ContactSlot>& slots, const char* what) const {
  if (slots.size() != slots_.size())
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(slots.size()) + " slots for " +
                                std::to_string(slots_.size()));
}

void ContactPairing::shareSlotValues(std::vector<ContactSlot>& slots, const std::vector<int>& wanted) const {
  shareValues(slots, wanted);
}

long ContactPairing::shareValues(std::vector<ContactSlot>& slots, const std::vector<int>& wanted) const {
  // Checked on every rank together: a wrong list on one rank must not leave
  // the others waiting in the exchange.
  const MPI_Comm comm = rawComm(topo_.comm());
  std::string bad;
  if (slots.size() != slots_.size())
    bad = "shareSlotValues: " + std::to_string(slots.size()) + " slots for " + std::to_string(slots_.size());
  for (int k : wanted)
    if (bad.empty() && (k < 0 || size_t(k) >= slots_.size()))
      bad = "shareSlotValues: slot " + std::to_string(k) + " wanted of " + std::to_string(slots_.size());
  raiseCollectively<std::invalid_argument>(comm, bad);
  // The conventional element's values are on every rank after every update.
  if (!topo_.options().decomposed) return 0;
  // Two exchanges: the slots each rank wants to their owners, the values back.
  const int me = commRank(comm);
  struct Request {
    int slot, rank;
  };
  std::vector<std::vector<Request>> ask(size_t(commSize(comm)));
  for (int k : wanted)
    if (topo_.slotOwner(k) != me) ask[size_t(topo_.slotOwner(k))].push_back({k, me});
  std::vector<std::vector<SlotValueRecord>> answer(ask.size());
  const std::vector<Request> asked = exchangeRecords(comm, ask);
  for (const Request& r : asked) answer[size_t(r.rank)].push_back(valuesOf(slots[r.slot], r.slot));
  const std::vector<SlotValueRecord> values = exchangeRecords(comm, answer);
  for (const SlotValueRecord& r : values) takeValues(r, slots[r.slot]);
  return long(asked.size() * sizeof(Request) + values.size() * sizeof(SlotValueRecord));
}

long ContactPairing::sharedSlotBytes() { return long(sizeof(SlotValueRecord)); }

void ContactPairing::shareEverySlotsValues() { shareSlotValues(slots_, slotIndices(slots_.size())); }

int ContactPairing::numActive() const {
  return int(std::count_if(slots_.begin(), slots_.end(), [](const ContactSlot& s) { return s.active && s.paired(); }));
}

ContactSummary ContactPairing::reduceSummary() const {
  ContactSummary c;
  c.active = numActive();
  for (int k : topo_.ownedSlots()) {
    const ContactSlot& s = slots_[k];
    if (!s.active || !s.paired()) continue;
    // The slave feels −λ n (compression: λ < 0 pushes it along +n), and
    // in a frictional pair −λ_t·τ along the surface.
    const Eigen::Vector3d t = s.tangentialForce();
    for (int d = 0; d < 3; ++d) c.force[d] -= s.state.multiplier * s.normal[d];
    if (s.tangential[0] != 0.0 || s.tangential[1] != 0.0)
      for (int d = 0; d < 3; ++d) c.force[d] += t[d];
  }
  MPI_Allreduce(MPI_IN_PLACE, c.force, 3, MPI_DOUBLE, MPI_SUM, rawComm(topo_.comm()));
  return c;
}

double ContactPairing::frictionalWork(const std::vector<ContactSlot>& converged) const {
  requireSlotList(converged, "frictionalWork");
  double w = 0.0;
  for (int k : topo_.ownedSlots()) {
    const ContactSlot& s = converged[k];
    if (s.active) w += s.tangential[0] * s.tangentialSlip[0] + s.tangential[1] * s.tangentialSlip[1];
  }
  MPI_Allreduce(MPI_IN_PLACE, &w, 1, MPI_DOUBLE, MPI_SUM, rawComm(topo_.comm()));
  return w;
}

FrozenGeometryError ContactPairing::frozenGeometryError(const std::vector<ContactSlot>& converged) const {
  requireSlotList(converged, "frozenGeometryError");
  const int dim = topo_.dim();
  // Reference position of facet point xi on the master facet with `nodes`.
  auto referencePoint = [&](CellType type, const ContactSlot& s, const std::array<double, 2>& xi) {
    Eigen::MatrixXd X(s.numMaster, dim);
    for (int a = 0; a < s.numMaster; ++a) X.row(a) = topo_.referencePosition(s.master[a]).head(dim).transpose();
    Eigen::Vector3d point, normal;
    return facetPointAndNormal(type, X, xi, point, normal) ? std::optional<Eigen::Vector3d>(point) : std::nullopt;
  };
  // Over the slots this rank owns (their converged values are here), then
  // summed over the ranks.
  double work[3] = {0.0, 0.0, 0.0};  // gap, normal, tangent
  for (int k : topo_.ownedSlots()) {
    const ContactSlot& before = converged[k];
    const ContactSlot& now = slots_[k];
    if (!before.active || !before.paired()) continue;
    const double lambda = before.state.multiplier;
    work[0] += lambda * (now.gap - before.gap);
    if (!now.paired()) continue;
    const CellType type = topo_.pair(before.pair).masterType;
    const auto from = referencePoint(type, before, before.frozen.xi);
    const auto to = referencePoint(type, now, now.frozen.xi);
    if (!(from && to)) continue;
    const double s = (*to - *from).norm();
    work[1] += std::abs(lambda) * (now.normal - before.frozen.normal).norm() * s;
    // Friction: the tangential force along the frozen basis, across the updated one.
    for (int a = 0; a + 1 < dim; ++a)
      if (before.tangential[a] != 0.0)
        work[2] += std::abs(before.tangential[a]) * (now.frozen.tangent[a] - before.frozen.tangent[a]).norm() * s;
  }
  MPI_Allreduce(MPI_IN_PLACE, work, 3, MPI_DOUBLE, MPI_SUM, rawComm(topo_.comm()));
  return {std::abs(work[0]), work[1], work[2]};
}

}  // namespace ddc
