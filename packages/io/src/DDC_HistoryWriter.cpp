#include "DDC_HistoryWriter.hpp"

#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <Teuchos_CommHelpers.hpp>

#include "DDC_Error.hpp"
#include "DDC_OutputDirectory.hpp"

namespace fs = std::filesystem;

namespace ddc {

namespace {

/// Broadcasts a string from rank 0.
std::string broadcastFromRoot(const Teuchos::Comm<int>& comm, const std::string& s) {
  int length = comm.getRank() == 0 ? static_cast<int>(s.size()) : 0;
  Teuchos::broadcast<int, int>(comm, 0, Teuchos::outArg(length));
  std::string out = comm.getRank() == 0 ? s : std::string(length, ' ');
  if (length > 0) Teuchos::broadcast<int, char>(comm, 0, length, &out[0]);
  return out;
}

}  // namespace

const std::vector<std::string>& HistoryWriter::standardColumns() {
  static const std::vector<std::string> columns = {
      "step",          "load_factor",     "strain_energy",   "newton_iterations",
      "dual_iterations", "active_contacts", "contact_force_x", "contact_force_y",
      "contact_exchanges", "wall_seconds"};
  return columns;
}

std::string HistoryWriter::formatValue(double v) {
  char buf[64];
  if (std::isfinite(v) && v == std::trunc(v) && std::fabs(v) < 9007199254740992.0) {
    std::snprintf(buf, sizeof(buf), "%lld", static_cast<long long>(v));
  } else {
    std::snprintf(buf, sizeof(buf), "%.17g", v);
  }
  return buf;
}

HistoryWriter::HistoryWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& path,
                             std::vector<std::string> columns)
    : comm_(std::move(comm)), path_(path), columns_(std::move(columns)) {
  DDC_INPUT_REQUIRE(!comm_.is_null(), "history file '" << path << "': null communicator");
  // Same arguments on every rank: these checks agree everywhere.
  DDC_INPUT_REQUIRE(!path.empty(), "history file: the path is empty");
  DDC_INPUT_REQUIRE(!columns_.empty(), "history file '" << path << "': no columns");
  std::set<std::string> seen;
  for (const std::string& c : columns_) {
    DDC_INPUT_REQUIRE(!c.empty() && c.find_first_of(",\"\r\n") == std::string::npos,
                      "history file '" << path << "': invalid column name '" << c
                                       << "' (expected non-empty, without ',', '\"' or line breaks)");
    DDC_INPUT_REQUIRE(seen.insert(c).second,
                      "history file '" << path << "': duplicate column name '" << c << "'");
  }

  std::string error;
  if (comm_->getRank() == 0) {
    std::error_code ec;
    if (fs::is_directory(fs::path(path), ec)) path_ = (fs::path(path) / defaultFileName()).string();
    try {
      file_ = std::make_unique<CheckedFile>(path_);
    } catch (const OutputError& e) {
      error = std::string("I") + "history file: " + e.what();
    }
    if (error.empty()) try {
      std::string header;
      for (std::size_t i = 0; i < columns_.size(); ++i) {
        if (i) header += ',';
        header += columns_[i];
      }
      header += '\n';
      file_->write(header);
      file_->flush();
    } catch (const OutputError& e) {
      error = std::string("O") + "history file: " + e.what();
    }
  }
  path_ = broadcastFromRoot(*comm_, path_);
  // A file that cannot be created is a wrong path (input); a failing write
  // is an output failure (a full disk).
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty() && error[0] == 'I') throw InputError(error.substr(1));
  if (!error.empty()) throw OutputError(error.substr(1));
}

HistoryWriter::~HistoryWriter() = default;

void HistoryWriter::appendRow(const std::vector<double>& values) {
  if (values.size() != columns_.size()) {
    DDC_THROW(std::invalid_argument, "history file '" << path_ << "': row has " << values.size()
                                                      << " values, expected " << columns_.size()
                                                      << " (one per column)");
  }
  std::string error;
  if (comm_->getRank() == 0) {
    std::string line;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i) line += ',';
      line += formatValue(values[i]);
    }
    line += '\n';
    try {
      if (!file_) DDC_THROW(OutputError, "cannot write history file '" << path_ << "': it is closed");
      file_->write(line);
      file_->flush();
    } catch (const OutputError& e) {
      error = e.what();
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) throw OutputError(error);
  ++numRows_;
}

void HistoryWriter::close() {
  std::string error;
  if (comm_->getRank() == 0 && file_) {
    try {
      file_->close();
    } catch (const OutputError& e) {
      error = e.what();
    }
    file_.reset();
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) throw OutputError(error);
}

}  // namespace ddc
