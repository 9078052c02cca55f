// Output directory of a run: results are staged and committed as a whole, so
// a failed or killed run never partially overwrites the results of an
// earlier one, and DDContact never removes or replaces a directory it did
// not write (doc/user-guide.md, "The output directory").
#pragma once

#include <string>
#include <vector>

#include <Teuchos_Comm.hpp>
#include <Teuchos_RCP.hpp>

// firstErrorOnAnyRank(): every rank gets the message of the lowest rank
// that had an error, so that all ranks throw together.
#include "DDC_MpiRecords.hpp"

namespace ddc {

/// What a result manifest records about the run that wrote it.
struct RunDescription {
  std::string input;    ///< the input deck (absolute path), "" for an in-memory parameter list
  std::string command;  ///< the command line, "" if not a command-line run
  /// A restart continuing the unfinished run whose staging directory this
  /// is (doc/user-guide.md, "Checkpoints and restart"): the name of its
  /// checkpoint file. A staging directory of an unfinished run that holds
  /// that file is kept as this run's staging directory instead of being
  /// removed. Empty: never kept.
  std::string resumeWith;
};

/// \brief The output directory of one run, written through a staging directory.
///
/// Names (D = the normalised output directory, see finalPath()):
///  - `D/ddcontact-result.txt`, the *manifest*: the mark of a DDContact
///    result. It records the program and version, the input, the command,
///    the start time and a status; a committed result has
///    `status: complete` and lists every file with its size and FNV-1a
///    fingerprint, and every directory.
///  - `D.partial`: the staging directory every writer writes into; its
///    manifest says `status: running` until commit().
///  - `D.old`: the previous result during a commit.
///  - `D.lock`: the lock file; rank 0 holds an advisory lock (fcntl) on it
///    from construction to destruction, so one run at a time uses D.
///
/// Construction (collective): rank 0 normalises the path (absolute, `..`
/// and symbolic links resolved), takes the lock, recovers from an
/// interrupted commit (see recoveryNotes()), refuses what it did not write
/// and creates `D.partial` with a running manifest. It refuses, with an
/// OutputError on every rank that names the directory and what to do:
///  - a D, D.partial or D.old that is not a directory, or a non-empty one
///    without a manifest (someone else's directory);
///  - a D whose manifest does not list all of its files (files added by
///    someone else), or one of whose listed files no longer has the size
///    and fingerprint the manifest records (edited by someone else), or
///    with a directory the manifest does not list;
///  - a D.partial of an unfinished run marked resumable (markResumable())
///    whose file is there, unless RunDescription::resumeWith keeps it;
///  - a D that another run holds (naming its pid, host, input and start).
/// An empty directory counts as nothing to lose and may be used.
///
/// commit() (collective): every rank has closed its files; rank 0 writes
/// the complete manifest (temporary file, fsync, rename), renames D to
/// D.old, D.partial to D (both within one parent directory, synced) and
/// removes D.old, then releases the lock before returning on any rank. At every instant D, D.old and D.partial hold together the
/// complete old or the complete new result, and the next run finishes or
/// undoes the interrupted commit without deleting the only complete result.
///
/// A run that fails never calls commit(): D is untouched and D.partial is
/// left for inspection if anything was written into it (the next run removes
/// it unless it was marked resumable, markResumable(); if nothing but the
/// manifest is there, the destructor removes it). The
/// destructor releases the lock and never commits.
///
/// All ranks must see the same file system (the usual shared-file-system
/// setup of MPI runs): rank 0 creates, renames and removes; every rank
/// writes its own files.
class OutputDirectory {
 public:
  /// Name of the manifest inside a result directory.
  static constexpr const char* manifestFileName() { return "ddcontact-result.txt"; }

  /// The final directory finalPath() names for `dir` (absolute, `.`, `..`
  /// and symbolic links resolved, no trailing separator); not collective.
  /// \throws InputError for a path that does not end in a directory name
  static std::string normalisedPath(const std::string& dir);

  /// Collective. See the class documentation.
  /// \throws InputError on every rank for an unusable path (empty, ending in
  ///   "." or "..", the root), OutputError on every rank for the refusals
  ///   listed above and for file-system errors (naming the path and the
  ///   operating system's reason).
  OutputDirectory(Teuchos::RCP<const Teuchos::Comm<int>> comm, std::string finalDir,
                  RunDescription run = RunDescription());
  ~OutputDirectory();

  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  /// Where to write: the staging directory before commit(), the final
  /// directory after it.
  const std::string& path() const { return committed_ ? finalDir_ : stagingDir_; }

  /// The directory the results end up in after commit(): absolute, with
  /// `.`/`..` and symbolic links resolved, without a trailing separator.
  const std::string& finalPath() const { return finalDir_; }

  /// The staging directory, `finalPath() + ".partial"`.
  const std::string& stagingPath() const { return stagingDir_; }

  /// The lock file, `finalPath() + ".lock"`.
  std::string lockPath() const { return finalDir_ + ".lock"; }

  /// Whether commit() has completed.
  bool committed() const { return committed_; }

  /// What construction did to recover from earlier runs (one sentence per
  /// action, e.g. that an interrupted commit was completed); the same on
  /// every rank. Print them: nothing is removed silently.
  const std::vector<std::string>& recoveryNotes() const { return notes_; }

  /// Collective. Publishes the staging directory as `finalPath()` (see the
  /// class documentation). Every rank must have closed its files before
  /// calling. A second call is a no-op.
  /// \throws OutputError on every rank if the commit fails; the earlier
  ///   result stays (or is restored) complete.
  void commit();

  /// Collective; before commit(). Marks the staging directory as that of a
  /// run that stopped or failed leaving `file` (its checkpoint) to continue
  /// from: a later run into the same directory refuses to remove it unless
  /// it continues it (RunDescription::resumeWith). Does nothing if `file` is
  /// not in the staging directory; a failure to mark is not reported (the
  /// run is ending with its own error).
  void markResumable(const std::string& file);

  /// The communicator the directory was created with.
  const Teuchos::RCP<const Teuchos::Comm<int>>& comm() const { return comm_; }

 private:
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::string finalDir_;
  std::string stagingDir_;
  RunDescription run_;
  std::string started_;
  std::vector<std::string> notes_;
  int lockFd_ = -1;  ///< rank 0: the descriptor holding the lock
  bool committed_ = false;
};

}  // namespace ddc
