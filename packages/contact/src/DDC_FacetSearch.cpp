// Facet search and tracking (see DDC_FacetSearch.hpp).
#include "DDC_FacetSearch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ddc {

ContactRejection facingVerdict(const Eigen::Vector3d& slaveNormal, const Eigen::Vector3d& masterNormal, double gap,
                               double penetrationLimit) {
  if (!(slaveNormal.dot(masterNormal) < 0.0)) return ContactRejection::NotFacing;
  if (gap < 0.0 && !(-gap < penetrationLimit)) return ContactRejection::TooDeep;
  return ContactRejection::None;
}

namespace {

Eigen::Vector3d lift(const Eigen::VectorXd& v) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < v.size() && k < 3; ++k) p[k] = v[k];
  return p;
}

/// The key of the pairing rule: nearest, then interior, then lowest index.
bool better(const FacetCandidate& a, const FacetCandidate& b) {
  if (a.facet < 0) return false;
  if (b.facet < 0) return true;
  if (a.distance != b.distance) return a.distance < b.distance;
  const bool ai = a.kind == FacetPointKind::Interior, bi = b.kind == FacetPointKind::Interior;
  if (ai != bi) return ai;
  return a.facet < b.facet;
}

}  // namespace

FacetCandidate nearestPoint(CellType facet, const Eigen::MatrixXd& nodes, const Eigen::VectorXd& xs) {
  const FacetProjection pr = projectOntoFacet(facet, nodes, xs);
  FacetCandidate c;
  c.xi = pr.xi;
  const Eigen::Vector3d s = lift(xs);
  if (pr.converged && pr.inside) {
    c.kind = FacetPointKind::Interior;
    c.point = pr.point;
    c.normal = pr.normal;
    c.gap = pr.gap;
    c.distance = (s - c.point).norm();
    return c;
  }
  // The boundary polyline: the end nodes of a segment (2-D), the chords
  // corner - mid-edge - corner of each edge of a face (3-D).
  const ReferenceCell& ref = referenceCell(facet);
  std::vector<std::pair<int, int>> chords;
  if (ref.dim == 1) {
    chords = {{0, 0}, {1, 1}};
  } else {
    for (const auto& e : ref.edges) {
      if (e.middle >= 0)
        chords.insert(chords.end(), {{e.start, e.middle}, {e.middle, e.end}});
      else
        chords.emplace_back(e.start, e.end);
    }
  }
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [i, j] : chords) {
    const Eigen::Vector3d a = lift(nodes.row(i).transpose()), b = lift(nodes.row(j).transpose());
    const Eigen::Vector3d d = b - a;
    const double len2 = d.squaredNorm();
    double t = len2 > 0 ? (s - a).dot(d) / len2 : 0.0;
    t = std::min(1.0, std::max(0.0, t));
    const Eigen::Vector3d p = a + t * d;
    const double dist = (s - p).norm();
    if (dist < best) {
      best = dist;
      c.point = p;
      c.kind = (t > 0.0 && t < 1.0) ? FacetPointKind::Edge : FacetPointKind::Vertex;
      for (int al = 0; al < 2; ++al) c.xi[al] = (1.0 - t) * ref.nodes[i][al] + t * ref.nodes[j][al];
    }
  }
  c.distance = best;
  c.gap = best;
  c.normal = best > 0 ? Eigen::Vector3d((s - c.point) / best) : pr.normal;
  return c;
}

FacetSearch::FacetSearch(CellType facet, std::vector<std::vector<int>> facets, double radius, int maxTrackingSteps)
    : type_(facet), dim_(facetSpaceDimension(facet)), facets_(std::move(facets)), radius_(radius),
      maxSteps_(maxTrackingSteps) {
  const int m = referenceCell(facet).numNodes;
  if (facets_.empty()) throw std::invalid_argument("FacetSearch: no facets");
  if (!(radius_ > 0.0) || !std::isfinite(radius_))
    throw std::invalid_argument("FacetSearch: the search radius must be positive and finite, got " +
                                std::to_string(radius_));
  for (size_t f = 0; f < facets_.size(); ++f)
    if (int(facets_[f].size()) != m)
      throw std::invalid_argument("FacetSearch: facet " + std::to_string(f) + " has " +
                                  std::to_string(facets_[f].size()) + " nodes, a " + cellTypeName(facet) + " has " +
                                  std::to_string(m));
  // Neighbours: facets sharing a node.
  std::vector<std::pair<int, int>> nodeFacet;
  for (size_t f = 0; f < facets_.size(); ++f)
    for (int n : facets_[f]) nodeFacet.emplace_back(n, int(f));
  std::sort(nodeFacet.begin(), nodeFacet.end());
  neighbours_.assign(facets_.size(), {});
  for (size_t a = 0; a < nodeFacet.size();) {
    size_t b = a;
    while (b < nodeFacet.size() && nodeFacet[b].first == nodeFacet[a].first) ++b;
    for (size_t i = a; i < b; ++i)
      for (size_t j = a; j < b; ++j)
        if (i != j) neighbours_[nodeFacet[i].second].push_back(nodeFacet[j].second);
    a = b;
  }
  for (auto& nb : neighbours_) {
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  }
}

FacetCandidate FacetSearch::evaluate(int f, const Eigen::VectorXd& xs) const {
  const auto& nodes = facets_[f];
  Eigen::MatrixXd x(nodes.size(), dim_);
  for (size_t i = 0; i < nodes.size(); ++i) x.row(i) = position_(nodes[i]).head(dim_).transpose();
  FacetCandidate c = nearestPoint(type_, x, xs);
  c.facet = f;
  return c;
}

long long FacetSearch::key(long long i, long long j, long long k) const { return (i * n_[1] + j) * n_[2] + k; }

void FacetSearch::buildGrid() {
  std::vector<Eigen::Vector3d> lo(facets_.size()), hi(facets_.size());
  Eigen::Vector3d gl = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), gh = -gl;
  double size = 0.0;
  for (size_t f = 0; f < facets_.size(); ++f) {
    lo[f] = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    hi[f] = -lo[f];
    for (int n : facets_[f]) {
      const Eigen::Vector3d p = lift(position_(n));
      lo[f] = lo[f].cwiseMin(p), hi[f] = hi[f].cwiseMax(p);
    }
    size += (hi[f] - lo[f]).norm();
    lo[f].array() -= radius_, hi[f].array() += radius_;
    gl = gl.cwiseMin(lo[f]), gh = gh.cwiseMax(hi[f]);
  }
  h_ = std::max(size / double(facets_.size()), radius_);
  origin_ = gl;
  for (int k = 0; k < 3; ++k) n_[k] = std::max(1LL, (long long)(std::floor((gh[k] - gl[k]) / h_)) + 1);
  bins_.clear();
  for (size_t f = 0; f < facets_.size(); ++f) {
    long long a[3], b[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = (long long)(std::floor((lo[f][k] - origin_[k]) / h_));
      b[k] = std::min(n_[k] - 1, (long long)(std::floor((hi[f][k] - origin_[k]) / h_)));
    }
    for (long long i = a[0]; i <= b[0]; ++i)
      for (long long j = a[1]; j <= b[1]; ++j)
        for (long long k = a[2]; k <= b[2]; ++k) bins_.emplace_back(key(i, j, k), int(f));
  }
  std::sort(bins_.begin(), bins_.end());
}

FacetCandidate FacetSearch::globalQuery(const Eigen::VectorXd& xs) {
  ++globalQueries_;
  FacetCandidate best;
  const Eigen::Vector3d s = lift(xs);
  long long c[3];
  for (int k = 0; k < 3; ++k) {
    c[k] = (long long)(std::floor((s[k] - origin_[k]) / h_));
    if (c[k] < 0 || c[k] >= n_[k]) return best;  // outside every inflated box
  }
  const long long kk = key(c[0], c[1], c[2]);
  auto it = std::lower_bound(bins_.begin(), bins_.end(), std::make_pair(kk, -1));
  for (; it != bins_.end() && it->first == kk; ++it) {
    const FacetCandidate cand = evaluate(it->second, xs);
    if (cand.distance <= radius_ && better(cand, best)) best = cand;
  }
  return best;
}

void FacetSearch::update(const std::vector<int>& slaves, const std::function<Eigen::VectorXd(int)>& position,
                         bool forceGlobal) {
  position_ = position;
  if (previous_.size() != slaves.size()) previous_.assign(slaves.size(), -1);
  candidates_.assign(slaves.size(), FacetCandidate());
  bool gridBuilt = false;
  auto global = [&](const Eigen::VectorXd& xs) {
    if (!gridBuilt) buildGrid(), gridBuilt = true;
    return globalQuery(xs);
  };
  for (size_t i = 0; i < slaves.size(); ++i) {
    const Eigen::VectorXd xs = position(slaves[i]).head(dim_);
    FacetCandidate c;
    if (!forceGlobal && previous_[i] >= 0) {
      ++trackingQueries_;
      c = evaluate(previous_[i], xs);
      int steps = 0;
      for (; steps <= maxSteps_; ++steps) {
        FacetCandidate next = c;
        for (int nb : neighbours_[c.facet]) {
          const FacetCandidate cand = evaluate(nb, xs);
          if (better(cand, next)) next = cand;
        }
        if (next.facet == c.facet) break;
        c = next;
      }
      if (steps > maxSteps_ || c.distance > radius_) {
        ++trackingFallbacks_;
        c = global(xs);
      }
    } else {
      c = global(xs);
    }
    candidates_[i] = c;
    previous_[i] = c.facet;
  }
}

}  // namespace ddc
