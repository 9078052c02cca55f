// Mesh of several bodies with named node sets and side sets, in 2-D or 3-D.
#pragma once

#include <mpi.h>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "DDC_ReferenceCell.hpp"

namespace ddc {

/// A boundary facet: facet `localSide` of element `element` as described by
/// referenceCell(cell type).facets (a side of a 2-D cell, a face of a 3-D
/// cell), with the element's global node numbers in the facet's node order
/// and outward orientation: in 2-D a side runs with the body on its left,
/// outward normal n = (dy, -dx)/|.|, two nodes for Quad4 and three (start,
/// end, middle) for Quad9; in 3-D the face corners run counter-clockwise
/// seen from outside (4/8/9 nodes for Hex8/20/27 faces, 3/6 for Tet4/10).
struct Segment {
  int element = -1;
  int localSide = -1;
  int numNodes = 0;
  std::array<int, 9> nodes{{-1, -1, -1, -1, -1, -1, -1, -1, -1}};
};

/// A body: a contiguous range of elements and nodes with one cell type.
struct Body {
  std::string name;
  CellType cellType = CellType::Quad4;
  int firstNode = 0, numNodes = 0;
  int firstElement = 0, numElements = 0;
  /// On a part of a mesh (Mesh::isPart()): the body's nodes and elements in
  /// the whole mesh (Mesh::bodyGlobalNodes()); unused on a whole mesh.
  long long wholeNodes = 0, wholeElements = 0;
};

/// A mesh of one dimension (2 or 3, set by its first body's cell type;
/// bodies of another dimension are refused). Bodies do not share nodes. Set
/// names are qualified by the body: "Upper Ring/outer". Each side set also
/// defines a node set of the same name (the nodes of its segments).
///
/// A mesh is either whole (what the generators and readers build: every
/// node's and element's id is its index) or a part of a whole mesh (part()):
/// some of its elements and their nodes, numbered from 0, each with its id
/// in the whole mesh beside it, the way a rank holds its share of a
/// distributed mesh (doc/architecture.md, "What a distributed mesh has to
/// change").
class Mesh {
 public:
  /// An id in the whole mesh (part()).
  using GlobalId = long long;

  /// Start a new body; nodes and elements added afterwards belong to it.
  /// Throws InputError if a body has this name already, `cellType` is not an
  /// element cell type, or its dimension differs from the other bodies'.
  int beginBody(const std::string& name, CellType cellType);
  /// Add a node of the current body; returns its global index. 2-D meshes
  /// keep z = 0.
  int addNode(double x, double y, double z = 0.0);
  /// Add an element of the current body; `nodes` holds numCellNodes() global
  /// node indices in Gmsh order. Returns the element index.
  int addElement(const int* nodes);
  /// Name a set of nodes (global indices). `localName` is qualified by the
  /// body: addNodeSet(b, "left", ...) defines "Body/left".
  void addNodeSet(int body, const std::string& localName, std::vector<int> nodes);
  /// Name a set of element sides; also defines the node set of the same name.
  void addSideSet(int body, const std::string& localName, std::vector<Segment> segments);
  /// The facet `localSide` of element `e`, oriented as documented.
  Segment makeSegment(int e, int localSide) const;
  /// Number of facets (sides or faces) of element `e`.
  int elementNumFacets(int e) const;
  /// The corner nodes of facet `f` of element `e`, sorted: equal for the two
  /// elements that share the facet.
  std::vector<int> facetKey(int e, int f) const;

  /// \name A part of a whole mesh
  ///@{
  /// The part made of `elements` (indices in this mesh, ascending, no
  /// repeats) and their nodes. Its elements keep that order and its nodes
  /// are in the order of their ids, so each body's nodes and elements stay
  /// contiguous and every body is kept (with no elements if none is
  /// chosen). Node sets keep the nodes the part holds, side sets the
  /// segments of its elements; ids are this mesh's ids, so a part of a part
  /// keeps the whole mesh's.
  /// \throws std::invalid_argument if `elements` is not ascending or holds
  ///         an index outside this mesh
  Mesh part(const std::vector<int>& elements) const;
  /// The part of the whole mesh this rank holds after every rank has sent
  /// each of its elements e to rank `destination[e]`, with the nodes and
  /// set memberships that go with it: how a mesh built on one rank, or in
  /// even ranges of elements, reaches the ranks of its subdomains.
  /// Elements and nodes are in the order of their ids, side sets' segments
  /// by element id and side (a 2-D side set is no longer one chain). Every
  /// rank's mesh must be a part of the same whole (or the whole on one rank
  /// and empty parts, part({}), on the others), no element on two ranks.
  /// Collective on `comm`.
  /// \throws std::invalid_argument if `destination` does not hold one rank
  ///         of `comm` per element
  Mesh migrated(MPI_Comm comm, const std::vector<int>& destination) const;
  /// The part of the whole mesh `whole`, held by rank `root` of `comm`
  /// alone, that rank r of P receives when the elements are dealt in even
  /// ranges of ids (elements [N r / P, N (r + 1) / P) of the N): how a mesh
  /// that only one rank can read or build reaches the others without any
  /// other rank holding it whole. The result is migrated()'s (sets sorted by
  /// id). Collective on `comm`; `whole` is read on the root only (nullptr
  /// elsewhere).
  /// \throws std::logic_error if the root's `whole` is null or a part
  static Mesh scatteredInRanges(MPI_Comm comm, int root, const Mesh* whole);
  /// A part built piece by piece, as a generator does that makes only some
  /// elements of a whole mesh (generateBox() with an ElementRange): no
  /// bodies, nodes or elements yet, a whole mesh of none.
  static Mesh startPart();
  /// Add a node of the current body of a part (startPart()) with its id in
  /// the whole mesh (ids ascending). Returns its index.
  int addPartNode(GlobalId id, double x, double y, double z = 0.0);
  /// Add an element of the current body of a part with its id in the whole
  /// mesh (ids ascending); `nodes` are indices in the part. Returns its index.
  int addPartElement(GlobalId id, const int* nodes);
  /// The whole mesh of a part (startPart()) grows by `nodes` nodes and
  /// `elements` elements: the current body, added in full to the whole.
  void growWhole(GlobalId nodes, GlobalId elements);
  /// Whether this mesh is a part of a larger one (made by part()).
  bool isPart() const { return isPart_; }
  /// The id of node n in the whole mesh (n itself in a whole mesh).
  GlobalId nodeId(int n) const { return isPart_ ? nodeId_[n] : n; }
  /// The id of element e in the whole mesh (e itself in a whole mesh).
  GlobalId elementId(int e) const { return isPart_ ? elementId_[e] : e; }
  /// Nodes and elements of the whole mesh.
  GlobalId numGlobalNodes() const { return isPart_ ? globalNodes_ : numNodes(); }
  GlobalId numGlobalElements() const { return isPart_ ? globalElements_ : numElements(); }
  /// Nodes and elements of body b in the whole mesh.
  GlobalId bodyGlobalNodes(int b) const { return isPart_ ? bodies_[b].wholeNodes : bodies_[b].numNodes; }
  GlobalId bodyGlobalElements(int b) const { return isPart_ ? bodies_[b].wholeElements : bodies_[b].numElements; }
  /// The index of the node whose id in the whole mesh is `id`; −1 if this
  /// mesh does not hold it.
  int localNode(GlobalId id) const;
  ///@}

  /// \name Memory budget of the replicated mesh (doc/user-guide.md, "Memory")
  /// Every rank holds the whole mesh and the analysis keeps per-node and
  /// per-DOF indexes of it on every rank: about replicatedBytes() per rank.
  ///@{
  /// Bytes per rank of a replicated mesh of `nodes` nodes and `elements`
  /// elements of `nodesPerElement` nodes, with the analysis's indexes.
  static double replicatedBytes(double nodes, double elements, int nodesPerElement);
  /// Generators check against this before they allocate (default: none).
  /// \param hint what the user can do, appended to the message
  void setMemoryBudget(double bytes, std::string source, std::string hint);
  /// \throws InputError naming `path`, the sizes, the estimate and the budget
  ///         if the mesh so far plus a body of `nodes` nodes and `elements`
  ///         elements (and the generator's grid of points) would not fit;
  ///         on a part, `nodes` and `elements` are the part's share of the
  ///         body.
  void requireRoom(double nodes, double elements, int nodesPerElement, const std::string& path) const;
  ///@}

  /// The coordinate limit (doc/user-guide.md, "Checks of a mesh file"): a coordinate
  /// must be finite and at most this in magnitude; lengths far from 1 under-
  /// or overflow in the element arithmetic (Jacobians are cubes of lengths in
  /// 3-D). The mesh readers check every node they read against it.
  static constexpr double kMaxCoordinate = 1e100;
  /// `v` is finite and |v| <= kMaxCoordinate.
  static bool admissibleCoordinate(double v) { return std::abs(v) <= kMaxCoordinate; }

  /// Spatial dimension: 2 or 3, 0 before the first body.
  int dim() const { return dim_; }

  int numBodies() const { return static_cast<int>(bodies_.size()); }
  const Body& body(int b) const { return bodies_.at(b); }
  /// Index of the body with this name; throws InputError listing the bodies.
  int bodyIndex(const std::string& name) const;

  int numNodes() const { return static_cast<int>(coords_.size()); }
  int numElements() const { return static_cast<int>(elemBody_.size()); }
  /// Coordinates (x, y, z); z = 0 in 2-D.
  const std::array<double, 3>& coord(int n) const { return coords_[n]; }
  std::array<double, 3>& coord(int n) { return coords_[n]; }
  /// "x, y" (2-D) or "x, y, z" (3-D) of node n, for messages.
  std::string coordText(int n) const;
  int elementBody(int e) const { return elemBody_[e]; }
  CellType elementType(int e) const { return bodies_[elemBody_[e]].cellType; }
  int elementNumNodes(int e) const { return elemOffset_[e + 1] - elemOffset_[e]; }
  const int* elementNodes(int e) const { return elemNodes_.data() + elemOffset_[e]; }

  bool hasNodeSet(const std::string& name) const { return nodeSets_.count(name) != 0; }
  bool hasSideSet(const std::string& name) const { return sideSets_.count(name) != 0; }
  /// Throws InputError naming the set and listing the known ones.
  const std::vector<int>& nodeSet(const std::string& name) const;
  const std::vector<Segment>& sideSet(const std::string& name) const;
  std::vector<std::string> nodeSetNames() const;
  std::vector<std::string> sideSetNames() const;

  /// Throws InputError if an element references a node outside its body, a
  /// body has no elements, a node belongs to no element, or (3-D bodies) an
  /// element is inverted or degenerate by cornerJacobian(); the message names
  /// the body, the element and where det J fails. 2-D elements are checked
  /// by the Analysis with the element's own Jacobian (which also sees Quad9
  /// mid-side nodes) and are not repeated here. checkConnectivity(), then
  /// checkShapes() of every element.
  void check() const;
  /// The part of check() that needs the whole mesh: every body has elements,
  /// references only its own nodes and uses every one of them. On a part,
  /// every body has elements in the whole mesh and the part's elements and
  /// nodes keep these rules; messages name ids in the whole mesh.
  void checkConnectivity() const;
  /// The part of check() element by element, for the elements [first, last)
  /// (3-D: cornerJacobian(); nothing in 2-D), so that ranks can share it.
  /// Messages name the element and node by their ids in the whole mesh.
  void checkShapes(int first, int last) const;

 private:
  /// A part with this mesh's dimension, whole sizes, budget and bodies,
  /// holding nothing yet (part(), migrated()).
  Mesh emptyPart() const;
  /// A part's bodies without nodes or elements start where the body
  /// before them ends.
  void placeEmptyBodies();

  int dim_ = 0;
  std::vector<Body> bodies_;
  std::vector<std::array<double, 3>> coords_;
  std::vector<int> elemBody_;
  std::vector<int> elemOffset_{0};
  std::vector<int> elemNodes_;
  std::map<std::string, std::vector<int>> nodeSets_;
  std::map<std::string, std::vector<Segment>> sideSets_;
  bool isPart_ = false;
  std::vector<GlobalId> nodeId_, elementId_;  ///< a part's ids in the whole mesh (ascending)
  GlobalId globalNodes_ = 0, globalElements_ = 0;
  double memoryBudget_ = -1.0;  ///< < 0: none
  std::string budgetSource_, budgetHint_;
};

}  // namespace ddc
