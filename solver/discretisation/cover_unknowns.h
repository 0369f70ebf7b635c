// Which unknowns each physical cover moves with: its own, or — for a sliver cover — those of the
// neighbour cover it overlaps most. See cover_unknowns.cpp.
#pragma once

#include <cstdint>
#include <vector>

#include "common/mesh.h"

namespace nmm::solve {

struct CoverUnknowns {
  std::vector<std::int32_t> unknown;  ///< [pc] index of its first unknown (cover_space.h)
  std::vector<std::int32_t> master;   ///< [pc] itself, or the cover whose unknowns it shares
  std::vector<double> max_weight;     ///< [pc] –, largest weight of the cover on its support
  std::vector<std::int32_t> cover_of_unknown;  ///< [unknowns/dofs_per_cover] owner of each block
  std::size_t tied = 0;                        ///< covers sharing a neighbour's unknowns
  int dofs_per_cover = 2;                      ///< unknowns of one cover (cover_space.h)
  int unknowns() const { return dofs_per_cover * static_cast<int>(cover_of_unknown.size()); }
};

/// Covers whose weight is below min_weight (in [0, 1/3)) on all of their support, or whose
/// support is smaller than min_support·h² and bounded by a crack (an element of it has an edge on
/// joint first_crack_joint or a later one: the cracks a run grew; -1: none), share the unknowns
/// of a neighbour; the others get theirs in cover order (so without slivers cover c owns unknowns
/// m·c .. m·c + m − 1, m = dofs_per_cover).
CoverUnknowns assign_cover_unknowns(const Mesh& mesh, double min_weight, int dofs_per_cover = 2,
                                    double min_support = 0, std::int32_t first_crack_joint = -1);

}  // namespace nmm::solve
