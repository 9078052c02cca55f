#include "DDC_ExodusFile.hpp"

#include <exodusII.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_ExodusCells.hpp"
#include "DDC_NetcdfClassicExtent.hpp"
#include "DDC_Parameters.hpp"
#include "DDC_ReferenceCell.hpp"

namespace ddc {

namespace {

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

ex_entity_type entityType(ExodusFile::Objects kind) {
  return kind == ExodusFile::Objects::ElementBlocks ? EX_ELEM_BLOCK
         : kind == ExodusFile::Objects::NodeSets    ? EX_NODE_SET
                                                     : EX_SIDE_SET;
}

}  // namespace

ExodusFile::ExodusFile(const std::string& name, const std::string& context) : name_(name), context_(context) {
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

ExodusFile::~ExodusFile() {
  if (id_ >= 0) ex_close(id_);
}

// A classic netCDF file holds all the data its header declares
// (doc/user-guide.md, "Checks of a mesh file"): checked before the library
// opens it, which would read zeros past the end of a file cut short and
// allocate what a corrupt header declares.
void ExodusFile::requireWholeClassicFile() const {
  const NetcdfClassicExtent x = netcdfClassicExtent(name_);
  if (!x.classic) return;
  if (!x.readable)
    fail("its netCDF header cannot be read (" + x.problem +
         "): the file is truncated (cut short) or corrupt; write or copy it again");
  if (bytes() < x.end) {
    std::ostringstream os;
    os << "it has " << std::llround(bytes()) << " bytes, but its header places the data of variable '" << x.variable
       << "' up to byte " << std::llround(x.end)
       << ": the file is truncated (cut short) or its header is corrupt (it declares more than the file holds); "
          "write or copy it again";
    fail(os.str());
  }
}

// The file's container, by its first bytes: netCDF classic (CDF1, 2 or 5:
// every fixed-size variable is stored in full), HDF5 (netCDF-4: may be
// compressed, and unwritten chunks take no room) or neither.
ExodusFile::Format ExodusFile::format() const {
  char magic[4] = {0, 0, 0, 0};
  std::ifstream in(name_, std::ios::binary);
  in.read(magic, 4);
  if (magic[0] == 'C' && magic[1] == 'D' && magic[2] == 'F') return Format::Classic;
  if (magic[0] == '\x89' && magic[1] == 'H' && magic[2] == 'D' && magic[3] == 'F') return Format::Hdf5;
  return Format::Other;
}

double ExodusFile::bytes() const {
  std::error_code ec;
  const auto n = std::filesystem::file_size(name_, ec);
  return ec ? 0.0 : double(n);
}

void ExodusFile::fail(const std::string& what) const {
  DDC_THROW(InputError, context_ << ": Exodus II file '" << name_ << "': " << what);
}

void ExodusFile::check(int status, const std::string& what) const {
  if (status < 0) fail("cannot read " + what + ": " + exodusLibraryError(status));
}

std::vector<int> ExodusFile::ids(Objects kind, const char* what) const {
  const ex_entity_type type = entityType(kind);
  const int n = int(ex_inquire_int(id_, type == EX_ELEM_BLOCK ? EX_INQ_ELEM_BLK
                                        : type == EX_NODE_SET ? EX_INQ_NODE_SETS
                                                              : EX_INQ_SIDE_SETS));
  if (n < 0) fail(std::string("cannot read the number of ") + what);
  std::vector<int> ids(n);
  if (n) check(ex_get_ids(id_, type, ids.data()), what);
  return ids;
}

std::vector<std::string> ExodusFile::names(Objects kind, int count, const char* what) const {
  const int len = std::max(32, int(ex_inquire_int(id_, EX_INQ_DB_MAX_USED_NAME_LENGTH)));
  ex_set_max_name_length(id_, len);
  std::vector<std::vector<char>> buf(count, std::vector<char>(len + 1, '\0'));
  std::vector<char*> p;
  for (auto& b : buf) p.push_back(b.data());
  if (count) check(ex_get_names(id_, entityType(kind), p.data()), what);
  std::vector<std::string> out;
  for (auto& b : buf) out.emplace_back(b.data());
  return out;
}

ExodusBodyHeader::ExodusBodyHeader(const ExodusFile& ex, const std::string& bodyName, CellType type,
                                   const std::string& path, const std::string& wantedBlock)
    : ex_(ex), bodyName_(bodyName), type_(type), bodyDim_(cellDimension(type)), nen_(numCellNodes(type)) {
  char title[MAX_LINE_LENGTH + 1] = {0};
  int numBlocks = 0, numNodeSets = 0, numSideSets = 0;
  ex_.check(ex_get_init(ex_.id(), title, &dim_, &numNodes_, &numElems_, &numBlocks, &numNodeSets, &numSideSets),
            "its sizes");
  if (dim_ != bodyDim_ && !(bodyDim_ == 2 && dim_ == 3))
    ex_.fail("it is " + std::to_string(dim_) + "-D, but the element type " + cellTypeName(type_) + " of body '" +
             bodyName_ + "' is " + std::to_string(bodyDim_) + "-D");
  // The block that is the body: by name or id, or the file's only block.
  ids_ = ex_.ids(ExodusFile::Objects::ElementBlocks, "the element block ids");
  names_ = ex_.names(ExodusFile::Objects::ElementBlocks, int(ids_.size()), "the element block names");
  std::ostringstream list;  // "'name' (id 1), ..." or "none"
  for (size_t b = 0; b < ids_.size(); ++b)
    list << (b ? ", " : "") << "'" << (names_[b].empty() ? std::to_string(ids_[b]) : names_[b]) << "' (id " << ids_[b]
         << ")";
  const std::string blocks = ids_.empty() ? std::string("none") : list.str();
  if (wantedBlock.empty()) {
    if (ids_.size() != 1)
      ex_.fail("it has " + std::to_string(ids_.size()) + " element blocks (" + blocks + "); set '" +
               joinPath(path, "Element Block") + "' to the one that is body '" + bodyName_ + "'");
    block_ = 0;
  } else {
    for (size_t b = 0; b < ids_.size() && block_ < 0; ++b)
      if (names_[b] == wantedBlock || std::to_string(ids_[b]) == wantedBlock) block_ = int(b);
    if (block_ < 0)
      ex_.fail("no element block '" + wantedBlock + "' ('" + joinPath(path, "Element Block") +
               "'); its blocks are " + blocks);
  }
  blockLabel_ =
      "element block '" + (names_[block_].empty() ? std::to_string(ids_[block_]) : names_[block_]) + "'";
  size_.resize(ids_.size()), nodesPerElement_.resize(ids_.size()), type_names_.resize(ids_.size());
  for (size_t b = 0; b < ids_.size(); ++b) {
    char etype[MAX_STR_LENGTH + 1] = {0};
    int n = 0, npe = 0, nedge = 0, nface = 0, nattr = 0;
    ex_.check(ex_get_block(ex_.id(), EX_ELEM_BLOCK, ids_[b], etype, &n, &npe, &nedge, &nface, &nattr),
              "element block " + std::to_string(ids_[b]));
    size_[b] = n, nodesPerElement_[b] = npe, type_names_[b] = upper(etype);
  }
  for (int b = 0; b < block_; ++b) firstElem_ += size_[b];
}

void ExodusBodyHeader::checkBlock() const {
  const auto accepted = exodusElementTypeNames(type_);
  if (std::find(accepted.begin(), accepted.end(), type_names_[block_]) == accepted.end() ||
      nodesPerElement_[block_] != nen_) {
    std::ostringstream os;
    os << blockLabel_ << " has elements of type '" << type_names_[block_] << "' with " << nodesPerElement_[block_]
       << " nodes; the element type " << cellTypeName(type_) << " of body '" << bodyName_ << "' needs " << nen_
       << "-node elements of type";
    for (size_t i = 0; i < accepted.size(); ++i) os << (i ? " or '" : " '") << accepted[i] << "'";
    ex_.fail(os.str());
  }
  if (size_[block_] == 0) ex_.fail(blockLabel_ + " has no elements");
}

void ExodusBodyHeader::requireFileNode(int n) const {
  if (n < 1 || n > numNodes_)
    ex_.fail(blockLabel_ + " names node " + std::to_string(n) + "; the file has nodes 1 to " +
             std::to_string(numNodes_));
}

void ExodusBodyHeader::requireAdmissibleNode(int n, const std::array<double, 3>& x) const {
  if (bodyDim_ == 2 && std::abs(x[2]) > 1e-10 * std::max({1.0, std::abs(x[0]), std::abs(x[1])}))
    ex_.fail("node " + std::to_string(n + 1) + " of " + blockLabel_ + " has z = " + std::to_string(x[2]) +
             ", and body '" + bodyName_ + "' is 2-D (planar meshes in z = 0 only)");
  // Finite coordinates within Mesh::kMaxCoordinate (doc/user-guide.md,
  // "Checks of a mesh file").
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

void ExodusBodyHeader::requireValidElement(int e, const std::array<std::array<double, 3>, 8>& corners) const {
  const CornerJacobian j = cornerJacobian(type_, corners.data());
  if (j.verdict != CornerJacobian::Verdict::Valid)
    ex_.fail("element " + std::to_string(firstElem_ + e + 1) + " (element " + std::to_string(e + 1) + " of " +
             blockLabel_ + ") is " + describeCornerJacobian(type_, j));
}

void ExodusBodyHeader::requireSetNode(const std::string& name, int v) const {
  if (v < 1 || v > numNodes_)
    ex_.fail("node set '" + name + "' names node " + std::to_string(v) + "; the file has nodes 1 to " +
             std::to_string(numNodes_));
}

int ExodusBodyHeader::sideSetFacet(const std::string& name, int elem, int side) const {
  if (elem < 1 || elem > numElems_)
    ex_.fail("side set '" + name + "' names element " + std::to_string(elem) + "; the file has elements 1 to " +
             std::to_string(numElems_));
  const int e = elem - 1 - firstElem_;
  if (e < 0 || e >= size_[block_]) return -1;  // a side of another block
  const int f = exodusFacetOfSide(type_, side);
  if (f < 0)
    ex_.fail("side set '" + name + "' names side " + std::to_string(side) + " of element " + std::to_string(elem) +
             ", and a " + type_names_[block_] + " element has sides 1 to " +
             std::to_string(referenceCell(type_).facets.size()));
  return f;
}

std::string ExodusBodyHeader::setName(ExodusFile::Objects kind, const std::string& name, int id) {
  if (!name.empty()) return name;
  return (kind == ExodusFile::Objects::NodeSets ? "nodeset_" : "sideset_") + std::to_string(id);
}

}  // namespace ddc
