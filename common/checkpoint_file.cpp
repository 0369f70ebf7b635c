// The checkpoint container (checkpoint_file.h): header, section table, CRC-32 per section.
#include "common/checkpoint_file.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <set>

#include "common/atomic_file.h"
#include "common/byte_fields.h"
#include "common/crc32.h"
#include "common/error.h"
#include "common/whole_file.h"

namespace nmm {

namespace {

constexpr char kMagic[8] = {'N', 'M', 'M', 'S', 'T', 'A', 'T', 'E'};
constexpr std::uint32_t kEndianMarker = 0x01020304u;
constexpr std::size_t kHeaderSize = 32, kEntrySize = 32, kHeaderCrcOffset = 20;

using bytes::get_u32;
using bytes::get_u64;
using bytes::put_u32;
using bytes::put_u64;

bool tag_ok(const char* raw, std::string& tag) {
  tag.clear();
  int len = 0;
  while (len < 8 && raw[len] != '\0') {
    const unsigned char c = static_cast<unsigned char>(raw[len]);
    if (c < 0x21 || c > 0x7e) return false;
    tag += static_cast<char>(c);
    ++len;
  }
  if (len == 0) return false;
  for (int i = len; i < 8; ++i)
    if (raw[i] != '\0') return false;
  return true;
}

std::string at_byte(std::uint64_t n) { return "byte " + std::to_string(n); }

}  // namespace

std::string checkpoint_to_bytes(const CheckpointSections& sections) {
  const std::size_t table_end = kHeaderSize + kEntrySize * sections.size();
  std::size_t total = table_end;
  for (const auto& s : sections) total += s.second.size();
  std::string out(total, '\0');
  std::memcpy(&out[0], kMagic, 8);
  put_u32(out, 8, kCheckpointFormatVersion);
  put_u32(out, 12, kEndianMarker);
  put_u32(out, 16, static_cast<std::uint32_t>(sections.size()));
  put_u64(out, 24, total);
  std::size_t pos = table_end;
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const auto& [tag, data] = sections[i];
    const std::size_t e = kHeaderSize + kEntrySize * i;
    std::memcpy(&out[e], tag.data(), std::min<std::size_t>(tag.size(), 8));
    put_u64(out, e + 8, pos);
    put_u64(out, e + 16, data.size());
    put_u32(out, e + 24, crc32_of(data.data(), data.size()));
    if (!data.empty()) std::memcpy(&out[pos], data.data(), data.size());
    pos += data.size();
  }
  put_u32(out, kHeaderCrcOffset, header_crc(out, table_end, kHeaderCrcOffset));
  return out;
}

CheckpointSections checkpoint_from_bytes(const std::string& b, const std::string& name) {
  auto bad = [&](const std::string& where, const std::string& what) -> void {
    throw InputError(name, where, what);
  };
  if (b.size() < kHeaderSize)
    bad(at_byte(b.size()), "not a checkpoint: the file is " + std::to_string(b.size()) +
                               " bytes, shorter than the 32-byte header");
  if (std::memcmp(b.data(), kMagic, 8) != 0)
    bad(at_byte(0), "not a checkpoint (.nmmstate) file: wrong magic");
  if (get_u32(b, 12) != kEndianMarker) bad(at_byte(12), "wrong byte order marker");
  if (get_u32(b, 8) != kCheckpointFormatVersion)
    bad(at_byte(8), "checkpoint format version " + std::to_string(get_u32(b, 8)) +
                        ", this nmm-solve reads version " +
                        std::to_string(kCheckpointFormatVersion));
  const std::uint64_t total = get_u64(b, 24);
  if (total != b.size())
    bad(at_byte(24), "the header says the file has " + std::to_string(total) + " bytes, it has " +
                         std::to_string(b.size()) + " (truncated or damaged)");
  const std::uint64_t count = get_u32(b, 16);
  if (count > (b.size() - kHeaderSize) / kEntrySize)
    bad(at_byte(16), "section count " + std::to_string(count) + " does not fit in the file");
  const std::size_t table_end = kHeaderSize + kEntrySize * static_cast<std::size_t>(count);
  if (header_crc(b, table_end, kHeaderCrcOffset) != get_u32(b, kHeaderCrcOffset))
    bad(at_byte(kHeaderCrcOffset), "header CRC-32 mismatch (the header or section table is damaged)");
  CheckpointSections out;
  std::set<std::string> seen;
  std::uint64_t pos = table_end;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t e = kHeaderSize + kEntrySize * i;
    std::string tag;
    if (!tag_ok(b.data() + e, tag)) bad(at_byte(e), "section " + std::to_string(i) + ": bad tag");
    if (!seen.insert(tag).second) bad(at_byte(e), "section " + tag + " appears twice");
    const std::uint64_t off = get_u64(b, e + 8), size = get_u64(b, e + 16);
    if (off != pos || size > b.size() - off)
      bad(at_byte(e + 8), "section " + tag + ": offset " + std::to_string(off) + " size " +
                              std::to_string(size) + " out of place or past the end");
    if (get_u32(b, e + 28) != 0) bad(at_byte(e + 28), "section " + tag + ": reserved field not zero");
    if (crc32_of(b.data() + off, static_cast<std::size_t>(size)) != get_u32(b, e + 24))
      bad("section " + tag, "CRC-32 mismatch (the data is damaged)");
    out.emplace_back(tag, b.substr(static_cast<std::size_t>(off), static_cast<std::size_t>(size)));
    pos = off + size;
  }
  if (pos != b.size()) bad(at_byte(pos), "bytes after the last section");
  return out;
}

void write_checkpoint_file(const CheckpointSections& sections, const std::string& path) {
  write_file_atomically(path, checkpoint_to_bytes(sections));
}

CheckpointSections read_checkpoint_file(const std::string& path) {
  return checkpoint_from_bytes(read_whole_file(path), path);
}

}  // namespace nmm
