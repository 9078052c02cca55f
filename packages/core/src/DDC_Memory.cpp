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

/// The ranks sharing this host's memory: their communicator and count.
struct HostRanks {
  MPI_Comm comm = MPI_COMM_NULL;
  int size = 1;
  explicit HostRanks(const Teuchos::Comm<int>& world) {
    MPI_Comm_split_type(rawComm(world), MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &comm);
    MPI_Comm_size(comm, &size);
  }
  ~HostRanks() { MPI_Comm_free(&comm); }
  HostRanks(const HostRanks&) = delete;
  HostRanks& operator=(const HostRanks&) = delete;
  std::string names() const {
    return size == 1 ? "this rank" : "the " + std::to_string(size) + " ranks on this host";
  }
};

/// What the ranks of this host may still allocate together: the host's
/// MemAvailable or the control group's room, whichever is smaller.
MemoryLimit hostAvailable() {
  MemoryLimit host;
  const double available = procKiB("/proc/meminfo", "MemAvailable");
  if (available >= 0.0) host = {available, "MemAvailable " + formatBytes(available) + " of this host"};
  const std::string cg = cgroupDirectory();
  if (!cg.empty()) {
    const double max = cgroupBytes(cg + "/memory.max"), current = cgroupBytes(cg + "/memory.current");
    if (max >= 0.0 && current >= 0.0 && std::max(0.0, max - current) < host.bytes)
      host = {std::max(0.0, max - current),
              "control-group limit " + formatBytes(max) + " (" + formatBytes(current) + " used)"};
  }
  return host;
}

/// What this process may still map (RLIMIT_AS less its mapped size), and the limit.
MemoryLimit processAvailable(double* limit = nullptr) {
  MemoryLimit process;
  struct rlimit rl {};
  if (::getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
    const double mapped = std::max(0.0, procKiB("/proc/self/status", "VmSize"));
    const double cap = static_cast<double>(rl.rlim_cur);
    if (limit) *limit = cap;
    process = {std::max(0.0, cap - mapped), "address-space limit " + formatBytes(cap) +
                                                " per process (ulimit -v), " + formatBytes(mapped) + " already mapped"};
  }
  return process;
}

/// The rank with the smallest `key` (the lowest such rank on ties).
int smallestRank(const Teuchos::Comm<int>& comm, double key) {
  struct {
    double key;
    int rank;
  } in{std::min(key, 1e300), comm.getRank()}, out{};
  MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MINLOC, rawComm(comm));
  return out.rank;
}

/// `text` of rank `root`, on every rank.
std::string broadcastText(const Teuchos::Comm<int>& comm, int root, std::string text) {
  int length = static_cast<int>(text.size());
  MPI_Bcast(&length, 1, MPI_INT, root, rawComm(comm));
  text.resize(length);
  MPI_Bcast(&text[0], length, MPI_CHAR, root, rawComm(comm));
  return text;
}

std::string percent(double fraction) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%.0f %%", 100.0 * fraction);
  return buf;
}

}  // namespace

MemoryLimit availableMemory(const Teuchos::Comm<int>& comm) {
  const HostRanks host(comm);
  MemoryLimit mine;
  const MemoryLimit shared = hostAvailable();
  if (!shared.source.empty())
    mine = {shared.bytes / host.size, shared.source + " shared by " + host.names()};
  const MemoryLimit process = processAvailable();
  if (!process.source.empty() && process.bytes < mine.bytes) mine = process;
  // The smallest over the ranks, with its source from the rank that has it.
  const int root = smallestRank(comm, mine.bytes);
  MPI_Bcast(&mine.bytes, 1, MPI_DOUBLE, root, rawComm(comm));
  mine.source = broadcastText(comm, root, mine.source);
  return mine;
}

MemoryBudget judgeMemory(double estimate, double hostEstimate, double hostAvailable, int sharing,
                         double processAvailable, double margin) {
  auto ratio = [margin](double available, double need) {
    return need > 0.0 ? available / (margin * need) : std::numeric_limits<double>::infinity();
  };
  const double host = ratio(hostAvailable, hostEstimate), process = ratio(processAvailable, estimate);
  MemoryBudget b;
  b.headroom = std::min(host, process);
  if (std::isinf(b.headroom)) return b;
  b.fits = b.headroom >= 1.0;
  const std::string withMargin = ", less a margin of " + percent(margin - 1.0) + " for what the estimate may miss";
  if (host <= process) {
    b.available = hostAvailable / (margin * std::max(sharing, 1));
    b.source = "host" + withMargin;
  } else {
    b.available = processAvailable / margin;
    b.source = "process" + withMargin;
  }
  return b;
}

MemoryBudget memoryBudget(const Teuchos::Comm<int>& comm, double estimate, double margin) {
  const HostRanks host(comm);
  double hostEstimate = 0.0, hostResident = 0.0, resident = residentBytes();
  MPI_Allreduce(&estimate, &hostEstimate, 1, MPI_DOUBLE, MPI_SUM, host.comm);
  MPI_Allreduce(&resident, &hostResident, 1, MPI_DOUBLE, MPI_SUM, host.comm);
  const MemoryLimit shared = hostAvailable();
  double addressLimit = std::numeric_limits<double>::infinity();
  const MemoryLimit process = processAvailable(&addressLimit);
  MemoryBudget mine = judgeMemory(estimate, hostEstimate, shared.bytes, host.size, process.bytes, margin);
  // Spell out the decisive limit.
  if (mine.source.rfind("host", 0) == 0) {
    std::string what = shared.source + " shared by " + host.names();
    if (host.size > 1) what += ", which need an estimated " + formatBytes(hostEstimate) + " together";
    mine.source = what + mine.source.substr(4);
  } else if (mine.source.rfind("process", 0) == 0) {
    mine.source = process.source + mine.source.substr(7);
  }
  mine.hostLimit = shared.bytes + hostResident;
  mine.processLimit = addressLimit;
  // Every rank decides as the one shortest of memory does.
  const int root = smallestRank(comm, mine.headroom);
  MemoryBudget result = mine;
  result.source = broadcastText(comm, root, mine.source);
  MPI_Bcast(&result.available, 1, MPI_DOUBLE, root, rawComm(comm));
  MPI_Bcast(&result.headroom, 1, MPI_DOUBLE, root, rawComm(comm));
  result.fits = result.headroom >= 1.0;
  return result;
}

std::string memoryAboveBudget(const Teuchos::Comm<int>& comm, const MemoryBudget& budget, double fraction) {
  const HostRanks host(comm);
  double resident = residentBytes(), hostResident = 0.0;
  MPI_Allreduce(&resident, &hostResident, 1, MPI_DOUBLE, MPI_SUM, host.comm);
  std::string why;
  if (std::isfinite(budget.hostLimit) && hostResident > fraction * budget.hostLimit) {
    why = (host.size == 1 ? std::string("this rank holds ") : host.names() + " hold ") + formatBytes(hostResident) +
          ", above " + percent(fraction) + " of the " + formatBytes(budget.hostLimit) +
          " the memory check allowed (what the host had available at the start plus what the ranks held then)";
  } else if (std::isfinite(budget.processLimit)) {
    const double mapped = std::max(0.0, procKiB("/proc/self/status", "VmSize"));
    if (mapped > fraction * budget.processLimit)
      why = "rank " + std::to_string(comm.getRank()) + " maps " + formatBytes(mapped) + ", above " + percent(fraction) +
            " of its address-space limit " + formatBytes(budget.processLimit) + " (ulimit -v)";
  }
  return broadcastText(comm, smallestRank(comm, why.empty() ? 1e300 : comm.getRank()), why);
}

double residentBytes() { return std::max(0.0, procKiB("/proc/self/status", "VmRSS")); }

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
