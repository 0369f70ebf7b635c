// The contacts near a contact along the same pair of blocks: what the tributary-length rules
// (tributary_length.h, cohesive_tributary.h) weigh a contact's stretch of joint against.
//
// Contacts with a stretch of their own are listed by (pair of blocks, grid cell of size h) — a
// neighbour within reach is at most twice a half-edge, one element edge, away, so it lies in one
// of the 3 × 3 cells round P's — and sorted by (blocks, cell column, cell row, index): the
// neighbours of P's cell in one cell column are one run of the list, found by binary search in
// the run of P's pair of blocks. (A hash map of cells held every pair of blocks in a cell; this
// is a tenth of its time.) The visiting order is the list's, so the rules' sums are the same
// whatever the caller.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace nmm::solve {

class ContactNeighbours {
 public:
  /// One contact to list: its pair of blocks (lower first), its point P (m) and its index.
  struct Entry {
    std::int32_t b0, b1;
    double px, py;
    std::uint32_t i;
  };
  /// h (m): the cell size, the mesh size.
  ContactNeighbours(const std::vector<Entry>& entries, double h) : h_(h) {
    // Sorted by the lower block first by counting, then each block's few entries by the whole
    // key: the same list as one std::sort of all (the keys are unique by index), with far fewer
    // comparisons (the tributary lengths of a static 20 × 20 brick wall at h = 2 m: 545 → 392 µs
    // a step).
    std::int32_t top = -1;
    for (const Entry& e : entries) top = std::max(top, e.b0);
    std::vector<std::size_t> start(static_cast<std::size_t>(top) + 2, 0);
    for (const Entry& e : entries) ++start[static_cast<std::size_t>(e.b0) + 1];
    for (std::size_t b = 0; b + 1 < start.size(); ++b) start[b + 1] += start[b];
    keys_.resize(entries.size());
    {
      std::vector<std::size_t> at(start.begin(), start.end() - 1);
      for (const Entry& e : entries) keys_[at[static_cast<std::size_t>(e.b0)]++] = {e.b0, e.b1, cell(e.px), cell(e.py), e.i};
    }
    for (std::size_t b = 0; b + 1 < start.size(); ++b)
      if (start[b + 1] - start[b] > 1)
        std::sort(keys_.begin() + static_cast<std::ptrdiff_t>(start[b]), keys_.begin() + static_cast<std::ptrdiff_t>(start[b + 1]));
    // The run of each entry's pair of blocks in the list, [first, end).
    const auto same_pair = [&](std::size_t k, std::size_t q) { return keys_[k].b0 == keys_[q].b0 && keys_[k].b1 == keys_[q].b1; };
    run_first_.resize(keys_.size());
    run_end_.resize(keys_.size());
    for (std::size_t k = 0; k < keys_.size(); ++k) run_first_[k] = k > 0 && same_pair(k - 1, k) ? run_first_[k - 1] : k;
    for (std::size_t k = keys_.size(); k-- > 0;)
      run_end_[k] = k + 1 < keys_.size() && same_pair(k, k + 1) ? run_end_[k + 1] : k + 1;
  }

  /// Listed contacts, in the list's order.
  std::size_t size() const { return keys_.size(); }
  /// The index of the k-th listed contact.
  std::uint32_t index(std::size_t k) const { return keys_[k].i; }

  /// visit(j) for every other listed contact j in the 3 × 3 cells round the k-th one's point
  /// (px, py), of its pair of blocks, in the list's order.
  template <class Visit>
  void for_each_near(std::size_t k, double px, double py, const Visit& visit) const {
    const Key& a = keys_[k];
    const auto run = keys_.begin() + static_cast<std::ptrdiff_t>(run_first_[k]);
    const auto end = keys_.begin() + static_cast<std::ptrdiff_t>(run_end_[k]);
    const std::int64_t ci = cell(px), cj = cell(py);
    for (std::int64_t di = -1; di <= 1; ++di) {
      const Key last{a.b0, a.b1, ci + di, cj + 1, std::numeric_limits<std::uint32_t>::max()};
      for (auto it = std::lower_bound(run, end, Key{a.b0, a.b1, ci + di, cj - 1, 0}); it != end && !(last < *it); ++it)
        if (it->i != a.i) visit(it->i);
    }
  }

 private:
  struct Key {
    std::int32_t b0, b1;
    std::int64_t cx, cy;
    std::uint32_t i;
    bool operator<(const Key& o) const {
      if (b0 != o.b0) return b0 < o.b0;
      if (b1 != o.b1) return b1 < o.b1;
      if (cx != o.cx) return cx < o.cx;
      if (cy != o.cy) return cy < o.cy;
      return i < o.i;
    }
  };
  std::int64_t cell(double x) const { return static_cast<std::int64_t>(std::floor(x / h_)); }

  double h_;
  std::vector<Key> keys_;
  std::vector<std::size_t> run_first_, run_end_;
};

}  // namespace nmm::solve
