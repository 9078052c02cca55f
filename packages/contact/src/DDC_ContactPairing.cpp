// The pairing part of the contact component: the slots' pairing and its
// record, the initial-penetration check, and the step-control helpers (see
// DDC_ContactPairing.hpp). The searches are in DDC_ContactPairingSearch.cpp,
// the active set and the element contributions in
// DDC_ContactPairingEvaluation.cpp.
#include "DDC_ContactPairing.hpp"

#include "DDC_MpiRecords.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "DDC_Error.hpp"

namespace ddc {

ContactPairing::ContactPairing(const ContactTopology& topology) : topo_(topology) {}

ContactPairing::~ContactPairing() = default;

void ContactPairing::start() {
  slots_.clear();
  for (const ContactTopology::Slot& t : topo_.slots()) {
    ContactSlot s;
    s.pair = t.pair;
    s.slaveNode = t.slaveNode;
    s.tributaryLength = t.tributaryLength;
    slots_.push_back(s);
  }
  searches_.clear();
  for (const Pair& pair : topo_.pairs()) {
    std::vector<std::vector<int>> facets;
    for (size_t f = 0; f < pair.masterFacets.size(); ++f) facets.push_back(pair.facetNodes(int(f)));
    searches_.push_back(std::make_unique<FacetSearch>(pair.masterType, facets, topo_.options().searchRadius));
  }
}

Eigen::Vector3d ContactPairing::currentPosition(int id, const std::vector<double>& v) const {
  const int i = topo_.index(id);
  DDC_CHECK(i >= 0, "node " << id << " is not on a contact surface");
  Eigen::Vector3d x = topo_.referenceAt(i);
  for (int c = 0; c < topo_.dim(); ++c) x[c] += v[size_t(topo_.dim()) * i + c];
  return x;
}

// ---- the pairing ---------------------------------------------------------------------

bool ContactPairing::updatePairing(const Vector& u, bool global, bool freeze, std::vector<int>* changedSlots) {
  topo_.requireCommitted("updatePairing");
  // Decomposed contact pairs at step ends only (global search): the
  // geometry goes only where bounding boxes say it is needed. Conventional
  // NTS (the monolithic reference) tracks the pairing inside Newton on
  // replicated surface positions.
  const bool distributed = topo_.options().decomposed && global;
  std::vector<double> v;
  FoundAll found;
  const Position position = [&](int n) { return currentPosition(n, v); };
  if (distributed) {
    distributedSearch(u, found);
  } else {
    // Positions only: the multipliers are not read here.
    Vector s(topo_.surfaceMap());
    s.doImport(u, *topo_.surfaceImporter(), Tpetra::INSERT);
    ++exchanges_;
    bytesExchanged_ += topo_.bytesPerExchange();
    auto d = s.getData();
    v.assign(d.begin(), d.end());
    replicatedSearch(position, global, found);
  }
  bool changed = false;
  for (int p = 0; p < topo_.numPairs(); ++p) {
    const Pair& pair = topo_.pair(p);
    for (size_t i = 0; i < found[p].size(); ++i) {
      ContactSlot& s = slots_[pair.slots[i]];
      if (!found[p][i].known) continue;  // unchanged, evaluated elsewhere
      if (!distributed && !global && keepPreviousFacet(pair, s, found[p][i], position, freeze)) continue;
      if (assignFacet(pair, s, found[p][i], freeze)) {
        changed = true;
        if (changedSlots) changedSlots->push_back(pair.slots[i]);
      }
    }
  }
  notePairing(found);
  pairedOnce_ = true;
  if (changed) buildEvaluationMaps();
  return changed;
}

bool ContactPairing::keepPreviousFacet(const Pair& pair, ContactSlot& s, const Found& c, const Position& position,
                                       bool freeze) const {
  // Hysteresis (Newton iterations only): a slave whose projection onto
  // its previous facet lies within kPairingHysteresis of that facet
  // keeps it. Without it a slave sitting on a master node can flip
  // between the two adjacent facets every iteration and Newton stalls;
  // and a slave sitting on the free end of the master surface (two
  // blocks of one width) flips between paired and "past the end" with
  // the round-off of its position (a different summation order on two
  // ranks is enough), which the active-set check reports as cycling.
  constexpr double kPairingHysteresis = 1e-2;  // fraction of the facet's reference size
  const bool paired = c.facet >= 0 && !c.pastFreeEnd;
  if (!(s.paired() && (paired ? c.facet != s.segment : c.pastFreeEnd))) return false;
  const int dim = topo_.dim();
  const FacetProjection pr = projectOntoFacet(pair.masterType, facetPositions(pair, s.segment, position),
                                              position(s.slaveNode).head(dim));
  const double h = 2.0 * kPairingHysteresis;  // reference facets have sides 1 (simplex) or 2
  const bool near = pr.converged && (referenceCell(pair.masterType).simplex
                                         ? pr.xi[0] >= -h / 2 && pr.xi[1] >= -h / 2 && pr.xi[0] + pr.xi[1] <= 1 + h / 2
                                         : std::abs(pr.xi[0]) <= 1 + h && (dim == 2 || std::abs(pr.xi[1]) <= 1 + h));
  // The kept facet must pass the facing rule like any pairing.
  if (!near || facingVerdict(c.slaveNormal, pr.normal, pr.gap,
                             kFacingDepthFraction * pair.masterFacets[s.segment].depth) != ContactRejection::None)
    return false;
  s.gap = pr.gap;
  s.normal = pr.normal;
  if (freeze) freezeGeometry(pair, s, pr.xi, pr.normal);
  return true;
}

void ContactPairing::freezeGeometry(const Pair& pair, ContactSlot& s, const std::array<double, 2>& xi,
                                    const Eigen::Vector3d& normal, const Eigen::Vector3d& tangent) const {
  // ξ^p and n^p (paper eq. 1), and for a frictional pair the tangent basis
  // τ^p rotated least from the last step's (tangentBasis()), which only
  // the slot's owner is sure to hold: another rank takes the owner's τ_1.
  const Eigen::Vector3d previous = s.frozen.tangent[0];
  s.frozen.xi = xi;
  s.frozen.normal = normal;
  if (pair.friction > 0.0)
    s.frozen.tangent = tangent.isZero(0.0) ? tangentBasis(topo_.dim(), normal, previous)
                                           : std::array<Eigen::Vector3d, 2>{tangent, normal.cross(tangent)};
}

bool ContactPairing::assignFacet(const Pair& pair, ContactSlot& s, const Found& c, bool freeze) const {
  const int facet = c.facet >= 0 && !c.pastFreeEnd ? c.facet : -1;
  const bool changed = facet != s.segment;
  s.segment = facet;
  s.master.fill(-1);
  s.numMaster = 0;
  s.masterElement = -1;
  if (facet < 0) {
    s.active = false;
    s.gap = 0.0;
    return changed;
  }
  const ContactTopology::Facet& r = pair.masterFacets[facet];
  std::copy(r.nodes.begin(), r.nodes.begin() + r.numNodes, s.master.begin());
  s.numMaster = r.numNodes;
  s.masterElement = r.element;
  s.gap = c.gap;
  s.normal = c.normal;
  if (freeze) freezeGeometry(pair, s, c.xi, c.normal, c.tangent);
  return changed;
}

void ContactPairing::notePairing(const FoundAll& found) {
  // `found` and the slots are the same on every rank: so are the warnings.
  const int dim = topo_.dim();
  everPaired_.resize(topo_.numPairs(), 0);
  facingReported_.resize(topo_.numPairs(), 0);
  for (int p = 0; p < topo_.numPairs(); ++p) {
    const Pair& pair = topo_.pair(p);
    int notFacing = 0, example = -1;
    for (size_t i = 0; i < pair.slots.size() && i < found[p].size(); ++i) {
      if (slots_[pair.slots[i]].paired()) everPaired_[p] = 1;
      if (found[p][i].notFacing && !slots_[pair.slots[i]].paired() && notFacing++ == 0) example = int(i);
    }
    if (everPaired_[p] || facingReported_[p] || notFacing == 0) continue;
    facingReported_[p] = 1;
    const int node = slots_[pair.slots[example]].slaveNode;
    const Eigen::Vector3d x = topo_.referencePosition(node);
    const Eigen::Vector3d n = found[p][example].normal + Eigen::Vector3d::Zero();  // + 0: no "-0"
    std::ostringstream os;
    os << "contact pair '" << pair.path << "': none of its " << pair.slots.size() << " slave nodes pairs, and "
       << notFacing << " of them lie within the search radius of master facets that do not face them (e.g. slave "
       << "node " << node << " at (" << x.x() << ", " << x.y();
    if (dim == 3) os << ", " << x.z();
    os << "), nearest master facet normal (" << n.x() << ", " << n.y();
    if (dim == 3) os << ", " << n.z();
    os << ")): the master side set '" << pair.masterName << "' faces away from or across the slave side set '"
       << pair.slaveName << "'; contact there is not enforced (doc/contact.md, 'Which slave nodes pair')";
    warnings_.push_back(os.str());
  }
}

std::vector<std::string> ContactPairing::takeWarnings() {
  std::vector<std::string> out;
  out.swap(warnings_);
  return out;
}

std::vector<std::string> ContactPairing::neverPairedPairs() const {
  std::vector<std::string> out;
  for (int p = 0; p < topo_.numPairs(); ++p)
    if (size_t(p) >= everPaired_.size() || !everPaired_[p])
      out.push_back("contact pair '" + topo_.pair(p).path + "' (slave '" + topo_.pair(p).slaveName + "', master '" +
                    topo_.pair(p).masterName + "')");
  return out;
}

std::vector<char> ContactPairing::pairedRecord() const {
  std::vector<char> out(topo_.numPairs(), 0);
  for (size_t p = 0; p < out.size() && p < everPaired_.size(); ++p) out[p] = everPaired_[p];
  return out;
}

void ContactPairing::addPairedRecord(const std::vector<char>& record) {
  const size_t pairs = size_t(topo_.numPairs());
  if (record.size() != pairs)
    throw std::invalid_argument("addPairedRecord: " + std::to_string(record.size()) + " entries for " +
                                std::to_string(pairs) + " pairs");
  everPaired_.resize(pairs, 0);
  for (size_t p = 0; p < pairs; ++p)
    if (record[p]) everPaired_[p] = 1;
}

std::array<long, 3> ContactPairing::searchCounters() const {
  std::array<long, 3> c{0, 0, distributedQueries_};
  for (const auto& s : searches_) {
    c[0] += s->trackingQueries();
    c[1] += s->trackingFallbacks();
    c[2] += s->globalQueries();
  }
  return c;
}

// ---- the initial penetration -------------------------------------------------------------

void ContactPairing::checkInitialPenetration(
    const std::vector<std::function<int(const Eigen::VectorXd&)>>& locate,
    const std::function<std::vector<Eigen::VectorXd>(int, int)>& inward) const {
  // doc/contact.md "Which slave nodes pair": a slave node inside the master
  // body that the search does not pair keeps λ = 0 for ever, so the bodies
  // would silently stay overlapped there. A node on the master body's
  // boundary is not inside, but if the slave body next to it is (points
  // towards its elements' centroids), the bodies overlap there all the same:
  // those nodes are reported where no node of the pair is inside.
  // Reference configuration, replicated surfaces and slots. Each rank
  // locates the points in the master elements it holds (all of them with a
  // whole mesh on every rank); the ranks agree per slot on its first point
  // found inside and on the lowest element id containing it, so every rank
  // reaches the same verdict.
  const int dim = topo_.dim();
  const MPI_Comm comm = rawComm(topo_.comm());
  constexpr long long kNone = std::numeric_limits<long long>::max();
  for (size_t p = 0; p < size_t(topo_.numPairs()) && p < locate.size(); ++p) {
    if (!locate[p]) continue;
    const Pair& pair = topo_.pair(int(p));
    // The unpaired slave nodes inside; if there are none, those next to
    // which the slave body is inside (`probe`).
    int first = -1, count = 0, element = -1;
    for (const bool probe : {false, true}) {
      if (first >= 0 || (probe && !inward)) break;
      // Per slot: (its first point inside) · 2^31 + (the element's id).
      std::vector<long long> found(pair.slots.size(), kNone);
      for (size_t i = 0; i < pair.slots.size(); ++i) {
        const int k = pair.slots[i];
        if (slots_[k].paired()) continue;
        const std::vector<Eigen::VectorXd> points =
            probe ? inward(int(p), slots_[k].slaveNode)
                  : std::vector<Eigen::VectorXd>{topo_.referencePosition(slots_[k].slaveNode).head(dim)};
        for (size_t j = 0; j < points.size() && found[i] == kNone; ++j) {
          const int e = locate[p](points[j]);
          if (e >= 0) found[i] = (long long)j << 31 | e;
        }
      }
      if (!found.empty())  // the slots are on every rank: all ranks agree
        MPI_Allreduce(MPI_IN_PLACE, found.data(), int(found.size()), MPI_LONG_LONG, MPI_MIN, comm);
      for (size_t i = 0; i < found.size(); ++i) {
        if (found[i] == kNone) continue;
        if (first < 0) first = pair.slots[i], element = int(found[i] & 0x7fffffff);
        ++count;
      }
    }
    if (first < 0) continue;
    const int node = slots_[first].slaveNode;
    const Eigen::Vector3d xs = topo_.referencePosition(node);
    std::ostringstream where;
    where << "(" << xs.x() << ", " << xs.y();
    if (dim == 3) where << ", " << xs.z();
    where << ")";
    double depth = std::numeric_limits<double>::infinity();
    const std::string why = whyNotPaired(pair, node, depth);
    DDC_THROW(InputError, "contact pair '"
                              << pair.path << "': slave node " << node << " at " << where.str()
                              << " of the slave side set '" << pair.slaveName
                              << "' starts inside the master body (element " << element << "), at depth " << depth
                              << " below the master side set '" << pair.masterName
                              << "', and contact cannot push it out: " << why
                              << " (doc/contact.md, 'Which slave nodes pair')"
                              << (count > 1 ? "; " + std::to_string(count - 1) + " more slave node(s) of this pair likewise"
                                            : std::string())
                              << ". Move the bodies apart so that they at most touch, or overlap by less than half an "
                                 "element, in the reference configuration");
  }
}

std::string ContactPairing::whyNotPaired(const Pair& pair, int node, double& depth) const {
  // Why a slave node is not paired: the nearest point of the whole surface
  // (all facets: a diagnostic, once), then the pairing rules on that facet.
  // In 2-D a facet is a segment of the side set. `depth`: the distance to
  // that nearest point.
  const int dim = topo_.dim();
  const Position reference = [&](int n) { return topo_.referencePosition(n); };
  const Eigen::Vector3d xs = reference(node);
  const char* word = referenceCell(pair.masterType).dim == 1 ? "segment" : "facet";
  auto vec = [&](const Eigen::Vector3d& a) {
    std::ostringstream o;
    const Eigen::Vector3d z = a + Eigen::Vector3d::Zero();  // + 0: no "-0"
    o << "(" << z.x() << ", " << z.y();
    if (dim == 3) o << ", " << z.z();
    o << ")";
    return o.str();
  };
  FacetCandidate nearest;
  nearest.distance = std::numeric_limits<double>::infinity();
  for (int g = 0; g < int(pair.masterFacets.size()); ++g) {
    FacetCandidate c = nearestPoint(pair.masterType, facetPositions(pair, g, reference), xs.head(dim));
    c.facet = g;
    if (c.distance < nearest.distance) nearest = c;
  }
  depth = nearest.distance;
  FacetSearch probe(pair.masterType, {pair.facetNodes(nearest.facet)},
                    std::max(2.0 * nearest.distance, std::numeric_limits<double>::min()));
  probe.update({node}, [&](int n) { return Eigen::VectorXd(reference(n).head(dim)); }, true);
  const Found f = facetPairing(pair, probe, {nearest.facet}, {node}, reference)[0];
  const ContactTopology::Facet& r = pair.masterFacets[nearest.facet];
  std::ostringstream facet, why;
  facet << word << " " << r.id << " (element " << r.element << ")";
  const double limit = kFacingDepthFraction * r.depth;
  const double radius = topo_.options().searchRadius;
  if (nearest.distance > radius) {
    why << "it is farther than the search radius (" << radius << ", Contact/Search Radius) from every master "
        << word;
  } else if (f.pastFreeEnd) {
    why << "its nearest point of the master surface is on the surface's free boundary (" << facet.str() << ")";
  } else if (!(f.slaveNormal.dot(f.normal) < 0.0)) {
    why << "its outward normal " << vec(f.slaveNormal) << " does not face the outward normal " << vec(f.normal)
        << " of its nearest master " << facet.str();
  } else {
    why << "it lies " << -f.gap << " behind its nearest master " << facet.str() << ", not less than half the depth of that "
        << word << "'s element (" << limit << " = " << kFacingDepthFraction << " x " << r.depth << ")";
  }
  return why.str();
}

// ---- step control ----------------------------------------------------------------------------

bool ContactPairing::restoreSlots(const std::vector<ContactSlot>& saved) {
  DDC_CHECK(saved.size() == slots_.size(), "restoreSlots: " << saved.size() << " slots for " << slots_.size());
  bool changed = false;
  for (size_t k = 0; k < slots_.size(); ++k)
    if (saved[k].segment != slots_[k].segment) changed = true;
  slots_ = saved;
  if (changed && topo_.hasDofs()) buildEvaluationMaps();
  return changed;
}

// ---- queries -------------------------------------------------------------------------------------

bool ContactPairing::fullyPrescribed(int k) const {
  const ContactSlot& s = slots_[k];
  if (!s.paired()) return false;
  if (!topo_.nodePrescribed(s.slaveNode)) return false;
  for (int a = 0; a < s.numMaster; ++a)
    if (!topo_.nodePrescribed(s.master[a])) return false;
  return true;
}

}  // namespace ddc
