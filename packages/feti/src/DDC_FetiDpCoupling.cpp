// FETI-DP, coupled extra rows (doc/feti-dp.md "Coupled rows"): the
// multipliers lambda = T x of the dual unknowns, the equations G (B u) + E x,
// and the preconditioner's scaling D of the compliant rows. See
// DDC_FetiDpImpl.hpp (RowCoupling) and FetiDpSolver::setConstraintCoupling().
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "DDC_FetiDpImpl.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {

/// v's owned values as a std::vector (the coupling mixes entries in place).
std::vector<double> copyOf(const Vector& v) {
  auto d = v.getData();
  return std::vector<double>(d.begin(), d.end());
}

/// y = A x for the rows of A listed in `listed` (A's terms), P x for the others.
void applyListed(const std::vector<RowCoupling::Term>& terms, const std::vector<char>& listed, const Vector* mask,
                 const std::vector<double>& x, Vector& y) {
  auto yv = y.getDataNonConst();
  auto mv = mask ? mask->getData() : Teuchos::ArrayRCP<const double>();
  for (size_t i = 0; i < x.size(); ++i) yv[i] = listed[i] ? 0.0 : (mask ? mv[i] : 1.0) * x[i];
  for (const auto& t : terms) yv[t.i] += t.v * x[t.j];
}

/// y = Aᵀ x for A = the listed rows' terms and P elsewhere.
void applyListedTransposed(const std::vector<RowCoupling::Term>& terms, const std::vector<char>& listed,
                           const Vector* mask, const std::vector<double>& x, Vector& y) {
  auto yv = y.getDataNonConst();
  auto mv = mask ? mask->getData() : Teuchos::ArrayRCP<const double>();
  for (size_t i = 0; i < x.size(); ++i) yv[i] = listed[i] ? 0.0 : (mask ? mv[i] : 1.0) * x[i];
  for (const auto& t : terms) yv[t.j] += t.v * x[t.i];
}

}  // namespace

void JumpOperator::multipliers(const Vector& x, Vector& lambda) const {
  if (!coupling.any()) {
    lambda.assign(x);
    applyMask(lambda);
    return;
  }
  applyListed(coupling.columns, coupling.listedT, mask.get(), copyOf(x), lambda);
}

void JumpOperator::equations(Vector& y, const Vector* x) const {
  if (!coupling.any()) {
    applyMask(y);
    return;
  }
  applyListed(coupling.rowsOfG, coupling.listedG, mask.get(), copyOf(y), y);
  if (x == nullptr || coupling.compliance.empty()) return;
  auto yv = y.getDataNonConst();
  auto xv = x->getData();
  for (size_t i = 0; i < coupling.compliance.size(); ++i) yv[i] += coupling.compliance[i] * xv[i];
}

void JumpOperator::equationsTransposedScaled(const Vector& x, Vector& w) const {
  if (!coupling.any()) {
    w.assign(x);
    applyMask(w);
    return;
  }
  std::vector<double> xs = copyOf(x);
  for (size_t i = 0; i < coupling.scale.size(); ++i) xs[i] *= coupling.scale[i];
  applyListedTransposed(coupling.rowsOfG, coupling.listedG, mask.get(), xs, w);
}

void JumpOperator::equationsScaled(Vector& y) const {
  equations(y, nullptr);
  if (coupling.scale.empty()) return;
  auto yv = y.getDataNonConst();
  for (size_t i = 0; i < coupling.scale.size(); ++i) yv[i] *= coupling.scale[i];
}

/// D_i = (1 + E_i (G M^{-1} Gᵀ)_ii)^{-1/2} on the compliant rows: their
/// equation is (F + E)_ii, whose inverse M^{-1} approximates without E;
/// the diagonal is estimated by one application of the preconditioner to
/// the indicator of the compliant rows (neighbouring compliant rows add
/// their off-diagonal terms: an estimate, enough for a scaling).
void FetiDpSolver::Impl::scaleCompliantRows() {
  RowCoupling& c = jump.coupling;
  c.scale.clear();
  int any = 0, anyAll = 0;
  for (double e : c.compliance) any |= e > 0.0;
  MPI_Allreduce(&any, &anyAll, 1, MPI_INT, MPI_MAX, ctx.mpi);
  if (!anyAll || mOp.is_null()) return;
  Vector probe(jump.lmMap), y(jump.lmMap);
  {
    auto p = probe.getDataNonConst();
    for (size_t i = 0; i < c.compliance.size(); ++i) p[i] = c.compliance[i] > 0.0 ? 1.0 : 0.0;
  }
  mOp->apply(probe, y);
  c.scale.assign(probe.getLocalLength(), 1.0);
  auto yv = y.getData();
  for (size_t i = 0; i < c.compliance.size(); ++i)
    if (c.compliance[i] > 0.0) c.scale[i] = 1.0 / std::sqrt(1.0 + c.compliance[i] * std::max(yv[i], 0.0));
}

void FetiDpSolver::setConstraintCoupling(const std::vector<CoupledRow>& rows) {
  Impl& m = *impl_;
  JumpOperator& jump = m.jump;
  const size_t n = jump.extraRowMap.is_null() ? 0 : jump.extraRowMap->getNodeNumElements();
  const size_t nLm = jump.lmMap.is_null() ? 0 : jump.lmMap->getNodeNumElements();
  const LO off = LO(jump.nCompatOwned);
  if (jump.mask.is_null() && !jump.lmMap.is_null()) {  // no setConstraintState(): every row active
    jump.mask = rcp(new Vector(jump.lmMap));
    jump.mask->putScalar(1.0);
  }
  RowCoupling c;
  c.listedT.assign(nLm, 0);
  c.listedG.assign(nLm, 0);
  c.compliance.assign(nLm, 0.0);
  auto mk = jump.mask.is_null() ? Teuchos::ArrayRCP<const double>() : jump.mask->getData();
  auto active = [&](LO k) { return mk.is_null() || mk[off + k] != 0.0; };
  std::string msg;
  auto fail = [&](const std::string& what, LO row) {
    if (msg.empty())
      msg = "FetiDpSolver::setConstraintCoupling: row " + std::to_string(row) + ": " + what;
  };
  auto inRange = [&](LO k) { return k >= 0 && size_t(k) < n; };
  for (const CoupledRow& r : rows) {
    if (!inRange(r.row)) {
      fail("not a local row of the row map (" + std::to_string(n) + " rows)", r.row);
      continue;
    }
    const LO i = off + r.row;
    if (c.listedT[i] || c.listedG[i]) fail("listed twice", r.row);
    if (!r.multiplier.empty()) c.listedT[i] = 1;
    for (const auto& [j, a] : r.multiplier) {
      if (!inRange(j) || !active(j) || !std::isfinite(a))
        fail("a multiplier column must be an active local row with a finite coefficient", r.row);
      else
        c.columns.push_back({i, off + j, a});
    }
    if (!(r.compliance >= 0.0) || !std::isfinite(r.compliance)) fail("the compliance must be finite and >= 0", r.row);
    if ((!r.equation.empty() || r.compliance != 0.0) && !active(r.row))
      fail("an equation or a compliance on an inactive row", r.row);
    if (!r.equation.empty()) c.listedG[i] = 1;
    for (const auto& [j, g] : r.equation) {
      if (!inRange(j) || !std::isfinite(g))
        fail("an equation term must name a local row with a finite coefficient", r.row);
      else
        c.rowsOfG.push_back({i, off + j, g});
    }
    c.compliance[i] = r.compliance;
  }
  raiseCollectively<std::invalid_argument>(m.ctx.mpi, msg);
  // Symmetric when T = Gᵀ: compare T(i, j) with G(j, i) on every pair a
  // listed row touches (the unlisted rows are P on both sides).
  std::map<std::pair<LO, LO>, std::pair<double, double>> tg;
  for (const auto& t : c.columns) tg[{t.i, t.j}].first += t.v;
  for (const auto& g : c.rowsOfG) tg[{g.j, g.i}].second += g.v;
  for (size_t i = 0; i < nLm; ++i) {
    if (!c.listedT[i] && !c.listedG[i]) continue;
    const double p = mk.is_null() ? 1.0 : mk[i];
    if (!c.listedT[i]) tg[{LO(i), LO(i)}].first += p;
    if (!c.listedG[i]) tg[{LO(i), LO(i)}].second += p;
  }
  int symmetric = 1, all = 1;
  for (const auto& [ij, v] : tg)
    if (std::abs(v.first - v.second) > 1e-12 * std::max({std::abs(v.first), std::abs(v.second), 1e-300})) symmetric = 0;
  MPI_Allreduce(&symmetric, &all, 1, MPI_INT, MPI_MIN, m.ctx.mpi);
  c.symmetric = all != 0;
  bool compliant = false;
  for (double e : c.compliance) compliant |= e > 0.0;
  if (!compliant) c.compliance.clear();
  jump.coupling = std::move(c);
  jump.coupling.scale.clear();
  m.couplingScaled = false;
}

}  // namespace ddc
