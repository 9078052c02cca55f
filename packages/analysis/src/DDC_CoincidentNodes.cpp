#include "DDC_CoincidentNodes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

#include "DDC_Error.hpp"

namespace ddc {

namespace {

/// Relative distance (of the mesh's bounding-box diagonal) within which two
/// nodes are at one position: far above the round-off of generated or read
/// coordinates (~1e-16), far below any element a mesh resolves.
constexpr double kCoincidence = 1e-9;

/// The first coincident pair of nodes found for two bodies, and how many.
struct Shared {
  int nodeA = -1, nodeB = -1, count = 0;
};

/// Body of each node.
std::vector<int> nodeBodies(const Mesh& mesh) {
  std::vector<int> body(mesh.numNodes(), 0);
  for (int b = 0; b < mesh.numBodies(); ++b)
    std::fill(body.begin() + mesh.body(b).firstNode, body.begin() + mesh.body(b).firstNode + mesh.body(b).numNodes,
              b);
  return body;
}

/// Per pair of bodies (lower index first), the nodes at one position: every
/// node in a cell of size tol of a grid over the bounding box, a hash map of
/// the cells, each node compared with the nodes of its 3^dim neighbouring
/// cells.
std::map<std::pair<int, int>, Shared> sharedPositions(const Mesh& mesh) {
  // One body has no pair of bodies to compare (hashing every node of a
  // 1.4M-DOF block took a quarter of the checks before partitioning).
  if (mesh.numBodies() < 2) return {};
  const int dim = mesh.dim(), n = mesh.numNodes();
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (int c = 0; c < 3; ++c) lo[c] = hi[c] = n ? mesh.coord(0)[c] : 0.0;
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < dim; ++c) lo[c] = std::min(lo[c], mesh.coord(i)[c]), hi[c] = std::max(hi[c], mesh.coord(i)[c]);
  double diag = 0.0;
  for (int c = 0; c < dim; ++c) diag = std::hypot(diag, hi[c] - lo[c]);
  const double tol = kCoincidence * diag;
  std::map<std::pair<int, int>, Shared> shared;
  if (n == 0 || !(tol > 0.0)) return shared;
  auto cellOf = [&](int i) {
    std::array<std::int64_t, 3> k{0, 0, 0};
    for (int c = 0; c < dim; ++c) k[c] = std::int64_t(std::floor((mesh.coord(i)[c] - lo[c]) / tol));
    return k;
  };
  auto key = [](const std::array<std::int64_t, 3>& k) {
    return std::uint64_t(k[0]) * 73856093u ^ std::uint64_t(k[1]) * 19349663u ^ std::uint64_t(k[2]) * 83492791u;
  };
  std::unordered_multimap<std::uint64_t, int> cells;
  cells.reserve(size_t(n));
  for (int i = 0; i < n; ++i) cells.emplace(key(cellOf(i)), i);
  const std::vector<int> body = nodeBodies(mesh);
  const int reach = dim == 3 ? 1 : 0;
  for (int i = 0; i < n; ++i) {
    const auto k = cellOf(i);
    std::vector<int> seen;  // a node in two neighbouring cells of one hash: once (a few candidates)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -reach; dz <= reach; ++dz) {
          const auto range = cells.equal_range(key({k[0] + dx, k[1] + dy, k[2] + dz}));
          for (auto it = range.first; it != range.second; ++it) {
            const int j = it->second;
            if (body[j] <= body[i] || std::find(seen.begin(), seen.end(), j) != seen.end()) continue;
            seen.push_back(j);
            double d = 0.0;
            for (int c = 0; c < dim; ++c) d = std::max(d, std::abs(mesh.coord(i)[c] - mesh.coord(j)[c]));
            if (d > tol) continue;
            Shared& s = shared[{body[i], body[j]}];
            if (s.count++ == 0) s.nodeA = i, s.nodeB = j;
          }
        }
  }
  return shared;
}

}  // namespace

void requireJoinedCoincidentNodes(const Mesh& mesh, const ContactOptions& contact) {
  std::set<std::pair<int, int>> joined;
  for (const auto& pr : contact.pairs) {
    const int s = mesh.bodyIndex(pr.slaveSet.substr(0, pr.slaveSet.find('/')));
    const int m = mesh.bodyIndex(pr.masterSet.substr(0, pr.masterSet.find('/')));
    joined.insert({std::min(s, m), std::max(s, m)});
  }
  for (const auto& [bodies, s] : sharedPositions(mesh)) {
    if (joined.count(bodies)) continue;
    const std::string a = mesh.body(bodies.first).name, b = mesh.body(bodies.second).name;
    DDC_THROW(InputError,
              "mesh: bodies '" << a << "' and '" << b << "' have nodes at " << s.count
                               << " common position(s) (node " << s.nodeA << " of '" << a << "' and node " << s.nodeB
                               << " of '" << b << "' at (" << mesh.coordText(s.nodeA)
                               << ")), and no contact pair joins them: bodies share no nodes, so they would be "
                                  "analysed as separate pieces there, carrying no load across. If they are one "
                                  "piece (e.g. two element blocks of one conforming mesh), mesh them as one body; "
                                  "if they touch, add a pair between them to 'Contact/Pairs'; otherwise move them "
                                  "apart (doc/user-guide.md, 'Bodies that touch')");
  }
}

}  // namespace ddc
