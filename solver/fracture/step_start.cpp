// The start of a step kept for taking it again: see step_start.h.
#include "solver/fracture/step_start.h"

#include <utility>

namespace nmm::solve {

void StepStart::keep(const RunState& s, const std::vector<ContactHistory>& history) {
  // Copy assignment: each vector reuses the capacity it has (no allocation once sizes settle).
  state_ = s;
  history_ = history;
}

void StepStart::restore(RunState& s) {
  // The diagnostics count both solves.
  state_.iterations = s.iterations;
  state_.cuts = s.cuts;
  state_.friction_unsettled = s.friction_unsettled;
  state_.max_capped = s.max_capped;
  state_.max_penetration = s.max_penetration;
  state_.max_step_displacement = s.max_step_displacement;
  std::swap(s, state_);  // the solution's buffers are kept for the next keep
}

}  // namespace nmm::solve
