#include "DDC_NodeDirectory.hpp"

#include <algorithm>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

NodeDirectory::NodeDirectory(MPI_Comm comm, const Mesh& mesh) : comm_(comm), mesh_(&mesh) {
  int me = 0;
  MPI_Comm_rank(comm_, &me);
  MPI_Comm_size(comm_, &ranks_);
  std::vector<std::vector<Note>> send(ranks_);
  for (int n = 0; n < mesh.numNodes(); ++n) send[directoryRank(mesh.nodeId(n))].push_back({mesh.nodeId(n), me});
  for (const Note& h : exchangeRecords(comm_, send)) holders_.emplace_back(h.node, h.value);
  std::sort(holders_.begin(), holders_.end());
  // Each holder learns the lowest holder (the first of the node's run).
  for (auto& v : send) v.clear();
  for (size_t i = 0, j = 0; i < holders_.size(); i = j)
    for (j = i; j < holders_.size() && holders_[j].first == holders_[i].first; ++j)
      send[holders_[j].second].push_back({holders_[i].first, holders_[i].second});
  lowest_.assign(mesh.numNodes(), ranks_);
  for (const Note& h : exchangeRecords(comm_, send)) lowest_[mesh.localNode(h.node)] = h.value;
  for (int n = 0; n < mesh.numNodes(); ++n)
    DDC_CHECK(lowest_[n] < ranks_, "NodeDirectory: node " << mesh.nodeId(n) << " is held by no rank");
}

int NodeDirectory::directoryRank(Mesh::GlobalId id) const {
  const Mesh::GlobalId numIds = std::max<Mesh::GlobalId>(mesh_->numGlobalNodes(), 1);
  return static_cast<int>(id * ranks_ / numIds);
}

std::vector<std::pair<int, int>> NodeDirectory::toHolders(const std::vector<Note>& notes) const {
  std::vector<std::vector<Note>> send(ranks_);
  for (const Note& n : notes) send[directoryRank(n.node)].push_back(n);
  const std::vector<Note> said = exchangeRecords(comm_, send);
  for (auto& v : send) v.clear();
  for (const Note& n : said) {
    const auto run = std::equal_range(holders_.begin(), holders_.end(), std::make_pair(n.node, -1),
                                      [](const auto& a, const auto& b) { return a.first < b.first; });
    DDC_CHECK(run.first != run.second, "NodeDirectory: a note on node " << n.node << ", which no rank holds");
    for (auto it = run.first; it != run.second; ++it) send[it->second].push_back(n);
  }
  std::vector<std::pair<int, int>> heard;
  for (const Note& n : exchangeRecords(comm_, send)) heard.emplace_back(mesh_->localNode(n.node), n.value);
  std::sort(heard.begin(), heard.end());  // local order is id order
  return heard;
}

std::vector<std::vector<int>> NodeDirectory::unite(const std::vector<std::vector<int>>& values) const {
  std::vector<Note> notes;
  for (int n = 0; n < mesh_->numNodes(); ++n)
    for (int v : values[n]) notes.push_back({mesh_->nodeId(n), v});
  std::vector<std::vector<int>> all(mesh_->numNodes());
  for (const auto& h : toHolders(notes))
    if (all[h.first].empty() || all[h.first].back() != h.second) all[h.first].push_back(h.second);
  return all;
}

std::vector<char> NodeDirectory::anyHolder(const std::vector<char>& flags) const {
  std::vector<Note> notes;
  for (int n = 0; n < mesh_->numNodes(); ++n)
    if (flags[n]) notes.push_back({mesh_->nodeId(n), 1});
  std::vector<char> any(mesh_->numNodes(), 0);
  for (const auto& h : toHolders(notes)) any[h.first] = 1;
  return any;
}

}  // namespace ddc
