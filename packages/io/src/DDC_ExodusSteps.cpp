// The Exodus II results of an earlier run read back for a restart
// (ExodusWriter::copySteps()): one file or the pieces of one, written on
// any number of ranks, copied into this run's file(s) by node and element
// id, so that a run continued on another number of ranks, or with the
// mesh on every rank instead of in parts, holds every step (doc/user-guide.md,
// "Restart"). Also the names of the pieces (ExodusWriter::piecePath(),
// resultFiles()).
#include <Teuchos_CommHelpers.hpp>
#include <exodusII.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_ExodusWriter.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_ResultFile.hpp"

namespace ddc {

std::string ExodusWriter::piecePath(const std::string& path, int ranks, int rank) {
  const std::string r = std::to_string(rank);
  const size_t digits = std::to_string(ranks).size();
  return path + "." + std::to_string(ranks) + "." + std::string(digits - std::min(digits, r.size()), '0') + r;
}

std::vector<std::string> ExodusWriter::resultFiles(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return {path};
  // The pieces: NAME.P.r in the directory of `path`; P from the first found.
  const fs::path p(path);
  const std::string prefix = p.filename().string() + ".";
  const fs::path directory = p.has_parent_path() ? p.parent_path() : fs::path(".");
  for (const auto& entry : fs::directory_iterator(directory, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    const size_t dot = rest.find('.');
    if (dot == 0 || dot == std::string::npos || rest.find_first_not_of("0123456789.") != std::string::npos) continue;
    const int ranks = std::atoi(rest.substr(0, dot).c_str());
    if (ranks <= 0) continue;
    std::vector<std::string> files;
    for (int r = 0; r < ranks; ++r) {
      files.push_back(piecePath(path, ranks, r));
      if (!fs::is_regular_file(files.back(), ec)) return {};
    }
    return files;
  }
  return {};
}

namespace {

/// One file of an earlier run's results, open for reading: where its nodes
/// and each block's elements go in this rank's file (-1: not there).
struct SourceFile {
  int id = -1;
  std::string path;
  std::vector<int> nodeTarget;
  std::vector<std::vector<int>> blockTarget;  ///< per block: per element of the block
  ~SourceFile() {
    if (id >= 0) ex_close(id);
  }
};

/// The index of `id` in the ascending `ids`, or -1.
int indexOf(const std::vector<long long>& ids, long long id) {
  auto it = std::lower_bound(ids.begin(), ids.end(), id);
  return it != ids.end() && *it == id ? int(it - ids.begin()) : -1;
}

/// Opens `path` and maps its nodes and elements to `mesh`'s by id; returns
/// why it cannot be copied from ("" if it can). `covered` marks the mesh's
/// nodes and elements found.
std::string openSource(SourceFile& f, const std::string& path, const Mesh& mesh, const ExodusVariables& variables,
                       std::vector<char>& nodeCovered, std::vector<char>& elementCovered) {
  f.path = path;
  int cpuWordSize = 8, ioWordSize = 0;
  float version = 0.0f;
  f.id = ex_open(path.c_str(), EX_READ, &cpuWordSize, &ioWordSize, &version);
  if (f.id < 0) return "cannot read '" + path + "': " + exodusLibraryError(f.id);
  auto count = [&](ex_entity_type type) {
    int n = 0;
    return ex_get_variable_param(f.id, type, &n) < 0 ? -1 : n;
  };
  const int64_t nodes = ex_inquire_int(f.id, EX_INQ_NODES), elements = ex_inquire_int(f.id, EX_INQ_ELEM);
  // A piece states the whole mesh's node count; one file is the whole mesh.
  int64_t wholeNodes = nodes;
  {
    int wn = 0, we = 0, wb = 0, wns = 0, wss = 0;
    if (ex_get_init_global(f.id, &wn, &we, &wb, &wns, &wss) >= 0 && wn > 0) wholeNodes = wn;
  }
  if (count(EX_NODAL) != int(variables.nodal.size()) || count(EX_ELEM_BLOCK) != int(variables.element.size()) ||
      count(EX_GLOBAL) != int(variables.global.size()) || wholeNodes != mesh.numGlobalNodes() ||
      int(ex_inquire_int(f.id, EX_INQ_ELEM_BLK)) != mesh.numBodies())
    return "'" + path + "' has other variables or another mesh";
  // Ids in the whole mesh (1-based; without maps, the position).
  std::vector<int> nodeIds(static_cast<size_t>(nodes)), elementIds(static_cast<size_t>(elements));
  if ((nodes > 0 && ex_get_id_map(f.id, EX_NODE_MAP, nodeIds.data()) < 0) ||
      (elements > 0 && ex_get_id_map(f.id, EX_ELEM_MAP, elementIds.data()) < 0))
    return "cannot read the node or element ids of '" + path + "'";
  std::vector<long long> meshNodes(size_t(mesh.numNodes())), meshElements(size_t(mesh.numElements()));
  for (int n = 0; n < mesh.numNodes(); ++n) meshNodes[size_t(n)] = mesh.nodeId(n);
  for (int e = 0; e < mesh.numElements(); ++e) meshElements[size_t(e)] = mesh.elementId(e);
  f.nodeTarget.resize(size_t(nodes));
  for (size_t i = 0; i < nodeIds.size(); ++i) {
    const int n = f.nodeTarget[i] = indexOf(meshNodes, nodeIds[i] - 1);
    if (n >= 0) nodeCovered[size_t(n)] = 1;
  }
  // The elements of block b + 1 follow those of the blocks before it.
  size_t first = 0;
  f.blockTarget.assign(size_t(mesh.numBodies()), {});
  for (int b = 0; b < mesh.numBodies(); ++b) {
    ex_block block{};
    block.id = b + 1;
    block.type = EX_ELEM_BLOCK;
    if (ex_get_block_param(f.id, &block) < 0 || first + size_t(block.num_entry) > elementIds.size())
      return "'" + path + "' has other variables or another mesh";
    const Body& body = mesh.body(b);
    for (int64_t k = 0; k < block.num_entry; ++k) {
      int e = indexOf(meshElements, elementIds[first + size_t(k)] - 1);
      if (e >= 0 && (e < body.firstElement || e >= body.firstElement + body.numElements)) e = -1;
      f.blockTarget[size_t(b)].push_back(e);
      if (e >= 0) elementCovered[size_t(e)] = 1;
    }
    first += size_t(block.num_entry);
  }
  return "";
}

/// Opens every file of `source` and maps it to `mesh`; returns why the
/// steps cannot be copied ("" if they can).
std::string openSources(const std::vector<std::string>& files, const std::string& source, const Mesh& mesh,
                        const ExodusVariables& variables, std::vector<std::unique_ptr<SourceFile>>& in) {
  if (files.empty()) return "cannot read '" + source + "': no such file, nor its pieces";
  std::vector<char> nodeCovered(size_t(mesh.numNodes()), 0), elementCovered(size_t(mesh.numElements()), 0);
  for (const std::string& file : files) {
    in.push_back(std::make_unique<SourceFile>());
    const std::string why = openSource(*in.back(), file, mesh, variables, nodeCovered, elementCovered);
    if (!why.empty()) return why;
  }
  const bool covered = std::count(nodeCovered.begin(), nodeCovered.end(), 0) == 0 &&
                       std::count(elementCovered.begin(), elementCovered.end(), 0) == 0;
  return covered ? "" : "'" + source + "' has other variables or another mesh";
}

/// Step `step` of every variable from the files `in` into the open file
/// `out` (`file`), by id. Returns an error message or "".
std::string copyStep(int step, const std::vector<std::unique_ptr<SourceFile>>& in, int out, const std::string& file,
                     const Mesh& mesh, const ExodusVariables& variables) {
  std::string error;
  std::vector<double> values, column;
  // Variable `var` of block `id` from every file into `column`.
  auto read = [&](ex_entity_type type, int var, int64_t id, const SourceFile& f, const std::vector<int>& target) {
    values.resize(target.size());
    if (target.empty()) return true;
    const int r = ex_get_var(f.id, step, type, var, id, int64_t(target.size()), values.data());
    if (r < 0) error = "cannot read step " + std::to_string(step) + " of '" + f.path + "': " + exodusLibraryError(r);
    for (size_t k = 0; r >= 0 && k < target.size(); ++k)
      if (target[k] >= 0) column[size_t(target[k])] = values[k];
    return r >= 0;
  };
  auto write = [&](ex_entity_type type, int var, int64_t id, int64_t length, const double* data) {
    const int w = length > 0 ? ex_put_var(out, step, type, var, id, length, data) : 0;
    if (w < 0)
      error = "cannot write step " + std::to_string(step) + " of the Exodus II results '" + file +
              "': " + exodusLibraryError(w);
    return w >= 0;
  };
  double time = 0.0;
  bool ok = ex_get_time(in.front()->id, step, &time) >= 0 && ex_put_time(out, step, &time) >= 0;
  if (!ok) return "cannot copy the time of step " + std::to_string(step) + " from '" + in.front()->path + "'";
  for (int k = 0; ok && k < int(variables.nodal.size()); ++k) {
    column.assign(size_t(mesh.numNodes()), 0.0);
    for (size_t i = 0; ok && i < in.size(); ++i) ok = read(EX_NODAL, k + 1, 1, *in[i], in[i]->nodeTarget);
    ok = ok && write(EX_NODAL, k + 1, 1, mesh.numNodes(), column.data());
  }
  for (int b = 0; ok && b < mesh.numBodies(); ++b)
    for (int k = 0; ok && k < int(variables.element.size()); ++k) {
      column.assign(size_t(mesh.numElements()), 0.0);
      for (size_t i = 0; ok && i < in.size(); ++i)
        ok = read(EX_ELEM_BLOCK, k + 1, b + 1, *in[i], in[i]->blockTarget[size_t(b)]);
      const Body& body = mesh.body(b);
      ok = ok && write(EX_ELEM_BLOCK, k + 1, b + 1, body.numElements, column.data() + body.firstElement);
    }
  const int numGlobal = int(variables.global.size());
  if (ok && numGlobal > 0) {
    values.resize(size_t(numGlobal));
    const int r = ex_get_var(in.front()->id, step, EX_GLOBAL, 1, 0, numGlobal, values.data());
    if (r < 0) return "cannot read step " + std::to_string(step) + " of '" + in.front()->path + "'";
    write(EX_GLOBAL, 1, 0, numGlobal, values.data());
  }
  return error;
}

}  // namespace

std::pair<int, std::string> ExodusWriter::copySteps(const std::string& source, int count) {
  // Rank 0 lists the files; every writing rank reads all of them.
  std::vector<std::string> files = comm_->getRank() == 0 ? resultFiles(source) : std::vector<std::string>();
  files = broadcastStrings(*comm_, files);
  std::string error, shortfall;
  int copied = 0;
  if (writes() && exoid_ >= 0) {
    std::vector<std::unique_ptr<SourceFile>> in;
    shortfall = openSources(files, source, mesh_, variables_, in);
    int available = count;
    for (const auto& f : in) available = std::min(available, int(ex_inquire_int(f->id, EX_INQ_TIME)));
    const int n = shortfall.empty() ? available : 0;
    if (shortfall.empty() && n < count)
      shortfall = "'" + source + "' has " + std::to_string(available) + " of the " + std::to_string(count) +
                  " steps before the checkpoint";
    for (int step = 1; error.empty() && step <= n; ++step)
      if ((error = copyStep(step, in, exoid_, file_, mesh_, variables_)).empty()) copied = step;
    if (error.empty() && n > 0 && ex_update(exoid_) < 0) error = "cannot flush the Exodus II results '" + file_ + "'";
  }
  error = firstErrorOnAnyRank(rawComm(*comm_), error);
  if (!error.empty()) throw OutputError(error);
  // Every rank copies as many steps as the rank that copied fewest, and
  // reports that rank's shortfall.
  int fewest = writes() ? copied : count;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MIN, fewest, Teuchos::outArg(fewest));
  const std::string mine = writes() && copied == fewest ? shortfall : std::string();
  shortfall = firstErrorOnAnyRank(rawComm(*comm_), fewest < count ? mine : std::string());
  steps_ = fewest;
  return {fewest, shortfall};
}

}  // namespace ddc
