// FETI-DP, subdomain factorisations (doc/feti-dp.md "The dual problem"): the
// split of each K^s into remainder / primal blocks, K_rr^s (or K^s with its
// primal DOFs as Schur rows) and its factorisation, Phi^s = K_rr^{-1} K_rPi
// and S_PiPi^s: the local part of the DualOperator. See DDC_FetiDpImpl.hpp.
#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_FetiDpImpl.hpp"
#include "DDC_LocalCsr.hpp"

namespace ddc {

/// The local solvers and, unless the local solver condenses K^s on the
/// primal DOFs itself (LocalProblem::schur), the pattern of K_rr
/// (CrsMatrix on MPI_COMM_SELF).
void DualOperator::build(const std::vector<Subdomain>& subs, const DirectSolverFactory& factory,
                         const Teuchos::ParameterList& localParams, const std::string& where) {
  local.clear();
  local.resize(subs.size());
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const Subdomain& s = subs[ls];
    LocalProblem& lp = local[ls];
    if (s.nr > 0) {
      Teuchos::ParameterList p(localParams);
      lp.solver = factory.create(p, where);
      lp.schur = localSchur && s.np > 0 && lp.solver->setSchurIndices(s.pDof);
    }
    if (lp.schur) {
      lp.rMap = s.K->getRowMap();  // the solver's rows: every local DOF
    } else {
      lp.Krr = extractBlock(*s.K, s.rIdx, s.nr);
      lp.rMap = lp.Krr->getRowMap();
    }
    lp.rB = rcp(new MultiVector(lp.rMap, 1));
    lp.rX = rcp(new MultiVector(lp.rMap, 1));
    lp.fr.assign(s.nr, 0.0);
    lp.xr.assign(s.nr, 0.0);
    lp.fp.assign(s.np, 0.0);
    lp.up.assign(s.np, 0.0);
    lp.bn.assign(lp.schur ? s.n : 0, 0.0);
    lp.xn.assign(lp.schur ? s.n : 0, 0.0);
  }
}

RCP<CrsMatrix> feti_internal::extractBlock(const CrsMatrix& K, const std::vector<LO>& index, LO size) {
  const auto& rowMap = *K.getRowMap();
  const auto& colMap = *K.getColMap();
  const LO n = LO(rowMap.getNodeNumElements());
  std::vector<size_t> count(size, 0);
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  for (LO lr = 0; lr < n; ++lr) {
    const LO br = index[static_cast<LO>(rowMap.getGlobalElement(lr))];
    if (br == kNone) continue;
    K.getLocalRowView(lr, inds, vals);
    for (size_t e = 0; e < inds.extent(0); ++e)
      if (index[static_cast<LO>(colMap.getGlobalElement(inds(e)))] != kNone) ++count[br];
  }
  auto map = rcp(new Map(static_cast<Tpetra::global_size_t>(size), 0, K.getComm()));
  auto B = rcp(new CrsMatrix(map, Teuchos::ArrayView<const size_t>(count.data(), count.size())));
  std::vector<GO> bc;
  std::vector<double> bv;
  for (LO lr = 0; lr < n; ++lr) {
    const LO br = index[static_cast<LO>(rowMap.getGlobalElement(lr))];
    if (br == kNone) continue;
    K.getLocalRowView(lr, inds, vals);
    bc.clear(), bv.clear();
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const LO c = index[static_cast<LO>(colMap.getGlobalElement(inds(e)))];
      if (c != kNone) bc.push_back(c), bv.push_back(vals(e));
    }
    B->insertGlobalValues(br, Teuchos::ArrayView<const GO>(bc.data(), bc.size()),
                          Teuchos::ArrayView<const double>(bv.data(), bv.size()));
  }
  B->fillComplete(map, map);
  return B;
}

namespace {

/// The diagonal of a CrsMatrix on MPI_COMM_SELF with the contiguous map 0..n-1.
void diagonalOf(const CrsMatrix& A, LO n, std::vector<double>& d) {
  d.assign(n, 0.0);
  const auto& rowMap = *A.getRowMap();
  const auto& colMap = *A.getColMap();
  const LocalCsr a(A);
  for (LO lr = 0; lr < n; ++lr) {
    const GO row = rowMap.getGlobalElement(lr);
    for (size_t e = a.ptr[lr]; e < a.ptr[lr + 1]; ++e)
      if (colMap.getGlobalElement(a.col[e]) == row) d[row] += a.val[e];
  }
}

/// The values of K_rr (unless schur), K_rPi, K_Pir, K_PiPi, the diagonals
/// of the Subdomain and the 1-norm of K_rr (for the condition estimate),
/// from K (K^T = T^T K^s T first, with edge/face constraints).
/// \throws std::logic_error if the pattern of K changed.
void refreshValues(Subdomain& s, LocalProblem& lp) {
  if (s.cob.active()) s.cob.update(*s.Kuser);
  const auto& rowMap = *s.K->getRowMap();
  const auto& colMap = *s.K->getColMap();
  if (!lp.schur) {
    lp.Krr->resumeFill();
    lp.Krr->setAllToScalar(0.0);
  }
  lp.KrP.clear(), lp.KPr.clear();
  lp.KPP.assign(lp.schur ? 0 : size_t(s.np) * s.np, 0.0);
  s.diag.assign(s.n, 0.0);
  std::vector<double> colSum(s.nr, 0.0);
  const LocalCsr k(*s.K);
  std::vector<GO> rc;
  std::vector<double> rv;
  bool patternOk = true;
  for (LO lr = 0; lr < s.n; ++lr) {
    const LO row = static_cast<LO>(rowMap.getGlobalElement(lr));
    rc.clear(), rv.clear();
    const LO rr = s.rIdx[row], pr = s.pIdx[row];
    for (size_t e = k.ptr[lr]; e < k.ptr[lr + 1]; ++e) {
      const LO col = static_cast<LO>(colMap.getGlobalElement(k.col[e]));
      const double v = k.val[e];
      if (col == row) s.diag[row] += v;
      const LO rc2 = s.rIdx[col], pc = s.pIdx[col];
      if (rr != kNone && rc2 != kNone) {
        if (!lp.schur) rc.push_back(rc2), rv.push_back(v);
        colSum[rc2] += std::abs(v);
      } else if (lp.schur) {
        continue;  // the primal blocks stay inside the solver's Schur complement
      } else if (rr != kNone) {
        lp.KrP.push_back(Triplet{rr, pc, v});
      } else if (rc2 != kNone) {
        lp.KPr.push_back(Triplet{pr, rc2, v});
      } else {
        lp.KPP[size_t(pr) + size_t(pc) * s.np] += v;
      }
    }
    if (rr != kNone && !lp.schur)
      patternOk = patternOk && lp.Krr->sumIntoGlobalValues(rr, LO(rc.size()), rv.data(), rc.data()) == LO(rc.size());
  }
  if (!lp.schur) lp.Krr->fillComplete(lp.rMap, lp.rMap);
  if (!patternOk)
    throw std::logic_error("the sparsity pattern of K changed since setTopology(); call setTopology() again");
  lp.krrNorm1 = colSum.empty() ? 0.0 : *std::max_element(colSum.begin(), colSum.end());
  if (s.cob.active())
    diagonalOf(*s.Kuser, s.n, s.diagUser);
  else
    s.diagUser = s.diag;
}

/// A condition estimate ||K_rr||_1 ||K_rr^{-1} z||_1 / ||z||_1 (one step of
/// inverse iteration) with a pseudo-random column z, from the factorised
/// local solver: a singular K_rr that the factorisation did not flag (tiny
/// instead of zero pivots, as LDL^T of a floating subdomain gives) shows up
/// as an estimate near 1/eps. Without the Schur capability the same
/// multi-RHS solve gives the np columns of Phi = K_rr^{-1} K_rPi into
/// lp.Phi. (With it, solve() solves the interior problem K_rr alone.)
double conditionEstimateAndPhi(const Subdomain& s, LocalProblem& lp) {
  const size_t nPhi = lp.schur ? 0 : size_t(s.np);
  MultiVector R(lp.rMap, nPhi + 1), X(lp.rMap, nPhi + 1);
  for (const Triplet& t : lp.KrP) R.sumIntoLocalValue(t.i, size_t(t.j), t.v);
  // Row of remainder index r in R / X.
  auto at = [&](LO r) { return lp.schur ? s.rDof[r] : r; };
  {
    std::mt19937 gen(12345u + static_cast<unsigned>(s.id));
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto z = R.getDataNonConst(nPhi);
    for (LO r = 0; r < s.nr; ++r) z[at(r)] = u(gen);
  }
  lp.solver->solve(R, X);
  for (size_t p = 0; p < nPhi; ++p) {
    auto x = X.getData(p);
    std::copy(x.begin(), x.end(), lp.Phi.begin() + p * s.nr);
  }
  double zn = 0.0, yn = 0.0;
  {
    auto z = R.getData(nPhi);
    auto y = X.getData(nPhi);
    for (LO r = 0; r < s.nr; ++r) zn += std::abs(z[at(r)]), yn += std::abs(y[at(r)]);
  }
  return lp.krrNorm1 * yn / zn;
}

/// Whether the estimate, Phi and (schur) S_PiPi^s are all finite.
bool allFinite(double est, const LocalProblem& lp) {
  bool finite = std::isfinite(est);
  for (double v : lp.Phi) finite = finite && std::isfinite(v);
  if (lp.schur)
    for (double v : lp.S) finite = finite && std::isfinite(v);
  return finite;
}

}  // namespace

/// Refresh the values (K^T = T^T K^s T first, with edge/face constraints),
/// the diagonals of the Subdomain, K_rr and the primal blocks; factorise
/// K_rr^s (or K^s with Schur rows), compute Phi^s, S_PiPi^s and check K_rr^s
/// for singularity. Returns an error message or "".
std::string DualOperator::factor(const Context& ctx, Subdomain& s, size_t ls, bool analysed) {
  LocalProblem& lp = local[ls];
  const std::string who = "FETI-DP: subdomain " + std::to_string(s.id) + " (" + std::to_string(s.nr) +
                          " remainder DOFs, " + std::to_string(s.np) + " primal DOFs)";
  const std::string fix =
      ": its remainder stiffness K_rr is singular; the corner rule could not fix this subdomain's rigid modes "
      "(give it more primal DOFs: >= 2 distinct primal nodes in 2-D, edge or face averages by 'Primal "
      "Constraints', or Dirichlet data; a host code without the analysis' corner rule chooses its vertices "
      "with findPrimalVertices())";
  try {
    refreshValues(s, lp);
  } catch (const std::exception& e) {
    return who + ": " + e.what();
  }

  lp.Phi.assign(lp.schur ? 0 : size_t(s.nr) * s.np, 0.0);
  if (s.nr > 0) {
    try {
      if (!analysed) lp.solver->symbolic(lp.schur ? RCP<const CrsMatrix>(s.K) : RCP<const CrsMatrix>(lp.Krr));
      lp.solver->numeric();
      if (lp.schur) lp.solver->schurComplement(lp.S);  // S_PiPi^s, in primal order
    } catch (const SolverError& e) {
      return who + fix + " [" + e.what() + "]";
    }
    const double est = conditionEstimateAndPhi(s, lp);
    if (!allFinite(est, lp) || (singularityThreshold > 0.0 && est > singularityThreshold)) {
      std::ostringstream os;
      os << who << fix << " [condition estimate of K_rr " << std::scientific << est << " > '"
         << ctx.param("Local Singularity Threshold") << "' = " << singularityThreshold << "]";
      return os.str();
    }
  }
  ++s.factorizations;
  if (lp.schur) return "";
  // S_PiPi^s = K_PiPi - K_Pir Phi
  lp.S = lp.KPP;
  for (const Triplet& t : lp.KPr)
    for (LO q = 0; q < s.np; ++q)
      lp.S[size_t(t.i) + size_t(q) * s.np] -= t.v * lp.Phi[size_t(t.j) + size_t(q) * s.nr];
  return "";
}

}  // namespace ddc
