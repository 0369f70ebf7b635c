// The container of the binary mesh file (.nmm): a 24-byte header, a table of 40-byte section
// entries and the sections, 8-byte aligned with zero padding between them (docs/mesh-format.md,
// "Container"). What the sections hold is mesh_file.cpp's; this pair writes and checks the frame.
//
// The reader treats the bytes as hostile: every offset and size is checked before it is used,
// in 64 bits with explicit overflow guards, and every byte of the file is covered either by a
// CRC-32 (header + table, each section) or by the rule that padding is zero, so any single-bit
// error is reported rather than silently accepted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace nmm::mesh_container {

constexpr std::size_t kHeaderSize = 24;  ///< bytes: magic, version, byte order marker, count, CRC
constexpr std::size_t kEntrySize = 40;   ///< bytes of one section table entry

/// Element type of a section (the table entry's type code).
enum ElementType : std::uint32_t { kTypeU8 = 1, kTypeI32 = 2, kTypeF64 = 3, kTypeBytes = 4 };

/// A section to write: its tag (1 to 8 printable ASCII characters), type and bytes.
struct OutSection {
  std::string tag;
  std::uint32_t type;
  const char* data;
  std::size_t size;  ///< bytes
};

/// A section as the table of a file read describes it (checked against the file's size).
struct InSection {
  std::string tag;
  std::uint32_t type = 0;
  std::uint64_t offset = 0;  ///< bytes from the start of the file, a multiple of 8
  std::uint64_t size = 0;    ///< bytes
  std::size_t entry = 0;     ///< index in the section table, for messages
};

/// The file's bytes: header, table and sections in the given order (the format version is
/// mesh_file.h's kMeshFormatVersion).
std::string build_container(const std::vector<OutSection>& sections);

/// Checks the header, the table and the section bounds, CRCs and padding. Returns the sections
/// by tag (unknown tags included; the caller ignores them). Throws InputError(name, "byte N",
/// what) on the first problem.
std::map<std::string, InSection> parse_container(const std::string& bytes, const std::string& name);

/// The section `tag` the format requires, with its element type and a size that is a whole
/// number of elements; InputError naming its table entry otherwise.
const InSection& require(const std::map<std::string, InSection>& sections, const char* tag,
                         std::uint32_t type, const std::string& name);

/// "byte N": where an error is, for InputError.
std::string byte_at(std::uint64_t offset);

}  // namespace nmm::mesh_container
