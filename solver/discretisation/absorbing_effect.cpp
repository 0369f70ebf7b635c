// The absorbing boundaries as an effect of the step: see absorbing_effect.h.
#include "solver/discretisation/absorbing_effect.h"

#include "common/error.h"
#include "solver/discretisation/absorbing_boundary.h"

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

}  // namespace nmm::solve
