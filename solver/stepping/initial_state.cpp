// The state a run starts from: see initial_state.h.
#include "solver/stepping/initial_state.h"

#include "solver/discretisation/insitu_stress.h"

namespace nmm::solve {

RunState initial_state(const Model& model, const CoverSpace& space) {
  const Mesh& mesh = model.mesh();
  const SceneDef& scene = model.scene();
  const std::size_t ne = mesh.element_count(), nc = mesh.cover_count();
  const std::size_t dpc = static_cast<std::size_t>(space.dofs_per_cover());
  RunState s;
  s.cover_xy.resize(2 * nc);
  for (std::size_t c = 0; c < nc; ++c) {
    s.cover_xy[2 * c] = mesh.node_xy[2 * mesh.cover_node[c]];
    s.cover_xy[2 * c + 1] = mesh.node_xy[2 * mesh.cover_node[c] + 1];
  }
  s.cover_u.assign(dpc * nc, 0.0);
  s.velocity.assign(dpc * nc, 0.0);
  s.accel.assign(dpc * nc, 0.0);
  s.stress.assign(3 * static_cast<std::size_t>(space.terms()) * ne, 0.0);
  s.loop_xy = mesh.loop_xy;
  s.loop_u.assign(s.loop_xy.size(), 0.0);
  s.body_removed.assign(scene.bodies.size(), 0);
  s.body_removed_at.assign(scene.bodies.size(), -1);
  if (scene.insitu_stress.present)
    apply_insitu_stress(scene.insitu_stress, mesh, space.order(), space.scale(), s.stress);
  s.fixed = model.fixed_points();
  s.loads = model.load_points();
  s.measure = model.measure_points();
  return s;
}

}  // namespace nmm::solve
