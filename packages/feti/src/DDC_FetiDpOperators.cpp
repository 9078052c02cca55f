// FETI-DP, operators (doc/feti-dp.md "The dual problem", "Preconditioner and
// scaling"): K~^{-1} and F = B K~^{-1} B^T (DualOperator), and the Tpetra
// operators Belos iterates with (F and the preconditioner M^{-1}). See
// DDC_FetiDpImpl.hpp.
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <stdexcept>

#include "DDC_FetiDpImpl.hpp"

namespace ddc {

namespace {

/// F = B K~^{-1} B^T as a Tpetra operator on the LM map.
class FOperator : public Operator {
 public:
  explicit FOperator(FetiDpSolver::Impl* impl) : impl_(impl) {}
  RCP<const Map> getDomainMap() const override { return impl_->jump.lmMap; }
  RCP<const Map> getRangeMap() const override { return impl_->jump.lmMap; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, Scalar alpha,
             Scalar beta) const override {
    if (mode != Teuchos::NO_TRANS) throw std::logic_error("FETI-DP F operator: only NO_TRANS is supported");
    Vector tmp(impl_->jump.lmMap);
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      impl_->dual.apply(impl_->subs, impl_->jump, impl_->coarse, *X.getVector(j), tmp);
      auto yj = Y.getVectorNonConst(j);
      if (beta == 0.0) yj->putScalar(0.0);  // ignore NaN/Inf in Y (BLAS convention)
      yj->update(alpha, tmp, beta);
    }
  }

 private:
  FetiDpSolver::Impl* impl_;
};

/// The preconditioner M^{-1} as a Tpetra operator on the LM map.
class MOperator : public Operator {
 public:
  explicit MOperator(FetiDpSolver::Impl* impl) : impl_(impl) {}
  RCP<const Map> getDomainMap() const override { return impl_->jump.lmMap; }
  RCP<const Map> getRangeMap() const override { return impl_->jump.lmMap; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, Scalar alpha,
             Scalar beta) const override {
    if (mode != Teuchos::NO_TRANS) throw std::logic_error("FETI-DP preconditioner: only NO_TRANS is supported");
    Vector tmp(impl_->jump.lmMap);
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      impl_->prec.apply(impl_->subs, impl_->jump, *X.getVector(j), tmp);
      auto yj = Y.getVectorNonConst(j);
      if (beta == 0.0) yj->putScalar(0.0);
      yj->update(alpha, tmp, beta);
    }
  }

 private:
  FetiDpSolver::Impl* impl_;
};

}  // namespace

/// f_r^s += sign * (B^sT lambda)_r and f_Pi^s += sign * (B^sT lambda)_Pi.
void DualOperator::scatterBt(const JumpOperator& jump, const Vector& lambda, double sign) {
  jump.ovWork->doImport(lambda, *jump.lmImport, Tpetra::INSERT);
  auto l = jump.ovWork->getData();
  for (size_t ls = 0; ls < local.size(); ++ls) {
    jump.rows[ls].Br.addTransposed(l.getRawPtr(), sign, local[ls].fr.data());
    jump.rows[ls].Bp.addTransposed(l.getRawPtr(), sign, local[ls].fp.data());
  }
}

/// (u_r^s, u_Pi) = K~^{-1} (f_r^s, f_Pi) where f_Pi = sum_s R^T f_Pi^s +
/// fPi (the latter on the coarse map, may be null). Inputs in local[].fr,
/// fp; outputs in local[].xr (= u_r^s), up (= u_Pi^s) and coarse.sol.
///
/// Per subdomain, the coarse right-hand side is f_Pi^s - K_Pir K_rr^{-1}
/// f_r^s and the back-substitution u_r = K_rr^{-1} (f_r - K_rPi u_Pi): with
/// the Schur capability one condensation and one expansion (a forward and a
/// backward sweep), otherwise a K_rr solve and the stored Phi.
void DualOperator::applyKtildeInv(const std::vector<Subdomain>& subs, CoarseProblem& coarse, const Vector* fPi) {
  auto solveRemainder = [this](LocalProblem& lp) {
    const double t0 = MPI_Wtime();
    {
      auto b = lp.rB->getDataNonConst(0);
      std::copy(lp.fr.begin(), lp.fr.end(), b.begin());
    }
    lp.solver->solve(*lp.rB, *lp.rX);
    auto x = lp.rX->getData(0);
    std::copy(x.begin(), x.end(), lp.xr.begin());
    tLocalSolve += MPI_Wtime() - t0;
  };
  for (size_t ls = 0; ls < local.size(); ++ls)
    if (subs[ls].nr > 0 && !local[ls].schur) solveRemainder(local[ls]);
  if (coarse.n == 0) {
    for (LocalProblem& lp : local) std::fill(lp.up.begin(), lp.up.end(), 0.0);
    return;
  }
  // g_Pi = f_Pi - sum_s R_Pi^T K_Pir K_rr^{-1} f_r
  coarse.ovWork->putScalar(0.0);
  {
    auto g = coarse.ovWork->getDataNonConst();
    std::vector<double> gp;
    for (size_t ls = 0; ls < local.size(); ++ls) {
      const Subdomain& s = subs[ls];
      LocalProblem& lp = local[ls];
      if (lp.schur) {
        const double t0 = MPI_Wtime();
        for (LO r = 0; r < s.nr; ++r) lp.bn[s.rDof[r]] = lp.fr[r];
        for (LO p = 0; p < s.np; ++p) lp.bn[s.pDof[p]] = lp.fp[p];
        gp.resize(s.np);
        lp.solver->condense(lp.bn.data(), gp.data());
        tLocalSolve += MPI_Wtime() - t0;
      } else {
        gp = lp.fp;
        addTriplets(lp.KPr, -1.0, lp.xr.data(), gp.data());
      }
      for (LO p = 0; p < s.np; ++p) g[coarse.sub[ls].ovLid[p]] += gp[p];
    }
  }
  coarse.solve(fPi);
  auto u = coarse.ovWork->getData();
  for (size_t ls = 0; ls < local.size(); ++ls) {
    const Subdomain& s = subs[ls];
    LocalProblem& lp = local[ls];
    for (LO p = 0; p < s.np; ++p) lp.up[p] = u[coarse.sub[ls].ovLid[p]];
    if (lp.schur) {
      const double t1 = MPI_Wtime();
      lp.solver->expand(lp.up.data(), lp.xn.data());
      for (LO r = 0; r < s.nr; ++r) lp.xr[r] = lp.xn[s.rDof[r]];
      tLocalSolve += MPI_Wtime() - t1;
      continue;
    }
    // u_r = x_r - Phi u_Pi^s
    for (LO q = 0; q < s.np; ++q) {
      const double uq = lp.up[q];
      const double* phi = lp.Phi.data() + size_t(q) * s.nr;
      for (LO r = 0; r < s.nr; ++r) lp.xr[r] -= phi[r] * uq;
    }
  }
}

/// y = B u with u = (local[].xr, up).
void DualOperator::gatherB(const JumpOperator& jump, Vector& y) {
  jump.ovWork->putScalar(0.0);
  {
    auto l = jump.ovWork->getDataNonConst();
    for (size_t ls = 0; ls < local.size(); ++ls) {
      jump.rows[ls].Br.add(local[ls].xr.data(), l.getRawPtr());
      jump.rows[ls].Bp.add(local[ls].up.data(), l.getRawPtr());
    }
  }
  y.putScalar(0.0);
  y.doExport(*jump.ovWork, *jump.lmExport, Tpetra::ADD);
}

/// y = G F T x + E x: P F P x without coupled rows, P = the mask (restrained
/// rows out; doc/feti-dp.md "Coupled rows").
void DualOperator::apply(const std::vector<Subdomain>& subs, JumpOperator& jump, CoarseProblem& coarse,
                         const Vector& x, Vector& y) {
  for (LocalProblem& lp : local) {
    std::fill(lp.fr.begin(), lp.fr.end(), 0.0);
    std::fill(lp.fp.begin(), lp.fp.end(), 0.0);
  }
  if (jump.mask.is_null()) {
    scatterBt(jump, x, 1.0);
  } else {
    jump.multipliers(x, *jump.work);
    scatterBt(jump, *jump.work, 1.0);
  }
  applyKtildeInv(subs, coarse, nullptr);
  gatherB(jump, y);
  jump.equations(y, &x);
  ++nApply;
}

void FetiDpSolver::Impl::makeOperators() {
  fOp = rcp(new FOperator(this));
  mOp = prec.kind == Preconditioner::Kind::None ? Teuchos::null : RCP<Operator>(rcp(new MOperator(this)));
}

}  // namespace ddc
