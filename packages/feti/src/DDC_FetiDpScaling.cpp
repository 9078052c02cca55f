// FETI-DP, scaling (doc/feti-dp.md "Preconditioner and scaling", "Extra
// rows"): the weights of B_D in the preconditioner, and the sparse blocks of
// B and B_D the operators apply. See DDC_FetiDpImpl.hpp.
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

/// Scaling weights of B_D.
///
/// Compatibility rows: the entry of subdomain s in the row between s and t
/// at DOF j is multiplied by w_t(j) / sum_k w_k(j), with w = 1
/// (multiplicity: 1/m_j) or w = K^k_jj (stiffness, rho-scaling). The
/// partner's weight is the row sum of the weights minus the own one.
///
/// Extra rows (contact): a row joins the sides it has entries in, in
/// general two different bodies. A side is one connected part of a
/// subdomain (Subdomain::part): a subdomain holding pieces of two bodies
/// that only the row joins gives it two sides. Each side k sees the row
/// with the stiffness rho_k = sum over its entries of c_j^2 |K^k_jj| (the
/// caller's basis: the diagonal of B^k K^k B^kT); its entries are weighted
///     D_k = (rho - rho_k) / ((m - 1) rho),   rho = sum_k rho_k,
/// over the m sides (D = 1 for m = 1; 1/m with multiplicity scaling).
/// For two sides this is rho-scaling, D_1 = rho_2 / (rho_1 + rho_2): the
/// preconditioner's diagonal D_1^2 rho_1 + D_2^2 rho_2 = rho_1 rho_2 /
/// (rho_1 + rho_2) is then the inverse of the row's flexibility 1/rho_1 +
/// 1/rho_2, whatever the stiffness ratio of the two bodies. Equal weights
/// 1/2 instead give (rho_1 + rho_2)/4: with a body 1000 times stiffer than
/// the other, the contact rows' preconditioner was ~250 times too stiff and
/// the dual iterations grew tenfold (doc/feti-dp.md, "Extra rows").
void JumpOperator::computeWeights(const Context& ctx, const std::vector<Subdomain>& subs) {
  const bool stiffCompat = scaling == Scaling::Stiffness;
  const bool stiffExtra = scaling != Scaling::Multiplicity;
  auto weight = [&](const Subdomain& s, LO dof) { return stiffCompat ? std::abs(s.diag[dof]) : 1.0; };
  // Compatibility weights: w per copy, summed over the copies (wOv) and per
  // row (rowOv).
  Vector wOv(ctx.dofOvMap), wOwned(ctx.ownedMap), rowOv(lmOvMap), row(lmMap);
  {
    auto w = wOv.getDataNonConst();
    auto rs = rowOv.getDataNonConst();
    for (size_t ls = 0; ls < subs.size(); ++ls) {
      const Subdomain& s = subs[ls];
      for (LO r = 0; r < s.nr; ++r)
        if (s.dIdx[r] != kNone) w[s.ovLid[s.rDof[r]]] += weight(s, s.rDof[r]);
      for (const Entry& e : rows[ls].entries)
        if (!e.extra) rs[e.lm] += weight(s, e.dof);
    }
  }
  wOwned.doExport(wOv, *ctx.dofExport, Tpetra::ADD);
  wOv.doImport(wOwned, *ctx.dofImport, Tpetra::INSERT);
  row.doExport(rowOv, *lmExport, Tpetra::ADD);
  rowOv.doImport(row, *lmImport, Tpetra::INSERT);
  auto w = wOv.getData();
  auto rs = rowOv.getData();

  // Extra rows: the stiffness of each side (key), rho = sum over the
  // caller's entries of c^2 times the DOF's diagonal assembled over its
  // copies (the caller's basis), summed at the row's owner, who turns the
  // sides of a row into their weights D.
  Vector dOv(ctx.dofOvMap), dOwned(ctx.ownedMap);
  {
    auto d = dOv.getDataNonConst();
    for (const Subdomain& s : subs)
      for (LO k = 0; k < s.n; ++k) d[s.ovLid[k]] += std::abs(s.diagUser[k]);
  }
  dOwned.doExport(dOv, *ctx.dofExport, Tpetra::ADD);
  dOv.doImport(dOwned, *ctx.dofImport, Tpetra::INSERT);
  Vector rhoOv(sideOvMap), rho(sideMap);
  {
    auto d = dOv.getData();
    auto r = rhoOv.getDataNonConst();
    for (size_t ls = 0; ls < subs.size(); ++ls) {
      const Subdomain& s = subs[ls];
      for (const GidEntry& e : rows[ls].extraUser) {
        const LO key = sideOvMap->getLocalElement(e.lm * sideSpan + s.sideOf(e.dof));
        if (key != Teuchos::OrdinalTraits<LO>::invalid()) r[key] += e.coef * e.coef * d[s.ovLid[e.dof]];
      }
    }
  }
  rho.doExport(rhoOv, *sideExport, Tpetra::ADD);
  {
    // Owned keys of a row are contiguous (sorted by row, then side).
    auto r = rho.getDataNonConst();
    const LO n = LO(sideMap->getNodeNumElements());
    std::vector<double> D(size_t(n), 1.0);
    for (LO a = 0; a < n;) {
      const GO rowGid = sideMap->getGlobalElement(a) / sideSpan;
      LO b = a;
      double total = 0.0;
      while (b < n && sideMap->getGlobalElement(b) / sideSpan == rowGid) total += r[b++];
      const double m = double(b - a);
      for (LO k = a; k < b; ++k)
        if (m >= 2.0) D[k] = stiffExtra && total > 0.0 ? (total - r[k]) / ((m - 1.0) * total) : 1.0 / m;
      a = b;
    }
    for (LO k = 0; k < n; ++k) r[k] = D[k];
  }
  rhoOv.doImport(rho, *sideImport, Tpetra::INSERT);
  auto D = rhoOv.getData();


  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const Subdomain& s = subs[ls];
    Rows& rw = rows[ls];
    for (Entry& e : rw.entries) {
      if (e.extra) {
        if (e.split) {
          // omega_k: this copy's share in the compatibility weights.
          const double sum = w[s.ovLid[e.dof]];
          e.coef = e.full * (sum > 0.0 ? weight(s, e.dof) / sum : s.invMult[e.dof]);
        }
        e.scaled = (e.sideKey >= 0 ? D[e.sideKey] : 1.0) * e.full;
        continue;
      }
      const double sum = w[s.ovLid[e.dof]];
      const double other = rs[e.lm] - weight(s, e.dof);
      // A zero diagonal (degenerate input) falls back to multiplicity.
      e.scaled = sum > 0.0 && other >= 0.0 ? e.coef * other / sum : e.coef * s.invMult[e.dof];
    }
  }
  assembleBlocks(subs, true);
  weightsCurrent = true;
}

/// The sparse blocks the operators apply, from the entries (sorted by row):
/// B on the remainder and primal DOFs and, with `weights`, B_D on the dual
/// DOFs and the lumped diagonal of extra rows on primal (or interior) DOFs.
/// Without that term a row lying on primal DOFs only (a slave node on a
/// primal master node) has no preconditioner at all and CG breaks down.
void JumpOperator::assembleBlocks(const std::vector<Subdomain>& subs, bool weights) {
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const Subdomain& s = subs[ls];
    Rows& rw = rows[ls];
    rw.Br.clear(), rw.Bp.clear(), rw.BDd.clear(), rw.lumped.clear();
    for (const Entry& e : rw.entries) {
      const LO r = s.rIdx[e.dof];
      if (r != kNone) rw.Br.push(e.lm, r, e.coef);
      else rw.Bp.push(e.lm, s.pIdx[e.dof], e.coef);
      if (!weights) continue;
      if (r != kNone && s.dIdx[r] != kNone) rw.BDd.push(e.lm, s.dIdx[r], e.scaled);
      else if (e.extra) rw.lumped.push(e.lm, e.lm, e.scaled * e.scaled * std::abs(s.diag[e.dof]));
    }
  }
}

}  // namespace ddc
