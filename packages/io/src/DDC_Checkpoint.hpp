// Checkpoint files: named sections of data in one file that is either
// complete and intact or refused - the storage a restart reads (the state it
// holds is the analysis's business, not this file's).
//
// Format (version 1): the line "DDContact checkpoint 1\n"; the number of
// sections (u64); per section its name (u32 length, bytes) and its payload
// (u64 length, bytes); last the FNV-1a 64-bit hash of everything before it
// (u64). Integers are little-endian (the machines DDContact runs on).
// Sections hold bytes, doubles, or a distributed vector as (global index,
// value) pairs in increasing index order, so that it reads back on any
// number of ranks and any distribution of its map.
//
// Writing gathers the distributed vectors to rank 0, which writes the file
// with writeFileAtomically() (a checkpoint is the old one or the new one,
// never half). Reading: rank 0 reads and checks the file and broadcasts it.
#pragma once

#include <Teuchos_Comm.hpp>
#include <map>
#include <string>
#include <vector>

#include "DDC_TpetraTypes.hpp"

namespace ddc {

/// Collects the sections of one checkpoint and writes it (see the top of
/// this file). Sections keep their names unique.
class CheckpointWriter {
 public:
  explicit CheckpointWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm);
  /// Bytes the same on every rank (rank 0's are written).
  /// \throws std::invalid_argument if `name` is empty or already used
  void putBytes(const std::string& name, const std::string& bytes);
  /// Doubles the same on every rank (rank 0's are written).
  void putDoubles(const std::string& name, const std::vector<double>& values);
  /// A distributed vector (collective): every entry of its map, by global
  /// index.
  void putVector(const std::string& name, const Vector& v);
  /// Write the checkpoint to `path` (collective; rank 0 writes).
  /// \throws OutputError on every rank naming the file and the reason;
  ///         `path` then holds what it held before.
  void write(const std::string& path) const;

 private:
  void add(const std::string& name, std::string payload);
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::vector<std::pair<std::string, std::string>> sections_;  ///< rank 0's
};

/// Reads a checkpoint written by CheckpointWriter (see the top of this file).
class CheckpointReader {
 public:
  /// Read and check `path` (collective).
  /// \throws InputError on every rank naming the file and what is wrong:
  ///         missing or unreadable, not a DDContact checkpoint (or another
  ///         version), truncated, or corrupted (the hash does not match).
  CheckpointReader(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& path);
  /// Whether the checkpoint has a section `name`.
  bool has(const std::string& name) const { return sections_.count(name) != 0; }
  /// \throws InputError naming the file and the section if it is missing.
  const std::string& bytes(const std::string& name) const;
  /// \throws InputError naming the file and the section if it is missing or
  ///         not a whole number of doubles.
  std::vector<double> doubles(const std::string& name) const;
  /// Fill `v` (its map's global indices, any distribution) from the stored
  /// vector `name`.
  /// \throws InputError naming the file, the section and a global index of
  ///         v's map the vector does not have (on every rank).
  void vector(const std::string& name, Vector& v) const;
  /// The file read.
  const std::string& path() const { return path_; }

 private:
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::string path_;
  std::map<std::string, std::string> sections_;
};

}  // namespace ddc
