// The global system matrix: symmetric, stored as its lower triangle in compressed columns, with
// a sparsity pattern built once from the element–cover incidence, and CHOLMOD's factorisation.
//
// Pattern and numbers are kept apart (deal.II step-8 style): build_pattern() fixes the nonzeros
// and precomputes, for every element, where each entry of its 6×6 block lands in the value
// array, so assembly is a scatter with no search. CHOLMOD's symbolic analysis (fill-reducing
// ordering, supernodes) runs only when the pattern changes; each step refactors the numbers.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

namespace nmm::solve {

class SystemMatrix {
 public:
  using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  /// Builds the pattern of the n×n matrix (n = unknowns) coupling, for each group, all the
  /// unknowns in it: one group of 6 per element (its three covers × two directions), one of 12
  /// per contact (the covers of both elements; an unknown may appear twice in a group).
  /// Group g holds dofs[offsets[g] .. offsets[g+1]).
  void build_pattern(int n, const std::vector<int>& offsets, const std::vector<int>& dofs);

  /// Unknowns whose diagonal is perturbed by eps·K_ii in the factorisation (linearly dependent
  /// ones); solve() then refines iteratively. Empty (the default): plain Cholesky.
  void set_regularised(std::vector<int> unknowns, double eps) {
    regularised_ = std::move(unknowns);
    eps_ = eps;
  }
  /// Iterative-refinement passes of the last solve (0 without regularisation).
  int refinements() const { return refinements_; }

  /// Sets every value to zero, keeping the pattern.
  void set_zero();

  /// Adds the symmetric m×m block `k` (column-major, m = size of group g) of group g.
  void add_group(std::size_t g, const double* k);

  /// Saves the current values; restore() brings them back (the part of the matrix that does not
  /// change during the open–close iteration of a step).
  void save() { saved_.assign(k_.valuePtr(), k_.valuePtr() + k_.nonZeros()); }
  void restore() { std::copy(saved_.begin(), saved_.end(), k_.valuePtr()); }

  /// Adds `value` to the diagonal entry of unknown i.
  void add_diagonal(int i, double value);

  /// Factorises the current values (symbolic analysis only after a new pattern). Returns false if
  /// the matrix is not positive definite; failed_unknown() then names the unknown where it broke.
  bool factorize();

  /// Solves K·x = b with the last factorisation (refined when regularised).
  Eigen::VectorXd solve(const Eigen::VectorXd& b);

  int failed_unknown() const { return failed_unknown_; }
  int size() const { return static_cast<int>(k_.rows()); }
  const Sparse& matrix() const { return k_; }
  std::size_t analyses() const { return analyses_; }  ///< symbolic analyses done so far

 private:
  // Eigen's CHOLMOD wrapper, with the failing column exposed.
  struct Llt : Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> {
    int failed_column() const;
  };
  Sparse k_;
  std::vector<std::int32_t> slot_offset_;  // [group+1] CSR into slots_
  std::vector<std::int32_t> slots_;  // [m² per group] value index of entry (i, j), -1 above diagonal
  std::vector<double> saved_;
  std::vector<std::int32_t> diag_;   // [n] value index of each diagonal entry
  Llt llt_;
  bool analysed_ = false;
  std::size_t analyses_ = 0;
  int failed_unknown_ = -1;
  std::vector<int> regularised_;
  double eps_ = 0;
  int refinements_ = 0;
};

}  // namespace nmm::solve
