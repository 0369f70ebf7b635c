// The start of a step, kept so that the step can be solved again from it when its solution
// breaks the rock (time_stepper.cpp attempt; fracture.h rule 3).
//
// A run that can crack must be able to take every step again from where it began: the state
// (run_state.h) and the contact history of the step's start. Kept as copies into buffers that
// live from step to step, so a quiet step costs a copy into memory already there (15 MB at 10⁵
// elements: 2 ms copied into fresh memory, page faults included, about 1 ms into kept memory,
// bench/fracture_quiet_bench.cpp), and the copy is exact: the step taken again computes bit for
// bit what it would have computed the first time. Taking the step again swaps the kept state in
// (no copy back), with the diagnostics of the attempt that broke the rock: summary.json counts
// both solves.
#pragma once

#include <vector>

#include "solver/contact/contact.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

class StepStart {
 public:
  /// The step starts from state `s` and contact history `history`: both are kept.
  void keep(const RunState& s, const std::vector<ContactHistory>& history);
  /// The step is taken again: `s` (its solution, which broke the rock) becomes the kept start,
  /// with the solution's diagnostics (open–close iterations, cuts, largest penetration, ...).
  void restore(RunState& s);
  /// The kept start, to be carried onto a new mesh before restore() swaps it in.
  RunState& state() { return state_; }
  /// The contact history kept (to be carried onto a new mesh).
  const std::vector<ContactHistory>& history() const { return history_; }

 private:
  RunState state_;                       // the step's start
  std::vector<ContactHistory> history_;  // the contact history of the step's start
};

}  // namespace nmm::solve
