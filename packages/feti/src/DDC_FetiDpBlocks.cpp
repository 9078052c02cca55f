// FETI-DP, subdomain blocks (doc/feti-dp.md "Dual problem"): the splits of
// each K^s into remainder / primal and interior / dual blocks, their patterns
// and values, the local factorisations, Phi^s = K_rr^{-1} K_rPi and
// S_PiPi^s. See DDC_FetiDpImpl.hpp.
#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_FetiDpImpl.hpp"
#include "DDC_MapOwners.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

/// Patterns of K_rr (unless the local solver condenses K^s on the primal
/// DOFs itself, Sub::schur) and K_II (CrsMatrix on MPI_COMM_SELF), and the
/// solvers.
void FetiDpSolver::Impl::buildBlocks(Sub& s) {
  const auto selfComm = s.K->getComm();
  s.rSolver.reset();
  s.iSolver.reset();
  s.schur = false;
  if (s.nr > 0) {
    Teuchos::ParameterList p(localSolverParams);
    s.rSolver = factory.create(p, param("Local Solver"));
    s.schur = localSchur && s.np > 0 && s.rSolver->setSchurIndices(s.pDof);
  }
  if (prec == Prec::Dirichlet && s.ni > 0 && s.nd > 0) {
    Teuchos::ParameterList p(localSolverParams);
    s.iSolver = factory.create(p, param("Local Solver"));
  }
  const auto& rowMap = *s.K->getRowMap();
  const auto& colMap = *s.K->getColMap();
  std::vector<size_t> rCount(s.schur ? 0 : s.nr, 0), iCount(s.ni, 0);
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  for (LO lr = 0; lr < s.n; ++lr) {
    const LO row = static_cast<LO>(rowMap.getGlobalElement(lr));
    s.K->getLocalRowView(lr, inds, vals);
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const LO col = static_cast<LO>(colMap.getGlobalElement(inds(e)));
      const LO rr = s.rIdx[row], rc = s.rIdx[col];
      if (rr == kNone || rc == kNone) continue;
      if (!s.schur) ++rCount[rr];
      if (s.iIdx[rr] != kNone && s.iIdx[rc] != kNone) ++iCount[s.iIdx[rr]];
    }
  }
  s.iMap = rcp(new Map(static_cast<Tpetra::global_size_t>(s.ni), 0, selfComm));
  s.Kii = rcp(new CrsMatrix(s.iMap, Teuchos::ArrayView<const size_t>(iCount.data(), iCount.size())));
  if (s.schur) {
    s.rMap = s.K->getRowMap();  // the solver's rows: every local DOF
    s.Krr = Teuchos::null;
  } else {
    s.rMap = rcp(new Map(static_cast<Tpetra::global_size_t>(s.nr), 0, selfComm));
    s.Krr = rcp(new CrsMatrix(s.rMap, Teuchos::ArrayView<const size_t>(rCount.data(), rCount.size())));
  }
  std::vector<GO> rc, ic;
  std::vector<double> rv, iv;
  for (LO lr = 0; lr < s.n; ++lr) {
    const LO row = static_cast<LO>(rowMap.getGlobalElement(lr));
    const LO rr = s.rIdx[row];
    if (rr == kNone) continue;
    s.K->getLocalRowView(lr, inds, vals);
    rc.clear(), rv.clear(), ic.clear(), iv.clear();
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const LO col = static_cast<LO>(colMap.getGlobalElement(inds(e)));
      const LO c = s.rIdx[col];
      if (c == kNone) continue;
      rc.push_back(c), rv.push_back(vals(e));
      if (s.iIdx[rr] != kNone && s.iIdx[c] != kNone) ic.push_back(s.iIdx[c]), iv.push_back(vals(e));
    }
    if (!s.schur)
      s.Krr->insertGlobalValues(rr, Teuchos::ArrayView<const GO>(rc.data(), rc.size()),
                                Teuchos::ArrayView<const double>(rv.data(), rv.size()));
    if (s.iIdx[rr] != kNone)
      s.Kii->insertGlobalValues(s.iIdx[rr], Teuchos::ArrayView<const GO>(ic.data(), ic.size()),
                                Teuchos::ArrayView<const double>(iv.data(), iv.size()));
  }
  if (!s.schur) s.Krr->fillComplete(s.rMap, s.rMap);
  s.Kii->fillComplete(s.iMap, s.iMap);
  s.rB = rcp(new MultiVector(s.rMap, 1));
  s.rX = rcp(new MultiVector(s.rMap, 1));
  s.iB = rcp(new MultiVector(s.iMap, 1));
  s.iX = rcp(new MultiVector(s.iMap, 1));
  s.fr.assign(s.nr, 0.0);
  s.xr.assign(s.nr, 0.0);
  s.fp.assign(s.np, 0.0);
  s.up.assign(s.np, 0.0);
  s.vd.assign(s.nd, 0.0);
  s.wd.assign(s.nd, 0.0);
  s.bn.assign(s.schur ? s.n : 0, 0.0);
  s.xn.assign(s.schur ? s.n : 0, 0.0);
}


// ---------------------------------------------------------------------------
// numeric
// ---------------------------------------------------------------------------

/// Copy the current K^s values into the blocks (same pattern as setTopology).
void FetiDpSolver::Impl::refreshBlocks(Sub& s) {
  if (s.cob.active()) s.cob.update(*s.Kuser);
  const auto& rowMap = *s.K->getRowMap();
  const auto& colMap = *s.K->getColMap();
  if (!s.schur) {
    s.Krr->resumeFill();
    s.Krr->setAllToScalar(0.0);
  }
  s.Kii->resumeFill();
  s.Kii->setAllToScalar(0.0);
  s.KrP.clear(), s.KPr.clear(), s.KID.clear(), s.KDI.clear(), s.KDD.clear();
  s.KPP.assign(s.schur ? 0 : size_t(s.np) * s.np, 0.0);
  s.diag.assign(s.n, 0.0);
  std::vector<double> colSum(s.nr, 0.0);
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  std::vector<GO> rc, ic;
  std::vector<double> rv, iv;
  bool patternOk = true;
  for (LO lr = 0; lr < s.n; ++lr) {
    const LO row = static_cast<LO>(rowMap.getGlobalElement(lr));
    s.K->getLocalRowView(lr, inds, vals);
    rc.clear(), rv.clear(), ic.clear(), iv.clear();
    const LO rr = s.rIdx[row], pr = s.pIdx[row];
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const LO col = static_cast<LO>(colMap.getGlobalElement(inds(e)));
      const double v = vals(e);
      if (col == row) s.diag[row] += v;
      const LO rcIdx = s.rIdx[col], pc = s.pIdx[col];
      if (rr != kNone && rcIdx != kNone) {
        if (!s.schur) rc.push_back(rcIdx), rv.push_back(v);
        colSum[rcIdx] += std::abs(v);
        const LO ir = s.iIdx[rr], ic2 = s.iIdx[rcIdx], dr = s.dIdx[rr], dc = s.dIdx[rcIdx];
        if (ir != kNone && ic2 != kNone) ic.push_back(ic2), iv.push_back(v);
        else if (ir != kNone) s.KID.push_back(Triplet{ir, dc, v});
        else if (ic2 != kNone) s.KDI.push_back(Triplet{dr, ic2, v});
        else s.KDD.push_back(Triplet{dr, dc, v});
      } else if (s.schur) {
        continue;  // the primal blocks stay inside the solver's Schur complement
      } else if (rr != kNone) {
        s.KrP.push_back(Triplet{rr, pc, v});
      } else if (rcIdx != kNone) {
        s.KPr.push_back(Triplet{pr, rcIdx, v});
      } else {
        s.KPP[size_t(pr) + size_t(pc) * s.np] += v;
      }
    }
    if (rr != kNone) {
      if (!s.schur)
        patternOk =
            patternOk && s.Krr->sumIntoGlobalValues(rr, LO(rc.size()), rv.data(), rc.data()) == LO(rc.size());
      if (s.iIdx[rr] != kNone)
        patternOk =
            patternOk && s.Kii->sumIntoGlobalValues(s.iIdx[rr], LO(ic.size()), iv.data(), ic.data()) == LO(ic.size());
    }
  }
  if (!s.schur) s.Krr->fillComplete(s.rMap, s.rMap);
  s.Kii->fillComplete(s.iMap, s.iMap);
  if (!patternOk)
    throw std::logic_error("the sparsity pattern of K changed since setTopology(); call setTopology() again");
  s.krrNorm1 = colSum.empty() ? 0.0 : *std::max_element(colSum.begin(), colSum.end());
  if (!s.cob.active()) {
    s.diagUser = s.diag;
  } else {
    s.diagUser.assign(s.n, 0.0);
    const auto& uRow = *s.Kuser->getRowMap();
    const auto& uCol = *s.Kuser->getColMap();
    for (LO lr = 0; lr < s.n; ++lr) {
      s.Kuser->getLocalRowView(lr, inds, vals);
      const GO row = uRow.getGlobalElement(lr);
      for (size_t e = 0; e < inds.extent(0); ++e)
        if (uCol.getGlobalElement(inds(e)) == row) s.diagUser[row] += vals(e);
    }
  }
}

/// Factorise K_rr^s, compute Phi^s, S_PiPi^s and check K_rr^s for
/// singularity; factorise K_II^s. Returns an error message or "".
std::string FetiDpSolver::Impl::factorSub(Sub& s) {
  const std::string who = "FETI-DP: subdomain " + std::to_string(s.id) + " (" + std::to_string(s.nr) +
                          " remainder DOFs, " + std::to_string(s.np) + " primal DOFs)";
  const std::string fix =
      ": its remainder stiffness K_rr is singular; the corner rule could not fix this subdomain's rigid modes "
      "(give it more primal DOFs: >= 2 distinct primal nodes in 2-D, or Dirichlet data)";
  try {
    refreshBlocks(s);
  } catch (const std::exception& e) {
    return who + ": " + e.what();
  }
  s.Phi.assign(s.schur ? 0 : size_t(s.nr) * s.np, 0.0);
  if (s.nr > 0) {
    try {
      if (!analysed) s.rSolver->symbolic(s.schur ? RCP<const CrsMatrix>(s.K) : RCP<const CrsMatrix>(s.Krr));
      s.rSolver->numeric();
      if (s.schur) s.rSolver->schurComplement(s.S);  // S_PiPi^s, in primal order
    } catch (const SolverError& e) {
      return who + fix + " [" + e.what() + "]";
    }
    // A condition estimate ||K_rr||_1 ||K_rr^{-1} z||_1 / ||z||_1 (one step
    // of inverse iteration) with a pseudo-random column z: a singular K_rr
    // that the factorisation did not flag (tiny instead of zero pivots, as
    // LDL^T of a floating subdomain gives) shows up as an estimate near
    // 1/eps. Without the Schur capability the same multi-RHS solve gives the
    // np columns of Phi = K_rr^{-1} K_rPi. (With it, solve() solves the
    // interior problem K_rr alone.)
    const size_t nPhi = s.schur ? 0 : size_t(s.np);
    MultiVector R(s.rMap, nPhi + 1), X(s.rMap, nPhi + 1);
    for (const Triplet& t : s.KrP) R.sumIntoLocalValue(t.i, size_t(t.j), t.v);
    // Row of remainder index r in R / X.
    auto at = [&s](LO r) { return s.schur ? s.rDof[r] : r; };
    {
      std::mt19937 gen(12345u + static_cast<unsigned>(s.id));
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      auto z = R.getDataNonConst(nPhi);
      for (LO r = 0; r < s.nr; ++r) z[at(r)] = u(gen);
    }
    s.rSolver->solve(R, X);
    for (size_t p = 0; p < nPhi; ++p) {
      auto x = X.getData(p);
      std::copy(x.begin(), x.end(), s.Phi.begin() + p * s.nr);
    }
    double zn = 0.0, yn = 0.0;
    {
      auto z = R.getData(nPhi);
      auto y = X.getData(nPhi);
      for (LO r = 0; r < s.nr; ++r) zn += std::abs(z[at(r)]), yn += std::abs(y[at(r)]);
    }
    const double est = s.krrNorm1 * yn / zn;
    bool finitePhi = std::isfinite(est);
    for (double v : s.Phi) finitePhi = finitePhi && std::isfinite(v);
    if (s.schur)
      for (double v : s.S) finitePhi = finitePhi && std::isfinite(v);
    if (!finitePhi || (singularityThreshold > 0.0 && est > singularityThreshold)) {
      std::ostringstream os;
      os << who << fix << " [condition estimate of K_rr " << std::scientific << est << " > '"
         << param("Local Singularity Threshold") << "' = " << singularityThreshold << "]";
      return os.str();
    }
  }
  if (s.schur) return "";
  // S_PiPi^s = K_PiPi - K_Pir Phi
  s.S = s.KPP;
  for (const Triplet& t : s.KPr)
    for (LO q = 0; q < s.np; ++q) s.S[size_t(t.i) + size_t(q) * s.np] -= t.v * s.Phi[size_t(t.j) + size_t(q) * s.nr];
  return "";
}

}  // namespace ddc
