// The system matrix in its factor's order: A1 = tril(P A Pᵀ), what CHOLMOD's supernodal numeric
// factorisation reads.
//
// With P the fill-reducing permutation of the analysis (perm[k]: the unknown eliminated k-th,
// pinv its inverse), entry (i, j), i ≤ j, of the stored upper triangle of A lands at
// (max(pinv[i], pinv[j]), min(pinv[i], pinv[j])) of A1, stored lower in compressed columns:
//   A1(r, c) = A(perm[r], perm[c]),  r ≥ c.
// cholmod_factorize_p makes A1 from A on every numeric factorisation (cholmod_ptranspose: a pass
// counting each column, a pass placing the entries, two arrays allocated and freed) and hands
// it to cholmod_super_numeric. A1's pattern depends only on A's pattern and P, both fixed
// between two analyses, so it is laid out here once per analysis, with for each entry of A1 the
// entry of A it copies; a factorisation then only gathers the values (no arithmetic: the same
// bits, and super_numeric assigns each entry of A1 to its place in the factor, whatever the
// order of the rows in a column, so the factor is CHOLMOD's own bit for bit; test_system_matrix).
// Measured: docs/performance.md (e), docs/notes/2026-11-dda-walls.md (2026-11-30, afternoon).
#pragma once

#include <cstddef>
#include <vector>

#include <cholmod.h>

namespace nmm::solve {

class PermutedLower {
 public:
  /// Lays out A1 for the n×n matrix whose upper triangle has the compressed columns (outer,
  /// inner), under the permutation perm (perm[k]: the unknown eliminated k-th; null: none).
  /// Each column's rows ascending.
  void build(int n, const int* outer, const int* inner, const int* perm);
  /// Forgets the layout (a new analysis, a new pattern); the arrays' storage is kept.
  void clear();
  bool ready() const { return ready_; }
  /// A1's values from A's (`values`: A's value array, in the pattern build() was given).
  void fill(const double* values);
  /// CHOLMOD's view of A1 (its arrays, not a copy): real, packed, sorted, lower (stype −1).
  cholmod_sparse view();
  /// Bytes of A1's pattern, values and the copy map.
  std::size_t bytes() const {
    return (p_.capacity() + i_.capacity() + from_.capacity()) * sizeof(int) + x_.capacity() * sizeof(double);
  }

 private:
  int n_ = 0;
  bool ready_ = false;
  std::vector<int> p_;     // [n+1] A1's column starts
  std::vector<int> i_;     // [nnz] A1's rows
  std::vector<int> from_;  // [nnz] the entry of A's value array each entry of A1 copies
  std::vector<double> x_;  // [nnz] A1's values
};

}  // namespace nmm::solve
