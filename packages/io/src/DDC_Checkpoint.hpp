// Checkpoint files: named sections of data in one file that is either
// complete and intact or refused - the storage a restart reads (the state it
// holds is the analysis's business, not this file's).
//
// Format (version 2): the line "DDContact checkpoint 2\n"; the number of
// sections (u64); per section its name (u32 length, bytes), a kind (u8) and
// - kind 0, bytes: the payload (u64 length, bytes);
// - kind 1, a distributed vector: the number of pieces P (u64), the entry
//   count of each piece (P u64), the FNV-1a 64-bit hash of each piece's
//   entries (P u64), then the pieces' entries, piece after piece, each entry
//   a (global index i64, value f64) pair;
// last the FNV-1a 64-bit hash of every byte before it except the vectors'
// entries (which their pieces' hashes cover). Integers are little-endian
// (the machines DDContact runs on).
//
// Nothing is gathered on one rank. Writing: each rank writes its own piece
// of each vector (its entries in increasing index order) with MPI-IO at its
// offset, rank 0 the rest, all into path + ".tmp", which rank 0 then renames
// into place (a checkpoint is the old one or the new one, never half).
// Reading, on any number of ranks Q: rank 0 reads and checks everything but
// the entries and broadcasts it; rank q reads the pieces q, q + Q, ... and
// checks their hashes; a vector is read into any map by sending each entry
// to the owner of its index. Version 1 files (one hash over the whole file,
// each vector sorted in one section) are still read, by rank 0.
#pragma once

#include <Teuchos_Comm.hpp>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "DDC_TpetraTypes.hpp"

namespace ddc {

/// Collects the sections of one checkpoint and writes it (see the top of
/// this file). Sections keep their names unique.
class CheckpointWriter {
 public:
  explicit CheckpointWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm);
  ~CheckpointWriter();
  /// Bytes the same on every rank (rank 0's are written).
  /// \throws std::invalid_argument if `name` is empty or already used
  void putBytes(const std::string& name, const std::string& bytes);
  /// Doubles the same on every rank (rank 0's are written).
  void putDoubles(const std::string& name, const std::vector<double>& values);
  /// A distributed vector (collective): every entry of its map, by global
  /// index. Each rank keeps its own entries.
  void putVector(const std::string& name, const Vector& v);
  /// Write the checkpoint to `path` (collective; every rank writes its
  /// pieces).
  /// \throws OutputError on every rank naming the file and the reason;
  ///         `path` then holds what it held before.
  void write(const std::string& path) const;

 private:
  /// One vector section as the writer holds it: this rank's piece, and
  /// every piece's entry count and hash (the same on every rank).
  struct VectorPiece {
    std::string bytes;
    std::vector<std::uint64_t> counts, hashes;
  };
  struct Section {
    std::string name, payload;           ///< payload: a section of bytes
    std::unique_ptr<VectorPiece> piece;  ///< a vector section
  };
  /// Bytes this rank writes at an offset of the file.
  struct Segment {
    std::uint64_t offset;
    std::string_view bytes;
  };
  void add(const std::string& name, std::string payload, std::unique_ptr<VectorPiece> piece);
  /// What this rank writes where (collective): rank 0 everything but the
  /// entries (kept in `heads`), every rank its pieces.
  std::vector<Segment> layout(std::vector<std::string>& heads) const;
  /// Rank 0: the file's bytes but the entries, in runs (`heads`, at
  /// `headAt`) ending with the hash, and where each vector's entries begin.
  void composeHeads(std::vector<std::string>& heads, std::vector<std::uint64_t>& headAt,
                    std::vector<std::uint64_t>& dataStart) const;
  /// Write the segments into `tmp` (MPI-IO; fault injection matches `path`);
  /// the first error on any rank, "" if none (collective).
  std::string writeSegments(const std::string& tmp, const std::string& path,
                            const std::vector<Segment>& segments) const;
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::vector<Section> sections_;
};

/// Reads a checkpoint written by CheckpointWriter (see the top of this file).
class CheckpointReader {
 public:
  /// Read and check `path` (collective).
  /// \throws InputError on every rank naming the file and what is wrong:
  ///         missing or unreadable, not a DDContact checkpoint (or another
  ///         version), truncated, or corrupted (the hash does not match).
  CheckpointReader(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& path);
  ~CheckpointReader();
  /// Whether the checkpoint has a section `name` (bytes or a vector).
  bool has(const std::string& name) const;
  /// \throws InputError naming the file and the section if it is missing.
  const std::string& bytes(const std::string& name) const;
  /// \throws InputError naming the file and the section if it is missing or
  ///         not a whole number of doubles.
  std::vector<double> doubles(const std::string& name) const;
  /// Fill `v` (its map's global indices, any distribution, one owner per
  /// index) from the stored vector `name` (collective).
  /// \throws InputError naming the file, the section and a global index of
  ///         v's map the vector does not have (on every rank).
  void vector(const std::string& name, Vector& v) const;
  /// The file read.
  const std::string& path() const { return path_; }

 private:
  /// Where a vector section's pieces lie in the file (the same on every rank).
  struct VectorTable {
    std::uint64_t dataStart = 0;
    std::vector<std::uint64_t> counts, hashes;
    std::uint64_t entries() const;
  };
  void readVersion1(double size);
  void readVersion2(double size);
  /// Rank 0: the sections and vector tables of a version 2 file, checked;
  /// the error, "" if none.
  std::string readHead2(double size, std::map<std::string, VectorTable>& tables);
  /// This rank's pieces of every vector, checked against their hashes.
  void readPieces(double size);
  /// Rank 0's sections of bytes to every rank.
  void broadcastSections();
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::string path_;
  std::map<std::string, std::string> sections_;     ///< sections of bytes, on every rank
  std::map<std::string, VectorTable> tables_;       ///< vector sections, on every rank
  std::map<std::string, std::string> pieces_;       ///< this rank's entries of each vector
};

}  // namespace ddc
