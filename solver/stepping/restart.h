// Continuing a run from a checkpoint (nmm-solve --restart; docs/interface.md "Rock-engineering
// set-ups and restart"): the checkpoint's state (run_state.h) is the run's, bitwise, except
// where the restarted run's scene says otherwise:
//   - tracked points (fixed, load, measure): the checkpoint's where the scene still names the
//     same points (the same starting positions, in order); points the run's scene adds or
//     changes start where the scene puts them, in the current configuration;
//   - excavate: the bodies the scene lists are removed at the restart (excavation.h).
// The body count must match the scene's: geometry other than excavate cannot change.
//
// A checkpoint (checkpoint.nmmstate; docs/checkpoint-format.md) holds the state, the contact
// history and, with contact, the factorised matrix the next step's solve starts from (the
// factorisation lives on from step to step as a preconditioner), so that a restart continues
// bitwise as the straight run.
#pragma once

#include <string>

#include "solver/discretisation/run_state.h"
#include "solver/stepping/run_view.h"

namespace nmm::solve {

/// The state a restarted run continues from: `checkpoint` (read from `name`) with the tracked
/// points of `scene_start` (the state the run's scene starts from) where they differ.
/// InputError naming `name` if the checkpoint's body count is not the scene's (`bodies`).
RunState restarted_state(const RunState& checkpoint, const RunState& scene_start,
                         std::size_t bodies, const std::string& name);

/// Writes the run's checkpoint to `path` atomically; safe between steps, e.g. from an interrupt
/// handler's deferred path.
void write_checkpoint(const RunView& v, const std::string& path);

}  // namespace nmm::solve
