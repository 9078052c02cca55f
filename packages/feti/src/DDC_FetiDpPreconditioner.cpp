// FETI-DP, preconditioner (doc/feti-dp.md "Preconditioner and scaling"):
// M^{-1} = sum_s B_D^s S^s B_D^sT with the Dirichlet Schur complement S^s =
// K_DD - K_DI K_II^{-1} K_ID of each subdomain on its dual DOFs (primal DOFs
// fixed), or the lumped S^s = K_DD, and the blocks it needs. The weights of
// B_D are the JumpOperator's (DDC_FetiDpScaling.cpp). See DDC_FetiDpImpl.hpp.
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_FetiDpImpl.hpp"
#include "DDC_LocalCsr.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

/// Pattern of K_II (CrsMatrix on MPI_COMM_SELF) and, for the Dirichlet
/// preconditioner, its solver.
void Preconditioner::build(const std::vector<Subdomain>& subs, const DirectSolverFactory& factory,
                           const Teuchos::ParameterList& localParams, const std::string& where) {
  blocks.clear();
  blocks.resize(subs.size());
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const Subdomain& s = subs[ls];
    Blocks& b = blocks[ls];
    if (kind == Kind::Dirichlet && s.ni > 0 && (s.nd > 0 || interiorsOnly)) {
      Teuchos::ParameterList p(localParams);
      b.solver = factory.create(p, where);
    }
    std::vector<LO> interior(s.n, kNone);
    for (LO k = 0; k < s.n; ++k)
      if (s.rIdx[k] != kNone) interior[k] = s.iIdx[s.rIdx[k]];
    b.Kii = extractBlock(*s.K, interior, s.ni);
    b.iMap = b.Kii->getRowMap();
    b.iB = rcp(new MultiVector(b.iMap, 1));
    b.iX = rcp(new MultiVector(b.iMap, 1));
    b.vd.assign(s.nd, 0.0);
    b.wd.assign(s.nd, 0.0);
  }
}

/// The values of K_II, K_ID, K_DI, K_DD from each K (after
/// DualOperator::factor(), which refreshes K^ with edge/face constraints),
/// and the K_II factorisations of the Dirichlet preconditioner.
void Preconditioner::factor(const Context& ctx, const std::vector<Subdomain>& subs, bool analysed) {
  std::string msg;
  for (size_t ls = 0; ls < subs.size() && msg.empty(); ++ls) {
    const Subdomain& s = subs[ls];
    Blocks& b = blocks[ls];
    const auto& rowMap = *s.K->getRowMap();
    const auto& colMap = *s.K->getColMap();
    b.Kii->resumeFill();
    b.Kii->setAllToScalar(0.0);
    b.KID.clear(), b.KDI.clear(), b.KDD.clear();
    const LocalCsr k(*s.K);
    std::vector<GO> ic;
    std::vector<double> iv;
    bool patternOk = true;
    for (LO lr = 0; lr < s.n; ++lr) {
      const LO rr = s.rIdx[static_cast<LO>(rowMap.getGlobalElement(lr))];
      if (rr == kNone) continue;
      ic.clear(), iv.clear();
      const LO ir = s.iIdx[rr], dr = s.dIdx[rr];
      for (size_t e = k.ptr[lr]; e < k.ptr[lr + 1]; ++e) {
        const LO rc = s.rIdx[static_cast<LO>(colMap.getGlobalElement(k.col[e]))];
        if (rc == kNone) continue;
        const double v = k.val[e];
        const LO icol = s.iIdx[rc], dc = s.dIdx[rc];
        if (ir != kNone && icol != kNone) ic.push_back(icol), iv.push_back(v);
        else if (interiorsOnly) continue;
        else if (ir != kNone) b.KID.push_back(Triplet{ir, dc, v});
        else if (icol != kNone) b.KDI.push_back(Triplet{dr, icol, v});
        else b.KDD.push_back(Triplet{dr, dc, v});
      }
      if (ir != kNone)
        patternOk = patternOk && b.Kii->sumIntoGlobalValues(ir, LO(ic.size()), iv.data(), ic.data()) == LO(ic.size());
    }
    b.Kii->fillComplete(b.iMap, b.iMap);
    if (!patternOk) {
      msg = "FETI-DP: subdomain " + std::to_string(s.id) +
            ": the sparsity pattern of K changed since setTopology(); call setTopology() again";
      break;
    }
    if (!b.solver) continue;
    try {
      if (!analysed) b.solver->symbolic(b.Kii);
      b.solver->numeric();
    } catch (const SolverError& e) {
      msg = "FETI-DP: subdomain " + std::to_string(s.id) +
            ": the interior stiffness K_II of the Dirichlet preconditioner is singular (an interior part not "
            "connected to the interface, primal DOFs or Dirichlet data?) [" +
            e.what() + "]; or use '" + ctx.param("Preconditioner") + "' = Lumped";
    }
  }
  raiseCollectively<SolverError>(ctx.mpi, msg);
}

/// y = D G M^{-1} Gᵀ D x (P M^{-1} P x without coupled rows), M^{-1} = sum_s B_D^s S^s B_D^sT with S^s = K_DD - K_DI
/// K_II^{-1} K_ID (Dirichlet) or K_DD (lumped). Primal DOFs count as fixed,
/// so entries of compatibility rows on primal DOFs do not enter; entries of
/// extra rows on primal or interior DOFs enter lumped and diagonal
/// (JumpOperator::Rows::lumped).
void Preconditioner::apply(const std::vector<Subdomain>& subs, const JumpOperator& jump, const Vector& x, Vector& y) {
  const double t0 = MPI_Wtime();
  if (jump.mask.is_null()) {
    jump.ovWork->doImport(x, *jump.lmImport, Tpetra::INSERT);
  } else {
    jump.equationsTransposedScaled(x, *jump.work);
    jump.ovWork->doImport(*jump.work, *jump.lmImport, Tpetra::INSERT);
  }
  std::vector<double> yOv(jump.lmOvMap->getNodeNumElements(), 0.0);
  {
    auto l = jump.ovWork->getData();
    for (size_t ls = 0; ls < subs.size(); ++ls) {
      const Subdomain& s = subs[ls];
      const JumpOperator::Rows& rw = jump.rows[ls];
      Blocks& b = blocks[ls];
      rw.lumped.add(l.getRawPtr(), yOv.data());
      std::fill(b.vd.begin(), b.vd.end(), 0.0);
      rw.BDd.addTransposed(l.getRawPtr(), 1.0, b.vd.data());
      std::fill(b.wd.begin(), b.wd.end(), 0.0);
      addTriplets(b.KDD, 1.0, b.vd.data(), b.wd.data());
      if (b.solver) {
        const double t1 = MPI_Wtime();
        b.vi.assign(s.ni, 0.0);
        addTriplets(b.KID, 1.0, b.vd.data(), b.vi.data());
        {
          auto in = b.iB->getDataNonConst(0);
          std::copy(b.vi.begin(), b.vi.end(), in.begin());
        }
        b.solver->solve(*b.iB, *b.iX);
        auto out = b.iX->getData(0);
        addTriplets(b.KDI, -1.0, out.getRawPtr(), b.wd.data());
        tDirichletSolve += MPI_Wtime() - t1;
      }
      rw.BDd.add(b.wd.data(), yOv.data());
    }
  }
  {
    auto l = jump.ovWork->getDataNonConst();
    std::copy(yOv.begin(), yOv.end(), l.begin());
  }
  y.putScalar(0.0);
  y.doExport(*jump.ovWork, *jump.lmExport, Tpetra::ADD);
  jump.equationsScaled(y);
  ++nApply;
  tApply += MPI_Wtime() - t0;
}

}  // namespace ddc
