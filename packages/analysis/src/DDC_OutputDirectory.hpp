// Output directory of a run: results are staged and committed as a whole, so
// a failed run never partially overwrites the results of an earlier one
// (DESIGN.md §4, "without overwriting earlier results").
#pragma once

#include <string>

#include <Teuchos_Comm.hpp>
#include <Teuchos_RCP.hpp>

namespace ddc {

/// \brief The output directory of one run, written through a staging directory.
///
/// Construction (collective) makes rank 0 create a fresh, empty staging
/// directory `finalDir + ".partial"` (an old staging directory from an earlier
/// failed run is removed first; missing parent directories are created).
/// Every writer (HistoryWriter, VtkWriter, ...) writes into path().
///
/// commit() (collective) makes the results visible under `finalDir`: rank 0
/// renames an existing `finalDir` to `finalDir + ".old"`, renames the staging
/// directory to `finalDir` and removes the `.old` tree.  Both renames are
/// within one parent directory, so on a POSIX file system `finalDir` always
/// holds either the complete old or the complete new results.
///
/// If the run fails (an exception propagates and commit() is never called),
/// nothing is committed: the results of an earlier run in `finalDir` stay
/// untouched, and the staging directory `finalDir + ".partial"` is left in
/// place for inspection (it is removed by the next run with the same
/// `finalDir`).  The destructor never commits.
///
/// All ranks must see the same file system (the usual shared-file-system
/// setup of MPI runs): rank 0 creates the directories, every rank writes into
/// them.
///
/// Errors (permission denied, a regular file where a directory is needed,
/// `finalDir` being an existing non-directory, ...) are detected on rank 0,
/// broadcast, and raised as ddc::InputError naming the directory on every
/// rank, so all ranks fail together and none hangs.
class OutputDirectory {
 public:
  /// Collective. Creates the staging directory (see class documentation).
  /// \throws InputError on every rank if `finalDir` is empty or the staging
  ///   directory cannot be created.
  OutputDirectory(Teuchos::RCP<const Teuchos::Comm<int>> comm, std::string finalDir);

  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  /// Where to write: the staging directory before commit(), the final
  /// directory after it.
  const std::string& path() const { return committed_ ? finalDir_ : stagingDir_; }

  /// The directory the results end up in after commit() (normalised, without
  /// a trailing separator).
  const std::string& finalPath() const { return finalDir_; }

  /// The staging directory, `finalPath() + ".partial"`.
  const std::string& stagingPath() const { return stagingDir_; }

  /// Whether commit() has completed.
  bool committed() const { return committed_; }

  /// Collective. Replaces `finalDir` by the staging directory (see class
  /// documentation). Every rank must have finished (closed or flushed) its
  /// files before calling. A second call is a no-op.
  /// \throws InputError on every rank if the renames fail; in that case an
  ///   existing earlier `finalDir` is restored when possible.
  void commit();

  /// The communicator the directory was created with.
  const Teuchos::RCP<const Teuchos::Comm<int>>& comm() const { return comm_; }

 private:
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::string finalDir_;
  std::string stagingDir_;
  bool committed_ = false;
};

/// \brief Collective error agreement for output code.
///
/// Every rank passes its own error message ("" = no error). Returns "" on
/// every rank if no rank had an error, otherwise, on every rank, the message
/// of the lowest rank that had one. Use it after rank-local work (file I/O,
/// validation) and throw if the result is non-empty, so that all ranks throw
/// together and none is left waiting in a later collective call.
std::string firstErrorOnAnyRank(const Teuchos::Comm<int>& comm, const std::string& localError);

}  // namespace ddc
