#include "DDC_Substructuring.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_Model.hpp"

namespace ddc {

std::vector<char> selectPrimalNodes(const Model& model, std::vector<std::string>* report) {
  const Mesh& mesh = model.mesh();
  const auto& part = model.partition();
  const int numNodes = mesh.numNodes();
  // Subdomains of each node, and mesh-boundary nodes (on a side of one element).
  std::vector<std::vector<int>> nodeSubs(numNodes);
  std::map<std::pair<int, int>, int> sideCount;
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int s = part.elementSubdomain[e];
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
      auto& v = nodeSubs[mesh.elementNodes(e)[i]];
      if (std::find(v.begin(), v.end(), s) == v.end()) v.push_back(s);
    }
    for (int side = 0; side < 4; ++side) {
      const Segment seg = mesh.makeSegment(e, side);
      sideCount[{std::min(seg.nodes[0], seg.nodes[1]), std::max(seg.nodes[0], seg.nodes[1])}]++;
    }
  }
  std::vector<char> onBoundary(numNodes, 0);
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int side = 0; side < 4; ++side) {
      const Segment seg = mesh.makeSegment(e, side);
      if (sideCount[{std::min(seg.nodes[0], seg.nodes[1]), std::max(seg.nodes[0], seg.nodes[1])}] == 1)
        for (int i = 0; i < seg.numNodes; ++i) onBoundary[seg.nodes[i]] = 1;
    }
  std::vector<char> primal(numNodes, 0);
  for (int n = 0; n < numNodes; ++n)
    if (nodeSubs[n].size() >= 3 || (nodeSubs[n].size() == 2 && onBoundary[n])) primal[n] = 1;

  // Rule 3: anchor every subdomain.
  std::vector<int> subBody(part.numSubdomains, 0);
  for (int e = 0; e < mesh.numElements(); ++e) subBody[part.elementSubdomain[e]] = mesh.elementBody(e);
  std::vector<std::vector<int>> subNodes(part.numSubdomains);
  for (int n = 0; n < numNodes; ++n)
    for (int s : nodeSubs[n]) subNodes[s].push_back(n);
  for (int s = 0; s < part.numSubdomains; ++s) {
    std::vector<int> anchors, interface;
    int primalCount = 0;
    bool fixedDir[2] = {false, false};
    for (int n : subNodes[s]) {
      const bool cx = model.isConstrained(model.dof(n, 0)), cy = model.isConstrained(model.dof(n, 1));
      fixedDir[0] = fixedDir[0] || cx;
      fixedDir[1] = fixedDir[1] || cy;
      if (primal[n]) ++primalCount;
      if (primal[n] || cx || cy) anchors.push_back(n);
      if (nodeSubs[n].size() >= 2 && !primal[n]) interface.push_back(n);
    }
    auto anchored = [&] {
      return primalCount >= 2 || (anchors.size() >= 2 && (primalCount >= 1 || (fixedDir[0] && fixedDir[1])));
    };
    int added = 0;
    while (!anchored()) {
      if (interface.empty()) {
        std::ostringstream os;
        os << "subdomain " << s << " (body '" << mesh.body(subBody[s]).name
           << "') is floating: it has too few prescribed displacements and no interface nodes left to make primal, "
              "so FETI-DP cannot fix its rigid-body modes; add boundary conditions or partition it with its "
              "neighbours (Partition/Method)";
        throw InputError(os.str());
      }
      // The interface node farthest from the current anchors (or from the
      // first interface node when there are none).
      auto dist2 = [&](int a, int b) {
        const double dx = mesh.coord(a)[0] - mesh.coord(b)[0], dy = mesh.coord(a)[1] - mesh.coord(b)[1];
        return dx * dx + dy * dy;
      };
      int best = -1;
      double bestD = -1;
      for (size_t i = 0; i < interface.size(); ++i) {
        double d = 1e300;
        if (anchors.empty()) d = dist2(interface[i], interface[0]);
        for (int a : anchors) d = std::min(d, dist2(interface[i], a));
        if (d > bestD) bestD = d, best = static_cast<int>(i);
      }
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
      report->push_back(os.str());
    }
  }
  return primal;
}

std::vector<SubdomainSystem> buildSubdomainSystems(const Model& model, const std::vector<char>& primalNode) {
  const Mesh& mesh = model.mesh();
  const auto& part = model.partition();
  const int me = model.comm()->getRank();
  std::map<int, SubdomainSystem> byId;
  for (int e : model.localElements()) {
    const int s = part.elementSubdomain[e];
    DDC_ASSERT(model.subdomainRank(s) == me, "local element of a foreign subdomain");
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
        for (int c = 0; c < 2; ++c) {
          const GO g = model.dof(mesh.elementNodes(e)[i], c);
          if (!model.isConstrained(g)) dofSet.insert(g);
        }
    sys.dofs.assign(dofSet.begin(), dofSet.end());
    std::map<GO, int> local;
    for (size_t i = 0; i < sys.dofs.size(); ++i) local[sys.dofs[i]] = static_cast<int>(i);
    sys.primal.assign(sys.dofs.size(), 0);
    for (int e : sys.elements) {
      std::vector<int> l;
      for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
        const int n = mesh.elementNodes(e)[i];
        for (int c = 0; c < 2; ++c) {
          const GO g = model.dof(n, c);
          const auto it = local.find(g);
          l.push_back(it == local.end() ? -1 : it->second);
          if (it != local.end() && primalNode[n]) sys.primal[it->second] = 1;
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
