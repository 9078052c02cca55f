// selectPrimalNodes() (DDC_Substructuring.hpp): the primal nodes of the
// FETI-DP subdomains, on a whole mesh or on parts of it (doc/feti-dp.md,
// "Primal nodes", "On parts of the mesh").
#include "DDC_Substructuring.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include <Eigen/Dense>

#include "DDC_Error.hpp"
#include "DDC_Model.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_NodeDirectory.hpp"

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

/// What the ranks agree on while they select the primal nodes. On a whole
/// mesh every rank holds every element and decides everything itself. On
/// parts (Mesh::part()) a rank holds its subdomains' elements and their
/// nodes: what the holders of a node see of it is united through a
/// NodeDirectory, what depends on a subdomain (its shared faces, its
/// anchoring) is decided by the subdomain's rank, and the decisions that
/// later ones read are taken in turns, rank by rank, so that they are made
/// in the same order as on one rank (subdomains are numbered rank by rank,
/// subdomainOwnerRank()) and give the same primal nodes.
class Agreement {
 public:
  explicit Agreement(const Model& model)
      : model_(model), comm_(rawComm(*model.comm())), me_(model.comm()->getRank()), ranks_(model.comm()->getSize()) {
    if (model.mesh().isPart()) directory_ = std::make_unique<NodeDirectory>(comm_, model.mesh());
  }

  bool onParts() const { return directory_ != nullptr; }
  MPI_Comm comm() const { return comm_; }
  /// The rank that decides for subdomain s.
  int rankOf(int s) const { return onParts() ? model_.subdomainRank(s) : me_; }
  bool decides(int s) const { return rankOf(s) == me_; }
  /// Turns in which decisions are taken: one per rank on parts.
  int turns() const { return onParts() ? ranks_ : 1; }
  bool myTurn(int t) const { return !onParts() || t == me_; }

  /// Per node, the union of what its holders give (NodeDirectory::unite()).
  std::vector<std::vector<int>> unite(std::vector<std::vector<int>> values) const {
    if (!onParts()) return values;
    return directory_->unite(values);
  }
  /// Per node, whether any holder flags it.
  std::vector<char> anyHolder(std::vector<char> flags) const {
    if (!onParts()) return flags;
    return directory_->anyHolder(flags);
  }
  /// The nodes this rank marked primal (`marked`) marked on every rank
  /// that holds them. Collective on parts.
  void spread(const std::vector<int>& marked, std::vector<char>& primal) const {
    if (!onParts()) return;
    std::vector<NodeDirectory::Note> notes;
    for (int n : marked) notes.push_back({model_.mesh().nodeId(n), 1});
    for (const auto& h : directory_->toHolders(notes)) primal[h.first] = 1;
  }
  /// Records for the ranks that decide (send[r] to rank r, ranks() of
  /// them): what this rank saw of their subdomains. On a whole mesh this
  /// rank decides everything and sends nothing.
  template <class T>
  std::vector<T> exchange(const std::vector<std::vector<T>>& send) const {
    if (!onParts()) return {};
    return exchangeRecords(comm_, send);
  }
  int ranks() const { return ranks_; }
  int me() const { return me_; }

  /// The lines every rank gave, in rank order, on every rank.
  std::vector<std::string> gatherLines(const std::vector<std::string>& lines) const {
    if (!onParts()) return lines;
    std::string text;
    for (const auto& l : lines) text += l + '\n';
    int len = static_cast<int>(text.size());
    std::vector<int> lens(ranks_), offsets(ranks_, 0);
    MPI_Allgather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, comm_);
    for (int r = 1; r < ranks_; ++r) offsets[r] = offsets[r - 1] + lens[r - 1];
    std::string all(static_cast<size_t>(offsets[ranks_ - 1] + lens[ranks_ - 1]), '\n');
    char dummy = 0;
    MPI_Allgatherv(text.empty() ? &dummy : &text[0], len, MPI_CHAR, all.empty() ? &dummy : &all[0], lens.data(),
                   offsets.data(), MPI_CHAR, comm_);
    std::vector<std::string> out;
    std::istringstream in(all);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
  }

 private:
  const Model& model_;
  MPI_Comm comm_;
  int me_, ranks_;
  std::unique_ptr<NodeDirectory> directory_;
};

/// Per node, the subdomains of its elements (in the order they are met; on
/// parts, of every rank's elements, sorted).
std::vector<std::vector<int>> nodeSubdomains(const Mesh& mesh, const Partition& part, const Agreement& agree) {
  std::vector<std::vector<int>> nodeSubs(mesh.numNodes());
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int s = part.elementSubdomain[e];
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
      auto& v = nodeSubs[mesh.elementNodes(e)[i]];
      if (std::find(v.begin(), v.end(), s) == v.end()) v.push_back(s);
    }
  }
  return agree.unite(std::move(nodeSubs));
}

/// On parts: a facet of one element on this rank may be the facet of an
/// element on another rank. Those whose corners all lie on other ranks'
/// subdomains as well are counted over the ranks, each at the directory
/// rank of its lowest corner id (ids split evenly over the ranks).
void countFacetsOverRanks(const Mesh& mesh, const std::vector<std::vector<int>>& nodeSubs, const Agreement& agree,
                          std::map<std::vector<int>, int>& facetCount) {
  constexpr size_t kMaxCorners = 4;
  struct FacetNote {
    std::array<Mesh::GlobalId, kMaxCorners> corner;  ///< ascending, then -1
    int rank;
  };
  auto elsewhere = [&](int n) {
    return std::any_of(nodeSubs[n].begin(), nodeSubs[n].end(), [&](int s) { return !agree.decides(s); });
  };
  const Mesh::GlobalId numIds = std::max<Mesh::GlobalId>(mesh.numGlobalNodes(), 1);
  std::vector<std::vector<FacetNote>> send(agree.ranks());
  for (const auto& kv : facetCount) {
    if (kv.second != 1 || !std::all_of(kv.first.begin(), kv.first.end(), elsewhere)) continue;
    DDC_CHECK(kv.first.size() <= kMaxCorners, "a facet of " << kv.first.size() << " corners");
    FacetNote note{{-1, -1, -1, -1}, agree.me()};
    for (size_t i = 0; i < kv.first.size(); ++i) note.corner[i] = mesh.nodeId(kv.first[i]);
    send[static_cast<int>(note.corner[0] * agree.ranks() / numIds)].push_back(note);
  }
  std::vector<FacetNote> heard = agree.exchange(send);
  std::sort(heard.begin(), heard.end(), [](const FacetNote& a, const FacetNote& b) { return a.corner < b.corner; });
  for (auto& v : send) v.clear();
  for (size_t i = 0, j = 0; i < heard.size(); i = j) {
    for (j = i; j < heard.size() && heard[j].corner == heard[i].corner; ++j) {}
    if (j - i >= 2)
      for (size_t k = i; k < j; ++k) send[heard[k].rank].push_back(heard[k]);
  }
  for (const FacetNote& f : agree.exchange(send)) {
    std::vector<int> local;
    for (size_t i = 0; i < kMaxCorners && f.corner[i] >= 0; ++i) local.push_back(mesh.localNode(f.corner[i]));
    facetCount[local] = 2;
  }
}

/// Per node, whether it lies on the mesh boundary (on a facet of one element).
std::vector<char> meshBoundaryNodes(const Mesh& mesh, const std::vector<std::vector<int>>& nodeSubs,
                                    const Agreement& agree) {
  std::map<std::vector<int>, int> facetCount;
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int f = 0; f < mesh.elementNumFacets(e); ++f) facetCount[mesh.facetKey(e, f)]++;
  if (agree.onParts()) countFacetsOverRanks(mesh, nodeSubs, agree, facetCount);
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
/// on through it to a vertex there; on parts, through an element of any
/// rank).
struct EdgeNodes {
  std::vector<std::vector<int>> place;
  std::vector<char> candidate, dominated;

  EdgeNodes(const Mesh& mesh, const std::vector<std::vector<int>>& nodeSubs, const std::vector<char>& onBoundary,
            const Agreement& agree)
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
    dominated = agree.anyHolder(std::move(dominated));
  }
};

/// VertexRule::EdgeEnds: with edge averages the inside of an edge needs no
/// primal nodes: the edge nodes (place >= 3) fall into classes, connected
/// through elements and sharing one place. A one-node class is a vertex
/// (the vertices of Klawonn & Widlund 2006, where edges meet); a class that
/// touches no such vertex (an edge running into the mesh boundary, a line
/// where an interface meets it) gets its two ends: the node farthest from
/// the class centroid and the node farthest from that. On parts a class is
/// decided by the rank of the lowest subdomain of its place, which holds
/// all of its nodes (they are nodes of that subdomain's elements); the other
/// ranks send it the links and touches their elements make.
void markEdgeEnds(const Model& model, const EdgeNodes& edges, const Agreement& agree, std::vector<char>& primal) {
  const Mesh& mesh = model.mesh();
  const int numNodes = mesh.numNodes();
  const auto& candidate = edges.candidate;
  auto classRank = [&](int n) {
    for (int s : edges.place[n])
      if (s >= 0) return agree.rankOf(s);
    return -1;
  };
  std::vector<int> root(numNodes);
  for (int n = 0; n < numNodes; ++n) root[n] = n;
  std::function<int(int)> find = [&](int n) { return root[n] == n ? n : root[n] = find(root[n]); };
  auto join = [&](int p, int q) {
    const int a = find(p), b = find(q);
    if (a != b) root[std::max(a, b)] = std::min(a, b);
  };
  struct Link {
    Mesh::GlobalId a, b;
  };
  std::vector<std::vector<Link>> links(agree.ranks());
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int* en = mesh.elementNodes(e);
    for (int i = 0; i < mesh.elementNumNodes(e); ++i)
      for (int j = i + 1; j < mesh.elementNumNodes(e); ++j)
        if (candidate[en[i]] && candidate[en[j]] && edges.place[en[i]] == edges.place[en[j]]) {
          const int r = classRank(en[i]);
          if (r == agree.me()) join(en[i], en[j]);
          else links[r].push_back({mesh.nodeId(en[i]), mesh.nodeId(en[j])});
        }
  }
  for (const Link& l : agree.exchange(links)) join(mesh.localNode(l.a), mesh.localNode(l.b));
  std::map<int, std::vector<int>> classes;
  for (int n = 0; n < numNodes; ++n)
    if (candidate[n] && classRank(n) == agree.me()) classes[find(n)].push_back(n);
  auto dist2 = [&](const Eigen::Vector3d& x, int n) { return (Eigen::Vector3d(mesh.coord(n).data()) - x).squaredNorm(); };
  auto farthest = [&](const std::vector<int>& members, const Eigen::Vector3d& x) {
    int best = members[0];
    for (int n : members)
      if (dist2(x, n) > dist2(x, best)) best = n;
    return best;
  };
  std::vector<int> marked;
  for (const auto& kv : classes)
    if (kv.second.size() == 1) marked.push_back(kv.second[0]);
  for (int n : marked) primal[n] = 1;
  agree.spread(marked, primal);
  // On contact surfaces the rule of EdgeNodes stays: the contact rows
  // couple subdomains there, and without these primal nodes the dual
  // iterations of the ironing example (a stiff die on a soft slab)
  // exceeded 500 in its first step.
  for (int n = 0; n < numNodes; ++n)
    if (candidate[n] && model.isContactSurfaceNode(n) && !edges.dominated[n]) primal[n] = 1;
  std::vector<char> touches(numNodes, 0);  // per class root: an element links it to a vertex
  std::vector<std::vector<Mesh::GlobalId>> touched(agree.ranks());
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int* en = mesh.elementNodes(e);
    bool vertex = false;
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) vertex = vertex || primal[en[i]];
    if (!vertex) continue;
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
      if (!candidate[en[i]]) continue;
      const int r = classRank(en[i]);
      if (r == agree.me()) touches[find(en[i])] = 1;
      else touched[r].push_back(mesh.nodeId(en[i]));
    }
  }
  for (Mesh::GlobalId id : agree.exchange(touched)) touches[find(mesh.localNode(id))] = 1;
  marked.clear();
  for (const auto& kv : classes) {
    if (kv.second.size() == 1 || touches[kv.first]) continue;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int n : kv.second) centre += Eigen::Vector3d(mesh.coord(n).data());
    centre /= double(kv.second.size());
    const int a = farthest(kv.second, centre);
    marked.push_back(a);
    marked.push_back(farthest(kv.second, Eigen::Vector3d(mesh.coord(a).data())));
  }
  for (int n : marked) primal[n] = 1;
  agree.spread(marked, primal);
}

/// Rule 2b for the faces in `shared` (a pair of subdomains -> the nodes
/// both hold), in order. \returns the nodes it made primal.
std::vector<int> anchorFaces(const Model& model, const std::map<std::pair<int, int>, std::vector<int>>& shared,
                             std::vector<char>& primal) {
  const Mesh& mesh = model.mesh();
  std::vector<int> marked;
  std::vector<char> all(mesh.numNodes(), 0);
  for (const auto& kv : shared) {
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
      marked.push_back(rest[best]);
      anchors.push_back(rest[best]);
      rest.erase(rest.begin() + long(best));
    }
  }
  return marked;
}

/// Rule 2b (3-D, EdgeEnds): the edge ends alone may join two subdomains
/// that share a face at two points only, a hinge; the subassembled problem
/// then has a mechanism (a chain of METIS slabs has no edges at all). Each
/// face gets primal nodes until the relative rigid modes of its two
/// subdomains are fixed (three nodes not on one line), the farthest from
/// the existing ones first. A face is decided by the rank of its lower
/// subdomain, in turns (Agreement).
void anchorSharedFaces(const Model& model, const std::vector<std::vector<int>>& nodeSubs, const Agreement& agree,
                       std::vector<char>& primal) {
  const Mesh& mesh = model.mesh();
  const int numNodes = mesh.numNodes();
  std::map<std::pair<int, int>, std::vector<int>> shared;
  for (int n = 0; n < numNodes; ++n)
    for (size_t i = 0; i < nodeSubs[n].size(); ++i)
      for (size_t j = 0; j < nodeSubs[n].size(); ++j)
        if (nodeSubs[n][i] < nodeSubs[n][j] && agree.decides(nodeSubs[n][i]))
          shared[{nodeSubs[n][i], nodeSubs[n][j]}].push_back(n);
  for (int t = 0; t < agree.turns(); ++t) {
    std::vector<int> marked;
    if (agree.myTurn(t)) marked = anchorFaces(model, shared, primal);
    agree.spread(marked, primal);
  }
}

/// Rule 3 for subdomain `s` (nodes `subNodes`, of body `body`): interface
/// nodes made primal, the farthest from its anchors first, until its rigid
/// modes are fixed, or (`massive`) until none is left; the nodes it made
/// primal into `marked`, what it did into `report`.
/// \throws InputError if it floats and `massive` is false.
void anchorSubdomain(const Model& model, int s, const std::vector<int>& subNodes, int body,
                     const std::vector<std::vector<int>>& nodeSubs, std::vector<char>& primal,
                     std::vector<int>& marked, std::vector<std::string>* report, bool massive) {
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
    marked.push_back(n);
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

/// Rule 3: anchor every subdomain (anchorSubdomain()), each by its rank,
/// in turns (Agreement); a floating subdomain is refused on every rank.
void anchorSubdomains(const Model& model, const std::vector<std::vector<int>>& nodeSubs, const Agreement& agree,
                      std::vector<char>& primal, std::vector<std::string>* report, bool massive) {
  const Mesh& mesh = model.mesh();
  const auto& part = model.partition();
  std::vector<int> subBody(part.numSubdomains, 0);
  for (int e = 0; e < mesh.numElements(); ++e) subBody[part.elementSubdomain[e]] = mesh.elementBody(e);
  std::vector<std::vector<int>> subNodes(part.numSubdomains);
  for (int n = 0; n < mesh.numNodes(); ++n)
    for (int s : nodeSubs[n])
      if (agree.decides(s)) subNodes[s].push_back(n);
  std::vector<std::string> lines;
  for (int t = 0; t < agree.turns(); ++t) {
    std::vector<int> marked;
    std::string floating;
    if (agree.myTurn(t)) try {
        for (int s = 0; s < part.numSubdomains; ++s)
          if (agree.decides(s))
            anchorSubdomain(model, s, subNodes[s], subBody[s], nodeSubs, primal, marked, &lines, massive);
      } catch (const InputError& e) {
        floating = e.what();
      }
    raiseCollectively<InputError>(agree.comm(), floating);
    agree.spread(marked, primal);
  }
  if (report)
    for (auto& line : agree.gatherLines(lines)) report->push_back(std::move(line));
}

}  // namespace

std::vector<char> selectPrimalNodes(const Model& model, std::vector<std::string>* report, VertexRule rule,
                                    bool massive) {
  const Mesh& mesh = model.mesh();
  const int numNodes = mesh.numNodes();
  const int dim = mesh.dim();
  const Agreement agree(model);
  const std::vector<std::vector<int>> nodeSubs = nodeSubdomains(mesh, model.partition(), agree);
  const std::vector<char> onBoundary = meshBoundaryNodes(mesh, nodeSubs, agree);
  std::vector<char> primal(numNodes, 0);
  if (dim == 2) {
    for (int n = 0; n < numNodes; ++n)
      if (nodeSubs[n].size() >= 3 || (nodeSubs[n].size() == 2 && onBoundary[n])) primal[n] = 1;
  } else {
    // 3-D vertices: the ends of the subdomain edges.
    const EdgeNodes edges(mesh, nodeSubs, onBoundary, agree);
    if (rule == VertexRule::EdgeEnds)
      markEdgeEnds(model, edges, agree, primal);
    else
      for (int n = 0; n < numNodes; ++n) primal[n] = edges.candidate[n] && !edges.dominated[n];
  }
  if (dim == 3 && rule == VertexRule::EdgeEnds) anchorSharedFaces(model, nodeSubs, agree, primal);
  anchorSubdomains(model, nodeSubs, agree, primal, report, massive);
  return primal;
}

}  // namespace ddc
