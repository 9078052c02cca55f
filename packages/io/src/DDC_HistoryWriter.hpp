// history.csv: one row per converged load step (doc/user-guide.md, "The
// output directory").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Teuchos_Comm.hpp>
#include <Teuchos_RCP.hpp>

#include "DDC_ResultFile.hpp"

namespace ddc {

/// \brief Writes the step history as CSV; only rank 0 touches the file.
///
/// The header line is the column names joined by ','. Each row is written
/// with full precision ("%.17g", so values read back bit-identical); values
/// that are integral (|v| < 2^53, e.g. step numbers, iteration counts) are
/// written without a decimal point. Every row is handed to the operating
/// system when it is appended (a run that crashes leaves a valid CSV file with
/// all rows completed so far), and every write is checked (CheckedFile): a
/// full disk is an error naming the file, never a silently truncated history.
/// close() syncs the file to disk; call it before OutputDirectory::commit().
///
/// Constructor and appendRow() are collective: call them on every rank with
/// the same arguments. Only rank 0 writes; the other ranks take part in the
/// error agreement, so an I/O error raises the same exception on every rank.
class HistoryWriter {
 public:
  /// Name of the history file inside the output directory.
  static constexpr const char* defaultFileName() { return "history.csv"; }

  /// The stable columns (doc/user-guide.md), exactly and in this order:
  /// step,load_factor,strain_energy,newton_iterations,dual_iterations,
  /// active_contacts,contact_force_x,contact_force_y,contact_exchanges,wall_seconds.
  /// Callers may append extra columns.
  static const std::vector<std::string>& standardColumns();

  /// Collective. Creates (truncates) the file and writes the header.
  /// \param path  the CSV file to write; if `path` is an existing directory
  ///   (e.g. OutputDirectory::path()), the file is `path/history.csv`.
  /// \param columns  column names: non-empty, unique, without ',', '"' or
  ///   line breaks.
  /// \throws InputError (every rank) if the columns are invalid or the file
  ///   cannot be created; OutputError (every rank) if the header cannot be
  ///   written (a full disk).
  HistoryWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& path,
                std::vector<std::string> columns);

  HistoryWriter(const HistoryWriter&) = delete;
  HistoryWriter& operator=(const HistoryWriter&) = delete;
  ~HistoryWriter();

  /// Collective. Appends one row and flushes it.
  /// \throws std::invalid_argument (every rank) if values.size() != columns().size();
  /// \throws OutputError (a std::runtime_error, every rank) if writing fails on rank 0.
  void appendRow(const std::vector<double>& values);

  /// Collective. Syncs the file to disk (fsync) and closes it; later
  /// appendRow() calls fail. A second call is a no-op.
  /// \throws OutputError (every rank) naming the file if the sync or close fails.
  void close();

  /// The file written, resolved as described for the constructor (the same
  /// on every rank: rank 0 resolves it and broadcasts it).
  const std::string& path() const { return path_; }

  const std::vector<std::string>& columns() const { return columns_; }

  /// Number of rows appended so far.
  int numRows() const { return numRows_; }

  /// Formats one value as written to the file ("%.17g", integral values as integers).
  static std::string formatValue(double v);

 private:
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::string path_;
  std::vector<std::string> columns_;
  std::unique_ptr<CheckedFile> file_;  ///< rank 0 only
  int numRows_ = 0;
};

}  // namespace ddc
