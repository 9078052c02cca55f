#include "DDC_Mesh.hpp"

#include "DDC_Memory.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"

namespace ddc {

int Mesh::beginBody(const std::string& name, CellType cellType) {
  for (const auto& b : bodies_)
    DDC_INPUT_REQUIRE(b.name != name, "mesh: two bodies are named '" << name << "'");
  DDC_INPUT_REQUIRE(!name.empty() && name.find('/') == std::string::npos,
                    "mesh: body name '" << name << "' must be non-empty and contain no '/'");
  const auto& types = elementCellTypes();
  DDC_INPUT_REQUIRE(std::find(types.begin(), types.end(), cellType) != types.end(),
                    "mesh: body '" << name << "': " << cellTypeName(cellType)
                                   << " is a facet cell type, not an element type");
  const int d = cellDimension(cellType);
  DDC_INPUT_REQUIRE(bodies_.empty() || d == dim_,
                    "mesh: body '" << name << "' has " << d << "-D cells (" << cellTypeName(cellType)
                                   << ") but body '" << bodies_.front().name << "' has " << dim_ << "-D cells ("
                                   << cellTypeName(bodies_.front().cellType)
                                   << "); all bodies of a mesh must have the same dimension");
  dim_ = d;
  Body b;
  b.name = name;
  b.cellType = cellType;
  b.firstNode = numNodes();
  b.firstElement = numElements();
  bodies_.push_back(b);
  return numBodies() - 1;
}

int Mesh::addNode(double x, double y, double z) {
  DDC_CHECK(!bodies_.empty(), "addNode before beginBody");
  DDC_CHECK(dim_ == 3 || z == 0.0, "addNode: z = " << z << " in a 2-D mesh");
  coords_.push_back({x, y, z});
  bodies_.back().numNodes++;
  return numNodes() - 1;
}

Mesh Mesh::startPart() {
  Mesh p;
  p.isPart_ = true;
  return p;
}

int Mesh::addPartNode(GlobalId id, double x, double y, double z) {
  DDC_CHECK(isPart_, "addPartNode on a whole mesh");
  DDC_CHECK(nodeId_.empty() || id > nodeId_.back(), "addPartNode: id " << id << " after " << nodeId_.back());
  nodeId_.push_back(id);
  return addNode(x, y, z);
}

int Mesh::addPartElement(GlobalId id, const int* nodes) {
  DDC_CHECK(isPart_, "addPartElement on a whole mesh");
  DDC_CHECK(elementId_.empty() || id > elementId_.back(),
            "addPartElement: id " << id << " after " << elementId_.back());
  elementId_.push_back(id);
  return addElement(nodes);
}

void Mesh::growWhole(GlobalId nodes, GlobalId elements) {
  DDC_CHECK(isPart_ && nodes >= 0 && elements >= 0, "growWhole on a whole mesh or by a negative count");
  DDC_CHECK(!bodies_.empty(), "growWhole before beginBody");
  globalNodes_ += nodes;
  globalElements_ += elements;
  bodies_.back().wholeNodes += nodes;
  bodies_.back().wholeElements += elements;
}

int Mesh::addElement(const int* nodes) {
  DDC_CHECK(!bodies_.empty(), "addElement before beginBody");
  const int nn = numCellNodes(bodies_.back().cellType);
  elemNodes_.insert(elemNodes_.end(), nodes, nodes + nn);
  elemOffset_.push_back(static_cast<int>(elemNodes_.size()));
  elemBody_.push_back(numBodies() - 1);
  bodies_.back().numElements++;
  return numElements() - 1;
}

void Mesh::addNodeSet(int body, const std::string& localName, std::vector<int> nodes) {
  const std::string name = bodies_.at(body).name + "/" + localName;
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  auto& set = nodeSets_[name];
  std::vector<int> merged;
  std::set_union(set.begin(), set.end(), nodes.begin(), nodes.end(), std::back_inserter(merged));
  set.swap(merged);
}

void Mesh::addSideSet(int body, const std::string& localName, std::vector<Segment> segments) {
  std::vector<int> nodes;
  for (const auto& s : segments) nodes.insert(nodes.end(), s.nodes.begin(), s.nodes.begin() + s.numNodes);
  addNodeSet(body, localName, std::move(nodes));
  auto& set = sideSets_[bodies_.at(body).name + "/" + localName];
  set.insert(set.end(), segments.begin(), segments.end());
}

Segment Mesh::makeSegment(int e, int localSide) const {
  const auto& facets = referenceCell(elementType(e)).facets;
  DDC_CHECK(localSide >= 0 && localSide < static_cast<int>(facets.size()), "bad local side " << localSide);
  const auto& f = facets[localSide];
  Segment s;
  s.element = e;
  s.localSide = localSide;
  s.numNodes = static_cast<int>(f.nodes.size());
  const int* en = elementNodes(e);
  for (int i = 0; i < s.numNodes; ++i) s.nodes[i] = en[f.nodes[i]];
  return s;
}

int Mesh::elementNumFacets(int e) const {
  return static_cast<int>(referenceCell(elementType(e)).facets.size());
}

std::vector<int> Mesh::facetKey(int e, int f) const {
  const auto& facet = referenceCell(elementType(e)).facets.at(f);
  const int* en = elementNodes(e);
  std::vector<int> key;
  for (int i = 0; i < referenceCell(facet.type).numCorners; ++i) key.push_back(en[facet.nodes[i]]);
  std::sort(key.begin(), key.end());
  return key;
}

int Mesh::bodyIndex(const std::string& name) const {
  for (int b = 0; b < numBodies(); ++b)
    if (bodies_[b].name == name) return b;
  std::vector<std::string> names;
  for (const auto& b : bodies_) names.push_back(b.name);
  DDC_THROW(InputError, "mesh: no body named '" << name << "'; bodies are " << quotedNames(names));
}

const std::vector<int>& Mesh::nodeSet(const std::string& name) const {
  auto it = nodeSets_.find(name);
  DDC_INPUT_REQUIRE(it != nodeSets_.end(),
                    "mesh: no node set named '" << name << "'; known node sets are "
                                                 << quotedNames(nodeSetNames()));
  return it->second;
}

const std::vector<Segment>& Mesh::sideSet(const std::string& name) const {
  auto it = sideSets_.find(name);
  DDC_INPUT_REQUIRE(it != sideSets_.end(),
                    "mesh: no side set named '" << name << "'; known side sets are "
                                                 << quotedNames(sideSetNames()));
  return it->second;
}

std::vector<std::string> Mesh::nodeSetNames() const {
  std::vector<std::string> n;
  for (const auto& kv : nodeSets_) n.push_back(kv.first);
  return n;
}

std::vector<std::string> Mesh::sideSetNames() const {
  std::vector<std::string> n;
  for (const auto& kv : sideSets_) n.push_back(kv.first);
  return n;
}

void Mesh::check() const {
  checkConnectivity();
  checkShapes(0, numElements());
}

void Mesh::checkConnectivity() const {
  std::vector<char> used(numNodes(), 0);
  for (int b = 0; b < numBodies(); ++b) {
    const Body& body = bodies_[b];
    DDC_INPUT_REQUIRE(bodyGlobalElements(b) > 0, "mesh: body '" << body.name << "' has no elements");
    for (int e = body.firstElement; e < body.firstElement + body.numElements; ++e) {
      const int* en = elementNodes(e);
      for (int i = 0; i < elementNumNodes(e); ++i) {
        DDC_INPUT_REQUIRE(en[i] >= body.firstNode && en[i] < body.firstNode + body.numNodes,
                          "mesh: element " << elementId(e) << " of body '" << body.name << "' references node "
                                           << (isPart_ ? nodeId(en[i]) : en[i]) << " outside the body");
        used[en[i]] = 1;
      }
    }
  }
  for (int n = 0; n < numNodes(); ++n)
    DDC_INPUT_REQUIRE(used[n], "mesh: node " << nodeId(n) << " at (" << coords_[n][0] << ", " << coords_[n][1]
                                            << (dim_ == 3 ? ", " + std::to_string(coords_[n][2]) : std::string())
                                            << ") belongs to no element");
}

void Mesh::checkShapes(int first, int last) const {
  if (dim_ != 3) return;
  for (int e = std::max(first, 0); e < std::min(last, numElements()); ++e) {
    const Body& body = bodies_[elemBody_[e]];
    const int* en = elementNodes(e);
    std::array<std::array<double, 3>, 8> corners;
    for (int i = 0; i < referenceCell(body.cellType).numCorners; ++i) corners[i] = coords_[en[i]];
    const CornerJacobian j = cornerJacobian(body.cellType, corners.data());
    DDC_INPUT_REQUIRE(j.verdict == CornerJacobian::Verdict::Valid,
                      "mesh: element " << elementId(e) << " of body '" << body.name << "' ("
                                       << cellTypeName(body.cellType) << ", first node " << nodeId(en[0]) << " at (" << coords_[en[0]][0] << ", "
                                       << coords_[en[0]][1] << ", " << coords_[en[0]][2] << ")) is "
                                       << describeCornerJacobian(body.cellType, j));
  }
}

Mesh Mesh::emptyPart() const {
  Mesh p;
  p.dim_ = dim_;
  p.isPart_ = true;
  p.globalNodes_ = numGlobalNodes();
  p.globalElements_ = numGlobalElements();
  p.memoryBudget_ = memoryBudget_;
  p.budgetSource_ = budgetSource_;
  p.budgetHint_ = budgetHint_;
  for (int body = 0; body < numBodies(); ++body) {
    Body q = bodies_[body];
    q.wholeNodes = bodyGlobalNodes(body);
    q.wholeElements = bodyGlobalElements(body);
    q.firstNode = q.numNodes = q.firstElement = q.numElements = 0;
    p.bodies_.push_back(q);
  }
  return p;
}

void Mesh::placeEmptyBodies() {
  for (size_t b = 0; b < bodies_.size(); ++b) {
    Body& q = bodies_[b];
    const int nodesBefore = b == 0 ? 0 : bodies_[b - 1].firstNode + bodies_[b - 1].numNodes;
    const int elementsBefore = b == 0 ? 0 : bodies_[b - 1].firstElement + bodies_[b - 1].numElements;
    if (q.numNodes == 0) q.firstNode = nodesBefore;
    if (q.numElements == 0) q.firstElement = elementsBefore;
  }
}

Mesh Mesh::part(const std::vector<int>& elements) const {
  for (size_t i = 0; i < elements.size(); ++i)
    if (elements[i] < 0 || elements[i] >= numElements() || (i > 0 && elements[i] <= elements[i - 1]))
      throw std::invalid_argument("Mesh::part: element " + std::to_string(elements[i]) + " at position " +
                                  std::to_string(i) + " is outside the mesh or not ascending");
  // Local index of each node of the chosen elements, in node (= id) order.
  std::vector<int> local(numNodes(), -1);
  for (int e : elements)
    for (int i = 0; i < elementNumNodes(e); ++i) local[elementNodes(e)[i]] = 0;
  Mesh p = emptyPart();
  // Bodies are contiguous ranges of nodes and elements, so walking both in
  // order fills each body's range before the next one's.
  for (int body = 0, n = 0; n < numNodes(); ++n) {
    if (local[n] < 0) continue;
    while (n >= bodies_[body].firstNode + bodies_[body].numNodes) p.bodies_[++body].firstNode = p.numNodes();
    local[n] = p.numNodes();
    p.coords_.push_back(coords_[n]);
    p.nodeId_.push_back(nodeId(n));
    p.bodies_[body].numNodes++;
  }
  std::vector<int> localElement(numElements(), -1);
  for (int e : elements) {
    const int b = elemBody_[e];
    if (p.bodies_[b].numElements == 0) p.bodies_[b].firstElement = p.numElements();
    localElement[e] = p.numElements();
    for (int i = 0; i < elementNumNodes(e); ++i) p.elemNodes_.push_back(local[elementNodes(e)[i]]);
    p.elemOffset_.push_back(static_cast<int>(p.elemNodes_.size()));
    p.elemBody_.push_back(b);
    p.elementId_.push_back(elementId(e));
    p.bodies_[b].numElements++;
  }
  p.placeEmptyBodies();
  for (const auto& [name, nodes] : nodeSets_) {
    auto& set = p.nodeSets_[name];
    for (int n : nodes)
      if (local[n] >= 0) set.push_back(local[n]);
  }
  for (const auto& [name, segments] : sideSets_) {
    auto& set = p.sideSets_[name];
    for (Segment s : segments) {
      if (localElement[s.element] < 0) continue;
      s.element = localElement[s.element];
      for (int i = 0; i < s.numNodes; ++i) s.nodes[i] = local[s.nodes[i]];
      set.push_back(s);
    }
  }
  return p;
}

namespace {

/// A node sent with an element: its id and coordinates.
struct NodeRecord {
  Mesh::GlobalId id;
  std::array<double, 3> x;
};

/// A node in a node set, or an element side in a side set (the sets by
/// their index in the sorted names, the same on every rank).
struct SetRecord {
  int set, side;
  Mesh::GlobalId entity;
};

}  // namespace

Mesh Mesh::migrated(MPI_Comm comm, const std::vector<int>& destination) const {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  if (static_cast<int>(destination.size()) != numElements())
    throw std::invalid_argument("Mesh::migrated: " + std::to_string(destination.size()) + " destinations for " +
                                std::to_string(numElements()) + " elements");
  for (int r : destination)
    if (r < 0 || r >= ranks) throw std::invalid_argument("Mesh::migrated: destination rank " + std::to_string(r));
  // Elements as [id, body, node ids...], by destination.
  std::vector<std::vector<GlobalId>> elementsTo(ranks);
  std::vector<std::pair<int, int>> nodeTo;  // (node, destination) of every element sent
  for (int e = 0; e < numElements(); ++e) {
    auto& out = elementsTo[destination[e]];
    out.push_back(elementId(e));
    out.push_back(elemBody_[e]);
    for (int i = 0; i < elementNumNodes(e); ++i) {
      out.push_back(nodeId(elementNodes(e)[i]));
      nodeTo.emplace_back(elementNodes(e)[i], destination[e]);
    }
  }
  std::sort(nodeTo.begin(), nodeTo.end());
  nodeTo.erase(std::unique(nodeTo.begin(), nodeTo.end()), nodeTo.end());
  std::vector<std::vector<NodeRecord>> nodesTo(ranks);
  for (const auto& [n, r] : nodeTo) nodesTo[r].push_back({nodeId(n), coords_[n]});
  // Set memberships go where the node or the element goes.
  std::vector<std::vector<SetRecord>> setsTo(ranks);
  const std::vector<std::string> nodeNames = nodeSetNames(), sideNames = sideSetNames();
  for (size_t k = 0; k < nodeNames.size(); ++k)
    for (int n : nodeSets_.at(nodeNames[k])) {
      auto it = std::lower_bound(nodeTo.begin(), nodeTo.end(), std::make_pair(n, -1));
      for (; it != nodeTo.end() && it->first == n; ++it) setsTo[it->second].push_back({int(k), -1, nodeId(n)});
    }
  for (size_t k = 0; k < sideNames.size(); ++k)
    for (const Segment& seg : sideSets_.at(sideNames[k]))
      setsTo[destination[seg.element]].push_back({int(k), seg.localSide, elementId(seg.element)});
  std::vector<std::pair<int, int>>().swap(nodeTo);
  const std::vector<GlobalId> elements = exchangeRecords(comm, elementsTo);
  std::vector<std::vector<GlobalId>>().swap(elementsTo);
  std::vector<NodeRecord> nodes = exchangeRecords(comm, nodesTo);
  std::vector<std::vector<NodeRecord>>().swap(nodesTo);
  std::vector<SetRecord> sets = exchangeRecords(comm, setsTo);
  std::vector<std::vector<SetRecord>>().swap(setsTo);

  Mesh p = emptyPart();
  // The received elements in id order: (id, position of its record).
  std::vector<std::pair<GlobalId, size_t>> order;
  for (size_t at = 0; at < elements.size();) {
    order.emplace_back(elements[at], at);
    at += 2 + size_t(numCellNodes(bodies_.at(size_t(elements[at + 1])).cellType));
  }
  std::sort(order.begin(), order.end());
  for (size_t i = 1; i < order.size(); ++i)
    DDC_CHECK(order[i].first != order[i - 1].first, "Mesh::migrated: element " << order[i].first << " sent twice");
  // Nodes in id order (a node shared by elements of several senders comes
  // from each); each takes the body of its elements.
  std::sort(nodes.begin(), nodes.end(), [](const NodeRecord& a, const NodeRecord& b) { return a.id < b.id; });
  nodes.erase(std::unique(nodes.begin(), nodes.end(), [](const NodeRecord& a, const NodeRecord& b) { return a.id == b.id; }),
              nodes.end());
  for (const NodeRecord& r : nodes) {
    p.nodeId_.push_back(r.id);
    p.coords_.push_back(r.x);
  }
  std::vector<int> nodeBody(nodes.size(), -1);
  for (const auto& [id, at] : order) {
    const int b = static_cast<int>(elements[at + 1]);
    const int nn = numCellNodes(bodies_[b].cellType);
    if (p.bodies_[b].numElements++ == 0) p.bodies_[b].firstElement = p.numElements();
    for (int i = 0; i < nn; ++i) {
      const int n = p.localNode(elements[at + 2 + i]);
      DDC_CHECK(n >= 0, "Mesh::migrated: node " << elements[at + 2 + i] << " of element " << id << " not received");
      p.elemNodes_.push_back(n);
      nodeBody[n] = b;
    }
    p.elemOffset_.push_back(static_cast<int>(p.elemNodes_.size()));
    p.elemBody_.push_back(b);
    p.elementId_.push_back(id);
  }
  for (size_t n = 0; n < nodes.size(); ++n)
    if (p.bodies_[nodeBody[n]].numNodes++ == 0) p.bodies_[nodeBody[n]].firstNode = static_cast<int>(n);
  p.placeEmptyBodies();
  // Sets by name (every name, even where this rank holds none of it).
  for (const auto& name : nodeNames) p.nodeSets_[name];
  for (const auto& name : sideNames) p.sideSets_[name];
  std::sort(sets.begin(), sets.end(), [](const SetRecord& a, const SetRecord& b) {
    return a.set != b.set ? a.set < b.set : a.entity != b.entity ? a.entity < b.entity : a.side < b.side;
  });
  for (const SetRecord& r : sets) {
    if (r.side < 0) {
      auto& set = p.nodeSets_[nodeNames[size_t(r.set)]];
      const int n = p.localNode(r.entity);
      if (set.empty() || set.back() != n) set.push_back(n);
      continue;
    }
    const auto it = std::lower_bound(p.elementId_.begin(), p.elementId_.end(), r.entity);
    p.sideSets_[sideNames[size_t(r.set)]].push_back(p.makeSegment(int(it - p.elementId_.begin()), r.side));
  }
  return p;
}

namespace {

/// Appends a value's bytes to `out`.
template <class T>
void pack(std::vector<char>& out, const T& v) {
  const char* p = reinterpret_cast<const char*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}
void packString(std::vector<char>& out, const std::string& s) {
  pack(out, s.size());
  out.insert(out.end(), s.begin(), s.end());
}
/// Reads what pack() appended, from `at` on.
template <class T>
T unpack(const std::vector<char>& in, size_t& at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}
std::string unpackString(const std::vector<char>& in, size_t& at) {
  const auto n = unpack<size_t>(in, at);
  std::string s(in.data() + at, n);
  at += n;
  return s;
}

}  // namespace

Mesh Mesh::scatteredInRanges(MPI_Comm comm, int root, const Mesh* whole) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // The root's shell - dimension, whole sizes, bodies, set names - to every
  // rank, so that each can receive its elements (migrated()).
  std::vector<char> buffer;
  const bool wholeAtRoot = rank != root || (whole && !whole->isPart());
  if (rank == root && wholeAtRoot) {
    pack(buffer, whole->dim_);
    pack(buffer, whole->numGlobalNodes());
    pack(buffer, whole->numGlobalElements());
    pack(buffer, whole->numBodies());
    for (int b = 0; b < whole->numBodies(); ++b) {
      packString(buffer, whole->bodies_[b].name);
      pack(buffer, whole->bodies_[b].cellType);
      pack(buffer, whole->bodyGlobalNodes(b));
      pack(buffer, whole->bodyGlobalElements(b));
    }
    const auto nodeNames = whole->nodeSetNames(), sideNames = whole->sideSetNames();
    pack(buffer, nodeNames.size());
    for (const auto& n : nodeNames) packString(buffer, n);
    pack(buffer, sideNames.size());
    for (const auto& n : sideNames) packString(buffer, n);
  }
  long long size = wholeAtRoot ? static_cast<long long>(buffer.size()) : -1;
  MPI_Bcast(&size, 1, MPI_LONG_LONG, root, comm);
  if (size < 0) throw std::logic_error("Mesh::scatteredInRanges: the root holds no whole mesh");
  buffer.resize(size_t(size));
  MPI_Bcast(buffer.data(), int(size), MPI_CHAR, root, comm);
  if (rank == root) {
    // Element e of N to rank r when N r / P <= e < N (r + 1) / P.
    std::vector<int> destination(size_t(whole->numElements()));
    const long long n = whole->numElements();
    for (int r = 0; r < ranks; ++r)
      for (long long e = evenShareStart(n, r, ranks); e < evenShareStart(n, r + 1, ranks); ++e)
        destination[size_t(e)] = r;
    return whole->migrated(comm, destination);
  }
  Mesh shell;
  shell.isPart_ = true;
  size_t at = 0;
  shell.dim_ = unpack<int>(buffer, at);
  shell.globalNodes_ = unpack<GlobalId>(buffer, at);
  shell.globalElements_ = unpack<GlobalId>(buffer, at);
  const int bodies = unpack<int>(buffer, at);
  for (int b = 0; b < bodies; ++b) {
    Body q;
    q.name = unpackString(buffer, at);
    q.cellType = unpack<CellType>(buffer, at);
    q.wholeNodes = unpack<long long>(buffer, at);
    q.wholeElements = unpack<long long>(buffer, at);
    shell.bodies_.push_back(q);
  }
  for (size_t k = unpack<size_t>(buffer, at); k > 0; --k) shell.nodeSets_[unpackString(buffer, at)];
  for (size_t k = unpack<size_t>(buffer, at); k > 0; --k) shell.sideSets_[unpackString(buffer, at)];
  return shell.migrated(comm, {});
}

int Mesh::localNode(GlobalId id) const {
  if (!isPart_) return id >= 0 && id < numNodes() ? static_cast<int>(id) : -1;
  const auto it = std::lower_bound(nodeId_.begin(), nodeId_.end(), id);
  return it != nodeId_.end() && *it == id ? static_cast<int>(it - nodeId_.begin()) : -1;
}

std::string Mesh::coordText(int n) const {
  std::ostringstream os;
  os << coords_[n][0] << ", " << coords_[n][1];
  if (dim_ == 3) os << ", " << coords_[n][2];
  return os.str();
}

double Mesh::replicatedBytes(double nodes, double elements, int nodesPerElement) {
  // Per node: coordinates (24 B), node sets, the analysis's owner and first
  // DOF, a prescribed bit per DOF, the rigid-motion body index; per
  // element: connectivity, offsets, body, partition, and the element graph
  // METIS partitions. Counted from those arrays with room for their
  // overheads when the model also held a condition, an entity and a flag
  // for every DOF (~40 B per node more than now, doc/performance.md "Memory
  // at set-up"); kept as an upper bound, not measured on its own: in the
  // runs of doc/user-guide.md, "Memory" it is 2 % (Hex8) to 14 % (Quad4) of
  // the estimate.
  return 200.0 * nodes + (64.0 + 24.0 * nodesPerElement) * elements;
}

void Mesh::setMemoryBudget(double bytes, std::string source, std::string hint) {
  memoryBudget_ = bytes;
  budgetSource_ = std::move(source);
  budgetHint_ = std::move(hint);
}

void Mesh::requireRoom(double nodes, double elements, int nodesPerElement, const std::string& path) const {
  if (memoryBudget_ < 0.0) return;
  const double have = replicatedBytes(numNodes(), numElements(), 27);
  // The generator's grid of points (coordinates and node numbers, 28 B a
  // point) exists while it runs; its cells are visited one at a time.
  const double need = have + replicatedBytes(nodes, elements, nodesPerElement) + 28.0 * nodes;
  DDC_INPUT_REQUIRE(need <= memoryBudget_,
                    "'" << path << "': the mesh would have " << std::llround(nodes) << " nodes and "
                        << std::llround(elements) << " elements, about " << formatBytes(need)
                        << (isPart_ ? " on this rank (its share of the mesh)"
                                    : " on every rank (each rank holds the whole mesh)")
                        << ", more than the " << formatBytes(memoryBudget_) << " available ("
                        << budgetSource_ << ")" << (budgetHint_.empty() ? "" : "; " + budgetHint_));
}

}  // namespace ddc
