// FETI-DP, scaling (doc/feti-dp.md "Preconditioners and scalings"): the
// weights of B_D in the preconditioner. See DDC_FetiDpImpl.hpp.
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

/// Scaling weights of B_D: the entry of subdomain s in the row between s and
/// t at DOF j is multiplied by w_t(j) / sum_k w_k(j), with w = 1
/// ("Multiplicity": 1/m_j) or w = K^k_jj ("Stiffness", rho-scaling). The
/// partner's weight is the row sum of the weights minus the own one.
void FetiDpSolver::Impl::computeScaling() {
  auto weight = [&](const Sub& s, LO dof) { return stiffnessScaling ? std::abs(s.diag[dof]) : 1.0; };
  Vector wOv(dofOvMap), wOwned(ownedMap), rowOv(lmOvMap), row(lmMap);
  {
    auto w = wOv.getDataNonConst();
    auto rs = rowOv.getDataNonConst();
    for (const Sub& s : subs) {
      for (LO r = 0; r < s.nr; ++r)
        if (s.dIdx[r] != kNone) w[s.ovLid[s.rDof[r]]] += weight(s, s.rDof[r]);
      for (const BEntry& e : s.B)
        if (!e.extra) rs[e.lm] += weight(s, e.dof);
    }
  }
  wOwned.doExport(wOv, *dofExport, Tpetra::ADD);
  wOv.doImport(wOwned, *dofImport, Tpetra::INSERT);
  row.doExport(rowOv, *lmExport, Tpetra::ADD);
  rowOv.doImport(row, *lmImport, Tpetra::INSERT);
  auto w = wOv.getData();
  auto rs = rowOv.getData();
  for (Sub& s : subs)
    for (BEntry& e : s.B) {
      if (e.extra) {
        // An extra (contact) row joins two sides (slave and master), like a
        // compatibility row between two copies: weight 1/2 on each side.
        e.scaled = 0.5 * e.coef;
        continue;
      }
      const double sum = w[s.ovLid[e.dof]];
      const double other = rs[e.lm] - weight(s, e.dof);
      // A zero diagonal (degenerate input) falls back to multiplicity.
      e.scaled = sum > 0.0 && other >= 0.0 ? e.coef * other / sum : e.coef * s.invMult[e.dof];
    }
}

}  // namespace ddc
