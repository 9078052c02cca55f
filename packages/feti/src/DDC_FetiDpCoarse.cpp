// FETI-DP, coarse problem (doc/feti-dp.md "Dual problem"): the primal map,
// the coarse matrix S_PiPi = sum_s R^T S_PiPi^s R assembled over it, and its
// solver. See DDC_FetiDpImpl.hpp.
#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_FetiDpImpl.hpp"
#include "DDC_MapOwners.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

/// Primal map (GIDs = DOF ids, owned by the DOF's owner), the contiguous
/// coarse map with the same layout (MUMPS wants 0..N-1), the overlapped
/// coarse map of this rank's subdomains and the coarse matrix pattern.
void FetiDpSolver::Impl::buildCoarse() {
  std::vector<GO> ownedPrimal;
  coarseOwnedLid.clear();
  {
    // A DOF is primal if any (hence every) subdomain having it says so;
    // mark at the owner.
    Vector pOv(dofOvMap), pOwned(ownedMap), aOv(dofOvMap), aOwned(ownedMap);
    {
      auto p = pOv.getDataNonConst();
      auto a = aOv.getDataNonConst();
      for (const Sub& s : subs)
        for (LO k = 0; k < s.n; ++k) {
          if (s.primal[k]) p[s.ovLid[k]] = 1.0;
          if (s.cob.holdsConstraint(k)) a[s.ovLid[k]] = 1.0;
        }
    }
    pOwned.doExport(pOv, *dofExport, Tpetra::ADD);
    aOwned.doExport(aOv, *dofExport, Tpetra::ADD);
    auto p = pOwned.getData();
    auto a = aOwned.getData();
    coarseIsEdgeFace.clear();
    GO myEdgeFace = 0;
    for (LO l = 0; l < LO(p.size()); ++l)
      if (p[l] > 0.0) {
        ownedPrimal.push_back(ownedMap->getGlobalElement(l));
        coarseOwnedLid.push_back(l);
        coarseIsEdgeFace.push_back(a[l] > 0.0);
        myEdgeFace += a[l] > 0.0;
      }
    nEdgeFace = sumAll(mpi, myEdgeFace);
  }
  primalMap = makeMap(ownedPrimal, ownedMap->getIndexBase(), comm);
  coarseMap = rcp(new Map(kInvalidSize, ownedPrimal.size(), 0, comm));
  nCoarse = static_cast<GO>(coarseMap->getGlobalNumElements());
  std::vector<long long> offsets(size);
  {
    long long mine = coarseMap->getNodeNumElements() ? coarseMap->getMinGlobalIndex() : 0;
    MPI_Allgather(&mine, 1, MPI_LONG_LONG, offsets.data(), 1, MPI_LONG_LONG, mpi);
  }

  // Coarse GIDs of every subdomain's primal DOFs.
  std::vector<GO> gids;
  for (const Sub& s : subs)
    for (LO p = 0; p < s.np; ++p) gids.push_back(s.dofs[s.pDof[p]]);
  std::vector<int> pids;
  std::vector<LO> lids;
  owners(*primalMap, gids, pids, lids);
  std::vector<GO> ovGids;
  size_t k = 0;
  for (Sub& s : subs) {
    s.coarseGid.resize(s.np);
    s.coarseOwner.resize(s.np);
    for (LO p = 0; p < s.np; ++p, ++k) {
      DDC_ASSERT(pids[k] >= 0, "primal DOF " << gids[k] << " missing from the primal map");
      s.coarseGid[p] = offsets[pids[k]] + lids[k];
      s.coarseOwner[p] = pids[k];
      ovGids.push_back(s.coarseGid[p]);
    }
  }
  std::sort(ovGids.begin(), ovGids.end());
  ovGids.erase(std::unique(ovGids.begin(), ovGids.end()), ovGids.end());
  coarseOvMap = makeMap(ovGids, 0, comm);
  coarseImport = rcp(new Import(coarseMap, coarseOvMap));
  coarseExport = rcp(new Export(coarseOvMap, coarseMap));
  for (Sub& s : subs) {
    s.coarseOvLid.resize(s.np);
    for (LO p = 0; p < s.np; ++p) s.coarseOvLid[p] = coarseOvMap->getLocalElement(s.coarseGid[p]);
  }

  // Pattern of the coarse matrix: the dense S_PiPi^s blocks, sent to the
  // owners of their rows.
  std::vector<std::vector<CoarseRecord>> send(size);
  for (const Sub& s : subs)
    for (LO p = 0; p < s.np; ++p)
      for (LO q = 0; q < s.np; ++q) send[s.coarseOwner[p]].push_back(CoarseRecord{s.coarseGid[p], s.coarseGid[q], 0.0});
  std::vector<CoarseRecord> recv = exchangeRecords(mpi, send);
  const LO nOwned = LO(coarseMap->getNodeNumElements());
  std::vector<std::set<GO>> cols(nOwned);
  for (const auto& r : recv) cols[coarseMap->getLocalElement(r.row)].insert(r.col);
  std::vector<size_t> counts(nOwned);
  for (LO l = 0; l < nOwned; ++l) counts[l] = cols[l].size();
  coarse = rcp(new CrsMatrix(coarseMap, Teuchos::ArrayView<const size_t>(counts.data(), counts.size())));
  for (LO l = 0; l < nOwned; ++l) {
    std::vector<GO> c(cols[l].begin(), cols[l].end());
    std::vector<double> z(c.size(), 0.0);
    coarse->insertGlobalValues(coarseMap->getGlobalElement(l), Teuchos::ArrayView<const GO>(c.data(), c.size()),
                               Teuchos::ArrayView<const double>(z.data(), z.size()));
  }
  coarse->fillComplete(coarseMap, coarseMap);
  coarseSolver.reset();
  if (nCoarse > 0) {
    Teuchos::ParameterList p(coarseSolverParams);
    coarseSolver = factory.create(p, param("Coarse Solver"));
  }
}


/// Sum the S_PiPi^s blocks into the distributed coarse matrix: rows this
/// rank owns directly, the others as records sent to their owners (so the
/// records, 24 bytes per entry, cover only the rows shared with other ranks).
void FetiDpSolver::Impl::assembleCoarse() {
  coarse->resumeFill();
  coarse->setAllToScalar(0.0);
  std::vector<std::vector<CoarseRecord>> send(size);
  std::vector<double> row;
  for (Sub& s : subs) {
    row.resize(s.np);
    for (LO p = 0; p < s.np; ++p) {
      // row p of S^s (stored column-major)
      for (LO q = 0; q < s.np; ++q) row[q] = s.S[size_t(p) + size_t(q) * s.np];
      const int owner = s.coarseOwner[p];
      if (owner == rank) {
        coarse->sumIntoGlobalValues(s.coarseGid[p], s.np, row.data(), s.coarseGid.data());
      } else {
        for (LO q = 0; q < s.np; ++q) send[owner].push_back(CoarseRecord{s.coarseGid[p], s.coarseGid[q], row[q]});
      }
    }
    std::vector<double>().swap(s.S);  // needed again only after the next factorisation
  }
  std::vector<CoarseRecord> recv = exchangeRecords(mpi, send);
  for (auto& v : send) std::vector<CoarseRecord>().swap(v);
  for (const auto& r : recv) coarse->sumIntoGlobalValues(r.row, 1, &r.v, &r.col);
  coarse->fillComplete(coarseMap, coarseMap);
}

}  // namespace ddc
