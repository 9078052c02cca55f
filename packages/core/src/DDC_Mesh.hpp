// Two-dimensional mesh of several bodies with named node sets and side sets.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace ddc {

/// Element geometry. Node ordering follows Gmsh: corners counter-clockwise,
/// then (Quad9) mid-side nodes 4:(0-1) 5:(1-2) 6:(2-3) 7:(3-0), centre 8.
enum class CellType { Quad4, Quad9 };

/// Number of nodes of a cell type.
int numCellNodes(CellType t);
/// Human-readable name ("Quad4", "Quad9").
const char* cellTypeName(CellType t);

/// A boundary segment: side `localSide` of element `element` (side s runs
/// from corner s to corner (s+1)%4). Nodes are listed in the element's
/// counter-clockwise sense: for a body on the left of the direction of
/// travel the outward normal is n = (dy, -dx)/|.|. Two nodes for Quad4,
/// three (start, end, middle) for Quad9.
struct Segment {
  int element = -1;
  int localSide = -1;
  int numNodes = 0;
  std::array<int, 3> nodes{{-1, -1, -1}};
};

/// A body: a contiguous range of elements and nodes with one cell type.
struct Body {
  std::string name;
  CellType cellType = CellType::Quad4;
  int firstNode = 0, numNodes = 0;
  int firstElement = 0, numElements = 0;
};

/// A replicated 2-D mesh. Bodies do not share nodes. Set names are qualified
/// by the body: "Upper Ring/outer". Each side set also defines a node set of
/// the same name (the nodes of its segments).
class Mesh {
 public:
  /// Start a new body; nodes and elements added afterwards belong to it.
  /// \pre no body with this name yet (throws InputError otherwise).
  int beginBody(const std::string& name, CellType cellType);
  /// Add a node of the current body; returns its global index.
  int addNode(double x, double y);
  /// Add an element of the current body; `nodes` holds numCellNodes() global
  /// node indices in Gmsh order. Returns the element index.
  int addElement(const int* nodes);
  /// Name a set of nodes (global indices). `localName` is qualified by the
  /// body: addNodeSet(b, "left", ...) defines "Body/left".
  void addNodeSet(int body, const std::string& localName, std::vector<int> nodes);
  /// Name a set of element sides; also defines the node set of the same name.
  void addSideSet(int body, const std::string& localName, std::vector<Segment> segments);
  /// The segment for side `localSide` of element `e`, oriented as documented.
  Segment makeSegment(int e, int localSide) const;

  int numBodies() const { return static_cast<int>(bodies_.size()); }
  const Body& body(int b) const { return bodies_.at(b); }
  /// Index of the body with this name; throws InputError listing the bodies.
  int bodyIndex(const std::string& name) const;

  int numNodes() const { return static_cast<int>(coords_.size()); }
  int numElements() const { return static_cast<int>(elemBody_.size()); }
  const std::array<double, 2>& coord(int n) const { return coords_[n]; }
  std::array<double, 2>& coord(int n) { return coords_[n]; }
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

  /// Nodes that belong to no element (rejected by check()).
  /// Throws InputError if an element references a node outside its body, a
  /// body has no elements, or a node belongs to no element.
  void check() const;

 private:
  std::vector<Body> bodies_;
  std::vector<std::array<double, 2>> coords_;
  std::vector<int> elemBody_;
  std::vector<int> elemOffset_{0};
  std::vector<int> elemNodes_;
  std::map<std::string, std::vector<int>> nodeSets_;
  std::map<std::string, std::vector<Segment>> sideSets_;
};

}  // namespace ddc
