// FETI-DP, interface (doc/feti-dp.md "Unknowns", "The jump operator B",
// "Extra rows"): the checks of the caller's subdomains, DOF multiplicities,
// which DOFs are primal / dual (setTopology()), and the JumpOperator's rows:
// the compatibility rows of B~ (one per pair of subdomains sharing a
// non-primal DOF), the caller's extra rows split over the copies of shared
// dual DOFs, and the LM maps. See DDC_FetiDpImpl.hpp.
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

// ---------------------------------------------------------------------------
// topology
// ---------------------------------------------------------------------------

namespace {

/// The connected parts of the graph of K (on MPI_COMM_SELF, square): part[k]
/// per row, numbered 0.. in the order of their lowest row; returns the
/// number of parts.
int connectedParts(const CrsMatrix& K, std::vector<int>& part) {
  const LO n = LO(K.getNodeNumRows());
  std::vector<LO> parent(static_cast<size_t>(n));
  for (LO k = 0; k < n; ++k) parent[size_t(k)] = k;
  auto root = [&](LO k) {
    while (parent[size_t(k)] != k) k = parent[size_t(k)] = parent[size_t(parent[size_t(k)])];
    return k;
  };
  const auto& colMap = *K.getColMap();
  const auto& rowMap = *K.getRowMap();
  CrsMatrix::local_inds_host_view_type cols;
  CrsMatrix::values_host_view_type vals;
  for (LO k = 0; k < n; ++k) {
    K.getLocalRowView(k, cols, vals);
    for (size_t e = 0; e < cols.extent(0); ++e) {
      const LO c = rowMap.getLocalElement(colMap.getGlobalElement(cols(e)));
      if (c == Teuchos::OrdinalTraits<LO>::invalid()) continue;
      const LO a = root(k), b = root(c);
      if (a != b) parent[size_t(std::max(a, b))] = std::min(a, b);
    }
  }
  part.assign(size_t(n), -1);
  int count = 0;
  for (LO k = 0; k < n; ++k) {
    const LO r = root(k);
    part[size_t(k)] = r == k ? count++ : part[size_t(r)];
  }
  return count;
}

/// Step 1 of setTopology(): the caller's subdomains into `subs` (their
/// component, coordinate and dimension data aside, for the edge/face
/// constraints), checked one by one; returns the first error or "".
std::string takeSubdomains(std::vector<FetiSubdomain>& local, std::vector<Subdomain>& subs,
                           std::vector<std::vector<int>>& components, std::vector<std::vector<double>>& coords,
                           std::vector<int>& dims) {
  std::ostringstream err;
  subs.resize(local.size());
  components.resize(local.size());
  coords.resize(local.size());
  dims.resize(local.size());
  for (size_t ls = 0; ls < local.size() && err.str().empty(); ++ls) {
    FetiSubdomain& in = local[ls];
    Subdomain& s = subs[ls];
    s.id = in.id;
    s.n = static_cast<LO>(in.dofs.size());
    s.dofs = std::move(in.dofs);
    s.primal = std::move(in.primal);
    s.constrainable = std::move(in.constrainable);
    if (s.constrainable.empty()) s.constrainable.assign(s.dofs.size(), 0);
    s.K = in.K;
    s.Kuser = Teuchos::null;
    s.cob = ChangeOfBasis();
    components[ls] = std::move(in.component);
    coords[ls] = std::move(in.coordinates);
    dims[ls] = in.dim;
    if (s.primal.size() != s.dofs.size()) {
      err << "subdomain " << s.id << ": " << s.primal.size() << " primal flags for " << s.dofs.size() << " DOFs";
    } else if (s.constrainable.size() != s.dofs.size()) {
      err << "subdomain " << s.id << ": " << s.constrainable.size() << " constrainable flags for " << s.dofs.size()
          << " DOFs";
    } else if (s.K.is_null() || !s.K->isFillComplete()) {
      err << "subdomain " << s.id << ": K must be a fill-complete CrsMatrix";
    } else if (s.K->getRowMap()->getGlobalNumElements() != s.dofs.size() ||
               s.K->getRowMap()->getNodeNumElements() != s.dofs.size() ||
               !s.K->getRowMap()->isSameAs(*s.K->getDomainMap()) ||
               !s.K->getRowMap()->isSameAs(*s.K->getRangeMap()) || s.K->getRowMap()->getIndexBase() != 0 ||
               !s.K->getRowMap()->isContiguous()) {
      err << "subdomain " << s.id << ": K must live on MPI_COMM_SELF with row = range = domain map 0.."
          << s.dofs.size() << "-1 (one row per DOF), got " << s.K->getRowMap()->getGlobalNumElements() << " rows";
    } else {
      std::vector<GO> sorted(s.dofs);
      std::sort(sorted.begin(), sorted.end());
      auto dup = std::adjacent_find(sorted.begin(), sorted.end());
      if (dup != sorted.end()) err << "subdomain " << s.id << ": DOF " << *dup << " appears twice";
    }
  }
  return err.str();
}

/// Subdomain ids unique across ranks; Subdomain::index, and the sides of
/// extra rows: the connected parts of each subdomain, numbered across all
/// subdomains in the order of their index (Subdomain::part, partBase;
/// returns the number of sides, at least 1). Collective.
GO numberSubdomainsAndSides(const Context& ctx, std::vector<Subdomain>& subs) {
  int nLocal = static_cast<int>(subs.size());
  std::vector<int> counts(ctx.size), displs(ctx.size, 0);
  MPI_Allgather(&nLocal, 1, MPI_INT, counts.data(), 1, MPI_INT, ctx.mpi);
  for (int r = 1; r < ctx.size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<int> ids(subs.size()), all(displs[ctx.size - 1] + counts[ctx.size - 1] + 1);
  for (size_t i = 0; i < subs.size(); ++i) ids[i] = subs[i].id;
  MPI_Allgatherv(ids.empty() ? all.data() : ids.data(), nLocal, MPI_INT, all.data(), counts.data(), displs.data(),
                 MPI_INT, ctx.mpi);
  all.pop_back();
  std::sort(all.begin(), all.end());
  auto dup = std::adjacent_find(all.begin(), all.end());
  if (dup != all.end())
    throw std::invalid_argument("FetiDpSolver::setTopology: subdomain id " + std::to_string(*dup) + " is used twice");
  for (Subdomain& s : subs) s.index = int(std::lower_bound(all.begin(), all.end(), s.id) - all.begin());
  std::vector<int> parts(all.size(), 0);
  for (Subdomain& s : subs) parts[size_t(s.index)] = connectedParts(*s.K, s.part);
  MPI_Allreduce(MPI_IN_PLACE, parts.data(), int(parts.size()), MPI_INT, MPI_SUM, ctx.mpi);
  std::vector<int> base(parts.size() + 1, 0);
  for (size_t k = 0; k < parts.size(); ++k) base[k + 1] = base[k] + parts[k];
  for (Subdomain& s : subs) s.partBase = base[size_t(s.index)];
  return std::max<GO>(1, GO(base.back()));
}

/// Step 2: the overlapped DOF map of this rank's subdomains, its Import /
/// Export to the owned map and Subdomain::ovLid; every DOF must be in the
/// owned map. Collective.
void buildDofMaps(Context& ctx, std::vector<Subdomain>& subs) {
  std::vector<GO> gids;
  for (const Subdomain& s : subs) gids.insert(gids.end(), s.dofs.begin(), s.dofs.end());
  std::sort(gids.begin(), gids.end());
  gids.erase(std::unique(gids.begin(), gids.end()), gids.end());
  ctx.dofOvMap = makeMap(gids, ctx.ownedMap->getIndexBase(), ctx.comm);
  std::vector<int> pids;
  std::vector<LO> lids;
  owners(*ctx.ownedMap, gids, pids, lids);
  std::string msg;
  for (size_t k = 0; k < gids.size(); ++k)
    if (pids[k] < 0) {
      msg = "FetiDpSolver::setTopology: DOF " + std::to_string(gids[k]) + " of a subdomain on rank " +
            std::to_string(ctx.rank) + " is not in the owned DOF map";
      break;
    }
  raiseCollectively<std::invalid_argument>(ctx.mpi, msg);
  ctx.dofImport = rcp(new Import(ctx.ownedMap, ctx.dofOvMap));
  ctx.dofExport = rcp(new Export(ctx.dofOvMap, ctx.ownedMap));
  for (Subdomain& s : subs) {
    s.ovLid.resize(s.n);
    for (LO k = 0; k < s.n; ++k) s.ovLid[k] = ctx.dofOvMap->getLocalElement(s.dofs[k]);
  }
}

/// Step 3: the multiplicity of each DOF (Context::ownedMult; returned per
/// LID of dofOvMap), counted at the owner, which also checks that a DOF is
/// primal in all subdomains sharing it or in none. Collective.
std::vector<int> countMultiplicity(Context& ctx, const std::vector<Subdomain>& subs) {
  std::vector<int> ovMult(ctx.dofOvMap->getNodeNumElements());
  Vector cOv(ctx.dofOvMap), pOv(ctx.dofOvMap), cOwned(ctx.ownedMap), pOwned(ctx.ownedMap);
  {
    auto c = cOv.getDataNonConst();
    auto p = pOv.getDataNonConst();
    for (const Subdomain& s : subs)
      for (LO k = 0; k < s.n; ++k) {
        c[s.ovLid[k]] += 1.0;
        if (s.primal[k]) p[s.ovLid[k]] += 1.0;
      }
  }
  cOwned.doExport(cOv, *ctx.dofExport, Tpetra::ADD);
  pOwned.doExport(pOv, *ctx.dofExport, Tpetra::ADD);
  std::string msg;
  {
    auto c = cOwned.getData();
    auto p = pOwned.getData();
    ctx.ownedMult.assign(c.size(), 0);
    for (LO l = 0; l < LO(c.size()); ++l) {
      ctx.ownedMult[l] = static_cast<int>(std::lround(c[l]));
      const long np = std::lround(p[l]);
      if (np != 0 && np != ctx.ownedMult[l] && msg.empty())
        msg = "FetiDpSolver::setTopology: DOF " + std::to_string(ctx.ownedMap->getGlobalElement(l)) +
              " is primal in " + std::to_string(np) + " of the " + std::to_string(ctx.ownedMult[l]) +
              " subdomains sharing it; a DOF must be primal in all of them or in none";
    }
  }
  raiseCollectively<std::invalid_argument>(ctx.mpi, msg);
  cOv.doImport(cOwned, *ctx.dofImport, Tpetra::INSERT);
  auto c = cOv.getData();
  for (size_t l = 0; l < ovMult.size(); ++l) ovMult[l] = static_cast<int>(std::lround(c[l]));
  return ovMult;
}

/// A DOF is constrainable in every subdomain having it if it is in one:
/// the change of basis must choose the same representatives everywhere.
/// Collective.
void shareConstrainable(const Context& ctx, std::vector<Subdomain>& subs) {
  Vector fOv(ctx.dofOvMap), fOwned(ctx.ownedMap);
  {
    auto f = fOv.getDataNonConst();
    for (const Subdomain& s : subs)
      for (LO k = 0; k < s.n; ++k)
        if (s.constrainable[k]) f[s.ovLid[k]] = 1.0;
  }
  fOwned.doExport(fOv, *ctx.dofExport, Tpetra::ADD);
  fOv.doImport(fOwned, *ctx.dofImport, Tpetra::INSERT);
  auto f = fOv.getData();
  for (Subdomain& s : subs)
    for (LO k = 0; k < s.n; ++k) s.constrainable[k] = f[s.ovLid[k]] > 0.0 ? 1 : 0;
}

/// Step 4: the splits of one subdomain: remainder / primal, and for the
/// Dirichlet preconditioner the remainder into dual interface (Delta:
/// shared, non-primal) and interior (I) DOFs.
void splitDofs(Subdomain& s, const std::vector<int>& ovMult) {
  s.rIdx.assign(s.n, kNone);
  s.pIdx.assign(s.n, kNone);
  s.invMult.assign(s.n, 1.0);
  s.rDof.clear();
  s.pDof.clear();
  for (LO k = 0; k < s.n; ++k) {
    s.invMult[k] = 1.0 / ovMult[s.ovLid[k]];
    if (s.primal[k]) {
      s.pIdx[k] = LO(s.pDof.size());
      s.pDof.push_back(k);
    } else {
      s.rIdx[k] = LO(s.rDof.size());
      s.rDof.push_back(k);
    }
  }
  s.nr = LO(s.rDof.size());
  s.np = LO(s.pDof.size());
  s.dIdx.assign(s.nr, kNone);
  s.iIdx.assign(s.nr, kNone);
  s.iR.clear();
  s.nd = 0;
  for (LO r = 0; r < s.nr; ++r) {
    // Dual: shared with another subdomain, or touched by extra rows (so
    // that the Dirichlet preconditioner sees those rows too).
    if (ovMult[s.ovLid[s.rDof[r]]] >= 2 || s.constrainable[s.rDof[r]]) {
      s.dIdx[r] = s.nd++;
    } else {
      s.iIdx[r] = LO(s.iR.size());
      s.iR.push_back(r);
    }
  }
  s.ni = LO(s.iR.size());
}

}  // namespace

void FetiDpSolver::Impl::buildTopology(std::vector<FetiSubdomain> local, RCP<const Map> owned) {
  haveTopology = analysed = factored = false;
  subs.clear();
  {
    const auto scaling = jump.scaling;
    jump = JumpOperator();
    jump.scaling = scaling;
  }
  if (owned.is_null()) throw std::invalid_argument("FetiDpSolver::setTopology: null owned DOF map");
  ctx.ownedMap = owned;

  // 1. Per-subdomain sanity (local checks, raised collectively), ids.
  std::vector<std::vector<int>> components;
  std::vector<std::vector<double>> coords;
  std::vector<int> dims;
  const std::string err = takeSubdomains(local, subs, components, coords, dims);
  raiseCollectively<std::invalid_argument>(ctx.mpi, err.empty() ? "" : "FetiDpSolver::setTopology: " + err);
  jump.sideSpan = numberSubdomainsAndSides(ctx, subs);

  // 2. Overlapped DOF map of this rank's subdomains; all DOFs in the owned map.
  buildDofMaps(ctx, subs);

  // 3. Multiplicity and primal consistency: counts summed at the owner.
  const std::vector<int> ovMult = countMultiplicity(ctx, subs);
  shareConstrainable(ctx, subs);
  addEdgeFaceConstraints(components, coords, dims);

  // 4. Per-subdomain splits.
  for (Subdomain& s : subs) splitDofs(s, ovMult);

  jump.buildCompatibility(ctx, subs);
  coarse.build(ctx, subs, factory, coarseSolverParams);
  std::string msg;
  try {
    dual.build(subs, factory, localSolverParams, param("Local Solver"));
    prec.build(subs, factory, localSolverParams, param("Local Solver"));
  } catch (const std::exception& e) {
    msg = std::string("FetiDpSolver::setTopology: ") + e.what();
  }
  raiseCollectively<std::invalid_argument>(ctx.mpi, msg);
  dofOvWork = rcp(new Vector(ctx.dofOvMap));
  if (bddc) iface.build(ctx, subs);
  makeOperators();
  haveTopology = true;
}

/// Edge/face constraints ("Primal Constraints"; doc/feti-dp.md): classify the
/// interface by the subdomains sharing each DOF (findEdgeFaceConstraints()),
/// make the representative DOFs of each group primal and work on K^s in the
/// basis where they hold the group's constraint values (ChangeOfBasis).
void FetiDpSolver::Impl::addEdgeFaceConstraints(const std::vector<std::vector<int>>& components,
                                                const std::vector<std::vector<double>>& coords,
                                                const std::vector<int>& dims) {
  coarse.nEdgeFace = 0;
  if (primalChoice == PrimalConstraints::Vertices) return;
  const std::string choice = primalConstraintNames()[size_t(primalChoice)];
  std::string msg;
  int dmin = INT_MAX, dmax = INT_MIN;
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    dmin = std::min(dmin, dims[ls]);
    dmax = std::max(dmax, dims[ls]);
    if (msg.empty() && ((dims[ls] != 2 && dims[ls] != 3) || components[ls].size() != subs[ls].dofs.size()))
      msg = "FetiDpSolver::setTopology: subdomain " + std::to_string(subs[ls].id) + ": '" +
            param("Primal Constraints") + "' = " + choice + " needs FetiSubdomain::dim (2 or 3, got " +
            std::to_string(dims[ls]) + ") and one FetiSubdomain::component per DOF (got " +
            std::to_string(components[ls].size()) + " for " + std::to_string(subs[ls].dofs.size()) +
            " DOFs); or set it to Vertices";
    else if (msg.empty() && rotations && coords[ls].size() != subs[ls].dofs.size() * size_t(dims[ls]))
      msg = "FetiDpSolver::setTopology: subdomain " + std::to_string(subs[ls].id) + ": '" +
            param("Rotational Constraints") + "' = true needs FetiSubdomain::coordinates (" +
            std::to_string(dims[ls]) + " per DOF, got " + std::to_string(coords[ls].size()) + " for " +
            std::to_string(subs[ls].dofs.size()) + " DOFs); or set it to false";
  }
  raiseCollectively<std::invalid_argument>(ctx.mpi, msg);
  int loc[2] = {dmin == INT_MAX ? INT_MIN : -dmin, dmax}, glob[2];
  MPI_Allreduce(loc, glob, 2, MPI_INT, MPI_MAX, ctx.mpi);
  if (glob[1] == INT_MIN) return;  // no subdomains at all
  if (-glob[0] != glob[1])
    throw std::invalid_argument("FetiDpSolver::setTopology: the subdomains disagree on FetiSubdomain::dim (" +
                                std::to_string(-glob[0]) + " and " + std::to_string(glob[1]) + ")");
  std::vector<EdgeFaceInput> in(subs.size());
  for (size_t ls = 0; ls < subs.size(); ++ls)
    in[ls] = EdgeFaceInput{subs[ls].id, subs[ls].dofs, subs[ls].primal, components[ls],
                           rotations ? coords[ls] : std::vector<double>()};
  const auto groups = findEdgeFaceConstraints(ctx.mpi, *ctx.ownedMap, in, glob[1], primalChoice, rotations);
  for (size_t ls = 0; ls < subs.size() && msg.empty(); ++ls) {
    Subdomain& s = subs[ls];
    if (groups[ls].empty()) continue;
    try {
      s.cob = ChangeOfBasis(s.n, groups[ls], s.constrainable);
      for (LO k = 0; k < s.n; ++k)
        if (s.cob.holdsConstraint(k)) s.primal[k] = 1;
      s.Kuser = s.K;
      s.K = s.cob.setPattern(*s.Kuser);
    } catch (const std::exception& e) {
      msg = "FetiDpSolver::setTopology: subdomain " + std::to_string(s.id) + ": change of basis: " + e.what();
    }
  }
  raiseCollectively<std::invalid_argument>(ctx.mpi, msg);
}

// ---------------------------------------------------------------------------
// JumpOperator: the rows
// ---------------------------------------------------------------------------

/// Compatibility constraints: the owner of each shared non-primal DOF
/// receives (DOF, subdomain id, rank, local subdomain, local DOF) from every
/// subdomain having it, creates one row per pair of them (+1 for the smaller
/// id, -1 for the other), keeps the list of copies (sharers, for splitting
/// extra rows) and returns the entries to the subdomains' ranks.
void JumpOperator::buildCompatibility(const Context& ctx, const std::vector<Subdomain>& subs) {
  rows.assign(subs.size(), Rows());
  std::vector<int> pids;
  std::vector<LO> lids;
  std::vector<std::vector<ShareRecord>> send(ctx.size);
  {
    // Owners of the shared non-primal DOFs of this rank's subdomains.
    std::vector<GO> gids;
    std::vector<std::pair<int, LO>> who;  // (local subdomain, local DOF)
    for (size_t ls = 0; ls < subs.size(); ++ls) {
      const Subdomain& s = subs[ls];
      for (LO r = 0; r < s.nr; ++r)
        if (s.dIdx[r] != kNone && s.invMult[s.rDof[r]] < 1.0) {
          gids.push_back(s.dofs[s.rDof[r]]);
          who.emplace_back(int(ls), s.rDof[r]);
        }
    }
    owners(*ctx.ownedMap, gids, pids, lids);
    for (size_t k = 0; k < gids.size(); ++k)
      send[pids[k]].push_back(ShareRecord{gids[k], subs[who[k].first].id, ctx.rank, who[k].first, who[k].second});
  }
  std::vector<ShareRecord> recv = exchangeRecords(ctx.mpi, send);
  std::sort(recv.begin(), recv.end(), [](const ShareRecord& a, const ShareRecord& b) {
    return a.gid != b.gid ? a.gid < b.gid : a.subId < b.subId;
  });

  // Count rows, then number them contiguously across ranks (rank order).
  GO nRows = 0, nGroups = 0;
  for (size_t a = 0; a < recv.size();) {
    size_t b = a;
    while (b < recv.size() && recv[b].gid == recv[a].gid) ++b;
    const GO m = GO(b - a);
    nRows += m * (m - 1) / 2;
    ++nGroups;
    a = b;
  }
  long long myRows = nRows, offset = 0;
  MPI_Exscan(&myRows, &offset, 1, MPI_LONG_LONG, MPI_SUM, ctx.mpi);
  if (ctx.rank == 0) offset = 0;
  nDual = sumAll(ctx.mpi, nGroups);

  std::vector<std::vector<LmRecord>> reply(ctx.size);
  GO next = offset;
  sharers.clear();
  for (size_t a = 0; a < recv.size();) {
    size_t b = a;
    while (b < recv.size() && recv[b].gid == recv[a].gid) ++b;
    if (b - a >= 2) sharers[recv[a].gid].assign(recv.begin() + long(a), recv.begin() + long(b));
    for (size_t i = a; i < b; ++i)
      for (size_t j = i + 1; j < b; ++j) {
        reply[recv[i].rank].push_back(LmRecord{next, recv[i].localSub, recv[i].dof, +1.0});
        reply[recv[j].rank].push_back(LmRecord{next, recv[j].localSub, recv[j].dof, -1.0});
        ++next;
      }
    a = b;
  }
  nCompat = sumAll(ctx.mpi, nRows);
  compatOffset = offset;
  nCompatOwned = nRows;

  std::vector<LmRecord> entries = exchangeRecords(ctx.mpi, reply);
  for (const auto& e : entries) rows[e.localSub].compat.push_back(GidEntry{e.lm, e.dof, e.coef});
  finalize(ctx, subs);
}

/// The extra rows of each local subdomain (new basis, LM GIDs) into
/// Rows::extra. An entry on a dual DOF shared by several subdomains is
/// split over all its copies: coefficient c omega_k on copy k (omega = the
/// compatibility scaling weights, a partition of unity; set by
/// computeWeights(), 1/m_j until then), so that with B_D = D_side c on every
/// copy the product B B_D^T is the identity on the extra rows as on the
/// compatibility rows. The continuity of the copies makes the constraint
/// the same: sum_k c omega_k u_j^k = c u_j. Entries on other DOFs stay where
/// the caller put them.
std::string JumpOperator::distributeExtra(const Context& ctx, const std::vector<Subdomain>& subs,
                                          const std::vector<std::vector<GidEntry>>& rowsNew) {
  std::string msg;
  std::vector<std::vector<SplitRequest>> send(ctx.size);
  std::vector<GO> gids;
  std::vector<std::pair<size_t, size_t>> where;
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const Subdomain& s = subs[ls];
    rows[ls].extra.clear();
    for (size_t i = 0; i < rowsNew[ls].size(); ++i) {
      const GidEntry& e = rowsNew[ls][i];
      if (s.rIdx[e.dof] != kNone && s.invMult[e.dof] < 1.0) {
        gids.push_back(s.dofs[e.dof]);
        where.emplace_back(ls, i);
      } else {
        rows[ls].extra.push_back(GidEntry{e.lm, e.dof, e.coef, e.coef, s.sideOf(e.dof), false});
      }
    }
  }
  std::vector<int> pids;
  std::vector<LO> lids;
  owners(*ctx.ownedMap, gids, pids, lids);
  for (size_t k = 0; k < gids.size(); ++k) {
    const GidEntry& e = rowsNew[where[k].first][where[k].second];
    send[pids[k]].push_back(SplitRequest{e.lm, gids[k], e.coef, subs[where[k].first].sideOf(e.dof)});
  }
  std::vector<SplitRequest> requests = exchangeRecords(ctx.mpi, send);
  std::vector<std::vector<SplitEntry>> forward(ctx.size);
  for (const auto& r : requests) {
    const auto it = sharers.find(r.gid);
    if (it == sharers.end()) {
      if (msg.empty())
        msg = "FetiDpSolver::setConstraintRows: DOF " + std::to_string(r.gid) + " has no copies on record";
      continue;
    }
    for (const auto& c : it->second) forward[c.rank].push_back(SplitEntry{r.lm, c.localSub, c.dof, r.full, r.side});
  }
  for (const auto& e : exchangeRecords(ctx.mpi, forward)) {
    const Subdomain& s = subs[e.localSub];
    rows[e.localSub].extra.push_back(GidEntry{e.lm, e.dof, e.full * s.invMult[e.dof], e.full, e.side, true});
  }
  // One entry per (row, DOF, side): a caller may have put a row's entry on
  // two copies of one DOF; their shares add up.
  for (Rows& rw : rows) {
    auto& extra = rw.extra;
    std::sort(extra.begin(), extra.end(), [](const GidEntry& a, const GidEntry& b) {
      return a.lm != b.lm ? a.lm < b.lm : a.dof != b.dof ? a.dof < b.dof : a.side < b.side;
    });
    std::vector<GidEntry> merged;
    for (const auto& e : extra) {
      if (!merged.empty() && merged.back().lm == e.lm && merged.back().dof == e.dof && merged.back().side == e.side) {
        merged.back().coef += e.coef;
        merged.back().full += e.full;
        merged.back().split = merged.back().split || e.split;
      } else {
        merged.push_back(e);
      }
    }
    extra.swap(merged);
  }
  return msg;
}

/// The LM maps from the compatibility rows and the extra rows: lmMap owns
/// this rank's compatibility rows and its extra rows (those of its part of
/// extraRowMap); lmOvMap has every row this rank's subdomains touch. Also
/// the side maps, the entries (LIDs), the work vectors, the mask (all rows
/// in) and the row entry counts. The weights follow in computeWeights().
void JumpOperator::finalize(const Context& ctx, const std::vector<Subdomain>& subs) {
  std::vector<GO> owned;
  for (GO k = 0; k < nCompatOwned; ++k) owned.push_back(compatOffset + k);
  const GO nExtraOwned = extraRowMap.is_null() ? 0 : GO(extraRowMap->getNodeNumElements());
  for (GO k = 0; k < nExtraOwned; ++k) owned.push_back(nCompat + extraOffset + k);
  lmMap = makeMap(owned, 0, ctx.comm);
  std::vector<GO> lmGids;
  for (const Rows& rw : rows) {
    for (const auto& e : rw.compat) lmGids.push_back(e.lm);
    for (const auto& e : rw.extra) lmGids.push_back(e.lm);
  }
  std::sort(lmGids.begin(), lmGids.end());
  lmGids.erase(std::unique(lmGids.begin(), lmGids.end()), lmGids.end());
  lmOvMap = makeMap(lmGids, 0, ctx.comm);
  lmImport = rcp(new Import(lmMap, lmOvMap));
  lmExport = rcp(new Export(lmOvMap, lmMap));
  // Side keys of the extra rows: this rank's (entries and the caller's
  // entries in the caller's basis), owned by the row's owner in lmMap.
  {
    std::vector<GO> keys;
    for (size_t ls = 0; ls < rows.size(); ++ls) {
      for (const auto& e : rows[ls].extra) keys.push_back(e.lm * sideSpan + e.side);
      for (const auto& e : rows[ls].extraUser) keys.push_back(e.lm * sideSpan + subs[ls].sideOf(e.dof));
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<GO> rowsOfKeys(keys.size());
    for (size_t k = 0; k < keys.size(); ++k) rowsOfKeys[k] = keys[k] / sideSpan;
    std::vector<int> pids;
    std::vector<LO> lids;
    owners(*lmMap, rowsOfKeys, pids, lids);
    std::vector<std::vector<KeyRecord>> send(ctx.size);
    for (size_t k = 0; k < keys.size(); ++k)
      if (pids[k] >= 0) send[pids[k]].push_back(KeyRecord{keys[k]});
    std::vector<GO> ownedKeys;
    for (const auto& r : exchangeRecords(ctx.mpi, send)) ownedKeys.push_back(r.key);
    std::sort(ownedKeys.begin(), ownedKeys.end());
    ownedKeys.erase(std::unique(ownedKeys.begin(), ownedKeys.end()), ownedKeys.end());
    sideMap = makeMap(ownedKeys, 0, ctx.comm);
    sideOvMap = makeMap(keys, 0, ctx.comm);
    sideImport = rcp(new Import(sideMap, sideOvMap));
    sideExport = rcp(new Export(sideOvMap, sideMap));
  }
  for (Rows& rw : rows) {
    rw.entries.clear();
    for (const auto& e : rw.compat) rw.entries.push_back(Entry{lmOvMap->getLocalElement(e.lm), e.dof, e.coef, e.coef, false});
    for (const auto& e : rw.extra)
      rw.entries.push_back(Entry{lmOvMap->getLocalElement(e.lm), e.dof, e.coef, e.coef, true, e.full,
                                 sideOvMap->getLocalElement(e.lm * sideSpan + e.side), e.split});
    // Deterministic order within a subdomain (by LM, then DOF).
    std::sort(rw.entries.begin(), rw.entries.end(),
              [](const Entry& a, const Entry& b) { return a.lm != b.lm ? a.lm < b.lm : a.dof < b.dof; });
  }
  ovWork = rcp(new Vector(lmOvMap));
  work = rcp(new Vector(lmMap));
  rhs = rcp(new Vector(lmMap));
  lastLambda = rcp(new Vector(lmMap));
  mask = Teuchos::null;
  coupling = RowCoupling();
  Vector countOv(lmOvMap);
  {
    auto c = countOv.getDataNonConst();
    for (const Rows& rw : rows)
      for (const Entry& e : rw.entries) c[e.lm] += 1.0;
  }
  rowEntries = rcp(new Vector(lmMap));
  rowEntries->doExport(countOv, *lmExport, Tpetra::ADD);
  assembleBlocks(subs, false);
  weightsCurrent = false;
}

void JumpOperator::applyMask(Vector& v) const {
  if (!mask.is_null()) v.elementWiseMultiply(1.0, *mask, v, 0.0);
}

}  // namespace ddc
