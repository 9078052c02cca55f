// FETI-DP, coarse problem (doc/feti-dp.md "The dual problem"): the primal
// map, the coarse matrix S_PiPi = sum_s R^T S_PiPi^s R assembled over it,
// and its solver (CoarseProblem). See DDC_FetiDpImpl.hpp.
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

namespace {

/// The primal DOFs this rank owns (GIDs, ascending): a DOF is primal if any
/// (hence every) subdomain having it says so; marked at the owner. Per
/// coarse LID its ownedMap LID and whether it holds an edge/face
/// constraint value; the global number of those (collective).
std::vector<GO> markPrimalAtOwners(const Context& ctx, const std::vector<Subdomain>& subs, std::vector<LO>& ownedLid,
                                   std::vector<char>& isEdgeFace, GO& nEdgeFace) {
  std::vector<GO> ownedPrimal;
  Vector pOv(ctx.dofOvMap), pOwned(ctx.ownedMap), aOv(ctx.dofOvMap), aOwned(ctx.ownedMap);
  {
    auto p = pOv.getDataNonConst();
    auto a = aOv.getDataNonConst();
    for (const Subdomain& s : subs)
      for (LO k = 0; k < s.n; ++k) {
        if (s.primal[k]) p[s.ovLid[k]] = 1.0;
        if (s.cob.holdsConstraint(k)) a[s.ovLid[k]] = 1.0;
      }
  }
  pOwned.doExport(pOv, *ctx.dofExport, Tpetra::ADD);
  aOwned.doExport(aOv, *ctx.dofExport, Tpetra::ADD);
  auto p = pOwned.getData();
  auto a = aOwned.getData();
  isEdgeFace.clear();
  GO myEdgeFace = 0;
  for (LO l = 0; l < LO(p.size()); ++l)
    if (p[l] > 0.0) {
      ownedPrimal.push_back(ctx.ownedMap->getGlobalElement(l));
      ownedLid.push_back(l);
      isEdgeFace.push_back(a[l] > 0.0);
      myEdgeFace += a[l] > 0.0;
    }
  nEdgeFace = sumAll(ctx.mpi, myEdgeFace);
  return ownedPrimal;
}

/// Coarse GIDs and owners of every subdomain's primal DOFs (`sub`; offsets:
/// the first coarse GID of each rank); returns the coarse GIDs this rank's
/// subdomains touch, sorted and unique (collective).
std::vector<GO> numberSubdomainPrimals(const Context& ctx, const std::vector<Subdomain>& subs, const Map& primalMap,
                                       const std::vector<long long>& offsets,
                                       std::vector<CoarseProblem::Indices>& sub) {
  std::vector<GO> gids;
  for (const Subdomain& s : subs)
    for (LO p = 0; p < s.np; ++p) gids.push_back(s.dofs[s.pDof[p]]);
  std::vector<int> pids;
  std::vector<LO> lids;
  owners(primalMap, gids, pids, lids);
  std::vector<GO> ovGids;
  sub.assign(subs.size(), CoarseProblem::Indices());
  std::string msg;
  size_t k = 0;
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    CoarseProblem::Indices& ix = sub[ls];
    ix.gid.resize(subs[ls].np);
    ix.owner.resize(subs[ls].np);
    for (LO p = 0; p < subs[ls].np; ++p, ++k) {
      if (pids[k] < 0) {  // cannot happen: every primal DOF was marked at its owner above
        if (msg.empty()) msg = "FETI-DP: primal DOF " + std::to_string(gids[k]) + " missing from the primal map";
        continue;
      }
      ix.gid[p] = offsets[pids[k]] + lids[k];
      ix.owner[p] = pids[k];
      ovGids.push_back(ix.gid[p]);
    }
  }
  raiseCollectively<std::logic_error>(ctx.mpi, msg);
  std::sort(ovGids.begin(), ovGids.end());
  ovGids.erase(std::unique(ovGids.begin(), ovGids.end()), ovGids.end());
  return ovGids;
}

/// The pattern of the coarse matrix on `map`, zero-valued and fill-complete:
/// the dense S_PiPi^s blocks, sent to the owners of their rows (collective).
RCP<CrsMatrix> coarsePattern(const Context& ctx, const RCP<const Map>& map,
                             const std::vector<CoarseProblem::Indices>& sub) {
  std::vector<std::vector<CoarseRecord>> send(ctx.size);
  for (const CoarseProblem::Indices& ix : sub)
    for (size_t p = 0; p < ix.gid.size(); ++p)
      for (size_t q = 0; q < ix.gid.size(); ++q) send[ix.owner[p]].push_back(CoarseRecord{ix.gid[p], ix.gid[q], 0.0});
  std::vector<CoarseRecord> recv = exchangeRecords(ctx.mpi, send);
  const LO nOwned = LO(map->getNodeNumElements());
  std::vector<std::set<GO>> cols(nOwned);
  for (const auto& r : recv) cols[map->getLocalElement(r.row)].insert(r.col);
  std::vector<size_t> counts(nOwned);
  for (LO l = 0; l < nOwned; ++l) counts[l] = cols[l].size();
  auto matrix = rcp(new CrsMatrix(map, Teuchos::ArrayView<const size_t>(counts.data(), counts.size())));
  for (LO l = 0; l < nOwned; ++l) {
    std::vector<GO> c(cols[l].begin(), cols[l].end());
    std::vector<double> z(c.size(), 0.0);
    matrix->insertGlobalValues(map->getGlobalElement(l), Teuchos::ArrayView<const GO>(c.data(), c.size()),
                               Teuchos::ArrayView<const double>(z.data(), z.size()));
  }
  matrix->fillComplete(map, map);
  return matrix;
}

}  // namespace

/// Primal map (GIDs = DOF ids, owned by the DOF's owner), the contiguous
/// coarse map with the same layout (MUMPS wants 0..N-1), the overlapped
/// coarse map of this rank's subdomains and the coarse matrix pattern.
void CoarseProblem::build(const Context& ctx, const std::vector<Subdomain>& subs, const DirectSolverFactory& factory,
                          const Teuchos::ParameterList& params) {
  ownedLid.clear();
  const std::vector<GO> ownedPrimal = markPrimalAtOwners(ctx, subs, ownedLid, isEdgeFace, nEdgeFace);
  primalMap = makeMap(ownedPrimal, ctx.ownedMap->getIndexBase(), ctx.comm);
  map = rcp(new Map(kInvalidSize, ownedPrimal.size(), 0, ctx.comm));
  n = static_cast<GO>(map->getGlobalNumElements());
  std::vector<long long> offsets(ctx.size);
  {
    long long mine = map->getNodeNumElements() ? map->getMinGlobalIndex() : 0;
    MPI_Allgather(&mine, 1, MPI_LONG_LONG, offsets.data(), 1, MPI_LONG_LONG, ctx.mpi);
  }
  const std::vector<GO> ovGids = numberSubdomainPrimals(ctx, subs, *primalMap, offsets, sub);
  ovMap = makeMap(ovGids, 0, ctx.comm);
  import = rcp(new Import(map, ovMap));
  exporter = rcp(new Export(ovMap, map));
  for (Indices& ix : sub) {
    ix.ovLid.resize(ix.gid.size());
    for (size_t p = 0; p < ix.gid.size(); ++p) ix.ovLid[p] = ovMap->getLocalElement(ix.gid[p]);
  }
  matrix = coarsePattern(ctx, map, sub);
  solver.reset();
  if (n > 0) {
    Teuchos::ParameterList p(params);
    solver = factory.create(p, ctx.param("Coarse Solver"));
  }
  ovWork = rcp(new Vector(ovMap));
  work = rcp(new Vector(map));
  sol = rcp(new Vector(map));
}

/// Sum the S_PiPi^s blocks into the distributed coarse matrix: rows this
/// rank owns directly, the others as records sent to their owners (so the
/// records, 24 bytes per entry, cover only the rows shared with other ranks),
/// and factorise it.
void CoarseProblem::assembleAndFactor(const Context& ctx, std::vector<std::vector<double>>& S, bool analysed) {
  if (n == 0) return;
  matrix->resumeFill();
  matrix->setAllToScalar(0.0);
  std::vector<std::vector<CoarseRecord>> send(ctx.size);
  std::vector<double> row;
  for (size_t ls = 0; ls < sub.size(); ++ls) {
    const Indices& ix = sub[ls];
    const LO np = LO(ix.gid.size());
    row.resize(np);
    for (LO p = 0; p < np; ++p) {
      // row p of S^s (stored column-major)
      for (LO q = 0; q < np; ++q) row[q] = S[ls][size_t(p) + size_t(q) * np];
      const int owner = ix.owner[p];
      if (owner == ctx.rank) {
        matrix->sumIntoGlobalValues(ix.gid[p], np, row.data(), ix.gid.data());
      } else {
        for (LO q = 0; q < np; ++q) send[owner].push_back(CoarseRecord{ix.gid[p], ix.gid[q], row[q]});
      }
    }
    std::vector<double>().swap(S[ls]);  // needed again only after the next factorisation
  }
  std::vector<CoarseRecord> recv = exchangeRecords(ctx.mpi, send);
  for (auto& v : send) std::vector<CoarseRecord>().swap(v);
  for (const auto& r : recv) matrix->sumIntoGlobalValues(r.row, 1, &r.v, &r.col);
  matrix->fillComplete(map, map);
  try {
    if (!analysed) solver->symbolic(matrix);
    solver->numeric();
  } catch (const SolverError& e) {
    // The coarse solver's errors are collective (same INFOG on every rank).
    DDC_THROW(SolverError, "FETI-DP: the coarse matrix S_PiPi (" << n << " primal DOFs) could not be factorised: "
                                                                 << e.what() << " (is the whole structure floating?)");
  }
}

void CoarseProblem::solve(const Vector* fPi) {
  const double t0 = MPI_Wtime();
  work->putScalar(0.0);
  work->doExport(*ovWork, *exporter, Tpetra::ADD);
  if (fPi) work->update(1.0, *fPi, 1.0);
  solver->solve(*work, *sol);
  ovWork->doImport(*sol, *import, Tpetra::INSERT);
  tSolve += MPI_Wtime() - t0;
}

}  // namespace ddc
