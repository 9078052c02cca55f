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

}  // namespace

ExodusWriter::ExodusWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& path, const Mesh& mesh,
                           ExodusVariables variables)
    : comm_(std::move(comm)), path_(path), mesh_(mesh), variables_(std::move(variables)) {
  const int dim = mesh.dim();
  std::string error;
  if (comm_->getRank() == 0) {
    // Each call below returns < 0 on failure; the first failure is the message.
    auto check = [&](int status, const char* what) {
      if (status < 0 && error.empty())
        error = "cannot write the Exodus II results '" + path_ + "' (" + what + "): " + writeError(path_, status);
      return status >= 0;
    };
    ex_opts(0);  // no messages on stderr, no abort: errors come back here
    int cpuWordSize = 8, ioWordSize = 8;
    exoid_ = ex_create(path_.c_str(), EX_CLOBBER, &cpuWordSize, &ioWordSize);
    if (exoid_ < 0) {
      check(exoid_, "create");
    } else {
      ex_set_max_name_length(exoid_, 80);
      const auto nodeSets = mesh.nodeSetNames();
      const auto sideSets = mesh.sideSetNames();
      bool ok = check(ex_put_init(exoid_, "DDContact results", dim, mesh.numNodes(), mesh.numElements(),
                                  mesh.numBodies(), int64_t(nodeSets.size()), int64_t(sideSets.size())),
                      "init");
      // Reference coordinates.
      std::vector<double> x(mesh.numNodes()), y(mesh.numNodes()), z(mesh.numNodes());
      for (int n = 0; n < mesh.numNodes(); ++n) x[n] = mesh.coord(n)[0], y[n] = mesh.coord(n)[1], z[n] = mesh.coord(n)[2];
      ok = ok && check(ex_put_coord(exoid_, x.data(), y.data(), dim == 3 ? z.data() : nullptr), "coordinates");
      char cx[] = "x", cy[] = "y", cz[] = "z";
      char* coordNames[] = {cx, cy, cz};
      ok = ok && check(ex_put_coord_names(exoid_, coordNames), "coordinate names");
      // One element block per body.
      std::vector<std::string> blockNames;
      for (int b = 0; ok && b < mesh.numBodies(); ++b) {
        const Body& body = mesh.body(b);
        const auto& order = exodusNodeOrder(body.cellType);
        const int nn = int(order.size());
        ok = check(ex_put_block(exoid_, EX_ELEM_BLOCK, b + 1, exodusElementType(body.cellType), body.numElements, nn,
                                0, 0, 0),
                   "element block");
        std::vector<int> conn;
        conn.reserve(size_t(body.numElements) * nn);
        for (int e = body.firstElement; e < body.firstElement + body.numElements; ++e) {
          const int* en = mesh.elementNodes(e);
          for (int i = 0; i < nn; ++i) conn.push_back(en[order[i]] + 1);
        }
        ok = ok && check(ex_put_conn(exoid_, EX_ELEM_BLOCK, b + 1, conn.data(), nullptr, nullptr), "connectivity");
        blockNames.push_back(body.name);
      }
      auto putNames = [&](ex_entity_type type, const std::vector<std::string>& names, const char* what) {
        if (names.empty()) return true;
        NameList list(names);
        return check(ex_put_names(exoid_, type, list.pointers.data()), what);
      };
      ok = ok && putNames(EX_ELEM_BLOCK, blockNames, "block names");
      // Node sets and side sets, ids from 1 in name order.
      for (size_t s = 0; ok && s < nodeSets.size(); ++s) {
        std::vector<int> nodes;
        for (int n : mesh.nodeSet(nodeSets[s])) nodes.push_back(n + 1);
        ok = check(ex_put_set_param(exoid_, EX_NODE_SET, int(s) + 1, int64_t(nodes.size()), 0), "node set") &&
             check(ex_put_set(exoid_, EX_NODE_SET, int(s) + 1, nodes.data(), nullptr), "node set");
      }
      ok = ok && putNames(EX_NODE_SET, nodeSets, "node set names");
      for (size_t s = 0; ok && s < sideSets.size(); ++s) {
        std::vector<int> elements, sides;
        for (const Segment& seg : mesh.sideSet(sideSets[s])) {
          elements.push_back(seg.element + 1);
          sides.push_back(exodusSideNumber(mesh.elementType(seg.element), seg.localSide));
        }
        ok = check(ex_put_set_param(exoid_, EX_SIDE_SET, int(s) + 1, int64_t(elements.size()), 0), "side set") &&
             check(ex_put_set(exoid_, EX_SIDE_SET, int(s) + 1, elements.data(), sides.data()), "side set");
      }
      ok = ok && putNames(EX_SIDE_SET, sideSets, "side set names");
      // Variable names.
      auto putVariables = [&](ex_entity_type type, const std::vector<std::string>& names, const char* what) {
        if (names.empty()) return true;
        NameList list(names);
        return check(ex_put_variable_param(exoid_, type, int(names.size())), what) &&
               check(ex_put_variable_names(exoid_, type, int(names.size()), list.pointers.data()), what);
      };
      ok = ok && putVariables(EX_NODAL, variables_.nodal, "nodal variables") &&
           putVariables(EX_ELEM_BLOCK, variables_.element, "element variables") &&
           putVariables(EX_GLOBAL, variables_.global, "global variables");
      ok = ok && check(ex_update(exoid_), "flush");
    }
  }
  error = firstErrorOnAnyRank(rawComm(*comm_), error);
  if (!error.empty()) {
    if (exoid_ >= 0) ex_close(exoid_);
    exoid_ = -1;
    throw OutputError(error);
  }
}

ExodusWriter::~ExodusWriter() {
  if (exoid_ >= 0) ex_close(exoid_);
}

std::pair<int, std::string> ExodusWriter::copySteps(const std::string& source, int count) {
  const Mesh& mesh = mesh_;
  const int numNodal = int(variables_.nodal.size()), numElement = int(variables_.element.size());
  const int numGlobal = int(variables_.global.size());
  std::string error, shortfall;
  int copied = 0;
  if (comm_->getRank() == 0 && exoid_ >= 0) {
    int cpuWordSize = 8, ioWordSize = 0;
    float version = 0.0f;
    const int in = ex_open(source.c_str(), EX_READ, &cpuWordSize, &ioWordSize, &version);
    if (in < 0) {
      shortfall = "cannot read '" + source + "': " + exodusLibraryError(in);
    } else {
      // The same variables (the same model and kind of analysis).
      auto variables = [](int id, ex_entity_type type) {
        int n = 0;
        return ex_get_variable_param(id, type, &n) < 0 ? -1 : n;
      };
      const int available = int(ex_inquire_int(in, EX_INQ_TIME));
      if (variables(in, EX_NODAL) != numNodal || variables(in, EX_ELEM_BLOCK) != numElement ||
          variables(in, EX_GLOBAL) != numGlobal ||
          int(ex_inquire_int(in, EX_INQ_NODES)) != mesh.numNodes() ||
          int(ex_inquire_int(in, EX_INQ_ELEM_BLK)) != mesh.numBodies()) {
        shortfall = "'" + source + "' has other variables or another mesh";
      } else {
        const int n = std::min(count, available);
        if (n < count)
          shortfall = "'" + source + "' has " + std::to_string(available) + " of the " + std::to_string(count) +
                      " steps before the checkpoint";
        std::vector<double> values;
        auto copy = [&](int step, ex_entity_type type, int var, int64_t id, int64_t length) {
          values.resize(size_t(length));
          const int r = ex_get_var(in, step, type, var, id, length, values.data());
          if (r < 0) {
            error = "cannot read step " + std::to_string(step) + " of '" + source + "': " + exodusLibraryError(r);
            return false;
          }
          const int w = ex_put_var(exoid_, step, type, var, id, length, values.data());
          if (w < 0)
            error = "cannot write step " + std::to_string(step) + " of the Exodus II results '" + path_ +
                    "': " + writeError(path_, w);
          return w >= 0;
        };
        bool ok = true;
        for (int step = 1; ok && step <= n; ++step) {
          double time = 0.0;
          ok = ex_get_time(in, step, &time) >= 0 && ex_put_time(exoid_, step, &time) >= 0;
          if (!ok) error = "cannot copy the time of step " + std::to_string(step) + " from '" + source + "'";
          for (int k = 0; ok && k < numNodal; ++k) ok = copy(step, EX_NODAL, k + 1, 1, mesh.numNodes());
          for (int b = 0; ok && b < mesh.numBodies(); ++b)
            for (int k = 0; ok && k < numElement; ++k)
              ok = copy(step, EX_ELEM_BLOCK, k + 1, b + 1, mesh.body(b).numElements);
          if (ok && numGlobal > 0) ok = copy(step, EX_GLOBAL, 1, 0, int64_t(numGlobal));
          if (ok) copied = step;
        }
        if (ok && ex_update(exoid_) < 0) error = "cannot flush the Exodus II results '" + path_ + "'";
      }
      ex_close(in);
    }
  }
  error = firstErrorOnAnyRank(rawComm(*comm_), error);
  if (!error.empty()) throw OutputError(error);
  shortfall = broadcastStrings(*comm_, {shortfall}).front();
  Teuchos::broadcast(*comm_, 0, Teuchos::outArg(copied));
  steps_ = copied;
  return {copied, shortfall};
}

void ExodusWriter::close() {
  std::string error;
  if (exoid_ >= 0) {
    const int status = ex_close(exoid_);
    exoid_ = -1;
    if (status < 0) error = "cannot close the Exodus II results '" + path_ + "': " + exodusLibraryError(status);
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
  if (comm_->getRank() == 0 && values.global.size() != variables_.global.size())
    bad = std::to_string(values.global.size()) + " global values for " + std::to_string(variables_.global.size()) +
          " names";
  for (int n : values.nodes)
    if (n < 0 || n >= mesh.numNodes()) bad = "node " + std::to_string(n) + " is not in the mesh";
  for (int e : values.elements)
    if (e < 0 || e >= mesh.numElements()) bad = "element " + std::to_string(e) + " is not in the mesh";
  bad = firstErrorOnAnyRank(rawComm(*comm_), bad);
  if (!bad.empty()) throw std::invalid_argument("ExodusWriter::writeStep: " + bad);
  const auto nodal = gatherColumns(*comm_, values.nodes, values.nodal, numNodal, mesh.numNodes());
  const auto element = gatherColumns(*comm_, values.elements, values.element, numElement, mesh.numElements());
  std::string error;
  if (comm_->getRank() == 0 && exoid_ >= 0) {
    auto check = [&](int status, const char* what) {
      if (status < 0 && error.empty())
        error = "cannot write step " + std::to_string(steps_ + 1) + " of the Exodus II results '" + path_ + "' (" +
                what + "): " + writeError(path_, status);
      return status >= 0;
    };
    const int step = steps_ + 1;
    bool ok = true;
    if (simulatedFullDisk(path_)) {
      ok = false;
      error = "cannot write step " + std::to_string(step) + " of the Exodus II results '" + path_ +
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
