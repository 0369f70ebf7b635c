#include "common/crc32.h"

#include <zlib.h>

#include <algorithm>

namespace nmm {

std::uint32_t crc32_update(std::uint32_t crc, const char* data, std::size_t n) {
  uLong c = crc;
  while (n > 0) {
    const std::size_t chunk = std::min<std::size_t>(n, std::size_t{1} << 30);
    c = ::crc32(c, reinterpret_cast<const Bytef*>(data), static_cast<uInt>(chunk));
    data += chunk;
    n -= chunk;
  }
  return static_cast<std::uint32_t>(c);
}

std::uint32_t crc32_of(const char* data, std::size_t n) {
  return crc32_update(static_cast<std::uint32_t>(::crc32(0L, Z_NULL, 0)), data, n);
}

std::uint32_t header_crc(const std::string& bytes, std::size_t table_end, std::size_t crc_offset) {
  static const char zeros[4] = {0, 0, 0, 0};
  std::uint32_t c = crc32_of(bytes.data(), crc_offset);
  c = crc32_update(c, zeros, 4);
  return crc32_update(c, bytes.data() + crc_offset + 4, table_end - crc_offset - 4);
}

}  // namespace nmm
