// Edge and face averages for FETI-DP: classification and change of basis
// (see DDC_FetiPrimalAverages.hpp, doc/feti-dp.md).
#include "DDC_FetiPrimalAverages.hpp"

#include <Tpetra_CrsGraph.hpp>
#include <algorithm>
#include <map>
#include <stdexcept>

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

std::vector<std::vector<std::vector<LO>>> findPrimalAverages(MPI_Comm comm, const Map& ownedMap,
                                                             const std::vector<AverageInput>& subs, int dim,
                                                             PrimalConstraints choice) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::string msg;
  if (dim != 2 && dim != 3) msg = "findPrimalAverages: spatial dimension " + std::to_string(dim) + ", expected 2 or 3";
  for (const auto& s : subs) {
    if (!msg.empty()) break;
    if (s.primal.size() != s.dofs.size() || s.component.size() != s.dofs.size()) {
      msg = "findPrimalAverages: subdomain " + std::to_string(s.id) + ": " + std::to_string(s.dofs.size()) +
            " DOFs but " + std::to_string(s.primal.size()) + " primal flags and " +
            std::to_string(s.component.size()) + " components (one per DOF expected)";
      break;
    }
    for (int c : s.component)
      if (c < 0 || c >= dim) {
        msg = "findPrimalAverages: subdomain " + std::to_string(s.id) + ": DOF component " + std::to_string(c) +
              " outside 0.." + std::to_string(dim - 1);
        break;
      }
  }
  raiseCollectively<std::invalid_argument>(comm, msg);

  std::vector<std::vector<std::vector<LO>>> out(subs.size());
  if (choice == PrimalConstraints::Vertices) return out;

  // 1. Send every non-primal DOF to its owner, which learns who shares it.
  std::vector<std::vector<ShareMsg>> send(size);
  {
    std::vector<GO> gids;
    std::vector<std::pair<int, LO>> who;
    for (size_t ls = 0; ls < subs.size(); ++ls)
      for (LO k = 0; k < LO(subs[ls].dofs.size()); ++k)
        if (!subs[ls].primal[k]) gids.push_back(subs[ls].dofs[k]), who.emplace_back(int(ls), k);
    Teuchos::Array<int> pids(gids.size());
    Teuchos::Array<LO> lids(gids.size());
    ownedMap.getRemoteIndexList(Teuchos::ArrayView<const GO>(gids.data(), gids.size()), pids(), lids());
    for (size_t k = 0; k < gids.size(); ++k) {
      if (pids[k] < 0) {
        if (msg.empty()) msg = "findPrimalAverages: DOF " + std::to_string(gids[k]) + " is not in the owned DOF map";
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

  // 3. Group each subdomain's DOFs by (sharing set, component). Every
  //    subdomain of a set has all DOFs of that set, so all of them form the
  //    same groups.
  const bool faces = choice == PrimalConstraints::VerticesEdgesAndFaces;
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const auto& s = subs[ls];
    std::map<std::pair<std::vector<int>, int>, std::vector<LO>> groups;
    for (LO k = 0; k < LO(s.dofs.size()); ++k) {
      auto& set = sets[ls][k];
      if (set.size() < 2) continue;
      std::sort(set.begin(), set.end());
      // 2-D: a set of two is an edge; a non-primal node of three or more
      // (a cross point the caller left dual) is no edge. 3-D: two = face,
      // three or more = edge.
      const bool isEdge = dim == 2 ? set.size() == 2 : set.size() >= 3;
      const bool isFace = dim == 3 && set.size() == 2;
      if (isEdge || (isFace && faces)) groups[{set, s.component[k]}].push_back(k);
    }
    for (auto& kv : groups) {
      auto& g = kv.second;
      std::sort(g.begin(), g.end(), [&](LO a, LO b) { return s.dofs[a] < s.dofs[b]; });
      out[ls].push_back(std::move(g));
    }
    std::sort(out[ls].begin(), out[ls].end(),
              [&](const std::vector<LO>& a, const std::vector<LO>& b) { return s.dofs[a[0]] < s.dofs[b[0]]; });
  }
  return out;
}

// ---------------------------------------------------------------------------
// ChangeOfBasis
// ---------------------------------------------------------------------------

ChangeOfBasis::ChangeOfBasis(LO n, std::vector<std::vector<LO>> groups)
    : n_(n), groups_(std::move(groups)), head_(size_t(n), -1), group_(size_t(n), -1) {
  for (size_t g = 0; g < groups_.size(); ++g)
    for (LO d : groups_[g]) {
      if (d < 0 || d >= n || group_[d] >= 0)
        throw std::invalid_argument("ChangeOfBasis: DOF " + std::to_string(d) + " out of range or in two groups");
      group_[d] = LO(g);
      head_[d] = groups_[g][0];
    }
}

void ChangeOfBasis::tRow(LO i, std::vector<std::pair<LO, double>>& out) const {
  out.clear();
  if (group_[i] < 0) {
    out.emplace_back(i, 1.0);
    return;
  }
  const auto& g = groups_[group_[i]];
  out.emplace_back(g[0], 1.0);
  if (i == g[0]) {
    for (size_t k = 1; k < g.size(); ++k) out.emplace_back(g[k], -1.0);
  } else {
    out.emplace_back(i, 1.0);
  }
}

Teuchos::RCP<CrsMatrix> ChangeOfBasis::setPattern(const CrsMatrix& K) {
  const auto& rowMap = *K.getRowMap();
  const auto& colMap = *K.getColMap();
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  kOffsets_.assign(size_t(n_) + 1, 0);
  hatCols_.assign(size_t(n_), {});
  struct Contribution {
    size_t src;
    LO a, b;
    double coef;
  };
  std::vector<Contribution> contrib;
  std::vector<std::pair<LO, double>> ti, tj;
  for (LO lr = 0; lr < n_; ++lr) {
    const LO i = LO(rowMap.getGlobalElement(lr));
    K.getLocalRowView(lr, inds, vals);
    kOffsets_[lr + 1] = kOffsets_[lr] + inds.extent(0);
    tRow(i, ti);
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const LO j = LO(colMap.getGlobalElement(inds(e)));
      tRow(j, tj);
      for (const auto& [a, ca] : ti)
        for (const auto& [b, cb] : tj) {
          contrib.push_back(Contribution{kOffsets_[lr] + e, a, b, ca * cb});
          hatCols_[a].push_back(b);
        }
    }
  }
  hatOffsets_.assign(size_t(n_) + 1, 0);
  Teuchos::Array<size_t> nnz(n_);
  for (LO a = 0; a < n_; ++a) {
    auto& c = hatCols_[a];
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    nnz[a] = c.size();
    hatOffsets_[a + 1] = hatOffsets_[a] + c.size();
  }
  plan_.clear();
  plan_.reserve(contrib.size());
  for (const auto& c : contrib) {
    const auto& cols = hatCols_[c.a];
    const size_t pos = size_t(std::lower_bound(cols.begin(), cols.end(), c.b) - cols.begin());
    plan_.push_back(PlanEntry{c.src, hatOffsets_[c.a] + pos, c.coef});
  }
  auto map = Teuchos::rcp(new Map(static_cast<Tpetra::global_size_t>(n_), 0, K.getComm()));
  auto graph = Teuchos::rcp(new CrsGraph(map, map, nnz()));
  for (LO a = 0; a < n_; ++a) graph->insertLocalIndices(a, Teuchos::ArrayView<const LO>(hatCols_[a]));
  graph->fillComplete(map, map);
  hat_ = Teuchos::rcp(new CrsMatrix(graph));
  hat_->fillComplete(map, map);
  update(K);
  return hat_;
}

void ChangeOfBasis::update(const CrsMatrix& K) {
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  std::vector<double> k(kOffsets_.back());
  for (LO lr = 0; lr < n_; ++lr) {
    K.getLocalRowView(lr, inds, vals);
    if (kOffsets_[lr] + inds.extent(0) != kOffsets_[lr + 1])
      throw std::logic_error("the sparsity pattern of K changed since setTopology(); call setTopology() again");
    for (size_t e = 0; e < vals.extent(0); ++e) k[kOffsets_[lr] + e] = vals(e);
  }
  std::vector<double> h(hatOffsets_.back(), 0.0);
  for (const auto& p : plan_) h[p.dst] += p.coef * k[p.src];
  hat_->resumeFill();
  for (LO a = 0; a < n_; ++a)
    hat_->replaceLocalValues(a, Teuchos::ArrayView<const LO>(hatCols_[a]),
                             Teuchos::ArrayView<const double>(h.data() + hatOffsets_[a], hatCols_[a].size()));
  hat_->fillComplete(hat_->getDomainMap(), hat_->getRangeMap());
}

void ChangeOfBasis::forceToNew(std::vector<double>& f) const {
  for (const auto& g : groups_) {
    const double f0 = f[g[0]];
    double sum = f0;
    for (size_t k = 1; k < g.size(); ++k) {
      sum += f[g[k]];
      f[g[k]] -= f0;
    }
    f[g[0]] = sum;
  }
}

void ChangeOfBasis::displacementToOld(std::vector<double>& u) const {
  for (const auto& g : groups_) {
    const double avg = u[g[0]];
    double dev = 0.0;
    for (size_t k = 1; k < g.size(); ++k) {
      dev += u[g[k]];
      u[g[k]] += avg;
    }
    u[g[0]] = avg - dev;
  }
}

void ChangeOfBasis::displacementToNew(std::vector<double>& u) const {
  for (const auto& g : groups_) {
    double sum = 0.0;
    for (LO d : g) sum += u[d];
    const double avg = sum / double(g.size());
    for (size_t k = 1; k < g.size(); ++k) u[g[k]] -= avg;
    u[g[0]] = avg;
  }
}

std::vector<std::pair<LO, double>> ChangeOfBasis::rowToNew(const std::vector<std::pair<LO, double>>& row) const {
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
