#include "DDC_NetcdfClassicExtent.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace ddc {

namespace {

/// Big-endian reader of a classic header; throws std::runtime_error at its end.
class HeaderReader {
 public:
  HeaderReader(std::ifstream& in, int version) : in_(in), version_(version) {}
  std::uint64_t u32() { return bytes(4); }
  /// NON_NEG / nelems: 8 bytes in CDF-5, 4 otherwise.
  std::uint64_t count() { return bytes(version_ == 5 ? 8 : 4); }
  /// A variable's begin: 4 bytes in CDF-1, 8 otherwise.
  std::uint64_t offset() { return bytes(version_ == 1 ? 4 : 8); }
  std::string name() {
    const std::uint64_t n = count();
    if (n > 65536) throw std::runtime_error("a name of " + std::to_string(n) + " characters");
    std::string s(size_t(n), '\0');
    read(&s[0], n);
    skip((4 - n % 4) % 4);
    return s;
  }
  void skip(std::uint64_t n) {
    in_.seekg(std::streamoff(n), std::ios::cur);
    if (!in_) throw std::runtime_error("the header ends early");
  }

 private:
  std::uint64_t bytes(int n) {
    unsigned char b[8];
    read(reinterpret_cast<char*>(b), n);
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v = (v << 8) | b[i];
    return v;
  }
  void read(char* p, std::uint64_t n) {
    in_.read(p, std::streamsize(n));
    if (!in_) throw std::runtime_error("the header ends early");
  }
  std::ifstream& in_;
  int version_;
};

/// Bytes of one value of netCDF type `t` (0: unknown).
int typeSize(std::uint64_t t) {
  static const int sizes[] = {0, 1, 1, 2, 4, 4, 8, 1, 2, 4, 8, 8};
  return t < 12 ? sizes[t] : 0;
}

/// Skips an attribute list (absent or NC_ATTRIBUTE nelems attributes).
void skipAttributes(HeaderReader& h) {
  const std::uint64_t tag = h.u32(), n = h.count();
  if (tag != 0 && tag != 0x0C) throw std::runtime_error("an attribute list tag " + std::to_string(tag));
  for (std::uint64_t a = 0; a < n; ++a) {
    h.name();
    const int size = typeSize(h.u32());
    if (!size) throw std::runtime_error("an attribute of unknown type");
    const std::uint64_t bytes = h.count() * size;
    h.skip(bytes + (4 - bytes % 4) % 4);
  }
}

}  // namespace

NetcdfClassicExtent netcdfClassicExtent(const std::string& file) {
  NetcdfClassicExtent x;
  std::ifstream in(file, std::ios::binary);
  char magic[4] = {0, 0, 0, 0};
  in.read(magic, 4);
  if (!in || magic[0] != 'C' || magic[1] != 'D' || magic[2] != 'F' || (magic[3] != 1 && magic[3] != 2 && magic[3] != 5))
    return x;
  x.classic = true;
  HeaderReader h(in, magic[3]);
  try {
    std::uint64_t numrecs = h.count();
    if (numrecs == (magic[3] == 5 ? ~std::uint64_t(0) : 0xFFFFFFFFu)) numrecs = 0;  // STREAMING: not yet known
    std::uint64_t tag = h.u32(), n = h.count();
    if (tag != 0 && tag != 0x0A) throw std::runtime_error("a dimension list tag " + std::to_string(tag));
    std::vector<std::uint64_t> dims;  // 0: the record dimension
    for (std::uint64_t d = 0; d < n; ++d) h.name(), dims.push_back(h.count());
    skipAttributes(h);
    tag = h.u32(), n = h.count();
    if (tag != 0 && tag != 0x0B) throw std::runtime_error("a variable list tag " + std::to_string(tag));
    double recordBegin = -1.0, recordSize = 0.0;
    std::string recordVariable;
    for (std::uint64_t v = 0; v < n; ++v) {
      const std::string name = h.name();
      const std::uint64_t rank = h.count();
      double size = 1.0;
      bool record = false;
      for (std::uint64_t r = 0; r < rank; ++r) {
        const std::uint64_t id = h.count();
        if (id >= dims.size()) throw std::runtime_error("variable '" + name + "' names an unknown dimension");
        if (dims[id] == 0 && r == 0) record = true;
        else size *= double(dims[id]);
      }
      skipAttributes(h);
      const int type = typeSize(h.u32());
      if (!type) throw std::runtime_error("variable '" + name + "' of unknown type");
      h.count();  // vsize: recomputed (it saturates for variables over 4 GiB)
      const double begin = double(h.offset());
      size *= type;
      if (record) {
        if (recordBegin < 0.0 || begin < recordBegin) recordBegin = begin;
        recordSize += size;
        recordVariable = name;
      } else if (begin + size > x.end) {
        x.end = begin + size, x.variable = name;
      }
    }
    if (recordBegin >= 0.0 && recordBegin + double(numrecs) * recordSize > x.end)
      x.end = recordBegin + double(numrecs) * recordSize, x.variable = recordVariable;
  } catch (const std::runtime_error& e) {
    x.readable = false;
    x.problem = e.what();
  }
  return x;
}

}  // namespace ddc
