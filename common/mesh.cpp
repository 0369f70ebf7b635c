#include "common/mesh.h"

#include <vector>

namespace nmm {

std::size_t Mesh::mathematical_cover_count() const {
  std::vector<char> has(node_count(), 0);
  for (std::int32_t n : cover_node) has[static_cast<std::size_t>(n)] = 1;
  std::size_t count = 0;
  for (char h : has) count += h ? 1 : 0;
  return count;
}

double element_area(const Mesh& mesh, std::size_t e) {
  // Shoelace relative to the first vertex: keeps the round-off proportional to the element's own
  // size, not to its distance from the origin.
  const std::size_t b = static_cast<std::size_t>(mesh.element_loop_offset[e]);
  const std::size_t n = static_cast<std::size_t>(mesh.element_loop_offset[e + 1]) - b;
  const double* p = mesh.loop_xy.data() + 2 * b;
  double twice = 0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double ax = p[2 * i] - p[0], ay = p[2 * i + 1] - p[1];
    const double bx = p[2 * i + 2] - p[0], by = p[2 * i + 3] - p[1];
    twice += ax * by - ay * bx;
  }
  return 0.5 * twice;
}

double total_area(const Mesh& mesh) {
  double sum = 0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) sum += element_area(mesh, e);
  return sum;
}

}  // namespace nmm
