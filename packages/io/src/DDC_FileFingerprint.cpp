#include "DDC_FileFingerprint.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

namespace ddc {

std::uint64_t fnv1a(const char* data, std::size_t n, std::uint64_t hash) {
  for (std::size_t i = 0; i < n; ++i) {
    hash ^= static_cast<unsigned char>(data[i]);
    hash *= 1099511628211ull;
  }
  return hash;
}

bool fileFingerprint(const std::string& path, std::uint64_t& hash) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::uint64_t h = 14695981039346656037ull;
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    h = fnv1a(buffer.data(), static_cast<std::size_t>(in.gcount()), h);
  }
  if (in.bad()) return false;
  hash = h;
  return true;
}

std::string hexFingerprint(std::uint64_t hash) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
  return buf;
}

}  // namespace ddc
