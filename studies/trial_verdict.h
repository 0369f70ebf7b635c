// Stable or failing: the verdict on one strength-reduction trial, from the run's history.csv,
// frames and summary.json (docs/interface.md).
//
// What is watched: the measure points (history.csv), or the blocks (each block's mean
// displacement over its manifold-element vertices, from the frames at the trial's start, half,
// three quarters and end), or both; by default the measure points when the scene has some, else
// the blocks. For every watched item p, with positions x_p(t) and d_p(t) = |x_p(t) − x_p(t0)| its
// displacement since the trial's first output:
//   v_late = |x_p(t_end) − x_p(t_3/4)| / (t_end − t_3/4)   (mean speed over the last quarter)
//   v_mid  = |x_p(t_3/4) − x_p(t_1/2)| / (t_3/4 − t_1/2)   (over the quarter before)
// (t_1/2, t_3/4: the output rows nearest half and three quarters of the trial.) The trial is
//   failing  when the run stopped (exit 3: diverged, step cut below its floor — blocks flying off),
//            or some point moved more than max_displacement (0 = no limit),
//            or some point still moves faster than velocity_floor and is not clearly slowing
//            down (v_late > decay_ratio·v_mid, default ratio 0.5): a block sliding at the reduced
//            strength accelerates (v_late/v_mid ≈ 1.4 for a constant acceleration), one
//            creeping at constant speed has ratio 1, one that snags and goes on slowly too;
//   stable   otherwise: every point stops, or its speed at least halves from one quarter of the
//            trial to the next (a transient after the strength drop that the contacts arrest).
// The floor sets the resolution: a block with acceleration a over a trial of duration T is seen
// moving once a·7T/8 > velocity_floor; with the default 1 mm/s and T = 0.5 s that is 2.3 mm/s²,
// i.e. F within 0.05 % for a block on a 30° plane (a = g·sin α·(1 − F_s/F)).
#pragma once

#include <string>

namespace nmm::studies {

enum class Watch { automatic, points, blocks, both };

struct VerdictCriterion {
  Watch watch = Watch::automatic;
  double velocity_floor = 1e-3;  ///< m/s, speeds below it count as stopped
  double max_displacement = 0;   ///< m, any displacement beyond it is failure; 0 = no limit
  double decay_ratio = 0.5;      ///< –, v_late/v_mid at or below which a moving point is arresting
};

struct TrialVerdict {
  bool failing = false;
  std::string reason;           ///< one line: the rule that decided and the numbers
  double max_displacement = 0;  ///< m, largest d_p(t_end) over the points
  double end_velocity = 0;      ///< m/s, largest v_late over the points
};

/// Parses "auto", "points", "blocks", "both" (InputError naming --watch otherwise).
Watch parse_watch(const std::string& word);

/// Judges the run in `out_dir` that ended with `exit_status` (0 or 3). Throws RunError when the
/// output cannot be read, or what is watched is missing or has fewer than 4 outputs.
TrialVerdict judge_trial(const std::string& out_dir, int exit_status, const VerdictCriterion& c);

}  // namespace nmm::studies
