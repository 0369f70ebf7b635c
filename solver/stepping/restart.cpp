// Continuing a run from a checkpoint: see restart.h.
#include "solver/stepping/restart.h"

#include "common/checkpoint_file.h"
#include "common/error.h"
#include "common/mesh_file.h"
#include "solver/contact/contact_history.h"

namespace nmm::solve {

namespace {

/// The same points: the same count and starting positions, in order.
bool same_points(const std::vector<TrackedPoint>& a, const std::vector<TrackedPoint>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].x0 != b[i].x0 || a[i].y0 != b[i].y0) return false;
  return true;
}

}  // namespace

RunState restarted_state(const RunState& checkpoint, const RunState& scene_start,
                         std::size_t bodies, const std::string& name) {
  if (checkpoint.body_removed.size() != bodies)
    throw InputError(name, "section BODIES", "the checkpoint has " +
                                                 std::to_string(checkpoint.body_removed.size()) +
                                                 " bodies, the scene " + std::to_string(bodies));
  RunState next = checkpoint;
  if (!same_points(next.fixed, scene_start.fixed)) next.fixed = scene_start.fixed;
  if (!same_points(next.loads, scene_start.loads)) next.loads = scene_start.loads;
  if (!same_points(next.measure, scene_start.measure)) next.measure = scene_start.measure;
  return next;
}

void write_checkpoint(const RunView& v, const std::string& path) {
  // The run state's sections and the effects' (the state they carry: EffectOutput::checkpoint_sections).
  CheckpointSections sections = state_sections(v);
  // The factorisation an effect that solves the steps its own way reuses from step to step (the
  // contacts': effect.h solves()), so a restart continues with the same round-off.
  for (const Effect* e : v.effects)
    if (e->active() && e->solves()) {
      sections.emplace_back("FACTOR", v.system.factor_source());
      break;
    }
  // What the mesh changes keep (a changed mesh and what changed it), after the factorisation.
  for (const MeshChange* c : v.changes) c->checkpoint_sections(v.state, v.mesh, sections);
  write_checkpoint_file(sections, path);
}

}  // namespace nmm::solve
