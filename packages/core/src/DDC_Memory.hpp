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

/// The memory check of a run: its estimate, with a margin for what the
/// estimate may miss, against what the ranks of each host share (MemAvailable
/// or the control group's limit, whichever is smaller) and what each process
/// may map (RLIMIT_AS). Also the limits a running analysis watches
/// (memoryAboveBudget()).
struct MemoryBudget {
  bool fits = true;
  /// What the decisive limit offers over what is needed with the margin
  /// (fits: >= 1).
  double headroom = std::numeric_limits<double>::infinity();
  /// What a rank may plan for once the margin is taken off: the decisive
  /// limit per rank divided by the margin (infinity: no limit found).
  double available = std::numeric_limits<double>::infinity();
  /// The decisive limit, e.g. "MemAvailable 23 GiB of this host shared by the
  /// 8 ranks on this host, which need an estimated 23 GiB together, less a
  /// margin of 25 % for what the estimate may miss"
  std::string source;
  /// Bytes the ranks of this host may hold together: their resident size at
  /// the check plus what the host then had available.
  double hostLimit = std::numeric_limits<double>::infinity();
  /// Bytes of address space this process may map (RLIMIT_AS).
  double processLimit = std::numeric_limits<double>::infinity();
};

/// Collective. \param estimate this rank's estimated growth in bytes
/// \param margin the factor (>= 1) the estimate is multiplied by
/// Every rank gets the same `fits`, `headroom`, `available` and `source`
/// (those of the rank that is shortest of memory); the limits are each
/// rank's own.
MemoryBudget memoryBudget(const Teuchos::Comm<int>& comm, double estimate, double margin);

/// The decision of memoryBudget() on given figures (for tests): the
/// host's ranks need `hostEstimate` together and have `hostAvailable`
/// (`sharing` ranks), this process needs `estimate` and may still map
/// `processAvailable`. Returns fits, available (per rank, after the margin)
/// and which limit decides ("host" or "process" in `source`).
MemoryBudget judgeMemory(double estimate, double hostEstimate, double hostAvailable, int sharing,
                         double processAvailable, double margin);

/// Collective: "" while the ranks stay within `fraction` of the budget's
/// limits; else what is above it, e.g. "the 2 ranks on this host hold
/// 21 GiB, above 90 % of the 22 GiB the memory check allowed them" (the
/// same text on every rank).
std::string memoryAboveBudget(const Teuchos::Comm<int>& comm, const MemoryBudget& budget, double fraction);

/// Resident size of this process now (bytes; /proc/self/status VmRSS).
double residentBytes();

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
