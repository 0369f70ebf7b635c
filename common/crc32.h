// CRC-32 (zlib's: reflected 0xEDB88320, init and final XOR 0xFFFFFFFF) for the binary files
// with a section table: the mesh file (docs/mesh-format.md) and the checkpoint
// (docs/checkpoint-format.md). Both put a header CRC at the same offset.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace nmm {

/// CRC-32 continued over n more bytes (fed to zlib in chunks, so lengths over 4 GiB are right).
std::uint32_t crc32_update(std::uint32_t crc, const char* data, std::size_t n);

/// CRC-32 of n bytes.
std::uint32_t crc32_of(const char* data, std::size_t n);

/// CRC-32 of bytes [0, table_end) with the 4 bytes at crc_offset (the header CRC field itself)
/// counted as zero.
std::uint32_t header_crc(const std::string& bytes, std::size_t table_end, std::size_t crc_offset);

}  // namespace nmm
