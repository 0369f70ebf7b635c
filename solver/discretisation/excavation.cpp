// Excavation: bodies drop out, their faces' locked-in traction is released (excavation.h).
#include "solver/discretisation/excavation.h"

#include <algorithm>

namespace nmm::solve {

void excavate_bodies(const std::vector<int>& bodies, const Mesh& mesh, std::size_t stress_terms,
                     RunState& s) {
  const std::size_t per_element = 3 * stress_terms;
  for (int b : bodies) {
    if (b < 0 || static_cast<std::size_t>(b) >= s.body_removed.size() || s.body_removed[b]) continue;
    s.body_removed[b] = 1;
    s.body_removed_at[b] = s.step;
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
      if (mesh.element_body[e] == b)
        std::fill_n(s.stress.begin() + static_cast<long>(per_element * e), per_element, 0.0);
  }
}

std::vector<std::uint8_t> removed_elements(const Mesh& mesh, const RunState& s) {
  std::vector<std::uint8_t> r(mesh.element_count(), 0);
  for (std::size_t e = 0; e < r.size(); ++e) r[e] = s.body_removed[mesh.element_body[e]];
  return r;
}

void hold_removed_covers(const Mesh& mesh, int dofs_per_cover, const std::vector<std::uint8_t>& removed,
                         RunState& s) {
  const std::size_t dpc = static_cast<std::size_t>(dofs_per_cover);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    if (!removed[e]) continue;
    for (int k = 0; k < 3; ++k) {
      const std::size_t c = static_cast<std::size_t>(mesh.element_covers[3 * e + k]);
      for (std::size_t i = 0; i < dpc; ++i) s.velocity[c * dpc + i] = s.accel[c * dpc + i] = 0;
    }
    if (!s.block_force.empty())
      std::fill_n(s.block_force.begin() + static_cast<long>(3 * mesh.element_block[e]), 3, 0.0);
  }
}

double interface_traction_factor(const RunState& s, std::int32_t body, std::int64_t release_steps) {
  if (!s.body_removed[body]) return 1.0;
  const std::int64_t k = s.step + 1 - s.body_removed_at[body];  // the step being taken, 1-based
  return std::max(0.0, 1.0 - static_cast<double>(k) / static_cast<double>(release_steps));
}

}  // namespace nmm::solve
