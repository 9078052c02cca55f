// Mesh-free primal vertices (see DDC_FetiPrimalVertices.hpp).
#include "DDC_FetiPrimalVertices.hpp"

#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

#include "DDC_FetiEdgeFaceConstraints.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

std::vector<std::vector<char>> findPrimalVertices(MPI_Comm comm, const Map& ownedMap,
                                                  const std::vector<FetiSubdomain>& subs, int dim) {
  std::string msg;
  if (dim != 2 && dim != 3) msg = "findPrimalVertices: spatial dimension " + std::to_string(dim) + ", expected 2 or 3";
  for (const auto& s : subs) {
    if (!msg.empty()) break;
    const size_t n = s.dofs.size();
    if (s.coordinates.size() != n * size_t(dim))
      msg = "findPrimalVertices: subdomain " + std::to_string(s.id) + ": " + std::to_string(dim) +
            " coordinates per DOF needed, got " + std::to_string(s.coordinates.size()) + " for " + std::to_string(n) +
            " DOFs";
    else if (s.K.is_null() || s.K->getNodeNumRows() != n)
      msg = "findPrimalVertices: subdomain " + std::to_string(s.id) + ": K must be " + std::to_string(n) + " x " +
            std::to_string(n);
  }
  raiseCollectively<std::invalid_argument>(comm, msg);

  // Interface sets of every DOF (nothing is primal yet).
  std::vector<EdgeFaceInput> in(subs.size());
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    in[ls].id = subs[ls].id;
    in[ls].dofs = subs[ls].dofs;
    in[ls].primal.assign(subs[ls].dofs.size(), 0);
  }
  const auto sets = dofSharingSets(comm, ownedMap, in);

  // Per subdomain: nodes (DOFs at the same coordinates) and, per interface
  // DOF, whether a DOF of a *different* node with the same interface set is
  // coupled to it in K.
  Vector twinOwned(Teuchos::rcpFromRef(ownedMap));
  std::vector<std::vector<char>> twin(subs.size());
  std::vector<std::vector<LO>> nodeOf(subs.size());
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const auto& s = subs[ls];
    const LO n = LO(s.dofs.size());
    std::map<std::vector<double>, LO> nodes;
    nodeOf[ls].resize(n);
    for (LO k = 0; k < n; ++k) {
      std::vector<double> x(s.coordinates.begin() + size_t(k) * dim, s.coordinates.begin() + size_t(k + 1) * dim);
      nodeOf[ls][k] = nodes.emplace(std::move(x), LO(nodes.size())).first->second;
    }
    twin[ls].assign(n, 0);
    const auto& colMap = *s.K->getColMap();
    typename CrsMatrix::local_inds_host_view_type cols;
    typename CrsMatrix::values_host_view_type vals;
    for (LO k = 0; k < n; ++k) {
      if (sets[ls][k].size() < 2) continue;
      s.K->getLocalRowView(s.K->getRowMap()->getLocalElement(GO(k)), cols, vals);
      for (size_t j = 0; j < cols.extent(0); ++j) {
        const LO c = LO(colMap.getGlobalElement(cols(j)));
        if (c < 0 || c >= n || nodeOf[ls][c] == nodeOf[ls][k]) continue;
        if (sets[ls][c] == sets[ls][k]) twin[ls][k] = 1;
      }
    }
  }
  // A node has a twin if any subdomain sees one (the element coupling two
  // nodes of a set belongs to one subdomain of that set): max over the
  // copies of each DOF, at its owner, then back to every copy.
  std::vector<GO> gids;
  for (const auto& s : subs) gids.insert(gids.end(), s.dofs.begin(), s.dofs.end());
  std::sort(gids.begin(), gids.end());
  gids.erase(std::unique(gids.begin(), gids.end()), gids.end());
  auto ovMap = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                    Teuchos::ArrayView<const GO>(gids), 0, ownedMap.getComm()));
  Vector twinOv(ovMap);
  for (size_t ls = 0; ls < subs.size(); ++ls)
    for (size_t k = 0; k < subs[ls].dofs.size(); ++k)
      if (twin[ls][k]) twinOv.replaceGlobalValue(subs[ls].dofs[k], 1.0);
  Tpetra::Export<LO, GO, Node> exporter(ovMap, Teuchos::rcpFromRef(ownedMap));
  twinOwned.doExport(twinOv, exporter, Tpetra::ABSMAX);
  twinOv.doImport(twinOwned, exporter, Tpetra::INSERT);
  auto t = twinOv.getData();

  // Vertices: interface nodes none of whose DOFs has a twin.
  std::vector<std::vector<char>> out(subs.size());
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const auto& s = subs[ls];
    const LO n = LO(s.dofs.size());
    std::map<LO, char> nodeHasTwin;
    for (LO k = 0; k < n; ++k)
      if (sets[ls][k].size() >= 2) nodeHasTwin[nodeOf[ls][k]] |= char(t[ovMap->getLocalElement(s.dofs[k])] != 0.0);
    out[ls].assign(n, 0);
    for (LO k = 0; k < n; ++k)
      if (sets[ls][k].size() >= 2 && !nodeHasTwin[nodeOf[ls][k]]) out[ls][k] = 1;
  }
  return out;
}

}  // namespace ddc
