// Plane point and polygon types shared by the scene and the joint network definitions.
#pragma once

#include <vector>

namespace nmm {

struct Vec2 {
  double x = 0;  ///< m (or N for forces, m/s² for gravity)
  double y = 0;
};
inline bool operator==(const Vec2& a, const Vec2& b) { return a.x == b.x && a.y == b.y; }

/// A closed polygon as its vertices, any orientation, first vertex not repeated at the end. m.
using Ring = std::vector<Vec2>;

}  // namespace nmm
