// The supports' reactions as an effect of the step: see support_effect.h.
#include "solver/discretisation/support_effect.h"

#include <nlohmann/json.hpp>

#include "solver/discretisation/excavation.h"

namespace nmm::solve {

void SupportEffect::commit(EffectStep& step, const Eigen::VectorXd& d) {
  last_ = support_reactions(model_, step.context, d);
  last_step_ = step.s.step + 1;  // the accepted state's (time_stepper.cpp: after update_state)
}

std::vector<SupportReaction> SupportEffect::reactions(const RunState& s) const {
  if (!active()) return {};
  if (s.step == last_step_) return last_;
  return support_reactions(model_, s, removed_elements(model_.mesh(), s));
}

void SupportEffect::write_outputs(OutputStep& out) const {
  const std::vector<SupportReaction> r = reactions(out.state);
  if (r.empty()) return;
  OutputTable& t = out.tables.table("reactions.csv", "step,time,support,fx,fy,travel");
  for (std::size_t i = 0; i < r.size(); ++i) {
    t.row(out.step, out.time);
    t.add_index(static_cast<std::int64_t>(i));
    t.add(r[i].fx);
    t.add(r[i].fy);
    t.add(r[i].travel);
    t.end_row();
  }
}

void SupportEffect::summarise(const RunState& s, nlohmann::json& summary) const {
  const std::vector<SupportReaction> r = reactions(s);
  if (r.empty()) return;
  nlohmann::json supports = nlohmann::json::array();
  for (std::size_t i = 0; i < r.size(); ++i)
    supports.push_back({{"support", i},
                        {"fx_n_per_m", r[i].fx},
                        {"fy_n_per_m", r[i].fy},
                        {"travel_m", r[i].travel},
                        {"direction", {r[i].dx, r[i].dy}},
                        {"load_n_per_m", r[i].load()}});
  summary["supports"] = supports;
}

}  // namespace nmm::solve
