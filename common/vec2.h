// Plane point and polygon types shared by the scene and the joint network definitions.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace nmm {

struct Vec2 {
  double x = 0;  ///< m (or N for forces, m/s² for gravity)
  double y = 0;
};
inline bool operator==(const Vec2& a, const Vec2& b) { return a.x == b.x && a.y == b.y; }

/// The length of (dx, dy). Not std::hypot: its guard against overflow and underflow of the
/// squares costs a sixth of contact detection's time, and plane coordinates in metres square
/// far inside the range of a double.
inline double length(double dx, double dy) { return std::sqrt(dx * dx + dy * dy); }

/// A closed polygon as its vertices, any orientation, first vertex not repeated at the end. m.
using Ring = std::vector<Vec2>;

/// An axis-aligned box, m.
struct Box {
  double x0, y0, x1, y1;

  /// The box of no points (x0 > x1, its sides −inf): the first add() makes it that point.
  static Box empty() {
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {inf, inf, -inf, -inf};
  }
  void add(double x, double y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  /// m, the longer side: the size of a model for scales and tolerances.
  double longer_side() const { return std::max(x1 - x0, y1 - y0); }
  bool overlaps(const Box& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};

/// The bounding box of a ring (Box::empty() for none).
inline Box bounding_box(const Ring& r) {
  Box b = Box::empty();
  for (const Vec2& p : r) b.add(p.x, p.y);
  return b;
}

/// The bounding box of points stored as x, y pairs ([2·n] m: loop_xy, cover_xy).
inline Box bounding_box_xy(const std::vector<double>& xy) {
  Box b = Box::empty();
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2) b.add(xy[i], xy[i + 1]);
  return b;
}

/// The box as a ring, counter-clockwise from its lower left corner.
inline Ring box_ring(const Box& b) { return {{b.x0, b.y0}, {b.x1, b.y0}, {b.x1, b.y1}, {b.x0, b.y1}}; }

}  // namespace nmm
