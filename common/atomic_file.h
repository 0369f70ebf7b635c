// Output files appear whole or not at all (the quality bar: never a half-written output file).
#pragma once

#include <string>

namespace nmm {

/// Writes `contents` to `path.tmp.<pid>` in the target's folder, flushes it to disk (fsync),
/// renames it over `path` (atomic within one file system) and flushes the folder. On failure
/// the temporary is removed and InputError(path, "", "cannot write: <reason>") is thrown.
/// Shared by the mesh file, the checkpoint and every text output writer.
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace nmm
