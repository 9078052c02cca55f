// readExodusBodyInRange(): an Exodus II body read in slabs, each rank the
// elements of its range and the sets' entries of an even share, with the
// whole reader's numbering and messages (DDC_ExodusMesh.hpp). No rank reads
// or holds the whole block, its coordinates or its sets.
//
// The body's nodes are the block's nodes in file order, so a node's number
// in the body needs to know which file nodes before it the block uses. The
// file's nodes are dealt to the ranks in even ranges: each rank asks the
// owners of its elements' nodes for them, an owner numbers the nodes it was
// asked for after those of the ranks before it (one exclusive scan), reads
// its range's coordinates, checks them and answers. Set memberships go the
// same way, through the node's owner to every rank that holds the node.
#include <mpi.h>

#include <exodusII.h>

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_ExodusCells.hpp"
#include "DDC_ExodusFile.hpp"
#include "DDC_ExodusMesh.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {

/// A rank that holds file node `node` (0-based), to the node's owner.
struct NodeRequest {
  int node, rank;
};
/// The owner's answer: the node's number in the body and its coordinates.
struct NodeAnswer {
  long long bodyNode;
  int node;
  double x[3];
};
/// File node `node` is in set `set` (node sets first, then side sets).
struct SetMember {
  int set, node;
};
/// Side `facet` of the block's element `element` (0-based in the block) is
/// in side set `set`, to the rank that holds the element.
struct SideRecord {
  int set, element, facet;
};

/// The rank of `starts` (P + 1 ascending starts of contiguous ranges) whose
/// range holds `i`.
int rangeRank(const std::vector<long long>& starts, long long i) {
  return int(std::upper_bound(starts.begin(), starts.end(), i) - starts.begin()) - 1;
}

/// One body read in slabs by readExodusBodyInRange(), in the steps of
/// read(); each step agrees on its errors over the ranks before the next
/// collective, and every check is ExodusBodyHeader's.
class ExodusBodyRangeReader {
 public:
  ExodusBodyRangeReader(Mesh& part, const std::string& bodyName, CellType type, const std::string& path,
                        const ElementRange& range, MPI_Comm comm)
      : part_(part), bodyName_(bodyName), type_(type), path_(path), nen_(numCellNodes(type)), comm_(comm),
        rank_(commRank(comm)), ranks_(commSize(comm)) {
    firstNodeId_ = part.numGlobalNodes();
    firstElementId_ = part.numGlobalElements();
    elementStarts_ = contiguousRangeStarts(range.first, range.last, comm, "readExodusBodyInRange()");
    range_ = range;
  }

  int read(Teuchos::ParameterList& params, const std::string& baseDirectory) {
    runCollectively<InputError>(comm_, [&] {
      ex_ = openExodusBodyFile(params, bodyName_, path_, baseDirectory);
      h_ = std::make_unique<ExodusBodyHeader>(*ex_, bodyName_, type_, path_,
                                              params.get<std::string>("Element Block"));
      const long long size = h_->blockSize();
      lo_ = int(std::clamp(range_.first - firstElementId_, 0LL, size));
      hi_ = int(std::clamp(range_.last - firstElementId_, (long long)lo_, size));
      // What this rank allocates: its elements, and coordinates for at most
      // its share of the file's nodes (ExodusBodyReader's budget check).
      part_.requireRoom(double(h_->fileNodes()) / ranks_, hi_ - lo_, nen_, path_);
      h_->checkBlock();
    });
    for (int r = 0; r <= ranks_; ++r) nodeStarts_.push_back(evenShareStart(h_->fileNodes(), r, ranks_));
    readConnectivity();
    numberNodes();
    addNodesAndElements();
    readSets();
    return body_;
  }

 private:
  /// This rank's elements' connectivity, each entry a node of the file.
  void readConnectivity() {
    conn_.assign(size_t(hi_ - lo_) * nen_, 0);
    runCollectively<InputError>(comm_, [&] {
      if (hi_ > lo_)
        ex_->check(ex_get_partial_conn(ex_->id(), EX_ELEM_BLOCK, h_->blockId(), lo_ + 1, hi_ - lo_, conn_.data(),
                                       nullptr, nullptr),
                   "the connectivity of " + h_->blockLabel());
      for (int n : conn_) h_->requireFileNode(n);
    });
    for (int n : conn_) nodes_.push_back(n - 1);
    std::sort(nodes_.begin(), nodes_.end());
    nodes_.erase(std::unique(nodes_.begin(), nodes_.end()), nodes_.end());
    runCollectively<InputError>(comm_, [&] { part_.requireRoom(double(nodes_.size()), hi_ - lo_, nen_, path_); });
  }

  /// Each of this rank's nodes numbered in the body and placed, through the
  /// nodes' owners (see the top of this file).
  void numberNodes() {
    std::vector<std::vector<NodeRequest>> ask(ranks_);
    for (int n : nodes_) ask[rangeRank(nodeStarts_, n)].push_back({n, rank_});
    requests_ = exchangeRecords(comm_, ask);
    std::sort(requests_.begin(), requests_.end(), [](const NodeRequest& a, const NodeRequest& b) {
      return a.node != b.node ? a.node < b.node : a.rank < b.rank;
    });
    for (const NodeRequest& q : requests_)
      if (used_.empty() || used_.back() != q.node) used_.push_back(q.node);
    long long count = (long long)used_.size(), before = 0;
    MPI_Exscan(&count, &before, 1, MPI_LONG_LONG, MPI_SUM, comm_);
    if (rank_ == 0) before = 0;
    MPI_Allreduce(&count, &bodyNodes_, 1, MPI_LONG_LONG, MPI_SUM, comm_);
    // The owner's coordinates, from the first to the last node it was asked for.
    const int first = used_.empty() ? 0 : used_.front(), span = used_.empty() ? 0 : used_.back() - first + 1;
    std::vector<double> x(span), y(span), z(span, 0.0);
    runCollectively<InputError>(comm_, [&] {
      if (span > 0)
        ex_->check(ex_get_partial_coord(ex_->id(), first + 1, span, x.data(), y.data(),
                                        h_->fileDim() == 3 ? z.data() : nullptr),
                   "the coordinates");
      for (int n : used_) h_->requireAdmissibleNode(n, {x[n - first], y[n - first], z[n - first]});
    });
    std::vector<std::vector<NodeAnswer>> answer(ranks_);
    for (const NodeRequest& q : requests_) {
      const int i = q.node - first;
      const long long bodyNode = before + (std::lower_bound(used_.begin(), used_.end(), q.node) - used_.begin());
      answer[q.rank].push_back({bodyNode, q.node, {x[i], y[i], z[i]}});
    }
    answers_ = exchangeRecords(comm_, answer);
    std::sort(answers_.begin(), answers_.end(),
              [](const NodeAnswer& a, const NodeAnswer& b) { return a.node < b.node; });
  }

  /// The body in the part: its nodes in file order, its elements in the
  /// block's order with their ids, each valid.
  void addNodesAndElements() {
    body_ = part_.beginBody(bodyName_, type_);
    firstPartNode_ = part_.numNodes();
    const bool is3d = cellDimension(type_) == 3;
    for (const NodeAnswer& a : answers_)
      part_.addPartNode(firstNodeId_ + a.bodyNode, a.x[0], a.x[1], is3d ? a.x[2] : 0.0);
    firstPartElement_ = part_.numElements();
    const auto& order = exodusNodeOrder(type_);
    const ReferenceCell& ref = referenceCell(type_);
    runCollectively<InputError>(comm_, [&] {
      for (int e = lo_; e < hi_; ++e) {
        int nodes[27];
        for (int i = 0; i < nen_; ++i) nodes[order[i]] = partNode(conn_[size_t(e - lo_) * nen_ + i] - 1);
        std::array<std::array<double, 3>, 8> corners;
        for (int i = 0; i < ref.numCorners; ++i) corners[i] = part_.coord(nodes[i]);
        h_->requireValidElement(e, corners);
        part_.addPartElement(firstElementId_ + e, nodes);
      }
    });
    part_.growWhole(bodyNodes_, h_->blockSize());
  }

  /// The part's index of file node n (one of this rank's nodes).
  int partNode(int n) const {
    return firstPartNode_ + int(std::lower_bound(nodes_.begin(), nodes_.end(), n) - nodes_.begin());
  }

  /// The node and side sets: the file's, restricted to the body, on the
  /// ranks that hold their nodes and elements; a set the whole body has is
  /// named on every rank (Mesh::part()).
  void readSets() {
    const auto nodeKind = ExodusFile::Objects::NodeSets, sideKind = ExodusFile::Objects::SideSets;
    std::vector<int> nsIds, ssIds;
    std::vector<std::string> nsNames, ssNames;
    runCollectively<InputError>(comm_, [&] {
      nsIds = ex_->ids(nodeKind, "the node set ids");
      nsNames = ex_->names(nodeKind, int(nsIds.size()), "the node set names");
      ssIds = ex_->ids(sideKind, "the side set ids");
      ssNames = ex_->names(sideKind, int(ssIds.size()), "the side set names");
    });
    const int ns = int(nsIds.size()), ss = int(ssIds.size());
    std::vector<std::string> names;
    for (int s = 0; s < ns; ++s) names.push_back(ExodusBodyHeader::setName(nodeKind, nsNames[s], nsIds[s]));
    for (int s = 0; s < ss; ++s) names.push_back(ExodusBodyHeader::setName(sideKind, ssNames[s], ssIds[s]));
    std::vector<std::vector<SetMember>> toOwner(ranks_);
    for (int s = 0; s < ns; ++s) readNodeSet(nsIds[s], s, names[s], toOwner);
    std::vector<std::vector<SideRecord>> toHolder(ranks_);
    for (int s = 0; s < ss; ++s) readSideSet(ssIds[s], s, names[ns + s], toHolder);
    // The sides to the ranks of their elements; their nodes to the nodes' owners.
    std::vector<std::vector<Segment>> segments(ss);
    std::vector<int> exists(ns + ss, 0);
    for (const SideRecord& r : exchangeRecords(comm_, toHolder)) {
      exists[ns + r.set] = 1;
      segments[r.set].push_back(part_.makeSegment(firstPartElement_ + r.element - lo_, r.facet));
      const Segment& seg = segments[r.set].back();
      for (int i = 0; i < seg.numNodes; ++i)
        toOwner[rangeRank(nodeStarts_, nodes_[seg.nodes[i] - firstPartNode_])].push_back(
            {ns + r.set, nodes_[seg.nodes[i] - firstPartNode_]});
    }
    // The owners send each membership of a node of the body to the ranks that hold it.
    std::vector<std::vector<SetMember>> toHolders(ranks_);
    for (const SetMember& m : exchangeRecords(comm_, toOwner)) {
      auto [from, to] = std::equal_range(requests_.begin(), requests_.end(), NodeRequest{m.node, 0},
                                         [](const NodeRequest& a, const NodeRequest& b) { return a.node < b.node; });
      if (from != to) exists[m.set] = 1;
      for (auto q = from; q != to; ++q) toHolders[q->rank].push_back(m);
    }
    std::vector<std::vector<int>> members(ns + ss);
    for (const SetMember& m : exchangeRecords(comm_, toHolders)) members[m.set].push_back(partNode(m.node));
    MPI_Allreduce(MPI_IN_PLACE, exists.data(), ns + ss, MPI_INT, MPI_MAX, comm_);
    for (int s = 0; s < ns; ++s)
      if (exists[s]) part_.addNodeSet(body_, names[s], std::move(members[s]));
    for (int s = 0; s < ss; ++s) {
      if (!exists[ns + s]) continue;
      // As Mesh::migrated() orders them: by element and side.
      std::stable_sort(segments[s].begin(), segments[s].end(), [](const Segment& a, const Segment& b) {
        return a.element != b.element ? a.element < b.element : a.localSide < b.localSide;
      });
      part_.addSideSet(body_, names[ns + s], std::move(segments[s]));
      part_.addNodeSet(body_, names[ns + s], std::move(members[ns + s]));
    }
  }

  /// This rank's share of node set `id`'s entries, checked, each to its owner.
  void readNodeSet(int id, int s, const std::string& name, std::vector<std::vector<SetMember>>& toOwner) {
    std::vector<int> entries;
    runCollectively<InputError>(comm_, [&] {
      int n = 0, ndf = 0;
      ex_->check(ex_get_set_param(ex_->id(), EX_NODE_SET, id, &n, &ndf), "node set '" + name + "'");
      const auto [a, b] = evenShare(n, comm_);
      entries.resize(size_t(b - a));
      if (b > a)
        ex_->check(ex_get_partial_node_set(ex_->id(), id, a + 1, b - a, entries.data()), "node set '" + name + "'");
      for (int v : entries) h_->requireSetNode(name, v);
    });
    for (int v : entries) toOwner[rangeRank(nodeStarts_, v - 1)].push_back({s, v - 1});
  }

  /// This rank's share of side set `id`'s entries, checked; each side of
  /// the block to the rank that holds its element.
  void readSideSet(int id, int s, const std::string& name, std::vector<std::vector<SideRecord>>& toHolder) {
    runCollectively<InputError>(comm_, [&] {
      int n = 0, ndf = 0;
      ex_->check(ex_get_set_param(ex_->id(), EX_SIDE_SET, id, &n, &ndf), "side set '" + name + "'");
      const auto [a, b] = evenShare(n, comm_);
      std::vector<int> elems(size_t(b - a)), sides(size_t(b - a));
      if (b > a)
        ex_->check(ex_get_partial_side_set(ex_->id(), id, a + 1, b - a, elems.data(), sides.data()),
                   "side set '" + name + "'");
      for (size_t k = 0; k < elems.size(); ++k) {
        const int f = h_->sideSetFacet(name, elems[k], sides[k]);
        if (f < 0) continue;
        const int e = elems[k] - 1 - h_->firstFileElement();
        toHolder[rangeRank(elementStarts_, firstElementId_ + e)].push_back({s, e, f});
      }
    });
  }

  Mesh& part_;
  const std::string& bodyName_;
  const CellType type_;
  const std::string& path_;
  const int nen_;
  const MPI_Comm comm_;
  const int rank_, ranks_;
  ElementRange range_;
  long long firstNodeId_ = 0, firstElementId_ = 0;  ///< the body's first ids in the whole mesh
  std::vector<long long> elementStarts_;  ///< the ranks' ranges of whole-mesh element ids, and the end
  std::vector<long long> nodeStarts_;     ///< the owners' ranges of file nodes, and the end
  std::unique_ptr<ExodusFile> ex_;
  std::unique_ptr<ExodusBodyHeader> h_;
  int lo_ = 0, hi_ = 0;  ///< this rank's elements of the block
  std::vector<int> conn_;                ///< their connectivity (file numbers, 1-based)
  std::vector<int> nodes_;               ///< their file nodes (0-based, ascending)
  std::vector<NodeRequest> requests_;    ///< as owner: who holds which of its nodes (by node, rank)
  std::vector<int> used_;                ///< as owner: its nodes the block uses (ascending)
  std::vector<NodeAnswer> answers_;      ///< this rank's nodes, by file node
  long long bodyNodes_ = 0;              ///< the whole body's nodes
  int body_ = -1, firstPartNode_ = 0, firstPartElement_ = 0;
};

}  // namespace

long long exodusBodyElementCount(Teuchos::ParameterList& params, const std::string& bodyName, CellType type,
                                 const std::string& path, const std::string& baseDirectory) {
  const auto ex = openExodusBodyFile(params, bodyName, path, baseDirectory);
  return ExodusBodyHeader(*ex, bodyName, type, path, params.get<std::string>("Element Block")).blockSize();
}

int readExodusBodyInRange(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                          const std::string& path, const std::string& baseDirectory, const ElementRange& range,
                          MPI_Comm comm) {
  DDC_CHECK(part.isPart(), "readExodusBodyInRange() into a whole mesh");
  return ExodusBodyRangeReader(part, bodyName, type, path, range, comm).read(params, baseDirectory);
}

}  // namespace ddc
