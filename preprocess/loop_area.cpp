// Equations and why: loop_area.h.
#include "preprocess/loop_area.h"

#include <CGAL/Exact_rational.h>

#include <cmath>
#include <limits>

namespace nmm::pre {

int loop_area_sign(const Vec2* loop, std::size_t n) {
  if (n < 3) return 0;
  const Vec2 o = loop[0];
  double twice_area = 0;  // m², about the first vertex (less cancellation)
  double magnitude = 0;   // m², Σ of the terms' absolute values
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = loop[i], q = loop[(i + 1) % n];
    const double a = (p.x - o.x) * (q.y - o.y), b = (q.x - o.x) * (p.y - o.y);
    twice_area += a - b;
    magnitude += std::abs(a) + std::abs(b);
  }
  const double bound =
      static_cast<double>(2 * n + 4) * std::numeric_limits<double>::epsilon() * magnitude;
  if (twice_area > bound) return 1;
  if (twice_area < -bound) return -1;
  CGAL::Exact_rational exact = 0;  // m², twice the area about the origin: the same for a loop
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = loop[i], q = loop[(i + 1) % n];
    exact += CGAL::Exact_rational(p.x) * CGAL::Exact_rational(q.y) -
             CGAL::Exact_rational(q.x) * CGAL::Exact_rational(p.y);
  }
  return static_cast<int>(CGAL::sign(exact));
}

}  // namespace nmm::pre
