#include "system_matrix.h"

#include <algorithm>

namespace nmm::solve {

void SystemMatrix::build_pattern(int n, const std::vector<std::array<int, 6>>& groups) {
  // Lower-triangle (row ≥ column) entries of every group, then compressed columns.
  std::vector<std::vector<int>> rows(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) rows[i].push_back(i);  // every diagonal, even of a lone unknown
  for (const auto& g : groups)
    for (int a : g)
      for (int b : g)
        if (a > b) rows[b].push_back(a);
  std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0);
  std::vector<int> inner;
  for (int c = 0; c < n; ++c) {
    auto& r = rows[c];
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    inner.insert(inner.end(), r.begin(), r.end());
    outer[c + 1] = static_cast<int>(inner.size());
    std::vector<int>().swap(r);
  }
  k_ = Sparse(n, n);
  k_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), k_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), k_.innerIndexPtr());
  std::fill(k_.valuePtr(), k_.valuePtr() + inner.size(), 0.0);

  auto find = [&](int row, int col) {
    const int* b = k_.innerIndexPtr() + outer[col];
    const int* e = k_.innerIndexPtr() + outer[col + 1];
    return static_cast<std::int32_t>(std::lower_bound(b, e, row) - k_.innerIndexPtr());
  };
  slots_.assign(36 * groups.size(), -1);
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) {
        const int r = groups[g][i], c = groups[g][j];
        if (r >= c) slots_[36 * g + 6 * j + i] = find(r, c);
      }
  diag_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) diag_[i] = find(i, i);
  analysed_ = false;
  // A matrix that is not positive definite is reported by us (failed_unknown), on one line;
  // CHOLMOD itself must not print.
  llt_.cholmod().print = 0;
}

void SystemMatrix::set_zero() { std::fill(k_.valuePtr(), k_.valuePtr() + k_.nonZeros(), 0.0); }

void SystemMatrix::add_group(std::size_t g, const double* k) {
  const std::int32_t* s = slots_.data() + 36 * g;
  double* v = k_.valuePtr();
  for (int e = 0; e < 36; ++e)
    if (s[e] >= 0) v[s[e]] += k[e];
}

void SystemMatrix::add_diagonal(int i, double value) { k_.valuePtr()[diag_[i]] += value; }

int SystemMatrix::Llt::failed_column() const {
  // CHOLMOD records the column where the factorisation stopped (L->minor) in its fill-reducing
  // order; L->Perm maps it back to our unknown.
  const cholmod_factor* f = this->m_cholmodFactor;
  if (!f || f->minor >= f->n) return -1;
  return f->Perm ? static_cast<const int*>(f->Perm)[f->minor] : static_cast<int>(f->minor);
}

bool SystemMatrix::factorize() {
  if (!analysed_) {
    llt_.analyzePattern(k_);
    analysed_ = true;
    ++analyses_;
  }
  llt_.factorize(k_);
  failed_unknown_ = -1;
  if (llt_.info() != Eigen::Success) {
    failed_unknown_ = llt_.failed_column();
    return false;
  }
  return true;
}

Eigen::VectorXd SystemMatrix::solve(const Eigen::VectorXd& b) { return llt_.solve(b); }

}  // namespace nmm::solve
