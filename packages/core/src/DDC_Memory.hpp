// Memory: what a rank may still use, and what the process is doing when it
// runs out (doc/user-guide.md, "Memory").
//
// availableMemory() is the smallest of three limits, each shared by the
// ranks of one host: the host's MemAvailable (/proc/meminfo), the memory
// limit of the process's control group (cgroup v2 memory.max less
// memory.current), and the process's own address-space limit (RLIMIT_AS, as
// `ulimit -v` or `prlimit --as` set it) less what it already maps. A run
// whose estimate exceeds it is refused before it allocates (the estimate is
// the caller's: ddc::estimateMemory() for an analysis, Mesh::requireRoom()
// for a mesh being generated).
//
// Activity names what the process is doing, so that a std::bad_alloc
// anywhere can be reported with the phase and its sizes: scopes nest, the
// innermost one is currentActivity().
#pragma once

#include <Teuchos_Comm.hpp>
#include <limits>
#include <string>

namespace ddc {

/// Bytes a rank may still allocate, and the limit that sets it.
struct MemoryLimit {
  double bytes = std::numeric_limits<double>::infinity();
  /// e.g. "MemAvailable 21.3 GiB of this host shared by 2 ranks"; "" if no limit was found
  std::string source;
};

/// Collective: the smallest availability over the ranks (every rank gets the
/// same answer). Reads /proc and /sys only; no limit found gives infinity.
MemoryLimit availableMemory(const Teuchos::Comm<int>& comm);

/// "812 MiB", "3.2 GiB", "1.5 TiB" (binary units, 2 significant digits
/// at least).
std::string formatBytes(double bytes);

/// Peak resident memory of this process so far (bytes; getrusage).
double peakResidentBytes();

/// RAII: while alive, currentActivity() is `what` (e.g. "building the mesh
/// of body 'Block'"). Left by an exception, it stays current, so that the
/// handler that catches a std::bad_alloc can still name it.
class Activity {
 public:
  explicit Activity(std::string what);
  ~Activity();
  Activity(const Activity&) = delete;
  Activity& operator=(const Activity&) = delete;

 private:
  std::string previous_;
  int uncaught_ = 0;
};

/// The innermost live Activity ("starting" when there is none).
const std::string& currentActivity();

}  // namespace ddc
