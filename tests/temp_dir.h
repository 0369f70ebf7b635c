// A fresh empty folder for one test, removed with everything in it at the end: tests that write
// files (ctest -j runs them side by side) neither see each other's files nor leave any behind.
// Shared by the tests of the mesh file, the inspector, the run config and the output writer.
#pragma once

#include <stdlib.h>  // mkdtemp

#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>

namespace nmm::test {

class TempDir {
 public:
  /// Makes <system temporary folder>/nmm-test-XXXXXX (mkdtemp: a new name every time).
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "nmm-test-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed: " + pattern);
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;  // a destructor must not throw; a leftover folder is harmless
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

  /// The path of `name` in the folder, as the string the readers and writers take.
  std::string path(const std::string& name) const { return (path_ / name).string(); }

  /// Writes `text` to `name` in the folder and returns its path.
  std::string file(const std::string& name, const std::string& text) const {
    const std::string p = path(name);
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  /// The names directly in the folder (not below), to check what a write left behind.
  std::set<std::string> entries() const {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path_))
      names.insert(entry.path().filename().string());
    return names;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace nmm::test
