#include "DDC_Substructuring.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <algorithm>
#include <map>
#include <set>

#include "DDC_Error.hpp"
#include "DDC_Model.hpp"

namespace ddc {

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
