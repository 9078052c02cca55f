// Contact search and tracking on straight segments, the test reference of
// the facet search; the rules are documented in the header.
#include "DDC_ContactSearch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "DDC_Error.hpp"
#include "DDC_Mesh.hpp"

namespace ddc {

// ---------------------------------------------------------------------------
// MasterSurface

MasterSurface::MasterSurface(std::vector<std::array<int, 2>> segments) : segments_(std::move(segments)) {
  DDC_INPUT_REQUIRE(!segments_.empty(), "contact master surface: no segments");
  const int n = numSegments();
  for (int k = 0; k < n; ++k) {
    const auto& s = segments_[k];
    DDC_INPUT_REQUIRE(s[0] >= 0 && s[1] >= 0,
                      "contact master surface: segment " << k << " has a negative node id (" << s[0] << ", " << s[1]
                                                         << ")");
    DDC_INPUT_REQUIRE(s[0] != s[1], "contact master surface: segment " << k << " starts and ends at node " << s[0]);
    nodes_.push_back(s[0]);
    nodes_.push_back(s[1]);
  }
  std::sort(nodes_.begin(), nodes_.end());
  nodes_.erase(std::unique(nodes_.begin(), nodes_.end()), nodes_.end());

  // Along a consistently oriented simple chain every node is the start (x1)
  // of at most one segment and the end (x2) of at most one segment.
  std::vector<int> startsAt(nodes_.size(), -1), endsAt(nodes_.size(), -1);
  for (int k = 0; k < n; ++k) {
    const int a = localNode(segments_[k][0]), b = localNode(segments_[k][1]);
    DDC_INPUT_REQUIRE(startsAt[a] < 0, "contact master surface: node "
                                           << segments_[k][0] << " starts segments " << startsAt[a] << " and " << k
                                           << "; the surface must be simple chains oriented with the body on the "
                                              "left (no branches, pinches, repeated or reversed segments)");
    DDC_INPUT_REQUIRE(endsAt[b] < 0, "contact master surface: node "
                                         << segments_[k][1] << " ends segments " << endsAt[b] << " and " << k
                                         << "; the surface must be simple chains oriented with the body on the "
                                            "left (no branches, pinches, repeated or reversed segments)");
    startsAt[a] = k;
    endsAt[b] = k;
  }
  neighbours_.resize(n);
  for (int k = 0; k < n; ++k) {
    neighbours_[k][0] = endsAt[localNode(segments_[k][0])];    // the segment ending where k starts
    neighbours_[k][1] = startsAt[localNode(segments_[k][1])];  // the segment starting where k ends
  }
}

int MasterSurface::localNode(int node) const {
  auto it = std::lower_bound(nodes_.begin(), nodes_.end(), node);
  return it != nodes_.end() && *it == node ? static_cast<int>(it - nodes_.begin()) : -1;
}

// ---------------------------------------------------------------------------
// ContactSearch

/// Projection of one slave onto one segment, and its ordering key.
struct ContactSearch::Eval {
  int segment = -1;
  double d2 = std::numeric_limits<double>::infinity();  // squared distance to the clamped point
  bool outside = false;                                  // ξ < 0 or ξ > 1
  double xi = 0.0;                                       // unclamped
  Eigen::Vector2d point = Eigen::Vector2d::Zero();

  /// The total order of the header: (d², outside, segment index).
  bool operator<(const Eval& o) const {
    if (d2 != o.d2) return d2 < o.d2;
    if (outside != o.outside) return !outside;
    return segment < o.segment;
  }
};

ContactSearch::ContactSearch(MasterSurface master, std::vector<int> slaveNodes, double searchRadius,
                             int maxTrackingSteps)
    : master_(std::move(master)), slaves_(std::move(slaveNodes)), radius_(searchRadius), maxSteps_(maxTrackingSteps) {
  DDC_INPUT_REQUIRE(std::isfinite(radius_) && radius_ > 0.0,
                    "contact search: the search radius must be positive and finite, got " << radius_);
  DDC_INPUT_REQUIRE(maxSteps_ >= 0, "contact search: the tracking step limit must be >= 0, got " << maxSteps_);
  std::vector<int> sorted = slaves_;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    DDC_INPUT_REQUIRE(sorted[i] >= 0, "contact search: negative slave node id " << sorted[i]);
    DDC_INPUT_REQUIRE(i == 0 || sorted[i] != sorted[i - 1], "contact search: slave node " << sorted[i]
                                                                                          << " is listed twice");
    DDC_INPUT_REQUIRE(master_.localNode(sorted[i]) < 0,
                      "contact search: slave node " << sorted[i] << " is also a node of the master surface");
  }
  candidates_.resize(slaves_.size());
  x_.resize(master_.nodes().size());
  for (int k = 0; k < master_.numSegments(); ++k)
    local_.push_back({master_.localNode(master_.segment(k)[0]), master_.localNode(master_.segment(k)[1])});
}

ContactSearch::ContactSearch(MasterSurface master, std::vector<int> slaveNodes, double searchRadius, FacingRule rule,
                             int maxTrackingSteps)
    : ContactSearch(std::move(master), std::move(slaveNodes), searchRadius, maxTrackingSteps) {
  DDC_INPUT_REQUIRE(static_cast<int>(rule.masterDepths.size()) == master_.numSegments(),
                    "contact search: " << rule.masterDepths.size() << " master element depths for "
                                       << master_.numSegments() << " master segments");
  for (std::size_t k = 0; k < rule.masterDepths.size(); ++k)
    DDC_INPUT_REQUIRE(std::isfinite(rule.masterDepths[k]) && rule.masterDepths[k] > 0.0,
                      "contact search: the element of master segment " << k << " has depth " << rule.masterDepths[k]
                                                                        << "; it must be positive");
  // Slave segments at each slave node (a node has one or two on a simple
  // surface; more are accepted, their normals are summed alike).
  std::vector<int> order(slaves_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return slaves_[a] < slaves_[b]; });
  auto slaveIndex = [&](int node) {
    auto it = std::lower_bound(order.begin(), order.end(), node, [&](int i, int n) { return slaves_[i] < n; });
    return it != order.end() && slaves_[*it] == node ? *it : -1;
  };
  slaveSegmentsAt_.assign(slaves_.size(), {});
  for (std::size_t g = 0; g < rule.slaveSegments.size(); ++g) {
    const auto& sg = rule.slaveSegments[g];
    DDC_INPUT_REQUIRE(sg[0] >= 0 && sg[1] >= 0 && sg[0] != sg[1],
                      "contact search: slave segment " << g << " (nodes " << sg[0] << ", " << sg[1]
                                                       << ") must join two distinct nodes");
    for (int n : sg) {
      const int i = slaveIndex(n);
      if (i >= 0) slaveSegmentsAt_[i].push_back(static_cast<int>(g));
    }
  }
  for (std::size_t i = 0; i < slaves_.size(); ++i)
    DDC_INPUT_REQUIRE(!slaveSegmentsAt_[i].empty(),
                      "contact search: slave node " << slaves_[i] << " is on no slave segment (the facing rule needs "
                                                       "its outward normal)");
  rule_ = std::move(rule);
  hasRule_ = true;
}

double ContactSearch::penetrationLimit(int k) const {
  return hasRule_ ? kFacingDepthFraction * rule_.masterDepths[k] : std::numeric_limits<double>::infinity();
}

Eigen::Vector2d ContactSearch::slaveNormal(std::size_t i,
                                           const std::function<Eigen::Vector2d(int node)>& currentPosition) const {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (int g : slaveSegmentsAt_[i]) {
    const auto& sg = rule_.slaveSegments[g];
    const Eigen::Vector2d t = currentPosition(sg[1]) - currentPosition(sg[0]);
    const double len = t.norm();
    if (!(len > 0.0) || !std::isfinite(len))
      DDC_THROW(SolverError, "contact search: slave segment (nodes " << sg[0] << ", " << sg[1]
                                                                     << ") has zero or non-finite length");
    sum += Eigen::Vector2d(t.y(), -t.x()) / len;  // the unit outward normal (body on the left)
  }
  const double n = sum.norm();
  // Normals that cancel (a fold of the slave surface) give no direction: such
  // a node faces nothing.
  return n > 0.0 ? Eigen::Vector2d(sum / n) : Eigen::Vector2d::Zero();
}

ContactRejection facingVerdict(const Eigen::Vector2d& slaveNormal, const Eigen::Vector2d& masterNormal, double gap,
                               double penetrationLimit) {
  // z = 0 adds exact zeros to the dot product: the same verdict.
  return facingVerdict(Eigen::Vector3d(slaveNormal.x(), slaveNormal.y(), 0.0),
                       Eigen::Vector3d(masterNormal.x(), masterNormal.y(), 0.0), gap, penetrationLimit);
}

ContactSearch::Eval ContactSearch::evaluate(int k, const Eigen::Vector2d& xs) {
  ++counters_.projections;
  const Eigen::Vector2d& x1 = x_[local_[k][0]];
  const Eigen::Vector2d& x2 = x_[local_[k][1]];
  const Eigen::Vector2d t = x2 - x1;
  Eval e;
  e.segment = k;
  e.xi = (xs - x1).dot(t) / t.squaredNorm();
  // Clamped points are the node coordinates themselves, so the two segments
  // meeting at a node tie exactly there. Within kEndTolerance of an end the
  // slave counts as inside (header).
  if (e.xi <= 0.0) {
    e.point = x1;
    e.outside = e.xi < -kEndTolerance;
  } else if (e.xi >= 1.0) {
    e.point = x2;
    e.outside = e.xi > 1.0 + kEndTolerance;
  } else {
    e.point = x1 + e.xi * t;
  }
  e.d2 = (xs - e.point).squaredNorm();
  return e;
}

long long ContactSearch::cellIndex(double v, double origin) const {
  const double c = std::floor((v - origin) / h_);
  return static_cast<long long>(std::max(0.0, c));
}

long long ContactSearch::cellKey(long long ix, long long iy) const {
  return std::min(ix, nx_ - 1) * ny_ + std::min(iy, ny_ - 1);
}

void ContactSearch::buildGrid() {
  ++counters_.gridBuilds;
  const int n = master_.numSegments();
  // Inflate a little beyond the radius so rounding in the bounding boxes can
  // never drop a segment whose computed distance is <= radius.
  const double inflate = radius_ * (1.0 + 1e-8);
  std::vector<std::array<double, 4>> boxes(n);  // xmin, ymin, xmax, ymax (inflated)
  double meanLength = 0.0, maxExtent = 0.0;
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d& a = x_[local_[k][0]];
    const Eigen::Vector2d& b = x_[local_[k][1]];
    meanLength += (b - a).norm() / n;
    maxExtent = std::max({maxExtent, std::abs(b.x() - a.x()), std::abs(b.y() - a.y())});
    auto& box = boxes[k];
    box = {std::min(a.x(), b.x()) - inflate, std::min(a.y(), b.y()) - inflate, std::max(a.x(), b.x()) + inflate,
           std::max(a.y(), b.y()) + inflate};
    lo[0] = std::min(lo[0], box[0]);
    lo[1] = std::min(lo[1], box[1]);
    hi[0] = std::max(hi[0], box[2]);
    hi[1] = std::max(hi[1], box[3]);
  }
  // Bins about one segment (or one radius) wide: a query then meets O(1)
  // segments per bin; a long segment among short ones covers at most ~100 bins.
  h_ = std::max({meanLength, radius_, maxExtent / 8.0});
  x0_ = lo[0];
  y0_ = lo[1];
  nx_ = std::max(1LL, static_cast<long long>(std::ceil((hi[0] - lo[0]) / h_)));
  ny_ = std::max(1LL, static_cast<long long>(std::ceil((hi[1] - lo[1]) / h_)));
  xHi_ = hi[0];
  yHi_ = hi[1];

  bins_.clear();
  for (int k = 0; k < n; ++k) {
    const auto& box = boxes[k];
    const long long i0 = std::min(cellIndex(box[0], x0_), nx_ - 1), i1 = std::min(cellIndex(box[2], x0_), nx_ - 1);
    const long long j0 = std::min(cellIndex(box[1], y0_), ny_ - 1), j1 = std::min(cellIndex(box[3], y0_), ny_ - 1);
    for (long long i = i0; i <= i1; ++i)
      for (long long j = j0; j <= j1; ++j) bins_.emplace_back(cellKey(i, j), k);
  }
  std::sort(bins_.begin(), bins_.end());
  gridValid_ = true;
}

ContactSearch::Eval ContactSearch::globalQuery(const Eigen::Vector2d& xs) {
  ++counters_.globalSearches;
  if (!gridValid_) buildGrid();
  // Every point within the radius of a segment lies in that segment's
  // inflated box, hence inside the grid box and in a bin the segment is in.
  if (!(xs.x() >= x0_ && xs.x() <= xHi_ && xs.y() >= y0_ && xs.y() <= yHi_)) return Eval();
  const long long key = cellKey(cellIndex(xs.x(), x0_), cellIndex(xs.y(), y0_));
  auto first = std::lower_bound(bins_.begin(), bins_.end(), std::make_pair(key, std::numeric_limits<int>::min()));
  Eval best;
  const double r2 = radius_ * radius_;
  for (auto it = first; it != bins_.end() && it->first == key; ++it) {
    const Eval e = evaluate(it->second, xs);
    if (e.d2 <= r2 && e < best) best = e;
  }
  return best;  // segment -1 if none within the radius
}

ContactSearch::Eval ContactSearch::trackingQuery(int start, const Eigen::Vector2d& xs) {
  ++counters_.trackingCalls;
  Eval cur = evaluate(start, xs);
  for (int steps = 0;; ++steps) {
    // Descend along the surface on the key (d², outside, index): the keys
    // strictly decrease, so the walk cannot cycle, even on a closed loop.
    Eval next = cur;
    for (int end = 0; end < 2; ++end) {
      const int j = master_.neighbour(cur.segment, end);
      if (j < 0) continue;
      const Eval e = evaluate(j, xs);
      if (e < next) next = e;
    }
    if (next.segment == cur.segment) break;
    if (steps + 1 > maxSteps_) return Eval();  // step limit exceeded
    cur = next;
  }
  // A local minimum past a free end: the walk would leave the surface.
  if (cur.outside && master_.neighbour(cur.segment, cur.xi < 0.0 ? 0 : 1) < 0) return Eval();
  if (!(cur.d2 <= radius_ * radius_)) return Eval();
  return cur;  // segment -1: tracking failed
}

void ContactSearch::update(const std::function<Eigen::Vector2d(int node)>& currentPosition, bool forceGlobal) {
  const auto& nodes = master_.nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i) x_[i] = currentPosition(nodes[i]);
  for (int k = 0; k < master_.numSegments(); ++k) {
    const auto& s = master_.segment(k);
    const double len2 = (x_[local_[k][1]] - x_[local_[k][0]]).squaredNorm();
    if (!(len2 > 0.0) || !std::isfinite(len2))
      DDC_THROW(SolverError, "contact search: master segment " << k << " (nodes " << s[0] << ", " << s[1]
                                                               << ") has zero or non-finite length");
  }
  gridValid_ = false;

  for (std::size_t i = 0; i < slaves_.size(); ++i) {
    const Eigen::Vector2d xs = currentPosition(slaves_[i]);
    if (!xs.allFinite())
      DDC_THROW(SolverError, "contact search: slave node " << slaves_[i] << " has a non-finite position");
    ContactCandidate& c = candidates_[i];
    Eval e;
    bool tracked = false;
    if (!forceGlobal && c.segment >= 0) {
      e = trackingQuery(c.segment, xs);
      tracked = e.segment >= 0;
      if (!tracked) ++counters_.trackingFallbacks;
    }
    if (!tracked) e = globalQuery(xs);

    c = ContactCandidate();
    const int k = e.segment;
    if (k < 0) continue;
    const Eigen::Vector2d& x1 = x_[local_[k][0]];
    const Eigen::Vector2d t = x_[local_[k][1]] - x1;
    c.segment = k;
    c.xi = std::min(1.0, std::max(0.0, e.xi));
    c.normal = Eigen::Vector2d(t.y(), -t.x()) / t.norm();
    c.gap = c.normal.dot(xs - x1);
    c.point = e.point;
    c.distance = std::sqrt(e.d2);
    c.viaCorner = e.outside;
    if (hasRule_) {
      // The facing rule acts on the nearest segment only (header): a slave
      // whose nearest segment fails it is not paired with another one.
      c.slaveNormal = slaveNormal(i, currentPosition);
      c.rejection = facingVerdict(c.slaveNormal, c.normal, c.gap, penetrationLimit(k));
      if (c.rejection != ContactRejection::None) {
        c.rejectedSegment = k;
        c.segment = -1;
      }
    }
  }
}

// ---------------------------------------------------------------------------

std::vector<std::array<int, 2>> masterSegmentsFromSideSet(const Mesh& mesh, const std::string& sideSet) {
  const auto& sides = mesh.sideSet(sideSet);
  std::vector<std::array<int, 2>> out;
  out.reserve(sides.size());
  for (const Segment& s : sides) {
    DDC_INPUT_REQUIRE(s.numNodes == 2, "side set '" << sideSet << "': contact surfaces must be Quad4 sides for now (side "
                                                    << s.localSide << " of element " << s.element << " has "
                                                    << s.numNodes << " nodes)");
    out.push_back({s.nodes[0], s.nodes[1]});
  }
  return out;
}

std::vector<double> masterElementDepths(const Mesh& mesh, const std::string& sideSet) {
  const auto segments = masterSegmentsFromSideSet(mesh, sideSet);  // checks the set and its sides
  const auto& sides = mesh.sideSet(sideSet);
  std::vector<double> depth(sides.size(), 0.0);
  for (std::size_t k = 0; k < sides.size(); ++k) {
    const auto& a = mesh.coord(segments[k][0]);
    const auto& b = mesh.coord(segments[k][1]);
    const Eigen::Vector2d t(b[0] - a[0], b[1] - a[1]);
    const Eigen::Vector2d n = Eigen::Vector2d(t.y(), -t.x()).normalized();
    const int e = sides[k].element;
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
      const auto& x = mesh.coord(mesh.elementNodes(e)[i]);
      depth[k] = std::max(depth[k], -n.dot(Eigen::Vector2d(x[0] - a[0], x[1] - a[1])));
    }
    DDC_INPUT_REQUIRE(depth[k] > 0.0, "side set '" << sideSet << "': element " << e
                                                   << " has no extent behind its side " << sides[k].localSide
                                                   << " (degenerate element)");
  }
  return depth;
}

}  // namespace ddc
