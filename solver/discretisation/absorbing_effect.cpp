// The absorbing boundaries as an effect of the step: see absorbing_effect.h.
#include "solver/discretisation/absorbing_effect.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "solver/discretisation/absorbing_boundary.h"
#include "solver/discretisation/state_bytes.h"

namespace nmm::solve {

bool AbsorbingEffect::install(RunState& s, const std::string& name) {
  const auto unknowns = static_cast<std::size_t>(space_.unknowns());
  if (!s.absorbing_key.empty() && s.absorbing_key == absorbing_key(model_.scene()) &&
      s.absorbing_reaction.size() != unknowns)
    throw InputError(name, "section ABSORB", "the carried reaction has " + std::to_string(s.absorbing_reaction.size()) +
                                                 " unknowns, the run " + std::to_string(unknowns));
  if (model_.scene().absorbing.empty()) {
    s.absorbing_key.clear();
    s.absorbing_reaction.clear();
    s.absorbed_work = 0;
    s.absorbing_load_work = 0;
  }
  return true;  // the reaction is on the covers' unknowns: a factorisation still fits
}

void AbsorbingEffect::carry_over(const MeshPieces& from, RunState& s) const {
  s.absorbing_reaction =
      absorbing_reaction_onto(s.absorbing_reaction, from.old_space, from.cover_parent, model_, space_);
}

Outcome AbsorbingEffect::begin_step(EffectStep& step) {
  if (!absorbing_reaction_due(model_.scene(), step.s)) return {};
  // Cleared first: the force at rest is the state's without a carried reaction (the form's
  // absorbing terms apply the carried one).
  step.s.absorbing_key.clear();
  step.s.absorbing_reaction.clear();
  const Eigen::VectorXd& residual = step.host.force_at_rest();
  step.s.absorbing_reaction =
      absorbing_reaction_of(model_, step.context.config, residual, space_.unknowns());
  step.s.absorbing_key = absorbing_key(model_.scene());
  return {};
}

void AbsorbingEffect::commit(EffectStep& step, const Eigen::VectorXd& d) {
  const AbsorbingWork w = absorbing_work(model_, step.context, d);
  step.s.absorbed_work += w.absorbed;
  step.s.absorbing_load_work += w.loads;
}

void AbsorbingEffect::checkpoint_sections(const RunState& s, const Mesh& /*mesh*/, CheckpointSections& sections) const {
  if (s.absorbing_key.empty()) return;  // none taken: the checkpoint keeps the bytes of a run without
  ByteWriter w;
  w.put_vector(s.absorbing_key);
  w.put_vector(s.absorbing_reaction);
  w.put(s.absorbed_work);
  w.put(s.absorbing_load_work);
  sections.emplace_back("ABSORB", w.take());
}

void AbsorbingEffect::restore_sections(const CheckpointSections& sections, const Mesh& mesh, const std::string& name,
                                       RunState& s) const {
  const auto it = std::find_if(sections.begin(), sections.end(), [](const auto& x) { return x.first == "ABSORB"; });
  if (it == sections.end()) return;
  ByteReader r(it->second, name, "ABSORB");
  s.absorbing_key = r.get_vector<double>(SIZE_MAX, "absorbing boundaries");
  s.absorbing_reaction = r.get_vector<double>(SIZE_MAX, "carried reaction");
  s.absorbed_work = r.get<double>();
  s.absorbing_load_work = r.get<double>();
  double sum = s.absorbed_work + s.absorbing_load_work;
  for (double x : s.absorbing_key) sum += x;
  for (double x : s.absorbing_reaction) sum += x;
  const auto per_cover = static_cast<std::size_t>(space_.dofs_per_cover());
  if (s.absorbing_key.empty() || !std::isfinite(sum) || s.absorbing_reaction.size() % per_cover != 0 ||
      s.absorbing_reaction.size() > per_cover * mesh.cover_count())
    r.fail("the carried reaction does not fit the mesh, or holds a value that is not finite");
  r.expect_end();
}

}  // namespace nmm::solve
