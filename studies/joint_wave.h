// A compressional wave crossing one joint: what is read off a run of the bar against the
// displacement-discontinuity model (the scene and the closed form: reference/wave_bar.h).
//
// Read-off (JointWaveErrors): the displacement histories at x_a and x_b against the closed form
// from the wave's arrival x/c to valid_until(x) (RMS of the difference over the samples there,
// relative to the largest closed-form |u| there; before x/c both are still); the half-rise
// time after the joint (u_b reaching half the final displacement 2p/(ωZ)); the peak particle
// velocity after the joint (the largest Δu/Δt between samples against the closed form's peak,
// found where dσ_t/ds = 0, i.e. σ_t = σ_i).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/outcome.h"
#include "common/mesh.h"
#include "common/scene.h"
#include "reference/wave_bar.h"

namespace nmm::solve {
class TimeStepper;
}  // namespace nmm::solve

namespace nmm::studies {

/// The histories a run records: time and the x displacement at both measure points, one row
/// per step (row 0 at t = 0).
struct JointWaveHistory {
  std::vector<double> time;    ///< s
  std::vector<double> before;  ///< m, u_x at measure point 0
  std::vector<double> after;   ///< m, u_x at measure point 1
  Outcome outcome;             ///< how the run ended
};

/// Runs the scene (from reference::joint_wave_scene or the data file) on its mesh to its last step.
JointWaveHistory run_joint_wave(const Mesh& mesh, const SceneDef& scene);
/// The same on a stepper made for it (nmm-study times it); on_step(n) after the n-th step.
JointWaveHistory run_joint_wave(solve::TimeStepper& st, const SceneDef& scene,
                                const std::function<void(std::int64_t)>& on_step);

/// The run against the closed form (read-off above).
struct JointWaveErrors {
  double before_rms = 0;      ///< –, displacement history at x_a, RMS relative to its peak
  /// –, the same until the reflection off the joint arrives at (2x_j − x_a)/c: the incident
  /// wave alone, what the loading, the rock and the rollers give before any joint is involved
  double incident_rms = 0;
  double after_rms = 0;       ///< –, displacement history at x_b, likewise
  double half_rise = 0;       ///< s, run − closed form at x_b (> 0: the run is late)
  double half_rise_exact = 0; ///< s, the closed form's
  double peak_velocity = 0;   ///< m/s, the run's largest Δu/Δt at x_b
  double peak_velocity_exact = 0;  ///< m/s, σ_t's peak / Z
  double peak_velocity_error() const { return peak_velocity / peak_velocity_exact - 1; }
};
JointWaveErrors joint_wave_errors(const reference::JointWaveSetup& s, const JointWaveHistory& h);

}  // namespace nmm::studies
