// Point location in a body's elements; the rules are in the header.
#include "DDC_BodyLocator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include "DDC_Error.hpp"
#include "DDC_Mesh.hpp"

namespace ddc {

BodyLocator::BodyLocator(const Mesh& mesh, int body)
    : mesh_(mesh), firstElement_(mesh.body(body).firstElement), numElements_(mesh.body(body).numElements) {
  std::vector<std::array<double, 4>> boxes(numElements_);  // xmin, ymin, xmax, ymax
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  double meanSize = 0.0;
  for (int i = 0; i < numElements_; ++i) {
    auto& b = boxes[i];
    b = {lo[0], lo[1], hi[0], hi[1]};
    const int* nodes = mesh_.elementNodes(firstElement_ + i);
    for (int a = 0; a < 4; ++a) {
      const auto& x = mesh_.coord(nodes[a]);
      b[0] = std::min(b[0], x[0]), b[1] = std::min(b[1], x[1]);
      b[2] = std::max(b[2], x[0]), b[3] = std::max(b[3], x[1]);
    }
    lo[0] = std::min(lo[0], b[0]), lo[1] = std::min(lo[1], b[1]);
    hi[0] = std::max(hi[0], b[2]), hi[1] = std::max(hi[1], b[3]);
    meanSize += std::max(b[2] - b[0], b[3] - b[1]) / numElements_;
  }
  if (numElements_ == 0) return;
  // Boundary edges: corner edges that only one element of the body has.
  std::map<std::pair<int, int>, int> edgeCount;
  auto edgeKey = [&](int e, int a) {
    const int* nodes = mesh_.elementNodes(e);
    const auto& side = referenceCell(mesh_.elementType(e)).facets[a];
    const int p = nodes[side.nodes[0]], q = nodes[side.nodes[1]];
    return std::make_pair(std::min(p, q), std::max(p, q));
  };
  for (int i = 0; i < numElements_; ++i)
    for (int a = 0; a < 4; ++a) ++edgeCount[edgeKey(firstElement_ + i, a)];
  boundaryEdge_.resize(numElements_);
  for (int i = 0; i < numElements_; ++i)
    for (int a = 0; a < 4; ++a) boundaryEdge_[i][a] = edgeCount[edgeKey(firstElement_ + i, a)] == 1;
  // Bins about one element wide (at most ~1e6 of them over the body's box):
  // a query meets O(1) elements.
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  h_ = std::max({meanSize, extent / 1000.0, std::numeric_limits<double>::min()});
  x0_ = lo[0];
  y0_ = lo[1];
  nx_ = std::max(1LL, static_cast<long long>(std::ceil((hi[0] - lo[0]) / h_)));
  ny_ = std::max(1LL, static_cast<long long>(std::ceil((hi[1] - lo[1]) / h_)));
  // Each element goes into every bin its box, grown by the margin, touches: a
  // point within the margin of an element's edge finds that element.
  for (int i = 0; i < numElements_; ++i) {
    const auto& b = boxes[i];
    const double grow = kInsideMargin * std::max(b[2] - b[0], b[3] - b[1]);
    for (long long ix = cell(b[0] - grow, x0_, nx_); ix <= cell(b[2] + grow, x0_, nx_); ++ix)
      for (long long iy = cell(b[1] - grow, y0_, ny_); iy <= cell(b[3] + grow, y0_, ny_); ++iy)
        bins_.emplace_back(ix * ny_ + iy, firstElement_ + i);
  }
  std::sort(bins_.begin(), bins_.end());
}

long long BodyLocator::cell(double v, double origin, long long n) const {
  const double c = std::floor((v - origin) / h_);
  return std::min(n - 1, static_cast<long long>(std::max(0.0, c)));
}

bool BodyLocator::inClosure(int e, const Eigen::Vector2d& x) const {
  const int* nodes = mesh_.elementNodes(e);
  for (int a = 0; a < 4; ++a) {
    const auto& side = referenceCell(mesh_.elementType(e)).facets[a];
    const auto& p = mesh_.coord(nodes[side.nodes[0]]);
    const auto& q = mesh_.coord(nodes[side.nodes[1]]);
    const Eigen::Vector2d t(q[0] - p[0], q[1] - p[1]), d(x.x() - p[0], x.y() - p[1]);
    // Not right of the edge by more than the margin: t × d >= −margin · |t|².
    if (!(t.x() * d.y() - t.y() * d.x() >= -kInsideMargin * t.squaredNorm())) return false;
  }
  return true;
}

bool BodyLocator::onBoundaryEdge(int e, int a, const Eigen::Vector2d& x) const {
  if (!boundaryEdge_[e - firstElement_][a]) return false;
  const int* nodes = mesh_.elementNodes(e);
  const auto& side = referenceCell(mesh_.elementType(e)).facets[a];
  const auto& p = mesh_.coord(nodes[side.nodes[0]]);
  const auto& q = mesh_.coord(nodes[side.nodes[1]]);
  const Eigen::Vector2d t(q[0] - p[0], q[1] - p[1]), d(x.x() - p[0], x.y() - p[1]);
  const double xi = std::min(1.0, std::max(0.0, d.dot(t) / t.squaredNorm()));
  return (d - xi * t).norm() <= kInsideMargin * t.norm();
}

int BodyLocator::elementContaining(const Eigen::Vector2d& x) const {
  if (bins_.empty() || !x.allFinite()) return -1;
  const double fx = (x.x() - x0_) / h_, fy = (x.y() - y0_) / h_;
  if (fx < -1.0 || fy < -1.0 || fx > double(nx_) + 1.0 || fy > double(ny_) + 1.0) return -1;
  const long long key = cell(x.x(), x0_, nx_) * ny_ + cell(x.y(), y0_, ny_);
  auto it = std::lower_bound(bins_.begin(), bins_.end(), std::make_pair(key, std::numeric_limits<int>::min()));
  int found = -1;
  for (; it != bins_.end() && it->first == key; ++it) {
    const int e = it->second;
    if (!inClosure(e, x)) continue;
    for (int a = 0; a < 4; ++a)
      if (onBoundaryEdge(e, a, x)) return -1;  // on the body's boundary: not inside
    if (found < 0) found = e;  // bins are sorted by element: the lowest index
  }
  return found;
}

}  // namespace ddc
