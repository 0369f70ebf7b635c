// The binary mesh file (.nmm). Byte layout and every rule the reader enforces: docs/mesh-format.md.
//
// The reader treats the file as hostile: every offset, size and index is checked before it is
// used, arithmetic on file values is done in 64 bits with explicit overflow guards, and nothing is
// allocated beyond the size of the file itself. Every byte of the file is covered either by a
// CRC-32 (header + table, each section) or by the rule that padding is zero, so any single-bit
// error is reported rather than silently accepted.
#include "common/mesh_file.h"

#include <openssl/evp.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>
#include <vector>

#include "common/atomic_file.h"
#include "common/byte_fields.h"
#include "common/crc32.h"
#include "common/error.h"
#include "common/number_format.h"
#include "common/whole_file.h"

namespace nmm {

namespace {

// ---- layout constants (docs/mesh-format.md) ---------------------------------------------------

constexpr char kMagic[8] = {'N', 'M', 'M', 'M', 'E', 'S', 'H', '\0'};
constexpr std::uint32_t kEndianMarker = 0x01020304u;
constexpr std::uint32_t kEndianMarkerSwapped = 0x04030201u;
constexpr std::size_t kHeaderSize = 24;
constexpr std::size_t kEntrySize = 40;
constexpr std::size_t kHeaderCrcOffset = 20;
// Far more than any version will need; it bounds the work done on a hostile section count.
constexpr std::uint32_t kMaxSections = 1024;
// PROVENANCE is a handful of short strings; the cap keeps a hostile JSON document small.
constexpr std::uint64_t kMaxProvenanceBytes = 1u << 20;
// Depth allowed in the PROVENANCE JSON: a hostile deeply nested document must not exhaust the
// stack, while leaving room for later versions to add structured fields.
constexpr int kMaxJsonDepth = 16;
constexpr std::size_t kMetaSize = 16;
// Highest-order cover functions in use need 12 unknowns; the bound stops an absurd value from
// making a solver allocate cover_count × dofs_per_cover of nonsense.
constexpr int kMaxDofsPerCover = 64;

enum ElementType : std::uint32_t { kTypeU8 = 1, kTypeI32 = 2, kTypeF64 = 3, kTypeBytes = 4 };

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

// One array of Mesh per section. Exactly one of the member pointers is set, matching `type`.
struct ArrayField {
  const char* tag;
  const char* array;  // the Mesh member's name, for messages
  ElementType type;
  std::vector<double> Mesh::*f64;
  std::vector<std::int32_t> Mesh::*i32;
  std::vector<std::uint8_t> Mesh::*u8;
};

constexpr ArrayField kArrays[] = {
    {"NODEXY", "node_xy", kTypeF64, &Mesh::node_xy, nullptr, nullptr},
    {"TRINODES", "triangle_nodes", kTypeI32, nullptr, &Mesh::triangle_nodes, nullptr},
    {"COVNODE", "cover_node", kTypeI32, nullptr, &Mesh::cover_node, nullptr},
    {"COVBODY", "cover_body", kTypeI32, nullptr, &Mesh::cover_body, nullptr},
    {"ELTRI", "element_triangle", kTypeI32, nullptr, &Mesh::element_triangle, nullptr},
    {"ELBODY", "element_body", kTypeI32, nullptr, &Mesh::element_body, nullptr},
    {"ELBLOCK", "element_block", kTypeI32, nullptr, &Mesh::element_block, nullptr},
    {"ELCOVERS", "element_covers", kTypeI32, nullptr, &Mesh::element_covers, nullptr},
    {"ELLOOPS", "element_loop_offset", kTypeI32, nullptr, &Mesh::element_loop_offset, nullptr},
    {"LOOPXY", "loop_xy", kTypeF64, &Mesh::loop_xy, nullptr, nullptr},
    {"LOOPORIG", "loop_edge_origin", kTypeU8, nullptr, nullptr, &Mesh::loop_edge_origin},
    {"LOOPJNT", "loop_edge_joint", kTypeI32, nullptr, &Mesh::loop_edge_joint, nullptr},
    {"BLKBODY", "block_body", kTypeI32, nullptr, &Mesh::block_body, nullptr},
    {"CEDGE", "contact_edge", kTypeI32, nullptr, &Mesh::contact_edge, nullptr},
    {"CEELEM", "contact_edge_element", kTypeI32, nullptr, &Mesh::contact_edge_element, nullptr},
    {"CEOPP", "contact_edge_opposite", kTypeI32, nullptr, &Mesh::contact_edge_opposite, nullptr},
};

constexpr const char* kTagMeta = "META";
constexpr const char* kTagProvenance = "PROV";
constexpr const char* kTagScene = "SCENE";

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

std::string byte_at(std::uint64_t offset) {
  return "byte " + std::to_string(offset);
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

// ---- container: header + section table + sections ----------------------------------------------

struct OutSection {
  std::string tag;
  std::uint32_t type;
  const char* data;
  std::size_t size;
};

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

struct InSection {
  std::string tag;
  std::uint32_t type = 0;
  std::uint64_t offset = 0;
  std::uint64_t size = 0;
  std::size_t entry = 0;  // index in the section table, for messages
};

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

template <typename T>
void copy_array(const std::string& bytes, const InSection& s, std::vector<T>& out) {
  out.resize(static_cast<std::size_t>(s.size / sizeof(T)));
  if (s.size > 0)
    std::memcpy(out.data(), bytes.data() + s.offset, static_cast<std::size_t>(s.size));
}

// ---- PROVENANCE -----------------------------------------------------------------------------

std::string provenance_json(const Mesh& mesh) {
  nlohmann::json j;
  j["tool"] = mesh.tool;
  j["tool_version"] = mesh.tool_version;
  j["scene_file"] = mesh.scene_file;
  j["scene_sha256"] = to_hex(mesh.scene_sha256);
  j["format_version"] = kMeshFormatVersion;
  // Keys come out sorted (std::map), so the text is a function of the values alone; bytes that
  // are not UTF-8 (a Latin-1 file name) become U+FFFD instead of aborting the write.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

bool parse_hex_digest(const std::string& hex, std::array<std::uint8_t, 32>& out) {
  if (hex.size() != 64) return false;
  for (std::size_t i = 0; i < 32; ++i) {
    int v = 0;
    for (int k = 0; k < 2; ++k) {
      const char c = hex[2 * i + static_cast<std::size_t>(k)];
      int d;
      if (c >= '0' && c <= '9')
        d = c - '0';
      else if (c >= 'a' && c <= 'f')
        d = c - 'a' + 10;
      else
        return false;
      v = v * 16 + d;
    }
    out[i] = static_cast<std::uint8_t>(v);
  }
  return true;
}

void read_provenance(const std::string& text, std::uint32_t version, Mesh& mesh,
                     const std::string& name) {
  const std::string where = std::string("section ") + kTagProvenance;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text, [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
      if (depth > kMaxJsonDepth)
        throw InputError(name, where, "JSON nested deeper than " + std::to_string(kMaxJsonDepth));
      return true;
    });
  } catch (const nlohmann::json::exception& e) {
    throw InputError(name, where, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError(name, where, "not a JSON object");
  auto text_field = [&](const char* key) -> std::string {
    const auto it = j.find(key);
    if (it == j.end() || !it->is_string())
      throw InputError(name, where, std::string("\"") + key + "\" is missing or not a string");
    return it->get<std::string>();
  };
  mesh.tool = text_field("tool");  // any program may write the format; it is kept as written
  mesh.tool_version = text_field("tool_version");
  mesh.scene_file = text_field("scene_file");
  if (!parse_hex_digest(text_field("scene_sha256"), mesh.scene_sha256))
    throw InputError(name, where, "\"scene_sha256\" is not 64 lowercase hexadecimal digits");
  const auto fv = j.find("format_version");
  if (fv == j.end() || !fv->is_number_unsigned() || fv->get<std::uint64_t>() != version)
    throw InputError(name, where,
                     "\"format_version\" is missing or differs from the header's version " +
                         std::to_string(version));
  if (j.size() != 5)
    throw InputError(name, where,
                     "has " + std::to_string(j.size()) +
                         " keys; it holds exactly tool, tool_version, scene_file, scene_sha256 "
                         "and format_version");
  // One text for one set of values: a file that is read must write back to the same bytes
  // (docs/mesh-format.md), so any other spelling of the same JSON — other spacing, escapes, key
  // order, bytes after the document — is refused rather than silently normalised.
  const std::string canonical = provenance_json(mesh);
  if (canonical != text) {
    std::size_t at = 0;
    while (at < text.size() && at < canonical.size() && text[at] == canonical[at]) ++at;
    throw InputError(name, where,
                     "byte " + std::to_string(at) +
                         " of the text differs from the writer's form (sorted keys, two-space "
                         "indent, no escapes beyond JSON's, one final newline)");
  }
}

// ---- validation helpers -------------------------------------------------------------------------

[[noreturn]] void bad(const std::string& name, const char* tag, const std::string& message) {
  throw InputError(name, std::string("section ") + tag, message);
}

std::string n(std::int64_t v) {
  return std::to_string(v);
}

void check_size(const std::string& name, const char* tag, const char* array, std::size_t actual,
                std::size_t expected, const std::string& because) {
  if (actual != expected)
    bad(name, tag,
        std::string(array) + " has " + n(static_cast<std::int64_t>(actual)) + " entries, but " +
            because);
}

void check_finite(const std::string& name, const char* tag, const char* what,
                  const std::vector<double>& xy) {
  for (std::size_t i = 0; i < xy.size(); ++i)
    if (!std::isfinite(xy[i]))
      bad(name, tag,
          std::string(what) + " " + n(static_cast<std::int64_t>(i / 2)) + " coordinate " +
              (i % 2 ? "y" : "x") + " is " + format_number(xy[i]));
}

}  // namespace

// ---- public API -------------------------------------------------------------------------------

std::array<std::uint8_t, 32> sha256(const std::string& bytes) {
  std::array<std::uint8_t, 32> out{};
  unsigned int len = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), out.data(), &len, EVP_sha256(), nullptr) != 1 ||
      len != out.size())
    throw std::runtime_error("SHA-256 failed (OpenSSL EVP_Digest)");
  return out;
}

std::string to_hex(const std::array<std::uint8_t, 32>& digest) {
  static const char digits[] = "0123456789abcdef";
  std::string s;
  s.reserve(64);
  for (std::uint8_t b : digest) {
    s += digits[b >> 4];
    s += digits[b & 15];
  }
  return s;
}

std::string mesh_to_bytes(const Mesh& mesh) {
  // META: f64 mesh_size, i32 dofs_per_cover, u32 reserved (zero).
  char meta[kMetaSize] = {};
  const std::int32_t dofs = mesh.dofs_per_cover;
  std::memcpy(meta, &mesh.mesh_size, 8);
  std::memcpy(meta + 8, &dofs, 4);
  const std::string provenance = provenance_json(mesh);

  std::vector<OutSection> sections;
  sections.push_back({kTagMeta, kTypeBytes, meta, kMetaSize});
  sections.push_back({kTagProvenance, kTypeBytes, provenance.data(), provenance.size()});
  for (const ArrayField& f : kArrays) {
    if (f.f64) {
      const auto& v = mesh.*f.f64;
      sections.push_back({f.tag, f.type, reinterpret_cast<const char*>(v.data()), v.size() * 8});
    } else if (f.i32) {
      const auto& v = mesh.*f.i32;
      sections.push_back({f.tag, f.type, reinterpret_cast<const char*>(v.data()), v.size() * 4});
    } else {
      const auto& v = mesh.*f.u8;
      sections.push_back({f.tag, f.type, reinterpret_cast<const char*>(v.data()), v.size()});
    }
  }
  sections.push_back({kTagScene, kTypeBytes, mesh.scene_text.data(), mesh.scene_text.size()});
  return build_container(sections);
}

Mesh mesh_from_bytes(const std::string& bytes, const std::string& name) {
  const std::map<std::string, InSection> sections = parse_container(bytes, name);
  Mesh mesh;

  const InSection& meta = require(sections, kTagMeta, kTypeBytes, name);
  if (meta.size != kMetaSize)
    throw InputError(name, byte_at(meta.offset),
                     "section META: size " + std::to_string(meta.size) + ", expected " +
                         std::to_string(kMetaSize));
  std::int32_t dofs;
  std::memcpy(&mesh.mesh_size, bytes.data() + meta.offset, 8);
  std::memcpy(&dofs, bytes.data() + meta.offset + 8, 4);
  mesh.dofs_per_cover = dofs;
  if (get_u32(bytes, static_cast<std::size_t>(meta.offset) + 12) != 0)
    throw InputError(name, byte_at(meta.offset + 12), "section META: reserved field is not zero");

  for (const ArrayField& f : kArrays) {
    const InSection& s = require(sections, f.tag, f.type, name);
    if (f.f64)
      copy_array(bytes, s, mesh.*f.f64);
    else if (f.i32)
      copy_array(bytes, s, mesh.*f.i32);
    else
      copy_array(bytes, s, mesh.*f.u8);
  }

  const InSection& scene = require(sections, kTagScene, kTypeBytes, name);
  mesh.scene_text.assign(bytes, static_cast<std::size_t>(scene.offset),
                         static_cast<std::size_t>(scene.size));

  const InSection& prov = require(sections, kTagProvenance, kTypeBytes, name);
  if (prov.size > kMaxProvenanceBytes)
    throw InputError(name, byte_at(prov.offset),
                     "section PROV: " + std::to_string(prov.size) +
                         " bytes, more than the limit of " + std::to_string(kMaxProvenanceBytes));
  read_provenance(
      bytes.substr(static_cast<std::size_t>(prov.offset), static_cast<std::size_t>(prov.size)),
      kMeshFormatVersion, mesh, name);
  // The digest ties the mesh to the scene it was made from; a mismatch means the file was
  // assembled from parts that do not belong together.
  if (sha256(mesh.scene_text) != mesh.scene_sha256)
    throw InputError(name, std::string("section ") + kTagProvenance,
                     "scene_sha256 does not match the SHA-256 of section SCENE");

  validate_mesh(mesh, name);
  return mesh;
}

void validate_mesh(const Mesh& mesh, const std::string& name) {
  // ---- META
  if (!(std::isfinite(mesh.mesh_size) && mesh.mesh_size > 0))
    bad(name, kTagMeta,
        "mesh_size is " + format_number(mesh.mesh_size) + "; it must be a positive finite length");
  if (mesh.dofs_per_cover < 1 || mesh.dofs_per_cover > kMaxDofsPerCover)
    bad(name, kTagMeta,
        "dofs_per_cover is " + n(mesh.dofs_per_cover) + "; it must be between 1 and " +
            n(kMaxDofsPerCover));

  // ---- nodes and triangles
  if (mesh.node_xy.size() % 2 != 0)
    bad(name, "NODEXY",
        "node_xy has " + n(static_cast<std::int64_t>(mesh.node_xy.size())) +
            " values, not a whole number of (x, y) pairs");
  check_finite(name, "NODEXY", "node", mesh.node_xy);
  const std::int64_t nodes = static_cast<std::int64_t>(mesh.node_count());
  if (mesh.triangle_nodes.size() % 3 != 0)
    bad(name, "TRINODES",
        "triangle_nodes has " + n(static_cast<std::int64_t>(mesh.triangle_nodes.size())) +
            " values, not a multiple of 3");
  for (std::size_t i = 0; i < mesh.triangle_nodes.size(); ++i) {
    const std::int64_t v = mesh.triangle_nodes[i];
    if (v < 0 || v >= nodes)
      bad(name, "TRINODES",
          "triangle " + n(static_cast<std::int64_t>(i / 3)) + " node " +
              n(static_cast<std::int64_t>(i % 3)) + " is " + n(v) + ", but there are " + n(nodes) +
              " nodes");
  }
  const std::int64_t triangles = static_cast<std::int64_t>(mesh.triangle_count());

  // ---- physical covers
  const std::size_t covers = mesh.cover_count();
  for (std::size_t c = 0; c < covers; ++c) {
    const std::int64_t v = mesh.cover_node[c];
    if (v < 0 || v >= nodes)
      bad(name, "COVNODE",
          "cover " + n(static_cast<std::int64_t>(c)) + " node is " + n(v) + ", but there are " +
              n(nodes) + " nodes");
  }
  check_size(name, "COVBODY", "cover_body", mesh.cover_body.size(), covers,
             "there are " + n(static_cast<std::int64_t>(covers)) + " covers (cover_node)");
  for (std::size_t c = 0; c < covers; ++c)
    if (mesh.cover_body[c] < 0)
      bad(name, "COVBODY",
          "cover " + n(static_cast<std::int64_t>(c)) + " body is " + n(mesh.cover_body[c]) +
              "; body indices are >= 0");

  // ---- blocks
  const std::int64_t blocks = static_cast<std::int64_t>(mesh.block_count());
  for (std::size_t b = 0; b < mesh.block_body.size(); ++b)
    if (mesh.block_body[b] < 0)
      bad(name, "BLKBODY",
          "block " + n(static_cast<std::int64_t>(b)) + " body is " + n(mesh.block_body[b]) +
              "; body indices are >= 0");

  // ---- manifold elements
  const std::size_t elements = mesh.element_count();
  const std::int64_t elements64 = static_cast<std::int64_t>(elements);
  const std::string per_element = "there are " + n(elements64) + " elements (element_triangle)";
  for (std::size_t e = 0; e < elements; ++e) {
    const std::int64_t t = mesh.element_triangle[e];
    if (t < 0 || t >= triangles)
      bad(name, "ELTRI",
          "element " + n(static_cast<std::int64_t>(e)) + " triangle is " + n(t) +
              ", but there are " + n(triangles) + " triangles");
  }
  check_size(name, "ELBODY", "element_body", mesh.element_body.size(), elements, per_element);
  for (std::size_t e = 0; e < elements; ++e)
    if (mesh.element_body[e] < 0)
      bad(name, "ELBODY",
          "element " + n(static_cast<std::int64_t>(e)) + " body is " + n(mesh.element_body[e]) +
              "; body indices are >= 0");
  check_size(name, "ELBLOCK", "element_block", mesh.element_block.size(), elements, per_element);
  for (std::size_t e = 0; e < elements; ++e) {
    const std::int64_t b = mesh.element_block[e];
    if (b < 0 || b >= blocks)
      bad(name, "ELBLOCK",
          "element " + n(static_cast<std::int64_t>(e)) + " block is " + n(b) + ", but there are " +
              n(blocks) + " blocks");
    // A block is a piece of one body, so its elements lie in that body.
    if (mesh.block_body[static_cast<std::size_t>(b)] != mesh.element_body[e])
      bad(name, "ELBLOCK",
          "element " + n(static_cast<std::int64_t>(e)) + " is in body " + n(mesh.element_body[e]) +
              ", but its block " + n(b) + " is in body " +
              n(mesh.block_body[static_cast<std::size_t>(b)]));
  }
  check_size(name, "ELCOVERS", "element_covers", mesh.element_covers.size(), 3 * elements,
             "3 × " + n(elements64) + " elements need " + n(3 * elements64));
  for (std::size_t e = 0; e < elements; ++e) {
    const std::size_t tri = static_cast<std::size_t>(mesh.element_triangle[e]);
    for (std::size_t k = 0; k < 3; ++k) {
      const std::int64_t c = mesh.element_covers[3 * e + k];
      const std::string which = "element " + n(static_cast<std::int64_t>(e)) + " cover " +
                                n(static_cast<std::int64_t>(k));
      if (c < 0 || c >= static_cast<std::int64_t>(covers))
        bad(name, "ELCOVERS",
            which + " is " + n(c) + ", but there are " + n(static_cast<std::int64_t>(covers)) +
                " physical covers");
      // Cover k of an element is the cover of the element's triangle's node k (same order).
      const std::int32_t node = mesh.cover_node[static_cast<std::size_t>(c)];
      const std::int32_t tri_node = mesh.triangle_nodes[3 * tri + k];
      if (node != tri_node)
        bad(name, "ELCOVERS",
            which + " is " + n(c) + " on node " + n(node) + ", but node " +
                n(static_cast<std::int64_t>(k)) + " of triangle " +
                n(static_cast<std::int64_t>(tri)) + " is " + n(tri_node));
      // A physical cover is a piece of one body, so every element it covers lies in that body.
      const std::int32_t cover_body = mesh.cover_body[static_cast<std::size_t>(c)];
      if (cover_body != mesh.element_body[e])
        bad(name, "ELCOVERS",
            which + " is " + n(c) + " in body " + n(cover_body) + ", but the element is in body " +
                n(mesh.element_body[e]));
    }
  }

  // ---- element loops
  if (mesh.loop_xy.size() % 2 != 0)
    bad(name, "LOOPXY",
        "loop_xy has " + n(static_cast<std::int64_t>(mesh.loop_xy.size())) +
            " values, not a whole number of (x, y) pairs");
  check_finite(name, "LOOPXY", "loop vertex", mesh.loop_xy);
  const std::size_t vertices = mesh.loop_vertex_count();
  const std::int64_t vertices64 = static_cast<std::int64_t>(vertices);
  const auto& off = mesh.element_loop_offset;
  check_size(name, "ELLOOPS", "element_loop_offset", off.size(), elements + 1,
             "there are " + n(elements64) + " elements, so " + n(elements64 + 1) + " are needed");
  if (off[0] != 0)
    bad(name, "ELLOOPS", "element_loop_offset[0] is " + n(off[0]) + "; it must be 0");
  for (std::size_t e = 0; e < elements; ++e) {
    const std::int64_t len = std::int64_t{off[e + 1]} - off[e];
    if (len < 3)
      bad(name, "ELLOOPS",
          "element " + n(static_cast<std::int64_t>(e)) + " loop has " + n(len) +
              " vertices (element_loop_offset " + n(off[e]) + " to " + n(off[e + 1]) +
              "); a loop needs at least 3");
  }
  if (off[elements] != vertices64)
    bad(name, "ELLOOPS",
        "element_loop_offset ends at " + n(off[elements]) + ", but there are " + n(vertices64) +
            " loop vertices");
  check_size(name, "LOOPORIG", "loop_edge_origin", mesh.loop_edge_origin.size(), vertices,
             "there are " + n(vertices64) + " loop vertices");
  constexpr unsigned kKnownOrigins = kEdgeMesh | kEdgeJoint | kEdgeBoundary | kEdgeBridge;
  for (std::size_t v = 0; v < vertices; ++v) {
    const unsigned flags = mesh.loop_edge_origin[v];
    if (flags == 0 || (flags & ~kKnownOrigins) != 0)
      bad(name, "LOOPORIG",
          "loop vertex " + n(static_cast<std::int64_t>(v)) + " edge origin flags are " + n(flags) +
              "; they must be a nonzero combination of 1, 2, 4 and 8");
  }
  check_size(name, "LOOPJNT", "loop_edge_joint", mesh.loop_edge_joint.size(), vertices,
             "there are " + n(vertices64) + " loop vertices");
  for (std::size_t v = 0; v < vertices; ++v) {
    const std::int64_t j = mesh.loop_edge_joint[v];
    const bool on_joint = (mesh.loop_edge_origin[v] & kEdgeJoint) != 0;
    if (j < -1 || on_joint != (j >= 0))
      bad(name, "LOOPJNT",
          "loop vertex " + n(static_cast<std::int64_t>(v)) + " edge joint is " + n(j) +
              (on_joint ? ", but the edge is marked as lying on a joint"
                        : ", but the edge is not marked as lying on a joint (-1 expected)"));
  }

  // ---- contact-candidate edges
  const std::size_t contacts = mesh.contact_edge.size();
  const std::string per_contact =
      "there are " + n(static_cast<std::int64_t>(contacts)) + " contact edges (contact_edge)";
  check_size(name, "CEELEM", "contact_edge_element", mesh.contact_edge_element.size(), contacts,
             per_contact);
  check_size(name, "CEOPP", "contact_edge_opposite", mesh.contact_edge_opposite.size(), contacts,
             per_contact);
  for (std::size_t c = 0; c < contacts; ++c) {
    const std::string which = "contact edge " + n(static_cast<std::int64_t>(c));
    const std::int64_t e = mesh.contact_edge_element[c];
    if (e < 0 || e >= elements64)
      bad(name, "CEELEM",
          which + " element is " + n(e) + ", but there are " + n(elements64) + " elements");
    const std::int64_t v = mesh.contact_edge[c];
    const std::int64_t first = off[static_cast<std::size_t>(e)];
    const std::int64_t end = off[static_cast<std::size_t>(e) + 1];
    if (v < first || v >= end)
      bad(name, "CEDGE",
          which + " is loop vertex " + n(v) + ", outside the loop of its element " + n(e) +
              " (vertices " + n(first) + " to " + n(end - 1) + ")");
    if ((mesh.loop_edge_origin[static_cast<std::size_t>(v)] & (kEdgeJoint | kEdgeBoundary)) == 0)
      bad(name, "CEDGE",
          which + " is loop vertex " + n(v) +
              ", whose edge lies neither on a joint nor on a body boundary");
    const std::int64_t o = mesh.contact_edge_opposite[c];
    if (o < -1 || o >= elements64)
      bad(name, "CEOPP",
          which + " opposite element is " + n(o) + ", but there are " + n(elements64) +
              " elements (-1 for none)");
  }
}

void write_mesh_file(const Mesh& mesh, const std::string& path) {
  write_file_atomically(path, mesh_to_bytes(mesh));
}

Mesh read_mesh_file(const std::string& path) {
  return mesh_from_bytes(read_whole_file(path), path);
}

}  // namespace nmm
