#include "solver/discretisation/fill_ordering.h"

#include <algorithm>
#include <cstdint>

#include <cholmod.h>

namespace nmm::solve {

std::vector<int> block_ordering(int n, const int* outer, const int* inner, int block, FillOrdering method,
                                int blocked) {
  if (block < 1) block = 1;
  if (blocked < 0 || blocked > n) blocked = n;
  blocked -= blocked % block;
  const int nb = blocked / block;
  const int nodes = nb + (n - blocked);
  const auto node = [&](int i) { return i < blocked ? i / block : nb + (i - blocked); };
  // The node graph's upper triangle: node J's column holds the nodes I ≤ J of the rows in its
  // unknowns' columns (rows ≤ column, and node() does not decrease, so I ≤ J), each once.
  std::vector<int> p(static_cast<std::size_t>(nodes) + 1, 0), rows;
  rows.reserve(static_cast<std::size_t>(outer[n]) / static_cast<std::size_t>(block) + static_cast<std::size_t>(nodes));
  std::vector<int> mark(static_cast<std::size_t>(nodes), -1);
  for (int j = 0; j < nodes; ++j) {
    const int first = j < nb ? j * block : blocked + (j - nb);
    const int last = j < nb ? first + block : first + 1;
    const std::size_t start = rows.size();
    for (int c = first; c < last; ++c)
      for (int k = outer[c]; k < outer[c + 1]; ++k) {
        const int i = node(inner[k]);
        if (mark[static_cast<std::size_t>(i)] != j) {
          mark[static_cast<std::size_t>(i)] = j;
          rows.push_back(i);
        }
      }
    std::sort(rows.begin() + static_cast<std::ptrdiff_t>(start), rows.end());
    p[static_cast<std::size_t>(j) + 1] = static_cast<int>(rows.size());
  }
  cholmod_sparse g{};
  g.nrow = g.ncol = static_cast<std::size_t>(nodes);
  g.nzmax = rows.size();
  g.p = p.data();
  g.i = rows.data();
  g.stype = 1;
  g.itype = CHOLMOD_INT;
  g.xtype = CHOLMOD_PATTERN;
  g.dtype = CHOLMOD_DOUBLE;
  g.sorted = 1;
  g.packed = 1;
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  std::vector<int> order(static_cast<std::size_t>(nodes));
  const int ok = method == FillOrdering::metis ? cholmod_metis(&g, nullptr, 0, 0, order.data(), &c)
                                               : cholmod_amd(&g, nullptr, 0, order.data(), &c);
  cholmod_finish(&c);
  if (!ok) return {};
  std::vector<int> perm;
  perm.reserve(static_cast<std::size_t>(n));
  for (const int j : order) {
    const int first = j < nb ? j * block : blocked + (j - nb);
    const int last = j < nb ? first + block : first + 1;
    for (int i = first; i < last; ++i) perm.push_back(i);
  }
  return perm;
}


FactorRows::FactorRows(const cholmod_factor_struct& f) {
  const auto n = static_cast<int>(f.n);
  if (!f.is_super || !f.Perm || f.nsuper == 0) return;
  const int* perm = static_cast<const int*>(f.Perm);
  const int* super = static_cast<const int*>(f.super);
  pi_ = static_cast<const int*>(f.pi);
  rows_ = static_cast<const int*>(f.s);
  order_.resize(static_cast<std::size_t>(n));
  snode_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) order_[static_cast<std::size_t>(perm[k])] = k;
  for (std::size_t s = 0; s < f.nsuper; ++s)
    for (int c = super[s]; c < super[s + 1]; ++c) snode_[static_cast<std::size_t>(c)] = static_cast<int>(s);
  // A supernode's rows: its own columns, then the rows below, each part ascending in CHOLMOD's
  // supernodal analysis; checked here, a linear search where they are not.
  sorted_.resize(f.nsuper);
  for (std::size_t s = 0; s < f.nsuper; ++s) sorted_[s] = std::is_sorted(rows_ + pi_[s], rows_ + pi_[s + 1]);
}

bool FactorRows::within(int j, int i) const {
  int c = order_[static_cast<std::size_t>(j)], r = order_[static_cast<std::size_t>(i)];
  if (r < c) std::swap(r, c);
  const auto s = static_cast<std::size_t>(snode_[static_cast<std::size_t>(c)]);
  const int* first = rows_ + pi_[s];
  const int* last = rows_ + pi_[s + 1];
  return sorted_[s] ? std::binary_search(first, last, r) : std::find(first, last, r) != last;
}

// A new pair couples covers x (eliminated first) and y that the kept nested dissection had put in
// different subtrees below a separator a. Under the kept order, eliminating x makes y a row of x's
// column: x's path in the elimination tree is joined to y's below a, and every column on it takes
// the rows of the other's path — the fill of the separators between, which is why a pattern grown
// by new contacts needed a new ordering (docs/performance.md (h)). Placed just before a's first
// column instead, x is one more unknown block of that separator: its former neighbours' paths gain
// its rows up to a, and y's path the same, a few rows per supernode. Moving the other end instead
// would do as well; the first keeps the rule simple. An entry whose later end lies on the earlier
// one's path (a is its own supernode) fills that path by one row alone: left as it is.
std::vector<int> placed_ordering(const cholmod_factor_struct& f, const std::vector<std::pair<int, int>>& outside,
                                 int block, int blocked) {
  const auto n = static_cast<int>(f.n);
  if (!f.is_super || !f.Perm || f.nsuper == 0) return {};
  if (block < 1) block = 1;
  if (blocked < 0 || blocked > n) blocked = n;
  blocked -= blocked % block;
  const int* perm = static_cast<const int*>(f.Perm);
  const int* super = static_cast<const int*>(f.super);
  const int* pi = static_cast<const int*>(f.pi);
  const int* rows = static_cast<const int*>(f.s);
  const auto nsuper = static_cast<int>(f.nsuper);
  std::vector<int> order(static_cast<std::size_t>(n)), snode(static_cast<std::size_t>(n)),
      parent(static_cast<std::size_t>(nsuper), -1);
  for (int k = 0; k < n; ++k) order[static_cast<std::size_t>(perm[k])] = k;
  for (int s = 0; s < nsuper; ++s) {
    for (int c = super[s]; c < super[s + 1]; ++c) snode[static_cast<std::size_t>(c)] = s;
  }
  // A supernode's parent: the supernode of its first row below its own columns (the rows after
  // its columns ascend, CHOLMOD's supernodal analysis; the least of them taken in any case).
  for (int s = 0; s < nsuper; ++s) {
    const int width = super[s + 1] - super[s];
    int least = n;
    for (int p = pi[s] + width; p < pi[s + 1]; ++p) least = std::min(least, rows[p]);
    if (least < n) parent[static_cast<std::size_t>(s)] = snode[static_cast<std::size_t>(least)];
  }
  // target[k]: the column before which the unknown at position k moves (-1: stays).
  std::vector<int> target(static_cast<std::size_t>(n), -1);
  const auto first_of_cover = [&](int u) { return u < blocked ? u - u % block : u; };
  const auto cover_size = [&](int u) { return u < blocked ? block : 1; };
  for (const auto& [j, i] : outside) {
    int c = order[static_cast<std::size_t>(j)], r = order[static_cast<std::size_t>(i)];
    if (r < c) std::swap(r, c);
    int a = snode[static_cast<std::size_t>(c)], b = snode[static_cast<std::size_t>(r)];
    const int rs = b;
    while (a != b && a >= 0 && b >= 0) {  // postordered: a parent's index exceeds its children's
      if (a < b) a = parent[static_cast<std::size_t>(a)];
      else b = parent[static_cast<std::size_t>(b)];
    }
    if (a == rs) continue;  // r lies on c's path
    const int to = a < 0 ? n : super[a];  // different trees of a forest: after all
    const int u = perm[c], first = first_of_cover(u);
    for (int v = first; v < first + cover_size(u); ++v) {
      int& t = target[static_cast<std::size_t>(order[static_cast<std::size_t>(v)])];
      t = std::max(t, to);
    }
  }
  // The new order: each unknown at (its target, or its own position), a moved one before the
  // column at its target, ties in the old order.
  std::vector<std::pair<std::int64_t, int>> key(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const int t = target[static_cast<std::size_t>(k)];
    const std::int64_t at = t < 0 ? 2 * static_cast<std::int64_t>(k) + 1 : 2 * static_cast<std::int64_t>(t);
    key[static_cast<std::size_t>(k)] = {at * n + k, perm[k]};
  }
  std::sort(key.begin(), key.end());
  std::vector<int> placed(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) placed[static_cast<std::size_t>(k)] = key[static_cast<std::size_t>(k)].second;
  return placed;
}

}  // namespace nmm::solve
