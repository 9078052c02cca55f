#include "DDC_ExodusMesh.hpp"

#include <exodusII.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_ExodusCells.hpp"
#include "DDC_ExodusFile.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

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

/// One body read whole from an open file by readExodusBody(), in the steps
/// of read(); every check is ExodusBodyHeader's.
class ExodusBodyReader {
 public:
  ExodusBodyReader(const ExodusFile& ex, Mesh& mesh, const std::string& bodyName, CellType type,
                   const std::string& path)
      : ex_(ex), mesh_(mesh), bodyName_(bodyName), type_(type), path_(path), nen_(numCellNodes(type)),
        ref_(referenceCell(type)) {}

  int read(const std::string& wantedBlock) {
    const ExodusBodyHeader header(ex_, bodyName_, type_, path_, wantedBlock);
    h_ = &header;
    // The sizes the header declares fit the memory budget before anything
    // of those sizes is allocated (Mesh::requireRoom(); doc/user-guide.md,
    // "Checks of a mesh file"): all the file's coordinates are read, and a
    // netCDF-4 (HDF5) file may declare more than it stores (compressed or
    // unwritten chunks), so its size bounds nothing. (A classic file was
    // checked against its size when it was opened.)
    mesh_.requireRoom(double(header.fileNodes()), header.blockSize(), nen_, path_);
    header.checkBlock();
    readNodesAndElements();
    readNodeSets();
    readSideSets();
    h_ = nullptr;
    return body_;
  }

 private:
  /// The body, its nodes (those of the block, in file order) and elements.
  void readNodesAndElements() {
    const int numBlockElems = h_->blockSize(), numNodes = h_->fileNodes();
    std::vector<int> conn(size_t(numBlockElems) * nen_);
    ex_.check(ex_get_conn(ex_.id(), EX_ELEM_BLOCK, h_->blockId(), conn.data(), nullptr, nullptr),
              "the connectivity of " + h_->blockLabel());
    std::vector<double> x(numNodes), y(numNodes), z(numNodes, 0.0);
    ex_.check(ex_get_coord(ex_.id(), x.data(), y.data(), h_->fileDim() == 3 ? z.data() : nullptr),
              "the coordinates");
    local_.assign(numNodes, -1);
    for (int n : conn) {
      h_->requireFileNode(n);
      local_[n - 1] = 0;
    }
    mesh_.requireRoom(double(std::count(local_.begin(), local_.end(), 0)), numBlockElems, nen_, path_);
    body_ = mesh_.beginBody(bodyName_, type_);
    for (int n = 0; n < numNodes; ++n) {
      if (local_[n] < 0) continue;
      h_->requireAdmissibleNode(n, {x[n], y[n], z[n]});
      local_[n] = mesh_.addNode(x[n], y[n], cellDimension(type_) == 3 ? z[n] : 0.0);
    }
    addElements(conn);
    bodyFirstElement_ = mesh_.body(body_).firstElement;
  }

  /// The block's elements in DDContact's node order, each valid.
  void addElements(const std::vector<int>& conn) {
    const auto& order = exodusNodeOrder(type_);
    for (int e = 0; e < h_->blockSize(); ++e) {
      int nodes[27];
      for (int i = 0; i < nen_; ++i) nodes[order[i]] = local_[conn[size_t(e) * nen_ + i] - 1];
      std::array<std::array<double, 3>, 8> corners;
      for (int i = 0; i < ref_.numCorners; ++i) corners[i] = mesh_.coord(nodes[i]);
      h_->requireValidElement(e, corners);
      mesh_.addElement(nodes);
    }
  }

  /// The node sets, restricted to the body's nodes (empty ones dropped).
  void readNodeSets() {
    const auto kind = ExodusFile::Objects::NodeSets;
    const std::vector<int> nsIds = ex_.ids(kind, "the node set ids");
    const std::vector<std::string> nsNames = ex_.names(kind, int(nsIds.size()), "the node set names");
    for (size_t s = 0; s < nsIds.size(); ++s) {
      const std::string name = ExodusBodyHeader::setName(kind, nsNames[s], nsIds[s]);
      int n = 0, ndf = 0;
      ex_.check(ex_get_set_param(ex_.id(), EX_NODE_SET, nsIds[s], &n, &ndf), "node set '" + name + "'");
      std::vector<int> entries(n);
      if (n)
        ex_.check(ex_get_set(ex_.id(), EX_NODE_SET, nsIds[s], entries.data(), nullptr), "node set '" + name + "'");
      std::vector<int> nodes;
      for (int v : entries) {
        h_->requireSetNode(name, v);
        if (local_[v - 1] >= 0) nodes.push_back(local_[v - 1]);
      }
      if (!nodes.empty()) mesh_.addNodeSet(body_, name, std::move(nodes));
    }
  }

  /// The side sets, restricted to the body's elements (empty ones dropped).
  void readSideSets() {
    const auto kind = ExodusFile::Objects::SideSets;
    const std::vector<int> ssIds = ex_.ids(kind, "the side set ids");
    const std::vector<std::string> ssNames = ex_.names(kind, int(ssIds.size()), "the side set names");
    for (size_t s = 0; s < ssIds.size(); ++s) {
      const std::string name = ExodusBodyHeader::setName(kind, ssNames[s], ssIds[s]);
      int n = 0, ndf = 0;
      ex_.check(ex_get_set_param(ex_.id(), EX_SIDE_SET, ssIds[s], &n, &ndf), "side set '" + name + "'");
      std::vector<int> elems(n), sides(n);
      if (n)
        ex_.check(ex_get_set(ex_.id(), EX_SIDE_SET, ssIds[s], elems.data(), sides.data()), "side set '" + name + "'");
      std::vector<Segment> segments;
      for (int k = 0; k < n; ++k) {
        const int f = h_->sideSetFacet(name, elems[k], sides[k]);
        if (f >= 0) segments.push_back(mesh_.makeSegment(bodyFirstElement_ + elems[k] - 1 - h_->firstFileElement(), f));
      }
      if (!segments.empty()) mesh_.addSideSet(body_, name, std::move(segments));
    }
  }

  const ExodusFile& ex_;
  Mesh& mesh_;
  const std::string& bodyName_;
  const CellType type_;
  const std::string& path_;
  const int nen_;
  const ReferenceCell& ref_;
  const ExodusBodyHeader* h_ = nullptr;  ///< during read()
  std::vector<int> local_;  ///< file node (0-based) -> node of the mesh, -1: not in the body
  int body_ = -1;
  int bodyFirstElement_ = 0;
};

}  // namespace

int readExodusBody(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                   const std::string& path, const std::string& baseDirectory) {
  const auto ex = openExodusBodyFile(params, bodyName, path, baseDirectory);
  return ExodusBodyReader(*ex, mesh, bodyName, type, path).read(params.get<std::string>("Element Block"));
}

std::unique_ptr<ExodusFile> openExodusBodyFile(Teuchos::ParameterList& params, const std::string& bodyName,
                                               const std::string& path, const std::string& baseDirectory) {
  validateLevel(params, *ExodusMeshReader::getValidParameters(), path);
  const std::string file = params.get<std::string>("File");
  DDC_INPUT_REQUIRE(!file.empty(), "parameter '" << joinPath(path, "File")
                                                 << "' is required: the Exodus II file of body '" << bodyName << "'");
  const std::string resolved = resolveDeckFile(file, baseDirectory);
  return std::make_unique<ExodusFile>(resolved, "'" + joinPath(path, "File") + "' (body '" + bodyName + "')");
}

}  // namespace ddc
