// Reading a whole input file into memory: the scene, a config patch, a time table, the mesh file,
// a checkpoint, a frame. Every reader then parses from the bytes, so a parse error can name the
// byte or line it is at, and the file is read in one place with one error behaviour.
#pragma once

#include <string>

namespace nmm {

/// The bytes of the file at `path` (text or binary), read to its end. When it cannot be opened
/// or read (missing, no permission, a folder): InputError(path, "", failure + ": " + the
/// system's reason), e.g. "cannot read: No such file or directory" (exit status 2 in the tools).
std::string read_whole_file(const std::string& path, const std::string& failure = "cannot read");

/// A text input named in or beside a scene (the scene itself, a config patch, a time table, a
/// frame): read_whole_file worded "cannot read file: <reason>", as these messages have always
/// read (tests and users' scripts match them).
inline std::string read_text_file(const std::string& path) {
  return read_whole_file(path, "cannot read file");
}

}  // namespace nmm
