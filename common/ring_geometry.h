// Plane geometry of rings (closed polygons, the last vertex joined to the first), shared by the
// scene checks, the joint-network generator and the preprocessor's size estimate.
//
// Point in ring, even–odd rule (ray casting along +x): p is inside when a ray from p crosses the
// ring's edges an odd number of times; an edge (a, b) with a.y > p.y ≠ b.y > p.y is crossed when
//   p.x < a.x + (p.y − a.y)·(b.x − a.x)/(b.y − a.y).
// Points on an edge fall either way (callers that need a tolerance test the edges first).
// Area: the shoelace formula, |½ Σ (x_i y_{i+1} − x_{i+1} y_i)|, about the first vertex
// (ring_signed_area, scene.h) so the round-off scales with the ring's own size.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "common/scene.h"

namespace nmm {

/// Whether the ray from (px, py) along +x crosses the edge (ax, ay)–(bx, by) (the even–odd
/// rule's test above): the one crossing test of point_in_ring, point_in_loop and the contact
/// detection's walk around an element.
inline bool ray_crosses(double ax, double ay, double bx, double by, double px, double py) {
  return (ay > py) != (by > py) && px < ax + (py - ay) * (bx - ax) / (by - ay);
}

/// True when (x, y) lies inside the loop of n vertices xy[2i], xy[2i+1] (even–odd rule; slits
/// and bridges, walked both ways, cancel).
inline bool point_in_loop(const double* xy, std::size_t n, double x, double y) {
  bool inside = false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++)
    if (ray_crosses(xy[2 * i], xy[2 * i + 1], xy[2 * j], xy[2 * j + 1], x, y)) inside = !inside;
  return inside;
}

/// m, the distance from (x, y) to the nearest edge of the loop of n vertices xy[2i], xy[2i+1].
/// A point strictly inside a counter-clockwise loop of n vertices and area `area` (m²): a little
/// inside the middle of its longest edge, by a thousandth of the loop's mean width (area over that
/// edge's length) along the edge's inward normal, so that thin slivers get a point inside them too.
inline Vec2 point_inside_longest_edge(const double* xy, std::size_t n, double area) {
  std::size_t best = 0;
  double longest = -1;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double l = std::hypot(xy[2 * j] - xy[2 * i], xy[2 * j + 1] - xy[2 * i + 1]);
    if (l > longest) longest = l, best = i;
  }
  const std::size_t j = (best + 1) % n;
  const double dx = xy[2 * j] - xy[2 * best], dy = xy[2 * j + 1] - xy[2 * best + 1];
  const double width = area / longest;
  const double step = 1e-3 * width / longest;
  return {0.5 * (xy[2 * best] + xy[2 * j]) - step * dy, 0.5 * (xy[2 * best + 1] + xy[2 * j + 1]) + step * dx};
}

inline double distance_to_loop(const double* xy, std::size_t n, double x, double y) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double ax = xy[2 * j], ay = xy[2 * j + 1], bx = xy[2 * i], by = xy[2 * i + 1];
    const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((x - ax) * dx + (y - ay) * dy) / l2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    best = std::min(best, std::hypot(ax + t * dx - x, ay + t * dy - y));
  }
  return best;
}

/// True when p lies inside the ring (even–odd rule above).
bool point_in_ring(const Ring& ring, Vec2 p);

/// Area enclosed by the ring, m² (either orientation; 0 for fewer than three vertices).
double ring_area(const Ring& ring);

/// The box of every body's outer ring, m; Box::empty() without body points.
Box bodies_box(const std::vector<BodyDef>& bodies);

}  // namespace nmm
