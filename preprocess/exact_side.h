// Which side of a line a point lies on, decided exactly for points given in doubles: the
// arithmetic the cutter (cover_cutter.cpp, CGAL's exact kernel) decides with, so the solver can
// tell before a re-cut whether a crack's end reaches an element edge or stops a round-off short
// of it (solver/fracture/fracture.cpp crack_end).
//   side(a, b, p) = sign of (b − a) × (p − a) = sign |b_x − a_x  p_x − a_x; b_y − a_y  p_y − a_y|
// evaluated without rounding (CGAL's filtered exact orientation predicate).
#pragma once

#include "common/vec2.h"

namespace nmm::pre {

/// +1: p lies left of the line a → b, −1: right of it, 0: exactly on it.
int exact_side(const Vec2& a, const Vec2& b, const Vec2& p);

}  // namespace nmm::pre
