// The binary mesh file (.nmm): write atomically, read with every check. Layout: docs/mesh-format.md.
#pragma once

#include <cstdint>
#include <string>

#include "common/mesh.h"
#include "common/mesh_validation.h"  // validate_mesh(), which the reader runs on every file

namespace nmm {

/// Current format version written by write_mesh_file(); the reader accepts exactly this one.
constexpr std::uint32_t kMeshFormatVersion = 1;

/// Writes `mesh` to `path` atomically: a temporary file in the same folder, flushed, then renamed
/// over `path`. On failure nothing is left under `path` and InputError names the file.
void write_mesh_file(const Mesh& mesh, const std::string& path);

/// Reads and checks a mesh file: magic, version, endianness, section table bounds, CRC-32 of each
/// section, array sizes and every index range. Throws InputError(path, "byte N" or section, what).
Mesh read_mesh_file(const std::string& path);

/// Serialises to / parses from bytes (the same as the file contents); `name` is used in errors.
std::string mesh_to_bytes(const Mesh& mesh);
Mesh mesh_from_bytes(const std::string& bytes, const std::string& name);

/// SHA-256 of a byte string (OpenSSL), as 32 bytes, and as 64 lowercase hex characters.
std::array<std::uint8_t, 32> sha256(const std::string& bytes);
std::string to_hex(const std::array<std::uint8_t, 32>& digest);

}  // namespace nmm
