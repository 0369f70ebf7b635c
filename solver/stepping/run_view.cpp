// The quantities derived from a run's view: see run_view.h.
#include "solver/stepping/run_view.h"

#include "common/mesh_file.h"
#include "solver/contact/contact_history.h"
#include "solver/discretisation/support_effect.h"
#include "solver/stepping/run_effects.h"
#include "solver/discretisation/stress_field.h"

namespace nmm::solve {

std::vector<double> mean_stress(const RunView& v) { return mean_stress(v.mesh, v.space, v.state); }

std::array<double, 3> stress_at(const RunView& v, std::size_t e, double x, double y) {
  return stress_at(v.mesh, v.space, v.state, e, x, y);
}

std::vector<std::string> run_effects(const RunView& v) {
  return run_effects(v.model, v.state, v.effects, v.changes);
}

std::vector<const EffectEnergy*> energy_sources(const RunView& v) {
  std::vector<const EffectEnergy*> sources(v.metered.begin(), v.metered.end());
  for (const MeshChange* c : v.changes) sources.push_back(c);
  return sources;
}

std::vector<SupportReaction> support_reactions(const RunView& v) {
  // The one effect that keeps them (mesh_bound.h lists it).
  if (const auto* supports = find_effect<SupportEffect>(v)) return supports->reactions(v.state);
  return {};
}

CheckpointSections state_sections(const RunView& v) {
  CheckpointSections sections = state_to_sections(v.state, save_contact_history(v.contacts), v.mesh);
  for (const Effect* e : v.checkpointed) e->checkpoint_sections(v.state, v.mesh, sections);
  return sections;
}

std::string state_hash(const RunView& v) {
  std::string hash = state_hash(state_sections(v));
  // A change that carries nothing yet (a run whose mesh has not changed) leaves the hash as it was.
  for (const MeshChange* c : v.changes)
    if (const std::string bytes = c->hashed_state(); !bytes.empty()) hash = to_hex(sha256(hash + bytes));
  return hash;
}

}  // namespace nmm::solve
