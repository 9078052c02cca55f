#include "DDC_Memory.hpp"

#include <mpi.h>
#include <sys/resource.h>

#include <Teuchos_CommHelpers.hpp>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <sstream>

#include "DDC_MpiRecords.hpp"

namespace ddc {

namespace {

/// A "Name:   1234 kB" line of a /proc file, in bytes; -1 if absent.
double procKiB(const char* file, const char* name) {
  std::ifstream in(file);
  std::string line;
  const std::string key = std::string(name) + ":";
  while (std::getline(in, line))
    if (line.compare(0, key.size(), key) == 0) {
      std::istringstream is(line.substr(key.size()));
      double kib = -1.0;
      is >> kib;
      return kib >= 0.0 ? kib * 1024.0 : -1.0;
    }
  return -1.0;
}

/// A cgroup v2 file holding one number of bytes ("max": none); -1 if absent.
double cgroupBytes(const std::string& file) {
  std::ifstream in(file);
  std::string word;
  if (!(in >> word) || word == "max") return -1.0;
  try {
    return std::stod(word);
  } catch (...) {
    return -1.0;
  }
}

/// This process's cgroup v2 directory ("" if none).
std::string cgroupDirectory() {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("0::", 0) == 0) return "/sys/fs/cgroup" + line.substr(3);
  return "";
}

thread_local std::string activity = "starting";

}  // namespace

MemoryLimit availableMemory(const Teuchos::Comm<int>& comm) {
  // Ranks sharing this host (and its memory).
  MPI_Comm host;
  MPI_Comm_split_type(rawComm(comm), MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host);
  int sharing = 1;
  MPI_Comm_size(host, &sharing);
  MPI_Comm_free(&host);
  MemoryLimit mine;
  auto consider = [&](double bytes, const std::string& source) {
    if (bytes >= 0.0 && bytes < mine.bytes) mine = {bytes, source};
  };
  const std::string ranks = sharing == 1 ? "this rank" : "the " + std::to_string(sharing) + " ranks on this host";
  const double hostAvailable = procKiB("/proc/meminfo", "MemAvailable");
  if (hostAvailable >= 0.0)
    consider(hostAvailable / sharing, "MemAvailable " + formatBytes(hostAvailable) + " of this host shared by " + ranks);
  const std::string cg = cgroupDirectory();
  if (!cg.empty()) {
    const double max = cgroupBytes(cg + "/memory.max"), current = cgroupBytes(cg + "/memory.current");
    if (max >= 0.0 && current >= 0.0)
      consider(std::max(0.0, max - current) / sharing,
               "control-group limit " + formatBytes(max) + " (" + formatBytes(current) + " used) shared by " + ranks);
  }
  struct rlimit rl {};
  if (::getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
    const double mapped = procKiB("/proc/self/status", "VmSize");
    consider(std::max(0.0, static_cast<double>(rl.rlim_cur) - std::max(0.0, mapped)),
             "address-space limit " + formatBytes(static_cast<double>(rl.rlim_cur)) + " per process (ulimit -v), " +
                 formatBytes(std::max(0.0, mapped)) + " already mapped");
  }
  // The smallest over the ranks, with its source from the rank that has it.
  struct {
    double bytes;
    int rank;
  } in{std::isfinite(mine.bytes) ? mine.bytes : 1e300, comm.getRank()}, out{};
  MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MINLOC, rawComm(comm));
  std::string source = mine.source;
  int length = static_cast<int>(source.size());
  MPI_Bcast(&length, 1, MPI_INT, out.rank, rawComm(comm));
  source.resize(length);
  MPI_Bcast(&source[0], length, MPI_CHAR, out.rank, rawComm(comm));
  MemoryLimit result;
  if (out.bytes < 1e300) result = {out.bytes, source};
  return result;
}

std::string formatBytes(double bytes) {
  static const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (u < 6 && std::abs(bytes) >= 1024.0) bytes /= 1024.0, ++u;
  char buf[32];
  std::snprintf(buf, sizeof buf, bytes < 10.0 && u > 0 ? "%.1f %s" : "%.0f %s", bytes, units[u]);
  return buf;
}

double peakResidentBytes() {
  struct rusage ru {};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) * 1024.0;  // Linux: KiB
}

Activity::Activity(std::string what) : previous_(std::move(activity)), uncaught_(std::uncaught_exceptions()) {
  activity = std::move(what);
}
Activity::~Activity() {
  if (std::uncaught_exceptions() > uncaught_) return;  // unwinding: keep naming where it happened
  activity = std::move(previous_);
}
const std::string& currentActivity() { return activity; }

}  // namespace ddc
