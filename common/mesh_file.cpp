// The binary mesh file (.nmm). Byte layout and every rule the reader enforces: docs/mesh-format.md.
//
// The file is a container (common/mesh_container.h: header, section table, sections, each
// checked before use) holding one section per array of the Mesh, META (the mesh size and the
// unknowns per cover), PROV (who wrote it, from which scene, as canonical JSON) and SCENE (the
// scene's text). This file says which sections a mesh is made of and reads them back; the
// consistency of the arrays read is common/mesh_validation.h's. Nothing is allocated beyond the
// size of the file itself: an array is as long as the bytes its section holds.
#include "common/mesh_file.h"

#include <openssl/evp.h>

#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "common/atomic_file.h"
#include "common/byte_fields.h"
#include "common/error.h"
#include "common/mesh_container.h"
#include "common/whole_file.h"

namespace nmm {

using namespace mesh_container;

namespace {

// ---- sections (docs/mesh-format.md) -------------------------------------------------------------

// PROVENANCE is a handful of short strings; the cap keeps a hostile JSON document small.
constexpr std::uint64_t kMaxProvenanceBytes = 1u << 20;
// Depth allowed in the PROVENANCE JSON: a hostile deeply nested document must not exhaust the
// stack, while leaving room for later versions to add structured fields.
constexpr int kMaxJsonDepth = 16;
constexpr std::size_t kMetaSize = 16;

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

using bytes::get_u32;


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

void write_mesh_file(const Mesh& mesh, const std::string& path) {
  write_file_atomically(path, mesh_to_bytes(mesh));
}

Mesh read_mesh_file(const std::string& path) {
  return mesh_from_bytes(read_whole_file(path), path);
}

}  // namespace nmm
