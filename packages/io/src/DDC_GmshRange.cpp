// readGmshBodyInRange(): a Gmsh body read in ranges (DDC_Gmsh.hpp, "In
// ranges"), with the whole reader's numbering and messages. No rank holds
// the body's nodes or elements whole.
//
// Every rank reads the file as it streams by and keeps the body's elements
// of its range, the coordinates of the node tags it owns (even shares of
// the tags the $Nodes header announces), and the boundary-sized rest. The
// body's nodes are the tags its elements use, in increasing order: each rank
// asks the owners of its elements' tags, an owner numbers the tags it was
// asked for after those of the ranks before it (one exclusive scan) and
// answers with the number and the coordinates. Whether a tag is the body's
// is the owner's to say; whether a side set's face is one element's, the
// ranks count together; set memberships reach every rank that holds the
// node. Each check is GmshBody's, so a fault reads as the whole reader's.
#include <mpi.h>

#include <algorithm>
#include <array>
#include <climits>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_Gmsh.hpp"
#include "DDC_GmshFile.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {

using gmsh::ElementBlock;
using gmsh::MshData;

/// A rank that holds node `tag`, to the tag's owner.
struct NodeRequest {
  long long tag;
  int rank;
};
/// The owner's answer: the node's number in the body and its coordinates.
struct NodeAnswer {
  long long bodyNode, tag;
  double x[3];
};
/// Node `tag` is in node set `set` (an index into a list every rank has).
struct SetMember {
  long long tag;
  int set;
};

/// The first fault of the file over the ranks (the smallest line: a node
/// tag given twice is seen by its owner only), thrown on every rank.
void raiseFirstFault(MPI_Comm comm, const MshData& d) {
  struct {
    int line, rank;
  } mine{d.faultLine == 0 ? INT_MAX : d.faultLine, commRank(comm)}, first{};
  MPI_Allreduce(&mine, &first, 1, MPI_2INT, MPI_MINLOC, comm);
  if (first.line == INT_MAX) return;
  raiseCollectively<InputError>(comm, commRank(comm) == first.rank ? d.fault : std::string());
}

/// What this rank keeps of the file, every fault agreed on.
MshData parseInRanges(const std::string& fileName, const gmsh::MshKeep& keep, MPI_Comm comm) {
  MshData d;
  runCollectively<InputError>(comm, [&] { d = gmsh::parseMsh(fileName, &keep); });
  raiseFirstFault(comm, d);
  return d;
}

/// What keeps a rank from selecting the body's blocks while it reads.
void requireGroupsBeforeElements(const MshData& d, const std::string& fileName, const std::string& group) {
  DDC_INPUT_REQUIRE(group.empty() || !d.groupsAfterElements,
                    "Gmsh file '" << fileName << "': $PhysicalNames or $Entities comes after $Elements; a body "
                                  << "selected by a physical group ('" << group << "') is read in ranges only "
                                  << "from a file that names its groups first, as Gmsh writes it (or set "
                                  << "Partition/Mesh On Every Rank = true)");
}

/// One body read in ranges by readGmshFileInRange(), in the steps of
/// read(); each step agrees on its faults over the ranks before the next
/// collective.
class GmshBodyRangeReader : public gmsh::GmshBody {
 public:
  GmshBodyRangeReader(const MshData& d, const std::string& fileName, const std::string& bodyName, CellType type,
                      const std::string& group, Mesh& part, const ElementRange& range, MPI_Comm comm)
      : GmshBody(d, fileName, bodyName, type, group), part_(part), range_(range), comm_(comm),
        rank_(commRank(comm)), ranks_(commSize(comm)) {
    firstNodeId_ = part.numGlobalNodes();
    firstElementId_ = part.numGlobalElements();
    contiguousRangeStarts(range.first, range.last, comm, "readGmshFileInRange()");
  }

  int read() {
    runCollectively<InputError>(comm_, [&] {
      selectBodyGroup();
      collectBodyBlocks();
      requireGroupsBeforeElements(d_, fileName_, physicalGroup_);
    });
    numberNodes();
    addNodesAndElements();
    readSides();
    readNodeSets();
    commitSets();
    return body_;
  }

 private:
  /// 3. Each of this rank's nodes numbered in the body and placed, through
  /// the tags' owners.
  void numberNodes() {
    for (const auto* b : bodyBlocks_) nodes_.insert(nodes_.end(), b->nodes.begin(), b->nodes.end());
    std::sort(nodes_.begin(), nodes_.end());
    nodes_.erase(std::unique(nodes_.begin(), nodes_.end()), nodes_.end());
    std::vector<std::vector<NodeRequest>> ask(ranks_);
    for (long long t : nodes_) ask[gmsh::nodeOwner(d_, t, ranks_)].push_back({t, rank_});
    requests_ = exchangeRecords(comm_, ask);
    std::sort(requests_.begin(), requests_.end(), [](const NodeRequest& a, const NodeRequest& b) {
      return a.tag != b.tag ? a.tag < b.tag : a.rank < b.rank;
    });
    for (const NodeRequest& q : requests_)
      if (used_.empty() || used_.back() != q.tag) used_.push_back(q.tag);
    // The owners' tags in order: the first fault is the lowest rank's.
    runCollectively<InputError>(comm_, [&] {
      for (long long t : used_) {
        const auto it = d_.nodes.find(t);
        requireNode(t, it == d_.nodes.end() ? nullptr : &it->second);
      }
    });
    long long count = (long long)used_.size(), before = 0;
    MPI_Exscan(&count, &before, 1, MPI_LONG_LONG, MPI_SUM, comm_);
    if (rank_ == 0) before = 0;
    MPI_Allreduce(&count, &bodyNodes_, 1, MPI_LONG_LONG, MPI_SUM, comm_);
    std::vector<std::vector<NodeAnswer>> answer(ranks_);
    for (const NodeRequest& q : requests_) {
      const auto& p = d_.nodes.at(q.tag);
      const long long bodyNode = before + (std::lower_bound(used_.begin(), used_.end(), q.tag) - used_.begin());
      answer[q.rank].push_back({bodyNode, q.tag, {p[0], p[1], solid_ ? p[2] : 0.0}});
    }
    std::vector<NodeAnswer> answers = exchangeRecords(comm_, answer);
    std::sort(answers.begin(), answers.end(), [](const NodeAnswer& a, const NodeAnswer& b) { return a.tag < b.tag; });
    for (const NodeAnswer& a : answers) {
      bodyNode_.push_back(a.bodyNode);
      xyz_.push_back({a.x[0], a.x[1], a.x[2]});
    }
  }

  /// This rank's index of node `tag` (one of its nodes_), or -1.
  int localNode(long long tag) const {
    const auto it = std::lower_bound(nodes_.begin(), nodes_.end(), tag);
    return it != nodes_.end() && *it == tag ? int(it - nodes_.begin()) : -1;
  }

  /// 4. The body in the part: its nodes in tag order, its elements in file
  /// order with their ids, each valid (3-D) or counter-clockwise (2-D).
  void addNodesAndElements() {
    double mine = 0.0;
    for (const auto* b : bodyBlocks_) mine += double(b->tags.size());
    runCollectively<InputError>(comm_, [&] { part_.requireRoom(double(nodes_.size()), mine, nen_, fileName_); });
    body_ = part_.beginBody(bodyName_, type_);
    firstPartNode_ = part_.numNodes();
    for (size_t k = 0; k < nodes_.size(); ++k)
      part_.addPartNode(firstNodeId_ + bodyNode_[k], xyz_[k][0], xyz_[k][1], xyz_[k][2]);
    firstPartElement_ = part_.numElements();
    const long long lo = std::clamp(range_.first - firstElementId_, 0LL, numElems_);
    runCollectively<InputError>(comm_, [&] {
      long long e = lo;
      for (const auto* b : bodyBlocks_)
        for (size_t k = 0; k < b->tags.size(); ++k, ++e) {
          int n[27];
          for (int i = 0; i < nen_; ++i) n[i] = localNode(b->nodes[k * nen_ + i]);
          if (solid_)
            checkVolumeElement(*b, k, n, xyz_);
          else
            orientQuadrangle(*b, k, n, xyz_);
          conn_.insert(conn_.end(), n, n + nen_);
          entity_.push_back(b->entity);
          int p[27];
          for (int i = 0; i < nen_; ++i) p[i] = firstPartNode_ + n[i];
          part_.addPartElement(firstElementId_ + e, p);
        }
    });
    part_.growWhole(bodyNodes_, numElems_);
  }

  /// Whether each of `tags` is a node of the body (its owner says).
  std::vector<int> usedOnAnyRank(const std::vector<long long>& tags) const {
    std::vector<int> used(tags.size(), 0);
    for (size_t i = 0; i < tags.size(); ++i)
      used[i] = gmsh::nodeOwner(d_, tags[i], ranks_) == rank_ &&
                std::binary_search(used_.begin(), used_.end(), tags[i]);
    MPI_Allreduce(MPI_IN_PLACE, used.data(), int(used.size()), MPI_INT, MPI_MAX, comm_);
    return used;
  }

  /// The side set blocks the walk of GmshBody::readSideSets() reads whole.
  bool walked(const ElementBlock& b) const {
    return b.dim == dim_ - 1 && !gmsh::physicalsOf(d_, dim_ - 1, b.entity).empty() && b.type == wantFacet_ &&
           b.countError.empty();
  }

  /// 5. and 6. The side sets: what the whole reader finds of each face in
  /// its facet index, found by all ranks together -- whether its nodes are
  /// the body's, how many elements have its corners, and, from the rank
  /// that holds the one element, whether its other nodes are that face's.
  void readSides() {
    struct Face {
      const ElementBlock* block;
      size_t element, firstTag;  ///< in the block; in `tags`
    };
    std::vector<Face> faces;
    std::map<const ElementBlock*, int> firstFace;
    std::vector<long long> tags;
    std::map<std::vector<long long>, std::vector<int>> byCorners;
    for (const auto& b : d_.blocks) {
      if (!walked(b)) continue;
      firstFace[&b] = int(faces.size());
      for (size_t l = 0; l < b.tags.size(); ++l) {
        const auto from = b.nodes.begin() + l * b.numNodes;
        std::vector<long long> key(from, from + facetCorners_);
        std::sort(key.begin(), key.end());
        byCorners[key].push_back(int(faces.size()));
        faces.push_back({&b, l, tags.size()});
        tags.insert(tags.end(), from, from + b.numNodes);
      }
    }
    const int facets = int(faces.size());
    const std::vector<int> used = usedOnAnyRank(tags);
    std::vector<int> inBody(facets, 1), matches(facets, 0), otherNodes(facets, 0);
    std::vector<std::pair<int, int>> here(facets, {-1, -1});
    for (int f = 0; f < facets; ++f)
      for (int i = 0; i < faces[f].block->numNodes; ++i)
        if (!used[faces[f].firstTag + i]) inBody[f] = 0;
    const int ne = int(entity_.size());
    for (int e = 0; e < ne; ++e)
      for (int j = 0; j < int(ref_.facets.size()); ++j) {
        const auto& fn = ref_.facets[j].nodes;
        std::vector<long long> key(facetCorners_);
        for (int i = 0; i < facetCorners_; ++i) key[i] = nodes_[conn_[size_t(e) * nen_ + fn[i]]];
        std::sort(key.begin(), key.end());
        const auto it = byCorners.find(key);
        if (it == byCorners.end()) continue;
        std::vector<long long> theirs;
        for (size_t i = facetCorners_; i < fn.size(); ++i) theirs.push_back(nodes_[conn_[size_t(e) * nen_ + fn[i]]]);
        std::sort(theirs.begin(), theirs.end());
        for (int f : it->second) {
          ++matches[f];
          here[f] = {e, j};
          const auto from = tags.begin() + faces[f].firstTag;
          std::vector<long long> mine(from + facetCorners_, from + faces[f].block->numNodes);
          std::sort(mine.begin(), mine.end());
          if (mine != theirs) otherNodes[f] = 1;
        }
      }
    MPI_Allreduce(MPI_IN_PLACE, matches.data(), facets, MPI_INT, MPI_SUM, comm_);
    MPI_Allreduce(MPI_IN_PLACE, otherNodes.data(), facets, MPI_INT, MPI_MAX, comm_);
    std::map<std::string, std::set<std::pair<int, int>>> seen;
    runCollectively<InputError>(comm_, [&] {
      readSideSets(
          [&](const ElementBlock& b, size_t l) {
            const int f = firstFace.at(&b) + int(l);
            SideFacet s;
            s.inBody = inBody[f] != 0;
            s.matches = matches[f];
            s.sameHigherOrder = otherNodes[f] == 0;
            std::tie(s.element, s.facet) = here[f];
            return s;
          },
          [&](const SideFacet& s, const std::vector<int>& phys, const ElementBlock& b, size_t l) {
            for (int pt : phys) {
              const std::string name = gmsh::physicalName(d_, dim_ - 1, pt);
              auto& segments = segments_[name];  // the set exists on every rank
              if (s.element >= 0 && seen[name].insert({s.element, s.facet}).second)
                segments.push_back(part_.makeSegment(firstPartElement_ + s.element, s.facet));
              addHeld(name, std::vector<long long>(b.nodes.begin() + l * b.numNodes,
                                                   b.nodes.begin() + (l + 1) * b.numNodes));
            }
          });
    });
  }

  /// Node set `name` has `tags`: those this rank holds.
  void addHeld(const std::string& name, const std::vector<long long>& tags) {
    auto& s = members_[name];  // the set exists on every rank
    for (long long t : tags) {
      const int n = localNode(t);
      if (n >= 0) s.push_back(firstPartNode_ + n);
    }
  }

  /// 7. Physical points, curves (3-D) and surfaces / volumes -> node sets.
  void readNodeSets() {
    std::vector<long long> candidates;
    for (const auto& [entity, tags] : d_.pointNodes) candidates.insert(candidates.end(), tags.begin(), tags.end());
    for (const auto& b : d_.blocks)
      if (b.dim == 0 || (solid_ && b.dim == 1)) candidates.insert(candidates.end(), b.nodes.begin(), b.nodes.end());
    const std::vector<int> flags = usedOnAnyRank(candidates);
    std::unordered_map<long long, bool> used;
    for (size_t i = 0; i < candidates.size(); ++i) used[candidates[i]] = flags[i] != 0;
    const auto isUsed = [&](long long t) { return used.at(t); };
    const auto add = [&](const std::string& name, const std::vector<long long>& tags) { addHeld(name, tags); };
    runCollectively<InputError>(comm_, [&] {
      readPointNodeSets(isUsed, add);
      if (solid_) readCurveNodeSets(isUsed, add);
    });
    readVolumeNodeSets();
  }

  /// The physical surfaces (2-D) / volumes (3-D) of the body's elements:
  /// each of this rank's memberships through the node's owner to every
  /// rank that holds the node.
  void readVolumeNodeSets() {
    std::vector<std::string> names;
    for (const auto* b : bodyBlocks_)
      if (b->count > 0)
        for (int pt : gmsh::physicalsOf(d_, dim_, b->entity)) names.push_back(gmsh::physicalName(d_, dim_, pt));
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    for (const auto& name : names) members_[name];  // the set exists on every rank
    std::set<std::pair<int, long long>> mine;
    for (size_t e = 0; e < entity_.size(); ++e)
      for (int pt : gmsh::physicalsOf(d_, dim_, entity_[e])) {
        const int set = int(std::lower_bound(names.begin(), names.end(), gmsh::physicalName(d_, dim_, pt)) -
                            names.begin());
        for (int i = 0; i < nen_; ++i) mine.insert({set, nodes_[conn_[e * nen_ + i]]});
      }
    std::vector<std::vector<SetMember>> toOwner(ranks_);
    for (const auto& [set, tag] : mine) toOwner[gmsh::nodeOwner(d_, tag, ranks_)].push_back({tag, set});
    std::vector<std::vector<SetMember>> toHolders(ranks_);
    for (const SetMember& m : exchangeRecords(comm_, toOwner)) {
      auto [from, to] = std::equal_range(requests_.begin(), requests_.end(), NodeRequest{m.tag, 0},
                                         [](const NodeRequest& a, const NodeRequest& b) { return a.tag < b.tag; });
      for (auto q = from; q != to; ++q) toHolders[q->rank].push_back(m);
    }
    for (const SetMember& m : exchangeRecords(comm_, toHolders)) addHeld(names[m.set], {m.tag});
  }

  /// 8. The sets into the part: side sets' segments as Mesh::migrated()
  /// orders them (by element and side), every node set with the nodes this
  /// rank holds; every set the whole body has, on every rank.
  void commitSets() {
    for (auto& [name, segments] : segments_) {
      std::stable_sort(segments.begin(), segments.end(), [](const Segment& a, const Segment& b) {
        return a.element != b.element ? a.element < b.element : a.localSide < b.localSide;
      });
      part_.addSideSet(body_, name, std::move(segments));
    }
    for (auto& [name, nodes] : members_) part_.addNodeSet(body_, name, std::move(nodes));
  }

  Mesh& part_;
  const ElementRange range_;
  const MPI_Comm comm_;
  const int rank_, ranks_;
  long long firstNodeId_ = 0, firstElementId_ = 0;  ///< the body's first ids in the whole mesh
  std::vector<long long> nodes_;          ///< this rank's elements' node tags (ascending)
  std::vector<long long> bodyNode_;       ///< their numbers in the body
  std::vector<std::array<double, 3>> xyz_;  ///< their coordinates
  std::vector<NodeRequest> requests_;     ///< as owner: who holds which of its tags (by tag, rank)
  std::vector<long long> used_;           ///< as owner: its tags the body uses (ascending)
  long long bodyNodes_ = 0;               ///< the whole body's nodes
  std::vector<int> conn_;                 ///< this rank's elements, indices into nodes_
  std::vector<int> entity_;               ///< and the entity of each
  int body_ = -1, firstPartNode_ = 0, firstPartElement_ = 0;
  std::map<std::string, std::vector<Segment>> segments_;  ///< side sets: the segments of this rank's elements
  std::map<std::string, std::vector<int>> members_;       ///< node sets: the nodes this rank holds
};

}  // namespace

long long gmshFileElementCount(const std::string& fileName, const std::string& bodyName, CellType type,
                               const std::string& physicalGroup, MPI_Comm comm) {
  const gmsh::MshKeep keep{cellDimension(type), physicalGroup, 0, 0, commRank(comm), commSize(comm)};
  const MshData d = parseInRanges(fileName, keep, comm);
  gmsh::GmshBody body(d, fileName, bodyName, type, physicalGroup);
  runCollectively<InputError>(comm, [&] {
    body.selectBodyGroup();
    body.collectBodyBlocks();
    requireGroupsBeforeElements(d, fileName, physicalGroup);
  });
  return body.numElements();
}

int readGmshFileInRange(Mesh& part, const std::string& bodyName, CellType type, const std::string& fileName,
                        const std::string& physicalGroup, const ElementRange& range, MPI_Comm comm) {
  DDC_CHECK(part.isPart(), "readGmshFileInRange() into a whole mesh");
  const long long first = part.numGlobalElements();
  const gmsh::MshKeep keep{cellDimension(type), physicalGroup, std::max(0LL, range.first - first),
                           std::max(0LL, range.last - first), commRank(comm), commSize(comm)};
  const MshData d = parseInRanges(fileName, keep, comm);
  return GmshBodyRangeReader(d, fileName, bodyName, type, physicalGroup, part, range, comm).read();
}

long long gmshBodyElementCount(Teuchos::ParameterList& params, const std::string& bodyName, CellType type,
                               const std::string& path, const std::string& baseDirectory, MPI_Comm comm) {
  const GmshBodyFile in = gmshBodyFile(params, bodyName, type, path, baseDirectory);
  try {
    return gmshFileElementCount(in.file, bodyName, type, in.group, comm);
  } catch (const InputError& e) {
    throwForBody(e, bodyName, path);
  }
}

int readGmshBodyInRange(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                        const std::string& path, const std::string& baseDirectory, const ElementRange& range,
                        MPI_Comm comm) {
  const GmshBodyFile in = gmshBodyFile(params, bodyName, type, path, baseDirectory);
  try {
    return readGmshFileInRange(part, bodyName, type, in.file, in.group, range, comm);
  } catch (const InputError& e) {
    throwForBody(e, bodyName, path);
  }
}

}  // namespace ddc
