#include "DDC_Substructuring.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <Eigen/Dense>

#include "DDC_Error.hpp"
#include "DDC_Model.hpp"

namespace ddc {

namespace {

/// 3-D anchoring test: do the primal nodes (all three DOFs fixed in the
/// coarse problem) and the prescribed DOFs among `anchors` remove the six
/// rigid-body modes? They do iff the modes restricted to those DOFs are
/// linearly independent: the 6 x 6 Gram matrix of the restricted modes
/// (translations, and rotations about the anchors' centroid scaled by their
/// extent, so the test does not depend on units) has full numerical rank.
bool rigidModesFixed(const Model& model, const std::vector<int>& anchors, const std::vector<char>& primal) {
  if (anchors.empty()) return false;
  const Mesh& mesh = model.mesh();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int n : anchors) centre += Eigen::Vector3d(mesh.coord(n).data());
  centre /= static_cast<double>(anchors.size());
  double extent = 0.0;
  for (int n : anchors) extent = std::max(extent, (Eigen::Vector3d(mesh.coord(n).data()) - centre).norm());
  if (extent == 0.0) return false;
  Eigen::Matrix<double, 6, 6> gram = Eigen::Matrix<double, 6, 6>::Zero();
  for (int n : anchors) {
    const Eigen::Vector3d x = (Eigen::Vector3d(mesh.coord(n).data()) - centre) / extent;
    for (int c = 0; c < 3; ++c) {
      if (!primal[n] && !model.isConstrained(model.dof(n, c))) continue;
      // Row c of the modes at this node: u_c of the translations and of
      // the unit rotations about x, y, z (u = e_k × x).
      Eigen::Matrix<double, 6, 1> r = Eigen::Matrix<double, 6, 1>::Zero();
      r[c] = 1.0;
      for (int k = 0; k < 3; ++k) r[3 + k] = Eigen::Vector3d::Unit(k).cross(x)[c];
      gram += r * r.transpose();
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(gram, Eigen::EigenvaluesOnly);
  constexpr double kRankTolerance = 1e-8;  // relative: far above round-off, far below a real anchoring
  return eig.eigenvalues()[0] > kRankTolerance * eig.eigenvalues()[5];
}

/// Index in `candidates` (not empty) of the node farthest from the nearest
/// of `anchors` (from candidates[0] when there are none); the first on ties.
size_t farthestFrom(const Mesh& mesh, const std::vector<int>& candidates, const std::vector<int>& anchors) {
  auto dist2 = [&](int a, int b) {
    double d2 = 0.0;
    for (int c = 0; c < mesh.dim(); ++c) d2 += (mesh.coord(a)[c] - mesh.coord(b)[c]) * (mesh.coord(a)[c] - mesh.coord(b)[c]);
    return d2;
  };
  size_t best = 0;
  double bestD = -1;
  for (size_t i = 0; i < candidates.size(); ++i) {
    double d = 1e300;
    if (anchors.empty()) d = dist2(candidates[i], candidates[0]);
    for (int a : anchors) d = std::min(d, dist2(candidates[i], a));
    if (d > bestD) bestD = d, best = i;
  }
  return best;
}

/// Per node, the subdomains of its elements (in the order they are met).
std::vector<std::vector<int>> nodeSubdomains(const Mesh& mesh, const Partition& part) {
  std::vector<std::vector<int>> nodeSubs(mesh.numNodes());
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int s = part.elementSubdomain[e];
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
      auto& v = nodeSubs[mesh.elementNodes(e)[i]];
      if (std::find(v.begin(), v.end(), s) == v.end()) v.push_back(s);
    }
  }
  return nodeSubs;
}

/// Per node, whether it lies on the mesh boundary (on a facet of one element).
std::vector<char> meshBoundaryNodes(const Mesh& mesh) {
  std::map<std::vector<int>, int> facetCount;
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int f = 0; f < mesh.elementNumFacets(e); ++f) facetCount[mesh.facetKey(e, f)]++;
  std::vector<char> onBoundary(mesh.numNodes(), 0);
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int f = 0; f < mesh.elementNumFacets(e); ++f)
      if (facetCount[mesh.facetKey(e, f)] == 1) {
        const Segment seg = mesh.makeSegment(e, f);
        for (int i = 0; i < seg.numNodes; ++i) onBoundary[seg.nodes[i]] = 1;
      }
  return onBoundary;
}

/// The 3-D edge nodes. A node's place is its set of subdomains, with the
/// mesh boundary counted as one more (-1); a node whose place has >= 3
/// members lies on an edge (a candidate vertex), and it is dominated if a
/// node of one of its elements has a strictly larger place (the edge goes
/// on through it to a vertex there).
struct EdgeNodes {
  std::vector<std::vector<int>> place;
  std::vector<char> candidate, dominated;

  EdgeNodes(const Mesh& mesh, const std::vector<std::vector<int>>& nodeSubs, const std::vector<char>& onBoundary)
      : place(mesh.numNodes()), candidate(mesh.numNodes(), 0), dominated(mesh.numNodes(), 0) {
    const int numNodes = mesh.numNodes();
    for (int n = 0; n < numNodes; ++n) {
      place[n] = nodeSubs[n];
      if (onBoundary[n]) place[n].push_back(-1);
      std::sort(place[n].begin(), place[n].end());
    }
    for (int n = 0; n < numNodes; ++n) candidate[n] = nodeSubs[n].size() >= 2 && place[n].size() >= 3;
    for (int e = 0; e < mesh.numElements(); ++e) {
      const int* en = mesh.elementNodes(e);
      for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
        if (!candidate[en[i]]) continue;
        const auto& a = place[en[i]];
        for (int j = 0; j < mesh.elementNumNodes(e) && !dominated[en[i]]; ++j) {
          const auto& b = place[en[j]];
          if (b.size() > a.size() && std::includes(b.begin(), b.end(), a.begin(), a.end())) dominated[en[i]] = 1;
        }
      }
    }
  }
};

/// VertexRule::EdgeEnds: with edge averages the inside of an edge needs no
/// primal nodes: the edge nodes (place >= 3) fall into classes, connected
/// through elements and sharing one place. A one-node class is a vertex
/// (the vertices of Klawonn & Widlund 2006, where edges meet); a class that
/// touches no such vertex (an edge running into the mesh boundary, a line
/// where an interface meets it) gets its two ends: the node farthest from
/// the class centroid and the node farthest from that.
void markEdgeEnds(const Model& model, const EdgeNodes& edges, std::vector<char>& primal) {
  const Mesh& mesh = model.mesh();
  const int numNodes = mesh.numNodes();
  const auto& candidate = edges.candidate;
  std::vector<int> root(numNodes);
  for (int n = 0; n < numNodes; ++n) root[n] = n;
  std::function<int(int)> find = [&](int n) { return root[n] == n ? n : root[n] = find(root[n]); };
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int* en = mesh.elementNodes(e);
    for (int i = 0; i < mesh.elementNumNodes(e); ++i)
      for (int j = i + 1; j < mesh.elementNumNodes(e); ++j)
        if (candidate[en[i]] && candidate[en[j]] && edges.place[en[i]] == edges.place[en[j]]) {
          const int a = find(en[i]), b = find(en[j]);
          if (a != b) root[std::max(a, b)] = std::min(a, b);
        }
  }
  std::map<int, std::vector<int>> classes;
  for (int n = 0; n < numNodes; ++n)
    if (candidate[n]) classes[find(n)].push_back(n);
  auto dist2 = [&](const Eigen::Vector3d& x, int n) { return (Eigen::Vector3d(mesh.coord(n).data()) - x).squaredNorm(); };
  auto farthest = [&](const std::vector<int>& members, const Eigen::Vector3d& x) {
    int best = members[0];
    for (int n : members)
      if (dist2(x, n) > dist2(x, best)) best = n;
    return best;
  };
  for (const auto& kv : classes)
    if (kv.second.size() == 1) primal[kv.second[0]] = 1;
  // On contact surfaces the rule of EdgeNodes stays: the contact rows
  // couple subdomains there, and without these primal nodes the dual
  // iterations of the ironing example (a stiff die on a soft slab)
  // exceeded 500 in its first step.
  for (int n = 0; n < numNodes; ++n)
    if (candidate[n] && model.isContactSurfaceNode(n) && !edges.dominated[n]) primal[n] = 1;
  std::vector<char> touches(numNodes, 0);  // per class root: an element links it to a vertex
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int* en = mesh.elementNodes(e);
    bool vertex = false;
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) vertex = vertex || primal[en[i]];
    if (vertex)
      for (int i = 0; i < mesh.elementNumNodes(e); ++i)
        if (candidate[en[i]]) touches[find(en[i])] = 1;
  }
  for (const auto& kv : classes) {
    if (kv.second.size() == 1 || touches[kv.first]) continue;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int n : kv.second) centre += Eigen::Vector3d(mesh.coord(n).data());
    centre /= double(kv.second.size());
    const int a = farthest(kv.second, centre);
    primal[a] = 1;
    primal[farthest(kv.second, Eigen::Vector3d(mesh.coord(a).data()))] = 1;
  }
}

/// Rule 2b (3-D, EdgeEnds): the edge ends alone may join two subdomains
/// that share a face at two points only, a hinge; the subassembled problem
/// then has a mechanism (a chain of METIS slabs has no edges at all). Each
/// face gets primal nodes until the relative rigid modes of its two
/// subdomains are fixed (three nodes not on one line), the farthest from
/// the existing ones first.
void anchorSharedFaces(const Model& model, const std::vector<std::vector<int>>& nodeSubs, std::vector<char>& primal) {
  const Mesh& mesh = model.mesh();
  const int numNodes = mesh.numNodes();
  std::map<std::pair<int, int>, std::vector<int>> shared;
  for (int n = 0; n < numNodes; ++n)
    for (size_t i = 0; i < nodeSubs[n].size(); ++i)
      for (size_t j = 0; j < nodeSubs[n].size(); ++j)
        if (nodeSubs[n][i] < nodeSubs[n][j]) shared[{nodeSubs[n][i], nodeSubs[n][j]}].push_back(n);
  std::vector<char> all(numNodes, 0);
  for (auto& kv : shared) {
    // A face, not an edge or a point: its nodes do not lie on one line.
    for (int n : kv.second) all[n] = 1;
    const bool face = rigidModesFixed(model, kv.second, all);
    for (int n : kv.second) all[n] = 0;
    if (!face) continue;
    std::vector<int> anchors, rest;
    for (int n : kv.second) (primal[n] ? anchors : rest).push_back(n);
    while (!rigidModesFixed(model, anchors, primal) && !rest.empty()) {
      const size_t best = farthestFrom(mesh, rest, anchors);
      primal[rest[best]] = 1;
      anchors.push_back(rest[best]);
      rest.erase(rest.begin() + long(best));
    }
  }
}

/// Rule 3 for subdomain `s` (nodes `subNodes`, of body `body`): interface
/// nodes made primal, the farthest from its anchors first, until its rigid
/// modes are fixed, or (`massive`) until none is left; what it did into
/// `report`. \throws InputError if it floats and `massive` is false.
void anchorSubdomain(const Model& model, int s, const std::vector<int>& subNodes, int body,
                     const std::vector<std::vector<int>>& nodeSubs, std::vector<char>& primal,
                     std::vector<std::string>* report, bool massive) {
  const Mesh& mesh = model.mesh();
  const int dim = mesh.dim();
  std::vector<int> anchors, interface;
  int primalCount = 0;
  bool fixedDir[2] = {false, false};
  for (int n : subNodes) {
    bool constrained = false;
    for (int c = 0; c < dim; ++c) constrained = constrained || model.isConstrained(model.dof(n, c));
    if (dim == 2) {
      fixedDir[0] = fixedDir[0] || model.isConstrained(model.dof(n, 0));
      fixedDir[1] = fixedDir[1] || model.isConstrained(model.dof(n, 1));
    }
    if (primal[n]) ++primalCount;
    if (primal[n] || constrained) anchors.push_back(n);
    if (nodeSubs[n].size() >= 2 && !primal[n]) interface.push_back(n);
  }
  auto anchored = [&] {
    if (dim == 3) return rigidModesFixed(model, anchors, primal);
    return primalCount >= 2 || (anchors.size() >= 2 && (primalCount >= 1 || (fixedDir[0] && fixedDir[1])));
  };
  int added = 0;
  bool floating = false;
  while (!anchored()) {
    if (interface.empty() && massive) {
      floating = true;  // K^s + c M^s is nonsingular: no anchor needed
      break;
    }
    if (interface.empty()) {
      std::ostringstream os;
      os << "subdomain " << s << " (body '" << mesh.body(body).name
         << "') is floating: it has too few prescribed displacements and no interface nodes left to make primal, "
            "so FETI-DP cannot fix its rigid-body modes; add boundary conditions or partition it with its "
            "neighbours (Partition/Method)";
      throw InputError(os.str());
    }
    const int best = static_cast<int>(farthestFrom(mesh, interface, anchors));
    const int n = interface[best];
    interface.erase(interface.begin() + best);
    primal[n] = 1;
    ++primalCount;
    anchors.push_back(n);
    ++added;
  }
  if (added && report) {
    std::ostringstream os;
    os << "subdomain " << s << ": " << added << " interface node(s) made primal to fix its rigid-body modes";
    if (floating) os << " (not all of them: it floats, which its mass allows)";
    report->push_back(os.str());
  } else if (floating && report) {
    report->push_back("subdomain " + std::to_string(s) + " floats (no prescribed displacement or interface "
                      "node fixes its rigid-body modes); its mass makes K + c M nonsingular");
  }
}

/// Rule 3: anchor every subdomain (anchorSubdomain()).
void anchorSubdomains(const Model& model, const std::vector<std::vector<int>>& nodeSubs, std::vector<char>& primal,
                      std::vector<std::string>* report, bool massive) {
  const Mesh& mesh = model.mesh();
  const auto& part = model.partition();
  std::vector<int> subBody(part.numSubdomains, 0);
  for (int e = 0; e < mesh.numElements(); ++e) subBody[part.elementSubdomain[e]] = mesh.elementBody(e);
  std::vector<std::vector<int>> subNodes(part.numSubdomains);
  for (int n = 0; n < mesh.numNodes(); ++n)
    for (int s : nodeSubs[n]) subNodes[s].push_back(n);
  for (int s = 0; s < part.numSubdomains; ++s)
    anchorSubdomain(model, s, subNodes[s], subBody[s], nodeSubs, primal, report, massive);
}

}  // namespace

std::vector<char> selectPrimalNodes(const Model& model, std::vector<std::string>* report, VertexRule rule,
                                    bool massive) {
  const Mesh& mesh = model.mesh();
  const int numNodes = mesh.numNodes();
  const int dim = mesh.dim();
  const std::vector<std::vector<int>> nodeSubs = nodeSubdomains(mesh, model.partition());
  const std::vector<char> onBoundary = meshBoundaryNodes(mesh);
  std::vector<char> primal(numNodes, 0);
  if (dim == 2) {
    for (int n = 0; n < numNodes; ++n)
      if (nodeSubs[n].size() >= 3 || (nodeSubs[n].size() == 2 && onBoundary[n])) primal[n] = 1;
  } else {
    // 3-D vertices: the ends of the subdomain edges.
    const EdgeNodes edges(mesh, nodeSubs, onBoundary);
    if (rule == VertexRule::EdgeEnds)
      markEdgeEnds(model, edges, primal);
    else
      for (int n = 0; n < numNodes; ++n) primal[n] = edges.candidate[n] && !edges.dominated[n];
  }
  if (dim == 3 && rule == VertexRule::EdgeEnds) anchorSharedFaces(model, nodeSubs, primal);
  anchorSubdomains(model, nodeSubs, primal, report, massive);
  return primal;
}

std::vector<SubdomainSystem> buildSubdomainSystems(const Model& model, const std::vector<char>& primalNode) {
  const Mesh& mesh = model.mesh();
  const auto& part = model.partition();
  const int me = model.comm()->getRank();
  std::map<int, SubdomainSystem> byId;
  for (int e : model.localElements()) {
    const int s = part.elementSubdomain[e];
    DDC_CHECK(model.subdomainRank(s) == me, "local element of a foreign subdomain");
    auto& sys = byId[s];
    sys.id = s;
    sys.elements.push_back(e);
  }
  auto self = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
  std::vector<SubdomainSystem> out;
  for (auto& kv : byId) {
    SubdomainSystem& sys = kv.second;
    std::set<GO> dofSet;
    for (int e : sys.elements)
      for (int i = 0; i < mesh.elementNumNodes(e); ++i)
        for (int c = 0; c < mesh.dim(); ++c) {
          const GO g = model.dof(mesh.elementNodes(e)[i], c);
          if (!model.isConstrained(g)) dofSet.insert(g);
        }
    sys.dofs.assign(dofSet.begin(), dofSet.end());
    std::map<GO, int> local;
    for (size_t i = 0; i < sys.dofs.size(); ++i) local[sys.dofs[i]] = static_cast<int>(i);
    sys.primal.assign(sys.dofs.size(), 0);
    sys.component.assign(sys.dofs.size(), 0);
    sys.coordinates.assign(sys.dofs.size() * size_t(mesh.dim()), 0.0);
    for (int e : sys.elements) {
      std::vector<int> l;
      for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
        const int n = mesh.elementNodes(e)[i];
        for (int c = 0; c < mesh.dim(); ++c) {
          const GO g = model.dof(n, c);
          const auto it = local.find(g);
          l.push_back(it == local.end() ? -1 : it->second);
          if (it != local.end() && primalNode[n]) sys.primal[it->second] = 1;
          if (it != local.end()) {
            sys.component[it->second] = c;
            for (int d = 0; d < mesh.dim(); ++d) sys.coordinates[size_t(it->second) * mesh.dim() + d] = mesh.coord(n)[d];
          }
        }
      }
      sys.elementLocal.push_back(std::move(l));
    }
    const int n = static_cast<int>(sys.dofs.size());
    std::vector<std::vector<LO>> rows(n);
    for (const auto& l : sys.elementLocal)
      for (int a : l)
        if (a >= 0)
          for (int b : l)
            if (b >= 0) rows[a].push_back(b);
    Teuchos::Array<size_t> nnz(n);
    for (int r = 0; r < n; ++r) {
      std::sort(rows[r].begin(), rows[r].end());
      rows[r].erase(std::unique(rows[r].begin(), rows[r].end()), rows[r].end());
      nnz[r] = rows[r].size();
    }
    auto map = Teuchos::rcp(new Map(n, 0, self));
    auto graph = Teuchos::rcp(new CrsGraph(map, map, nnz()));
    for (int r = 0; r < n; ++r) graph->insertLocalIndices(r, Teuchos::ArrayView<const LO>(rows[r]));
    graph->fillComplete(map, map);
    sys.K = Teuchos::rcp(new CrsMatrix(graph));
    sys.K->fillComplete(map, map);
    out.push_back(std::move(sys));
  }
  return out;
}

}  // namespace ddc
