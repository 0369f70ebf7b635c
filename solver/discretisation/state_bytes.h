// Little helpers to put plain values into a checkpoint section and read them back with every
// bound checked (run_state.cpp, contact_history.cpp). Values are stored in the machine's byte
// order; the checkpoint header's endian marker refuses a file from the other order.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "common/error.h"

namespace nmm::solve {

class ByteWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    put<std::uint64_t>(v.size());
    if (!v.empty()) bytes_.append(reinterpret_cast<const char*>(v.data()), sizeof(T) * v.size());
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

/// Reads from one section; every read past the end is an InputError(file, "section TAG").
class ByteReader {
 public:
  ByteReader(const std::string& bytes, std::string file, std::string tag)
      : b_(bytes), file_(std::move(file)), tag_(std::move(tag)) {}
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(file_, "section " + tag_ + " byte " + std::to_string(pos_), what);
  }
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    if (sizeof(T) > b_.size() - pos_) fail("the section ends early");
    T v;
    std::memcpy(&v, b_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  /// A vector whose length must be `expected` (or anything when expected == SIZE_MAX).
  template <class T>
  std::vector<T> get_vector(std::size_t expected, const char* what) {
    const std::uint64_t n = get<std::uint64_t>();
    if (expected != SIZE_MAX && n != expected)
      fail(std::string(what) + " has " + std::to_string(n) + " entries, the mesh needs " +
           std::to_string(expected) + " (a checkpoint of another mesh?)");
    if (n > (b_.size() - pos_) / sizeof(T)) fail(std::string(what) + ": the section ends early");
    std::vector<T> v(static_cast<std::size_t>(n));
    if (n > 0) std::memcpy(v.data(), b_.data() + pos_, sizeof(T) * v.size());
    pos_ += sizeof(T) * v.size();
    return v;
  }
  /// The next value without reading past it (nothing: `fallback`).
  template <class T>
  T peek(T fallback) const {
    static_assert(std::is_trivially_copyable_v<T>);
    if (sizeof(T) > b_.size() - pos_) return fallback;
    T v;
    std::memcpy(&v, b_.data() + pos_, sizeof(T));
    return v;
  }
  bool at_end() const { return pos_ == b_.size(); }
  void expect_end() const {
    if (pos_ != b_.size()) fail("unexpected bytes after the data");
  }

 private:
  const std::string& b_;
  std::string file_, tag_;
  std::size_t pos_ = 0;
};

}  // namespace nmm::solve
