// Which side of a line a point lies on, exactly: see exact_side.h.
#include "preprocess/exact_side.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace nmm::pre {

int exact_side(const Vec2& a, const Vec2& b, const Vec2& p) {
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_2;
  switch (CGAL::orientation(Point(a.x, a.y), Point(b.x, b.y), Point(p.x, p.y))) {
    case CGAL::LEFT_TURN: return 1;
    case CGAL::RIGHT_TURN: return -1;
    default: return 0;
  }
}

}  // namespace nmm::pre
