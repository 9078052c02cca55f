// Point location in a body's elements; the rules are in the header.
#include "DDC_BodyLocator.hpp"

#include "DDC_MpiRecords.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_Mesh.hpp"

namespace ddc {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Largest extent of a box (lower corner in b[0..2], upper in b[3..5]) over
/// its first `dim` axes.
double largestExtent(const std::array<double, 6>& b, int dim) {
  double s = b[3] - b[0];
  for (int d = 1; d < dim; ++d) s = std::max(s, b[3 + d] - b[d]);
  return s;
}

/// Distance from x to the segment p–q.
double segmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& x) {
  const Eigen::Vector3d t = q - p, d = x - p;
  const double xi = std::min(1.0, std::max(0.0, d.dot(t) / t.squaredNorm()));
  return (d - xi * t).norm();
}

/// Distance from x to the closed triangle t: to its plane if x projects into
/// the triangle, else to the nearest edge.
double triangleDistance(const Eigen::Vector3d* t, const Eigen::Vector3d& x) {
  const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
  bool over = true;
  for (int k = 0; k < 3; ++k) over = over && (t[(k + 1) % 3] - t[k]).cross(x - t[k]).dot(n) >= 0.0;
  if (over) return std::abs(n.dot(x - t[0])) / n.norm();
  return std::min({segmentDistance(t[0], t[1], x), segmentDistance(t[1], t[2], x), segmentDistance(t[2], t[0], x)});
}

/// Solid angle of triangle t seen from x, positive if t runs counter-clockwise
/// seen from x (from inside for an outward face); Van Oosterom & Strackee,
/// IEEE Trans. Biomed. Eng. 30 (1983) 125. Well-conditioned unless x is
/// within round-off of the triangle, which the margin test handles first.
double solidAngle(const Eigen::Vector3d* t, const Eigen::Vector3d& x) {
  const Eigen::Vector3d a = t[0] - x, b = t[1] - x, c = t[2] - x;
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  return 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
}

/// A point of dimension `pointDim` was given for a body of the other one.
[[noreturn]] void throwWrongDimension(const Mesh& mesh, int body, int pointDim) {
  DDC_THROW(std::invalid_argument, "BodyLocator: a " << pointDim << "-D point for body '" << mesh.body(body).name
                                                     << "', which is " << mesh.dim() << "-D; pass an Eigen::Vector"
                                                     << mesh.dim() << "d");
}

}  // namespace

BodyLocator::BodyLocator(const Mesh& mesh, int body, MPI_Comm comm)
    : mesh_(mesh),
      body_(body),
      dim_(mesh.dim()),
      numFacets_(static_cast<int>(referenceCell(mesh.body(body).cellType).facets.size())),
      firstElement_(mesh.body(body).firstElement),
      numElements_(mesh.body(body).numElements) {
  const int numCorners = referenceCell(mesh.body(body).cellType).numCorners;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::array<double, 6>> boxes(numElements_);  // lower corner, upper corner
  std::array<double, 6> all = {inf, inf, inf, -inf, -inf, -inf};
  double meanSize = 0.0;
  for (int i = 0; i < numElements_; ++i) {
    auto& b = boxes[i];
    b = {inf, inf, inf, -inf, -inf, -inf};
    const int* nodes = mesh_.elementNodes(firstElement_ + i);
    for (int a = 0; a < numCorners; ++a) {
      const auto& x = mesh_.coord(nodes[a]);
      for (int d = 0; d < dim_; ++d) b[d] = std::min(b[d], x[d]), b[3 + d] = std::max(b[3 + d], x[d]);
    }
    for (int d = 0; d < dim_; ++d) all[d] = std::min(all[d], b[d]), all[3 + d] = std::max(all[3 + d], b[3 + d]);
    meanSize += largestExtent(b, dim_) / numElements_;
  }
  findBoundaryFacets(comm);  // collective on a part, also without elements here
  if (numElements_ == 0) return;
  // Bins about one element wide (at most ~1e6 of them over the body's box:
  // 1000 per axis in 2-D, 100 in 3-D): a query meets O(1) elements.
  const double smallest = largestExtent(all, dim_) / (dim_ == 2 ? 1000.0 : 100.0);
  h_ = std::max({meanSize, smallest, std::numeric_limits<double>::min()});
  for (int d = 0; d < dim_; ++d) {
    origin_[d] = all[d];
    n_[d] = std::max(1LL, static_cast<long long>(std::ceil((all[3 + d] - all[d]) / h_)));
  }
  // Each element goes into every bin its box, grown by the margin, touches: a
  // point within the margin of an element's facet finds that element.
  for (int i = 0; i < numElements_; ++i) {
    const auto& b = boxes[i];
    const double grow = kInsideMargin * largestExtent(b, dim_);
    std::array<long long, 3> lo{{0, 0, 0}}, hi{{0, 0, 0}};
    for (int d = 0; d < dim_; ++d) {
      lo[d] = cell(b[d] - grow, origin_[d], n_[d]);
      hi[d] = cell(b[3 + d] + grow, origin_[d], n_[d]);
    }
    for (long long ix = lo[0]; ix <= hi[0]; ++ix)
      for (long long iy = lo[1]; iy <= hi[1]; ++iy)
        for (long long iz = lo[2]; iz <= hi[2]; ++iz)
          bins_.emplace_back((ix * n_[1] + iy) * n_[2] + iz, firstElement_ + i);
  }
  std::sort(bins_.begin(), bins_.end());
  if (dim_ == 3) boxes_ = std::move(boxes);
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

void BodyLocator::findBoundaryFacets(MPI_Comm comm) {
  // Boundary facets: corner edges (2-D) or faces (3-D) that only one element
  // of the body has.
  std::map<std::vector<int>, int> facetCount;
  for (int i = 0; i < numElements_; ++i)
    for (int a = 0; a < numFacets_; ++a) ++facetCount[mesh_.facetKey(firstElement_ + i, a)];
  boundaryFacet_.assign(size_t(numElements_), {});
  for (int i = 0; i < numElements_; ++i)
    for (int a = 0; a < numFacets_; ++a) boundaryFacet_[i][a] = facetCount[mesh_.facetKey(firstElement_ + i, a)] == 1;
  if (!mesh_.isPart()) return;
  // On a part, a facet only one of this rank's elements has may be shared
  // with another rank's element: each such facet, by its corners' ids, goes
  // to the rank its smallest corner id names, which counts the ranks
  // sending it and answers with the count.
  struct Key {
    Mesh::GlobalId corner[4];
    int rank;  ///< the sender; in the answer, how many elements have the facet
    int at;    ///< the sender's element i * 6 + facet a
  };
  const int ranks = commSize(comm), me = commRank(comm);
  std::vector<std::vector<Key>> send(static_cast<size_t>(ranks));
  for (int i = 0; i < numElements_; ++i)
    for (int a = 0; a < numFacets_; ++a) {
      if (!boundaryFacet_[i][a]) continue;
      Key k{{-1, -1, -1, -1}, me, i * 6 + a};
      const std::vector<int> corners = mesh_.facetKey(firstElement_ + i, a);
      for (size_t c = 0; c < corners.size(); ++c) k.corner[c] = mesh_.nodeId(corners[c]);
      std::sort(k.corner, k.corner + corners.size());
      send[size_t(k.corner[0] % ranks)].push_back(k);
    }
  std::vector<Key> asked = exchangeRecords(comm, send);
  auto sameFacet = [](const Key& x, const Key& y) { return std::equal(x.corner, x.corner + 4, y.corner); };
  std::sort(asked.begin(), asked.end(), [](const Key& x, const Key& y) {
    return std::lexicographical_compare(x.corner, x.corner + 4, y.corner, y.corner + 4);
  });
  for (auto& v : send) v.clear();
  for (size_t j = 0; j < asked.size();) {
    size_t end = j;
    while (end < asked.size() && sameFacet(asked[end], asked[j])) ++end;
    for (size_t k = j; k < end; ++k) send[size_t(asked[k].rank)].push_back({{0, 0, 0, 0}, int(end - j), asked[k].at});
    j = end;
  }
  for (const Key& answer : exchangeRecords(comm, send))
    if (answer.rank > 1) boundaryFacet_[size_t(answer.at / 6)][size_t(answer.at % 6)] = 0;
}

bool BodyLocator::onBoundaryFacet(int e, int a, const Eigen::Vector2d& x) const {
  if (!boundaryFacet_[e - firstElement_][a]) return false;
  const int* nodes = mesh_.elementNodes(e);
  const auto& side = referenceCell(mesh_.elementType(e)).facets[a];
  const auto& p = mesh_.coord(nodes[side.nodes[0]]);
  const auto& q = mesh_.coord(nodes[side.nodes[1]]);
  const Eigen::Vector2d t(q[0] - p[0], q[1] - p[1]), d(x.x() - p[0], x.y() - p[1]);
  const double xi = std::min(1.0, std::max(0.0, d.dot(t) / t.squaredNorm()));
  return (d - xi * t).norm() <= kInsideMargin * t.norm();
}

int BodyLocator::faceTriangles(int e, int f, Triangle* triangles) const {
  // The face's corners in their outward order, starting at the one with the
  // smallest node number: a triangle as it is, a quadrilateral split along
  // the diagonal from that corner (the rule of the class documentation).
  const int* nodes = mesh_.elementNodes(e);
  const ReferenceFacet& face = referenceCell(mesh_.elementType(e)).facets[f];
  const int n = referenceCell(face.type).numCorners;
  int first = 0;
  for (int k = 1; k < n; ++k)
    if (nodes[face.nodes[k]] < nodes[face.nodes[first]]) first = k;
  auto corner = [&](int k) {
    const auto& x = mesh_.coord(nodes[face.nodes[(first + k) % n]]);
    return Eigen::Vector3d(x[0], x[1], x[2]);
  };
  triangles[0] = {corner(0), corner(1), corner(2)};
  if (n == 3) return 1;
  triangles[1] = {corner(0), corner(2), corner(3)};
  return 2;
}

double BodyLocator::margin(int e) const { return kInsideMargin * largestExtent(boxes_[e - firstElement_], 3); }

bool BodyLocator::inClosure(int e, const Eigen::Vector3d& x) const {
  const auto& b = boxes_[e - firstElement_];
  const double tol = margin(e);
  for (int d = 0; d < 3; ++d)
    if (x[d] < b[d] - tol || x[d] > b[3 + d] + tol) return false;
  double angle = 0.0;
  Triangle triangles[2];
  for (int f = 0; f < numFacets_; ++f)
    for (int k = 0, n = faceTriangles(e, f, triangles); k < n; ++k) {
      if (triangleDistance(triangles[k].data(), x) <= tol) return true;
      angle += solidAngle(triangles[k].data(), x);
    }
  return angle > 2.0 * kPi;  // 4π inside (winding number 1), 0 outside
}

bool BodyLocator::onBoundaryFacet(int e, int f, const Eigen::Vector3d& x) const {
  if (!boundaryFacet_[e - firstElement_][f]) return false;
  Triangle triangles[2];
  const int n = faceTriangles(e, f, triangles);
  const double tol = margin(e);
  for (int k = 0; k < n; ++k)
    if (triangleDistance(triangles[k].data(), x) <= tol) return true;
  return false;
}

template <class Point>
int BodyLocator::locate(const Point& x) const {
  if (bins_.empty() || !x.allFinite()) return -1;
  long long key = 0;
  for (int d = 0; d < dim_; ++d) {
    const double f = (x[d] - origin_[d]) / h_;
    if (f < -1.0 || f > double(n_[d]) + 1.0) return -1;
    key = key * n_[d] + cell(x[d], origin_[d], n_[d]);
  }
  auto it = std::lower_bound(bins_.begin(), bins_.end(), std::make_pair(key, std::numeric_limits<int>::min()));
  int found = -1;
  for (; it != bins_.end() && it->first == key; ++it) {
    const int e = it->second;
    if (!inClosure(e, x)) continue;
    for (int a = 0; a < numFacets_; ++a)
      if (onBoundaryFacet(e, a, x)) return -1;  // on the body's boundary: not inside
    if (found < 0) found = e;  // bins are sorted by element: the lowest index
  }
  return found;
}

int BodyLocator::elementContaining(const Eigen::Vector2d& x) const {
  if (dim_ != 2) throwWrongDimension(mesh_, body_, 2);
  return locate(x);
}

int BodyLocator::elementContaining(const Eigen::Vector3d& x) const {
  if (dim_ != 3) throwWrongDimension(mesh_, body_, 3);
  return locate(x);
}

}  // namespace ddc
