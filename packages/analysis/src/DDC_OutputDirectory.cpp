#include "DDC_OutputDirectory.hpp"

#include <filesystem>
#include <system_error>
#include <utility>

#include <Teuchos_CommHelpers.hpp>

#include "DDC_Error.hpp"

namespace fs = std::filesystem;

namespace ddc {

std::string firstErrorOnAnyRank(const Teuchos::Comm<int>& comm, const std::string& localError) {
  const int size = comm.getSize();
  const int rank = comm.getRank();
  const int mine = localError.empty() ? size : rank;
  int first = size;
  Teuchos::reduceAll<int, int>(comm, Teuchos::REDUCE_MIN, mine, Teuchos::outArg(first));
  if (first == size) return std::string();
  int length = (rank == first) ? static_cast<int>(localError.size()) : 0;
  Teuchos::broadcast<int, int>(comm, first, Teuchos::outArg(length));
  std::string message = (rank == first) ? localError : std::string(length, ' ');
  if (length > 0) Teuchos::broadcast<int, char>(comm, first, length, &message[0]);
  return message;
}

namespace {

/// "out/run/" -> "out/run"; rejects paths without a usable last component.
fs::path normalisedFinalDir(const std::string& finalDir) {
  DDC_INPUT_REQUIRE(!finalDir.empty(), "output directory: the path is empty");
  fs::path p = fs::path(finalDir).lexically_normal();
  if (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  const std::string last = p.filename().string();
  DDC_INPUT_REQUIRE(!last.empty() && last != "." && last != "..",
                    "output directory '" << finalDir
                                         << "': expected a path ending in a directory name");
  return p;
}

}  // namespace

OutputDirectory::OutputDirectory(Teuchos::RCP<const Teuchos::Comm<int>> comm, std::string finalDir)
    : comm_(std::move(comm)) {
  DDC_INPUT_REQUIRE(!comm_.is_null(), "output directory '" << finalDir << "': null communicator");
  // Same input on every rank, so this check (which may throw) agrees everywhere.
  const fs::path final = normalisedFinalDir(finalDir);
  fs::path staging = final;
  staging += ".partial";
  finalDir_ = final.string();
  stagingDir_ = staging.string();

  std::string error;
  if (comm_->getRank() == 0) {
    try {
      std::error_code ec;
      const fs::file_status st = fs::status(final, ec);
      if (fs::exists(st) && !fs::is_directory(st)) {
        error = "output directory '" + finalDir_ + "' exists and is not a directory";
      } else {
        fs::remove_all(staging);  // leftover of an earlier failed run
        fs::create_directories(staging);
        if (!fs::is_directory(staging)) {
          error = "cannot create output directory '" + finalDir_ + "' (staging directory '" +
                  stagingDir_ + "')";
        }
      }
    } catch (const fs::filesystem_error& e) {
      error = "cannot create output directory '" + finalDir_ + "' (staging directory '" +
              stagingDir_ + "'): " + e.code().message();
      if (!e.path1().empty()) error += " at '" + e.path1().string() + "'";
    } catch (const std::exception& e) {
      error = "cannot create output directory '" + finalDir_ + "': " + e.what();
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) throw InputError(error);
}

void OutputDirectory::commit() {
  if (committed_) return;
  // Every rank has finished writing into the staging directory.
  comm_->barrier();
  std::string error;
  if (comm_->getRank() == 0) {
    const fs::path final(finalDir_);
    const fs::path staging(stagingDir_);
    fs::path old = final;
    old += ".old";
    bool movedOld = false;
    try {
      fs::remove_all(old);  // leftover of an interrupted commit
      std::error_code ec;
      if (fs::exists(fs::symlink_status(final, ec))) {
        fs::rename(final, old);
        movedOld = true;
      }
      fs::rename(staging, final);
      // The new results are in place; failing to delete the old ones is not fatal.
      fs::remove_all(old, ec);
    } catch (const fs::filesystem_error& e) {
      error = "cannot commit output directory '" + finalDir_ + "' (from staging directory '" +
              stagingDir_ + "'): " + e.code().message();
      if (movedOld) {
        std::error_code ec;
        if (!fs::exists(fs::symlink_status(final, ec))) fs::rename(old, final, ec);
      }
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) throw InputError(error);
  committed_ = true;
}

}  // namespace ddc
