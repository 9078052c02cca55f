// The FNV-1a 64-bit fingerprint of a file's content: tells a changed file
// from the one recorded (not an attack; Fowler, Noll, Vo, "FNV hash",
// http://www.isthe.com/chongo/tech/comp/fnv/).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace ddc {

/// The FNV-1a 64-bit hash of `n` bytes, continuing from `hash` (the offset
/// basis for a new hash).
std::uint64_t fnv1a(const char* data, std::size_t n, std::uint64_t hash = 14695981039346656037ull);

/// The FNV-1a 64-bit hash of the file `path`, read in pieces; false if it
/// cannot be read as a regular file.
bool fileFingerprint(const std::string& path, std::uint64_t& hash);

/// The hash as 16 hexadecimal digits.
std::string hexFingerprint(std::uint64_t hash);

}  // namespace ddc
