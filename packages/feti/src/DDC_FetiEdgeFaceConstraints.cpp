// Edge and face averages for FETI-DP: classification and change of basis
// (see DDC_FetiEdgeFaceConstraints.hpp, doc/feti-dp.md).
#include "DDC_FetiEdgeFaceConstraints.hpp"

#include <Tpetra_CrsGraph.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "DDC_LocalCsr.hpp"
#include "DDC_MapOwners.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {

/// "Who has this DOF", sent to the DOF's owner.
struct ShareMsg {
  GO gid;
  int subId;
  int rank;
  int localSub;
  LO dof;
};

/// One member of the set of subdomains sharing a DOF, sent back.
struct MemberMsg {
  int localSub;
  LO dof;
  int subId;
};

}  // namespace

const std::vector<std::string>& primalConstraintNames() {
  static const std::vector<std::string> names = {"Vertices", "Vertices and Edges", "Vertices, Edges and Faces"};
  return names;
}

PrimalConstraints primalConstraintsFromName(const std::string& name) {
  const auto& n = primalConstraintNames();
  const auto it = std::find(n.begin(), n.end(), name);
  if (it == n.end()) throw std::invalid_argument("unknown primal constraint choice '" + name + "'");
  return static_cast<PrimalConstraints>(it - n.begin());
}

std::vector<std::vector<std::vector<int>>> dofSharingSets(MPI_Comm comm, const Map& ownedMap,
                                                          const std::vector<EdgeFaceInput>& subs) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::string msg;
  // 1. Send every non-primal DOF to its owner, which learns who shares it.
  std::vector<std::vector<ShareMsg>> send(size);
  {
    std::vector<GO> gids;
    std::vector<std::pair<int, LO>> who;
    for (size_t ls = 0; ls < subs.size(); ++ls)
      for (LO k = 0; k < LO(subs[ls].dofs.size()); ++k)
        if (!subs[ls].primal[k]) gids.push_back(subs[ls].dofs[k]), who.emplace_back(int(ls), k);
    std::vector<int> pids;
    std::vector<LO> lids;
    owners(ownedMap, gids, pids, lids);
    for (size_t k = 0; k < gids.size(); ++k) {
      if (pids[k] < 0) {
        if (msg.empty()) msg = "FETI-DP primal constraints: DOF " + std::to_string(gids[k]) + " is not in the owned DOF map";
        continue;
      }
      send[pids[k]].push_back(ShareMsg{gids[k], subs[who[k].first].id, rank, who[k].first, who[k].second});
    }
  }
  raiseCollectively<std::invalid_argument>(comm, msg);
  std::vector<ShareMsg> recv = exchangeRecords(comm, send);
  std::sort(recv.begin(), recv.end(), [](const ShareMsg& a, const ShareMsg& b) {
    return a.gid != b.gid ? a.gid < b.gid : a.subId < b.subId;
  });

  // 2. The owner returns the sorted set of sharing subdomains to each sharer.
  std::vector<std::vector<MemberMsg>> reply(size);
  for (size_t a = 0; a < recv.size();) {
    size_t b = a;
    while (b < recv.size() && recv[b].gid == recv[a].gid) ++b;
    if (b - a >= 2)
      for (size_t i = a; i < b; ++i)
        for (size_t j = a; j < b; ++j) reply[recv[i].rank].push_back(MemberMsg{recv[i].localSub, recv[i].dof, recv[j].subId});
    a = b;
  }
  std::vector<MemberMsg> members = exchangeRecords(comm, reply);
  std::vector<std::vector<std::vector<int>>> sets(subs.size());
  for (size_t ls = 0; ls < subs.size(); ++ls) sets[ls].resize(subs[ls].dofs.size());
  for (const auto& m : members) sets[m.localSub][m.dof].push_back(m.subId);

  return sets;
}

namespace {

/// Why the input of findEdgeFaceConstraints() is inconsistent, or "".
std::string edgeFaceInputError(const std::vector<EdgeFaceInput>& subs, int dim, bool rotations) {
  std::string msg;
  if (dim != 2 && dim != 3) msg = "findEdgeFaceConstraints: spatial dimension " + std::to_string(dim) + ", expected 2 or 3";
  for (const auto& s : subs) {
    if (!msg.empty()) break;
    if (s.primal.size() != s.dofs.size() || s.component.size() != s.dofs.size()) {
      msg = "findEdgeFaceConstraints: subdomain " + std::to_string(s.id) + ": " + std::to_string(s.dofs.size()) +
            " DOFs but " + std::to_string(s.primal.size()) + " primal flags and " +
            std::to_string(s.component.size()) + " components (one per DOF expected)";
      break;
    }
    if (rotations && s.coordinates.size() != s.dofs.size() * size_t(std::max(dim, 0))) {
      msg = "findEdgeFaceConstraints: subdomain " + std::to_string(s.id) + ": rotational constraints need " +
            std::to_string(dim) + " coordinates per DOF, got " + std::to_string(s.coordinates.size()) + " for " +
            std::to_string(s.dofs.size()) + " DOFs";
      break;
    }
    for (int c : s.component)
      if (c < 0 || c >= dim) {
        msg = "findEdgeFaceConstraints: subdomain " + std::to_string(s.id) + ": DOF component " + std::to_string(c) +
              " outside 0.." + std::to_string(dim - 1);
        break;
      }
  }
  return msg;
}

/// The DOFs of one subdomain grouped by sharing set (`sets`: per DOF, the
/// subdomains sharing it; sorted here), keeping the sets that are edges,
/// and with `faces` faces.
std::map<std::vector<int>, std::vector<LO>> groupBySharingSet(const EdgeFaceInput& s,
                                                              std::vector<std::vector<int>>& sets, int dim,
                                                              bool faces) {
  std::map<std::vector<int>, std::vector<LO>> groups;
  for (LO k = 0; k < LO(s.dofs.size()); ++k) {
    auto& set = sets[k];
    if (set.size() < 2) continue;
    std::sort(set.begin(), set.end());
    // 2-D: a set of two is an edge; a non-primal node of three or more
    // (a cross point the caller left dual) is no edge. 3-D: two = face,
    // three or more = edge.
    const bool isEdge = dim == 2 ? set.size() == 2 : set.size() >= 3;
    const bool isFace = dim == 3 && set.size() == 2;
    if (isEdge || (isFace && faces)) groups[set].push_back(k);
  }
  return groups;
}

/// Rigid rotations w x (x - x_c) restricted to the group, made orthogonal
/// to the rows so far (modified Gram-Schmidt); one that (nearly) vanishes
/// there is dropped.
void addRotationRows(const EdgeFaceInput& s, int dim, PrimalGroup& g) {
  const size_t m = g.dofs.size();
  std::vector<double> xc(dim, 0.0);
  for (size_t i = 0; i < m; ++i)
    for (int d = 0; d < dim; ++d) xc[d] += s.coordinates[size_t(g.dofs[i]) * dim + d] / double(m);
  const int nRot = dim == 2 ? 1 : 3;
  for (int r = 0; r < nRot; ++r) {
    std::vector<double> row(m, 0.0);
    for (size_t i = 0; i < m; ++i) {
      const double* x = &s.coordinates[size_t(g.dofs[i]) * dim];
      const int c = s.component[g.dofs[i]];
      // 2-D (and rotation about z): (-(y - y_c), x - x_c, 0); about x:
      // (0, -(z - z_c), y - y_c); about y: (z - z_c, 0, -(x - x_c)).
      const int axis = dim == 2 ? 2 : r;
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;  // the plane of the rotation
      if (c == a) row[i] = -(x[b] - xc[b]);
      if (c == b) row[i] = x[a] - xc[a];
    }
    double n0 = 0.0;
    for (double v : row) n0 += v * v;
    n0 = std::sqrt(n0);
    if (n0 == 0.0) continue;
    for (size_t q = 0; q < g.rows.size(); ++q) {
      double dot = 0.0, nn = 0.0;
      for (size_t i = 0; i < m; ++i) dot += row[i] * g.rows[q][i], nn += g.rows[q][i] * g.rows[q][i];
      for (size_t i = 0; i < m; ++i) row[i] -= dot / nn * g.rows[q][i];
    }
    double n1 = 0.0;
    for (double v : row) n1 += v * v;
    n1 = std::sqrt(n1);
    if (n1 <= 1e-8 * n0) continue;  // vanishes on this edge / face
    for (double& v : row) v /= n1;
    g.rows.push_back(std::move(row));
  }
}

/// The group of DOFs `dofs` of subdomain `s` (sorted by GID) with its rows:
/// the average of each component present, and with `rotations` the rigid
/// rotations.
PrimalGroup makeGroup(const EdgeFaceInput& s, std::vector<LO> dofs, int dim, bool rotations) {
  PrimalGroup g;
  g.dofs = std::move(dofs);
  std::sort(g.dofs.begin(), g.dofs.end(), [&](LO a, LO b) { return s.dofs[a] < s.dofs[b]; });
  const size_t m = g.dofs.size();
  // Translations: the average of each component present.
  for (int c = 0; c < dim; ++c) {
    std::vector<double> row(m, 0.0);
    double count = 0.0;
    for (size_t i = 0; i < m; ++i) count += s.component[g.dofs[i]] == c ? 1.0 : 0.0;
    if (count == 0.0) continue;
    for (size_t i = 0; i < m; ++i) row[i] = s.component[g.dofs[i]] == c ? 1.0 / count : 0.0;
    g.rows.push_back(std::move(row));
  }
  if (rotations) addRotationRows(s, dim, g);
  return g;
}

}  // namespace

std::vector<std::vector<PrimalGroup>> findEdgeFaceConstraints(MPI_Comm comm, const Map& ownedMap,
                                                              const std::vector<EdgeFaceInput>& subs, int dim,
                                                              PrimalConstraints choice, bool rotations) {
  raiseCollectively<std::invalid_argument>(comm, edgeFaceInputError(subs, dim, rotations));

  std::vector<std::vector<PrimalGroup>> out(subs.size());
  if (choice == PrimalConstraints::Vertices) return out;

  auto sets = dofSharingSets(comm, ownedMap, subs);

  // 3. Group each subdomain's DOFs by sharing set. Every subdomain of a set
  //    has all DOFs of that set, so all of them form the same groups (and,
  //    from the same data in the same order, the same rows).
  const bool faces = choice == PrimalConstraints::VerticesEdgesAndFaces;
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const auto& s = subs[ls];
    for (auto& kv : groupBySharingSet(s, sets[ls], dim, faces))
      out[ls].push_back(makeGroup(s, std::move(kv.second), dim, rotations));
    std::sort(out[ls].begin(), out[ls].end(), [&](const PrimalGroup& a, const PrimalGroup& b) {
      return s.dofs[a.dofs[0]] < s.dofs[b.dofs[0]];
    });
  }
  return out;
}

// ---------------------------------------------------------------------------
// ChangeOfBasis
// ---------------------------------------------------------------------------

ChangeOfBasis::ChangeOfBasis(LO n, const std::vector<PrimalGroup>& groups, const std::vector<char>& avoid)
    : n_(n), group_(size_t(n), -1), rep_(size_t(n), -1), other_(size_t(n), -1) {
  if (!avoid.empty() && avoid.size() != size_t(n))
    throw std::invalid_argument("ChangeOfBasis: " + std::to_string(avoid.size()) + " avoid flags for " +
                                std::to_string(n) + " DOFs");
  std::vector<char> seen(size_t(n), 0);
  for (const PrimalGroup& in : groups) {
    const size_t m = in.dofs.size(), k = in.rows.size();
    for (LO d : in.dofs) {
      if (d < 0 || d >= n || seen[d])
        throw std::invalid_argument("ChangeOfBasis: DOF " + std::to_string(d) + " out of range or in two groups");
      seen[d] = 1;
    }
    if (k == 0) continue;
    if (k > m) throw std::invalid_argument("ChangeOfBasis: more constraints than DOFs in a group");
    for (const auto& row : in.rows)
      if (row.size() != m) throw std::invalid_argument("ChangeOfBasis: a constraint row of the wrong length");
    // Representatives: Gaussian elimination on the rows with the largest
    // remaining entry as pivot (column pivoting), among the DOFs not to
    // avoid while one of them has an entry of at least a tenth of the
    // largest (a pivot that small still keeps C_R well conditioned).
    std::vector<std::vector<double>> A = in.rows;
    std::vector<char> used(m, 0);
    std::vector<size_t> pivots;
    double scale = 0.0;
    for (const auto& row : in.rows)
      for (double v : row) scale = std::max(scale, std::abs(v));
    constexpr double kPreferredPivotRatio = 0.1;
    for (size_t j = 0; j < k; ++j) {
      size_t p = m, q = m;
      double best = 0.0, bestPreferred = 0.0;
      for (size_t c = 0; c < m; ++c) {
        if (used[c]) continue;
        const double a = std::abs(A[j][c]);
        if (a > best) best = a, p = c;
        if ((avoid.empty() || !avoid[in.dofs[c]]) && a > bestPreferred) bestPreferred = a, q = c;
      }
      if (q != m && bestPreferred >= kPreferredPivotRatio * best) p = q;
      if (p == m || best <= 1e-12 * scale)
        throw std::invalid_argument("ChangeOfBasis: linearly dependent constraint rows in a group");
      used[p] = 1;
      pivots.push_back(p);
      for (size_t j2 = j + 1; j2 < k; ++j2) {
        const double f = A[j2][p] / A[j][p];
        for (size_t c = 0; c < m; ++c) A[j2][c] -= f * A[j][c];
      }
    }
    Group g;
    std::vector<size_t> oIdx;
    for (size_t p : pivots) g.R.push_back(in.dofs[p]);
    for (size_t c = 0; c < m; ++c)
      if (!used[c]) g.O.push_back(in.dofs[c]), oIdx.push_back(c);
    // C in (R, O) column order; C_R^{-1} by Gauss-Jordan with partial pivoting.
    const size_t o = g.O.size();
    g.C.assign(k * m, 0.0);
    std::vector<double> CR(k * k), inv(k * k, 0.0);
    for (size_t j = 0; j < k; ++j) {
      for (size_t l = 0; l < k; ++l) g.C[j * m + l] = CR[j * k + l] = in.rows[j][pivots[l]];
      for (size_t q = 0; q < o; ++q) g.C[j * m + k + q] = in.rows[j][oIdx[q]];
      inv[j * k + j] = 1.0;
    }
    for (size_t c = 0; c < k; ++c) {
      size_t p = c;
      for (size_t r = c + 1; r < k; ++r)
        if (std::abs(CR[r * k + c]) > std::abs(CR[p * k + c])) p = r;
      if (CR[p * k + c] == 0.0) throw std::invalid_argument("ChangeOfBasis: singular C_R");
      for (size_t l = 0; l < k; ++l) std::swap(CR[c * k + l], CR[p * k + l]), std::swap(inv[c * k + l], inv[p * k + l]);
      const double d = CR[c * k + c];
      for (size_t l = 0; l < k; ++l) CR[c * k + l] /= d, inv[c * k + l] /= d;
      for (size_t r = 0; r < k; ++r) {
        if (r == c) continue;
        const double f = CR[r * k + c];
        for (size_t l = 0; l < k; ++l) CR[r * k + l] -= f * CR[c * k + l], inv[r * k + l] -= f * inv[c * k + l];
      }
    }
    g.Minv = inv;
    g.W.assign(k * o, 0.0);
    for (size_t j = 0; j < k; ++j)
      for (size_t q = 0; q < o; ++q) {
        double v = 0.0;
        for (size_t l = 0; l < k; ++l) v += inv[j * k + l] * g.C[l * m + k + q];
        g.W[j * o + q] = v;
      }
    for (size_t l = 0; l < k; ++l) rep_[g.R[l]] = LO(l);
    for (size_t q = 0; q < o; ++q) other_[g.O[q]] = LO(q);
    for (LO d : in.dofs) group_[d] = LO(groups_.size());
    groups_.push_back(std::move(g));
  }
}

LO ChangeOfBasis::numConstraints() const {
  LO k = 0;
  for (const auto& g : groups_) k += LO(g.k());
  return k;
}

void ChangeOfBasis::tRow(LO i, std::vector<std::pair<LO, double>>& out) const {
  out.clear();
  if (rep_.empty() || rep_[i] < 0) {  // u_i = û_i (outside the groups, or in O)
    out.emplace_back(i, 1.0);
    return;
  }
  // u_R = C_R^{-1} û_R - W û_O
  const Group& g = groups_[group_[i]];
  const size_t j = size_t(rep_[i]), k = g.k(), o = g.O.size();
  for (size_t l = 0; l < k; ++l)
    if (g.Minv[j * k + l] != 0.0) out.emplace_back(g.R[l], g.Minv[j * k + l]);
  for (size_t q = 0; q < o; ++q)
    if (g.W[j * o + q] != 0.0) out.emplace_back(g.O[q], -g.W[j * o + q]);
}

void ChangeOfBasis::tCol(LO a, std::vector<std::pair<LO, double>>& out) const {
  out.clear();
  if (group_.empty() || group_[a] < 0) {
    out.emplace_back(a, 1.0);
    return;
  }
  const Group& g = groups_[group_[a]];
  const size_t k = g.k(), o = g.O.size();
  if (rep_[a] >= 0) {  // a = R_l: T(R_j, a) = C_R^{-1}(j, l)
    const size_t l = size_t(rep_[a]);
    for (size_t j = 0; j < k; ++j)
      if (g.Minv[j * k + l] != 0.0) out.emplace_back(g.R[j], g.Minv[j * k + l]);
    return;
  }
  // a = O_q: T(a, a) = 1, T(R_j, a) = -W(j, q)
  const size_t q = size_t(other_[a]);
  out.emplace_back(a, 1.0);
  for (size_t j = 0; j < k; ++j)
    if (g.W[j * o + q] != 0.0) out.emplace_back(g.R[j], -g.W[j * o + q]);
}

/// K T and then T^T (K T), row by row with a dense accumulator: the cost per
/// group is about |G|^2 k, and nothing of size |G|^2 k^2 is stored.
void ChangeOfBasis::multiply(const CrsMatrix& K, bool values) {
  const auto& rowMap = *K.getRowMap();
  const auto& colMap = *K.getColMap();
  const LocalCsr k(K);
  std::vector<double> acc(size_t(n_), 0.0);
  std::vector<char> mark(size_t(n_), 0);
  std::vector<LO> touched;
  std::vector<std::pair<LO, double>> t;
  // KT rows (in local DOF order of K's rows).
  std::vector<std::vector<std::pair<LO, double>>> kt(static_cast<size_t>(n_));
  for (LO lr = 0; lr < n_; ++lr) {
    const LO i = LO(rowMap.getGlobalElement(lr));
    touched.clear();
    for (size_t e = k.ptr[lr]; e < k.ptr[lr + 1]; ++e) {
      const LO j = LO(colMap.getGlobalElement(k.col[e]));
      tRow(j, t);
      for (const auto& [b, tb] : t) {
        if (!mark[b]) mark[b] = 1, touched.push_back(b);
        acc[b] += k.val[e] * tb;
      }
    }
    auto& row = kt[i];
    row.reserve(touched.size());
    for (LO b : touched) row.emplace_back(b, acc[b]), acc[b] = 0.0, mark[b] = 0;
  }
  // K̂ row a = sum_i T(i, a) KT(i, :). The values pass reads K̂'s columns
  // from its own graph (row map = column map: local column = DOF).
  if (!values) hatCols_.assign(size_t(n_), {});
  std::vector<double> h;
  std::optional<LocalCsr> hc;
  if (values) {
    hc.emplace(*hat_);
    h.assign(hc->ptr[n_], 0.0);
  }
  for (LO a = 0; a < n_; ++a) {
    tCol(a, t);
    touched.clear();
    for (const auto& [i, ti] : t)
      for (const auto& [b, v] : kt[i]) {
        if (!mark[b]) mark[b] = 1, touched.push_back(b);
        acc[b] += ti * v;
      }
    if (!values) {
      hatCols_[a] = touched;
      std::sort(hatCols_[a].begin(), hatCols_[a].end());
    } else {
      for (size_t q = hc->ptr[a]; q < hc->ptr[a + 1]; ++q) h[q] = acc[hc->col[q]];
    }
    for (LO b : touched) acc[b] = 0.0, mark[b] = 0;
  }
  if (!values) return;
  hc.reset();
  hat_->resumeFill();
  {
    // The values in CSR order, written in one pass (the graph is static).
    auto A = hat_->getLocalMatrixHost();
    std::copy(h.begin(), h.end(), A.values.data());
  }
  hat_->fillComplete(hat_->getDomainMap(), hat_->getRangeMap());
}

Teuchos::RCP<CrsMatrix> ChangeOfBasis::setPattern(const CrsMatrix& K) {
  // The pattern from a symbolic pass (structural zeros kept: the values of
  // K may change, its pattern may not).
  multiply(K, false);
  kNnz_ = K.getNodeNumEntries();
  Teuchos::Array<size_t> nnz(n_);
  for (LO a = 0; a < n_; ++a) nnz[a] = hatCols_[a].size();
  auto map = Teuchos::rcp(new Map(static_cast<Tpetra::global_size_t>(n_), 0, K.getComm()));
  auto graph = Teuchos::rcp(new CrsGraph(map, map, nnz()));
  for (LO a = 0; a < n_; ++a) graph->insertLocalIndices(a, Teuchos::ArrayView<const LO>(hatCols_[a]));
  std::vector<std::vector<LO>>().swap(hatCols_);  // the graph holds the pattern now
  graph->fillComplete(map, map);
  hat_ = Teuchos::rcp(new CrsMatrix(graph));
  hat_->fillComplete(map, map);
  update(K);
  return hat_;
}

void ChangeOfBasis::update(const CrsMatrix& K) {
  if (K.getNodeNumEntries() != kNnz_)
    throw std::logic_error("the sparsity pattern of K changed since setTopology(); call setTopology() again");
  multiply(K, true);
}

void ChangeOfBasis::forceToNew(std::vector<double>& f) const {
  // f̂_R = C_R^{-T} f_R,  f̂_O = f_O - W^T f_R
  std::vector<double> fr;
  for (const auto& g : groups_) {
    const size_t k = g.k(), o = g.O.size();
    fr.resize(k);
    for (size_t j = 0; j < k; ++j) fr[j] = f[g.R[j]];
    for (size_t l = 0; l < k; ++l) {
      double v = 0.0;
      for (size_t j = 0; j < k; ++j) v += g.Minv[j * k + l] * fr[j];
      f[g.R[l]] = v;
    }
    for (size_t q = 0; q < o; ++q) {
      double v = 0.0;
      for (size_t j = 0; j < k; ++j) v += g.W[j * o + q] * fr[j];
      f[g.O[q]] -= v;
    }
  }
}

void ChangeOfBasis::displacementToOld(std::vector<double>& u) const {
  // u_R = C_R^{-1} û_R - W û_O
  std::vector<double> ur;
  for (const auto& g : groups_) {
    const size_t k = g.k(), o = g.O.size();
    ur.assign(k, 0.0);
    for (size_t j = 0; j < k; ++j) {
      for (size_t l = 0; l < k; ++l) ur[j] += g.Minv[j * k + l] * u[g.R[l]];
      for (size_t q = 0; q < o; ++q) ur[j] -= g.W[j * o + q] * u[g.O[q]];
    }
    for (size_t j = 0; j < k; ++j) u[g.R[j]] = ur[j];
  }
}

void ChangeOfBasis::displacementToNew(std::vector<double>& u) const {
  // û_R = C u_G
  std::vector<double> ur;
  for (const auto& g : groups_) {
    const size_t k = g.k(), o = g.O.size(), m = k + o;
    ur.assign(k, 0.0);
    for (size_t j = 0; j < k; ++j) {
      for (size_t l = 0; l < k; ++l) ur[j] += g.C[j * m + l] * u[g.R[l]];
      for (size_t q = 0; q < o; ++q) ur[j] += g.C[j * m + k + q] * u[g.O[q]];
    }
    for (size_t j = 0; j < k; ++j) u[g.R[j]] = ur[j];
  }
}

std::vector<std::pair<LO, double>> ChangeOfBasis::rowToNew(const std::vector<std::pair<LO, double>>& row) const {
  // (T^T c)_a = sum_i T(i, a) c_i
  std::map<LO, double> acc;
  std::vector<std::pair<LO, double>> t;
  for (const auto& [i, c] : row) {
    tRow(i, t);
    for (const auto& [a, ta] : t) acc[a] += c * ta;
  }
  std::vector<std::pair<LO, double>> out;
  for (const auto& [a, v] : acc)
    if (v != 0.0) out.emplace_back(a, v);
  return out;
}

}  // namespace ddc
