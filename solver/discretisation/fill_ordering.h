// A fill-reducing ordering of a symmetric sparse matrix computed on its graph of covers: each
// run of `block` consecutive unknowns (a cover's displacement directions and higher-order terms:
// cover_space.h) is one node, and the ordering of the nodes is expanded to their unknowns.
//
// A cover's unknowns share every row's pattern (an element couples all unknowns of its covers),
// so the expanded ordering has the fill an ordering of the unknowns would have, and the graph to
// order is block² times smaller: METIS's nested dissection of the 10,000-block wall's matrix
// (222,516 unknowns) took 709 ms on the covers against 1,500 ms on the unknowns, for a factor
// within 4 % of the same size (bench/ordering_bench.cpp, docs/notes/2026-11-scale.md).
#pragma once

#include <utility>
#include <vector>

struct cholmod_factor_struct;  // cholmod.h's cholmod_factor

namespace nmm::solve {

enum class FillOrdering { amd, metis };

/// The permutation (perm[k] = the unknown eliminated k-th) of the n×n matrix whose upper
/// triangle's pattern is (outer, inner) in compressed columns, ordered on its cover graph: the
/// first `blocked` unknowns (rounded down to a multiple of `block`; all of them when negative)
/// form nodes of `block` consecutive unknowns, any further ones a node each. Empty if CHOLMOD's
/// ordering failed (out of memory).
std::vector<int> block_ordering(int n, const int* outer, const int* inner, int block, FillOrdering method,
                                int blocked = -1);

/// The rows of a supernodal factor's columns (CHOLMOD's, with its permutation), to ask whether a
/// matrix entry lies within its structure: an entry there adds no fill to a factor analysed under
/// the same order (system_matrix.cpp keeps_symbolic). Empty (ready() false) for any other factor.
class FactorRows {
 public:
  explicit FactorRows(const cholmod_factor_struct& f);
  bool ready() const { return !order_.empty(); }
  /// Entry (j, i) of the matrix, unknowns in the matrix's numbering, in either order.
  bool within(int j, int i) const;

 private:
  std::vector<int> order_, snode_;  // [unknown] its position; [position] its supernode
  std::vector<char> sorted_;        // [supernode] its rows ascend (else searched one by one)
  const int *pi_ = nullptr, *rows_ = nullptr;
};

/// A grown pattern's ordering without a new nested dissection: the order of the last factor `f`
/// (CHOLMOD supernodal, postordered: f.Perm) with the covers of the entries `outside` (column,
/// row: couplings of unknowns its structure lacks, a grown pattern's new pairs) placed anew. Of
/// each such entry the cover eliminated first moves, all its unknowns in their order, to just
/// before the first column of the lowest supernode that is an ancestor of both ends (the
/// separator between their subtrees); a cover of several such entries to the highest of theirs.
/// Every other unknown keeps its place. Why (the fill a new pair brings under the kept order,
/// and what placing it saves): fill_ordering.cpp. Empty if f is not a supernodal factor with a
/// permutation.
std::vector<int> placed_ordering(const cholmod_factor_struct& f, const std::vector<std::pair<int, int>>& outside,
                                 int block, int blocked = -1);

}  // namespace nmm::solve
