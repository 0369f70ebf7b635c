// The physical effects a run computes (summary.json "effects"; docs/interface.md): only those the
// scene calls for are assembled (integrators.h), so the list says what the numbers contain.
//   elasticity, inertia (dynamic) or static_inertia (DDA static: the mass term with v0 = 0),
//   gravity, point_loads, fixed_points, supports, tractions, water, insitu_stress,
//   base_acceleration, excavation (a body removed so far), then the contacts' (contact.h:
//   contact, friction, cohesion, tension, the joint laws...)
#pragma once

#include <string>
#include <vector>

#include "solver/contact/contact_set.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// The effects of a run of `model` in state s with `contacts`, in the order above.
std::vector<std::string> run_effects(const Model& model, const RunState& s, const ContactSet& contacts,
                                     bool fracture = false);

}  // namespace nmm::solve
