// The parsed Gmsh MSH 4.1 file and the checks of one body that every
// reader of it makes alike: the whole reader (readGmshFile(), every rank
// holds the whole body) and the reader in ranges (readGmshFileInRange(),
// each rank its range of the body's elements and a share of the nodes).
// What is supported and how each fault is named is DDC_Gmsh.hpp's file
// comment; both readers give the same message for the same fault.
//
// A reader in ranges keeps only part of the file's bulk (MshKeep): the
// coordinates of the node tags it owns and the connectivity of the body's
// elements in its range. Everything else -- the physical names, the
// entities, and the elements of lower dimension (side sets, curves, points)
// -- is the size of the body's boundary and is kept whole on every rank.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "DDC_Mesh.hpp"
#include "DDC_ReferenceCell.hpp"

namespace ddc::gmsh {

using EntityKey = std::pair<int, int>;  ///< (dimension, entity tag)

/// One block of $Elements. Its tags, lines and nodes hold the elements
/// [keptFrom, keptFrom + tags.size()) of the block's `count`: all of them
/// in a whole read, a rank's share (or none) of the body's blocks in a read
/// in ranges.
struct ElementBlock {
  int dim = 0, entity = 0, type = 0;
  int line = 0;                  ///< line of the block header
  long long count = 0;           ///< the block's elements in the file
  long long keptFrom = 0;        ///< the first kept element's index in the block
  std::vector<long long> tags;   ///< kept elements' tags
  std::vector<int> lines;        ///< line of each kept element
  std::vector<long long> nodes;  ///< node tags, numNodes per kept element
  int numNodes = 0;
  /// The first element with a wrong node count in a block whose check is
  /// left to the body that reads it, if any (whether kept or not).
  std::string countError;
  int countErrorLine = 0;
};

struct MshData {
  std::map<EntityKey, std::string> physicalNames;         ///< (dim, physical tag) -> name
  std::map<EntityKey, std::vector<int>> entityPhysicals;  ///< (dim, entity tag) -> physical tags
  bool hasEntities = false;
  bool hasNodes = false, hasElements = false;
  /// $PhysicalNames or $Entities came after $Elements (Gmsh writes them
  /// before): a read in ranges cannot select the body's blocks while it reads.
  bool groupsAfterElements = false;
  std::unordered_map<long long, std::array<double, 3>> nodes;  ///< tag -> x, y, z (kept ones)
  std::map<int, std::vector<long long>> pointNodes;             ///< point entity -> node tags
  std::vector<ElementBlock> blocks;                             ///< 0-D to 3-D blocks
  /// The node tags the first $Nodes header announces, [minNodeTag, maxNodeTag]:
  /// their even shares give the owners of a read in ranges (nodeOwner()).
  long long minNodeTag = 0, maxNodeTag = -1;
  /// A read in ranges: the first fault of the file, with its line (0:
  /// none). A node tag that appears twice is found only by its owner, so
  /// the ranks agree on the fault with the smallest line afterwards.
  int faultLine = 0;
  std::string fault;
};

/// What a read in ranges keeps of the file's bulk: the body's blocks are
/// those of dimension `bodyDim` (and of physical group `group` if it is not
/// empty); of their elements, taken in file order, those in [first, last);
/// of the nodes, those that nodeOwner() gives rank `rank` of `ranks`.
/// Elements of a higher dimension than the body's are counted, not kept.
struct MshKeep {
  int bodyDim = 2;
  std::string group;
  long long first = 0, last = 0;
  int rank = 0, ranks = 1;
};

/// Parse a whole file (keep = nullptr: everything kept; throws InputError
/// naming the file and line of the first fault), or what a rank keeps of it
/// (every line is still read and checked; the first fault is returned in
/// MshData::fault instead of thrown).
MshData parseMsh(const std::string& fileName, const MshKeep* keep = nullptr);

/// The rank of `ranks` that owns node tag `tag` in a read in ranges: even
/// shares of the tags the $Nodes header announces, tags outside them to
/// the first or last rank.
int nodeOwner(const MshData& d, long long tag, int ranks);

/// The name of physical group (dim, tag): its $PhysicalNames entry, or the
/// tag as text.
std::string physicalName(const MshData& d, int dim, int tag);
/// The physical tags of entity (dim, entity); empty if it has none.
const std::vector<int>& physicalsOf(const MshData& d, int dim, int entity);

/// One body of a parsed file: the checks and the steps that do not depend
/// on which of its elements a reader holds. Every fault throws InputError
/// naming the file (and the line where the check has one).
class GmshBody {
 public:
  GmshBody(const MshData& d, const std::string& fileName, const std::string& bodyName, CellType type,
           const std::string& physicalGroup);

  /// 1. The tag of the physical surface (2-D) / volume (3-D) selecting the
  /// body's elements (-1 without a selection); throws if there is none.
  void selectBodyGroup();
  /// 2. The blocks of the body's elements, type-checked; their elements
  /// counted (numElements()).
  void collectBodyBlocks();
  long long numElements() const { return numElems_; }
  const std::vector<const ElementBlock*>& bodyBlocks() const { return bodyBlocks_; }

 protected:
  /// Side set element `l` of block `b` as the body sees it: whether all its
  /// nodes are the body's, how many element facets have its corners, and
  /// whether its other nodes are those of that facet; `element` and
  /// `facet` say which one where the reader holds it (-1: elsewhere).
  struct SideFacet {
    bool inBody = false;
    int matches = 0;
    bool sameHigherOrder = true;
    int element = -1, facet = -1;
  };
  using SideVerdict = std::function<SideFacet(const ElementBlock&, size_t)>;
  using AddSide = std::function<void(const SideFacet&, const std::vector<int>& physicals, const ElementBlock&, size_t)>;
  /// 6. Every element of every side set block in file order, checked by its
  /// verdict, and added (to each of its physical groups) if it is the
  /// body's; with a selection, elements of other bodies are skipped.
  void readSideSets(const SideVerdict& verdict, const AddSide& add) const;

  using UsedTag = std::function<bool(long long tag)>;
  using AddNodes = std::function<void(const std::string& name, const std::vector<long long>& tags)>;
  /// 7. Physical points, and in 3-D physical curves, as node sets: `used`
  /// says whether the body has a node; `add` receives each set's tags.
  void readPointNodeSets(const UsedTag& used, const AddNodes& add) const;
  void readCurveNodeSets(const UsedTag& used, const AddNodes& add) const;

  /// Node `tag` of the body, at `p` (nullptr: not in $Nodes), is admissible.
  void requireNode(long long tag, const std::array<double, 3>* p) const;
  /// Element e (an index into b's kept elements) of local nodes `n` at
  /// `xyz`: a volume element must be valid; a quadrangle must have an area,
  /// and is reordered counter-clockwise if it is clockwise.
  void checkVolumeElement(const ElementBlock& b, size_t e, const int* n,
                          const std::vector<std::array<double, 3>>& xyz) const;
  void orientQuadrangle(const ElementBlock& b, size_t e, int* n, const std::vector<std::array<double, 3>>& xyz) const;

  [[noreturn]] void fail(const std::string& msg) const;
  [[noreturn]] void failAt(int line, const std::string& msg) const;
  /// A bad element `l` of a side set block: 3-D messages name its line.
  [[noreturn]] void failSideSet(const ElementBlock& b, size_t l, const std::string& msg) const;

  // the input and what follows from the body's element type
  const MshData& d_;
  const std::string& fileName_;
  const std::string& bodyName_;
  const std::string& physicalGroup_;
  const CellType type_;
  const ReferenceCell& ref_;
  const int dim_;
  const bool solid_;
  const bool quad9_;
  const int wantElement_;
  const CellType facetType_;
  const int wantFacet_;
  const int nen_;
  const int facetCorners_;
  const std::string groupWord_;       ///< selects the body
  const std::string facetGroupWord_;  ///< side sets
  const std::string facetWord_;
  const std::string dimWord_;
  // what steps 1 and 2 find
  int selectedTag_ = -1;
  std::vector<const ElementBlock*> bodyBlocks_;
  long long numElems_ = 0;

 private:
  bool selected(const ElementBlock& b) const;
  void checkElementType(const ElementBlock& b) const;
  [[noreturn]] void failSideSetType(const ElementBlock& b, const std::string& firstName) const;
};

}  // namespace ddc::gmsh
