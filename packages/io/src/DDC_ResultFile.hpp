// Checked writing of result files: every write, sync and close is checked
// and a failure names the path and the operating system's reason, so a full
// disk can never leave a truncated file behind a successful exit
// (doc/user-guide.md, "The output directory").
#pragma once

#include <string>
#include <string_view>

namespace ddc {

/// \brief A result file opened for writing through a POSIX descriptor.
///
/// Data are buffered (64 KiB) and handed to write(2) in a loop that resumes
/// after partial writes and interrupted calls; close() flushes, fsync(2)s and
/// closes, checking each step. Any failure throws ddc::OutputError naming the
/// file and strerror(errno) ("cannot write 'out.partial/history.csv': No
/// space left on device"). The object is rank-local: callers that write on
/// several ranks agree on errors collectively (firstErrorOnAnyRank()).
///
/// The destructor closes a file that was not closed, without syncing and
/// without reporting errors (the error path of a failed run).
class CheckedFile {
 public:
  /// Creates (truncates) `path` with mode 0644.
  /// \param faultName the name fault injection matches (see faultInjection());
  ///        "" means `path` itself.
  /// \throws OutputError if the file cannot be created.
  explicit CheckedFile(std::string path, std::string faultName = "");
  CheckedFile(const CheckedFile&) = delete;
  CheckedFile& operator=(const CheckedFile&) = delete;
  ~CheckedFile();

  /// Appends `data` (buffered). \throws OutputError when a flush fails.
  void write(std::string_view data);
  /// printf-style append (buffered). \throws OutputError when a flush fails.
  void printf(const char* format, ...) __attribute__((format(printf, 2, 3)));
  /// Hands the buffer to the operating system (no fsync).
  void flush();
  /// Flushes, fsync(2)s and closes. \throws OutputError naming the step that failed.
  void close();

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::string faultName_;
  std::string buffer_;
  int fd_ = -1;
  bool faultUsed_ = false;
};

/// Writes `content` to `path` so that `path` holds either its old content or
/// the complete new one: a temporary file in the same directory
/// (`path + ".tmp"`) is written, fsync'ed and closed with every step checked,
/// then renamed over `path`, and the directory is synced.
/// \param faultName as for CheckedFile ("" = `path`).
/// \throws OutputError naming the path and the reason; the temporary file is
///         removed.
void writeFileAtomically(const std::string& path, const std::string& content, const std::string& faultName = "");

/// fsync(2) of a directory, so that renames and new entries in it are durable.
/// \throws OutputError naming the directory.
void syncDirectory(const std::string& directory);

/// \brief Test seam for the failure paths of result writing and committing.
///
/// The environment variable DDCONTACT_FAULT_INJECTION holds comma-separated
/// `action@target` items, read once per process:
///  - `enospc@NAME`: the first write(2) to a result file whose name ends in
///    NAME writes half of its data and then fails with ENOSPC (what a full
///    disk does);
///  - `eio-fsync@NAME`, `eio-close@NAME`: fsync(2) / close(2) of that file
///    fail with EIO;
///  - `eacces@NAME`: creating that file fails with EACCES;
///  - `kill@STAGE`: the process kills itself (SIGKILL) when it reaches the
///    named stage of the output directory's lifecycle (OutputDirectory);
///  - `pause@STAGE=FILE`: the process waits at STAGE until FILE exists (at
///    most 120 s), so that a test can run a second program meanwhile.
///  - `sigterm@N`: rank 0 raises SIGTERM while the analysis solves step N
///    (a stop request, DDC_StopRequest.hpp);
///  - `newton-failure@N`: every attempt at step N fails as a Newton failure
///    does (the analysis' failure path, its checkpoint).
/// Names are matched against the file's path relative to the result
/// directory, e.g. `history.csv`, `vtk/step_00002_piece_0001.vtu`.
/// A file NAME matches a path equal to it or ending in "/NAME"; a STAGE
/// and a step N match exactly.
/// \return whether an item `action@target` is configured for `target`; for
///         `pause` the FILE after '=' is stored in `argument`.
bool faultInjection(const std::string& action, const std::string& target, std::string* argument = nullptr);

/// Whether any fault injection is configured (DDCONTACT_FAULT_INJECTION set).
bool faultInjectionActive();

/// Applies `kill@stage` and `pause@stage=FILE` for `stage` (a no-op unless
/// configured). Called by OutputDirectory at each stage of its lifecycle.
void faultInjectionStage(const std::string& stage);

}  // namespace ddc
