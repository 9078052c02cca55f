// The model's sparsity patterns (Model::buildTopology): the owned graph, the
// overlap map and the ghost graph (the overlap rows other ranks own).
//
// The columns of a node's DOF rows are the DOFs of the nodes it shares an
// element with, the same for each of its dim() rows; the patterns are built
// from those node neighbours, in compressed rows, and expanded one row at a
// time into the graph. A rank reads only its own elements: the neighbours
// other ranks' elements give the nodes it owns are sent by those ranks
// (Model::localNodes()). Collecting the element DOF lists per DOF row instead
// (each row receiving every element's whole list, then sorted and made
// unique) held about 1.5 kB per owned DOF in 3-D at once, 18 times the node
// neighbours: about 0.7 GB per rank on block_3d at 3.9M DOFs on 8 ranks, the
// run's set-up peak (doc/performance.md, "Memory at set-up").
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <map>
#include <memory>
#include <numeric>
#include <utility>

#include "DDC_Error.hpp"
#include "DDC_Model.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {

/// A node (its id in the whole mesh) and the first DOF of a node it shares
/// an element with: what a rank's elements give a node another rank owns.
/// The DOF, not the node, so that the owner need not hold the neighbour.
struct NodePair {
  Mesh::GlobalId node;
  GO neighbour;
  bool operator<(const NodePair& o) const { return node < o.node || (node == o.node && neighbour < o.neighbour); }
  bool operator==(const NodePair& o) const { return node == o.node && neighbour == o.neighbour; }
};

/// For each of `numRows` nodes (node n's row is row[n], -1: none), the first
/// DOFs (`firstDof`) of the nodes it shares one of `elements` with, itself
/// included, and those `extra` gives it (by row), sorted and unique.
struct NodeNeighbours {
  std::vector<size_t> offset;  ///< numRows + 1
  std::vector<GO> dofs;

  template <class FirstDof>
  NodeNeighbours(const Mesh& mesh, const std::vector<int>& elements, const std::vector<int>& row, int numRows,
                 const std::vector<std::pair<int, GO>>& extra, const FirstDof& firstDof)
      : offset(size_t(numRows) + 1, 0) {
    for (int e : elements) {
      const int nn = mesh.elementNumNodes(e);
      const int* en = mesh.elementNodes(e);
      for (int i = 0; i < nn; ++i)
        if (row[en[i]] >= 0) offset[row[en[i]] + 1] += nn;
    }
    for (const auto& p : extra) ++offset[p.first + 1];
    std::partial_sum(offset.begin(), offset.end(), offset.begin());
    dofs.resize(offset.back());
    std::vector<size_t> next(offset.begin(), offset.end() - 1);
    for (int e : elements) {
      const int nn = mesh.elementNumNodes(e);
      const int* en = mesh.elementNodes(e);
      for (int i = 0; i < nn; ++i) {
        if (row[en[i]] < 0) continue;
        for (int j = 0; j < nn; ++j) dofs[next[row[en[i]]]++] = firstDof(en[j]);
      }
    }
    for (const auto& p : extra) dofs[next[p.first]++] = p.second;
    // Sort and make each row unique, compacting the rows as they shrink.
    size_t out = 0, begin = 0;
    for (int r = 0; r < numRows; ++r) {
      const size_t end = offset[r + 1];
      std::sort(dofs.begin() + begin, dofs.begin() + end);
      const size_t count = std::unique(dofs.begin() + begin, dofs.begin() + end) - (dofs.begin() + begin);
      if (out != begin) std::copy(dofs.begin() + begin, dofs.begin() + begin + count, dofs.begin() + out);
      offset[r] = out;
      out += count;
      begin = end;
    }
    offset[numRows] = out;
    dofs.resize(out);
  }
  const GO* begin(int r) const { return dofs.data() + offset[r]; }
  const GO* end(int r) const { return dofs.data() + offset[r + 1]; }
};

/// The columns rows get from contact slots, by row (surface rows only).
/// Index: global ids (owned graph) or the overlap map's local ids (overlap
/// graph).
template <class Index>
using ExtraColumns = std::map<Index, std::vector<Index>>;

/// Each index of `dofs` couples with all of them (a contact slot's DOFs);
/// kept for the rows `keep(r)` accepts (those of the graph being built).
template <class Index, class Keep>
void addCoupled(const std::vector<Index>& dofs, ExtraColumns<Index>& extra, const Keep& keep) {
  for (Index r : dofs)
    if (keep(r)) extra[r].insert(extra[r].end(), dofs.begin(), dofs.end());
}

/// A fill-complete graph on `rows` and `cols` whose row r holds the local
/// column indices `columns(r, v)` puts in v, sorted and unique. It is
/// handed to Tpetra in compressed rows (inserting rows one index at a time
/// checks each index against the row so far: 40 % of building the model
/// on 1.4M DOFs). `columns` is called twice per row, to count and to fill,
/// so that no more than one row's columns exist besides the graph's arrays.
template <class Columns>
Teuchos::RCP<CrsGraph> compressedRowGraph(const Teuchos::RCP<const Map>& rows, const Teuchos::RCP<const Map>& cols,
                                          const Teuchos::RCP<const Map>& domainRange, const Columns& columns) {
  using LocalGraph = CrsGraph::local_graph_device_type;
  const size_t numRows = rows->getNodeNumElements();
  typename LocalGraph::row_map_type::non_const_type offset("DDContact::Model::GraphOffsets", numRows + 1);
  std::vector<LO> v;
  for (size_t r = 0; r < numRows; ++r) {
    columns(r, v);
    offset(r + 1) = offset(r) + v.size();
  }
  typename LocalGraph::entries_type::non_const_type indices("DDContact::Model::GraphIndices", offset(numRows));
  for (size_t r = 0; r < numRows; ++r) {
    columns(r, v);
    std::copy(v.begin(), v.end(), indices.data() + offset(r));
  }
  auto graph = Teuchos::rcp(new CrsGraph(rows, cols, offset, indices));
  graph->expertStaticFillComplete(domainRange, domainRange);
  return graph;
}

template <class Index>
void sortUnique(std::vector<Index>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

/// The nodes of this rank's elements (row[n] >= 0, in node order) and their
/// neighbours: for a node of another rank, those of this rank's elements;
/// for an owned node, also those of the other ranks' elements that touch
/// it, which those ranks send (so no rank reads another's elements).
struct Model::LocalNodes {
  std::vector<int> row;
  int numRows = 0;
  NodeNeighbours neighbours;
};

std::unique_ptr<Model::LocalNodes> Model::localNodes() const {
  const Mesh& mesh = *mesh_;
  const int me = comm_->getRank();
  std::vector<int> row(mesh.numNodes(), -1);
  for (int e : localElements_)
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) row[mesh.elementNodes(e)[i]] = 0;
  int numRows = 0;
  for (int n = 0; n < mesh.numNodes(); ++n)
    if (row[n] >= 0) row[n] = numRows++;
  // What this rank's elements give the nodes other ranks own, to the owners.
  std::vector<std::vector<NodePair>> send(comm_->getSize());
  for (int e : localElements_) {
    const int nn = mesh.elementNumNodes(e);
    const int* en = mesh.elementNodes(e);
    for (int i = 0; i < nn; ++i)
      if (nodeOwner_[en[i]] != me)
        for (int j = 0; j < nn; ++j) send[nodeOwner_[en[i]]].push_back({mesh.nodeId(en[i]), dof(en[j], 0)});
  }
  for (auto& v : send) sortUnique(v);
  const std::vector<NodePair> received = exchangeRecords(rawComm(*comm_), send);
  std::vector<std::vector<NodePair>>().swap(send);
  std::vector<std::pair<int, GO>> extra(received.size());
  for (size_t i = 0; i < received.size(); ++i) {
    const int n = mesh.localNode(received[i].node);
    DDC_CHECK(n >= 0 && nodeOwner_[n] == me && row[n] >= 0,
              "node " << received[i].node << " received as owned by rank " << me << ", which has no element of it");
    extra[i] = {row[n], received[i].neighbour};
  }
  NodeNeighbours neighbours(mesh, localElements_, row, numRows, extra, [this](int n) { return dof(n, 0); });
  return std::unique_ptr<LocalNodes>(new LocalNodes{std::move(row), numRows, std::move(neighbours)});
}

void Model::buildTopology() {
  const std::unique_ptr<LocalNodes> local = localNodes();
  buildOwnedGraph(*local);
  buildGhostGraph(*local);
  ++topologyVersion_;
}

void Model::buildOwnedGraph(const LocalNodes& local) {
  // Rows of owned DOFs with the columns of every element and contact slot
  // touching them: the elements' from the owned nodes' neighbours (other
  // ranks' elements included, localNodes()), the slots' from the slots
  // (all pairs are known on every rank).
  const int d = mesh_->dim();
  const GO first = ownedMap_->getMinGlobalIndex();
  const std::vector<int>& row = local.row;
  const NodeNeighbours& nb = local.neighbours;
  const size_t numOwned = ownedMap_->getNodeNumElements();
  const auto owned = [&](GO g) { return g >= first && g < first + GO(numOwned); };
  ExtraColumns<GO> extra;
  if (contact_)
    for (int k = 0; k < static_cast<int>(contact_->slots().size()); ++k)
      addCoupled(contact_->slotDofs(k), extra, owned);
  auto globalColumns = [&](size_t r, std::vector<GO>& cols) {
    cols.clear();
    const GO g = first + GO(r);
    const int n = overlapEntity_[r];
    if (n >= 0)
      for (const GO* m = nb.begin(row[n]); m != nb.end(row[n]); ++m)
        for (int c = 0; c < d; ++c) cols.push_back(*m + c);
    const auto it = extra.find(g);
    if (it != extra.end()) cols.insert(cols.end(), it->second.begin(), it->second.end());
  };
  // The column map as Tpetra's fillComplete makes it: the owned DOFs (each
  // row holds its own), then the others sorted by owning rank and id — by
  // id, as every rank owns one contiguous range in rank order. With one
  // rank it is the owned map itself.
  std::vector<GO> remote, cols;
  for (size_t r = 0; r < numOwned; ++r) {
    globalColumns(r, cols);
    for (GO g : cols)
      if (!owned(g)) remote.push_back(g);
    if (remote.size() > 4 * numOwned) sortUnique(remote);  // bounds the duplicates held
  }
  sortUnique(remote);
  Teuchos::RCP<const Map> colMap = ownedMap_;
  if (comm_->getSize() > 1) {
    std::vector<GO> gids(numOwned);
    std::iota(gids.begin(), gids.end(), first);
    gids.insert(gids.end(), remote.begin(), remote.end());
    colMap = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                  Teuchos::ArrayView<const GO>(gids), ownedMap_->getIndexBase(), comm_));
  }
  auto columns = [&](size_t r, std::vector<LO>& local) {
    globalColumns(r, cols);
    local.clear();
    for (GO g : cols)
      local.push_back(owned(g) ? LO(g - first)
                               : LO(numOwned + (std::lower_bound(remote.begin(), remote.end(), g) - remote.begin())));
    sortUnique(local);
  };
  ownedGraph_ = compressedRowGraph(ownedMap_, colMap, ownedMap_, columns);
}

void Model::buildGhostGraph(const LocalNodes& local) {
  // The overlap map: owned DOFs first, then the ghosts of local elements and
  // slots (so an owned DOF has the same LID in the overlap map, the owned
  // map and the owned graph's column map).
  const Mesh& mesh = *mesh_;
  const int d = mesh.dim(), me = comm_->getRank();
  const GO first = ownedMap_->getMinGlobalIndex();
  const size_t numOwned = ownedMap_->getNodeNumElements();
  const std::vector<int>& row = local.row;
  const int numLocalNodes = local.numRows;
  std::vector<GO> ghosts;
  auto addGhosts = [&](const std::vector<GO>& dofs) {
    for (GO g : dofs)
      if (g < first || g >= first + static_cast<GO>(numOwned)) ghosts.push_back(g);
  };
  for (int n = 0; n < mesh.numNodes(); ++n)
    if (row[n] >= 0 && nodeOwner_[n] != me)
      for (int c = 0; c < d; ++c) ghosts.push_back(dof(n, c));
  // The DOFs each local contact slot couples (global ids).
  std::vector<std::vector<GO>> slotLists;
  if (contact_) {
    for (int k : contact_->ownedSlots())
      slotLists.push_back(decomposed_ && contact_->slots()[k].paired() ? contact_->slaveSideDofs(k)
                                                                        : contact_->slotDofs(k));
    for (int k : contact_->localMasterSlots()) slotLists.push_back(contact_->masterSideDofs(k));
  }
  for (const auto& list : slotLists) addGhosts(list);
  sortUnique(ghosts);
  std::vector<GO> gids(numOwned);
  std::iota(gids.begin(), gids.end(), first);
  gids.insert(gids.end(), ghosts.begin(), ghosts.end());
  std::vector<GO>().swap(ghosts);
  overlapMap_ = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                     Teuchos::ArrayView<const GO>(gids), 0, comm_));
  importer_ = Teuchos::rcp(new Tpetra::Import<LO, GO, Node>(ownedMap_, overlapMap_));
  exporter_ = Teuchos::rcp(new Tpetra::Export<LO, GO, Node>(overlapMap_, ownedMap_));

  // The ghost graph: rows of the overlap map past the owned DOFs (the
  // ghosts), with the entries local elements and slots give them; columns
  // indexed by the overlap map, so element DOF lists are its column indices.
  // Owned rows are assembled into the tangent itself (ownedColumn_), so no
  // rank keeps a second copy of its rows of the matrix.
  // A ghost row holds only what this rank's elements give it: the
  // neighbours the owners received are in their rows, not here.
  const NodeNeighbours& nb = local.neighbours;
  ExtraColumns<LO> extra;
  for (const auto& list : slotLists) {
    std::vector<LO> l(list.size());
    for (size_t i = 0; i < list.size(); ++i) l[i] = overlapMap_->getLocalElement(list[i]);
    addCoupled(l, extra, [&](LO r) { return r >= LO(numOwned); });
  }
  std::vector<std::vector<GO>>().swap(slotLists);
  // A local node's d DOFs are consecutive in the overlap map.
  std::vector<LO> nodeLid(numLocalNodes);
  for (int n = 0; n < mesh.numNodes(); ++n)
    if (row[n] >= 0) nodeLid[row[n]] = overlapMap_->getLocalElement(dof(n, 0));
  setGhostEntities(gids, row, nodeLid);
  auto columns = [&](size_t ghost, std::vector<LO>& cols) {
    const size_t r = numOwned + ghost;
    cols.clear();
    const int n = overlapEntity_[r];
    if (n >= 0 && n < mesh.numNodes() && row[n] >= 0)
      for (const GO* m = nb.begin(row[n]); m != nb.end(row[n]); ++m) {
        const LO first = overlapMap_->getLocalElement(*m);
        for (int c = 0; c < d; ++c) cols.push_back(first + c);
      }
    const auto it = extra.find(LO(r));
    if (it != extra.end()) cols.insert(cols.end(), it->second.begin(), it->second.end());
    sortUnique(cols);
  };
  ghostRowMap_ = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                      Teuchos::ArrayView<const GO>(gids.data() + numOwned, gids.size() - numOwned),
                                      0, comm_));
  ghostGraph_ = compressedRowGraph(ghostRowMap_, overlapMap_, ownedMap_, columns);
  ghostExporter_ = Teuchos::rcp(new Tpetra::Export<LO, GO, Node>(ghostRowMap_, ownedMap_));
  // Overlap LID -> the owned graph's column LID (owned DOFs keep theirs).
  const Map& colMap = *ownedGraph_->getColMap();
  ownedColumn_.resize(gids.size());
  for (size_t l = 0; l < gids.size(); ++l) ownedColumn_[l] = l < numOwned ? LO(l) : colMap.getLocalElement(gids[l]);
}

void Model::setGhostEntities(const std::vector<GO>& gids, const std::vector<int>& row,
                             const std::vector<LO>& nodeLid) {
  // The ghosts of local nodes from the nodes; those of contact slots (nodes
  // of other ranks' elements, multipliers of slots other ranks own) by a
  // search over the contact surfaces' nodes and the slots.
  const int d = mesh_->dim();
  const size_t numOwned = ownedMap_->getNodeNumElements();
  overlapEntity_.resize(numOwned);
  overlapEntity_.resize(gids.size(), kUnresolvedEntity);
  for (int n = 0; n < mesh_->numNodes(); ++n) {
    if (row[n] < 0 || nodeOwner_[n] == comm_->getRank()) continue;
    for (int c = 0; c < d; ++c) overlapEntity_[static_cast<size_t>(nodeLid[row[n]]) + c] = n;
  }
  std::vector<std::pair<GO, size_t>> unresolved;
  for (size_t l = numOwned; l < gids.size(); ++l)
    if (overlapEntity_[l] == kUnresolvedEntity) unresolved.emplace_back(gids[l], l);
  if (unresolved.empty()) return;
  std::sort(unresolved.begin(), unresolved.end());
  auto resolve = [&](GO g, int entity) {
    const auto it = std::lower_bound(unresolved.begin(), unresolved.end(), std::make_pair(g, size_t(0)));
    if (it == unresolved.end() || it->first != g) return false;
    overlapEntity_[it->second] = entity;
    return true;
  };
  DDC_CHECK(contact_, "overlap DOFs that are not local nodes' without contact");
  // A surface node the part of the mesh lacks becomes a remote entity.
  remoteSurfaceNodes_.clear();
  for (int id : contact_->surfaceNodes()) {
    const int n = meshNodeOfContactNode(id);
    const int entity = n >= 0 ? n : mesh_->numNodes() + int(remoteSurfaceNodes_.size());
    bool reached = false;
    for (int c = 0; c < d; ++c) reached = resolve(contact_->surfaceNodeDof(id, c), entity) || reached;
    if (reached && n < 0) remoteSurfaceNodes_.push_back(id);
  }
  for (size_t k = 0; k < lmDof_.size(); ++k)
    for (int c = 0; c < contact_->numMultipliers(static_cast<int>(k)); ++c)
      resolve(lmDof_[k] + c, -1 - static_cast<int>(k));
  for (size_t l = numOwned; l < gids.size(); ++l)
    if (overlapEntity_[l] == kUnresolvedEntity)
      throw std::logic_error("Model: overlap DOF " + std::to_string(gids[l]) + " is neither a node's nor a multiplier's");
}

}  // namespace ddc
