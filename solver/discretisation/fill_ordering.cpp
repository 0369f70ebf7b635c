#include "solver/discretisation/fill_ordering.h"

#include <algorithm>

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

}  // namespace nmm::solve
