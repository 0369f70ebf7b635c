// The sign of a closed loop's area for vertices given in doubles, decided so that it does not
// depend on the corner the loop starts at:
//   2A = Σ_i (x_i − x_0)(y_{i+1} − y_0) − (x_{i+1} − x_0)(y_i − y_0)        (shoelace, m²)
// summed in doubles first; where |2A| lies within the sum's round-off bound
//   (2n + 4) · ε · Σ_i (|(x_i − x_0)(y_{i+1} − y_0)| + |(x_{i+1} − x_0)(y_i − y_0)|)
// the sign is taken in exact rationals (the vertices are doubles, so the loop has one area).
// The cutter drops a face whose rounded loop encloses no positive area (docs/fracture.md, "The
// re-cut is the full cut"); in doubles a zero-area needle read +1e-30 m² from one corner and
// −1e-30 m² from another, so a cut that reached the same face by another path kept it.
#pragma once

#include <cstddef>

#include "common/vec2.h"

namespace nmm::pre {

/// +1: the loop runs anticlockwise around a positive area, −1: clockwise, 0: no area at all.
int loop_area_sign(const Vec2* loop, std::size_t n);

}  // namespace nmm::pre
