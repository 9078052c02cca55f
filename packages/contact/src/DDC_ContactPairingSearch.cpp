// The searches of the pairing part of the contact component (see
// DDC_ContactPairing.hpp): the facet pairing with the facing and
// free-boundary rules, the replicated search and tracking, and the decomposed
// element's step-end search by the owners of the slave nodes after one
// bounding-box-limited exchange.
#include <algorithm>
#include <cmath>
#include <map>

#include "DDC_ContactPairing.hpp"
#include "DDC_Error.hpp"
#include "DDC_Friction.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {
/// A surface node's current position, sent to the ranks whose slave bounding
/// box contains it (D coordinates: the 2-D records stay as small as before).
template <int D>
struct NodePosition {
  int node;
  double x[D];
};
/// The pairing of one slot, found by the owner of its slave node, with the
/// first vector of the tangent basis the owner froze from its last one
/// (3-D; in 2-D the basis follows from the normal).
template <int D>
struct SlotPairing {
  enum Flag { kPastFreeEnd = 1, kViaCorner = 2, kNotFacing = 4 };
  int slot, facet, flags;
  double xi[D - 1], gap, distance, n[D], t1[D == 3 ? 3 : 1];
};
}  // namespace

Eigen::MatrixXd ContactPairing::facetPositions(const Pair& pair, int f, const Position& position) const {
  const ContactTopology::Facet& r = pair.masterFacets[f];
  Eigen::MatrixXd x(r.numNodes, topo_.dim());
  for (int a = 0; a < r.numNodes; ++a) x.row(a) = position(r.nodes[a]).head(topo_.dim()).transpose();
  return x;
}

Eigen::Vector3d ContactPairing::slaveNormal(const Pair& pair, int node, const Position& position) const {
  // The normalised sum of the unit outward normals of the slave facets at
  // the node, each at the node's reference coordinates in that facet.
  const int dim = topo_.dim();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const auto it = pair.slaveFacetsAt.find(node);
  if (it == pair.slaveFacetsAt.end()) return sum;
  const ReferenceCell& ref = referenceCell(pair.slaveType);
  for (const auto& [f, a] : it->second) {
    const ContactTopology::Facet& r = pair.slaveFacets[f];
    Eigen::MatrixXd x(r.numNodes, dim);
    for (int b = 0; b < r.numNodes; ++b) x.row(b) = position(r.nodes[b]).head(dim).transpose();
    Eigen::Vector3d point, normal;
    if (facetPointAndNormal(pair.slaveType, x, {ref.nodes[a][0], ref.nodes[a][1]}, point, normal)) sum += normal;
  }
  const double n = sum.norm();
  // Normals that cancel (a fold of the slave surface) give no direction: such
  // a node faces nothing.
  return n > 0.0 ? Eigen::Vector3d(sum / n) : Eigen::Vector3d::Zero();
}

std::vector<ContactPairing::Found> ContactPairing::facetPairing(const Pair& pair, FacetSearch& search,
                                                                const std::vector<int>& facets,
                                                                const std::vector<int>& slaves,
                                                                const Position& position) const {
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
      f.pastFreeEnd = pastFreeBoundary(pair, g, c, d, normal, position);
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

bool ContactPairing::pastFreeBoundary(const Pair& pair, int g, const FacetCandidate& c, const Eigen::Vector3d& d,
                                      const Eigen::Vector3d& normal, const Position& position) const {
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
    centre.head(topo_.dim()) += x.row(a).transpose() / corners;
    for (int b = a + 1; b < corners; ++b) size = std::max(size, (x.row(a) - x.row(b)).norm());
  }
  const double onSide = 1e-9 * size;  // round-off: the chord point is computed from these nodes
  bool past = false;
  for (const auto& side : pair.freeSides[g]) {
    // The side's pieces: its chords, or the end node of a segment.
    const size_t pieces = side.size() == 1 ? 1 : side.size() - 1;
    for (size_t a = 0; a < pieces && !past; ++a) {
      const Eigen::Vector3d p = position(side[a]), q = position(side[side.size() == 1 ? a : a + 1]);
      const Eigen::Vector3d t = q - p;
      const double s = t.squaredNorm() > 0 ? std::clamp((c.point - p).dot(t) / t.squaredNorm(), 0.0, 1.0) : 0.0;
      if ((c.point - p - s * t).norm() > onSide) continue;
      Eigen::Vector3d m = c.point - centre;
      m -= m.dot(normal) * normal;
      if (t.squaredNorm() > 0) m -= m.dot(t) / t.squaredNorm() * t;
      past = m.norm() > 0 && d.dot(m) > kFreeBoundaryMargin * size * m.norm();
    }
  }
  return past;
}

void ContactPairing::replicatedSearch(const Position& position, bool global, FoundAll& found) {
  const int dim = topo_.dim();
  found.assign(topo_.numPairs(), {});
  for (int p = 0; p < topo_.numPairs(); ++p) {
    const Pair& pair = topo_.pair(p);
    std::vector<int> all(pair.masterFacets.size());
    for (size_t g = 0; g < all.size(); ++g) all[g] = int(g);
    searches_[p]->update(
        pair.slaves, [&](int n) { return Eigen::VectorXd(position(n).head(dim)); }, global);
    found[p] = facetPairing(pair, *searches_[p], all, pair.slaves, position);
  }
}

void ContactPairing::distributedSearch(const Vector& u, FoundAll& found) {
  // 1.-2. The positions each rank's slave nodes may pair with; 3. the search
  // of the owners; 4. every slot's pairing to every rank. One exchange.
  std::map<int, Eigen::Vector3d> known;
  long bytes = topo_.dim() == 2 ? sendPositions<2>(u, known) : sendPositions<3>(u, known);
  long queries = 0;
  const auto mine = searchOwnedSlaves(known, queries);
  bytes += topo_.dim() == 2 ? shareFound<2>(mine, found) : shareFound<3>(mine, found);
  long total[2] = {bytes, queries}, sum[2];
  MPI_Allreduce(total, sum, 2, MPI_LONG, MPI_SUM, rawComm(topo_.comm()));
  ++exchanges_;
  bytesExchanged_ += sum[0];
  distributedQueries_ += sum[1];
}

template <int D>
long ContactPairing::sendPositions(const Vector& u, std::map<int, Eigen::Vector3d>& known) const {
  const MPI_Comm mpi = rawComm(topo_.comm());
  const int me = topo_.comm()->getRank(), P = topo_.comm()->getSize();
  auto ud = u.getData();
  const Map& hostMap = *topo_.hostMap();
  auto ownedPosition = [&](int n) {
    const int i = topo_.index(n);
    Eigen::Vector3d x = topo_.referenceAt(i);
    for (int c = 0; c < D; ++c) x[c] += ud[hostMap.getLocalElement(topo_.dofsAt(i)[c])];
    return x;
  };
  auto owner = [&](int n) { return topo_.ownerAt(topo_.index(n)); };
  // 1. Bounding box of this rank's slave nodes, inflated by a margin that
  //    covers every master facet (and its neighbours) a slave can pair with.
  double box[2 * D];
  for (int c = 0; c < D; ++c) box[c] = 1e300, box[D + c] = -1e300;
  for (int k : topo_.ownedSlots()) {
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
  const double margin = topo_.pairingMargin();
  for (int n : topo_.masterSurfaceNodes()) {
    if (owner(n) != me) continue;
    const Eigen::Vector3d x = ownedPosition(n);
    for (int r = 0; r < P; ++r) {
      const double* b = &boxes[2 * D * r];
      bool inside = true;
      for (int c = 0; c < D; ++c) inside = inside && x[c] >= b[c] - margin && x[c] <= b[D + c] + margin;
      if (inside) send[r].push_back(record(n, x));
    }
  }
  //    With them, the slave-surface neighbours of other ranks' slave nodes
  //    (the facing rule's nodal normals), unless already on the way.
  for (const auto& [node, r] : topo_.slaveNeighbourSends()) {
    const int n = node;
    if (std::any_of(send[r].begin(), send[r].end(), [n](const NodePosition<D>& q) { return q.node == n; })) continue;
    send[r].push_back(record(n, ownedPosition(n)));
  }
  long bytes = 0;
  for (int r = 0; r < P; ++r)
    if (r != me) bytes += long(send[r].size() * sizeof(NodePosition<D>));
  for (const auto& np : exchangeRecords(mpi, send)) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int c = 0; c < D; ++c) x[c] = np.x[c];
    known[np.node] = x;
  }
  for (int k : topo_.ownedSlots()) known[slots_[k].slaveNode] = ownedPosition(slots_[k].slaveNode);
  for (const auto& pair : topo_.pairs())  // slave-surface neighbours owned here
    for (const auto& f : pair.slaveFacets)
      for (int a = 0; a < f.numNodes; ++a)
        if (owner(f.nodes[a]) == me && !known.count(f.nodes[a])) known[f.nodes[a]] = ownedPosition(f.nodes[a]);
  return bytes;
}

std::vector<std::pair<int, ContactPairing::Found>> ContactPairing::searchOwnedSlaves(
    const std::map<int, Eigen::Vector3d>& known, long& queries) const {
  // 3. Per pair: the global search for this rank's slaves over the master
  //    facets whose nodes arrived (kept in their global order, so ties
  //    break as in the replicated search).
  const int me = topo_.comm()->getRank(), dim = topo_.dim();
  auto position = [&](int n) { return known.at(n); };
  std::vector<std::pair<int, Found>> out;
  for (const auto& pair : topo_.pairs()) {
    std::vector<int> localSlaves, localSlotIds;
    for (int k : pair.slots)
      if (topo_.slotOwner(k) == me) localSlaves.push_back(slots_[k].slaveNode), localSlotIds.push_back(k);
    std::vector<int> globalIndex;
    for (int g = 0; g < int(pair.masterFacets.size()); ++g) {
      const ContactTopology::Facet& r = pair.masterFacets[g];
      if (std::all_of(r.nodes.begin(), r.nodes.begin() + r.numNodes, [&](int n) { return known.count(n) > 0; }))
        globalIndex.push_back(g);
    }
    std::vector<Found> here(localSlaves.size());
    if (!localSlaves.empty() && !globalIndex.empty()) {
      queries += long(localSlaves.size());
      std::vector<std::vector<int>> facets;
      for (int g : globalIndex) facets.push_back(pair.facetNodes(g));
      FacetSearch search(pair.masterType, facets, topo_.options().searchRadius);
      search.update(localSlaves, [&](int n) { return Eigen::VectorXd(known.at(n).head(dim)); }, true);
      here = facetPairing(pair, search, globalIndex, localSlaves, position);
    }
    for (size_t i = 0; i < here.size(); ++i) out.emplace_back(localSlotIds[i], here[i]);
  }
  return out;
}

template <int D>
long ContactPairing::shareFound(const std::vector<std::pair<int, Found>>& mine, FoundAll& found) const {
  // 4. Each slot's pairing to the ranks that evaluate it: its owner (here)
  //    and the rank of its master facet. Every rank learns the slots whose
  //    facet changed (the pairing itself, segment and master nodes, stays
  //    replicated), and, while a pair has paired no slave node and has not
  //    been warned of, the slots a facet does not face (notePairing()).
  const MPI_Comm mpi = rawComm(topo_.comm());
  const int me = topo_.comm()->getRank(), P = topo_.comm()->getSize();
  found.assign(topo_.numPairs(), {});
  std::vector<int> indexInPair(slots_.size(), -1);
  for (int p = 0; p < topo_.numPairs(); ++p) {
    const auto& slots = topo_.pair(p).slots;
    found[p].assign(slots.size(), Found{});
    for (size_t i = 0; i < slots.size(); ++i) indexInPair[slots[i]] = int(i), found[p][i].known = false;
  }
  auto take = [&](const SlotPairing<D>& a) {
    Found& f = found[slots_[a.slot].pair][indexInPair[a.slot]];
    f.known = true;
    f.facet = a.facet;
    f.pastFreeEnd = (a.flags & SlotPairing<D>::kPastFreeEnd) != 0;
    f.viaCorner = (a.flags & SlotPairing<D>::kViaCorner) != 0;
    f.notFacing = (a.flags & SlotPairing<D>::kNotFacing) != 0;
    for (int c = 0; c < D - 1; ++c) f.xi[c] = a.xi[c];
    f.gap = a.gap;
    f.distance = a.distance;
    for (int c = 0; c < D; ++c) f.normal[c] = a.n[c];
    if constexpr (D == 3) f.tangent = Eigen::Vector3d(a.t1[0], a.t1[1], a.t1[2]);
  };
  std::vector<std::vector<SlotPairing<D>>> toMaster(P);
  std::vector<SlotPairing<D>> changes;
  for (const auto& [slot, f] : mine) {
    const int flags = (f.pastFreeEnd ? SlotPairing<D>::kPastFreeEnd : 0) |
                      (f.viaCorner ? SlotPairing<D>::kViaCorner : 0) | (f.notFacing ? SlotPairing<D>::kNotFacing : 0);
    SlotPairing<D> rec{slot, f.facet, flags, {}, f.gap, f.distance, {}, {}};
    for (int a = 0; a < D - 1; ++a) rec.xi[a] = f.xi[a];
    for (int c = 0; c < D; ++c) rec.n[c] = f.normal[c];
    const int p = slots_[slot].pair;
    const Pair& pair = topo_.pair(p);
    const int facet = f.facet >= 0 && !f.pastFreeEnd ? f.facet : -1;
    if constexpr (D == 3)
      if (facet >= 0 && pair.friction > 0.0) {
        const Eigen::Vector3d t1 = tangentBasis(D, f.normal, slots_[slot].frozen.tangent[0])[0];
        for (int c = 0; c < D; ++c) rec.t1[c] = t1[c];
      }
    take(rec);
    if (facet >= 0 && pair.masterFacets[facet].rank != me) toMaster[pair.masterFacets[facet].rank].push_back(rec);
    const bool unwarned = (size_t(p) >= everPaired_.size() || !everPaired_[p]) &&
                          (size_t(p) >= facingReported_.size() || !facingReported_[p]);
    if (facet != slots_[slot].segment || (f.notFacing && unwarned)) changes.push_back(rec);
  }
  long bytes = long(changes.size() * size_t(P - 1) * sizeof(SlotPairing<D>));
  for (int r = 0; r < P; ++r) bytes += long(toMaster[r].size() * sizeof(SlotPairing<D>));
  for (const auto& a : exchangeRecords(mpi, toMaster)) take(a);
  for (const auto& a : allGather(mpi, changes)) take(a);
  return bytes;
}

}  // namespace ddc
