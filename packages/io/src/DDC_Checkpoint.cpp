#include "DDC_Checkpoint.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_FileFingerprint.hpp"
#include "DDC_Memory.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_ResultFile.hpp"

namespace ddc {

namespace {

const std::string kMagic1 = "DDContact checkpoint 1\n";
const std::string kMagic2 = "DDContact checkpoint 2\n";
constexpr std::uint8_t kBytesSection = 0, kVectorSection = 1;
/// MPI-IO counts are ints: pieces are written in parts of at most this.
constexpr size_t kMaxWriteBytes = size_t(1) << 30;

template <class T>
void append(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// A (global index, value) pair of a stored vector.
struct Entry {
  long long gid;
  double value;
};

/// Reads fixed-size values from a byte string; false once past its end.
struct Cursor {
  const std::string& s;
  size_t pos = 0;
  template <class T>
  bool get(T& value) {
    if (s.size() - pos < sizeof(T)) return false;
    std::memcpy(&value, s.data() + pos, sizeof(T));
    pos += sizeof(T);
    return true;
  }
  bool get(std::string& out, size_t n) {
    if (s.size() - pos < n) return false;
    out.assign(s, pos, n);
    pos += n;
    return true;
  }
};

std::string mpiErrorText(int rc) {
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(rc, text, &length);
  return std::string(text, size_t(length));
}

}  // namespace

CheckpointWriter::CheckpointWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm) : comm_(std::move(comm)) {}
CheckpointWriter::~CheckpointWriter() = default;

void CheckpointWriter::add(const std::string& name, std::string payload, std::unique_ptr<VectorPiece> piece) {
  if (name.empty()) throw std::invalid_argument("CheckpointWriter: a section needs a name");
  for (const auto& s : sections_)
    if (s.name == name) throw std::invalid_argument("CheckpointWriter: section '" + name + "' given twice");
  sections_.push_back(Section{name, std::move(payload), std::move(piece)});
}

void CheckpointWriter::putBytes(const std::string& name, const std::string& bytes) { add(name, bytes, nullptr); }

void CheckpointWriter::putDoubles(const std::string& name, const std::vector<double>& values) {
  add(name, std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double)), nullptr);
}

void CheckpointWriter::putVector(const std::string& name, const Vector& v) {
  // Each rank keeps its own entries; only their counts and hashes travel.
  const auto map = v.getMap();
  const auto data = v.getData();
  std::vector<Entry> mine(v.getLocalLength());
  for (size_t l = 0; l < mine.size(); ++l) mine[l] = {static_cast<long long>(map->getGlobalElement(LO(l))), data[l]};
  std::sort(mine.begin(), mine.end(), [](const Entry& a, const Entry& b) { return a.gid < b.gid; });
  auto piece = std::make_unique<VectorPiece>();
  piece->bytes.assign(reinterpret_cast<const char*>(mine.data()), mine.size() * sizeof(Entry));
  const std::uint64_t own[2] = {mine.size(), fnv1a(piece->bytes.data(), piece->bytes.size())};
  std::vector<std::uint64_t> all(2 * size_t(comm_->getSize()));
  MPI_Allgather(own, 2, MPI_UINT64_T, all.data(), 2, MPI_UINT64_T, rawComm(*comm_));
  for (size_t r = 0; r < all.size(); r += 2) piece->counts.push_back(all[r]), piece->hashes.push_back(all[r + 1]);
  add(name, std::string(), std::move(piece));
}

std::vector<CheckpointWriter::Segment> CheckpointWriter::layout(std::vector<std::string>& heads) const {
  // Rank 0 composes everything but the entries (`heads`); every rank learns
  // where its pieces go from rank 0's layout (the sections of bytes are the
  // same on every rank, and rank 0's are written).
  const int rank = comm_->getRank();
  std::vector<Segment> segments;
  std::vector<std::uint64_t> dataStart, headAt;
  if (rank == 0) composeHeads(heads, headAt, dataStart);
  size_t vectors = 0;
  for (const Section& s : sections_) vectors += s.piece != nullptr;
  dataStart.resize(vectors);
  MPI_Bcast(dataStart.data(), int(vectors), MPI_UINT64_T, 0, rawComm(*comm_));
  for (size_t k = 0; k < heads.size(); ++k) segments.push_back({headAt[k], heads[k]});
  size_t k = 0;
  for (const Section& s : sections_) {
    if (!s.piece) continue;
    std::uint64_t offset = dataStart[k++];
    for (int r = 0; r < rank; ++r) offset += s.piece->counts[size_t(r)] * sizeof(Entry);
    if (!s.piece->bytes.empty()) segments.push_back({offset, s.piece->bytes});
  }
  return segments;
}

void CheckpointWriter::composeHeads(std::vector<std::string>& heads, std::vector<std::uint64_t>& headAt,
                                    std::vector<std::uint64_t>& dataStart) const {
  std::string head = kMagic2;
  append<std::uint64_t>(head, sections_.size());
  std::uint64_t at = 0, hash = fnv1a(nullptr, 0);
  auto flushHead = [&] {
    hash = fnv1a(head.data(), head.size(), hash);
    headAt.push_back(at);
    at += head.size();
    heads.push_back(std::move(head));
    head.clear();
  };
  for (const Section& s : sections_) {
    append<std::uint32_t>(head, std::uint32_t(s.name.size()));
    head += s.name;
    if (!s.piece) {
      append<std::uint8_t>(head, kBytesSection);
      append<std::uint64_t>(head, s.payload.size());
      head += s.payload;
      continue;
    }
    append<std::uint8_t>(head, kVectorSection);
    append<std::uint64_t>(head, s.piece->counts.size());
    for (std::uint64_t c : s.piece->counts) append<std::uint64_t>(head, c);
    for (std::uint64_t h : s.piece->hashes) append<std::uint64_t>(head, h);
    flushHead();
    dataStart.push_back(at);
    for (std::uint64_t c : s.piece->counts) at += c * sizeof(Entry);
  }
  append<std::uint64_t>(head, fnv1a(head.data(), head.size(), hash));
  flushHead();
}

std::string CheckpointWriter::writeSegments(const std::string& tmp, const std::string& path,
                                            const std::vector<Segment>& segments) const {
  // Every rank its segments, into one file opened with MPI-IO; the error
  // of the lowest rank that had one (collective).
  const MPI_Comm comm = rawComm(*comm_);
  MPI_File fh;
  int rc = MPI_File_open(comm, tmp.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &fh);
  if (rc == MPI_SUCCESS && faultInjection("eacces", path)) {  // the same on every rank
    MPI_File_close(&fh);
    rc = MPI_ERR_ACCESS;
  }
  std::string error = rc == MPI_SUCCESS ? "" : "cannot create '" + tmp + "': " + mpiErrorText(rc);
  error = firstErrorOnAnyRank(comm, error);
  if (!error.empty()) return error;
  rc = MPI_File_set_size(fh, 0);  // a stale file of that name may be longer
  if (rc != MPI_SUCCESS) error = "cannot truncate '" + tmp + "': " + mpiErrorText(rc);
  for (const Segment& seg : segments)
    for (size_t done = 0; error.empty() && done < seg.bytes.size(); done += kMaxWriteBytes) {
      const int n = int(std::min(kMaxWriteBytes, seg.bytes.size() - done));
      MPI_Status status;
      rc = MPI_File_write_at(fh, MPI_Offset(seg.offset + done), seg.bytes.data() + done, n, MPI_BYTE, &status);
      int written = 0;
      if (rc == MPI_SUCCESS) MPI_Get_count(&status, MPI_BYTE, &written);
      if (rc != MPI_SUCCESS)
        error = "cannot write '" + tmp + "': " + mpiErrorText(rc);
      else if (written != n || faultInjection("enospc", path))
        error = "cannot write '" + tmp + "': " + std::strerror(ENOSPC);
    }
  rc = MPI_File_sync(fh);  // collective
  if (error.empty() && rc != MPI_SUCCESS) error = "cannot write '" + tmp + "' to disk (sync): " + mpiErrorText(rc);
  rc = MPI_File_close(&fh);  // collective
  if (error.empty() && rc != MPI_SUCCESS) error = "cannot close '" + tmp + "': " + mpiErrorText(rc);
  return firstErrorOnAnyRank(comm, error);
}

void CheckpointWriter::write(const std::string& path) const {
  // Into path + ".tmp", which rank 0 then renames into place and whose
  // directory it syncs (writeFileAtomically()'s steps, shared by the ranks).
  std::vector<std::string> heads;
  const std::vector<Segment> segments = layout(heads);
  const std::string tmp = path + ".tmp";
  std::string error = writeSegments(tmp, path, segments);
  if (comm_->getRank() == 0) {
    std::error_code ec;
    if (!error.empty()) {
      if (!std::filesystem::is_directory(tmp, ec)) std::filesystem::remove(tmp, ec);
    } else if (::rename(tmp.c_str(), path.c_str()) != 0) {
      const int err = errno;
      std::filesystem::remove(tmp, ec);
      error = "cannot replace '" + path + "' by '" + tmp + "': " + std::strerror(err);
    } else {
      try {
        const std::string dir = std::filesystem::path(path).parent_path().string();
        syncDirectory(dir.empty() ? "." : dir);
      } catch (const OutputError& e) {
        error = e.what();
      }
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) throw OutputError(error);
}

namespace {

/// Rank 0's refusal of `path` before reading it, "" if none: not a regular
/// file (collective). `size`: its size in bytes, on every rank.
std::string refuseBeforeReading(const Teuchos::Comm<int>& comm, const std::string& path, double& size) {
  std::string error;
  size = 0;
  if (comm.getRank() == 0) {
    std::error_code ec;
    const auto st = std::filesystem::status(path, ec);
    if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
      error = "the checkpoint '" + path + "' is not a regular file (" +
              (std::filesystem::is_directory(st) ? "a directory" : "a device or special file") +
              "); move it away, or name another run";
    else if (std::filesystem::exists(st))
      size = double(std::filesystem::file_size(path, ec));
  }
  Teuchos::broadcast(comm, 0, Teuchos::outArg(size));
  return firstErrorOnAnyRank(comm, error);
}

/// The refusal of a read that takes `bytes` on some rank, more than the
/// memory available there allows; "" if none (collective).
std::string refuseMemory(const Teuchos::Comm<int>& comm, const std::string& path, double size, double bytes) {
  const MemoryLimit memory = availableMemory(comm);
  if (!(bytes > memory.bytes)) return std::string();
  return "the checkpoint '" + path + "' is " + formatBytes(size) + "; reading it takes about " + formatBytes(bytes) +
         " per rank, more than the " + formatBytes(memory.bytes) + " available (" + memory.source +
         "): restart on a host with more memory, or check that it is the file you meant";
}

std::string corrupted(const std::string& path, double size, const std::string& where = "") {
  std::ostringstream os;
  os << "the checkpoint '" << path << "' is corrupted or truncated (" << std::uint64_t(size)
     << " bytes): its checksum does not match its content" << where;
  return os.str();
}

}  // namespace

std::uint64_t CheckpointReader::VectorTable::entries() const {
  std::uint64_t n = 0;
  for (std::uint64_t c : counts) n += c;
  return n;
}

CheckpointReader::CheckpointReader(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& path)
    : comm_(std::move(comm)), path_(path) {
  double size = 0;
  std::string error = refuseBeforeReading(*comm_, path, size);
  DDC_INPUT_REQUIRE(error.empty(), error);
  std::string magic;
  if (comm_->getRank() == 0) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      error = "cannot read the checkpoint '" + path + "': " + std::strerror(errno);
    } else {
      magic.resize(kMagic2.size());
      in.read(&magic[0], std::streamsize(magic.size()));
      magic.resize(size_t(in.gcount()));
      if (magic != kMagic1 && magic != kMagic2)
        error = "'" + path + "' is not a DDContact checkpoint (version 1) or (version 2): it begins with neither \"" +
                kMagic1.substr(0, kMagic1.size() - 1) + "\" nor \"" + kMagic2.substr(0, kMagic2.size() - 1) + "\"";
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  DDC_INPUT_REQUIRE(error.empty(), error);
  int version = magic == kMagic1 ? 1 : 2;
  Teuchos::broadcast(*comm_, 0, Teuchos::outArg(version));
  if (version == 1)
    readVersion1(size);
  else
    readVersion2(size);
}

void CheckpointReader::readVersion1(double size) {
  // Rank 0 reads and checks the whole file; the others get its sections,
  // and rank 0 holds each vector whole.
  std::string error = refuseMemory(*comm_, path_, size, 2 * size);
  DDC_INPUT_REQUIRE(error.empty(), error);
  std::string content;
  if (comm_->getRank() == 0) {
    std::ifstream in(path_, std::ios::binary);
    std::ostringstream os;
    os << in.rdbuf();
    content = os.str();
    if (content.size() < kMagic1.size() + 2 * sizeof(std::uint64_t))
      error = "the checkpoint '" + path_ + "' is truncated (" + std::to_string(content.size()) + " bytes)";
  }
  error = firstErrorOnAnyRank(*comm_, error);
  DDC_INPUT_REQUIRE(error.empty(), error);
  // Rank 0 checks the hash first (a changed byte anywhere, or a file cut
  // short, whose last 8 bytes are then no hash), then parses the sections.
  std::map<std::string, std::string> vectors;
  if (comm_->getRank() == 0) {
    const size_t body = content.size() - sizeof(std::uint64_t);
    std::uint64_t stored = 0;
    std::memcpy(&stored, content.data() + body, sizeof stored);
    if (stored != fnv1a(content.data(), body)) {
      error = corrupted(path_, double(content.size()));
    } else {
      Cursor c{content, kMagic1.size()};
      std::uint64_t n = 0;
      bool ok = c.get(n);
      for (std::uint64_t k = 0; ok && k < n; ++k) {
        std::uint32_t nameLength = 0;
        std::uint64_t payloadLength = 0;
        std::string name, payload;
        ok = c.get(nameLength) && c.get(name, nameLength) && c.get(payloadLength) && c.get(payload, payloadLength) &&
             c.pos <= body;
        if (ok) sections_[name] = std::move(payload);
      }
      if (!ok || c.pos != body)
        error = "the checkpoint '" + path_ + "' is malformed: its sections do not end where its checksum begins";
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) {
    sections_.clear();
    DDC_THROW(InputError, error);
  }
  broadcastSections();
  // Version 1 does not say which sections are vectors: any of whole
  // (index, value) pairs may be read as one, from rank 0.
  for (const auto& [name, payload] : sections_) {
    if (payload.size() % sizeof(Entry) != 0) continue;
    VectorTable t;
    t.counts.assign(size_t(comm_->getSize()), 0);
    t.counts[0] = payload.size() / sizeof(Entry);
    tables_[name] = t;
    if (comm_->getRank() == 0) pieces_[name] = payload;
  }
}

void CheckpointReader::broadcastSections() {
  long long count = static_cast<long long>(sections_.size());
  Teuchos::broadcast(*comm_, 0, Teuchos::outArg(count));
  auto it = sections_.begin();
  for (long long k = 0; k < count; ++k) {
    std::string name, payload;
    if (comm_->getRank() == 0) name = it->first, payload = it->second, ++it;
    for (std::string* s : {&name, &payload}) {
      long long size = static_cast<long long>(s->size());
      Teuchos::broadcast(*comm_, 0, Teuchos::outArg(size));
      s->resize(size_t(size));
      if (size) Teuchos::broadcast(*comm_, 0, int(size), s->data());
    }
    if (comm_->getRank() != 0) sections_[name] = std::move(payload);
  }
}

std::string CheckpointReader::readHead2(double size, std::map<std::string, VectorTable>& tables) {
  // Rank 0: the sections and the vector tables, skipping the entries,
  // hashed as they are read; the file must end with that hash.
  std::ifstream in(path_, std::ios::binary);
  std::uint64_t hash = fnv1a(kMagic2.data(), kMagic2.size());
  std::uint64_t at = kMagic2.size();
  const std::uint64_t fileSize = std::uint64_t(size);
  bool ok = true;
  // Lengths are checked against what is left of the file before anything
  // is allocated for them (a corrupted length is no reason to run out of
  // memory).
  auto fits = [&](std::uint64_t n) { return n <= fileSize - std::min(fileSize, at); };
  auto read = [&](void* to, std::uint64_t n) {
    ok = ok && fits(n);
    if (!ok) return false;
    in.seekg(std::streamoff(at));
    in.read(static_cast<char*>(to), std::streamsize(n));
    ok = bool(in);
    if (ok) hash = fnv1a(static_cast<const char*>(to), size_t(n), hash), at += n;
    return ok;
  };
  std::uint64_t n = 0;
  read(&n, sizeof n);
  for (std::uint64_t k = 0; ok && k < n; ++k) {
    std::uint32_t nameLength = 0;
    std::uint8_t kind = 0;
    std::string name;
    if (!read(&nameLength, sizeof nameLength) || !(ok = fits(nameLength))) break;
    name.resize(nameLength);
    if (!read(&name[0], nameLength) || !read(&kind, sizeof kind)) break;
    std::uint64_t length = 0;
    if (!read(&length, sizeof length)) break;
    if (kind == kBytesSection) {
      if (!(ok = fits(length))) break;
      std::string payload(size_t(length), '\0');
      if (read(&payload[0], length)) sections_[name] = std::move(payload);
      continue;
    }
    // One piece per writing rank: a count and a hash each.
    if (!(ok = kind == kVectorSection && length <= (fileSize - std::min(fileSize, at)) / 16)) break;
    VectorTable t;
    t.counts.resize(size_t(length));
    t.hashes.resize(t.counts.size());
    if (!read(t.counts.data(), 8 * length) || !read(t.hashes.data(), 8 * length)) break;
    t.dataStart = at;
    const std::uint64_t entries = t.entries();
    ok = entries <= fileSize / sizeof(Entry) && entries * sizeof(Entry) <= fileSize - at;
    at += entries * sizeof(Entry);
    tables[name] = std::move(t);
  }
  std::uint64_t stored = 0;
  const std::uint64_t computed = hash;
  if (!ok || !read(&stored, sizeof stored) || stored != computed || at != fileSize) return corrupted(path_, size);
  return std::string();
}

void CheckpointReader::readVersion2(double size) {
  std::string error;
  std::map<std::string, VectorTable> tables;
  if (comm_->getRank() == 0) error = readHead2(size, tables);
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) {
    sections_.clear();
    DDC_THROW(InputError, error);
  }
  broadcastSections();
  // The vector tables, as one section-like record each.
  long long count = static_cast<long long>(tables.size());
  Teuchos::broadcast(*comm_, 0, Teuchos::outArg(count));
  auto it = tables.begin();
  for (long long k = 0; k < count; ++k) {
    std::string name, record;
    if (comm_->getRank() == 0) {
      name = it->first;
      append<std::uint64_t>(record, it->second.dataStart);
      for (std::uint64_t c : it->second.counts) append<std::uint64_t>(record, c);
      for (std::uint64_t h : it->second.hashes) append<std::uint64_t>(record, h);
      ++it;
    }
    for (std::string* s : {&name, &record}) {
      long long length = static_cast<long long>(s->size());
      Teuchos::broadcast(*comm_, 0, Teuchos::outArg(length));
      s->resize(size_t(length));
      if (length) Teuchos::broadcast(*comm_, 0, int(length), s->data());
    }
    VectorTable t;
    std::memcpy(&t.dataStart, record.data(), 8);
    const size_t pieces = (record.size() - 8) / 16;
    t.counts.resize(pieces), t.hashes.resize(pieces);
    std::memcpy(t.counts.data(), record.data() + 8, 8 * pieces);
    std::memcpy(t.hashes.data(), record.data() + 8 + 8 * pieces, 8 * pieces);
    tables_[name] = std::move(t);
  }
  readPieces(size);
}

void CheckpointReader::readPieces(double size) {
  // Rank q reads the pieces p = q, q + P, ... of every vector (P ranks
  // read) and checks each against its hash: no rank reads the whole file.
  const int ranks = comm_->getSize(), rank = comm_->getRank();
  double mine = 0.0;
  for (const auto& [name, t] : tables_)
    for (size_t p = size_t(rank); p < t.counts.size(); p += size_t(ranks)) mine += double(t.counts[p] * sizeof(Entry));
  double most = mine;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, mine, Teuchos::outArg(most));
  std::string error = refuseMemory(*comm_, path_, size, 3 * most);
  DDC_INPUT_REQUIRE(error.empty(), error);
  std::ifstream in(path_, std::ios::binary);
  for (const auto& [name, t] : tables_) {
    std::string& bytes = pieces_[name];
    std::uint64_t offset = t.dataStart;
    for (size_t p = 0; p < t.counts.size() && error.empty(); ++p) {
      const std::uint64_t n = t.counts[p] * sizeof(Entry);
      if (p % size_t(ranks) == size_t(rank)) {
        std::string piece(size_t(n), '\0');
        in.seekg(std::streamoff(offset));
        in.read(&piece[0], std::streamsize(n));
        if (!in || fnv1a(piece.data(), piece.size()) != t.hashes[p])
          error = corrupted(path_, size, " (piece " + std::to_string(p) + " of the vector '" + name + "')");
        bytes += piece;
      }
      offset += n;
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) {
    sections_.clear(), tables_.clear(), pieces_.clear();
    DDC_THROW(InputError, error);
  }
}

CheckpointReader::~CheckpointReader() = default;

bool CheckpointReader::has(const std::string& name) const {
  return sections_.count(name) != 0 || tables_.count(name) != 0;
}

const std::string& CheckpointReader::bytes(const std::string& name) const {
  const auto it = sections_.find(name);
  DDC_INPUT_REQUIRE(it != sections_.end(), "the checkpoint '" << path_ << "' has no section '" << name << "'");
  return it->second;
}

std::vector<double> CheckpointReader::doubles(const std::string& name) const {
  const std::string& b = bytes(name);
  DDC_INPUT_REQUIRE(b.size() % sizeof(double) == 0, "section '" << name << "' of the checkpoint '" << path_
                                                                 << "' is not a list of doubles");
  std::vector<double> v(b.size() / sizeof(double));
  if (!v.empty()) std::memcpy(v.data(), b.data(), b.size());
  return v;
}

void CheckpointReader::vector(const std::string& name, Vector& v) const {
  // Collective: the entries this rank read go to the owners of their
  // indices in v's map (a directory query), which fill v.
  const auto t = tables_.find(name);
  DDC_INPUT_REQUIRE(t != tables_.end(), "the checkpoint '" << path_ << "' has no vector '" << name << "'"
                                                            << (sections_.count(name) ? " (a section of bytes)" : ""));
  const auto piece = pieces_.find(name);
  std::vector<Entry> entries;
  if (piece != pieces_.end() && !piece->second.empty()) {
    entries.resize(piece->second.size() / sizeof(Entry));
    std::memcpy(entries.data(), piece->second.data(), entries.size() * sizeof(Entry));
  }
  // Tpetra's directory wants each index once per query (the last entry of
  // an index is kept).
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.gid < b.gid; });
  const auto kept = std::unique(entries.rbegin(), entries.rend(),
                                [](const Entry& a, const Entry& b) { return a.gid == b.gid; });
  entries.erase(entries.begin(), kept.base());
  const auto map = v.getMap();
  std::vector<GO> gids(entries.size());
  for (size_t k = 0; k < entries.size(); ++k) gids[k] = GO(entries[k].gid);
  std::vector<int> pids(gids.size());
  std::vector<LO> lids(gids.size());
  map->getRemoteIndexList(Teuchos::ArrayView<const GO>(gids.data(), gids.size()),
                          Teuchos::ArrayView<int>(pids.data(), pids.size()),
                          Teuchos::ArrayView<LO>(lids.data(), lids.size()));
  std::vector<std::vector<Entry>> send(size_t(comm_->getSize()));
  for (size_t k = 0; k < entries.size(); ++k)
    if (pids[k] >= 0) send[size_t(pids[k])].push_back(entries[k]);  // others: not in this model's map
  std::vector<Entry>().swap(entries);
  const std::vector<Entry> mine = exchangeRecords(rawComm(*comm_), send);
  std::string error;
  {
    auto data = v.getDataNonConst();
    std::vector<char> filled(v.getLocalLength(), 0);
    for (const Entry& e : mine) {
      const LO l = map->getLocalElement(GO(e.gid));
      if (l != Teuchos::OrdinalTraits<LO>::invalid()) data[l] = e.value, filled[size_t(l)] = 1;
    }
    for (size_t l = 0; l < filled.size() && error.empty(); ++l)
      if (!filled[l])
        error = "the vector '" + name + "' of the checkpoint '" + path_ + "' has no entry " +
                std::to_string(map->getGlobalElement(LO(l))) + " (it holds " + std::to_string(t->second.entries()) +
                " entries: a checkpoint of another model?)";
  }
  error = firstErrorOnAnyRank(*comm_, error);
  DDC_INPUT_REQUIRE(error.empty(), error);
}

}  // namespace ddc
