// libFuzzer target: the mesh file reader (common/mesh_file.cpp) on arbitrary bytes. Any input
// must end in a Mesh or an InputError. Read docs/mesh-format.md for the layout.
//
// CRC-32s guard every byte, so random mutations almost never get past them and the structural
// checks behind them (section placement, array sizes, index ranges) would go untested. The
// first input byte therefore picks a mode: even, the rest is read as it is; odd, the rest gets
// its header and section CRCs recomputed first (where the table lets us find them), so the
// fuzzer explores what lies behind the checksums.
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "common/error.h"
#include "common/mesh_file.h"

namespace {

std::uint32_t crc_of(const std::string& b, std::uint64_t at, std::uint64_t n) {
  return static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(b.data() + at), static_cast<uInt>(n)));
}

template <class T>
T load(const std::string& b, std::size_t at) {
  T v;
  std::memcpy(&v, b.data() + at, sizeof v);
  return v;
}

template <class T>
void store(std::string& b, std::size_t at, T v) {
  std::memcpy(&b[at], &v, sizeof v);
}

// Header 24 bytes, then count × 40-byte entries: offset u64 at +16, size u64 at +24, CRC u32 at
// +32; the header CRC at byte 20 covers [0, table end) with itself taken as zero.
void repair_crcs(std::string& b) {
  if (b.size() < 24) return;
  const std::uint32_t count = load<std::uint32_t>(b, 16);
  if (count > 1024 || 24 + 40ull * count > b.size()) return;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::size_t e = 24 + 40ull * i;
    const std::uint64_t off = load<std::uint64_t>(b, e + 16), size = load<std::uint64_t>(b, e + 24);
    if (off <= b.size() && size <= b.size() - off) store(b, e + 32, crc_of(b, off, size));
  }
  store<std::uint32_t>(b, 20, 0);
  store(b, 20, crc_of(b, 0, 24 + 40ull * count));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] & 1) repair_crcs(bytes);
  try {
    const nmm::Mesh mesh = nmm::mesh_from_bytes(bytes, "fuzz.nmm");
    // What was accepted must be self-consistent and write back to the same bytes.
    nmm::validate_mesh(mesh, "fuzz.nmm");
    if (nmm::mesh_to_bytes(mesh) != bytes) __builtin_trap();
  } catch (const nmm::InputError&) {
  }
  return 0;
}
