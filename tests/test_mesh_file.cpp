// Tests of the binary mesh file: round trips, byte-identical output, atomic writes, and a reader
// that rejects every corruption (bit flips, truncation, hostile tables) and every bad index.
//
// The container helpers below (crc32_ref, split, assemble) are written from docs/mesh-format.md
// alone, with a bitwise CRC-32 rather than zlib, so they double as a check that the document is
// precise enough to write an independent reader and writer.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/mesh.h"
#include "common/mesh_file.h"
#include "tests/temp_dir.h"

namespace nmm {
namespace {

using nmm::test::TempDir;

// ---- a small valid mesh -----------------------------------------------------------------------
//
// Two triangles of side 1: T0 = (n0, n1, n2), T1 = (n1, n3, n2). A joint (joint 0) runs from the
// midpoint of n0–n1 to the midpoint of n0–n2 and cuts off the corner of T0 at n0:
//   element 0: the corner of T0 (block 0), element 1: the rest of T0, element 2: T1 (block 1).
// The joint crosses the stars of n0, n1 and n2 from boundary to boundary, so each of those nodes
// has two physical covers (corner piece, rest); n3 has one.
constexpr double kH = 0.8660254037844386;  // sqrt(3)/2, not exactly representable: tests bits

Mesh small_mesh() {
  Mesh m;
  m.mesh_size = 1.0;
  m.dofs_per_cover = 2;
  m.node_xy = {0, 0, 1, 0, 0.5, kH, 1.5, kH};
  m.triangle_nodes = {0, 1, 2, 1, 3, 2};
  // covers: 0 n0 corner, 1 n0 rest, 2 n1 corner, 3 n1 rest, 4 n2 corner, 5 n2 rest, 6 n3
  m.cover_node = {0, 0, 1, 1, 2, 2, 3};
  m.cover_body = {0, 0, 0, 0, 0, 0, 0};
  m.element_triangle = {0, 0, 1};
  m.element_body = {0, 0, 0};
  m.element_block = {0, 1, 1};
  m.element_covers = {0, 2, 4, 1, 3, 5, 3, 6, 5};
  m.element_loop_offset = {0, 3, 7, 10};
  m.loop_xy = {0,   0, 0.5, 0,  0.25, kH / 2,                // element 0
               0.5, 0, 1,   0,  0.5,  kH,     0.25, kH / 2,  // element 1
               1,   0, 1.5, kH, 0.5,  kH};                   // element 2
  const std::uint8_t mb = kEdgeMesh | kEdgeBoundary;
  m.loop_edge_origin = {mb, kEdgeJoint, mb, mb, kEdgeMesh, mb, kEdgeJoint, mb, mb, kEdgeMesh};
  m.loop_edge_joint = {-1, 0, -1, -1, -1, -1, 0, -1, -1, -1};
  m.block_body = {0, 0};
  m.contact_edge = {0, 1, 2, 3, 5, 6, 7, 8};
  m.contact_edge_element = {0, 0, 0, 1, 1, 1, 2, 2};
  m.contact_edge_opposite = {-1, 1, -1, -1, -1, 0, -1, -1};
  m.tool_version = "0.1.0";
  m.scene_file = "two-triangles.json";
  m.scene_text =
      "// two triangles and a joint\n{\n  \"mesh_size\": 1.0, /* inline */\n  \"bodies\": []\n}\n";
  m.scene_sha256 = sha256(m.scene_text);
  return m;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

void expect_same_mesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(std::memcmp(&a.mesh_size, &b.mesh_size, sizeof(double)), 0);
  EXPECT_EQ(a.dofs_per_cover, b.dofs_per_cover);
  EXPECT_TRUE(same_bits(a.node_xy, b.node_xy));
  EXPECT_EQ(a.triangle_nodes, b.triangle_nodes);
  EXPECT_EQ(a.cover_node, b.cover_node);
  EXPECT_EQ(a.cover_body, b.cover_body);
  EXPECT_EQ(a.element_triangle, b.element_triangle);
  EXPECT_EQ(a.element_body, b.element_body);
  EXPECT_EQ(a.element_block, b.element_block);
  EXPECT_EQ(a.element_covers, b.element_covers);
  EXPECT_EQ(a.element_loop_offset, b.element_loop_offset);
  EXPECT_TRUE(same_bits(a.loop_xy, b.loop_xy));
  EXPECT_EQ(a.loop_edge_origin, b.loop_edge_origin);
  EXPECT_EQ(a.loop_edge_joint, b.loop_edge_joint);
  EXPECT_EQ(a.block_body, b.block_body);
  EXPECT_EQ(a.contact_edge, b.contact_edge);
  EXPECT_EQ(a.contact_edge_element, b.contact_edge_element);
  EXPECT_EQ(a.contact_edge_opposite, b.contact_edge_opposite);
  EXPECT_EQ(a.tool_version, b.tool_version);
  EXPECT_EQ(a.scene_file, b.scene_file);
  EXPECT_EQ(a.scene_text, b.scene_text);
  EXPECT_EQ(a.scene_sha256, b.scene_sha256);
}

// ---- an independent implementation of the container, from docs/mesh-format.md -----------------

std::uint32_t crc32_ref(const char* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= static_cast<unsigned char>(p[i]);
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}

std::uint32_t rd32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i)
    v = (v << 8) | static_cast<unsigned char>(s[at + static_cast<std::size_t>(i)]);
  return v;
}
std::uint64_t rd64(const std::string& s, std::size_t at) {
  return rd32(s, at) | (std::uint64_t{rd32(s, at + 4)} << 32);
}
void wr32(std::string& s, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    s[at + static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xFF);
}
void wr64(std::string& s, std::size_t at, std::uint64_t v) {
  wr32(s, at, static_cast<std::uint32_t>(v));
  wr32(s, at + 4, static_cast<std::uint32_t>(v >> 32));
}

constexpr std::size_t kHeader = 24;
constexpr std::size_t kEntry = 40;

std::size_t entry_at(std::size_t i) {
  return kHeader + kEntry * i;
}

// Recomputes the header CRC after a test has edited the header or the table.
void fix_header_crc(std::string& s) {
  const std::size_t end = kHeader + kEntry * rd32(s, 16);
  wr32(s, 20, 0);
  wr32(s, 20, crc32_ref(s.data(), end));
}

struct Sec {
  std::string tag;
  std::uint32_t type;
  std::string data;
};

std::vector<Sec> split(const std::string& s) {
  std::vector<Sec> out;
  for (std::size_t i = 0; i < rd32(s, 16); ++i) {
    const std::size_t e = entry_at(i);
    Sec sec;
    sec.tag = std::string(s.data() + e, strnlen(s.data() + e, 8));
    sec.type = rd32(s, e + 8);
    sec.data = s.substr(rd64(s, e + 16), rd64(s, e + 24));
    out.push_back(sec);
  }
  return out;
}

std::string assemble(const std::vector<Sec>& secs) {
  std::string s(kHeader + kEntry * secs.size(), '\0');
  std::memcpy(&s[0], "NMMMESH\0", 8);
  wr32(s, 8, 1);
  wr32(s, 12, 0x01020304u);
  wr32(s, 16, static_cast<std::uint32_t>(secs.size()));
  for (std::size_t i = 0; i < secs.size(); ++i) {
    while (s.size() % 8 != 0) s += '\0';
    const std::size_t e = entry_at(i);
    std::memcpy(&s[e], secs[i].tag.data(), secs[i].tag.size());
    wr32(s, e + 8, secs[i].type);
    wr64(s, e + 16, s.size());
    wr64(s, e + 24, secs[i].data.size());
    wr32(s, e + 32, crc32_ref(secs[i].data.data(), secs[i].data.size()));
    s += secs[i].data;
  }
  fix_header_crc(s);
  return s;
}

std::size_t index_of(const std::vector<Sec>& secs, const std::string& tag) {
  for (std::size_t i = 0; i < secs.size(); ++i)
    if (secs[i].tag == tag) return i;
  ADD_FAILURE() << "no section " << tag;
  return 0;
}

// ---- helpers for expected errors --------------------------------------------------------------

// Runs f, expects an InputError, returns it (by value: it is copyable).
InputError expect_input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got std::exception: " << e.what();
    return InputError("", "", "");
  }
  ADD_FAILURE() << "expected InputError, nothing was thrown";
  return InputError("", "", "");
}

InputError parse_error(const std::string& bytes) {
  return expect_input_error([&] { mesh_from_bytes(bytes, "m.nmm"); });
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// ---- round trips and writing ------------------------------------------------------------------

TEST(MeshFile, Sha256KnownVectors) {
  EXPECT_EQ(to_hex(sha256("")), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(to_hex(sha256("abc")),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(MeshFile, SmallMeshIsValid) {
  EXPECT_NO_THROW(validate_mesh(small_mesh(), "small"));
  EXPECT_NEAR(total_area(small_mesh()), 2 * 0.5 * kH, 1e-15);
}

TEST(MeshFile, RoundTripBytes) {
  const Mesh m = small_mesh();
  expect_same_mesh(mesh_from_bytes(mesh_to_bytes(m), "m.nmm"), m);
}

TEST(MeshFile, RoundTripKeepsDoubleBits) {
  Mesh m = small_mesh();
  m.mesh_size = 0.1;  // 0.1 and its neighbours differ only in the last bits
  m.node_xy[2] = std::nextafter(1.0, 2.0);
  m.loop_xy[6] = std::nextafter(1.0, 2.0);
  m.node_xy[0] = -0.0;
  m.loop_xy[0] = -0.0;
  const Mesh back = mesh_from_bytes(mesh_to_bytes(m), "m.nmm");
  expect_same_mesh(back, m);
  EXPECT_TRUE(std::signbit(back.node_xy[0]));
}

TEST(MeshFile, RoundTripFileAndNoTemporaryLeft) {
  TempDir dir;
  const std::string path = dir.path("mesh.nmm");
  const Mesh m = small_mesh();
  write_mesh_file(m, path);
  EXPECT_EQ(dir.entries(), std::set<std::string>{"mesh.nmm"});
  expect_same_mesh(read_mesh_file(path), m);
  EXPECT_EQ(slurp(path), mesh_to_bytes(m));
}

TEST(MeshFile, WritingTwiceGivesIdenticalBytes) {
  TempDir dir;
  const std::string a = dir.path("a.nmm"), b = dir.path("b.nmm");
  write_mesh_file(small_mesh(), a);
  write_mesh_file(small_mesh(), b);
  EXPECT_EQ(slurp(a), slurp(b));
  // Overwriting an existing file replaces it whole.
  Mesh other = small_mesh();
  other.tool_version = "9.9.9";
  write_mesh_file(other, a);
  EXPECT_EQ(read_mesh_file(a).tool_version, "9.9.9");
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"a.nmm", "b.nmm"}));
}

TEST(MeshFile, WriteIntoMissingFolderThrowsAndLeavesNothing) {
  TempDir dir;
  const std::string path = dir.path("missing/mesh.nmm");
  const InputError e = expect_input_error([&] { write_mesh_file(small_mesh(), path); });
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.where(), "");
  EXPECT_EQ(e.message(), "cannot write: No such file or directory");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(MeshFile, WriteOverAFolderThrowsAndRemovesTemporary) {
  TempDir dir;
  const std::string path = dir.path("sub");
  ASSERT_EQ(::mkdir(path.c_str(), 0700), 0);
  const InputError e = expect_input_error([&] { write_mesh_file(small_mesh(), path); });
  EXPECT_TRUE(contains(e.message(), "cannot write: ")) << e.what();
  EXPECT_EQ(dir.entries(), std::set<std::string>{"sub"});
  ::rmdir(path.c_str());
}

TEST(MeshFile, ReadMissingFileThrows) {
  TempDir dir;
  const InputError e = expect_input_error([&] { read_mesh_file(dir.path("none.nmm")); });
  EXPECT_EQ(e.message(), "cannot read: No such file or directory");
}

// ---- the layout as documented ---------------------------------------------------------------

TEST(MeshFile, LayoutMatchesTheDocument) {
  const Mesh m = small_mesh();
  const std::string bytes = mesh_to_bytes(m);
  EXPECT_EQ(std::string(bytes.data(), 8), std::string("NMMMESH\0", 8));
  EXPECT_EQ(rd32(bytes, 8), kMeshFormatVersion);
  EXPECT_EQ(rd32(bytes, 12), 0x01020304u);
  const std::vector<Sec> secs = split(bytes);
  std::vector<std::string> tags;
  for (const Sec& s : secs) tags.push_back(s.tag);
  EXPECT_EQ(tags, (std::vector<std::string>{"META", "PROV", "NODEXY", "TRINODES", "COVNODE",
                                            "COVBODY", "ELTRI", "ELBODY", "ELBLOCK", "ELCOVERS",
                                            "ELLOOPS", "LOOPXY", "LOOPORIG", "LOOPJNT", "BLKBODY",
                                            "CEDGE", "CEELEM", "CEOPP", "SCENE"}));
  for (std::size_t i = 0; i < secs.size(); ++i) EXPECT_EQ(rd64(bytes, entry_at(i) + 16) % 8, 0u);
  // The independent writer reproduces the file byte for byte.
  EXPECT_EQ(assemble(secs), bytes);

  EXPECT_EQ(secs[index_of(secs, "SCENE")].data, m.scene_text);
  const Sec& meta = secs[index_of(secs, "META")];
  ASSERT_EQ(meta.data.size(), 16u);
  double size;
  std::memcpy(&size, meta.data.data(), 8);
  EXPECT_EQ(size, 1.0);
  EXPECT_EQ(rd32(meta.data, 8), 2u);
  EXPECT_EQ(rd32(meta.data, 12), 0u);
  const Sec& loop = secs[index_of(secs, "LOOPXY")];
  EXPECT_EQ(loop.type, 3u);
  EXPECT_EQ(loop.data.size(), m.loop_xy.size() * 8);
  EXPECT_EQ(secs[index_of(secs, "LOOPORIG")].type, 1u);
  EXPECT_EQ(secs[index_of(secs, "CEOPP")].type, 2u);

  const nlohmann::json prov = nlohmann::json::parse(secs[index_of(secs, "PROV")].data);
  EXPECT_EQ(prov.at("tool"), "nmm-preprocess");
  EXPECT_EQ(prov.at("tool_version"), "0.1.0");
  EXPECT_EQ(prov.at("scene_file"), "two-triangles.json");
  EXPECT_EQ(prov.at("scene_sha256"), to_hex(sha256(m.scene_text)));
  EXPECT_EQ(prov.at("format_version"), 1);
  EXPECT_EQ(prov.size(), 5u);  // nothing else: in particular no timestamp
}

TEST(MeshFile, UnknownSectionsAreIgnored) {
  std::vector<Sec> secs = split(mesh_to_bytes(small_mesh()));
  secs.insert(secs.begin() + 3, Sec{"FUTURE", 99, "any bytes at all, of any length"});
  secs.push_back(Sec{"X", 1, ""});
  expect_same_mesh(mesh_from_bytes(assemble(secs), "m.nmm"), small_mesh());
}

TEST(MeshFile, EmptySectionSharingAnOffsetInEitherTableOrder) {
  std::vector<Sec> secs = split(mesh_to_bytes(small_mesh()));
  const std::size_t node = index_of(secs, "NODEXY");
  secs.insert(secs.begin() + static_cast<long>(node), Sec{"EMPTY", 4, ""});
  std::string bytes = assemble(secs);
  // The empty section and NODEXY start at the same byte.
  ASSERT_EQ(rd64(bytes, entry_at(node) + 16), rd64(bytes, entry_at(node + 1) + 16));
  expect_same_mesh(mesh_from_bytes(bytes, "m.nmm"), small_mesh());
  // Swapping their table entries must not change the verdict.
  const std::string a = bytes.substr(entry_at(node), kEntry);
  bytes.replace(entry_at(node), kEntry, bytes.substr(entry_at(node + 1), kEntry));
  bytes.replace(entry_at(node + 1), kEntry, a);
  fix_header_crc(bytes);
  expect_same_mesh(mesh_from_bytes(bytes, "m.nmm"), small_mesh());
}

TEST(MeshFile, EmptyArraysRoundTrip) {
  // A mesh may legitimately have no contact edges; empty sections still appear in the table.
  Mesh m = small_mesh();
  m.contact_edge.clear();
  m.contact_edge_element.clear();
  m.contact_edge_opposite.clear();
  const std::string bytes = mesh_to_bytes(m);
  expect_same_mesh(mesh_from_bytes(bytes, "m.nmm"), m);
  EXPECT_EQ(assemble(split(bytes)), bytes);
}

// ---- corruption -------------------------------------------------------------------------------

TEST(MeshFile, EveryBitFlipIsDetected) {
  const std::string good = mesh_to_bytes(small_mesh());
  // Every bit of the file: header, table, every section and the padding between sections.
  std::size_t rejected = 0;
  for (std::size_t i = 0; i < good.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::string bad = good;
      bad[i] = static_cast<char>(bad[i] ^ (1 << bit));
      try {
        mesh_from_bytes(bad, "m.nmm");
        ADD_FAILURE() << "flip of byte " << i << " bit " << bit << " was accepted";
      } catch (const InputError&) {
        ++rejected;
      } catch (const std::exception& e) {
        ADD_FAILURE() << "flip of byte " << i << " bit " << bit << ": " << e.what();
      }
    }
  }
  EXPECT_EQ(rejected, good.size() * 8);
}

TEST(MeshFile, EveryTruncationIsDetected) {
  const std::string good = mesh_to_bytes(small_mesh());
  for (std::size_t len = 0; len < good.size(); ++len) {
    const InputError e = parse_error(good.substr(0, len));
    EXPECT_FALSE(e.message().empty()) << len;
  }
}

TEST(MeshFile, ReadRejectsTruncatedFile) {
  TempDir dir;
  const std::string path = dir.path("t.nmm");
  write_mesh_file(small_mesh(), path);
  const std::string good = slurp(path);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << good.substr(0, good.size() - 5);
  const InputError e = expect_input_error([&] { read_mesh_file(path); });
  EXPECT_EQ(e.file(), path);
  EXPECT_TRUE(contains(e.message(), "past the end of the file")) << e.what();
}

TEST(MeshFile, TrailingBytesAreRejected) {
  const InputError e = parse_error(mesh_to_bytes(small_mesh()) + std::string(8, '\0'));
  EXPECT_TRUE(contains(e.message(), "follow the last section")) << e.what();
}

TEST(MeshFile, ShortFileMessage) {
  const InputError e = parse_error("NMMMESH");
  EXPECT_EQ(e.where(), "");
  EXPECT_TRUE(contains(e.message(), "not an nmm mesh file")) << e.what();
}

TEST(MeshFile, WrongMagicMessage) {
  std::string bytes = mesh_to_bytes(small_mesh());
  bytes[0] = 'X';
  const InputError e = parse_error(bytes);
  EXPECT_EQ(std::string(e.what()), "m.nmm: byte 0: not an nmm mesh file (wrong magic bytes)");
  // A text file is not a mesh file either.
  EXPECT_TRUE(contains(parse_error(std::string(100, 'a')).message(), "not an nmm mesh file"));
}

TEST(MeshFile, WrongVersionMessage) {
  std::string bytes = mesh_to_bytes(small_mesh());
  wr32(bytes, 8, 7);
  fix_header_crc(bytes);
  const InputError e = parse_error(bytes);
  EXPECT_EQ(std::string(e.what()), "m.nmm: byte 8: format version 7, this build reads version 1");
  // Even with a stale header CRC, the version is what gets reported.
  wr32(bytes, 8, 2);
  EXPECT_EQ(parse_error(bytes).message(), "format version 2, this build reads version 1");
}

TEST(MeshFile, OtherByteOrderIsRejected) {
  std::string bytes = mesh_to_bytes(small_mesh());
  wr32(bytes, 12, 0x04030201u);
  fix_header_crc(bytes);
  const InputError e = parse_error(bytes);
  EXPECT_EQ(e.where(), "byte 12");
  EXPECT_TRUE(contains(e.message(), "byte order")) << e.what();
}

TEST(MeshFile, HeaderChecksumMessage) {
  std::string bytes = mesh_to_bytes(small_mesh());
  bytes[entry_at(3) + 2] ^= 1;  // a tag letter: only the header CRC can catch it
  const InputError e = parse_error(bytes);
  EXPECT_EQ(e.where(), "byte 20");
  EXPECT_EQ(e.message(), "header checksum mismatch (file corrupted)");
}

TEST(MeshFile, SectionChecksumMessage) {
  std::string bytes = mesh_to_bytes(small_mesh());
  const std::size_t i = index_of(split(bytes), "LOOPXY");
  const std::uint64_t offset = rd64(bytes, entry_at(i) + 16);
  bytes[offset + 13] ^= 0x40;
  const InputError e = parse_error(bytes);
  EXPECT_EQ(std::string(e.what()), "m.nmm: byte " + std::to_string(offset) +
                                       ": section LOOPXY: checksum mismatch (file corrupted)");
}

TEST(MeshFile, HugeSectionCountIsRejected) {
  std::string bytes = mesh_to_bytes(small_mesh());
  for (std::uint32_t count : {0xFFFFFFFFu, 1025u, 1000u}) {
    wr32(bytes, 16, count);
    const InputError e = parse_error(bytes);
    EXPECT_EQ(e.where(), count > 1024 ? "byte 16" : "byte 24") << e.what();
  }
}

TEST(MeshFile, HugeOffsetOrSizeIsRejected) {
  const std::string good = mesh_to_bytes(small_mesh());
  const std::size_t e = entry_at(index_of(split(good), "NODEXY"));
  const std::uint64_t offset = rd64(good, e + 16);
  const std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
  struct Case {
    std::uint64_t offset, size;
  };
  // Each huge value alone, and a pair whose sum wraps around to a small number.
  for (const Case c : {Case{max - 7, 8}, Case{offset, max - 7}, Case{offset, max - offset + 9},
                       Case{std::uint64_t{1} << 62, 16}, Case{offset, std::uint64_t{1} << 40}}) {
    std::string bytes = good;
    wr64(bytes, e + 16, c.offset);
    wr64(bytes, e + 24, c.size);
    fix_header_crc(bytes);
    const InputError err = parse_error(bytes);
    EXPECT_EQ(err.where(), "byte " + std::to_string(e)) << err.what();
    EXPECT_TRUE(contains(err.message(), "section NODEXY: ")) << err.what();
  }
}

TEST(MeshFile, HostileTableEntriesAreRejected) {
  const std::string good = mesh_to_bytes(small_mesh());
  const std::vector<Sec> secs = split(good);
  struct Case {
    const char* what;
    std::function<void(std::string&)> edit;
    const char* expected;
  };
  const std::size_t node = entry_at(index_of(secs, "NODEXY"));
  const std::size_t tri = entry_at(index_of(secs, "TRINODES"));
  const Case cases[] = {
      {"unaligned offset", [&](std::string& b) { wr64(b, node + 16, rd64(b, node + 16) + 4); },
       "not a multiple of 8"},
      {"offset inside the table", [&](std::string& b) { wr64(b, node + 16, 8); },
       "inside the header or section table"},
      {"overlap", [&](std::string& b) { wr64(b, tri + 16, rd64(b, node + 16)); }, "overlaps"},
      {"reserved field", [&](std::string& b) { wr32(b, node + 12, 1); }, "reserved"},
      {"bad tag", [&](std::string& b) { b[node + 1] = '\n'; }, "printable ASCII"},
      {"tag not NUL padded", [&](std::string& b) { b[node + 7] = 'Z'; }, "printable ASCII"},
  };
  for (const Case& c : cases) {
    std::string bytes = good;
    c.edit(bytes);
    fix_header_crc(bytes);
    const InputError e = parse_error(bytes);
    EXPECT_TRUE(contains(e.message(), c.expected)) << c.what << ": " << e.what();
  }
}

TEST(MeshFile, SectionListErrors) {
  const std::vector<Sec> good = split(mesh_to_bytes(small_mesh()));
  {
    std::vector<Sec> secs = good;
    secs[index_of(secs, "CEELEM")].tag = "CEDGE";
    const InputError e = parse_error(assemble(secs));
    EXPECT_TRUE(contains(e.message(), "section CEDGE: appears twice")) << e.what();
  }
  {
    std::vector<Sec> secs = good;
    secs.erase(secs.begin() + static_cast<long>(index_of(secs, "LOOPJNT")));
    EXPECT_EQ(parse_error(assemble(secs)).message(), "section LOOPJNT is missing");
  }
  {
    std::vector<Sec> secs = good;
    secs[index_of(secs, "ELTRI")].type = 3;
    const InputError e = parse_error(assemble(secs));
    EXPECT_TRUE(contains(e.message(), "section ELTRI: element type code 3 (f64), expected 2"))
        << e.what();
  }
  {
    std::vector<Sec> secs = good;
    secs[index_of(secs, "LOOPXY")].data += "abc";
    const InputError e = parse_error(assemble(secs));
    EXPECT_TRUE(contains(e.message(),
                         "section LOOPXY: size 163 is not a multiple of the element "
                         "size 8"))
        << e.what();
  }
  {
    std::vector<Sec> secs = good;
    secs[index_of(secs, "META")].data += std::string(8, '\0');
    EXPECT_TRUE(contains(parse_error(assemble(secs)).message(), "section META: size 24"));
  }
  {
    std::vector<Sec> secs = good;
    secs[index_of(secs, "SCENE")].data += " ";
    const InputError e = parse_error(assemble(secs));
    EXPECT_EQ(e.where(), "section PROV");
    EXPECT_TRUE(contains(e.message(), "scene_sha256")) << e.what();
  }
}

TEST(MeshFile, HostileProvenanceIsRejected) {
  const std::vector<Sec> good = split(mesh_to_bytes(small_mesh()));
  const std::size_t p = index_of(good, "PROV");
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  const std::string hex = to_hex(sha256(small_mesh().scene_text));
  const std::string base = R"("tool": "t", "tool_version": "1", "scene_file": "s", )";
  for (const std::string& text :
       {deep, std::string("not json"), std::string("[]"), std::string("{\"tool\": 1}"),
        std::string("\xff\xfe"), "{" + base + R"("scene_sha256": "abc", "format_version": 1})",
        "{" + base + R"("scene_sha256": ")" + hex + R"(", "format_version": 2})",
        "{" + base + R"("scene_sha256": ")" + hex + R"(", "format_version": 1, "x": )" + deep +
            "}"}) {
    std::vector<Sec> secs = good;
    secs[p].data = text;
    const InputError e = parse_error(assemble(secs));
    EXPECT_EQ(e.where(), "section PROV") << e.what();
  }
}

// A file that is read must write back to the same bytes, so PROV holds one text per set of
// values: the writer's. Valid JSON with the same values spelt otherwise is refused, naming the
// first byte that differs.
TEST(MeshFile, ProvenanceMustBeInTheWritersForm) {
  const std::vector<Sec> good = split(mesh_to_bytes(small_mesh()));
  const std::size_t p = index_of(good, "PROV");
  const std::string canonical = good[p].data;
  const std::string hex = to_hex(sha256(small_mesh().scene_text));
  const std::string base = R"("tool": "t", "tool_version": "1", "scene_file": "s", )";
  struct Case {
    std::string text, byte;
  };
  std::string nul_end = canonical;
  nul_end.back() = '\0';  // found by libFuzzer: the final newline turned into NUL was accepted
  std::string escaped = canonical;
  escaped.replace(escaped.find("nmm-preprocess"), 1, "\\u006e");  // "n" written as \u006e
  for (const Case& c : std::vector<Case>{
           {nul_end, "byte " + std::to_string(canonical.size() - 1)},
           {canonical.substr(0, canonical.size() - 1), "byte " + std::to_string(canonical.size() - 1)},
           {canonical + "\n", "byte " + std::to_string(canonical.size())},
           {escaped, "byte " + std::to_string(canonical.find("nmm-preprocess"))},
           {"{" + base + R"("scene_sha256": ")" + hex + R"(", "format_version": 1})", "byte 1"}}) {
    std::vector<Sec> secs = good;
    secs[p].data = c.text;
    const InputError e = parse_error(assemble(secs));
    EXPECT_EQ(e.where(), "section PROV") << e.what();
    EXPECT_TRUE(contains(e.message(), c.byte + " of the text differs from the writer's form"))
        << e.what();
  }
  // An extra key is refused by name of the rule, whatever the spelling.
  std::vector<Sec> secs = good;
  secs[p].data = "{\"extra\": [1, {\"a\": 2}], " + base + R"("scene_sha256": ")" + hex +
                 R"(", "format_version": 1})";
  EXPECT_TRUE(contains(parse_error(assemble(secs)).message(), "has 6 keys")) << "extra key";
  // Another program's name is kept as written, and the file writes back to the same bytes.
  Mesh other = small_mesh();
  other.tool = "a-converter";
  const std::string bytes = mesh_to_bytes(other);
  const Mesh back = mesh_from_bytes(bytes, "m.nmm");
  EXPECT_EQ(back.tool, "a-converter");
  EXPECT_EQ(mesh_to_bytes(back), bytes);
}

// ---- validation ---------------------------------------------------------------------------------

struct BadCase {
  const char* what;
  std::function<void(Mesh&)> edit;
  const char* where;    // the section named in the error
  const char* message;  // a part of the message (the array or the item named)
};

const std::vector<BadCase>& bad_cases() {
  static const std::vector<BadCase> cases = {
      {"mesh size zero", [](Mesh& m) { m.mesh_size = 0; }, "section META", "mesh_size is 0"},
      {"mesh size NaN", [](Mesh& m) { m.mesh_size = std::nan(""); }, "section META", "mesh_size"},
      {"no dofs", [](Mesh& m) { m.dofs_per_cover = 0; }, "section META", "dofs_per_cover is 0"},
      {"odd node_xy", [](Mesh& m) { m.node_xy.push_back(1); }, "section NODEXY", "node_xy has 9"},
      {"infinite node", [](Mesh& m) { m.node_xy[5] = INFINITY; }, "section NODEXY",
       "node 2 coordinate y is inf"},
      {"triangle_nodes not triples", [](Mesh& m) { m.triangle_nodes.push_back(0); },
       "section TRINODES", "triangle_nodes has 7"},
      {"triangle node out of range", [](Mesh& m) { m.triangle_nodes[4] = 4; }, "section TRINODES",
       "triangle 1 node 1 is 4, but there are 4 nodes"},
      {"negative triangle node", [](Mesh& m) { m.triangle_nodes[0] = -1; }, "section TRINODES",
       "triangle 0 node 0 is -1"},
      {"cover node out of range", [](Mesh& m) { m.cover_node[6] = 99; }, "section COVNODE",
       "cover 6 node is 99"},
      {"cover_body length", [](Mesh& m) { m.cover_body.pop_back(); }, "section COVBODY",
       "cover_body has 6 entries"},
      {"negative cover body", [](Mesh& m) { m.cover_body[1] = -3; }, "section COVBODY",
       "cover 1 body is -3"},
      {"element triangle out of range", [](Mesh& m) { m.element_triangle[2] = 2; }, "section ELTRI",
       "element 2 triangle is 2, but there are 2 triangles"},
      {"element_body length", [](Mesh& m) { m.element_body.push_back(0); }, "section ELBODY",
       "element_body has 4 entries"},
      {"element block out of range", [](Mesh& m) { m.element_block[0] = 2; }, "section ELBLOCK",
       "element 0 block is 2, but there are 2 blocks"},
      {"block in another body", [](Mesh& m) { m.block_body[1] = 1; }, "section ELBLOCK",
       "element 1 is in body 0, but its block 1 is in body 1"},
      {"element_covers length", [](Mesh& m) { m.element_covers.pop_back(); }, "section ELCOVERS",
       "element_covers has 8 entries"},
      {"cover out of range", [](Mesh& m) { m.element_covers[7] = 9001; }, "section ELCOVERS",
       "element 2 cover 1 is 9001, but there are 7 physical covers"},
      {"cover of the wrong node", [](Mesh& m) { m.element_covers[1] = 4; }, "section ELCOVERS",
       "element 0 cover 1 is 4 on node 2, but node 1 of triangle 0 is 1"},
      {"cover in another body", [](Mesh& m) { m.cover_body[0] = 5; }, "section ELCOVERS",
       "element 0 cover 0 is 0 in body 5"},
      {"odd loop_xy", [](Mesh& m) { m.loop_xy.pop_back(); }, "section LOOPXY", "loop_xy has 19"},
      {"NaN loop vertex", [](Mesh& m) { m.loop_xy[8] = std::nan(""); }, "section LOOPXY",
       "loop vertex 4 coordinate x is nan"},
      {"loop offset length", [](Mesh& m) { m.element_loop_offset.pop_back(); }, "section ELLOOPS",
       "element_loop_offset has 3 entries"},
      {"loop offset not from 0", [](Mesh& m) { m.element_loop_offset[0] = 1; }, "section ELLOOPS",
       "element_loop_offset[0] is 1"},
      {"loop of two vertices", [](Mesh& m) { m.element_loop_offset[1] = 2; }, "section ELLOOPS",
       "element 0 loop has 2 vertices"},
      {"decreasing loop offsets", [](Mesh& m) { m.element_loop_offset[2] = 2; }, "section ELLOOPS",
       "element 1 loop has -1 vertices"},
      {"loop offsets end early", [](Mesh& m) { m.element_loop_offset[3] = 9; }, "section ELLOOPS",
       "element 2 loop has 2 vertices"},
      {"loop offsets end past the vertices", [](Mesh& m) { m.element_loop_offset[3] = 13; },
       "section ELLOOPS", "element_loop_offset ends at 13, but there are 10 loop vertices"},
      {"origin length", [](Mesh& m) { m.loop_edge_origin.pop_back(); }, "section LOOPORIG",
       "loop_edge_origin has 9 entries"},
      {"unknown origin flag", [](Mesh& m) { m.loop_edge_origin[4] = 32; }, "section LOOPORIG",
       "loop vertex 4 edge origin flags are 32"},
      {"joint edge without joint", [](Mesh& m) { m.loop_edge_joint[1] = -1; }, "section LOOPJNT",
       "loop vertex 1 edge joint is -1, but the edge is marked as lying on a joint"},
      {"joint on a non-joint edge", [](Mesh& m) { m.loop_edge_joint[0] = 3; }, "section LOOPJNT",
       "loop vertex 0 edge joint is 3"},
      {"contact element length", [](Mesh& m) { m.contact_edge_element.pop_back(); },
       "section CEELEM", "contact_edge_element has 7 entries, but there are 8 contact edges"},
      {"contact opposite length", [](Mesh& m) { m.contact_edge_opposite.push_back(-1); },
       "section CEOPP", "contact_edge_opposite has 9 entries"},
      {"contact element out of range", [](Mesh& m) { m.contact_edge_element[3] = 3; },
       "section CEELEM", "contact edge 3 element is 3, but there are 3 elements"},
      {"contact edge out of range", [](Mesh& m) { m.contact_edge[7] = 10; }, "section CEDGE",
       "contact edge 7 is loop vertex 10, outside the loop of its element 2 (vertices 7 to 9)"},
      {"contact edge in another element's loop", [](Mesh& m) { m.contact_edge[0] = 3; },
       "section CEDGE", "contact edge 0 is loop vertex 3, outside the loop of its element 0"},
      {"contact edge on a mesh edge", [](Mesh& m) { m.contact_edge[4] = 4; }, "section CEDGE",
       "contact edge 4 is loop vertex 4, whose edge lies neither"},
      {"opposite out of range", [](Mesh& m) { m.contact_edge_opposite[1] = 3; }, "section CEOPP",
       "contact edge 1 opposite element is 3"},
      {"opposite below -1", [](Mesh& m) { m.contact_edge_opposite[0] = -2; }, "section CEOPP",
       "contact edge 0 opposite element is -2"},
  };
  return cases;
}

TEST(MeshFile, ValidateCatchesEveryKindOfBadMesh) {
  for (const BadCase& c : bad_cases()) {
    Mesh m = small_mesh();
    c.edit(m);
    const InputError e = expect_input_error([&] { validate_mesh(m, "bad.nmm"); });
    EXPECT_EQ(e.file(), "bad.nmm") << c.what;
    EXPECT_EQ(e.where(), c.where) << c.what << ": " << e.what();
    EXPECT_TRUE(contains(e.message(), c.message)) << c.what << ": " << e.what();
  }
}

TEST(MeshFile, ReaderValidatesTheMesh) {
  // The writer stores what it is given; the reader must refuse it. Same errors, same places.
  for (const BadCase& c : bad_cases()) {
    Mesh m = small_mesh();
    c.edit(m);
    const InputError e = parse_error(mesh_to_bytes(m));
    EXPECT_EQ(e.where(), c.where) << c.what << ": " << e.what();
    EXPECT_TRUE(contains(e.message(), c.message)) << c.what << ": " << e.what();
  }
}

TEST(MeshFile, GarbageWithValidChecksumsNeverCrashes) {
  // Bit flips stop at the CRC. Here the CRCs are recomputed after the damage, so the garbage
  // reaches validate_mesh(): it must still end in InputError or a valid mesh, never an
  // out-of-bounds read (run under -fsanitize=address,undefined to see those).
  const std::vector<Sec> good = split(mesh_to_bytes(small_mesh()));
  std::uint32_t state = 12345;
  auto next = [&state] {  // xorshift32: deterministic, so a failure is reproducible
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return state;
  };
  const std::int32_t interesting[] = {-2147483647 - 1, -2, -1, 0, 1, 2, 3, 6, 7, 9, 10, 11,
                                      2147483647};
  std::size_t accepted = 0;
  for (int round = 0; round < 3000; ++round) {
    std::vector<Sec> secs = good;
    const int edits = 1 + static_cast<int>(next() % 3);
    for (int k = 0; k < edits; ++k) {
      Sec& s = secs[2 + next() % (secs.size() - 3)];  // an array section: not META, PROV, SCENE
      if (s.data.empty()) continue;
      if (s.type == 2) {
        const std::size_t i = 4 * (next() % (s.data.size() / 4));
        wr32(s.data, i, static_cast<std::uint32_t>(interesting[next() % 13]));
      } else if (s.type == 3 && next() % 2 == 0) {
        s.data.resize(s.data.size() - 8);  // drop a coordinate: lengths stop agreeing
      } else {
        s.data[next() % s.data.size()] = static_cast<char>(next());
      }
    }
    try {
      const Mesh m = mesh_from_bytes(assemble(secs), "m.nmm");
      ++accepted;
      EXPECT_NO_THROW(validate_mesh(m, "m.nmm"));
    } catch (const InputError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << "round " << round << ": " << e.what();
    }
  }
  EXPECT_LT(accepted, 3000u);
}

TEST(MeshFile, OneLineErrorForHostileTag) {
  std::string bytes = mesh_to_bytes(small_mesh());
  std::memcpy(&bytes[entry_at(0)], "A\nB\0\0\0\0\0", 8);
  fix_header_crc(bytes);
  const std::string what = parse_error(bytes).what();
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  EXPECT_TRUE(contains(what, "A\\x0aB")) << what;
}

}  // namespace
}  // namespace nmm
