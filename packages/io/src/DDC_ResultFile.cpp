#include "DDC_ResultFile.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>
#include <vector>

#include "DDC_Error.hpp"

namespace ddc {

namespace {

constexpr std::size_t kBufferBytes = 64 * 1024;

struct FaultItem {
  std::string action, target, argument;
};

/// DDCONTACT_FAULT_INJECTION, parsed once.
const std::vector<FaultItem>& faultItems() {
  static const std::vector<FaultItem> items = [] {
    std::vector<FaultItem> out;
    const char* env = std::getenv("DDCONTACT_FAULT_INJECTION");
    if (!env) return out;
    std::string s = env;
    std::size_t start = 0;
    while (start <= s.size()) {
      std::size_t end = s.find(',', start);
      if (end == std::string::npos) end = s.size();
      const std::string item = s.substr(start, end - start);
      const auto at = item.find('@');
      if (at != std::string::npos) {
        FaultItem f{item.substr(0, at), item.substr(at + 1), ""};
        const auto eq = f.target.find('=');
        if (eq != std::string::npos) {
          f.argument = f.target.substr(eq + 1);
          f.target = f.target.substr(0, eq);
        }
        out.push_back(f);
      }
      start = end + 1;
    }
    return out;
  }();
  return items;
}

bool nameMatches(const std::string& path, const std::string& name) {
  if (name.empty()) return false;
  if (path == name) return true;
  return path.size() > name.size() && path.compare(path.size() - name.size(), name.size(), name) == 0 &&
         path[path.size() - name.size() - 1] == '/';
}

std::string reason(int err) { return err ? std::strerror(err) : "unknown I/O error"; }

}  // namespace

bool faultInjection(const std::string& action, const std::string& target, std::string* argument) {
  for (const FaultItem& f : faultItems()) {
    if (f.action != action) continue;
    const bool stage = action == "kill" || action == "pause" || action == "sigterm" || action == "newton-failure";
    if (stage ? f.target == target : nameMatches(target, f.target)) {
      if (argument) *argument = f.argument;
      return true;
    }
  }
  return false;
}

bool faultInjectionActive() { return !faultItems().empty(); }

void faultInjectionStage(const std::string& stage) {
  if (!faultInjectionActive()) return;
  std::string file;
  if (faultInjection("pause", stage, &file)) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    std::error_code ec;
    while (!std::filesystem::exists(file, ec) && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (faultInjection("kill", stage)) {
    std::fflush(nullptr);
    ::raise(SIGKILL);
  }
}

CheckedFile::CheckedFile(std::string path, std::string faultName)
    : path_(std::move(path)), faultName_(faultName.empty() ? path_ : std::move(faultName)) {
  if (faultInjection("eacces", faultName_)) {
    DDC_THROW(OutputError, "cannot create '" << path_ << "': " << reason(EACCES));
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    const int err = errno;
    DDC_THROW(OutputError, "cannot create '" << path_ << "': " << reason(err));
  }
  buffer_.reserve(kBufferBytes);
}

CheckedFile::~CheckedFile() {
  if (fd_ >= 0) ::close(fd_);
}

void CheckedFile::write(std::string_view data) {
  buffer_.append(data.data(), data.size());
  if (buffer_.size() >= kBufferBytes) flush();
}

void CheckedFile::printf(const char* format, ...) {
  char small[256];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(small, sizeof small, format, args);
  va_end(args);
  if (n < 0) DDC_THROW(OutputError, "cannot format output for '" << path_ << "'");
  if (static_cast<std::size_t>(n) < sizeof small) {
    write(std::string_view(small, static_cast<std::size_t>(n)));
    return;
  }
  std::string big(static_cast<std::size_t>(n) + 1, '\0');
  va_start(args, format);
  std::vsnprintf(&big[0], big.size(), format, args);
  va_end(args);
  big.pop_back();
  write(big);
}

void CheckedFile::flush() {
  if (fd_ < 0) DDC_THROW(OutputError, "cannot write '" << path_ << "': the file is closed");
  const char* p = buffer_.data();
  std::size_t left = buffer_.size();
  // Injected full disk: half of the data goes out, then ENOSPC, as write(2)
  // does when the device fills up in the middle of a request.
  if (left > 0 && !faultUsed_ && faultInjection("enospc", faultName_)) {
    faultUsed_ = true;
    const std::size_t half = left / 2;
    if (half > 0 && ::write(fd_, p, half) < 0) {
      const int err = errno;
      DDC_THROW(OutputError, "cannot write '" << path_ << "': " << reason(err));
    }
    DDC_THROW(OutputError, "cannot write '" << path_ << "': " << reason(ENOSPC));
  }
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      DDC_THROW(OutputError, "cannot write '" << path_ << "': " << reason(err));
    }
    if (n == 0) DDC_THROW(OutputError, "cannot write '" << path_ << "': the device accepted no data");
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  buffer_.clear();
}

void CheckedFile::close() {
  flush();
  int err = 0;
  if (faultInjection("eio-fsync", faultName_))
    err = EIO;
  else if (::fsync(fd_) != 0)
    err = errno;
  if (err) {
    ::close(fd_);
    fd_ = -1;
    DDC_THROW(OutputError, "cannot write '" << path_ << "' to disk (fsync): " << reason(err));
  }
  const int rc = ::close(fd_);
  err = rc != 0 ? errno : 0;
  fd_ = -1;
  if (faultInjection("eio-close", faultName_)) err = EIO;
  if (err) DDC_THROW(OutputError, "cannot close '" << path_ << "': " << reason(err));
}

void writeFileAtomically(const std::string& path, const std::string& content, const std::string& faultName) {
  const std::string tmp = path + ".tmp";
  try {
    CheckedFile f(tmp, faultName.empty() ? path : faultName);
    f.write(content);
    f.close();
  } catch (const OutputError&) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    DDC_THROW(OutputError, "cannot replace '" << path << "' by '" << tmp << "': " << reason(err));
  }
  const std::string dir = std::filesystem::path(path).parent_path().string();
  syncDirectory(dir.empty() ? "." : dir);
}

void syncDirectory(const std::string& directory) {
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    DDC_THROW(OutputError, "cannot open directory '" << directory << "' to sync it: " << reason(err));
  }
  const int rc = ::fsync(fd);
  const int err = rc != 0 ? errno : 0;
  ::close(fd);
  // Some file systems cannot sync a directory (EINVAL); that is not a failure
  // of the data.
  if (rc != 0 && err != EINVAL && err != EROFS)
    DDC_THROW(OutputError, "cannot sync directory '" << directory << "': " << reason(err));
}

}  // namespace ddc
