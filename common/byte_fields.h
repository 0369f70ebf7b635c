// Fixed-width fields of the binary file formats (docs/mesh-format.md, docs/checkpoint-format.md).
// Values are copied with memcpy in host order: both formats are little-endian and carry a byte
// order marker, so a reader on a big-endian host refuses the file instead of misreading it.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

namespace nmm::bytes {

inline void put_u32(std::string& s, std::size_t at, std::uint32_t v) { std::memcpy(&s[at], &v, 4); }
inline void put_u64(std::string& s, std::size_t at, std::uint64_t v) { std::memcpy(&s[at], &v, 8); }
inline std::uint32_t get_u32(const std::string& s, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}
inline std::uint64_t get_u64(const std::string& s, std::size_t at) {
  std::uint64_t v;
  std::memcpy(&v, s.data() + at, 8);
  return v;
}

}  // namespace nmm::bytes
