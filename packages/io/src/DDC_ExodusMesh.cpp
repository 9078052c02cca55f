#include "DDC_ExodusMesh.hpp"

#include <exodusII.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_ExodusCells.hpp"
#include "DDC_NetcdfClassicExtent.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

/// An open Exodus II file, closed on scope exit.
class ExodusFile {
 public:
  ExodusFile(const std::string& name, const std::string& context) : name_(name), context_(context) {
    requireWholeClassicFile();
    ex_opts(0);  // errors come back as return values, not on stderr
    int cpuWordSize = 8, ioWordSize = 0;
    float version = 0.0f;
    id_ = ex_open(name.c_str(), EX_READ, &cpuWordSize, &ioWordSize, &version);
    if (id_ < 0)
      fail("cannot open it as an Exodus II file: " + exodusLibraryError(id_) +
           (format() == Format::Other ? std::string()
                                      : "; it starts as a netCDF file, so it is probably truncated (cut short) or "
                                        "corrupt: write or copy it again"));
  }
  ~ExodusFile() {
    if (id_ >= 0) ex_close(id_);
  }
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;
  int id() const { return id_; }
  /// A classic netCDF file holds all the data its header declares
  /// (doc/user-guide.md, "Checks of a mesh file"): checked before the library
  /// opens it, which would read zeros past the end of a file cut short and
  /// allocate what a corrupt header declares.
  void requireWholeClassicFile() const {
    const NetcdfClassicExtent x = netcdfClassicExtent(name_);
    if (!x.classic) return;
    if (!x.readable)
      fail("its netCDF header cannot be read (" + x.problem +
           "): the file is truncated (cut short) or corrupt; write or copy it again");
    if (bytes() < x.end) {
      std::ostringstream os;
      os << "it has " << std::llround(bytes()) << " bytes, but its header places the data of variable '"
         << x.variable << "' up to byte " << std::llround(x.end)
         << ": the file is truncated (cut short) or its header is corrupt (it declares more than the file holds); "
            "write or copy it again";
      fail(os.str());
    }
  }
  /// The file's container, by its first bytes: netCDF classic (CDF1, 2 or 5:
  /// every fixed-size variable is stored in full), HDF5 (netCDF-4: may be
  /// compressed, and unwritten chunks take no room) or neither.
  enum class Format { Classic, Hdf5, Other };
  Format format() const {
    char magic[4] = {0, 0, 0, 0};
    std::ifstream in(name_, std::ios::binary);
    in.read(magic, 4);
    if (magic[0] == 'C' && magic[1] == 'D' && magic[2] == 'F') return Format::Classic;
    if (magic[0] == '\x89' && magic[1] == 'H' && magic[2] == 'D' && magic[3] == 'F') return Format::Hdf5;
    return Format::Other;
  }
  /// The file's size in bytes.
  double bytes() const {
    std::error_code ec;
    const auto n = std::filesystem::file_size(name_, ec);
    return ec ? 0.0 : double(n);
  }
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

namespace {

/// The element blocks of the file, in file order.
struct ExodusBlocks {
  std::vector<int> ids;
  std::vector<std::string> names;
  std::vector<int> size, nodesPerElement;  ///< read by readSizes()
  std::vector<std::string> type;           ///< upper case

  /// "'name' (id 1), ..." or "none", for messages.
  std::string list() const {
    std::ostringstream os;
    for (size_t b = 0; b < ids.size(); ++b)
      os << (b ? ", " : "") << "'" << (names[b].empty() ? std::to_string(ids[b]) : names[b]) << "' (id " << ids[b]
         << ")";
    return ids.empty() ? std::string("none") : os.str();
  }
  void readSizes(const ExodusFile& ex) {
    size.resize(ids.size()), nodesPerElement.resize(ids.size()), type.resize(ids.size());
    for (size_t b = 0; b < ids.size(); ++b) {
      char etype[MAX_STR_LENGTH + 1] = {0};
      int n = 0, npe = 0, nedge = 0, nface = 0, nattr = 0;
      ex.check(ex_get_block(ex.id(), EX_ELEM_BLOCK, ids[b], etype, &n, &npe, &nedge, &nface, &nattr),
               "element block " + std::to_string(ids[b]));
      size[b] = n, nodesPerElement[b] = npe, type[b] = upper(etype);
    }
  }
};

/// One body read from an open file by readExodusBody(), in the steps of
/// read(); every check fails with ExodusFile::fail().
class ExodusBodyReader {
 public:
  ExodusBodyReader(const ExodusFile& ex, Mesh& mesh, const std::string& bodyName, CellType type,
                   const std::string& path)
      : ex_(ex), mesh_(mesh), bodyName_(bodyName), type_(type), path_(path), bodyDim_(cellDimension(type)),
        nen_(numCellNodes(type)), ref_(referenceCell(type)) {}

  int read(const std::string& wantedBlock) {
    readSizes();
    chooseBlock(wantedBlock);
    blocks_.readSizes(ex_);
    requireDeclaredSizesFit();
    checkBlock();
    readNodesAndElements();
    readNodeSets();
    readSideSets();
    return body_;
  }

 private:
  /// The file's sizes; its dimension must be the body's (or 3 for a 2-D body).
  void readSizes() {
    char title[MAX_LINE_LENGTH + 1] = {0};
    int numBlocks = 0, numNodeSets = 0, numSideSets = 0;
    ex_.check(ex_get_init(ex_.id(), title, &dim_, &numNodes_, &numElems_, &numBlocks, &numNodeSets, &numSideSets),
              "its sizes");
    if (dim_ != bodyDim_ && !(bodyDim_ == 2 && dim_ == 3))
      ex_.fail("it is " + std::to_string(dim_) + "-D, but the element type " + cellTypeName(type_) + " of body '" +
               bodyName_ + "' is " + std::to_string(bodyDim_) + "-D");
  }

  /// The block that is the body: by name or id, or the file's only block.
  void chooseBlock(const std::string& wanted) {
    blocks_.ids = ex_.ids(EX_ELEM_BLOCK, "the element block ids");
    blocks_.names = ex_.names(EX_ELEM_BLOCK, int(blocks_.ids.size()), "the element block names");
    if (wanted.empty()) {
      if (blocks_.ids.size() != 1)
        ex_.fail("it has " + std::to_string(blocks_.ids.size()) + " element blocks (" + blocks_.list() +
                 "); set '" + joinPath(path_, "Element Block") + "' to the one that is body '" + bodyName_ + "'");
      block_ = 0;
    } else {
      for (size_t b = 0; b < blocks_.ids.size() && block_ < 0; ++b)
        if (blocks_.names[b] == wanted || std::to_string(blocks_.ids[b]) == wanted) block_ = int(b);
      if (block_ < 0)
        ex_.fail("no element block '" + wanted + "' ('" + joinPath(path_, "Element Block") +
                 "'); its blocks are " + blocks_.list());
    }
    blockLabel_ = "element block '" +
                  (blocks_.names[block_].empty() ? std::to_string(blocks_.ids[block_]) : blocks_.names[block_]) + "'";
  }

  /// The block's elements are of the body's type, and there are some.
  /// Elements are numbered across the blocks in block order: firstElem_.
  void checkBlock() {
    for (int b = 0; b < block_; ++b) firstElem_ += blocks_.size[b];
    const auto accepted = exodusElementTypeNames(type_);
    if (std::find(accepted.begin(), accepted.end(), blocks_.type[block_]) == accepted.end() ||
        blocks_.nodesPerElement[block_] != nen_) {
      std::ostringstream os;
      os << blockLabel_ << " has elements of type '" << blocks_.type[block_] << "' with "
         << blocks_.nodesPerElement[block_] << " nodes; the element type " << cellTypeName(type_) << " of body '"
         << bodyName_ << "' needs " << nen_ << "-node elements of type";
      for (size_t i = 0; i < accepted.size(); ++i) os << (i ? " or '" : " '") << accepted[i] << "'";
      ex_.fail(os.str());
    }
    if (blocks_.size[block_] == 0) ex_.fail(blockLabel_ + " has no elements");
  }

  /// The sizes the header declares fit the memory budget before anything of
  /// those sizes is allocated (Mesh::requireRoom(); doc/user-guide.md,
  /// "Checks of a mesh file"): all the file's coordinates are read, and a
  /// netCDF-4 (HDF5) file may declare more than it stores (compressed or
  /// unwritten chunks), so its size bounds nothing. (A classic file was
  /// checked against its size when it was opened.)
  void requireDeclaredSizesFit() {
    mesh_.requireRoom(double(numNodes_), blocks_.size[block_], nen_, path_);
  }

  /// The body, its nodes (those of the block, in file order) and elements.
  void readNodesAndElements() {
    const int numBlockElems = blocks_.size[block_];
    std::vector<int> conn(size_t(numBlockElems) * nen_);
    ex_.check(ex_get_conn(ex_.id(), EX_ELEM_BLOCK, blocks_.ids[block_], conn.data(), nullptr, nullptr),
              "the connectivity of " + blockLabel_);
    std::vector<double> x(numNodes_), y(numNodes_), z(numNodes_, 0.0);
    ex_.check(ex_get_coord(ex_.id(), x.data(), y.data(), dim_ == 3 ? z.data() : nullptr), "the coordinates");
    local_.assign(numNodes_, -1);
    for (int n : conn) {
      if (n < 1 || n > numNodes_)
        ex_.fail(blockLabel_ + " names node " + std::to_string(n) + "; the file has nodes 1 to " +
                 std::to_string(numNodes_));
      local_[n - 1] = 0;
    }
    mesh_.requireRoom(double(std::count(local_.begin(), local_.end(), 0)), numBlockElems, nen_, path_);
    body_ = mesh_.beginBody(bodyName_, type_);
    for (int n = 0; n < numNodes_; ++n) {
      if (local_[n] < 0) continue;
      if (bodyDim_ == 2 && std::abs(z[n]) > 1e-10 * std::max({1.0, std::abs(x[n]), std::abs(y[n])}))
        ex_.fail("node " + std::to_string(n + 1) + " of " + blockLabel_ + " has z = " + std::to_string(z[n]) +
                 ", and body '" + bodyName_ + "' is 2-D (planar meshes in z = 0 only)");
      requireAdmissibleCoordinates(n, {x[n], y[n], z[n]});
      local_[n] = mesh_.addNode(x[n], y[n], bodyDim_ == 3 ? z[n] : 0.0);
    }
    addElements(conn);
    bodyFirstElement_ = mesh_.body(body_).firstElement;
  }

  /// Node n (0-based) of the file has finite coordinates within
  /// Mesh::kMaxCoordinate (doc/user-guide.md, "Checks of a mesh file").
  void requireAdmissibleCoordinates(int n, const std::array<double, 3>& x) const {
    for (int c = 0; c < dim_; ++c)
      if (!Mesh::admissibleCoordinate(x[c])) {
        std::ostringstream os;
        os << "node " << n + 1 << " of " << blockLabel_ << " has " << "xyz"[c] << " = " << x[c]
           << "; every coordinate must be a finite number within +-" << Mesh::kMaxCoordinate
           << " (the coordinate limit: lengths this large overflow in the element arithmetic): fix the node or "
              "choose other length units";
        ex_.fail(os.str());
      }
  }

  /// The block's elements in DDContact's node order, each valid.
  void addElements(const std::vector<int>& conn) {
    const auto& order = exodusNodeOrder(type_);
    for (int e = 0; e < blocks_.size[block_]; ++e) {
      int nodes[27];
      for (int i = 0; i < nen_; ++i) nodes[order[i]] = local_[conn[size_t(e) * nen_ + i] - 1];
      std::array<std::array<double, 3>, 8> corners;
      for (int i = 0; i < ref_.numCorners; ++i) corners[i] = mesh_.coord(nodes[i]);
      const CornerJacobian j = cornerJacobian(type_, corners.data());
      if (j.verdict != CornerJacobian::Verdict::Valid)
        ex_.fail("element " + std::to_string(firstElem_ + e + 1) + " (element " + std::to_string(e + 1) + " of " +
                 blockLabel_ + ") is " + describeCornerJacobian(type_, j));
      mesh_.addElement(nodes);
    }
  }

  /// The node sets, restricted to the body's nodes (empty ones dropped).
  void readNodeSets() {
    const std::vector<int> nsIds = ex_.ids(EX_NODE_SET, "the node set ids");
    const std::vector<std::string> nsNames = ex_.names(EX_NODE_SET, int(nsIds.size()), "the node set names");
    for (size_t s = 0; s < nsIds.size(); ++s) {
      const std::string name = nsNames[s].empty() ? "nodeset_" + std::to_string(nsIds[s]) : nsNames[s];
      int n = 0, ndf = 0;
      ex_.check(ex_get_set_param(ex_.id(), EX_NODE_SET, nsIds[s], &n, &ndf), "node set '" + name + "'");
      std::vector<int> entries(n);
      if (n)
        ex_.check(ex_get_set(ex_.id(), EX_NODE_SET, nsIds[s], entries.data(), nullptr), "node set '" + name + "'");
      std::vector<int> nodes;
      for (int v : entries) {
        if (v < 1 || v > numNodes_)
          ex_.fail("node set '" + name + "' names node " + std::to_string(v) + "; the file has nodes 1 to " +
                   std::to_string(numNodes_));
        if (local_[v - 1] >= 0) nodes.push_back(local_[v - 1]);
      }
      if (!nodes.empty()) mesh_.addNodeSet(body_, name, std::move(nodes));
    }
  }

  /// The side sets, restricted to the body's elements (empty ones dropped).
  void readSideSets() {
    const std::vector<int> ssIds = ex_.ids(EX_SIDE_SET, "the side set ids");
    const std::vector<std::string> ssNames = ex_.names(EX_SIDE_SET, int(ssIds.size()), "the side set names");
    for (size_t s = 0; s < ssIds.size(); ++s) {
      const std::string name = ssNames[s].empty() ? "sideset_" + std::to_string(ssIds[s]) : ssNames[s];
      int n = 0, ndf = 0;
      ex_.check(ex_get_set_param(ex_.id(), EX_SIDE_SET, ssIds[s], &n, &ndf), "side set '" + name + "'");
      std::vector<int> elems(n), sides(n);
      if (n)
        ex_.check(ex_get_set(ex_.id(), EX_SIDE_SET, ssIds[s], elems.data(), sides.data()), "side set '" + name + "'");
      std::vector<Segment> segments;
      for (int k = 0; k < n; ++k) {
        if (elems[k] < 1 || elems[k] > numElems_)
          ex_.fail("side set '" + name + "' names element " + std::to_string(elems[k]) +
                   "; the file has elements 1 to " + std::to_string(numElems_));
        const int e = elems[k] - 1 - firstElem_;
        if (e < 0 || e >= blocks_.size[block_]) continue;  // a side of another block
        const int f = exodusFacetOfSide(type_, sides[k]);
        if (f < 0)
          ex_.fail("side set '" + name + "' names side " + std::to_string(sides[k]) + " of element " +
                   std::to_string(elems[k]) + ", and a " + blocks_.type[block_] + " element has sides 1 to " +
                   std::to_string(ref_.facets.size()));
        segments.push_back(mesh_.makeSegment(bodyFirstElement_ + e, f));
      }
      if (!segments.empty()) mesh_.addSideSet(body_, name, std::move(segments));
    }
  }

  const ExodusFile& ex_;
  Mesh& mesh_;
  const std::string& bodyName_;
  const CellType type_;
  const std::string& path_;
  const int bodyDim_;
  const int nen_;
  const ReferenceCell& ref_;
  int dim_ = 0, numNodes_ = 0, numElems_ = 0;  ///< of the file
  ExodusBlocks blocks_;
  int block_ = -1;     ///< index into blocks_
  std::string blockLabel_;
  int firstElem_ = 0;  ///< 0-based file element number of the block's first element
  std::vector<int> local_;  ///< file node (0-based) -> node of the mesh, -1: not in the body
  int body_ = -1;
  int bodyFirstElement_ = 0;
};

}  // namespace

int readExodusBody(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                   const std::string& path, const std::string& baseDirectory) {
  validateLevel(params, *ExodusMeshReader::getValidParameters(), path);
  const std::string file = params.get<std::string>("File");
  DDC_INPUT_REQUIRE(!file.empty(), "parameter '" << joinPath(path, "File") << "' is required: the Exodus II file of body '"
                                                 << bodyName << "'");
  const std::string resolved = resolveDeckFile(file, baseDirectory);
  const ExodusFile ex(resolved, "'" + joinPath(path, "File") + "' (body '" + bodyName + "')");
  return ExodusBodyReader(ex, mesh, bodyName, type, path).read(params.get<std::string>("Element Block"));
}

}  // namespace ddc
