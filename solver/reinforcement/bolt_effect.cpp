// The bolts as an effect of the step: see bolt_effect.h.
#include "solver/reinforcement/bolt_effect.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "solver/reinforcement/bolt_layout.h"
#include "solver/reinforcement/bolt_readout.h"

namespace nmm::solve {

bool BoltEffect::install(RunState& s, const std::string& /*name*/) {
  // The state's bolts where the scene still has them, the others installed now (bolt_layout.h).
  // A bolt installed now (or one dropped) changes the system's size: a checkpoint's
  // factorisation no longer fits. (A bolt's points are the scene's: errors name the scene.)
  const std::vector<BoltState> carried = s.bolts;
  s.bolts = bolts_for_run(model_.scene(), model_.mesh(), s, carried, scene_name_);
  return s.bolts.size() == carried.size() &&
         std::equal(carried.begin(), carried.end(), s.bolts.begin(), [](const BoltState& a, const BoltState& b) {
           return a.type == b.type && a.ax == b.ax && a.ay == b.ay && a.bx == b.bx && a.by == b.by &&
                  a.installed_step == b.installed_step;
         });
}

void BoltEffect::number(const RunState& s, int first_unknown, std::size_t first_group) {
  bolts_.number(s.bolts, first_unknown);
  first_group_ = first_group;
  count_ = s.bolts.size();
}

void BoltEffect::add_groups(const RunState& /*s*/, std::vector<int>& offsets, std::vector<int>& dofs) const {
  bolts_.add_groups(offsets, dofs);
}

Outcome BoltEffect::begin_step(EffectStep& step) {
  bolts_.begin_step(step.context.config, step.s, step.context.removed);
  return {};
}

void BoltEffect::add_at_rest(EffectStep& rest) {
  bolts_.begin_step(rest.context.config, rest.s, rest.context.removed);
  bolts_.assemble(rest.system, rest.rhs, first_group_);
}

void BoltEffect::assemble(EffectStep& step) { bolts_.assemble(step.system, step.rhs, first_group_); }

Outcome BoltEffect::not_settled(double t) const {
  return Outcome::stop(StopCode::bolts_not_settled,
                       "the bolts' springs were still switching between elastic and yielding or slipping after " +
                           std::to_string(BoltSystem::kMaxRounds) + " solves of the step",
                       t);
}

void BoltEffect::commit(EffectStep& step, const Eigen::VectorXd& d) {
  bolts_.commit(d, step.context.config, step.s.bolts);
}

void BoltEffect::summarise(const RunState& s, nlohmann::json& summary) const {
  if (s.bolts.empty()) return;
  nlohmann::json bolts = nlohmann::json::array();
  for (std::size_t b = 0; b < s.bolts.size(); ++b) {
    const BoltState& bs = s.bolts[b];
    double slip = 0;
    for (double x : bs.slip) slip = std::max(slip, std::abs(x));
    nlohmann::json j = {{"bolt", b},
                        {"max_axial_force", bs.max_axial},
                        {"yielded", bs.yielded != 0},
                        {"broken", bs.broken != 0},
                        {"type", bs.type == 0 ? "anchored" : "grouted"},
                        {"installed_step", bs.installed_step}};
    if (bs.type != 0) j["max_slip_m"] = slip;
    bolts.push_back(j);
  }
  summary["bolts"] = bolts;
}

void BoltEffect::write_outputs(OutputStep& out) const {
  const std::vector<BoltState>& bolts = out.state.bolts;
  if (bolts.empty()) return;
  OutputTable& t = out.tables.table("bolts.csv", "step,time,bolt,s,axial_force,bond_force,x,y,ux,uy");
  for (std::size_t b = 0; b < bolts.size(); ++b)
    for (const BoltReading& r : bolt_readout(model_.scene().bolts[b], bolts[b])) {
      t.row(out.step, out.time);
      t.add_index(static_cast<std::int64_t>(b));
      for (double v : {r.s, r.axial, r.bond, r.x, r.y, r.ux, r.uy}) t.add(v);
      t.end_row();
    }
}

}  // namespace nmm::solve
