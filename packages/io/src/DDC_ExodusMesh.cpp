#include "DDC_ExodusMesh.hpp"

#include <exodusII.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <sstream>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_ExodusCells.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

/// An open Exodus II file, closed on scope exit.
class ExodusFile {
 public:
  ExodusFile(const std::string& name, const std::string& context) : name_(name), context_(context) {
    ex_opts(0);  // errors come back as return values, not on stderr
    int cpuWordSize = 8, ioWordSize = 0;
    float version = 0.0f;
    id_ = ex_open(name.c_str(), EX_READ, &cpuWordSize, &ioWordSize, &version);
    if (id_ < 0) fail("cannot open it as an Exodus II file: " + exodusLibraryError(id_));
  }
  ~ExodusFile() {
    if (id_ >= 0) ex_close(id_);
  }
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;
  int id() const { return id_; }
  /// Throws InputError: "<context>: Exodus II file '<name>': <what>".
  [[noreturn]] void fail(const std::string& what) const {
    DDC_THROW(InputError, context_ << ": Exodus II file '" << name_ << "': " << what);
  }
  /// Checks a library call's status.
  void check(int status, const std::string& what) const {
    if (status < 0) fail("cannot read " + what + ": " + exodusLibraryError(status));
  }
  /// Ids of the objects of a type (blocks, node sets, side sets).
  std::vector<int> ids(ex_entity_type type, const char* what) const {
    const int n = int(ex_inquire_int(id_, type == EX_ELEM_BLOCK ? EX_INQ_ELEM_BLK
                                          : type == EX_NODE_SET ? EX_INQ_NODE_SETS
                                                                : EX_INQ_SIDE_SETS));
    if (n < 0) fail(std::string("cannot read the number of ") + what);
    std::vector<int> ids(n);
    if (n) check(ex_get_ids(id_, type, ids.data()), what);
    return ids;
  }
  /// Names of the objects of a type ("" where the file has none).
  std::vector<std::string> names(ex_entity_type type, int count, const char* what) const {
    const int len = std::max(32, int(ex_inquire_int(id_, EX_INQ_DB_MAX_USED_NAME_LENGTH)));
    ex_set_max_name_length(id_, len);
    std::vector<std::vector<char>> buf(count, std::vector<char>(len + 1, '\0'));
    std::vector<char*> p;
    for (auto& b : buf) p.push_back(b.data());
    if (count) check(ex_get_names(id_, type, p.data()), what);
    std::vector<std::string> out;
    for (auto& b : buf) out.emplace_back(b.data());
    return out;
  }

 private:
  std::string name_, context_;
  int id_ = -1;
};

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> ExodusMeshReader::getValidParameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid;
  if (valid.is_null()) {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Exodus"));
    pl->set("File", std::string(""),
            "Exodus II mesh file (required); a relative path is resolved against the directory of the input deck");
    pl->set("Element Block", std::string(""),
            "The element block that is this body, by name or by id; empty: the file's only element block");
    valid = pl;
  }
  return valid;
}

int readExodusBody(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                   const std::string& path, const std::string& baseDirectory) {
  validateLevel(params, *ExodusMeshReader::getValidParameters(), path);
  const std::string file = params.get<std::string>("File");
  DDC_INPUT_REQUIRE(!file.empty(), "parameter '" << joinPath(path, "File") << "' is required: the Exodus II file of body '"
                                                 << bodyName << "'");
  const std::string resolved = resolveDeckFile(file, baseDirectory);
  const ExodusFile ex(resolved, "'" + joinPath(path, "File") + "' (body '" + bodyName + "')");
  const int exo = ex.id();

  // ---- the file's size and the block --------------------------------------
  char title[MAX_LINE_LENGTH + 1] = {0};
  int dim = 0, numNodes = 0, numElems = 0, numBlocks = 0, numNodeSets = 0, numSideSets = 0;
  ex.check(ex_get_init(exo, title, &dim, &numNodes, &numElems, &numBlocks, &numNodeSets, &numSideSets), "its sizes");
  const int bodyDim = cellDimension(type);
  if (dim != bodyDim && !(bodyDim == 2 && dim == 3))
    ex.fail("it is " + std::to_string(dim) + "-D, but the element type " + cellTypeName(type) + " of body '" +
            bodyName + "' is " + std::to_string(bodyDim) + "-D");
  const std::vector<int> blockIds = ex.ids(EX_ELEM_BLOCK, "the element block ids");
  const std::vector<std::string> blockNames = ex.names(EX_ELEM_BLOCK, int(blockIds.size()), "the element block names");
  auto listBlocks = [&] {
    std::ostringstream os;
    for (size_t b = 0; b < blockIds.size(); ++b)
      os << (b ? ", " : "") << "'" << (blockNames[b].empty() ? std::to_string(blockIds[b]) : blockNames[b]) << "' (id "
         << blockIds[b] << ")";
    return blockIds.empty() ? std::string("none") : os.str();
  };
  const std::string wanted = params.get<std::string>("Element Block");
  int block = -1;  // index into blockIds
  if (wanted.empty()) {
    if (blockIds.size() != 1)
      ex.fail("it has " + std::to_string(blockIds.size()) + " element blocks (" + listBlocks() + "); set '" +
              joinPath(path, "Element Block") + "' to the one that is body '" + bodyName + "'");
    block = 0;
  } else {
    for (size_t b = 0; b < blockIds.size() && block < 0; ++b)
      if (blockNames[b] == wanted || std::to_string(blockIds[b]) == wanted) block = int(b);
    if (block < 0)
      ex.fail("no element block '" + wanted + "' ('" + joinPath(path, "Element Block") + "'); its blocks are " +
              listBlocks());
  }
  const std::string blockLabel =
      "element block '" + (blockNames[block].empty() ? std::to_string(blockIds[block]) : blockNames[block]) + "'";
  // Elements are numbered across the blocks in block order: the first
  // element of each block.
  std::vector<int> blockSize(blockIds.size()), blockNodes(blockIds.size());
  std::vector<std::string> blockType(blockIds.size());
  for (size_t b = 0; b < blockIds.size(); ++b) {
    char etype[MAX_STR_LENGTH + 1] = {0};
    int n = 0, npe = 0, nedge = 0, nface = 0, nattr = 0;
    ex.check(ex_get_block(exo, EX_ELEM_BLOCK, blockIds[b], etype, &n, &npe, &nedge, &nface, &nattr),
             "element block " + std::to_string(blockIds[b]));
    blockSize[b] = n, blockNodes[b] = npe, blockType[b] = upper(etype);
  }
  int firstElem = 0;  // 0-based file element number of the block's first element
  for (int b = 0; b < block; ++b) firstElem += blockSize[b];
  const auto accepted = exodusElementTypeNames(type);
  const int nen = numCellNodes(type);
  if (std::find(accepted.begin(), accepted.end(), blockType[block]) == accepted.end() || blockNodes[block] != nen) {
    std::ostringstream os;
    os << blockLabel << " has elements of type '" << blockType[block] << "' with " << blockNodes[block]
       << " nodes; the element type " << cellTypeName(type) << " of body '" << bodyName << "' needs " << nen
       << "-node elements of type";
    for (size_t i = 0; i < accepted.size(); ++i) os << (i ? " or '" : " '") << accepted[i] << "'";
    ex.fail(os.str());
  }
  if (blockSize[block] == 0) ex.fail(blockLabel + " has no elements");

  // ---- nodes and elements ---------------------------------------------------
  std::vector<int> conn(size_t(blockSize[block]) * nen);
  ex.check(ex_get_conn(exo, EX_ELEM_BLOCK, blockIds[block], conn.data(), nullptr, nullptr),
           "the connectivity of " + blockLabel);
  std::vector<double> x(numNodes), y(numNodes), z(numNodes, 0.0);
  ex.check(ex_get_coord(exo, x.data(), y.data(), dim == 3 ? z.data() : nullptr), "the coordinates");
  std::vector<int> local(numNodes, -1);  // file node (0-based) -> node of the body (0-based within it)
  for (int n : conn) {
    if (n < 1 || n > numNodes)
      ex.fail(blockLabel + " names node " + std::to_string(n) + "; the file has nodes 1 to " + std::to_string(numNodes));
    local[n - 1] = 0;
  }
  mesh.requireRoom(double(std::count(local.begin(), local.end(), 0)), blockSize[block], nen, path);
  const int b = mesh.beginBody(bodyName, type);
  for (int n = 0; n < numNodes; ++n) {
    if (local[n] < 0) continue;
    if (bodyDim == 2 && std::abs(z[n]) > 1e-10 * std::max({1.0, std::abs(x[n]), std::abs(y[n])}))
      ex.fail("node " + std::to_string(n + 1) + " of " + blockLabel + " has z = " + std::to_string(z[n]) +
              ", and body '" + bodyName + "' is 2-D (planar meshes in z = 0 only)");
    local[n] = mesh.addNode(x[n], y[n], bodyDim == 3 ? z[n] : 0.0);
  }
  const auto& order = exodusNodeOrder(type);
  const ReferenceCell& ref = referenceCell(type);
  for (int e = 0; e < blockSize[block]; ++e) {
    int nodes[27];
    for (int i = 0; i < nen; ++i) nodes[order[i]] = local[conn[size_t(e) * nen + i] - 1];
    std::array<std::array<double, 3>, 8> corners;
    for (int i = 0; i < ref.numCorners; ++i) corners[i] = mesh.coord(nodes[i]);
    const CornerJacobian j = cornerJacobian(type, corners.data());
    if (j.verdict != CornerJacobian::Verdict::Valid)
      ex.fail("element " + std::to_string(firstElem + e + 1) + " (element " + std::to_string(e + 1) + " of " +
              blockLabel + ") is " + describeCornerJacobian(type, j));
    mesh.addElement(nodes);
  }
  const int bodyFirstElement = mesh.body(b).firstElement;

  // ---- node sets ----------------------------------------------------------
  const std::vector<int> nsIds = ex.ids(EX_NODE_SET, "the node set ids");
  const std::vector<std::string> nsNames = ex.names(EX_NODE_SET, int(nsIds.size()), "the node set names");
  for (size_t s = 0; s < nsIds.size(); ++s) {
    const std::string name = nsNames[s].empty() ? "nodeset_" + std::to_string(nsIds[s]) : nsNames[s];
    int n = 0, ndf = 0;
    ex.check(ex_get_set_param(exo, EX_NODE_SET, nsIds[s], &n, &ndf), "node set '" + name + "'");
    std::vector<int> entries(n);
    if (n) ex.check(ex_get_set(exo, EX_NODE_SET, nsIds[s], entries.data(), nullptr), "node set '" + name + "'");
    std::vector<int> nodes;
    for (int v : entries) {
      if (v < 1 || v > numNodes)
        ex.fail("node set '" + name + "' names node " + std::to_string(v) + "; the file has nodes 1 to " +
                std::to_string(numNodes));
      if (local[v - 1] >= 0) nodes.push_back(local[v - 1]);
    }
    if (!nodes.empty()) mesh.addNodeSet(b, name, std::move(nodes));
  }

  // ---- side sets ----------------------------------------------------------
  const std::vector<int> ssIds = ex.ids(EX_SIDE_SET, "the side set ids");
  const std::vector<std::string> ssNames = ex.names(EX_SIDE_SET, int(ssIds.size()), "the side set names");
  for (size_t s = 0; s < ssIds.size(); ++s) {
    const std::string name = ssNames[s].empty() ? "sideset_" + std::to_string(ssIds[s]) : ssNames[s];
    int n = 0, ndf = 0;
    ex.check(ex_get_set_param(exo, EX_SIDE_SET, ssIds[s], &n, &ndf), "side set '" + name + "'");
    std::vector<int> elems(n), sides(n);
    if (n) ex.check(ex_get_set(exo, EX_SIDE_SET, ssIds[s], elems.data(), sides.data()), "side set '" + name + "'");
    std::vector<Segment> segments;
    for (int k = 0; k < n; ++k) {
      if (elems[k] < 1 || elems[k] > numElems)
        ex.fail("side set '" + name + "' names element " + std::to_string(elems[k]) + "; the file has elements 1 to " +
                std::to_string(numElems));
      const int e = elems[k] - 1 - firstElem;
      if (e < 0 || e >= blockSize[block]) continue;  // a side of another block
      const int f = exodusFacetOfSide(type, sides[k]);
      if (f < 0)
        ex.fail("side set '" + name + "' names side " + std::to_string(sides[k]) + " of element " +
                std::to_string(elems[k]) + ", and a " + blockType[block] + " element has sides 1 to " +
                std::to_string(ref.facets.size()));
      segments.push_back(mesh.makeSegment(bodyFirstElement + e, f));
    }
    if (!segments.empty()) mesh.addSideSet(b, name, std::move(segments));
  }
  return b;
}

}  // namespace ddc
