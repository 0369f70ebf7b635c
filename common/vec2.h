// Plane point and polygon types shared by the scene and the joint network definitions.
#pragma once

#include <cmath>
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
  bool overlaps(const Box& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};

/// The bounding box of a non-empty ring.
inline Box bounding_box(const Ring& r) {
  Box b{r[0].x, r[0].y, r[0].x, r[0].y};
  for (const Vec2& p : r) {
    b.x0 = p.x < b.x0 ? p.x : b.x0;
    b.y0 = p.y < b.y0 ? p.y : b.y0;
    b.x1 = p.x > b.x1 ? p.x : b.x1;
    b.y1 = p.y > b.y1 ? p.y : b.y1;
  }
  return b;
}

}  // namespace nmm
