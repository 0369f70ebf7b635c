// An array parked in a temporary file while a phase needs its memory more than it does.
//
// The lean factorisation (system_matrix.cpp factorize_lean) holds arrays that nothing reads
// while CHOLMOD writes the double factor — the largest runs' memory peak — and that are needed
// again once the factor is rounded to float: the saved values without springs (8 bytes per
// stored entry: 0.15 GB at 930k unknowns) and the scatter's group unknowns (0.04 GB there).
// park() writes the array's bytes to an unlinked temporary file (in $TMPDIR, else /tmp) and
// lets its memory go; unpark() reads them back, the same bytes. The file's pages sit in the
// kernel's page cache, which gives them up under pressure (written out to disk), unlike a
// process's own pages on a machine without swap: the peak of resident memory drops by the
// array's bytes (docs/performance.md (h)).
//
// Cost: one write and one read of the bytes through the page cache, about 0.1 s of CPU per
// 0.15 GB, against the numeric factorisation's 10–13 s at that size. If the file cannot be made
// or written (no space, no folder), park() returns false and the array stays where it was:
// parking is an economy, never a condition of the run. A file that cannot be read back (the
// disk failed under the run) is a RunError: the values are gone.
#pragma once

#include <cstddef>
#include <type_traits>
#include <vector>

namespace nmm::solve {

/// An unlinked temporary file holding one run of bytes (one parked array).
class ParkingFile {
 public:
  ParkingFile() = default;
  ParkingFile(const ParkingFile&) = delete;
  ParkingFile& operator=(const ParkingFile&) = delete;
  ~ParkingFile() { close(); }
  /// Writes `bytes` bytes at `data` to a new temporary file; false (and no file) if it cannot.
  bool write(const void* data, std::size_t bytes);
  /// Reads the bytes written back into `data` and closes the file; a RunError if it cannot.
  void read(void* data);
  bool open() const { return fd_ >= 0; }
  std::size_t bytes() const { return bytes_; }

 private:
  void close();
  int fd_ = -1;
  std::size_t bytes_ = 0;
};

/// A std::vector of plain values parked in a ParkingFile (see above).
template <class T>
class ParkedArray {
  static_assert(std::is_trivially_copyable_v<T>, "parked as raw bytes");

 public:
  /// Moves v's values to the file and frees v's memory (v becomes empty); false if the file
  /// cannot be written (v untouched) or v is empty (nothing to gain).
  bool park(std::vector<T>& v) {
    if (v.empty() || !file_.write(v.data(), v.size() * sizeof(T))) return false;
    size_ = v.size();
    std::vector<T>().swap(v);
    return true;
  }
  /// Gives back to v (empty) the values of the last park(): the same bytes. Nothing if none is parked.
  void unpark(std::vector<T>& v) {
    if (!file_.open()) return;
    v.resize(size_);
    file_.read(v.data());
  }
  bool parked() const { return file_.open(); }

 private:
  ParkingFile file_;
  std::size_t size_ = 0;
};

}  // namespace nmm::solve
