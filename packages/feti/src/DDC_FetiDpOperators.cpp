// FETI-DP, operators (doc/feti-dp.md "Dual problem", "Preconditioners and
// scalings"): F = B K~^{-1} B^T and the Dirichlet / lumped preconditioner
// M^{-1} as Tpetra operators on the LM map for Belos, and the local and
// coarse solves they are made of. See DDC_FetiDpImpl.hpp.
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

/// F = B K~^{-1} B^T as a Tpetra operator on the LM map.
class FOperator : public Operator {
 public:
  explicit FOperator(FetiDpSolver::Impl* impl) : impl_(impl) {}
  RCP<const Map> getDomainMap() const override { return impl_->lmMap; }
  RCP<const Map> getRangeMap() const override { return impl_->lmMap; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, Scalar alpha,
             Scalar beta) const override {
    if (mode != Teuchos::NO_TRANS) throw std::logic_error("FETI-DP F operator: only NO_TRANS is supported");
    Vector tmp(impl_->lmMap);
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      impl_->applyF(*X.getVector(j), tmp);
      ++impl_->nApplyF;
      auto yj = Y.getVectorNonConst(j);
      if (beta == 0.0) yj->putScalar(0.0);  // ignore NaN/Inf in Y (BLAS convention)
      yj->update(alpha, tmp, beta);
    }
  }

 private:
  FetiDpSolver::Impl* impl_;
};

/// Dirichlet / lumped preconditioner M^{-1} = sum_s B_D^s S^s B_D^sT.
class MOperator : public Operator {
 public:
  explicit MOperator(FetiDpSolver::Impl* impl) : impl_(impl) {}
  RCP<const Map> getDomainMap() const override { return impl_->lmMap; }
  RCP<const Map> getRangeMap() const override { return impl_->lmMap; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, Scalar alpha,
             Scalar beta) const override {
    if (mode != Teuchos::NO_TRANS) throw std::logic_error("FETI-DP preconditioner: only NO_TRANS is supported");
    const double t0 = MPI_Wtime();
    Vector tmp(impl_->lmMap);
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      impl_->applyM(*X.getVector(j), tmp);
      ++impl_->nApplyM;
      auto yj = Y.getVectorNonConst(j);
      if (beta == 0.0) yj->putScalar(0.0);
      yj->update(alpha, tmp, beta);
    }
    impl_->tPrec += MPI_Wtime() - t0;
  }

 private:
  FetiDpSolver::Impl* impl_;
};

}  // namespace


void FetiDpSolver::Impl::applyMask(Vector& v) const {
  if (!mask.is_null()) v.elementWiseMultiply(1.0, *mask, v, 0.0);
}


// ---------------------------------------------------------------------------
// operators
// ---------------------------------------------------------------------------

void FetiDpSolver::Impl::localSolve(DirectSolver& solver, MultiVector& B, MultiVector& X,
                                    const std::vector<double>& in, std::vector<double>& out, double& timer) const {
  const double t0 = MPI_Wtime();
  {
    auto b = B.getDataNonConst(0);
    std::copy(in.begin(), in.end(), b.begin());
  }
  solver.solve(B, X);
  auto x = X.getData(0);
  out.assign(x.begin(), x.end());
  timer += MPI_Wtime() - t0;
}

/// f_r^s += sign * (B^sT lambda)_r and f_Pi^s += sign * (B^sT lambda)_Pi.
void FetiDpSolver::Impl::scatterBt(const Vector& lambda, double sign) {
  lmOvWork->doImport(lambda, *lmImport, Tpetra::INSERT);
  auto l = lmOvWork->getData();
  for (Sub& s : subs)
    for (const BEntry& e : s.B) {
      const double v = sign * e.coef * l[e.lm];
      if (s.rIdx[e.dof] != kNone) s.fr[s.rIdx[e.dof]] += v;
      else s.fp[s.pIdx[e.dof]] += v;
    }
}

/// (u_r^s, u_Pi) = K~^{-1} (f_r^s, f_Pi) where f_Pi = sum_s R^T f_Pi^s +
/// fPiAssembled (the latter on coarseMap, may be null). Inputs in s.fr,
/// s.fp; outputs in s.xr (= u_r^s), s.up (= u_Pi^s) and coarseSol.
///
/// Per subdomain, the coarse right-hand side is f_Pi^s - K_Pir K_rr^{-1}
/// f_r^s and the back-substitution u_r = K_rr^{-1} (f_r - K_rPi u_Pi): with
/// the Schur capability one condensation and one expansion (a forward and a
/// backward sweep), otherwise a K_rr solve and the stored Phi.
void FetiDpSolver::Impl::applyKtildeInv(const Vector* fPiAssembled) {
  for (Sub& s : subs)
    if (s.nr > 0 && !s.schur) localSolve(*s.rSolver, *s.rB, *s.rX, s.fr, s.xr, tLocalSolve);
  if (nCoarse == 0) {
    for (Sub& s : subs) std::fill(s.up.begin(), s.up.end(), 0.0);
    return;
  }
  // g_Pi = f_Pi - sum_s R_Pi^T K_Pir K_rr^{-1} f_r
  coarseOvWork->putScalar(0.0);
  {
    auto g = coarseOvWork->getDataNonConst();
    std::vector<double> gp;
    for (Sub& s : subs) {
      if (s.schur) {
        const double t0 = MPI_Wtime();
        for (LO r = 0; r < s.nr; ++r) s.bn[s.rDof[r]] = s.fr[r];
        for (LO p = 0; p < s.np; ++p) s.bn[s.pDof[p]] = s.fp[p];
        gp.resize(s.np);
        s.rSolver->condense(s.bn.data(), gp.data());
        tLocalSolve += MPI_Wtime() - t0;
      } else {
        gp = s.fp;
        for (const Triplet& t : s.KPr) gp[t.i] -= t.v * s.xr[t.j];
      }
      for (LO p = 0; p < s.np; ++p) g[s.coarseOvLid[p]] += gp[p];
    }
  }
  const double t0 = MPI_Wtime();
  coarseWork->putScalar(0.0);
  coarseWork->doExport(*coarseOvWork, *coarseExport, Tpetra::ADD);
  if (fPiAssembled) coarseWork->update(1.0, *fPiAssembled, 1.0);
  coarseSolver->solve(*coarseWork, *coarseSol);
  coarseOvWork->doImport(*coarseSol, *coarseImport, Tpetra::INSERT);
  tCoarseSolve += MPI_Wtime() - t0;
  auto u = coarseOvWork->getData();
  for (Sub& s : subs) {
    for (LO p = 0; p < s.np; ++p) s.up[p] = u[s.coarseOvLid[p]];
    if (s.schur) {
      const double t1 = MPI_Wtime();
      s.rSolver->expand(s.up.data(), s.xn.data());
      for (LO r = 0; r < s.nr; ++r) s.xr[r] = s.xn[s.rDof[r]];
      tLocalSolve += MPI_Wtime() - t1;
      continue;
    }
    // u_r = x_r - Phi u_Pi^s
    for (LO q = 0; q < s.np; ++q) {
      const double uq = s.up[q];
      const double* phi = s.Phi.data() + size_t(q) * s.nr;
      for (LO r = 0; r < s.nr; ++r) s.xr[r] -= phi[r] * uq;
    }
  }
}

/// y = B u with u = (s.xr, s.up) per subdomain.
void FetiDpSolver::Impl::gatherB(Vector& y) {
  lmOvWork->putScalar(0.0);
  {
    auto l = lmOvWork->getDataNonConst();
    for (const Sub& s : subs)
      for (const BEntry& e : s.B)
        l[e.lm] += e.coef * (s.rIdx[e.dof] != kNone ? s.xr[s.rIdx[e.dof]] : s.up[s.pIdx[e.dof]]);
  }
  y.putScalar(0.0);
  y.doExport(*lmOvWork, *lmExport, Tpetra::ADD);
}

/// y = P F P x, P = the mask (restrained rows out).
void FetiDpSolver::Impl::applyF(const Vector& x, Vector& y) {
  for (Sub& s : subs) {
    std::fill(s.fr.begin(), s.fr.end(), 0.0);
    std::fill(s.fp.begin(), s.fp.end(), 0.0);
  }
  if (mask.is_null()) {
    scatterBt(x, 1.0);
  } else {
    lmWork->elementWiseMultiply(1.0, *mask, x, 0.0);
    scatterBt(*lmWork, 1.0);
  }
  applyKtildeInv(nullptr);
  gatherB(y);
  applyMask(y);
}

/// M^{-1} x = sum_s B_D^s S^s B_D^sT x, S^s = K_DD - K_DI K_II^{-1} K_ID
/// (Dirichlet) or K_DD (lumped). Primal DOFs count as fixed, so entries of
/// compatibility rows on primal DOFs do not enter; entries of extra rows on
/// primal or interior DOFs enter lumped and diagonal (scaled^2 K_jj).
void FetiDpSolver::Impl::applyM(const Vector& x, Vector& y) {
  if (mask.is_null()) {
    lmOvWork->doImport(x, *lmImport, Tpetra::INSERT);
  } else {
    lmWork->elementWiseMultiply(1.0, *mask, x, 0.0);
    lmOvWork->doImport(*lmWork, *lmImport, Tpetra::INSERT);
  }
  std::vector<double> yOv(lmOvMap->getNodeNumElements(), 0.0);
  {
    auto l = lmOvWork->getData();
    std::vector<double> vi, wi;
    for (Sub& s : subs) {
      std::fill(s.vd.begin(), s.vd.end(), 0.0);
      for (const BEntry& e : s.B) {
        const LO r = s.rIdx[e.dof];
        if (r != kNone && s.dIdx[r] != kNone) {
          s.vd[s.dIdx[r]] += e.scaled * l[e.lm];
        } else if (e.extra) {
          // An extra row's entry on a primal (or interior) DOF: lumped,
          // diagonal, B_D K_jj B_D^T. Without it a row lying on primal DOFs
          // only (a slave node on a primal master node) has no
          // preconditioner at all and CG breaks down.
          yOv[e.lm] += e.scaled * e.scaled * std::abs(s.diag[e.dof]) * l[e.lm];
        }
      }
      std::fill(s.wd.begin(), s.wd.end(), 0.0);
      for (const Triplet& t : s.KDD) s.wd[t.i] += t.v * s.vd[t.j];
      if (s.iSolver) {
        vi.assign(s.ni, 0.0);
        for (const Triplet& t : s.KID) vi[t.i] += t.v * s.vd[t.j];
        localSolve(*s.iSolver, *s.iB, *s.iX, vi, wi, tDirichletSolve);
        for (const Triplet& t : s.KDI) s.wd[t.i] -= t.v * wi[t.j];
      }
      for (const BEntry& e : s.B) {
        const LO r = s.rIdx[e.dof];
        if (r != kNone && s.dIdx[r] != kNone) yOv[e.lm] += e.scaled * s.wd[s.dIdx[r]];
      }
    }
  }
  {
    auto l = lmOvWork->getDataNonConst();
    std::copy(yOv.begin(), yOv.end(), l.begin());
  }
  y.putScalar(0.0);
  y.doExport(*lmOvWork, *lmExport, Tpetra::ADD);
  applyMask(y);
}


void FetiDpSolver::Impl::makeOperators() {
  fOp = rcp(new FOperator(this));
  mOp = prec == Prec::None ? Teuchos::null : RCP<Operator>(rcp(new MOperator(this)));
}

}  // namespace ddc
