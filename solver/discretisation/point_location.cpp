// Which element holds a point: see point_location.h.
#include "solver/discretisation/point_location.h"

#include "common/ring_geometry.h"

namespace nmm::solve {

PointLocation locate_point(const Mesh& mesh, const std::vector<double>& loop_xy, Vec2 p,
                           const std::vector<std::uint8_t>* skip) {
  PointLocation best;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    if (skip && (*skip)[e]) continue;
    const std::size_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
    const double* xy = loop_xy.data() + 2 * b;
    if (point_in_loop(xy, n, p.x, p.y)) return {static_cast<std::int32_t>(e), 0.0};
    const double d = distance_to_loop(xy, n, p.x, p.y);
    if (d < best.distance) best = {static_cast<std::int32_t>(e), d};
  }
  return best;
}

}  // namespace nmm::solve
