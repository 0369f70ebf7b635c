// The mesh file's container: see mesh_container.h. Byte layout: docs/mesh-format.md.
#include "common/mesh_container.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "common/byte_fields.h"
#include "common/crc32.h"
#include "common/error.h"
#include "common/mesh_file.h"

namespace nmm::mesh_container {

namespace {

// ---- layout constants (docs/mesh-format.md) ---------------------------------------------------

constexpr char kMagic[8] = {'N', 'M', 'M', 'M', 'E', 'S', 'H', '\0'};
constexpr std::uint32_t kEndianMarker = 0x01020304u;
constexpr std::uint32_t kEndianMarkerSwapped = 0x04030201u;
constexpr std::size_t kHeaderCrcOffset = 20;
// Far more than any version will need; it bounds the work done on a hostile section count.
constexpr std::uint32_t kMaxSections = 1024;

const char* type_name(std::uint32_t type) {
  switch (type) {
    case kTypeU8:
      return "u8";
    case kTypeI32:
      return "i32";
    case kTypeF64:
      return "f64";
    case kTypeBytes:
      return "bytes";
    default:
      return "unknown";
  }
}

std::size_t type_size(std::uint32_t type) {
  switch (type) {
    case kTypeI32:
      return 4;
    case kTypeF64:
      return 8;
    default:
      return 1;
  }
}

// ---- little helpers ---------------------------------------------------------------------------

using bytes::get_u32;
using bytes::get_u64;
using bytes::put_u32;
using bytes::put_u64;

std::uint64_t align8(std::uint64_t n) {
  return (n + 7) & ~std::uint64_t{7};
}


// A scene file: text whose first non-blank characters open a JSON object or a // comment
// (scenes start with a comment block). A mesh file starts with the magic "NMMMESH\0".
bool looks_like_scene_json(const std::string& bytes) {
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return false;
  return bytes[first] == '{' || bytes.compare(first, 2, "//") == 0;
}

std::string hex32(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08x", static_cast<unsigned>(v));
  return buf;
}

// A tag from the file as printable text: hostile bytes are shown as \xNN so the one-line error
// format survives.
std::string tag_text(const char* raw) {
  std::string s;
  for (int i = 0; i < 8 && raw[i] != '\0'; ++i) {
    const unsigned char c = static_cast<unsigned char>(raw[i]);
    if (c >= 0x21 && c <= 0x7e) {
      s += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      s += buf;
    }
  }
  return s;
}

// A valid tag is 1 to 8 printable, non-space ASCII characters followed by NUL padding.
bool tag_is_valid(const char* raw) {
  int len = 0;
  while (len < 8 && raw[len] != '\0') {
    const unsigned char c = static_cast<unsigned char>(raw[len]);
    if (c < 0x21 || c > 0x7e) return false;
    ++len;
  }
  if (len == 0) return false;
  for (int i = len; i < 8; ++i)
    if (raw[i] != '\0') return false;
  return true;
}

}  // namespace

std::string byte_at(std::uint64_t offset) {
  return "byte " + std::to_string(offset);
}

// ---- container: header + section table + sections ----------------------------------------------

std::string build_container(const std::vector<OutSection>& sections) {
  const std::size_t table_end = kHeaderSize + kEntrySize * sections.size();
  std::vector<std::uint64_t> offsets;
  std::uint64_t pos = table_end;
  for (const OutSection& s : sections) {
    pos = align8(pos);
    offsets.push_back(pos);
    pos += s.size;
  }
  std::string out(static_cast<std::size_t>(pos), '\0');  // zero-filled: padding must be zero
  std::memcpy(&out[0], kMagic, 8);
  put_u32(out, 8, kMeshFormatVersion);
  put_u32(out, 12, kEndianMarker);
  put_u32(out, 16, static_cast<std::uint32_t>(sections.size()));
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const OutSection& s = sections[i];
    const std::size_t e = kHeaderSize + kEntrySize * i;
    std::memcpy(&out[e], s.tag.data(), std::min<std::size_t>(s.tag.size(), 8));
    put_u32(out, e + 8, s.type);
    put_u64(out, e + 16, offsets[i]);
    put_u64(out, e + 24, s.size);
    put_u32(out, e + 32, crc32_of(s.data, s.size));
    if (s.size > 0) std::memcpy(&out[static_cast<std::size_t>(offsets[i])], s.data, s.size);
  }
  put_u32(out, kHeaderCrcOffset, header_crc(out, table_end, kHeaderCrcOffset));
  return out;
}

// Checks the header, the table and the section bounds, CRCs and padding. Returns the sections by
// tag (unknown tags included; the caller ignores them).
std::map<std::string, InSection> parse_container(const std::string& bytes,
                                                 const std::string& name) {
  const std::uint64_t file_size = bytes.size();
  // The commonest mix-up first: the scene itself handed to a tool that reads meshes.
  if (looks_like_scene_json(bytes))
    throw InputError(name, byte_at(0),
                     "not an nmm mesh file but a scene (JSON): run nmm-preprocess SCENE.json -o "
                     "MESH.nmm first and pass MESH.nmm");
  if (file_size < kHeaderSize)
    throw InputError(name, "",
                     "file is " + std::to_string(file_size) + " bytes, shorter than the " +
                         std::to_string(kHeaderSize) +
                         "-byte header: not an nmm mesh file, or truncated");
  if (std::memcmp(bytes.data(), kMagic, 8) != 0)
    throw InputError(name, byte_at(0), "not an nmm mesh file (wrong magic bytes)");
  // Version before the checksum: a later version may checksum differently, and "wrong version"
  // is the message the user can act on.
  const std::uint32_t version = get_u32(bytes, 8);
  if (version != kMeshFormatVersion)
    throw InputError(name, byte_at(8),
                     "format version " + std::to_string(version) + ", this build reads version " +
                         std::to_string(kMeshFormatVersion));
  const std::uint32_t marker = get_u32(bytes, 12);
  if (marker == kEndianMarkerSwapped)
    throw InputError(name, byte_at(12),
                     "byte order marker reads " + hex32(marker) +
                         ": the file and this machine use different byte orders (nmm mesh files "
                         "are little-endian; this build cannot read them here)");
  if (marker != kEndianMarker)
    throw InputError(name, byte_at(12),
                     "byte order marker is " + hex32(marker) + ", expected " +
                         hex32(kEndianMarker) + " (file corrupted)");
  const std::uint32_t count = get_u32(bytes, 16);
  if (count > kMaxSections)
    throw InputError(name, byte_at(16),
                     "section count " + std::to_string(count) + " is more than the limit of " +
                         std::to_string(kMaxSections) + " (file corrupted)");
  const std::uint64_t table_end = kHeaderSize + std::uint64_t{kEntrySize} * count;
  if (table_end > file_size)
    throw InputError(name, byte_at(kHeaderSize),
                     "the section table of " + std::to_string(count) + " entries ends at byte " +
                         std::to_string(table_end) + ", but the file has only " +
                         std::to_string(file_size) + " bytes (truncated?)");
  if (header_crc(bytes, static_cast<std::size_t>(table_end), kHeaderCrcOffset) !=
      get_u32(bytes, kHeaderCrcOffset))
    throw InputError(name, byte_at(kHeaderCrcOffset), "header checksum mismatch (file corrupted)");

  std::map<std::string, InSection> by_tag;
  std::vector<InSection> all;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t e = kHeaderSize + kEntrySize * i;
    const char* raw = bytes.data() + e;
    const std::string where = byte_at(e);
    if (!tag_is_valid(raw))
      throw InputError(name, where,
                       "section table entry " + std::to_string(i) + ": tag \"" + tag_text(raw) +
                           "\" is not 1 to 8 printable ASCII characters padded with NUL bytes");
    InSection s;
    s.tag = tag_text(raw);
    s.type = get_u32(bytes, e + 8);
    s.offset = get_u64(bytes, e + 16);
    s.size = get_u64(bytes, e + 24);
    s.entry = i;
    const std::string what = "section " + s.tag + ": ";
    if (get_u32(bytes, e + 12) != 0 || get_u32(bytes, e + 36) != 0)
      throw InputError(name, where, what + "reserved table fields are not zero");
    if (s.offset % 8 != 0)
      throw InputError(name, where,
                       what + "offset " + std::to_string(s.offset) + " is not a multiple of 8");
    if (s.offset < table_end)
      throw InputError(
          name, where,
          what + "offset " + std::to_string(s.offset) + " lies inside the header or section table");
    // Written as two comparisons so that offset + size cannot wrap around.
    if (s.offset > file_size || s.size > file_size - s.offset)
      throw InputError(name, where,
                       what + "offset " + std::to_string(s.offset) + " and size " +
                           std::to_string(s.size) + " reach past the end of the file (" +
                           std::to_string(file_size) + " bytes; truncated?)");
    if (by_tag.count(s.tag))
      throw InputError(name, where,
                       what + "appears twice (table entries " +
                           std::to_string(by_tag[s.tag].entry) + " and " + std::to_string(i) + ")");
    by_tag[s.tag] = s;
    all.push_back(s);
  }

  // Sections in file order must not overlap, the gaps between them are zero padding, and the
  // file ends where the last one ends: every byte of the file then has a checked meaning.
  // Among equal offsets the empty sections come first, so that the outcome does not depend on
  // the table order.
  std::stable_sort(all.begin(), all.end(), [](const InSection& a, const InSection& b) {
    return a.offset != b.offset ? a.offset < b.offset : a.size < b.size;
  });
  std::uint64_t cursor = table_end;
  const InSection* previous = nullptr;
  for (const InSection& s : all) {
    if (s.offset < cursor)
      throw InputError(name, byte_at(s.offset),
                       "section " + s.tag + " overlaps section " +
                           (previous ? previous->tag : std::string("?")));
    for (std::uint64_t b = cursor; b < s.offset; ++b)
      if (bytes[static_cast<std::size_t>(b)] != '\0')
        throw InputError(name, byte_at(b),
                         "padding byte before section " + s.tag + " is not zero (file corrupted)");
    cursor = s.offset + s.size;
    previous = &s;
  }
  if (cursor != file_size)
    throw InputError(
        name, byte_at(cursor),
        std::to_string(file_size - cursor) + " bytes follow the last section (file corrupted)");

  for (const InSection& s : all) {
    const std::uint32_t stored = get_u32(bytes, kHeaderSize + kEntrySize * s.entry + 32);
    const std::uint32_t actual =
        crc32_of(bytes.data() + s.offset, static_cast<std::size_t>(s.size));
    if (stored != actual)
      throw InputError(name, byte_at(s.offset),
                       "section " + s.tag + ": checksum mismatch (file corrupted)");
  }
  return by_tag;
}

// Looks up a section the format requires and checks its element type and size.
const InSection& require(const std::map<std::string, InSection>& sections, const char* tag,
                         std::uint32_t type, const std::string& name) {
  const auto it = sections.find(tag);
  if (it == sections.end())
    throw InputError(name, "", std::string("section ") + tag + " is missing");
  const InSection& s = it->second;
  const std::string where = byte_at(kHeaderSize + kEntrySize * s.entry);
  if (s.type != type)
    throw InputError(name, where,
                     std::string("section ") + tag + ": element type code " +
                         std::to_string(s.type) + " (" + type_name(s.type) + "), expected " +
                         std::to_string(type) + " (" + type_name(type) + ")");
  if (s.size % type_size(type) != 0)
    throw InputError(name, where,
                     std::string("section ") + tag + ": size " + std::to_string(s.size) +
                         " is not a multiple of the element size " +
                         std::to_string(type_size(type)));
  return s;
}

}  // namespace nmm::mesh_container
