#include "DDC_CoincidentNodes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {

/// Relative distance (of the mesh's bounding-box diagonal) within which two
/// nodes are at one position: far above the round-off of generated or read
/// coordinates (~1e-16), far below any element a mesh resolves.
constexpr double kCoincidence = 1e-9;

/// Coarse cells that spread the nodes over the ranks on a part of a mesh,
/// in coincidence tolerances: a node near a cell's side (within a
/// tolerance) also goes to the neighbouring cell's rank, which happens to
/// few nodes.
constexpr double kSpreadCell = 1024.0;

/// A node of the search: its id in the whole mesh, position and body, and
/// whether this rank counts its pairs (own: the rank of its coarse cell).
struct PlacedNode {
  long long id;
  double x[3];
  int body, own;
};

/// The coincident pairs of nodes of two bodies: how many, and the pair of
/// lowest ids (the lower body's node first) with that node's position.
struct Shared {
  long long count = 0, idA = -1, idB = -1;
  double x[3] = {0, 0, 0};
};

/// One entry of the result, as the ranks send it.
struct SharedRecord {
  int bodyA, bodyB;
  Shared shared;
};

/// The search box: the mesh's bounding box and the tolerance (kCoincidence
/// of its diagonal), over the ranks on a part.
struct SearchBox {
  std::array<double, 3> lo{{0, 0, 0}};
  double tol = 0.0;
};

SearchBox searchBox(const Mesh& mesh, MPI_Comm comm) {
  const int dim = mesh.dim();
  std::array<double, 6> box{{1e308, 1e308, 1e308, 1e308, 1e308, 1e308}};  // lo, -hi
  for (int i = 0; i < mesh.numNodes(); ++i)
    for (int c = 0; c < dim; ++c)
      box[c] = std::min(box[c], mesh.coord(i)[c]), box[3 + c] = std::min(box[3 + c], -mesh.coord(i)[c]);
  if (mesh.isPart()) MPI_Allreduce(MPI_IN_PLACE, box.data(), 6, MPI_DOUBLE, MPI_MIN, comm);
  SearchBox out;
  if (box[0] > 1e307) return out;  // no node
  double diag = 0.0;
  for (int c = 0; c < dim; ++c) out.lo[c] = box[c], diag = std::hypot(diag, -box[3 + c] - box[c]);
  out.tol = kCoincidence * diag;
  return out;
}

/// Per pair of bodies (lower index first), the pairs of `nodes` at one
/// position of which the lower body's node is own: every node in a cell of
/// size tol of a grid, a hash map of the cells, each own node compared with
/// the nodes of its 3^dim neighbouring cells.
std::map<std::pair<int, int>, Shared> sharedPositions(const std::vector<PlacedNode>& nodes, const SearchBox& box,
                                                      int dim) {
  std::map<std::pair<int, int>, Shared> shared;
  const double tol = box.tol;
  if (nodes.empty() || !(tol > 0.0)) return shared;
  auto cellOf = [&](const PlacedNode& p) {
    std::array<std::int64_t, 3> k{0, 0, 0};
    for (int c = 0; c < dim; ++c) k[c] = std::int64_t(std::floor((p.x[c] - box.lo[c]) / tol));
    return k;
  };
  auto key = [](const std::array<std::int64_t, 3>& k) {
    return std::uint64_t(k[0]) * 73856093u ^ std::uint64_t(k[1]) * 19349663u ^ std::uint64_t(k[2]) * 83492791u;
  };
  std::unordered_multimap<std::uint64_t, size_t> cells;
  cells.reserve(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) cells.emplace(key(cellOf(nodes[i])), i);
  const int reach = dim == 3 ? 1 : 0;
  for (const PlacedNode& a : nodes) {
    if (!a.own) continue;
    const auto k = cellOf(a);
    std::vector<size_t> seen;  // a node in two neighbouring cells of one hash: once (a few candidates)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -reach; dz <= reach; ++dz) {
          const auto range = cells.equal_range(key({k[0] + dx, k[1] + dy, k[2] + dz}));
          for (auto it = range.first; it != range.second; ++it) {
            const PlacedNode& b = nodes[it->second];
            if (b.body <= a.body || std::find(seen.begin(), seen.end(), it->second) != seen.end()) continue;
            seen.push_back(it->second);
            double d = 0.0;
            for (int c = 0; c < dim; ++c) d = std::max(d, std::abs(a.x[c] - b.x[c]));
            if (d > tol) continue;
            Shared& s = shared[{a.body, b.body}];
            if (s.count++ == 0 || std::make_pair(a.id, b.id) < std::make_pair(s.idA, s.idB)) {
              s.idA = a.id, s.idB = b.id;
              std::copy(a.x, a.x + 3, s.x);
            }
          }
        }
  }
  return shared;
}

/// Body of each node of `mesh`.
std::vector<int> nodeBodies(const Mesh& mesh) {
  std::vector<int> body(mesh.numNodes(), 0);
  for (int b = 0; b < mesh.numBodies(); ++b)
    std::fill(body.begin() + mesh.body(b).firstNode, body.begin() + mesh.body(b).firstNode + mesh.body(b).numNodes,
              b);
  return body;
}

/// The nodes of a part, each sent to the rank of its coarse cell (own
/// there) and to those of the neighbouring cells its tolerance box
/// reaches; a node several ranks hold arrives several times and is kept
/// once. Collective.
std::vector<PlacedNode> spreadNodes(const Mesh& part, const SearchBox& box, MPI_Comm comm) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int dim = part.dim();
  const double cell = kSpreadCell * box.tol;
  auto home = [&](const std::array<std::int64_t, 3>& k) {
    const std::uint64_t h = std::uint64_t(k[0]) * 73856093u ^ std::uint64_t(k[1]) * 19349663u ^
                            std::uint64_t(k[2]) * 83492791u;
    return static_cast<int>(h % std::uint64_t(ranks));
  };
  const std::vector<int> body = nodeBodies(part);
  std::vector<std::vector<PlacedNode>> send(ranks);
  for (int n = 0; n < part.numNodes(); ++n) {
    PlacedNode p{part.nodeId(n), {part.coord(n)[0], part.coord(n)[1], part.coord(n)[2]}, body[n], 1};
    std::array<std::int64_t, 3> k{0, 0, 0};
    std::array<std::array<int, 3>, 3> reach{};  // per axis: -1, 0, +1 reached (twice the tolerance: round-off)
    for (int c = 0; c < 3; ++c) reach[c] = {0, 1, 0};
    for (int c = 0; c < dim; ++c) {
      const double at = (p.x[c] - box.lo[c]) / cell;
      k[c] = std::int64_t(std::floor(at));
      reach[c][0] = (at - double(k[c])) * cell < 2.0 * box.tol;
      reach[c][2] = (double(k[c] + 1) - at) * cell < 2.0 * box.tol;
    }
    std::vector<int> to;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          if (!reach[0][dx + 1] || !reach[1][dy + 1] || !reach[2][dz + 1]) continue;
          const bool own = dx == 0 && dy == 0 && dz == 0;
          const int r = home({k[0] + dx, k[1] + dy, k[2] + dz});
          p.own = own ? 1 : 0;
          send[r].push_back(p);
        }
  }
  std::vector<PlacedNode> got = exchangeRecords(comm, send);
  // One record per node: own if any copy is.
  std::sort(got.begin(), got.end(), [](const PlacedNode& a, const PlacedNode& b) {
    return a.id != b.id ? a.id < b.id : a.own > b.own;
  });
  got.erase(std::unique(got.begin(), got.end(), [](const PlacedNode& a, const PlacedNode& b) { return a.id == b.id; }),
            got.end());
  return got;
}

/// sharedPositions() of a whole mesh, or over the ranks' parts (every rank
/// gets the whole result). Collective on a part.
std::map<std::pair<int, int>, Shared> sharedPositions(const Mesh& mesh, MPI_Comm comm) {
  // One body has no pair of bodies to compare (hashing every node of a
  // 1.4M-DOF block took a quarter of the checks before partitioning).
  if (mesh.numBodies() < 2) return {};
  const SearchBox box = searchBox(mesh, comm);
  if (!mesh.isPart()) {
    const std::vector<int> body = nodeBodies(mesh);
    std::vector<PlacedNode> nodes;
    nodes.reserve(mesh.numNodes());
    for (int n = 0; n < mesh.numNodes(); ++n)
      nodes.push_back(PlacedNode{n, {mesh.coord(n)[0], mesh.coord(n)[1], mesh.coord(n)[2]}, body[n], 1});
    return sharedPositions(nodes, box, mesh.dim());
  }
  if (!(box.tol > 0.0)) return {};
  const auto mine = sharedPositions(spreadNodes(mesh, box, comm), box, mesh.dim());
  std::vector<SharedRecord> records;
  for (const auto& [bodies, s] : mine) records.push_back(SharedRecord{bodies.first, bodies.second, s});
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  std::map<std::pair<int, int>, Shared> all;
  for (const SharedRecord& r : exchangeRecords(comm, std::vector<std::vector<SharedRecord>>(ranks, records))) {
    Shared& s = all[{r.bodyA, r.bodyB}];
    if (s.count == 0 || std::make_pair(r.shared.idA, r.shared.idB) < std::make_pair(s.idA, s.idB)) {
      s.idA = r.shared.idA, s.idB = r.shared.idB;
      std::copy(r.shared.x, r.shared.x + 3, s.x);
    }
    s.count += r.shared.count;
  }
  return all;
}

std::string positionText(const double* x, int dim) {
  std::ostringstream os;
  os << x[0] << ", " << x[1];
  if (dim == 3) os << ", " << x[2];
  return os.str();
}

}  // namespace

void requireJoinedCoincidentNodes(const Mesh& mesh, const ContactOptions& contact, MPI_Comm comm) {
  std::set<std::pair<int, int>> joined;
  for (const auto& pr : contact.pairs) {
    const int s = mesh.bodyIndex(pr.slaveSet.substr(0, pr.slaveSet.find('/')));
    const int m = mesh.bodyIndex(pr.masterSet.substr(0, pr.masterSet.find('/')));
    joined.insert({std::min(s, m), std::max(s, m)});
  }
  for (const auto& [bodies, s] : sharedPositions(mesh, comm)) {
    if (joined.count(bodies)) continue;
    const std::string a = mesh.body(bodies.first).name, b = mesh.body(bodies.second).name;
    DDC_THROW(InputError,
              "mesh: bodies '" << a << "' and '" << b << "' have nodes at " << s.count
                               << " common position(s) (node " << s.idA << " of '" << a << "' and node " << s.idB
                               << " of '" << b << "' at (" << positionText(s.x, mesh.dim())
                               << ")), and no contact pair joins them: bodies share no nodes, so they would be "
                                  "analysed as separate pieces there, carrying no load across. If they are one "
                                  "piece (e.g. two element blocks of one conforming mesh), mesh them as one body; "
                                  "if they touch, add a pair between them to 'Contact/Pairs'; otherwise move them "
                                  "apart (doc/user-guide.md, 'Bodies that touch')");
  }
}

}  // namespace ddc
