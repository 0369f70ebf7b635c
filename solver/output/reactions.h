// What a run writes of its supports' reactions (docs/interface.md "Support reactions"; the
// force itself: solver/discretisation/support_reaction.h):
//   reactions.csv   at every output step, one row per entry of the scene's `supports` (numbered
//                   from 0 in its order): step,time,support,fx,fy,travel — fx, fy (N per m of
//                   thickness) the force the support exerts on the body, travel (m) how far a
//                   moving support has moved along its velocity (0 for a held one)
//   summary.json    "supports": per support at the run's end, "fx_n_per_m", "fy_n_per_m",
//                   "travel_m", "direction" (the unit vector of its velocity; [0, 0] held) and
//                   "load_n_per_m" (the force along it: what a loading platen applies)
// A run of a rock test reads its load against its travel from these (report/run_report.h draws
// load_travel.svg from them).
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "solver/discretisation/effect_output.h"
#include "solver/discretisation/support_reaction.h"
#include "solver/stepping/run_view.h"

namespace nmm::solve {

/// Every support's reaction in the run's state (its elements out of the model excluded).
std::vector<SupportReaction> support_reactions(const RunView& v);
/// reactions.csv's rows at an output step (none for a scene without supports).
void write_reactions(const RunView& v, OutputStep& out);
/// summary.json "supports" (left out for a scene without supports).
void summarise_reactions(const RunView& v, nlohmann::json& summary);

}  // namespace nmm::solve
