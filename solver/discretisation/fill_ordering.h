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

#include <vector>

namespace nmm::solve {

enum class FillOrdering { amd, metis };

/// The permutation (perm[k] = the unknown eliminated k-th) of the n×n matrix whose upper
/// triangle's pattern is (outer, inner) in compressed columns, ordered on its cover graph: the
/// first `blocked` unknowns (rounded down to a multiple of `block`; all of them when negative)
/// form nodes of `block` consecutive unknowns, any further ones a node each. Empty if CHOLMOD's
/// ordering failed (out of memory).
std::vector<int> block_ordering(int n, const int* outer, const int* inner, int block, FillOrdering method,
                                int blocked = -1);

}  // namespace nmm::solve
