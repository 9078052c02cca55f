#include "DDC_Checkpoint.hpp"

#include <algorithm>
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

const std::string kMagic = "DDContact checkpoint 1\n";


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

}  // namespace

CheckpointWriter::CheckpointWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm) : comm_(std::move(comm)) {}

void CheckpointWriter::add(const std::string& name, std::string payload) {
  if (name.empty()) throw std::invalid_argument("CheckpointWriter: a section needs a name");
  for (const auto& s : sections_)
    if (s.first == name) throw std::invalid_argument("CheckpointWriter: section '" + name + "' given twice");
  sections_.emplace_back(name, std::move(payload));
}

void CheckpointWriter::putBytes(const std::string& name, const std::string& bytes) { add(name, bytes); }

void CheckpointWriter::putDoubles(const std::string& name, const std::vector<double>& values) {
  add(name, std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double)));
}

void CheckpointWriter::putVector(const std::string& name, const Vector& v) {
  const auto map = v.getMap();
  const auto data = v.getData();
  std::vector<std::vector<Entry>> send(comm_->getSize());
  for (size_t l = 0; l < v.getLocalLength(); ++l)
    send[0].push_back({static_cast<long long>(map->getGlobalElement(LO(l))), data[l]});
  auto all = exchangeRecords(rawComm(*comm_), send);
  std::sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) { return a.gid < b.gid; });
  add(name, std::string(reinterpret_cast<const char*>(all.data()), all.size() * sizeof(Entry)));
}

void CheckpointWriter::write(const std::string& path) const {
  std::string error;
  if (comm_->getRank() == 0) {
    std::string out = kMagic;
    append<std::uint64_t>(out, sections_.size());
    for (const auto& [name, payload] : sections_) {
      append<std::uint32_t>(out, std::uint32_t(name.size()));
      out += name;
      append<std::uint64_t>(out, payload.size());
      out += payload;
    }
    append<std::uint64_t>(out, fnv1a(out.data(), out.size()));
    try {
      writeFileAtomically(path, out);
    } catch (const OutputError& e) {
      error = e.what();
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) throw OutputError(error);
}

namespace {

/// Rank 0's refusal of `path` before reading it, "" if none: not a regular
/// file, or larger than the memory reading it takes (the whole file on rank
/// 0 and its sections on every rank: twice its size) allows (collective).
std::string refuseBeforeReading(const Teuchos::Comm<int>& comm, const std::string& path) {
  std::string error;
  double size = 0;
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
  const MemoryLimit memory = availableMemory(comm);
  if (error.empty() && 2 * size > memory.bytes)
    error = "the checkpoint '" + path + "' is " + formatBytes(size) + "; reading it takes about " +
            formatBytes(2 * size) + " per rank, more than the " + formatBytes(memory.bytes) + " available (" +
            memory.source + "): restart on a host with more memory, or check that it is the file you meant";
  return firstErrorOnAnyRank(comm, error);
}

}  // namespace

CheckpointReader::CheckpointReader(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& path)
    : comm_(std::move(comm)), path_(path) {
  // Rank 0 reads and checks; the others get the checked bytes.
  std::string error = refuseBeforeReading(*comm_, path);
  DDC_INPUT_REQUIRE(error.empty(), error);
  std::string content;
  if (comm_->getRank() == 0) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      error = "cannot read the checkpoint '" + path + "': " + std::strerror(errno);
    } else {
      std::ostringstream os;
      os << in.rdbuf();
      content = os.str();
      const std::string head = content.substr(0, kMagic.size());
      if (head != kMagic) {
        error = "'" + path + "' is not a DDContact checkpoint (version 1): it does not begin with \"" +
                kMagic.substr(0, kMagic.size() - 1) + "\"";
      } else if (content.size() < kMagic.size() + 2 * sizeof(std::uint64_t)) {
        error = "the checkpoint '" + path + "' is truncated (" + std::to_string(content.size()) + " bytes)";
      }
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  DDC_INPUT_REQUIRE(error.empty(), error);
  // Rank 0 checks the hash first (a changed byte anywhere, or a file cut
  // short, whose last 8 bytes are then no hash), then parses the sections.
  if (comm_->getRank() == 0) {
    const size_t body = content.size() - sizeof(std::uint64_t);
    std::uint64_t stored = 0;
    std::memcpy(&stored, content.data() + body, sizeof stored);
    if (stored != fnv1a(content.data(), body)) {
      error = "the checkpoint '" + path + "' is corrupted or truncated (" + std::to_string(content.size()) +
              " bytes): its checksum does not match its content";
    } else {
      Cursor c{content, kMagic.size()};
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
        error = "the checkpoint '" + path + "' is malformed: its sections do not end where its checksum begins";
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) {
    sections_.clear();
    DDC_THROW(InputError, error);
  }
  // Broadcast the sections: names and payloads.
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
  const std::string& b = bytes(name);
  DDC_INPUT_REQUIRE(b.size() % sizeof(Entry) == 0, "section '" << name << "' of the checkpoint '" << path_
                                                                << "' is not a vector");
  std::vector<Entry> entries(b.size() / sizeof(Entry));
  if (!entries.empty()) std::memcpy(entries.data(), b.data(), b.size());
  const auto map = v.getMap();
  std::string error;
  {
    auto data = v.getDataNonConst();
    for (size_t l = 0; l < v.getLocalLength() && error.empty(); ++l) {
      const long long gid = static_cast<long long>(map->getGlobalElement(LO(l)));
      const auto e = std::lower_bound(entries.begin(), entries.end(), gid,
                                      [](const Entry& x, long long g) { return x.gid < g; });
      if (e == entries.end() || e->gid != gid)
        error = "the vector '" + name + "' of the checkpoint '" + path_ + "' has no entry " + std::to_string(gid) +
                " (it holds " + std::to_string(entries.size()) + " entries: a checkpoint of another model?)";
      else
        data[l] = e->value;
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  DDC_INPUT_REQUIRE(error.empty(), error);
}

}  // namespace ddc
