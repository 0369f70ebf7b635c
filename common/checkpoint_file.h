// The checkpoint file (.nmmstate): a container of named binary sections, written atomically and
// read with every check. What the sections hold is the solver's business
// (solver/discretisation/run_state.cpp); this file knows only the container. Layout (little-endian):
//
//   header, 32 bytes: magic "NMMSTATE" | u32 version | u32 endian marker 0x01020304 |
//                     u32 section count | u32 CRC-32 of header + table (this field as zero) |
//                     u64 total file size
//   table, 32 bytes per section: tag (8 bytes, NUL padded) | u64 offset | u64 size |
//                     u32 CRC-32 of the section | u32 zero
//   sections, in table order, each starting where the previous ended (no gaps, no overlap),
//   the last one ending at the file size.
//
// A flipped bit anywhere is caught by a CRC (or by the exact-layout rules); a truncated file by
// the size field. Every failure is an InputError(path, "byte N" or "section TAG", what).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace nmm {

constexpr std::uint32_t kCheckpointFormatVersion = 1;

/// Named sections in file order; tags are 1–8 printable ASCII characters, unique.
using CheckpointSections = std::vector<std::pair<std::string, std::string>>;

std::string checkpoint_to_bytes(const CheckpointSections& sections);
/// Parses and checks (magic, version, endianness, sizes, bounds, CRCs); `name` is used in errors.
CheckpointSections checkpoint_from_bytes(const std::string& bytes, const std::string& name);

/// Writes atomically: a temporary file in the same folder, fsync, rename over `path`. On failure
/// nothing is left under `path` and InputError names the file.
void write_checkpoint_file(const CheckpointSections& sections, const std::string& path);
CheckpointSections read_checkpoint_file(const std::string& path);

}  // namespace nmm
