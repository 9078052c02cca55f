#include "DDC_ExodusWriter.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <exodusII.h>

#include <sys/statvfs.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_NodeDirectory.hpp"
#include "DDC_ResultFile.hpp"

namespace ddc {

namespace {

/// Writable copies of `names` and pointers to them, for the Exodus II
/// calls that take char*[].
struct NameList {
  explicit NameList(std::vector<std::string> names) : copies(std::move(names)) {
    for (auto& c : copies) pointers.push_back(c.data());
  }
  std::vector<std::string> copies;
  std::vector<char*> pointers;
};

/// Rows of `width` values, each after its entity id, gathered on rank 0 as
/// columns over `count` entities (entities no rank sent stay 0).
/// Collective.
std::vector<std::vector<double>> gatherColumns(const Teuchos::Comm<int>& comm, const std::vector<int>& ids,
                                               const std::vector<double>& rows, size_t width, int count) {
  std::vector<std::vector<double>> send(comm.getSize());
  for (size_t i = 0; width > 0 && i < ids.size(); ++i) {
    send[0].push_back(double(ids[i]));  // exact: ids are far below 2^53
    send[0].insert(send[0].end(), rows.begin() + long(i * width), rows.begin() + long((i + 1) * width));
  }
  const auto received = exchangeRecords(rawComm(comm), send);
  std::vector<std::vector<double>> columns;
  if (comm.getRank() != 0) return columns;
  columns.assign(width, std::vector<double>(size_t(count), 0.0));
  for (size_t r = 0; r + width < received.size(); r += width + 1) {
    const int id = int(received[r]);
    for (size_t k = 0; k < width; ++k) columns[k][size_t(id)] = received[r + 1 + k];
  }
  return columns;
}

/// Rows of `width` values, each after its entity, as columns over `count`
/// entities of this rank's piece (entities not given stay 0).
std::vector<std::vector<double>> ownColumns(const std::vector<int>& ids, const std::vector<double>& rows, size_t width,
                                            int count) {
  std::vector<std::vector<double>> columns(width, std::vector<double>(size_t(count), 0.0));
  for (size_t i = 0; i < ids.size(); ++i)
    for (size_t k = 0; k < width; ++k) columns[k][size_t(ids[i])] = rows[i * width + k];
  return columns;
}

/// The size of every node set and side set in the whole mesh, from the
/// parts (collective): a node counted by the lowest rank that holds it, a
/// side by the rank of its element.
ExodusWriter::SetCounts wholeSetCounts(MPI_Comm comm, const Mesh& part) {
  const NodeDirectory directory(comm, part);
  const int rank = commRank(comm);
  ExodusWriter::SetCounts c;
  for (const std::string& name : part.nodeSetNames()) {
    int mine = 0;
    for (int n : part.nodeSet(name)) mine += directory.lowestHolder()[size_t(n)] == rank;
    c.nodeSets.push_back(mine);
  }
  for (const std::string& name : part.sideSetNames()) c.sideSets.push_back(int(part.sideSet(name).size()));
  MPI_Allreduce(MPI_IN_PLACE, c.nodeSets.data(), int(c.nodeSets.size()), MPI_INT, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, c.sideSets.data(), int(c.sideSets.size()), MPI_INT, MPI_SUM, comm);
  return c;
}

/// Why a write to the Exodus II file `path` failed: the library's message,
/// led by "No space left on device" when that is the cause (the library's
/// error code, or no space left on the file system of `path`).
std::string writeError(const std::string& path, int status) {
  const std::string why = exodusLibraryError(status);
  const char *msg = nullptr, *func = nullptr;
  int code = 0;
  ex_get_err(&msg, &func, &code);
  const std::string directory = std::filesystem::path(path).parent_path().string();
  struct statvfs fs {};
  const bool full = ::statvfs(directory.empty() ? "." : directory.c_str(), &fs) == 0 && fs.f_bavail == 0;
  return code == ENOSPC || full ? std::string(std::strerror(ENOSPC)) + " (" + why + ")" : why;
}

/// The test seam enospc@NAME (faultInjection(), DDC_ResultFile.hpp) for the
/// Exodus II file `path`: true for its first step written, as a full disk.
bool simulatedFullDisk(const std::string& path) {
  static bool used = false;
  if (used || !faultInjection("enospc", path)) return false;
  used = true;
  return true;
}

/// The calls that write one file: each returns < 0 on failure, and the
/// first failure is the message.
struct Calls {
  int exoid;
  std::string file;
  std::string error;
  bool operator()(int status, const char* what) {
    if (status < 0 && error.empty())
      error = "cannot write the Exodus II results '" + file + "' (" + what + "): " + writeError(file, status);
    return status >= 0;
  }
};

/// Names of blocks or sets (none: nothing to write).
bool putNames(Calls& ok, ex_entity_type type, const std::vector<std::string>& names, const char* what) {
  if (names.empty()) return true;
  NameList list(names);
  return ok(ex_put_names(ok.exoid, type, list.pointers.data()), what);
}

/// A piece's place in the whole (Nemesis I): the number of pieces, the
/// whole mesh's counts and its blocks' and sets' sizes, and the ids of the
/// piece's nodes and elements there.
bool putPieceInfo(Calls& ok, const Mesh& mesh, int pieces, const ExodusWriter::SetCounts& sets) {
  char parallel[] = "p";
  const size_t nodeSets = sets.nodeSets.size(), sideSets = sets.sideSets.size();
  if (!ok(ex_put_init_info(ok.exoid, pieces, 1, parallel), "pieces") ||
      !ok(ex_put_init_global(ok.exoid, mesh.numGlobalNodes(), mesh.numGlobalElements(), mesh.numBodies(),
                             int64_t(nodeSets), int64_t(sideSets)),
          "whole-mesh counts"))
    return false;
  std::vector<int> ids(size_t(mesh.numNodes()));
  for (int n = 0; n < mesh.numNodes(); ++n) ids[size_t(n)] = int(mesh.nodeId(n) + 1);
  if (!ok(ex_put_id_map(ok.exoid, EX_NODE_MAP, ids.data()), "node ids")) return false;
  ids.resize(size_t(mesh.numElements()));
  for (int e = 0; e < mesh.numElements(); ++e) ids[size_t(e)] = int(mesh.elementId(e) + 1);
  if (!ok(ex_put_id_map(ok.exoid, EX_ELEM_MAP, ids.data()), "element ids")) return false;
  auto from1 = [](size_t n) {
    std::vector<int> v(n);
    for (size_t i = 0; i < n; ++i) v[i] = int(i) + 1;
    return v;
  };
  std::vector<int> blockIds = from1(size_t(mesh.numBodies())), blockCounts, zeros(std::max(nodeSets, sideSets), 0);
  for (int b = 0; b < mesh.numBodies(); ++b) blockCounts.push_back(int(mesh.bodyGlobalElements(b)));
  std::vector<int> nodeSetIds = from1(nodeSets), sideSetIds = from1(sideSets);
  std::vector<int> nodeSetCounts = sets.nodeSets, sideSetCounts = sets.sideSets;
  return (blockIds.empty() || ok(ex_put_eb_info_global(ok.exoid, blockIds.data(), blockCounts.data()), "blocks")) &&
         (nodeSets == 0 ||
          ok(ex_put_ns_param_global(ok.exoid, nodeSetIds.data(), nodeSetCounts.data(), zeros.data()), "node sets")) &&
         (sideSets == 0 ||
          ok(ex_put_ss_param_global(ok.exoid, sideSetIds.data(), sideSetCounts.data(), zeros.data()), "side sets"));
}

/// The reference coordinates and their names.
bool putCoordinates(Calls& ok, const Mesh& mesh) {
  std::vector<double> x(mesh.numNodes()), y(mesh.numNodes()), z(mesh.numNodes());
  for (int n = 0; n < mesh.numNodes(); ++n) x[n] = mesh.coord(n)[0], y[n] = mesh.coord(n)[1], z[n] = mesh.coord(n)[2];
  char cx[] = "x", cy[] = "y", cz[] = "z";
  char* coordNames[] = {cx, cy, cz};
  return ok(ex_put_coord(ok.exoid, x.data(), y.data(), mesh.dim() == 3 ? z.data() : nullptr), "coordinates") &&
         ok(ex_put_coord_names(ok.exoid, coordNames), "coordinate names");
}

/// One element block per body (id b + 1, empty when the mesh has none of
/// its elements), named after it.
bool putBlocks(Calls& ok, const Mesh& mesh) {
  std::vector<std::string> blockNames;
  for (int b = 0; b < mesh.numBodies(); ++b) {
    const Body& body = mesh.body(b);
    const auto& order = exodusNodeOrder(body.cellType);
    const int nn = int(order.size());
    if (!ok(ex_put_block(ok.exoid, EX_ELEM_BLOCK, b + 1, exodusElementType(body.cellType), body.numElements, nn, 0, 0,
                         0),
            "element block"))
      return false;
    std::vector<int> conn;
    conn.reserve(size_t(body.numElements) * nn);
    for (int e = body.firstElement; e < body.firstElement + body.numElements; ++e) {
      const int* en = mesh.elementNodes(e);
      for (int i = 0; i < nn; ++i) conn.push_back(en[order[i]] + 1);
    }
    if (body.numElements > 0 && !ok(ex_put_conn(ok.exoid, EX_ELEM_BLOCK, b + 1, conn.data(), nullptr, nullptr),
                                    "connectivity"))
      return false;
    blockNames.push_back(body.name);
  }
  return putNames(ok, EX_ELEM_BLOCK, blockNames, "block names");
}

/// Node sets and side sets, ids from 1 in name order.
bool putSets(Calls& ok, const Mesh& mesh) {
  const auto nodeSets = mesh.nodeSetNames();
  const auto sideSets = mesh.sideSetNames();
  for (size_t s = 0; s < nodeSets.size(); ++s) {
    std::vector<int> nodes;
    for (int n : mesh.nodeSet(nodeSets[s])) nodes.push_back(n + 1);
    if (!ok(ex_put_set_param(ok.exoid, EX_NODE_SET, int(s) + 1, int64_t(nodes.size()), 0), "node set") ||
        (!nodes.empty() && !ok(ex_put_set(ok.exoid, EX_NODE_SET, int(s) + 1, nodes.data(), nullptr), "node set")))
      return false;
  }
  if (!putNames(ok, EX_NODE_SET, nodeSets, "node set names")) return false;
  for (size_t s = 0; s < sideSets.size(); ++s) {
    std::vector<int> elements, sides;
    for (const Segment& seg : mesh.sideSet(sideSets[s])) {
      elements.push_back(seg.element + 1);
      sides.push_back(exodusSideNumber(mesh.elementType(seg.element), seg.localSide));
    }
    if (!ok(ex_put_set_param(ok.exoid, EX_SIDE_SET, int(s) + 1, int64_t(elements.size()), 0), "side set") ||
        (!elements.empty() &&
         !ok(ex_put_set(ok.exoid, EX_SIDE_SET, int(s) + 1, elements.data(), sides.data()), "side set")))
      return false;
  }
  return putNames(ok, EX_SIDE_SET, sideSets, "side set names");
}

/// The names of the nodal, element and global variables.
bool putVariables(Calls& ok, const ExodusVariables& variables) {
  auto put = [&](ex_entity_type type, const std::vector<std::string>& names, const char* what) {
    if (names.empty()) return true;
    NameList list(names);
    return ok(ex_put_variable_param(ok.exoid, type, int(names.size())), what) &&
           ok(ex_put_variable_names(ok.exoid, type, int(names.size()), list.pointers.data()), what);
  };
  return put(EX_NODAL, variables.nodal, "nodal variables") &&
         put(EX_ELEM_BLOCK, variables.element, "element variables") &&
         put(EX_GLOBAL, variables.global, "global variables");
}

}  // namespace

ExodusWriter::ExodusWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& path, const Mesh& mesh,
                           ExodusVariables variables)
    : comm_(std::move(comm)), path_(path), mesh_(mesh), variables_(std::move(variables)) {
  std::string error;
  file_ = spread() ? piecePath(path_, comm_->getSize(), comm_->getRank()) : path_;
  if (spread()) setCounts_ = wholeSetCounts(rawComm(*comm_), mesh_);
  if (writes()) error = create(file_);
  error = firstErrorOnAnyRank(rawComm(*comm_), error);
  if (!error.empty()) {
    if (exoid_ >= 0) ex_close(exoid_);
    exoid_ = -1;
    throw OutputError(error);
  }
}

std::string ExodusWriter::create(const std::string& file) {
  const Mesh& mesh = mesh_;
  ex_opts(0);  // no messages on stderr, no abort: errors come back here
  int cpuWordSize = 8, ioWordSize = 8;
  exoid_ = ex_create(file.c_str(), EX_CLOBBER, &cpuWordSize, &ioWordSize);
  Calls ok{exoid_, file};
  if (exoid_ < 0) {
    ok(exoid_, "create");
    return ok.error;
  }
  ex_set_max_name_length(exoid_, 80);
  if (ok(ex_put_init(exoid_, "DDContact results", mesh.dim(), mesh.numNodes(), mesh.numElements(), mesh.numBodies(),
                     int64_t(mesh.nodeSetNames().size()), int64_t(mesh.sideSetNames().size())),
         "init") &&
      (!spread() || putPieceInfo(ok, mesh, comm_->getSize(), setCounts_)) && putCoordinates(ok, mesh) &&
      putBlocks(ok, mesh) && putSets(ok, mesh) && putVariables(ok, variables_))
    ok(ex_update(exoid_), "flush");
  return ok.error;
}

ExodusWriter::~ExodusWriter() {
  if (exoid_ >= 0) ex_close(exoid_);
}

void ExodusWriter::close() {
  std::string error;
  if (exoid_ >= 0) {
    const int status = ex_close(exoid_);
    exoid_ = -1;
    if (status < 0) error = "cannot close the Exodus II results '" + file_ + "': " + exodusLibraryError(status);
  }
  error = firstErrorOnAnyRank(rawComm(*comm_), error);
  if (!error.empty()) throw OutputError(error);
}

void ExodusWriter::writeStep(double time, const ExodusStepValues& values) {
  const Mesh& mesh = mesh_;
  const size_t numNodal = variables_.nodal.size(), numElement = variables_.element.size();
  std::string bad;
  if (values.nodal.size() != values.nodes.size() * numNodal ||
      values.element.size() != values.elements.size() * numElement)
    bad = "rows of another width than the variables";
  if (writes() && values.global.size() != variables_.global.size())
    bad = std::to_string(values.global.size()) + " global values for " + std::to_string(variables_.global.size()) +
          " names";
  for (int n : values.nodes)
    if (n < 0 || n >= mesh.numNodes()) bad = "node " + std::to_string(n) + " is not in the mesh";
  for (int e : values.elements)
    if (e < 0 || e >= mesh.numElements()) bad = "element " + std::to_string(e) + " is not in the mesh";
  bad = firstErrorOnAnyRank(rawComm(*comm_), bad);
  if (!bad.empty()) throw std::invalid_argument("ExodusWriter::writeStep: " + bad);
  const auto nodal = spread() ? ownColumns(values.nodes, values.nodal, numNodal, mesh.numNodes())
                              : gatherColumns(*comm_, values.nodes, values.nodal, numNodal, mesh.numNodes());
  const auto element = spread()
                           ? ownColumns(values.elements, values.element, numElement, mesh.numElements())
                           : gatherColumns(*comm_, values.elements, values.element, numElement, mesh.numElements());
  std::string error;
  if (writes() && exoid_ >= 0) {
    auto check = [&](int status, const char* what) {
      if (status < 0 && error.empty())
        error = "cannot write step " + std::to_string(steps_ + 1) + " of the Exodus II results '" + file_ + "' (" +
                what + "): " + writeError(file_, status);
      return status >= 0;
    };
    const int step = steps_ + 1;
    bool ok = true;
    if (simulatedFullDisk(path_)) {
      ok = false;
      error = "cannot write step " + std::to_string(step) + " of the Exodus II results '" + file_ +
              "' (time): " + std::strerror(ENOSPC) + " (fault injection)";
    }
    ok = ok && check(ex_put_time(exoid_, step, &time), "time");
    for (size_t k = 0; ok && k < numNodal; ++k)
      ok = check(ex_put_var(exoid_, step, EX_NODAL, int(k) + 1, 1, mesh.numNodes(), nodal[k].data()),
                 "nodal variable");
    // Element variables per block (the bodies are contiguous element ranges).
    for (int b = 0; ok && b < mesh.numBodies(); ++b) {
      const Body& body = mesh.body(b);
      for (size_t k = 0; ok && k < numElement; ++k)
        ok = check(ex_put_var(exoid_, step, EX_ELEM_BLOCK, int(k) + 1, b + 1, body.numElements,
                              element[k].data() + body.firstElement),
                   "element variable");
    }
    if (ok && !values.global.empty())
      ok = check(ex_put_var(exoid_, step, EX_GLOBAL, 1, 0, int64_t(values.global.size()), values.global.data()),
                 "global variables");
    ok = ok && check(ex_update(exoid_), "flush");
  }
  error = firstErrorOnAnyRank(rawComm(*comm_), error);
  if (!error.empty()) throw OutputError(error);
  ++steps_;
}

}  // namespace ddc
