// Plane geometry of rings (ring_geometry.h has the formulas).
#include "common/ring_geometry.h"

#include <cmath>

namespace nmm {

bool point_in_ring(const Ring& ring, Vec2 p) {
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    if (ray_crosses(ring[i].x, ring[i].y, ring[j].x, ring[j].y, p.x, p.y)) inside = !inside;
  }
  return inside;
}

double ring_area(const Ring& ring) { return std::abs(ring_signed_area(ring)); }

Box bodies_box(const std::vector<BodyDef>& bodies) {
  Box b = Box::empty();
  for (const BodyDef& body : bodies)
    for (const Vec2& p : body.outer) b.add(p.x, p.y);
  return b;
}

}  // namespace nmm
