// What a run writes of its supports' reactions: see reactions.h.
#include "solver/output/reactions.h"

#include <nlohmann/json.hpp>

#include "solver/discretisation/excavation.h"

namespace nmm::solve {

std::vector<SupportReaction> support_reactions(const RunView& v) {
  if (v.model.support_edges().empty()) return {};
  // The elements the step's assembly leaves out (time_stepper.cpp apply_removed): excavated
  // bodies, and the debris the cracks cut off.
  std::vector<std::uint8_t> removed = removed_elements(v.mesh, v.state);
  const std::vector<std::uint8_t>& debris = v.fracture.debris();
  for (std::size_t e = 0; e < debris.size() && e < removed.size(); ++e) removed[e] = removed[e] || debris[e];
  return support_reactions(v.model, v.state, removed);
}

void write_reactions(const RunView& v, OutputStep& out) {
  const std::vector<SupportReaction> r = support_reactions(v);
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

void summarise_reactions(const RunView& v, nlohmann::json& summary) {
  const std::vector<SupportReaction> r = support_reactions(v);
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
