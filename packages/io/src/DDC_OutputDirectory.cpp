#include "DDC_OutputDirectory.hpp"

#include <fcntl.h>
#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <system_error>
#include <thread>
#include <utility>

#include <Teuchos_CommHelpers.hpp>

#include "DDC_Error.hpp"
#include "DDC_FileFingerprint.hpp"
#include "DDC_ResultFile.hpp"

#ifndef DDC_VERSION
#define DDC_VERSION "unknown"
#endif

namespace fs = std::filesystem;

namespace ddc {

namespace {

constexpr const char* kManifestMagic = "ddcontact-result 1";
constexpr const char* kLockMagic = "ddcontact-lock 1";

/// Errors of the decisions on rank 0, carried to every rank with their kind.
struct Failure {
  enum Kind { None, Input, Output } kind = None;
  std::string message;
};

std::string broadcastString(const Teuchos::Comm<int>& comm, const std::string& s) {
  int length = comm.getRank() == 0 ? static_cast<int>(s.size()) : 0;
  Teuchos::broadcast<int, int>(comm, 0, Teuchos::outArg(length));
  std::string out = comm.getRank() == 0 ? s : std::string(length, ' ');
  if (length > 0) Teuchos::broadcast<int, char>(comm, 0, length, &out[0]);
  return out;
}

/// Raises the failure (decided on rank 0, or on any rank) on every rank.
void raiseEverywhere(const Teuchos::Comm<int>& comm, const Failure& f) {
  const std::string tagged = f.kind == Failure::None ? std::string() : (f.kind == Failure::Input ? "I" : "O") + f.message;
  const std::string agreed = firstErrorOnAnyRank(comm, tagged);
  if (agreed.empty()) return;
  if (agreed[0] == 'I') throw InputError(agreed.substr(1));
  throw OutputError(agreed.substr(1));
}

std::string nowUtc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string hostName() {
  char buf[256] = {0};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

std::string oneLine(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

std::string fsError(const fs::filesystem_error& e) {
  std::string m = e.code().message();
  if (!e.path1().empty()) m += " ('" + e.path1().string() + "')";
  return m;
}

/// "/a/b/run/" -> "/a/b/run", absolute, with "." / ".." and symbolic links
/// of the existing part resolved (so "P/sub/.." is P, as the file system sees it).
fs::path normalisedFinalDir(const std::string& finalDir) {
  DDC_INPUT_REQUIRE(!finalDir.empty(), "output directory: the path is empty");
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(finalDir, ec), ec);
  if (ec) p = fs::absolute(finalDir).lexically_normal();
  p = p.lexically_normal();
  if (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  const std::string last = p.filename().string();
  DDC_INPUT_REQUIRE(!last.empty() && last != "." && last != ".." && p != p.root_path(),
                    "output directory '" << finalDir << "' (" << p.string()
                                         << "): expected a path ending in a directory name");
  return p;
}

// ---- manifests ---------------------------------------------------------------------

struct Manifest {
  bool present = false;  ///< a readable manifest with the magic first line
  std::map<std::string, std::string> fields;
  std::map<std::string, std::uintmax_t> files;  ///< relative path -> size
  std::map<std::string, std::string> hashes;    ///< relative path -> fingerprint (hexFingerprint())
  std::vector<std::string> dirs;                ///< the directories below it (relative paths)
  /// Whether the manifest records fingerprints and directories (results of
  /// earlier versions list sizes only).
  bool fingerprinted() const { return !hashes.empty() || !dirs.empty(); }
  bool complete() const {
    auto it = fields.find("status");
    return present && it != fields.end() && it->second == "complete";
  }
};

Manifest readManifest(const fs::path& dir) {
  Manifest m;
  std::ifstream in(dir / OutputDirectory::manifestFileName());
  std::string line;
  if (!in || !std::getline(in, line) || line != kManifestMagic) return m;
  m.present = true;
  while (std::getline(in, line)) {
    const auto colon = line.find(": ");
    if (colon == std::string::npos) continue;
    const std::string key = line.substr(0, colon), value = line.substr(colon + 2);
    if (key == "file") {
      std::istringstream is(value);
      std::uintmax_t size = 0;
      is >> size;
      std::string rel;
      std::getline(is >> std::ws, rel);
      m.files[rel] = size;
    } else if (key == "fnv1a64") {
      const auto space = value.find(' ');
      if (space != std::string::npos) m.hashes[value.substr(space + 1)] = value.substr(0, space);
    } else if (key == "dir") {
      m.dirs.push_back(value);
    } else {
      m.fields[key] = value;
    }
  }
  return m;
}

/// Regular files below `dir` (relative paths), the manifest excluded; other
/// entries that are not directories (links, sockets, ...) are reported too.
std::vector<std::string> filesBelow(const fs::path& dir) {
  std::vector<std::string> out;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    if (it->is_directory() && !it->is_symlink()) continue;
    const std::string rel = it->path().lexically_relative(dir).generic_string();
    if (rel == OutputDirectory::manifestFileName()) continue;
    out.push_back(rel);
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// Directories below `dir` (relative paths, symbolic links not followed).
std::vector<std::string> directoriesBelow(const fs::path& dir) {
  std::vector<std::string> out;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it)
    if (it->is_directory() && !it->is_symlink()) out.push_back(it->path().lexically_relative(dir).generic_string());
  std::sort(out.begin(), out.end());
  return out;
}

/// Files and directories of the earlier result `dir` that are no longer as
/// DDContact wrote them (a file whose size or fingerprint differs from
/// its manifest's, a directory it did not make): the user's now. Manifests
/// of earlier versions record neither; nothing is reported for them.
std::vector<std::string> changedEntries(const fs::path& dir, const Manifest& m) {
  std::vector<std::string> out;
  if (!m.fingerprinted()) return out;
  for (const auto& [rel, hash] : m.hashes) {
    const fs::path p = dir / rel;
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(p, ec))) continue;  // gone: nothing of the user's to lose
    std::uint64_t h = 0;
    const auto size = m.files.find(rel);
    if (!fs::is_regular_file(fs::symlink_status(p, ec)) || size == m.files.end() ||
        fs::file_size(p, ec) != size->second || !fileFingerprint(p.string(), h) || hexFingerprint(h) != hash)
      out.push_back(rel);
  }
  for (const auto& rel : directoriesBelow(dir))
    if (std::find(m.dirs.begin(), m.dirs.end(), rel) == m.dirs.end()) out.push_back(rel + "/");
  return out;
}

/// Whether `dir` holds the complete result its manifest describes: status
/// complete, every listed file present with its size.
bool completeResult(const fs::path& dir) {
  const Manifest m = readManifest(dir);
  if (!m.complete()) return false;
  for (const auto& [rel, size] : m.files) {
    std::error_code ec;
    const fs::path p = dir / rel;
    if (!fs::is_regular_file(fs::symlink_status(p, ec)) || fs::file_size(p, ec) != size || ec) return false;
  }
  return true;
}

/// Files of `dir` its manifest does not list (someone else put them there).
std::vector<std::string> foreignFiles(const fs::path& dir, const Manifest& m) {
  std::vector<std::string> out;
  for (const auto& rel : filesBelow(dir))
    if (!m.files.count(rel)) out.push_back(rel);
  return out;
}

std::string listSome(const fs::path& dir, const std::vector<std::string>& rels) {
  std::string s;
  for (std::size_t i = 0; i < rels.size() && i < 5; ++i) s += (i ? ", '" : "'") + (dir / rels[i]).string() + "'";
  if (rels.size() > 5) s += " and " + std::to_string(rels.size() - 5) + " more";
  return s;
}

bool isEmptyDirectory(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec) && fs::is_empty(p, ec);
}

/// Removes a directory DDContact wrote (it has a manifest): its files first,
/// the manifest last, so that an interrupted removal still leaves a
/// directory the next run recognises as its own.
/// Why this process could not remove the tree `dir` (a directory whose
/// entries it may not delete: no write or search permission, typically
/// another user's result), or "" if it can. Removing a file needs write and
/// search permission on its directory, so each directory of the tree is
/// checked (symbolic links are not followed).
std::string unremovableReason(const fs::path& dir) {
  std::error_code ec;
  std::vector<fs::path> dirs{dir};
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->is_directory(ec) && !it->is_symlink(ec)) dirs.push_back(it->path());
  for (const auto& d : dirs) {
    if (::access(d.c_str(), W_OK | X_OK) == 0) continue;
    const int err = errno;
    struct stat st {};
    std::string owner = "?";
    if (::lstat(d.c_str(), &st) == 0) {
      const struct passwd* pw = ::getpwuid(st.st_uid);
      owner = pw ? std::string(pw->pw_name) : "uid " + std::to_string(st.st_uid);
    }
    return "'" + d.string() + "' (owner " + owner + ") does not let this user (" +
           [] {
             const struct passwd* me = ::getpwuid(::geteuid());
             return me ? std::string(me->pw_name) : "uid " + std::to_string(::geteuid());
           }() +
           ") delete its entries: " + std::strerror(err);
  }
  return "";
}

void removeResultTree(const fs::path& dir) {
  std::vector<fs::path> dirs;
  bool first = true;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    if (it->is_directory() && !it->is_symlink()) {
      dirs.push_back(it->path());
      continue;
    }
    if (it->path() == dir / OutputDirectory::manifestFileName()) continue;
    fs::remove(it->path());
    if (first) {
      faultInjectionStage("removing-old-result");
      first = false;
    }
  }
  std::sort(dirs.rbegin(), dirs.rend());  // children before parents
  for (const auto& d : dirs) fs::remove(d);
  fs::remove(dir / OutputDirectory::manifestFileName());
  fs::remove(dir);
}

void renameChecked(const fs::path& from, const fs::path& to) {
  if (::rename(from.c_str(), to.c_str()) != 0) {
    const int err = errno;
    DDC_THROW(OutputError, "cannot rename '" << from.string() << "' to '" << to.string() << "': " << std::strerror(err));
  }
  syncDirectory(to.parent_path().string());
}

std::string manifestHeader(const RunDescription& run, const std::string& started, int ranks) {
  std::ostringstream os;
  os << kManifestMagic << "\n"
     << "# The mark of a DDContact result directory (doc/user-guide.md, \"The output directory\").\n"
     << "# DDContact replaces or removes only directories that carry it and lists every file it wrote.\n"
     << "program: ddcontact " << DDC_VERSION << "\n"
     << "input: " << oneLine(run.input.empty() ? std::string("(parameter list in memory)") : run.input) << "\n"
     << "command: " << oneLine(run.command) << "\n"
     << "ranks: " << ranks << "\n"
     << "host: " << hostName() << "\n"
     << "pid: " << ::getpid() << "\n"
     << "started: " << started << "\n";
  return os.str();
}

// ---- the lock ---------------------------------------------------------------------

std::string readSmallFile(int fd) {
  std::string s(4096, '\0');
  const ssize_t n = ::pread(fd, &s[0], s.size(), 0);
  s.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  return s;
}

/// What a step of acquireLock() tells the loop of attempts.
enum class LockStep { Done, Retry, Failed };

/// Opens the lock file `lock`, creating it if absent: never through a
/// symbolic link (it would lock, write and finally unlink a file elsewhere);
/// `created` tells whether this run made the file (O_EXCL). Done with `fd`
/// open on a regular file; Retry when the file vanished between the two
/// opens; Failed with `failure` set.
LockStep openLockFile(const fs::path& lock, const fs::path& final, int& fd, bool& created, Failure& failure) {
  created = true;
  fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0 && errno == EEXIST) {
    created = false;
    fd = ::open(lock.c_str(), O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0 && errno == ENOENT) return LockStep::Retry;  // unlinked by its holder in between
  }
  if (fd < 0) {
    const int err = errno;
    if (err == ELOOP) {
      failure = {Failure::Input, "'" + lock.string() + "' is a symbolic link; DDContact needs that name for the "
                                 "lock of output directory '" + final.string() +
                                 "' and does not follow links there: remove the link or choose another --output-dir"};
      return LockStep::Failed;
    }
    if (err != EISDIR) {
      failure = {Failure::Output, "cannot create the lock file '" + lock.string() + "' of output directory '" +
                                      final.string() + "': " + std::strerror(err)};
      return LockStep::Failed;
    }
  }
  struct stat st {};
  if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    if (fd >= 0) ::close(fd);
    failure = {Failure::Input, "'" + lock.string() + "' exists and is not a regular file; DDContact needs that "
                               "name for the lock of output directory '" + final.string() +
                               "': move it away or choose another --output-dir"};
    return LockStep::Failed;
  }
  return LockStep::Done;
}

/// The failure when another process holds the lock on `fd`: who it is, from
/// what it writes right after locking (closes `fd`).
Failure heldByAnother(int fd, const fs::path& lock, const fs::path& final) {
  std::string holder = readSmallFile(fd);
  for (int i = 0; i < 50 && holder.find("started: ") == std::string::npos; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    holder = readSmallFile(fd);
  }
  ::close(fd);
  if (holder.rfind(kLockMagic, 0) != 0 && !holder.empty())
    return {Failure::Input, "'" + lock.string() + "' exists and is locked, but was not written by ddcontact; "
                            "DDContact needs that name for the lock of output directory '" + final.string() +
                            "': choose another --output-dir"};
  std::string who;
  std::istringstream is(holder);
  std::string line;
  std::getline(is, line);
  while (std::getline(is, line)) who += (who.empty() ? "" : ", ") + line;
  return {Failure::Input, "output directory '" + final.string() + "' is in use by another ddcontact run (" +
                              (who.empty() ? std::string("details not yet written") : who) + "; lock file '" +
                              lock.string() + "'): wait until it finishes, or choose another --output-dir"};
}

/// Takes the advisory write lock on `fd` without waiting; false (with `fd`
/// closed and `failure` set) if that fails, e.g. because another run holds it.
bool lockWithoutWaiting(int fd, const fs::path& lock, const fs::path& final, Failure& failure) {
  struct flock fl {};
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
#ifdef F_OFD_SETLK
  int rc = ::fcntl(fd, F_OFD_SETLK, &fl);
  if (rc != 0 && errno == EINVAL) rc = ::fcntl(fd, F_SETLK, &fl);
#else
  int rc = ::fcntl(fd, F_SETLK, &fl);
#endif
  if (rc == 0) return true;
  const int err = errno;
  if (err != EAGAIN && err != EACCES) {
    ::close(fd);
    failure = {Failure::Output, "cannot lock '" + lock.string() + "': " + std::strerror(err)};
    return false;
  }
  failure = heldByAnother(fd, lock, final);
  return false;
}

/// Writes who holds the lock into the locked file `fd`; false (with `fd`
/// closed and `failure` set) if that fails.
bool writeLockHolder(int fd, const fs::path& lock, const RunDescription& run, const std::string& started,
                     Failure& failure) {
  std::ostringstream info;
  info << kLockMagic << "\npid: " << ::getpid() << "\nhost: " << hostName() << "\ninput: "
       << oneLine(run.input.empty() ? std::string("(parameter list in memory)") : run.input)
       << "\nstarted: " << started << "\n";
  const std::string text = info.str();
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) {
    const int err = errno;
    ::close(fd);
    failure = {Failure::Output, "cannot write the lock file '" + lock.string() + "': " + std::strerror(err)};
    return false;
  }
  return true;
}

/// Takes the advisory lock on `lock` (rank 0). Returns the descriptor, or
/// -1 with `failure` set.
int acquireLock(const fs::path& lock, const fs::path& final, const RunDescription& run, const std::string& started,
                Failure& failure) {
  // An existing empty lock file is either another run's that has just
  // created it and not yet locked and written it, or someone else's file:
  // wait this many times 50 ms for its creator to write it before refusing.
  int emptyWaits = 20;
  for (int attempt = 0; attempt < 10; ++attempt) {
    int fd = -1;
    bool created = true;
    const LockStep opened = openLockFile(lock, final, fd, created, failure);
    if (opened == LockStep::Retry) continue;
    if (opened == LockStep::Failed) return -1;
    if (!lockWithoutWaiting(fd, lock, final, failure)) return -1;
    // The path may have been unlinked by the previous holder between our
    // open() and the lock: then we hold a lock nobody else sees. Retry.
    struct stat a {}, b {};
    if (::fstat(fd, &a) != 0 || ::stat(lock.c_str(), &b) != 0 || a.st_ino != b.st_ino || a.st_dev != b.st_dev) {
      ::close(fd);
      continue;
    }
    const std::string previous = readSmallFile(fd);
    if (previous.empty() && !created) {
      if (emptyWaits-- > 0) {
        ::close(fd);  // let its creator lock and write it
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        --attempt;
        continue;
      }
      ::close(fd);
      failure = {Failure::Input, "'" + lock.string() + "' exists, is empty and no ddcontact run holds it; DDContact "
                                 "needs that name for the lock of output directory '" + final.string() +
                                 "': remove the file (if a run was killed while creating it) or choose another "
                                 "--output-dir"};
      return -1;
    }
    if (!previous.empty() && previous.rfind(kLockMagic, 0) != 0) {
      ::close(fd);
      failure = {Failure::Input, "'" + lock.string() + "' exists and was not written by ddcontact; DDContact needs "
                                 "that name for the lock of output directory '" + final.string() +
                                 "': move the file away or choose another --output-dir"};
      return -1;
    }
    if (!writeLockHolder(fd, lock, run, started, failure)) return -1;
    return fd;
  }
  failure = {Failure::Output, "cannot lock '" + lock.string() + "': it keeps being replaced by other runs"};
  return -1;
}

void releaseLock(int& fd, const fs::path& lock) {
  if (fd < 0) return;
  // Unlink while holding the lock; a waiting opener detects the unlinked
  // inode (acquireLock) and retries on a fresh file.
  ::unlink(lock.c_str());
  ::close(fd);
  fd = -1;
}

/// Whether `p` is usable as one of D, D.partial, D.old: absent, a
/// directory with a manifest, or an empty directory (removed here).
/// Otherwise `failure` says why not.
bool checkOwned(const fs::path& p, const fs::path& final, const std::string& role, Failure& failure) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(p, ec);
  if (!fs::exists(st)) return true;
  if (!fs::is_directory(st)) {
    failure = {Failure::Input, "output directory '" + final.string() + "': '" + p.string() +
                                   "' exists and is not a directory (" + role +
                                   "); move it away or choose another --output-dir"};
    return false;
  }
  if (readManifest(p).present) return true;
  if (fs::is_empty(p, ec)) return true;
  failure = {Failure::Input,
             "output directory '" + final.string() + "': '" + p.string() + "' exists and was not written by ddcontact (" +
                 role + ", it has no " + OutputDirectory::manifestFileName() +
                 "); DDContact never removes or replaces a directory it did not write: choose another --output-dir, or "
                 "move or remove '" + p.string() + "' yourself"};
  return false;
}

/// The file a staging directory was marked resumable with
/// (OutputDirectory::markResumable()) if it is there, else "".
std::string resumableFile(const fs::path& staging) {
  const Manifest m = readManifest(staging);
  const auto it = m.fields.find("resumable");
  std::error_code ec;
  if (it == m.fields.end() || it->second.empty() || !fs::exists(fs::symlink_status(staging / it->second, ec)))
    return "";
  return it->second;
}

/// The refusals of the constructor before any recovery step moves
/// anything (rank 0, lock held): false with `failure` set if D, D.partial
/// or D.old is not this program's to replace or remove.
bool mayReplace(const fs::path& final, const fs::path& staging, const fs::path& old, Failure& failure) {
  if (!checkOwned(final, final, "the output directory", failure) ||
      !checkOwned(staging, final, "the staging directory of a run", failure) ||
      !checkOwned(old, final, "the previous result during a commit", failure))
    return false;
  // An earlier result may be replaced only if all its files are DDContact's;
  // checked before any recovery step moves it.
  if (fs::exists(final) && !isEmptyDirectory(final)) {
    const auto foreign = foreignFiles(final, readManifest(final));
    if (!foreign.empty()) {
      failure = {Failure::Input, "output directory '" + final.string() +
                                     "' is an earlier DDContact result but holds files DDContact did not write: " +
                                     listSome(final, foreign) +
                                     "; move them elsewhere or choose another --output-dir (a new result replaces "
                                     "the whole directory)"};
      return false;
    }
    const auto changed = changedEntries(final, readManifest(final));
    if (!changed.empty()) {
      const bool directory = changed.front().back() == '/';
      failure = {Failure::Input,
                 "output directory '" + final.string() + "' is an earlier DDContact result, but " +
                     listSome(final, changed) +
                     (directory ? " is a directory DDContact did not make there"
                                : " changed since DDContact wrote it (its size or content no longer matches " +
                                      std::string(OutputDirectory::manifestFileName()) + ")") +
                     ": it is yours now, and a new result would replace it; move it away or choose another "
                     "--output-dir"};
      return false;
    }
  }
  // A result this user cannot delete (another user's) would be moved to
  // D.old by the commit and stay there, and every later run would fail on
  // it: refuse before anything moves.
  if (fs::exists(final) && !isEmptyDirectory(final)) {
    const std::string why = unremovableReason(final);
    if (!why.empty()) {
      failure = {Failure::Input, "output directory '" + final.string() + "' holds an earlier result that this run "
                                 "could not remove when it replaces it: " + why +
                                 "; choose another --output-dir, or have its owner remove it"};
      return false;
    }
  }
  if (fs::exists(old) && !isEmptyDirectory(old)) {
    const std::string why = unremovableReason(old);
    if (!why.empty()) {
      failure = {Failure::Input, "'" + old.string() + "', a previous result of output directory '" +
                                 final.string() + "' left by an earlier commit, cannot be removed: " + why +
                                 "; have its owner remove it, or choose another --output-dir"};
      return false;
    }
  }
  return true;
}

/// The checks and recovery of the constructor (rank 0, lock held).
void prepare(const fs::path& final, const fs::path& staging, const fs::path& old, const std::string& resumeWith,
             std::vector<std::string>& notes, Failure& failure) {
  if (!mayReplace(final, staging, old, failure)) return;
  std::error_code ec;
  // Empty leftovers hold nothing; clear them so the cases below are simple.
  for (const fs::path& p : {staging, old})
    if (isEmptyDirectory(p)) fs::remove(p, ec);
  const bool hasFinal = fs::exists(final);

  // Recovery from a commit interrupted at any stage (see commit()).
  if (fs::exists(old)) {
    if (hasFinal && completeResult(final)) {
      removeResultTree(old);
      notes.push_back("removed '" + old.string() + "': a commit interrupted in an earlier run had already put the "
                      "newer complete result in '" + final.string() + "'");
    } else if (hasFinal && !isEmptyDirectory(final)) {
      failure = {Failure::Output, "output directory '" + final.string() + "': both it and '" + old.string() +
                                      "' exist and '" + final.string() + "' is not a complete result; keep the one you "
                                      "want and remove the other yourself"};
      return;
    } else {
      if (hasFinal) fs::remove(final);  // an empty directory
      if (fs::exists(staging) && completeResult(staging)) {
        renameChecked(staging, final);
        removeResultTree(old);
        notes.push_back("completed a commit interrupted in an earlier run: its complete result '" + staging.string() +
                        "' is now '" + final.string() + "'; the result it replaced ('" + old.string() +
                        "') was removed");
      } else {
        renameChecked(old, final);
        notes.push_back("restored '" + final.string() + "' from '" + old.string() +
                        "' (a commit was interrupted before the new result was complete)");
      }
    }
  }
  if (fs::exists(staging)) {
    if (completeResult(staging)) {
      // Killed after its manifest was complete, before the renames: finish
      // that commit (it is the newest complete result).
      if (fs::exists(final)) {
        if (isEmptyDirectory(final)) {
          fs::remove(final);
        } else {
          renameChecked(final, old);
        }
      }
      renameChecked(staging, final);
      if (fs::exists(old)) removeResultTree(old);
      notes.push_back("completed a commit interrupted in an earlier run: its complete result is now '" +
                      final.string() + "'");
    } else if (!resumeWith.empty() && fs::is_regular_file(staging / resumeWith)) {
      notes.push_back("continuing in '" + staging.string() + "', the staging directory of the earlier run that did "
                      "not finish");
    } else if (const std::string kept = resumableFile(staging); !kept.empty()) {
      failure = {Failure::Input, "output directory '" + final.string() + "': '" + staging.string() +
                                     "' is the staging directory of an earlier run that did not finish and holds "
                                     "its checkpoint '" + (staging / kept).string() +
                                     "'; continue that run with --restart '" + final.string() +
                                     "', or, to start anew and discard it, move or remove '" + staging.string() +
                                     "' first (or choose another --output-dir)"};
      return;
    } else {
      removeResultTree(staging);
      notes.push_back("removed '" + staging.string() + "', the staging directory of an earlier run that did not "
                      "finish");
    }
  }

}

}  // namespace

std::string OutputDirectory::normalisedPath(const std::string& dir) { return normalisedFinalDir(dir).string(); }

OutputDirectory::OutputDirectory(Teuchos::RCP<const Teuchos::Comm<int>> comm, std::string finalDir, RunDescription run)
    : comm_(std::move(comm)), run_(std::move(run)) {
  DDC_INPUT_REQUIRE(!comm_.is_null(), "output directory '" << finalDir << "': null communicator");
  const Teuchos::Comm<int>& c = *comm_;
  Failure failure;
  fs::path final;
  if (c.getRank() == 0) {
    try {
      final = normalisedFinalDir(finalDir);
    } catch (const InputError& e) {
      failure = {Failure::Input, e.what()};
    }
  }
  raiseEverywhere(c, failure);
  finalDir_ = broadcastString(c, final.string());
  stagingDir_ = finalDir_ + ".partial";
  started_ = broadcastString(c, nowUtc());

  std::string notes;
  if (c.getRank() == 0) {
    const fs::path staging(stagingDir_), old(finalDir_ + ".old");
    try {
      // An existing ancestor that is not a directory is a wrong path.
      for (fs::path a = final.parent_path(); !a.empty(); a = a.parent_path()) {
        std::error_code ec;
        const auto st = fs::status(a, ec);
        if (fs::exists(st) && !fs::is_directory(st)) {
          failure = {Failure::Input, "output directory '" + finalDir_ + "': '" + a.string() +
                                         "' exists and is not a directory"};
          break;
        }
        if (a == a.root_path()) break;
      }
      if (failure.kind == Failure::None) fs::create_directories(final.parent_path());
      if (failure.kind == Failure::None) lockFd_ = acquireLock(lockPath(), final, run_, started_, failure);
      if (failure.kind == Failure::None) faultInjectionStage("locked");
      if (failure.kind == Failure::None)
        prepare(final, staging, old, run_.resumeWith, notes_, failure);
      if (failure.kind == Failure::None) {
        fs::create_directory(staging);  // kept (resumeWith) or new
        // Fault-injection name "...:start" tells this write from the commit's.
        const std::string manifest = (staging / manifestFileName()).string();
        writeFileAtomically(manifest, manifestHeader(run_, started_, c.getSize()) + "status: running\n",
                            manifest + ":start");
        syncDirectory(final.parent_path().string());
      }
    } catch (const OutputError& e) {
      failure = {Failure::Output, e.what()};
    } catch (const fs::filesystem_error& e) {
      failure = {Failure::Output, "output directory '" + finalDir_ + "': " + fsError(e)};
    }
    for (const auto& n : notes_) notes += n + '\n';
    if (failure.kind != Failure::None && lockFd_ >= 0) {
      // Failed after taking the lock: remove a staging directory this run
      // created if nothing is in it, then release the lock.
      std::error_code ec;
      if (fs::is_directory(staging, ec) && fs::is_empty(staging, ec)) fs::remove(staging, ec);
      releaseLock(lockFd_, lockPath());
    }
  }
  raiseEverywhere(c, failure);
  notes = broadcastString(c, notes);
  notes_.clear();
  std::istringstream is(notes);
  for (std::string line; std::getline(is, line);) notes_.push_back(line);
  faultInjectionStage("staged");
}

OutputDirectory::~OutputDirectory() {
  if (lockFd_ >= 0 && !committed_) {
    // A run that failed before writing anything (e.g. bad input found after
    // the directory was opened) leaves nothing to inspect: remove its
    // staging directory rather than leave litter. Anything written stays.
    try {
      const fs::path staging(stagingDir_);
      if (filesBelow(staging).empty()) removeResultTree(staging);
    } catch (const std::exception&) {
    }
  }
  releaseLock(lockFd_, lockPath());
}

void OutputDirectory::markResumable(const std::string& file) {
  if (committed_) return;
  if (comm_->getRank() == 0) {
    const fs::path staging(stagingDir_);
    std::error_code ec;
    if (fs::is_regular_file(staging / file, ec)) {
      const std::string manifest = (staging / manifestFileName()).string();
      try {
        writeFileAtomically(manifest, manifestHeader(run_, started_, comm_->getSize()) + "status: running\n" +
                                          "resumable: " + oneLine(file) + "\n",
                            manifest + ":resumable");
      } catch (const OutputError&) {
        // Best effort: the run ends with its own error.
      }
    }
  }
  comm_->barrier();
}

void OutputDirectory::commit() {
  if (committed_) return;
  // Every rank has finished writing into the staging directory.
  comm_->barrier();
  Failure failure;
  if (comm_->getRank() == 0) {
    const fs::path final(finalDir_), staging(stagingDir_);
    fs::path old = final;
    old += ".old";
    bool movedOld = false;
    try {
      faultInjectionStage("commit-begin");
      // 1. The complete manifest: every file with its size.
      std::ostringstream os;
      os << manifestHeader(run_, started_, comm_->getSize()) << "finished: " << nowUtc() << "\n";
      for (const auto& rel : filesBelow(staging)) {
        if (rel == std::string(manifestFileName()) + ".tmp") continue;
        os << "file: " << fs::file_size(staging / rel) << " " << rel << "\n";
        std::uint64_t hash = 0;
        if (fileFingerprint((staging / rel).string(), hash))
          os << "fnv1a64: " << hexFingerprint(hash) << " " << rel << "\n";
      }
      for (const auto& rel : directoriesBelow(staging)) os << "dir: " << rel << "\n";
      os << "status: complete\n";
      writeFileAtomically((staging / manifestFileName()).string(), os.str());
      syncDirectory(final.parent_path().string());
      faultInjectionStage("commit-manifest-written");
      // 2. The earlier result must still be ours alone (someone may have
      //    added files since the run started).
      if (fs::exists(final) && !isEmptyDirectory(final)) {
        const Manifest m = readManifest(final);
        auto foreign = m.present ? foreignFiles(final, m) : filesBelow(final);
        if (m.present)
          for (const auto& rel : changedEntries(final, m)) foreign.push_back(rel);
        if (!m.present || !foreign.empty())
          DDC_THROW(OutputError, "cannot commit the results to '"
                                     << finalDir_ << "': since the run started it received files DDContact did not write ("
                                     << listSome(final, foreign) << "); the new results stay complete in '"
                                     << stagingDir_ << "' and the next run into '" << finalDir_
                                     << "' publishes them once those files are moved away");
      }
      // 3. The swap: D -> D.old, D.partial -> D.
      if (fs::exists(final)) {
        if (isEmptyDirectory(final)) {
          fs::remove(final);
        } else {
          renameChecked(final, old);
          movedOld = true;
          faultInjectionStage("commit-old-moved");
        }
      }
      renameChecked(staging, final);
      faultInjectionStage("commit-new-moved");
    } catch (const OutputError& e) {
      failure = {Failure::Output, e.what()};
    } catch (const fs::filesystem_error& e) {
      failure = {Failure::Output, "cannot commit output directory '" + finalDir_ + "': " + fsError(e)};
    }
    if (failure.kind != Failure::None && movedOld && !fs::exists(final)) {
      // Put the earlier result back; the new one stays complete in staging.
      std::error_code ec;
      fs::rename(old, final, ec);
    }
    if (failure.kind == Failure::None && movedOld) {
      // 4. The new result is in place; failing to delete the old one is not
      //    fatal (the next run removes it and says so).
      try {
        removeResultTree(old);
      } catch (const fs::filesystem_error& e) {
        std::cerr << "ddcontact: output: warning: the new result is in '" << finalDir_
                  << "', but the one it replaced could not be removed from '" << old.string() << "': " << fsError(e)
                  << " (the next run into this directory removes it)" << std::endl;
      }
    }
    // Committed: the directory is free for the next run as soon as commit()
    // returns on any rank (not only when rank 0 destroys this object).
    if (failure.kind == Failure::None) releaseLock(lockFd_, lockPath());
  }
  raiseEverywhere(*comm_, failure);
  committed_ = true;
}

}  // namespace ddc
