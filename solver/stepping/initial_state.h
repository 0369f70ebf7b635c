// The state a run starts from (run_state.h), before its first step:
//   cover nodes at their mesh nodes, loop vertices at the mesh's, no displacement, velocity or
//   acceleration (every coefficient of the space's cover functions zero);
//   stress zero, or the scene's in-situ stress (insitu_stress.h) at every element's polynomial
//   coefficients;
//   tracked points (fixed, load, measure) where the model located them (model.h);
//   no body removed (the scene's excavate is applied by the stepper: excavation.h).
#pragma once

#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// The state of step 0 of a run of `model` in `space`.
RunState initial_state(const Model& model, const CoverSpace& space);

}  // namespace nmm::solve
