// The slip rows of a slipping pair in the FETI-DP dual problem (see
// DDC_FetiSlipRows.hpp).
#include "DDC_FetiSlipRows.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <iterator>
#include <map>

namespace ddc {

SlipRowsInDual slipRowsInDual(const FrictionRows& fr, const std::vector<double>& b, const std::vector<char>& held,
                              LO normalRow, const std::vector<LO>& rows) {
  const int nt = int(rows.size());
  SlipRowsInDual out;
  out.active.assign(nt, 0);
  out.rhs.assign(nt, 0.0);
  out.known.assign(nt, 0.0);
  std::vector<int> free;
  for (int a = 0; a < nt; ++a)
    if (!held[a]) free.push_back(a);
  if (free.empty()) return out;
  // The directions v_j over the free rows: the eigenvectors of A there (a
  // single free row: its own direction).
  const int nf = int(free.size());
  Eigen::MatrixXd A(nf, nf), S(nf, nf);
  Eigen::VectorXd an(nf), bf(nf);
  for (int p = 0; p < nf; ++p) {
    an[p] = fr.lambdaNDerivative[free[p]];
    bf[p] = b[free[p]];
    for (int q = 0; q < nf; ++q) A(p, q) = fr.lambdaTDerivative(free[p], free[q]), S(p, q) = fr.slipDerivative(free[p], free[q]);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
  const Eigen::MatrixXd V = nf == 1 ? Eigen::MatrixXd::Identity(1, 1) : Eigen::MatrixXd(eig.eigenvectors());
  std::map<int, std::vector<std::pair<LO, double>>> columns;  // free row p -> its multiplier's terms
  int unknowns = 0;
  for (int j = 0; j < nf; ++j) {
    const Eigen::VectorXd v = V.col(j);
    const double alpha = v.dot(A * v), sigma = v.dot(S * v), aj = v.dot(an), bj = v.dot(bf);
    // σ = −k on the direction across the slip (k = μ p⁺/|z| ≤ 1).
    if (nf == 1 || -sigma < kCoupledSlipRowMinRatio) {
      for (int p = 0; p < nf; ++p) {
        out.known[free[p]] += bj / alpha * v[p];
        if (aj != 0.0) columns[p].emplace_back(normalRow, -aj / alpha * v[p]);
      }
      continue;
    }
    // A compliant row along v, its unknown held by the next free row.
    const int u = free[unknowns++];
    out.active[u] = 1;
    out.rhs[u] = bj / sigma;
    CoupledRow row;
    row.row = rows[u];
    // k = 1 − c_t α at most 1 but for the stick hysteresis and round-off
    // (a pair that slipped through the last step starts the next one on the
    // cone, |z| = μ p⁺): then the row is a hard one.
    row.compliance = std::max(alpha / -sigma, 0.0);
    for (int p = 0; p < nf; ++p) {
      row.equation.emplace_back(rows[free[p]], v[p]);
      columns[p].emplace_back(rows[u], v[p]);
    }
    out.coupled.push_back(row);
  }
  for (auto& [p, terms] : columns) {
    auto it = std::find_if(out.coupled.begin(), out.coupled.end(),
                           [&](const CoupledRow& r) { return r.row == rows[free[p]]; });
    if (it == out.coupled.end()) {
      out.coupled.push_back(CoupledRow{rows[free[p]], {}, {}, 0.0});
      it = std::prev(out.coupled.end());
    }
    it->multiplier = terms;
  }
  return out;
}

}  // namespace ddc
