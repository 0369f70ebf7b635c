// The physical effects a run computes (summary.json "effects"; docs/interface.md): only those the
// scene calls for are assembled (integrators.h), so the list says what the numbers contain.
//   elasticity, inertia (dynamic) or static_inertia (DDA static: the mass term with v0 = 0),
//   gravity, point_loads, fixed_points, supports, tractions, water, insitu_stress,
//   base_acceleration, excavation (a body removed so far) — the integrators' — then each effect's
//   in the order of the lists (effect_output.h effect_names)
#pragma once

#include <string>
#include <vector>

#include "solver/discretisation/effect.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"
#include "solver/stepping/mesh_change.h"

namespace nmm::solve {

/// The effects of a run of `model` in state s with `effects` and `changes` (the effects of the
/// steps and those that change the mesh: mesh_bound.h), in the order above.
std::vector<std::string> run_effects(const Model& model, const RunState& s, const std::vector<Effect*>& effects,
                                     const std::vector<MeshChange*>& changes);

}  // namespace nmm::solve
