// BDDC on FETI-DP's blocks (doc/feti-dp.md "BDDC"; Dohrmann 2003, Mandel,
// Dohrmann & Tezaur 2005). The Krylov solver iterates on the displacements of
// the interface DOFs (those not interior to a subdomain: dual and primal):
//
//   b_I eliminated:   z_I^s = K_II^{-1} b_I^s,   g = b_G - sum_s R^sT K_GI z_I^s
//   S u_G = g,        S = sum_s R^sT (K_GG - K_GI K_II^{-1} K_IG) R^s
//   M^{-1} r = sum_s R^sT D^s [K~^{-1} (D^s R^s r, 0 on I)]_G      (D^s = 1/m)
//   u_I^s = z_I^s - K_II^{-1} K_IG u_G^s
//
// K~^{-1} is FETI-DP's: the subdomain factorisations of K_rr (or K^s with
// Schur rows) and the coarse problem S_PiPi; K_II^{-1} is the Dirichlet
// preconditioner's factorisation. So BDDC adds only the K_IG, K_GI, K_GG
// blocks to FETI-DP's set-up, and its coarse solve sits in the
// preconditioner, where an approximate one leaves the answer exact (the
// multilevel BDDC of Tu 2007). See DDC_FetiDpImpl.hpp.
#include <BelosTpetraAdapter.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_FetiDpImpl.hpp"
#include "DDC_LocalCsr.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {

using Impl = FetiDpSolver::Impl;

/// v <- K_II^{-1} v in the interior index of one subdomain.
void solveInterior(Preconditioner::Blocks& b, std::vector<double>& v) {
  {
    auto in = b.iB->getDataNonConst(0);
    std::copy(v.begin(), v.end(), in.begin());
  }
  b.solver->solve(*b.iB, *b.iX);
  auto out = b.iX->getData(0);
  std::copy(out.begin(), out.end(), v.begin());
}

/// A Tpetra operator on the interface map from a member of Impl.
class InterfaceOperator : public Operator {
 public:
  using Apply = void (*)(Impl&, const Vector&, Vector&);
  InterfaceOperator(Impl* impl, Apply apply, const char* what) : impl_(impl), apply_(apply), what_(what) {}
  RCP<const Map> getDomainMap() const override { return impl_->iface.map; }
  RCP<const Map> getRangeMap() const override { return impl_->iface.map; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, Scalar alpha,
             Scalar beta) const override {
    if (mode != Teuchos::NO_TRANS) throw std::logic_error(std::string("BDDC ") + what_ + ": only NO_TRANS");
    Vector tmp(impl_->iface.map);
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      apply_(*impl_, *X.getVector(j), tmp);
      auto yj = Y.getVectorNonConst(j);
      if (beta == 0.0) yj->putScalar(0.0);  // ignore NaN/Inf in Y (BLAS convention)
      yj->update(alpha, tmp, beta);
    }
  }

 private:
  Impl* impl_;
  Apply apply_;
  const char* what_;
};

}  // namespace

void InterfaceProblem::build(const Context& ctx, const std::vector<Subdomain>& subs) {
  blocks.assign(subs.size(), Blocks{});
  std::string msg;
  Vector copiesOv(ctx.dofOvMap), copies(ctx.ownedMap);
  {
    auto c = copiesOv.getDataNonConst();
    for (size_t ls = 0; ls < subs.size(); ++ls) {
      const Subdomain& s = subs[ls];
      Blocks& b = blocks[ls];
      b.gIdx.assign(s.n, kNone);
      for (LO k = 0; k < s.n; ++k) {
        if (s.constrainable[k] && msg.empty())
          msg = "subdomain " + std::to_string(s.id) +
                " has DOFs that extra rows may touch (contact surfaces); BDDC takes no extra rows";
        if (interiorIndex(s, k) != kNone) continue;
        b.gIdx[k] = LO(b.gDof.size());
        b.gDof.push_back(k);
        c[s.ovLid[k]] += 1.0;
      }
    }
  }
  raiseCollectively<InputError>(ctx.mpi, msg.empty() ? "" : "'" + ctx.param("Method") + "' = BDDC: " + msg);
  copies.doExport(copiesOv, *ctx.dofExport, Tpetra::ADD);
  // Every copy of an interface DOF is on the interface, and an interior DOF
  // has one copy: what S and the weights 1/m rest on (stays on in Release).
  std::vector<GO> gids;
  ownedLid.clear();
  {
    auto c = copies.getData();
    for (LO l = 0; l < LO(c.size()); ++l) {
      const int m = ctx.ownedMult[l];
      if (c[l] > 0.0) {
        ownedLid.push_back(l);
        gids.push_back(ctx.ownedMap->getGlobalElement(l));
      }
      if ((c[l] > 0.0 && int(c[l]) != m) || (c[l] == 0.0 && m > 1)) {
        std::ostringstream os;
        os << "BDDC: DOF " << ctx.ownedMap->getGlobalElement(l) << " is shared by " << m << " subdomains but on the "
           << "interface of " << c[l] << " of them";
        msg = os.str();
        break;
      }
    }
  }
  raiseCollectively<std::logic_error>(ctx.mpi, msg);
  map = makeMap(gids, ctx.ownedMap->getIndexBase(), ctx.comm);
  owned = rcp(new Vector(ctx.ownedMap));
  ov = rcp(new Vector(ctx.dofOvMap));
}

void InterfaceProblem::refresh(const std::vector<Subdomain>& subs) {
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const Subdomain& s = subs[ls];
    Blocks& b = blocks[ls];
    b.KIG.clear(), b.KGI.clear(), b.KGG.clear();
    const auto& rowMap = *s.K->getRowMap();
    const auto& colMap = *s.K->getColMap();
    const LocalCsr k(*s.K);
    for (LO lr = 0; lr < s.n; ++lr) {
      const LO row = static_cast<LO>(rowMap.getGlobalElement(lr));
      const LO ir = interiorIndex(s, row), gr = b.gIdx[row];
      for (size_t e = k.ptr[lr]; e < k.ptr[lr + 1]; ++e) {
        const LO col = static_cast<LO>(colMap.getGlobalElement(k.col[e]));
        const LO ic = interiorIndex(s, col), gc = b.gIdx[col];
        if (ir != kNone && gc != kNone) b.KIG.push_back(Triplet{ir, gc, k.val[e]});
        else if (gr != kNone && ic != kNone) b.KGI.push_back(Triplet{gr, ic, k.val[e]});
        else if (gr != kNone) b.KGG.push_back(Triplet{gr, gc, k.val[e]});
      }
    }
    b.xg.assign(b.gDof.size(), 0.0);
    b.wg.assign(b.gDof.size(), 0.0);
    b.vi.assign(s.ni, 0.0);
    b.zi.assign(s.ni, 0.0);
  }
}

void InterfaceProblem::scatter(const Context& ctx, const Vector& x) {
  owned->putScalar(0.0);
  {
    auto o = owned->getDataNonConst();
    auto xv = x.getData();
    for (size_t g = 0; g < ownedLid.size(); ++g) o[ownedLid[g]] = xv[g];
  }
  ov->doImport(*owned, *ctx.dofImport, Tpetra::INSERT);
}

void InterfaceProblem::gather(const Context& ctx, const std::vector<double>& yOv, Vector& y) {
  {
    auto o = ov->getDataNonConst();
    std::copy(yOv.begin(), yOv.end(), o.begin());
  }
  owned->putScalar(0.0);
  owned->doExport(*ov, *ctx.dofExport, Tpetra::ADD);
  auto o = owned->getData();
  auto yv = y.getDataNonConst();
  for (size_t g = 0; g < ownedLid.size(); ++g) yv[g] = o[ownedLid[g]];
}

void InterfaceProblem::applySchur(const Context& ctx, const std::vector<Subdomain>& subs, Preconditioner& prec,
                                  const Vector& x, Vector& y) {
  scatter(ctx, x);
  std::vector<double>& yOv = yOvWork;  // kept: a fresh vector per iteration cost page faults
  yOv.assign(ov->getLocalLength(), 0.0);
  {
    auto xo = ov->getData();
    for (size_t ls = 0; ls < subs.size(); ++ls) {
      const Subdomain& s = subs[ls];
      Blocks& b = blocks[ls];
      for (size_t g = 0; g < b.gDof.size(); ++g) b.xg[g] = xo[s.ovLid[b.gDof[g]]];
      std::fill(b.wg.begin(), b.wg.end(), 0.0);
      addTriplets(b.KGG, 1.0, b.xg.data(), b.wg.data());
      if (s.ni > 0) {
        std::fill(b.vi.begin(), b.vi.end(), 0.0);
        addTriplets(b.KIG, 1.0, b.xg.data(), b.vi.data());
        solveInterior(prec.blocks[ls], b.vi);
        addTriplets(b.KGI, -1.0, b.vi.data(), b.wg.data());
      }
      for (size_t g = 0; g < b.gDof.size(); ++g) yOv[s.ovLid[b.gDof[g]]] += b.wg[g];
    }
  }
  gather(ctx, yOv, y);
  ++nApply;
}

/// The weighted restriction of r to each subdomain (D = 1/m, zero on the
/// interior) loaded as K~'s right-hand side, K~^{-1} by FETI-DP's subdomain
/// and coarse solves, and the weighted average of the subdomains' interface
/// values (the coarse solution at the primal DOFs).
void Impl::applyBddcPreconditioner(const Vector& r, Vector& z) {
  const double t0 = MPI_Wtime();
  iface.scatter(ctx, r);
  loadOverlapForces(*iface.ov);  // r imported once, by scatter()
  Vector fPi(coarse.map);
  primalForces(*iface.owned, fPi);
  dual.applyKtildeInv(subs, coarse, &fPi);
  assembleDisplacement(*iface.owned);
  auto o = iface.owned->getData();
  auto zv = z.getDataNonConst();
  for (size_t g = 0; g < iface.ownedLid.size(); ++g) zv[g] = o[iface.ownedLid[g]];
  ++prec.nApply;
  prec.tApply += MPI_Wtime() - t0;
}

double Impl::solveBddc(const Vector& b, Vector& u, FetiDpSolver::Info& info) {
  // g = b_G - sum_s R^sT K_GI K_II^{-1} b_I^s
  dofOvWork->doImport(b, *ctx.dofImport, Tpetra::INSERT);
  std::vector<double> yOv(dofOvWork->getLocalLength(), 0.0);
  {
    auto bo = dofOvWork->getData();
    for (size_t ls = 0; ls < subs.size(); ++ls) {
      const Subdomain& s = subs[ls];
      InterfaceProblem::Blocks& ib = iface.blocks[ls];
      if (s.ni == 0) continue;
      for (LO i = 0; i < s.ni; ++i) ib.zi[i] = bo[s.ovLid[s.rDof[s.iR[i]]]];
      solveInterior(prec.blocks[ls], ib.zi);
      std::fill(ib.wg.begin(), ib.wg.end(), 0.0);
      addTriplets(ib.KGI, -1.0, ib.zi.data(), ib.wg.data());
      for (size_t g = 0; g < ib.gDof.size(); ++g) yOv[s.ovLid[ib.gDof[g]]] += ib.wg[g];
    }
  }
  auto g = rcp(new MultiVector(iface.map, 1));
  auto uG = rcp(new MultiVector(iface.map, 1));
  iface.gather(ctx, yOv, *g->getVectorNonConst(0));
  {
    auto gv = g->getDataNonConst(0);
    auto bv = b.getData();
    for (size_t k = 0; k < iface.ownedLid.size(); ++k) gv[k] += bv[iface.ownedLid[k]];
  }

  // S u_G = g
  double gNorm = 0.0;
  {
    Teuchos::Array<double> n(1);
    g->norm2(n());
    gNorm = n[0];
  }
  const double tb0 = MPI_Wtime();
  if (gNorm > 0.0) {
    auto S = rcp(new InterfaceOperator(
        this, [](Impl& m, const Vector& x, Vector& y) { m.iface.applySchur(m.ctx, m.subs, m.prec, x, y); }, "S"));
    auto M = rcp(new InterfaceOperator(
        this, [](Impl& m, const Vector& x, Vector& y) { m.applyBddcPreconditioner(x, y); }, "preconditioner"));
    std::ostringstream system;
    system << "S u = g (" << iface.map->getGlobalNumElements() << " interface DOFs)";
    solveByBelos(S, M, g, uG, true, system.str(), info);
  }
  const double belosSeconds = MPI_Wtime() - tb0;

  // u_I = z_I - K_II^{-1} K_IG u_G, u_G as solved
  iface.scatter(ctx, *uG->getVector(0));
  std::fill(yOv.begin(), yOv.end(), 0.0);
  {
    auto uo = iface.ov->getData();
    for (size_t ls = 0; ls < subs.size(); ++ls) {
      const Subdomain& s = subs[ls];
      InterfaceProblem::Blocks& ib = iface.blocks[ls];
      if (s.ni == 0) continue;
      for (size_t k = 0; k < ib.gDof.size(); ++k) ib.xg[k] = uo[s.ovLid[ib.gDof[k]]];
      std::fill(ib.vi.begin(), ib.vi.end(), 0.0);
      addTriplets(ib.KIG, 1.0, ib.xg.data(), ib.vi.data());
      solveInterior(prec.blocks[ls], ib.vi);
      for (LO i = 0; i < s.ni; ++i) yOv[s.ovLid[s.rDof[s.iR[i]]]] = ib.zi[i] - ib.vi[i];
    }
  }
  {
    auto o = iface.ov->getDataNonConst();
    std::copy(yOv.begin(), yOv.end(), o.begin());
  }
  u.putScalar(0.0);
  u.doExport(*iface.ov, *ctx.dofExport, Tpetra::ADD);  // interior DOFs: one copy each
  auto uv = u.getDataNonConst();
  auto ug = uG->getData(0);
  for (size_t k = 0; k < iface.ownedLid.size(); ++k) uv[iface.ownedLid[k]] = ug[k];
  return belosSeconds;
}

}  // namespace ddc
