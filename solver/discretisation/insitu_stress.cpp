// In-situ stress field and its initialisation of the element stresses (insitu_stress.h).
#include "solver/discretisation/insitu_stress.h"

#include <algorithm>

#include "solver/discretisation/polynomial.h"

namespace nmm::solve {

std::array<double, 3> insitu_stress_at(const InsituStressDef& s, double /*x*/, double y) {
  const double depth = s.y_ref - y;
  return {s.sxx + depth * s.gxx, s.syy + depth * s.gyy, s.sxy + depth * s.gxy};
}

void apply_insitu_stress(const InsituStressDef& s, const Mesh& mesh, int order, double scale,
                         std::vector<double>& stress) {
  if (order > 0) {
    // The linear field exactly: constant term at the frame origin o, η term −h·gradient.
    const std::size_t T = static_cast<std::size_t>(monomial_count(order));
    const std::size_t eta = static_cast<std::size_t>(monomial_index(0, 1));
    const double grad[3] = {s.gxx, s.gyy, s.gxy};
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
      const std::int32_t node = mesh.cover_node[mesh.element_covers[3 * e]];
      const auto at_origin = insitu_stress_at(s, mesh.node_xy[2 * node], mesh.node_xy[2 * node + 1]);
      double* c = stress.data() + 3 * T * e;
      std::fill(c, c + 3 * T, 0.0);
      for (int r = 0; r < 3; ++r) {
        c[r] = at_origin[r];
        c[3 * eta + r] = -scale * grad[r];
      }
    }
    return;
  }
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    // Centroid of the loop (shoelace), about its first vertex for round-off.
    const std::int32_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
    const double* xy = mesh.loop_xy.data() + 2 * b;
    double a2 = 0, cx = 0, cy = 0;
    for (std::int32_t i = 0; i < n; ++i) {
      const std::int32_t j = (i + 1) % n;
      const double xi = xy[2 * i] - xy[0], yi = xy[2 * i + 1] - xy[1];
      const double xj = xy[2 * j] - xy[0], yj = xy[2 * j + 1] - xy[1];
      const double c = xi * yj - xj * yi;
      a2 += c;
      cx += (xi + xj) * c;
      cy += (yi + yj) * c;
    }
    const double x = a2 != 0 ? xy[0] + cx / (3 * a2) : xy[0];
    const double y = a2 != 0 ? xy[1] + cy / (3 * a2) : xy[1];
    const auto sig = insitu_stress_at(s, x, y);
    for (int k = 0; k < 3; ++k) stress[3 * e + k] = sig[k];
  }
}

}  // namespace nmm::solve
