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

#include "scene.h"

namespace nmm {

/// True when p lies inside the ring (even–odd rule above).
bool point_in_ring(const Ring& ring, Vec2 p);

/// Area enclosed by the ring, m² (either orientation; 0 for fewer than three vertices).
double ring_area(const Ring& ring);

}  // namespace nmm
