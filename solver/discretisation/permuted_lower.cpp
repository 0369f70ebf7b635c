#include "solver/discretisation/permuted_lower.h"

namespace nmm::solve {

void PermutedLower::build(int n, const int* outer, const int* inner, const int* perm) {
  const auto un = static_cast<std::size_t>(n);
  const auto nnz = static_cast<std::size_t>(outer[n]);
  std::vector<int> pinv(un);
  for (int k = 0; k < n; ++k) pinv[perm ? static_cast<std::size_t>(perm[k]) : static_cast<std::size_t>(k)] = k;
  // Two counting passes, as a transpose twice: the entries bucketed by A1's row, then, rows
  // taken in ascending order, into their columns; so each column's rows come out ascending
  // without a sort. Work ~ nnz + n, once per analysis.
  std::vector<int> row_start(un + 1, 0), row_col(nnz), row_from(nnz);
  for (int j = 0; j < n; ++j)
    for (int q = outer[j]; q < outer[j + 1]; ++q) {
      const int a = pinv[static_cast<std::size_t>(inner[q])], b = pinv[static_cast<std::size_t>(j)];
      ++row_start[static_cast<std::size_t>(a > b ? a : b) + 1];
    }
  for (std::size_t r = 0; r < un; ++r) row_start[r + 1] += row_start[r];
  {
    std::vector<int> at(row_start.begin(), row_start.end() - 1);
    for (int j = 0; j < n; ++j)
      for (int q = outer[j]; q < outer[j + 1]; ++q) {
        const int a = pinv[static_cast<std::size_t>(inner[q])], b = pinv[static_cast<std::size_t>(j)];
        const auto w = static_cast<std::size_t>(at[static_cast<std::size_t>(a > b ? a : b)]++);
        row_col[w] = a < b ? a : b;
        row_from[w] = q;
      }
  }
  p_.assign(un + 1, 0);
  for (std::size_t w = 0; w < nnz; ++w) ++p_[static_cast<std::size_t>(row_col[w]) + 1];
  for (std::size_t c = 0; c < un; ++c) p_[c + 1] += p_[c];
  i_.resize(nnz);
  from_.resize(nnz);
  x_.resize(nnz);
  std::vector<int> at(p_.begin(), p_.end() - 1);
  for (int r = 0; r < n; ++r)
    for (int w = row_start[static_cast<std::size_t>(r)]; w < row_start[static_cast<std::size_t>(r) + 1]; ++w) {
      const auto d = static_cast<std::size_t>(at[static_cast<std::size_t>(row_col[static_cast<std::size_t>(w)])]++);
      i_[d] = r;
      from_[d] = row_from[static_cast<std::size_t>(w)];
    }
  n_ = n;
  ready_ = true;
}

void PermutedLower::clear() { ready_ = false; }  // (the arrays kept: the next build reuses them)

void PermutedLower::fill(const double* values) {
  const std::size_t nnz = x_.size();
  const int* from = from_.data();
  double* x = x_.data();
  for (std::size_t d = 0; d < nnz; ++d) x[d] = values[from[d]];
}

cholmod_sparse PermutedLower::view() {
  cholmod_sparse a{};
  a.nrow = static_cast<std::size_t>(n_);
  a.ncol = static_cast<std::size_t>(n_);
  a.nzmax = x_.size();
  a.p = p_.data();
  a.i = i_.data();
  a.x = x_.data();
  a.stype = -1;
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  return a;
}

}  // namespace nmm::solve
