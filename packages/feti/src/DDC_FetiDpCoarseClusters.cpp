// BDDC, the coarse solve by clusters (doc/feti-dp.md "BDDC"; three-level
// BDDC, Tu 2007): instead of factorising S_PiPi = sum_s R^T S_PiPi^s R,
// this rank's subdomains are grouped into clusters, each cluster's
// S_PiPi^s are summed into one matrix A^c on the coarse DOFs it touches,
// and S_PiPi^{-1} is approximated by one application of BDDC with the
// clusters as subdomains (FetiDpSolver::applyInverseApproximately()): the
// clusters' own factorisations and a third-level coarse problem on the
// coarse DOFs shared by >= 3 clusters. It sits in the BDDC preconditioner,
// so the answer stays exact; the approximation costs iterations. See
// DDC_FetiDpImpl.hpp.
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_FetiDpImpl.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {

/// Groups of about `size` of this rank's subdomains, each grown breadth
/// first from the lowest-numbered subdomain not yet taken over the
/// subdomains that share a coarse DOF with one already in it.
std::vector<std::vector<size_t>> groupSubdomains(const CoarseProblem& coarse, int size) {
  const size_t nLocal = coarse.sub.size();
  std::vector<std::vector<size_t>> touching(coarse.ovMap->getNodeNumElements());
  for (size_t ls = 0; ls < nLocal; ++ls)
    for (LO lid : coarse.sub[ls].ovLid) touching[size_t(lid)].push_back(ls);
  std::vector<char> taken(nLocal, 0);
  std::vector<std::vector<size_t>> groups;
  for (size_t seed = 0; seed < nLocal; ++seed) {
    if (taken[seed]) continue;
    std::vector<size_t> group{seed};
    taken[seed] = 1;
    for (size_t q = 0; q < group.size() && group.size() < size_t(size); ++q)
      for (LO lid : coarse.sub[group[q]].ovLid)
        for (size_t t : touching[size_t(lid)])
          if (!taken[t] && group.size() < size_t(size)) {
            taken[t] = 1;
            group.push_back(t);
          }
    groups.push_back(std::move(group));
  }
  return groups;
}

/// The coarse DOFs (GIDs of coarse.map) of a cluster, sorted, and where
/// each member's primal DOFs sit among them.
std::vector<GO> clusterDofs(const CoarseProblem& coarse, CoarseClusters::Cluster& c) {
  std::vector<GO> dofs;
  for (size_t ls : c.members) dofs.insert(dofs.end(), coarse.sub[ls].gid.begin(), coarse.sub[ls].gid.end());
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  c.pos.assign(c.members.size(), {});
  for (size_t m = 0; m < c.members.size(); ++m)
    for (GO g : coarse.sub[c.members[m]].gid)
      c.pos[m].push_back(LO(std::lower_bound(dofs.begin(), dofs.end(), g) - dofs.begin()));
  return dofs;
}

/// The zero-valued, fill-complete pattern of A^c: the members' dense blocks.
RCP<CrsMatrix> clusterPattern(const CoarseClusters::Cluster& c, LO n) {
  std::vector<std::vector<GO>> cols(static_cast<size_t>(n));
  for (const auto& pos : c.pos)
    for (LO p : pos) cols[size_t(p)].insert(cols[size_t(p)].end(), pos.begin(), pos.end());
  std::vector<size_t> counts(static_cast<size_t>(n));
  for (LO r = 0; r < n; ++r) {
    auto& cr = cols[size_t(r)];
    std::sort(cr.begin(), cr.end());
    cr.erase(std::unique(cr.begin(), cr.end()), cr.end());
    counts[size_t(r)] = cr.size();
  }
  auto self = rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
  auto rowMap = rcp(new Map(Tpetra::global_size_t(n), 0, self));
  auto A = rcp(new CrsMatrix(rowMap, Teuchos::ArrayView<const size_t>(counts.data(), counts.size())));
  for (LO r = 0; r < n; ++r) {
    const auto& cr = cols[size_t(r)];
    std::vector<double> z(cr.size(), 0.0);
    A->insertGlobalValues(GO(r), Teuchos::ArrayView<const GO>(cr.data(), cr.size()),
                          Teuchos::ArrayView<const double>(z.data(), z.size()));
  }
  A->fillComplete(rowMap, rowMap);
  return A;
}

/// Per coarse DOF of ovMap: 1 if it is a third-level primal DOF, shared by
/// >= 3 clusters, or by 2 clusters and only 2 subdomains (collective).
std::vector<char> thirdLevelPrimal(const CoarseProblem& coarse, const std::vector<std::vector<GO>>& dofs) {
  Vector cOv(coarse.ovMap), sOv(coarse.ovMap), c(coarse.map), s(coarse.map);
  {
    auto cv = cOv.getDataNonConst();
    auto sv = sOv.getDataNonConst();
    for (const auto& d : dofs)
      for (GO g : d) cv[coarse.ovMap->getLocalElement(g)] += 1.0;
    for (const auto& ix : coarse.sub)
      for (LO lid : ix.ovLid) sv[lid] += 1.0;
  }
  c.doExport(cOv, *coarse.exporter, Tpetra::ADD);
  s.doExport(sOv, *coarse.exporter, Tpetra::ADD);
  {
    auto cv = c.getDataNonConst();
    auto sv = s.getData();
    for (size_t k = 0; k < cv.size(); ++k) cv[k] = (cv[k] >= 3.0 || (cv[k] == 2.0 && sv[k] == 2.0)) ? 1.0 : 0.0;
  }
  cOv.doImport(c, *coarse.import, Tpetra::INSERT);
  auto cv = cOv.getData();
  std::vector<char> primal(cv.size());
  for (size_t k = 0; k < cv.size(); ++k) primal[k] = cv[k] > 0.0;
  return primal;
}

}  // namespace

void CoarseClusters::build(const Context& ctx, const CoarseProblem& coarse, const DirectSolverFactory& factory) {
  clusters.clear();
  for (auto& members : groupSubdomains(coarse, coarse.clusterSize)) {
    clusters.emplace_back();
    clusters.back().members = std::move(members);
  }
  std::vector<std::vector<GO>> dofs;
  for (Cluster& c : clusters) dofs.push_back(clusterDofs(coarse, c));
  const std::vector<char> primalOv = thirdLevelPrimal(coarse, dofs);

  long long mine = static_cast<long long>(clusters.size()), first = 0;
  MPI_Exscan(&mine, &first, 1, MPI_LONG_LONG, MPI_SUM, ctx.mpi);
  if (ctx.rank == 0) first = 0;
  numClusters = sumAll(ctx.mpi, GO(mine));
  std::vector<FetiSubdomain> fs;
  GO myPrimal = 0;
  for (size_t k = 0; k < clusters.size(); ++k) {
    Cluster& c = clusters[k];
    const LO n = LO(dofs[k].size());
    c.A = clusterPattern(c, n);
    FetiSubdomain f;
    f.id = int(first + (long long)k);
    f.dofs = dofs[k];
    f.primal.resize(size_t(n));
    for (LO j = 0; j < n; ++j) f.primal[size_t(j)] = primalOv[size_t(coarse.ovMap->getLocalElement(dofs[k][size_t(j)]))];
    f.K = c.A;
    fs.push_back(std::move(f));
  }
  {
    // the third-level primal DOFs, each counted at its owner
    auto owned = std::vector<char>(coarse.map->getNodeNumElements(), 0);
    for (size_t k = 0; k < clusters.size(); ++k)
      for (size_t j = 0; j < dofs[k].size(); ++j) {
        const LO l = coarse.map->getLocalElement(dofs[k][j]);
        if (l != Teuchos::OrdinalTraits<LO>::invalid() && fs[k].primal[j]) owned[size_t(l)] = 1;
      }
    for (char o : owned) myPrimal += o;
  }
  numPrimal = sumAll(ctx.mpi, myPrimal);
  Teuchos::ParameterList params(coarse.clusterParams);
  inner = std::make_unique<FetiDpSolver>(ctx.comm, params, ctx.param("Coarse Clusters"), factory);
  inner->setTopology(std::move(fs), coarse.map);
}

void CoarseClusters::numeric(const std::vector<std::vector<double>>& S) {
  std::vector<double> row;
  std::vector<GO> cols;
  for (Cluster& c : clusters) {
    c.A->resumeFill();
    c.A->setAllToScalar(0.0);
    for (size_t m = 0; m < c.members.size(); ++m) {
      const std::vector<double>& Ss = S[c.members[m]];
      const std::vector<LO>& pos = c.pos[m];
      const size_t np = pos.size();
      cols.assign(pos.begin(), pos.end());
      row.resize(np);
      for (size_t p = 0; p < np; ++p) {
        for (size_t q = 0; q < np; ++q) row[q] = Ss[p + q * np];  // row p of S^s (column-major)
        c.A->sumIntoGlobalValues(GO(pos[p]), LO(np), row.data(), cols.data());
      }
    }
    c.A->fillComplete(c.A->getRowMap(), c.A->getRowMap());
  }
  inner->numeric();
}

}  // namespace ddc
